"""The GPU path (moderngl, OpenGL 4.5 core through EGL, headless): the extra ``tilesolve[gpu]``.

* :mod:`.context` -- one lazily created standalone context; :class:`GpuUnavailable` when none
  can be made (a one-line message naming what to install).
* :mod:`.texture` -- tile-based texture mapping with corner tiles (class notes §5.3-5.4,
  Wei 2004, Lagae and Dutré 2006): an atlas of the ``C**4`` corner tiles laid out as a tile
  packing, synthesised from an example image, mapped by a fragment shader that evaluates the
  direct stochastic corner tiling (§3.3.1) per fragment, bit for bit as the CPU does.
* :mod:`.wall` -- the procedural wall of 004 (§4.2-4.3, App. B, §5.2) as a shader: edge colours
  by the FNV/xorshift hashes and the 2x2 solver, bit for bit as :mod:`tilesolve.constructive.walls`,
  then per fragment the brick, the distance to its edge, its UV and a colour; multisampled.
  The same GLSL, as GLSL ES 3.00 (:func:`.wall.webgl_wall`), draws the studio's WebGL2 view.
* :mod:`.objects` -- the procedural object distribution function of Poisson disk tiles (§6.6.2)
  as a fragment shader: per pixel the closest point of the tiled distribution, its id, disk and
  local coordinates, equal to :func:`tilesolve.constructive.poisson.object_distribution`'s.

Nothing outside this package imports moderngl, so the CPU routes work without GL.
"""
