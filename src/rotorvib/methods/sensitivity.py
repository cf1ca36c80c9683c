"""Global sensitivity analysis: Sobol indices with bootstrap confidence intervals (SALib).

For a model ``Y = f(X)`` with independent inputs ``X_j`` uniform on their ranges, the
first-order index ``S1_j = V[E(Y | X_j)] / V(Y)`` is the share of the variance of ``Y`` that
``X_j`` explains alone, and the total index ``ST_j = E[V(Y | X_~j)] / V(Y)`` its share with all
its interactions.  Saltelli's scheme estimates both from ``N (D + 2)`` evaluations on a
scrambled Sobol sequence (Jansen's estimator for ``ST``); the confidence intervals come from
bootstrap resampling of the ``N`` base points.

The evaluations are grouped by base point, so the first ``n (D + 2)`` of them are the design for
``n`` base points: :func:`sobol_indices` gives the indices at several ``n`` from one set of
runs, which shows whether they have converged. What a study's dataset says of a value against
its bands is :mod:`rotorvib.methods.bands`, which reads the dataset without SALib.  SALib
(with ``scipy.stats``, about 0.4 s) is imported by the two functions that call it: a job that
reads a study's rows through its paper's module does not load it.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.checks import finite_array, integer, sobol_design_problem
from rotorvib.methods.bands import RESOLVED_HALF_WIDTH


def problem(ranges: dict[str, tuple[float, float]]) -> dict:
    """SALib's problem for inputs ``name -> (low, high)``, each uniform; ``ValueError`` naming
    an input whose range is not finite and increasing."""
    for name, (lo, hi) in ranges.items():
        if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
            raise ValueError(f"input {name!r}: range [{lo}, {hi}] must be finite and increasing")
    return {"num_vars": len(ranges), "names": list(ranges),
            "bounds": [[float(lo), float(hi)] for lo, hi in ranges.values()]}


def sample(spec: dict, n_base: int, seed: int) -> np.ndarray:
    """The ``n_base (D + 2)`` input points of Saltelli's scheme (``n_base``: a power of 2)."""
    if problem_text := sobol_design_problem(integer("n_base", n_base, 2), [n_base]):
        raise ValueError(f"n_base: {problem_text}")
    from SALib.sample import sobol as sobol_sample

    return sobol_sample.sample(spec, n_base, calc_second_order=False, seed=seed)


def sobol_indices(spec: dict, y, n_bases, *, resamples: int, seed: int,
                  conf_level: float = 0.95) -> dict[str, np.ndarray]:
    """``S1``, ``S1_conf``, ``ST``, ``ST_conf`` (half-widths of the ``conf_level`` intervals),
    each of shape ``(len(n_bases), D)``, from the first ``n (D + 2)`` outputs ``y`` for each
    ``n`` of ``n_bases``.  Non-finite outputs raise ``ValueError``; an output that does not vary
    has no variance to share out, and its indices are NaN (undefined; SALib would give 0)."""
    from SALib.analyze import sobol as sobol_analyze

    d = spec["num_vars"]
    y = finite_array("y", y, shape=(None,))
    out = {key: np.empty((len(n_bases), d)) for key in ("S1", "S1_conf", "ST", "ST_conf")}
    for i, n in enumerate(n_bases):
        if n * (d + 2) > len(y):
            raise ValueError(f"n_base = {n} needs {n * (d + 2)} outputs, {len(y)} given")
        part = y[:n * (d + 2)]
        if np.ptp(part) == 0.0:
            for key in out:
                out[key][i] = np.nan
            continue
        result = sobol_analyze.analyze(spec, part, calc_second_order=False,
                                       num_resamples=resamples, conf_level=conf_level,
                                       seed=seed)
        for key in out:
            out[key][i] = result[key]
    return out


def study_dataset(spec: dict, x, outputs: dict, nominal: dict, units: dict, *, n_bases,
                  resamples: int, seed: int, percentiles=(5.0, 50.0, 95.0)) -> xr.Dataset:
    """A sensitivity study as a dataset: the inputs ``x`` and ``outputs`` (quantity -> values
    at ``x``), the indices of every quantity at each of ``n_bases``, the ``percentiles`` of
    each quantity over its evaluations (its uncertainty band) and its ``nominal`` value.

    An output may be NaN where it has no value (a run that never balances has no balance
    time): its band is then over the points with a value only (``n_valued`` counts them, never
    a cap or penalty in their place), and its indices, which need every point, are NaN."""
    names = list(outputs)
    valued = {q: np.isfinite(np.asarray(outputs[q], float)) for q in names}
    undefined = {key: np.full((len(n_bases), spec["num_vars"]), np.nan)
                 for key in ("S1", "S1_conf", "ST", "ST_conf")}
    indices = {q: sobol_indices(spec, outputs[q], n_bases, resamples=resamples, seed=seed)
               if valued[q].all() else undefined for q in names}
    dims = ("quantity", "n_base", "input")
    data = {key: (dims, np.stack([indices[q][key] for q in names]),
                  {"long_name": text, "units": "1"})
            for key, text in (("S1", "first-order Sobol index"),
                              ("S1_conf", "half-width of the 95 % bootstrap interval of S1"),
                              ("ST", "total Sobol index"),
                              ("ST_conf", "half-width of the 95 % bootstrap interval of ST"))}
    y = np.stack([np.asarray(outputs[q], float) for q in names])
    data["y"] = (("quantity", "sample"), y, {"long_name": "model output at each input point "
                                                          "(units by quantity)", "units": "1"})
    with np.errstate(invalid="ignore"):
        band = np.array([np.percentile(row[np.isfinite(row)], percentiles) if np.isfinite(row).any()
                         else np.full(len(percentiles), np.nan) for row in y])
    data["band"] = (("quantity", "percentile"), band,
                    {"long_name": "percentiles of the output over the input points where it has "
                                  "a value (units by quantity)", "units": "1"})
    data["n_valued"] = ("quantity", np.array([int(valued[q].sum()) for q in names], np.int64),
                        {"long_name": "input points at which the output has a value (a run "
                                      "that never balances has no balance time)", "units": "1"})
    data["nominal"] = ("quantity", [float(nominal[q]) for q in names],
                       {"long_name": "output at the nominal inputs (units by quantity)",
                        "units": "1"})
    data["x"] = (("sample", "input"), np.asarray(x, float),
                 {"long_name": "input point of Saltelli's scheme (units by input)", "units": "1"})
    bounds = np.asarray(spec["bounds"], float)
    return xr.Dataset(
        data,
        coords={"input_name": ("input", np.array(spec["names"], dtype=object),
                               {"long_name": "uncertain input"}),
                "input_low": ("input", bounds[:, 0], {"long_name": "lower end of the input's "
                                                                   "range", "units": "1"}),
                "input_high": ("input", bounds[:, 1], {"long_name": "upper end of the input's "
                                                                    "range", "units": "1"}),
                "quantity_name": ("quantity", np.array(names, dtype=object),
                                  {"long_name": "reproduced quantity"}),
                "quantity_units": ("quantity", np.array([units[q] for q in names],
                                                        dtype=object),
                                   {"long_name": "units of the quantity"}),
                "n_base": ("n_base", np.asarray(n_bases, np.int32),
                           {"long_name": "base points of Saltelli's scheme", "units": "1"}),
                "percentile": ("percentile", np.asarray(percentiles, float),
                               {"long_name": "percentile of the output", "units": "1"})},
        attrs={"sobol_resamples": resamples, "sobol_seed": seed,
               "sobol_resolved_half_width": RESOLVED_HALF_WIDTH},
    )
