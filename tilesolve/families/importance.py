"""Importance sampling and stippling end to end (class notes Part IV: Penrose and polyomino
sampling; Part V: stippling): sample, verify, measure; the ``stipple`` family.

The family's question is an :class:`~tilesolve.model.importance.ImportanceProblem`; its one
route, ``sample``, runs the problem's sampler; its answer, a
:class:`~tilesolve.io.stipple.Samples`, is checked by :func:`stipple_violations`. Its file,
``tilesolve/stipple`` (:mod:`tilesolve.io.stipple`), embeds the density and the seed, so that
``tilesolve verify`` re-checks a stipple with no other file.

* :func:`stipple`: the samples of an :class:`~tilesolve.model.importance.ImportanceProblem`
  (:func:`tilesolve.constructive.importance.sample`), checked by
  :func:`tilesolve.verify.importance.importance_violations` (inside the domain; counts on 2 x 2
  and 4 x 4 blocks near the density's shares), with the density-weighted discrepancy.
* :func:`compare`: each method against plain rejection sampling in the same run: points a
  second and discrepancy on the image, and the spectra of the uniform case (a flat image, as
  the papers show them): the radially averaged power and anisotropy (Ulichney 1987;
  :func:`tilesolve.verify.poisson.radial_spectrum`), the averaged 2-D periodogram and its
  *peak factor*, the largest power over the mean of its annulus (about 10 for white noise,
  hundreds where a tiling's structure shows as spikes), also away from the main ring
  (:func:`spectrum_measures`). The polyomino sampler appears twice: with its learnt correction
  table (Ostromoukhov 2007; :class:`~tilesolve.constructive.importance.CorrectionTable`) and
  without it.

Examples
--------
>>> from tilesolve.model.importance import ImportanceProblem, builtin_density
>>> r = stipple(ImportanceProblem(builtin_density("radial", 32), 400, "penrose"), seed=1)
>>> r["violations"], 300 < len(r["points"]) < 500
([], True)
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from tilesolve.family import Codec, Demo, Family, RunOptions, register
from tilesolve.families.sampling_forms import STIPPLE_FORM
from tilesolve.io.stipple import FORMAT, VERSIONS, Samples, stipple_from_dict, stipple_to_dict
from tilesolve.model.importance import TEST_IMAGES, DensityMap, ImportanceProblem, builtin_density
from tilesolve.model.solution import Solution, Status
from tilesolve.verify.dappled import Violation

__all__ = ["FAMILY", "stipple", "compare", "spectrum_measures", "density_of", "VARIANTS", "sample_route",
           "stipple_violations", "image_violations"]

#: The rows of :func:`compare`: label, method, whether the correction table is asked for.
VARIANTS = (("penrose", "penrose", False), ("polyomino", "polyomino", True),
            ("uncorrected polyomino", "polyomino", False), ("rejection", "rejection", False))
#: Annuli within this fraction of the main ring's radius are the ring (:func:`spectrum_measures`).
RING_BAND = 0.2


def stipple(problem: ImportanceProblem, *, seed: int | None = None) -> dict:
    """Sample and check: ``points``, ``time_s`` (sampling alone), ``violations`` and
    ``discrepancy`` (density-weighted, on the problem's image)."""
    from tilesolve.constructive.importance import sample
    from tilesolve.verify.importance import importance_violations, weighted_discrepancy

    t0 = time.perf_counter()
    pts = sample(problem, seed=seed)
    dt = time.perf_counter() - t0
    values = problem.density.values
    return {"points": pts, "time_s": dt, "violations": importance_violations(pts, values, expected=problem.points),
            "discrepancy": weighted_discrepancy(pts, values)}


def _variant(problem: ImportanceProblem, method: str, correct: bool = True) -> ImportanceProblem:
    return ImportanceProblem(problem.density, problem.points, method, problem.tile,
                             0 if method == "rejection" else problem.lloyd, problem.jitter, correct)


def compare(problem: ImportanceProblem, *, seed: int | None = None, runs: int = 4,
            spectrum_points: int = 4096) -> list[dict]:
    """Every method of :data:`VARIANTS` on ``problem``'s image and settings (its ``method`` is
    ignored; rejection takes no Lloyd steps; the uncorrected polyomino row is left out where
    the tile has no correction table or the samples are jittered), one row each: ``name``,
    ``points``, ``time_s``, ``rate`` (points a second), ``discrepancy`` (on the image),
    ``violations``; and on a flat image of ``spectrum_points`` samples, ``runs`` seeds averaged,
    :func:`spectrum_measures`."""
    base = 0 if seed is None else seed
    flat = ImportanceProblem(builtin_density("flat", 64), spectrum_points, problem.method, problem.tile,
                             problem.lloyd, problem.jitter)
    k_max = int(min(3 * np.sqrt(spectrum_points), 256))
    rows = []
    for name, method, correct in VARIANTS:
        p = _variant(problem, method, correct)
        if name == "uncorrected polyomino" and not _variant(problem, method).corrected:
            continue  # the same sampler as the row above
        warm = ImportanceProblem(p.density, 64, method, p.tile, 0, p.jitter, correct)
        stipple(warm, seed=base)  # imports and tables loaded before the timed run
        one = stipple(p, seed=base)
        sets = [stipple(_variant(flat, method, correct), seed=base + i)["points"] for i in range(runs)]
        rows.append({"name": name if name != "polyomino" else f"polyomino ({problem.tile})",
                     "points": len(one["points"]), "time_s": one["time_s"],
                     "rate": len(one["points"]) / max(one["time_s"], 1e-9), "discrepancy": one["discrepancy"],
                     "violations": one["violations"], **spectrum_measures(sets, k_max)})
    return rows


def spectrum_measures(sets, k_max: int) -> dict:
    """The spectra of point sets of the unit square (averaged over ``sets``): ``frequency``,
    ``power``, ``anisotropy`` (dB; :func:`tilesolve.verify.poisson.radial_spectrum`, Ulichney
    1987) and its mean ``anisotropy_db``, ``periodogram`` (2-D), ``ring`` (the frequency of the
    largest radial power: the main ring of blue noise), ``peak`` (the peak factor: the largest
    power of the periodogram over the mean of its annulus) and ``off_ring_peak`` (the same away
    from the main ring: annuli more than :data:`RING_BAND` of its radius from it)."""
    from tilesolve.verify.poisson import periodogram, radial_spectrum

    f, power, aniso = radial_spectrum(sets, 1.0, k_max=k_max)
    grid = periodogram(sets, 1.0, k_max=k_max)
    ring = int(np.argmax(power[1:])) + 2  # annulus 1 (the domain's own window) left out
    return {"frequency": f, "power": power, "anisotropy": aniso, "anisotropy_db": float(np.mean(aniso)),
            "periodogram": grid, "ring": ring, "peak": _peak_factor(grid, power, k_max),
            "off_ring_peak": _peak_factor(grid, power, k_max, away_from=ring)}


def _peak_factor(grid: np.ndarray, ring_mean: np.ndarray, k_max: int, away_from: int | None = None) -> float:
    """The largest power of the periodogram over the mean of its annulus (annuli 2..k_max; with
    ``away_from``, those more than :data:`RING_BAND` of that annulus' radius from it)."""
    k = np.arange(-k_max, k_max + 1)
    ring = np.rint(np.hypot(*np.meshgrid(k, k, indexing="ij"))).astype(np.int64)
    keep = (ring >= 2) & (ring <= k_max)
    if away_from is not None:
        keep &= np.abs(ring - away_from) > RING_BAND * away_from
    return float((grid[keep] / ring_mean[ring[keep] - 1]).max())


def density_of(image: str | None, test_image: str | None) -> DensityMap:
    """The density a command samples: the picture file ``image`` or the built-in ``test_image``
    (``radial`` when neither is given)."""
    from tilesolve.errors import InvalidProblem

    if image and test_image:
        raise InvalidProblem("give an image file or --test-image, not both")
    if image:
        from tilesolve.io.stipple import read_density

        return read_density(image)
    return builtin_density(test_image or "radial", 256)


def sample_route(problem: ImportanceProblem, run: RunOptions) -> Solution:
    """The samples of the problem's sampler (:func:`tilesolve.constructive.importance.sample`)."""
    from tilesolve.constructive.importance import sample

    t0 = time.perf_counter()
    pts = sample(problem, seed=run.seed)
    return Solution(Status.SAT, Samples(pts), method="sample", seed=run.seed, time_s=time.perf_counter() - t0,
                    stats={"points": len(pts)})


def stipple_violations(problem: ImportanceProblem, answer: Any) -> list[Violation]:
    """The samples against the density (:func:`tilesolve.verify.importance.importance_violations`:
    inside the domain, the total and the counts of 2 x 2 and 4 x 4 blocks near their shares);
    samples that state a seed (a file's) are sampled again with it and compared exactly
    (:func:`tilesolve.verify.poisson.match_violations`): the sampling is the sampler's, it binds
    the seed, while the counts are checked independently. In a file (samples that state a seed)
    a density named after a built-in test image (:data:`~tilesolve.model.importance.TEST_IMAGES`)
    must be that image, pixel for pixel (:func:`image_violations`); a problem built in Python may
    name its own density as it likes."""
    from tilesolve.verify.importance import importance_violations

    if not isinstance(problem, ImportanceProblem) or not isinstance(answer, Samples):
        return [Violation("shape", "the answer is no set of samples of an importance problem")]
    out = image_violations(problem.density) if answer.seed is not None else []
    out += importance_violations(answer.points, problem.density.values, expected=problem.points)
    if answer.seed is None or any(v.kind == "bounds" for v in out):
        return out
    from tilesolve.constructive.importance import sample
    from tilesolve.verify.poisson import match_violations

    return out + match_violations(answer.points, sample(problem, seed=answer.seed),
                                  f"{problem.method} sampling with seed {answer.seed}")


def image_violations(density: DensityMap) -> list[Violation]:
    """A density that names a built-in test image (``radial``, ``gradient``, ``flat``) must equal
    :func:`~tilesolve.model.importance.builtin_density` of that name at its size, exactly (a
    stipple file's ``image`` is otherwise only a caption, and a file could claim the radial ramp
    while embedding another density); other names are the user's pictures, not checked."""
    if density.name not in TEST_IMAGES:
        return []
    rows, cols = density.values.shape
    if rows == cols and np.array_equal(density.values, builtin_density(density.name, rows).values):
        return []
    return [Violation("image", f"the density ({cols} x {rows} pixels) is not the built-in test image "
                               f"{density.name!r} it names ({density.name} at {rows} x {rows} pixels, "
                               "tilesolve.model.importance.builtin_density)")]


def auto_method(problem: ImportanceProblem) -> str:
    """``sample``: the one route (the problem names its sampler)."""
    return "sample"


def _draw(problem: ImportanceProblem, sol: Solution, path, fmt: str, *, title: str | None = None,
          **_ignored) -> None:
    """The stippled picture (:func:`tilesolve.io.stipple.write_stipple`)."""
    from tilesolve.io.stipple import write_stipple

    pts = sol.tiling.points
    write_stipple(path, pts, problem.density, title or f"{len(pts):,} points, {problem.describe().split(', ', 1)[1]}",
                  fmt)


def _demo() -> ImportanceProblem:
    return ImportanceProblem(builtin_density("radial", 128), 3000, "penrose", lloyd=4, jitter=True)


FAMILY = register(Family(
    name="stipple",
    title="importance sampling and stippling: samples whose density follows an image (Penrose, polyomino, "
          "rejection; class notes Parts IV-V)",
    problem_type=ImportanceProblem,
    routes={"sample": sample_route},
    auto=auto_method,
    verify=stipple_violations,
    codecs=(Codec(FORMAT, VERSIONS, stipple_from_dict, stipple_to_dict),),
    draw=_draw,
    demos=(Demo("stipple", "stippling: about 3,000 Penrose samples of the radial ramp, jittered, 4 Lloyd steps",
                _demo, method="sample"),),
    commands=("tilesolve.cli.sample:sample",),
    form=STIPPLE_FORM,
    route_help={"sample": "the problem's sampler: Penrose or polyomino subdivision (Ostromoukhov 2004, 2007) or "
                          "plain rejection, then its Lloyd steps"},
    answer="point set",
))
