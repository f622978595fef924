"""Tests of tilesolve.io.poisson_plots: the spectrum plot's panels hold every value."""
import re

import numpy as np

from tilesolve.io.poisson_plots import write_spectrum_plot


def _anisotropy_panel(tmp_path, anisotropy):
    f = np.linspace(0.1, 4.0, 40)
    series = [("tiles", f, np.ones_like(f), np.asarray(anisotropy, float))]
    path = tmp_path / "s.svg"
    write_spectrum_plot(path, series, "t", "svg")
    text = path.read_text()
    labels = re.findall(r">(-?[0-9.]+)</text>", text)
    lines = re.findall(r'points="([^"]+)"', text)
    return labels, [[float(v) for v in p.replace(",", " ").split()][1::2] for p in lines]


def test_anisotropy_within_ten_db_keeps_the_fixed_range(tmp_path):
    labels, _ = _anisotropy_panel(tmp_path, np.linspace(-3, 4, 40))
    assert "10" in labels and "-10" in labels


def test_anisotropy_past_ten_db_widens_the_panel_instead_of_clipping(tmp_path):
    values = np.linspace(-3, 17, 40)
    labels, ys = _anisotropy_panel(tmp_path, values)
    assert "20" in labels and "-10" in labels
    y = np.asarray(ys[1])                 # the anisotropy polyline
    assert len(np.unique(np.round(y, 2))) == len(values)  # no two values clipped onto one
