"""Pictures of Poisson disk windows and of their spectra (class notes §4.2.2, §4.3).

* :func:`write_points_picture`: the points of a window as dots (SVG with svgwrite, PNG with
  Pillow), faint tile borders, a caption with the window and the relative radius.
* :func:`write_spectrum_plot`: radially averaged power and anisotropy (Ulichney 1987) of
  several point sets against frequency, one line each, as SVG or PNG.

>>> import numpy as np
>>> from tilesolve.model.window import Window
>>> text = points_svg(np.array([[0.5, 0.5]]), Window(0, 0, 1, 1), 0.1, "one point")
>>> text.startswith("<svg") and "one point" in text
True
"""

from __future__ import annotations

import os
from typing import Sequence

import numpy as np

from tilesolve.errors import InvalidProblem
from tilesolve.io.atomic import atomic_write
from tilesolve.model.window import Window

__all__ = ["points_svg", "write_points_picture", "write_spectrum_plot", "texture_image", "write_texture_png",
           "MAX_PICTURE_POINTS", "MAX_TEXTURE_PIXELS"]

#: Most points a picture draws (an SVG of more is too slow to open).
MAX_PICTURE_POINTS = 200_000
#: Most pixels of a texture.
MAX_TEXTURE_PIXELS = 1 << 24
_SERIES = ("#0072B2", "#D55E00", "#009E73", "#CC79A7")


def _check(n: int) -> None:
    if n > MAX_PICTURE_POINTS:
        raise InvalidProblem(f"a picture draws at most {MAX_PICTURE_POINTS:,} points, the window has {n:,}: "
                             "draw a smaller window")


def points_svg(local: np.ndarray, window: Window, distance: float, caption: str, *, px: float | None = None) -> str:
    """SVG text of the points, tile units scaled to ``px`` pixels (about 640 pixels wide)."""
    import svgwrite

    _check(len(local))
    px = px or max(4.0, 640.0 / max(window.width, window.height))
    w, h = window.width * px, window.height * px
    dwg = svgwrite.Drawing(size=(f"{w:.0f}", f"{h + 24:.0f}"), profile="full", debug=False)
    dwg.add(dwg.rect((0, 0), (w, h + 24), fill="white"))
    grid = dwg.g(stroke="#cccccc", stroke_width=0.5)
    for i in range(window.width + 1):
        grid.add(dwg.line((i * px, 0), (i * px, h)))
    for j in range(window.height + 1):
        grid.add(dwg.line((0, j * px), (w, j * px)))
    dwg.add(grid)
    dots = dwg.g(fill="#0072B2")
    r = max(0.6, distance * px / 4)
    for x, y in local:
        dots.add(dwg.circle((round(x * px, 2), round(h - y * px, 2)), round(r, 2)))
    dwg.add(dots)
    dwg.add(dwg.text(caption, insert=(4, h + 17), font_size="12px", font_family="sans-serif", fill="#333333"))
    return dwg.tostring()


def write_points_picture(path: str | os.PathLike, local: np.ndarray, window: Window, distance: float,
                         caption: str, fmt: str) -> None:
    """The window's points as ``fmt`` (``"svg"`` or ``"png"``); y grows upwards in the picture."""
    if fmt == "svg":
        text = points_svg(local, window, distance, caption)
        with atomic_write(path) as f:
            f.write(text)
        return
    from PIL import Image, ImageDraw

    _check(len(local))
    px = max(4.0, 1024.0 / max(window.width, window.height))
    w, h = int(window.width * px), int(window.height * px)
    img = Image.new("RGB", (w, h + 20), "white")
    draw = ImageDraw.Draw(img)
    for i in range(window.width + 1):
        draw.line([(i * px, 0), (i * px, h)], fill=(220, 220, 220))
    for j in range(window.height + 1):
        draw.line([(0, j * px), (w, j * px)], fill=(220, 220, 220))
    r = max(1.0, distance * px / 4)
    for x, y in local:
        cx, cy = x * px, h - y * px
        draw.ellipse([cx - r, cy - r, cx + r, cy + r], fill=(0, 114, 178))
    draw.text((4, h + 4), caption, fill=(51, 51, 51))
    with atomic_write(path, "wb", encoding=None) as f:
        img.save(f, format="PNG")


def _layout(series, key: int, lo: float | None, hi: float | None, step: float | None = None):
    """The panel's value range: ``lo``/``hi`` where given, else the data's; with ``step``, the
    given range widened in steps of ``step`` until it holds every value, so nothing is clipped."""
    ys = np.concatenate([np.asarray(s[key]) for s in series])
    ys = ys[np.isfinite(ys)]
    if step is not None and ys.size:
        lo = min(lo, step * np.floor(float(ys.min()) / step))
        hi = max(hi, step * np.ceil(float(ys.max()) / step))
    return (lo if lo is not None else float(ys.min())), (hi if hi is not None else float(ys.max()) * 1.05)


def write_spectrum_plot(path: str | os.PathLike, series: Sequence[tuple[str, np.ndarray, np.ndarray, np.ndarray]],
                        title: str, fmt: str, *, xlabel: str = "frequency (cycles per tile side)") -> None:
    """Two panels (radial power, anisotropy in dB) of ``series``: ``(label, frequency, power,
    anisotropy)`` each; as ``fmt`` (``"svg"`` or ``"png"``); ``xlabel`` names the frequency's unit."""
    W, H, M = 720, 260, 50
    panels = [("radial power", 1, 0.0, None, None), ("anisotropy (dB)", 2, -10.0, 10.0, 5.0)]
    fmax = max(float(np.max(s[1])) for s in series)
    lines, texts, axes = [], [(M, 20, title)], []
    for p, (name, key, lo, hi, step) in enumerate(panels):
        lo, hi = _layout(series, key + 1, lo, hi, step)
        top = 40 + p * (H + 40)
        axes.append((M, top, W - 20, top + H))
        texts += [(M + 4, top + 14, name), (M - 46, top + 10, f"{hi:.3g}"), (M - 46, top + H, f"{lo:.3g}")]
        for k, s in enumerate(series):
            f, y = np.asarray(s[1]), np.clip(np.asarray(s[key + 1]), lo, hi)
            xs = M + f / fmax * (W - 20 - M)
            ys = top + H - (y - lo) / (hi - lo or 1) * H
            lines.append((_SERIES[k % len(_SERIES)], list(zip(xs.tolist(), ys.tolist()))))
            if p == 0:
                texts.append((W - 260, top + 16 + 14 * k, f"— {s[0]}", _SERIES[k % len(_SERIES)]))
    bottom = 40 + 2 * (H + 40)
    texts.append((M, bottom - 16, f"{xlabel}, 0 .. {fmax:.3g}"))
    if fmt == "svg":
        import svgwrite

        dwg = svgwrite.Drawing(size=(W, bottom), profile="full", debug=False)
        dwg.add(dwg.rect((0, 0), (W, bottom), fill="white"))
        for x0, y0, x1, y1 in axes:
            dwg.add(dwg.rect((x0, y0), (x1 - x0, y1 - y0), fill="none", stroke="#999999"))
        for colour, pts in lines:
            dwg.add(dwg.polyline([(round(x, 2), round(y, 2)) for x, y in pts], fill="none", stroke=colour,
                                 stroke_width=1.2))
        for t in texts:
            dwg.add(dwg.text(t[2], insert=(t[0], t[1]), font_size="12px", font_family="sans-serif",
                             fill=t[3] if len(t) > 3 else "#333333"))
        with atomic_write(path) as fh:
            fh.write(dwg.tostring())
        return
    from PIL import Image, ImageColor, ImageDraw

    img = Image.new("RGB", (W, bottom), "white")
    draw = ImageDraw.Draw(img)
    for x0, y0, x1, y1 in axes:
        draw.rectangle([x0, y0, x1, y1], outline=(153, 153, 153))
    for colour, pts in lines:
        draw.line(pts, fill=ImageColor.getrgb(colour), width=1)
    for t in texts:
        draw.text((t[0], t[1] - 11), t[2].replace("—", "-"), fill=ImageColor.getrgb(t[3]) if len(t) > 3 else (51, 51, 51))
    with atomic_write(path, "wb", encoding=None) as fh:
        img.save(fh, format="PNG")


def texture_image(evaluation: dict, image=None, background=None) -> np.ndarray:
    """An RGB texture (§6.6.2, figure 6.6) from the object distribution function evaluated at
    every pixel (:func:`tilesolve.families.poisson.objects`): inside a Poisson disk, the object
    (``image``, an RGBA array drawn in the disk's square ``[-1, 1]^2``, or a shaded disk coloured
    by the point's id); outside, the ``background`` picture (an RGB or RGBA array, repeated from
    the top-left corner: a wall, a texture), or a background shaded by the distance to the
    closest point."""
    inside, local, ident, dist = evaluation["inside"], evaluation["local"], evaluation["id"], evaluation["distance"]
    if background is None:
        shade = np.clip(1.0 - 0.35 * np.minimum(dist / max(float(dist.max()), 1e-12), 1.0), 0, 1)
        out = (np.array([236.0, 230.0, 214.0]) * shade[..., None])
    else:
        bg = np.asarray(background, dtype=np.float64)[..., :3]
        rows, cols = inside.shape
        out = bg[np.arange(rows) % bg.shape[0]][:, np.arange(cols) % bg.shape[1]]
    palette = np.array([[int(c[i:i + 2], 16) for i in (1, 3, 5)] for c in _SERIES], dtype=np.float64)
    if image is None:
        mix = (ident[..., 0] * 73856093 ^ ident[..., 1] * 19349663 ^ ident[..., 2] * 83492791) % len(palette)
        light = 1.0 - 0.5 * np.sum(local**2, axis=-1)
        disk = palette[mix] * np.clip(light, 0, 1)[..., None]
        out[inside] = disk[inside]
    else:
        img = np.asarray(image, dtype=np.float64)
        ih, iw = img.shape[:2]
        col = np.clip(((local[..., 0] + 1) / 2 * iw).astype(np.int64), 0, iw - 1)
        row = np.clip(((1 - local[..., 1]) / 2 * ih).astype(np.int64), 0, ih - 1)
        sampled = img[row, col]
        alpha = (sampled[..., 3:4] / 255.0) * inside[..., None]
        out = out * (1 - alpha) + sampled[..., :3] * alpha
    return np.clip(out + 0.5, 0, 255).astype(np.uint8)


def write_texture_png(path: str | os.PathLike, evaluation: dict, image=None, background=None) -> None:
    """:func:`texture_image` as a PNG."""
    from PIL import Image

    with atomic_write(path, "wb", encoding=None) as f:
        Image.fromarray(texture_image(evaluation, image, background), "RGB").save(f, format="PNG")
