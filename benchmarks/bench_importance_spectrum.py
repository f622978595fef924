"""Frequency artefacts of polyomino importance sampling, with and without its learnt correction
table (Ostromoukhov, "Sampling with polyominoes", SIGGRAPH 2007; class notes Part IV; issue 23
§3: "the notes' point is the absence of frequency artefacts in the polyomino version").

Every row samples the same constant-density window (the unit square, the flat test image) at
about N points, ``--runs`` seeds, and measures the averaged periodogram (Ulichney 1987):

* **ring**: the frequency (cycles per unit) of the largest radially averaged power, the main
  ring of blue noise (arbitrary for white noise, whose radial power is flat);
* **peak**: the peak factor, the largest periodogram value over the mean of its annulus (about
  ``ln(annulus size) / runs`` + 1 for a smooth spectrum; a lattice or a periodic pattern gives
  spikes of tens to hundreds), and **off-ring peak**, the same away from the main ring
  (annuli more than 20% of its radius from it);
* **anisotropy**: the mean over annuli of ``10 log10(var / mean^2)`` in dB (``-10 log10(runs)``
  for an isotropic spectrum);
* **discrepancy**: the star discrepancy of the points on the unit square (anchored boxes on a
  64 x 64 grid), mean over the runs;
* **verified**: the same sampler on the radial test image (256 x 256, 20,000 points), checked
  by the independent verifier (:func:`tilesolve.verify.importance.importance_violations`:
  inside the image, the count and the counts of 2 x 2 and 4 x 4 blocks near their shares).

Rows: the polyomino sampler (X pentomino, chair) uncorrected (samples at tile centroids) and
corrected (the default), and for the X pentomino the correction's ingredients apart (children
ranked in a random order alone; with the table's mean offsets but no spread); Penrose sampling
(Ostromoukhov 2004, unjittered), the sampler the 2007 paper improves on; the anchors on
the same window in the same run: plain rejection sampling (uniform random points: white noise)
and dart throwing (scipy's ``qmc.PoissonDisk``, Bridson, filling the square: blue noise). Writes the radial spectra
(SVG and PNG, the project's spectrum plot) and the periodograms (PNG) to ``--out``.

Usage::

    python benchmarks/bench_importance_spectrum.py                 # N = 4096, 8 runs
    python benchmarks/bench_importance_spectrum.py --quick         # N = 1024, 4 runs
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=4096, help="samples of the window (default: %(default)s)")
    ap.add_argument("--runs", type=int, default=8, help="seeds averaged (default: %(default)s)")
    ap.add_argument("--seed", type=int, default=1, help="first seed (default: %(default)s)")
    ap.add_argument("--quick", action="store_true", help="N = 1024, 4 runs")
    ap.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "results"),
                    help="folder of the pictures (default: benchmarks/results)")
    args = ap.parse_args()
    n, runs = (1024, 4) if args.quick else (args.points, args.runs)

    from scipy.stats import qmc

    from tilesolve.constructive.importance import _polyomino, load_corrections, sample
    from tilesolve.families.importance import spectrum_measures
    from tilesolve.io.poisson_plots import write_spectrum_plot
    from tilesolve.io.stipple import write_periodograms_png
    from tilesolve.model.importance import ImportanceProblem, builtin_density
    from tilesolve.verify.importance import importance_violations, weighted_discrepancy

    flat, radial = builtin_density("flat", 64), builtin_density("radial", 256)

    def poly(tile, correct):
        return lambda s: sample(ImportanceProblem(flat, n, "polyomino", tile, correct=correct), seed=s)

    def dart(s):
        # Bridson's algorithm filling the square at a radius that fits about n points (measured:
        # a maximal set holds about 0.61 / r^2 points a unit area)
        return qmc.PoissonDisk(2, radius=0.78 / np.sqrt(n), seed=s).fill_space()

    x = load_corrections("x-pentomino")
    rows = [
        ("polyomino (x-pentomino), uncorrected", poly("x-pentomino", False), ("x-pentomino", False)),
        ("  ranks shuffled, no table", lambda s: _polyomino(flat, n, "x-pentomino", False, s, shuffle=True), None),
        ("  ranks shuffled, table means only",
         lambda s: _polyomino(flat, n, "x-pentomino", False, s, shuffle=True, table=x, noise=False), None),
        ("polyomino (x-pentomino), corrected", poly("x-pentomino", True), ("x-pentomino", True)),
        ("polyomino (chair), uncorrected", poly("chair", False), ("chair", False)),
        ("polyomino (chair), corrected", poly("chair", True), ("chair", True)),
        ("penrose (Ostromoukhov 2004)", lambda s: sample(ImportanceProblem(flat, n, "penrose"), seed=s), "penrose"),
        ("rejection (white noise, anchor)", lambda s: sample(ImportanceProblem(flat, n, "rejection"), seed=s),
         None),
        ("dart throwing (scipy PoissonDisk, anchor)", dart, None),
    ]
    k_max = int(min(3 * np.sqrt(n), 256))
    print(f"constant density, unit square, about {n:,} points, {runs} runs averaged, frequencies up to {k_max}")
    print("| sampler | points | ring | peak | off-ring peak | anisotropy dB | discrepancy | verified (radial, 20k) "
          "| s a run |")
    print("|---|---:|---:|---:|---:|---:|---:|---|---:|")
    measured = {}
    for name, run, check in rows:
        t0 = time.perf_counter()
        sets = [np.asarray(run(args.seed + i)) for i in range(runs)]
        dt = (time.perf_counter() - t0) / runs
        m = spectrum_measures(sets, k_max)
        disc = float(np.mean([weighted_discrepancy(p, flat.values) for p in sets]))
        verified = ""
        if check:
            p = (ImportanceProblem(radial, 20_000, "penrose") if check == "penrose" else
                 ImportanceProblem(radial, 20_000, "polyomino", check[0], correct=check[1]))
            bad = importance_violations(sample(p, seed=args.seed), radial.values, expected=20_000)
            verified = "ok" if not bad else f"{len(bad)} violations"
        measured[name] = m
        print(f"| {name} | {np.mean([len(p) for p in sets]):,.0f} | {m['ring']} | {m['peak']:.1f} | "
              f"{m['off_ring_peak']:.1f} | {m['anisotropy_db']:.2f} | {disc:.4f} | {verified} | {dt:.2f} |")

    os.makedirs(args.out, exist_ok=True)
    anchors = ["rejection (white noise, anchor)", "dart throwing (scipy PoissonDisk, anchor)"]
    for tile in ("x-pentomino", "chair"):
        names = [f"polyomino ({tile}), uncorrected", f"polyomino ({tile}), corrected"] + anchors
        series = [(nm.split(" (anchor")[0].replace(", anchor)", ")"), measured[nm]["frequency"],
                   measured[nm]["power"], measured[nm]["anisotropy"]) for nm in names]
        title = f"polyomino sampling ({tile}) with and without its correction table: {n:,} points, {runs} runs"
        stem = os.path.join(args.out, f"importance_correction_{tile}")
        for fmt in ("svg", "png"):
            write_spectrum_plot(f"{stem}.{fmt}", series, title, fmt, xlabel="frequency (cycles per unit)")
        write_periodograms_png(f"{stem}_periodograms.png", [(s[0], measured[nm]["periodogram"])
                                                            for s, nm in zip(series, names)], title)
    print(f"pictures: {args.out}/importance_correction_{{x-pentomino,chair}}.{{svg,png}}, *_periodograms.png")


if __name__ == "__main__":
    main()
