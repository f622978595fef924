"""One headless OpenGL context for the GPU path, created on first use (moderngl through EGL).

moderngl's default standalone backend needs an X display; ``backend="egl"`` does not, and on a
machine without a GPU Mesa's llvmpipe renders on the CPU (that is how CI runs the GPU tests).
The shaders need OpenGL 4.5 core, which llvmpipe has (the procedural walls' 64-bit hashes are
written on pairs of 32-bit words, so that WebGL2 runs them too: no 64-bit integer extension).

Examples
--------
>>> info = gpu_info()
>>> sorted(info)[:3], info["max_texture_size"] >= 4096
(['extensions_int64', 'max_samples', 'max_texture_size'], True)
"""

from __future__ import annotations

from tilesolve.errors import BackendUnavailable

__all__ = ["GpuUnavailable", "DEBIAN_PACKAGES", "gpu_context", "gpu_info", "max_render_size", "release"]

#: What a Debian/Ubuntu machine needs for a headless context (Mesa's EGL and software rasteriser).
DEBIAN_PACKAGES = "libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri"

_state: dict = {}


class GpuUnavailable(BackendUnavailable):
    """No usable OpenGL context (moderngl missing, no EGL, or too old a GL); exit code 2."""


def gpu_context():
    """The shared standalone context (created on the first call; later calls return it).

    Raises
    ------
    GpuUnavailable
        One line naming what is missing: the ``gpu`` extra, or the Debian packages of EGL/Mesa
        (OpenGL 4.5).
    """
    if "ctx" in _state:
        return _state["ctx"]
    try:
        import moderngl
    except ImportError:
        raise GpuUnavailable("the GPU path needs moderngl: pip install 'tilesolve[gpu]'") from None
    try:
        ctx = moderngl.create_standalone_context(backend="egl", require=450)
    except Exception as exc:  # moderngl/glcontext raise plain Exceptions with multi-line texts
        why = " ".join(str(exc).split())[:160] or type(exc).__name__
        raise GpuUnavailable(f"no OpenGL 4.5 context through EGL ({why}); on Debian/Ubuntu install "
                             f"{DEBIAN_PACKAGES}") from None
    _state["ctx"] = ctx
    return ctx


def max_render_size(ctx=None) -> int:
    """The largest square that one render pass draws: the smaller of the texture and viewport limits."""
    ctx = ctx or gpu_context()
    vp = ctx.info["GL_MAX_VIEWPORT_DIMS"]
    return int(min(ctx.info["GL_MAX_TEXTURE_SIZE"], vp[0], vp[1], ctx.info["GL_MAX_RENDERBUFFER_SIZE"]))


def gpu_info() -> dict:
    """Renderer, vendor, version and the limits the renderers use, as a dict of plain values."""
    ctx = gpu_context()
    i = ctx.info
    return {
        "renderer": i["GL_RENDERER"],
        "vendor": i["GL_VENDOR"],
        "version": i["GL_VERSION"],
        "max_texture_size": int(i["GL_MAX_TEXTURE_SIZE"]),
        "max_viewport": tuple(int(v) for v in i["GL_MAX_VIEWPORT_DIMS"]),
        "max_samples": int(ctx.max_samples),
        "extensions_int64": "GL_ARB_gpu_shader_int64" in ctx.extensions,
    }


def release(fbo) -> None:
    """Free a framebuffer and its attachments (moderngl frees only what it is asked to)."""
    for a in fbo.color_attachments:
        a.release()
    if fbo.depth_attachment is not None:
        fbo.depth_attachment.release()
    fbo.release()
