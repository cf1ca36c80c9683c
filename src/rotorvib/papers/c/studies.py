"""Paper C's studies as labelled datasets (xarray), one function per dataset of the workflow.

Each function computes one study from model parameters and returns an ``xr.Dataset`` whose
variables carry ``long_name`` and ``units``; writing (with provenance) is left to
:func:`rotorvib.io.datasets.write_dataset`.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import xarray as xr

from rotorvib.io.coords import label_coord
from rotorvib.methods.optima import GAResult
from rotorvib.models.absorber.frequency_response import (bare_rotor_amplitude,
                                                         dimensionless_amplitude,
                                                         natural_frequencies, rotor_peak,
                                                         steady_state, theta_eq20)
from rotorvib.models.absorber.parameters import (DUAL_NAMES, Rotor, design_bounds,
                                                 dual_from_vector, dual_to_vector,
                                                 effective_mass_ratio, undamped)
from rotorvib.models.absorber.time_response import (linear_response, response_times, simulate,
                                                    undamped_resonance_envelope)
from rotorvib.models.absorber.tuning import CONSTRUCTIONS, den_hartog_single, mass_ratio_family

REFERENCE = ("Paper C: A dual dynamic vibration absorber for the torsional vibration of a rotor, "
             "tuned by a genetic algorithm (Persian, 2024; journal, volume and pages not in the "
             "source text; data/papers.yaml)")
_UNITS = {"m": "kg", "k": "N m-1", "c": "N s m-1", "d": "m"}
_W = {"long_name": "forcing frequency ratio omega/omega_n", "units": "1"}
_D = "dimensionless torsional amplitude D = |Theta| k_t / Gamma0"


def _parameter_coords() -> dict:
    return {"parameter_name": ("parameter", np.array(DUAL_NAMES, dtype=object),
                               {"long_name": "design variable of the dual absorber (Table 2)"})}


def _design(values, long_name) -> xr.DataArray:
    return xr.DataArray(np.asarray(values, float), dims="parameter",
                        attrs={"long_name": long_name + " (units: kg, N m-1, N s m-1, m by kind)",
                               "units": "1"})


def _amplitude(rotor, sets, omega, what):
    return xr.DataArray(dimensionless_amplitude(rotor, steady_state(rotor, sets, omega)[..., 0]),
                        dims="w", attrs={"long_name": f"{_D}, {what}", "units": "1"})


def ga_dataset(rotor: Rotor, result: GAResult, table2, bounds: dict) -> xr.Dataset:
    """Convergence history and optimum of the genetic algorithm beside Table 2 (section 4)."""
    lower, upper = design_bounds(bounds)
    x_t2 = dual_to_vector(table2)
    theta = {name: float(np.abs(theta_eq20(rotor, x, rotor.omega_n, printed_determinant=p)))
             for name, x, p in (("opt", result.x, False), ("table2", x_t2, False),
                                ("table2_printed_det", x_t2, True))}
    gen = np.arange(1, len(result.history["best_f"]) + 1)
    ds = xr.Dataset(
        {
            "best_objective": ("generation", result.history["best_f"],
                               {"long_name": "best |Theta(omega_n)| in the population", "units": "rad"}),
            "mean_objective": ("generation", result.history["mean_f"],
                               {"long_name": "population mean of |Theta(omega_n)|", "units": "rad"}),
            "n_evaluations": ("generation", result.history["n_eval"],
                              {"long_name": "cumulative objective evaluations", "units": "1"}),
            "best_design": (("generation", "parameter"), result.history["best_x"],
                            {"long_name": "best design of each generation (SI units by kind)",
                             "units": "1"}),
            "x_opt": _design(result.x, "design found by the genetic algorithm"),
            "x_table2": _design(x_t2, "design of Table 2"),
            "lower_bound": _design(lower, "lower bound of section 4"),
            "upper_bound": _design(upper, "upper bound of section 4"),
            "theta_opt": ((), theta["opt"], {"long_name": "|Theta(omega_n)| at the GA optimum, "
                                             "eq. (20) with the true determinant", "units": "rad"}),
            "theta_table2": ((), theta["table2"], {"long_name": "|Theta(omega_n)| for Table 2, "
                                                   "eq. (20) with the true determinant",
                                                   "units": "rad"}),
            "theta_table2_printed_det": ((), theta["table2_printed_det"],
                                         {"long_name": "|Theta(omega_n)| for Table 2, eq. (20) "
                                          "with the printed determinant", "units": "rad"}),
            "mass_ratio_opt": ((), result.x[1] / result.x[0],
                               {"long_name": "mass ratio m2/m1 at the GA optimum", "units": "1"}),
            "effective_mass_ratio_opt": ((), effective_mass_ratio(rotor, dual_from_vector(result.x)),
                                         {"long_name": "added inertia sum 2 m d^2 / J at the GA "
                                          "optimum", "units": "1"}),
        },
        coords={"generation": ("generation", gen, {"long_name": "GA generation", "units": "1"}),
                **_parameter_coords()},
        attrs={"title": "Paper C: genetic-algorithm tuning of the dual absorber",
               "summary": "Convergence history and optimum of |Theta(omega_n)| (eq. 20) over the "
                          "bounds of section 4, beside Table 2",
               "references": f"{REFERENCE}; section 4, Table 2"},
    )
    return ds


def frequency_response_dataset(rotor: Rotor, table2, x_opt, w) -> xr.Dataset:
    """Fig 5: D(w) without absorber, for Table 2, Table 2 undamped and the GA optimum; the
    undamped natural frequencies of Table 2 (where its undamped D is unbounded) and the true
    peak of each damped design over all frequencies (which may lie outside ``w``)."""
    omega = np.asarray(w) * rotor.omega_n
    x_t2 = dual_to_vector(table2)
    printed = dimensionless_amplitude(rotor, theta_eq20(rotor, x_t2, omega, printed_determinant=True))
    amplitudes = steady_state(rotor, table2, omega)
    peaks = [rotor_peak(rotor, sets) for sets in (table2, dual_from_vector(x_opt))]
    return xr.Dataset(
        {
            "natural_w_table2_undamped": (
                "mode", natural_frequencies(rotor, undamped(table2)),
                {"long_name": "undamped natural frequencies of Table 2 / omega_n (D unbounded "
                              "there unless the rotor does not move in the mode)", "units": "1"}),
            "peak_w": ("design", [p[0] for p in peaks],
                       {"long_name": "frequency of the largest D over all frequencies",
                        "units": "1"}),
            "peak_D": ("design", [p[1] for p in peaks],
                       {"long_name": f"largest {_D} over all frequencies", "units": "1"}),
            "D_none": ("w", bare_rotor_amplitude(w),
                       {"long_name": f"{_D}, no absorber, 1/|1 - w^2|", "units": "1",
                        "comment": "infinite at w = 1 (undamped resonance)"}),
            "D_table2": _amplitude(rotor, table2, omega, "Table 2 dual absorber"),
            "D_table2_undamped": _amplitude(rotor, undamped(table2), omega,
                                            "Table 2 dual absorber with zero damping"),
            "D_ga": _amplitude(rotor, dual_from_vector(x_opt), omega,
                               "dual absorber found by the genetic algorithm"),
            "D_table2_printed_det": ("w", printed,
                                     {"long_name": f"{_D}, Table 2, eq. (20) with the printed "
                                      "determinant", "units": "1"}),
            "omega_n": ((), rotor.omega_n, {"long_name": "natural frequency of the rotor without "
                                            "absorber, sqrt(k_t/J)", "units": "rad s-1"}),
            "static_deflection": ((), rotor.Gamma0 / rotor.k_t,
                                  {"long_name": "static twist Gamma0/k_t (D = 1)", "units": "rad"}),
            "S1_table2": ("w", np.abs(amplitudes[:, 1]),
                          {"long_name": "steady amplitude of absorber set 1, Table 2", "units": "m"}),
            "S2_table2": ("w", np.abs(amplitudes[:, 2]),
                          {"long_name": "steady amplitude of absorber set 2, Table 2", "units": "m"}),
        },
        coords={"w": ("w", np.asarray(w, float), _W),
                **label_coord("design", ["table2", "ga"],
                              "damped design: Table 2 or the GA optimum")},
        attrs={"title": "Paper C: frequency response of the rotor with and without absorbers",
               "summary": "D(w) of eq. (20) for no absorber, Table 2, Table 2 undamped and the "
                          "GA optimum (Fig 5)",
               "references": f"{REFERENCE}; eqs. (14)-(20), Fig 5"},
    )


def mass_ratio_dataset(rotor: Rotor, table2, mu, w, constructions) -> xr.Dataset:
    """Fig 6: D(construction, mu, w) for the mass-ratio family built from Table 2 under each
    construction of :data:`~rotorvib.models.absorber.tuning.CONSTRUCTIONS`."""
    omega = np.asarray(w) * rotor.omega_n
    D = np.stack([[dimensionless_amplitude(
        rotor, steady_state(rotor, mass_ratio_family(table2, m, c), omega)[..., 0]) for m in mu]
        for c in constructions])
    built = "; ".join(f"{c}: {CONSTRUCTIONS[c]}" for c in constructions)
    return xr.Dataset(
        {"D": (("construction", "mu", "w"), D,
               {"long_name": f"{_D}, dual absorber of mass ratio mu", "units": "1"})},
        coords={"construction_name": ("construction", np.array(constructions, dtype=object),
                                      {"long_name": f"construction of the family ({built})"}),
                "mu": ("mu", np.asarray(mu, float), {"long_name": "mass ratio m2/m1", "units": "1"}),
                "w": ("w", np.asarray(w, float), _W)},
        attrs={"title": "Paper C: frequency response for the mass-ratio family",
               "summary": f"D(w) for m2 = mu m1 ({built}), other parameters of Table 2 (Fig 6)",
               "references": f"{REFERENCE}; Fig 6"},
    )


def distance_dataset(rotor: Rotor, table2, offsets, w) -> xr.Dataset:
    """The abstract's distance study: D(offset, w) and the true peak of Table 2's design with
    both sets moved by ``offset`` (m) from the disk centre, ``d_j -> d_j + offset``."""
    if min(s.d for s in table2) + min(offsets) <= 0:
        raise ValueError(f"paper_c.distance_study.offsets: {min(offsets)} m moves a set through "
                         "the disk centre")
    omega = np.asarray(w) * rotor.omega_n
    designs = [tuple(replace(s, d=s.d + off) for s in table2) for off in offsets]
    D = np.stack([dimensionless_amplitude(rotor, steady_state(rotor, sets, omega)[..., 0])
                  for sets in designs])
    peaks = [rotor_peak(rotor, sets) for sets in designs]
    return xr.Dataset(
        {"D": (("offset", "w"), D, {"long_name": f"{_D}, Table 2 with both sets moved",
                                    "units": "1"}),
         "peak_w": ("offset", [p[0] for p in peaks],
                    {"long_name": "frequency of the largest D over all frequencies", "units": "1"}),
         "peak_D": ("offset", [p[1] for p in peaks],
                    {"long_name": f"largest {_D} over all frequencies", "units": "1"})},
        coords={"w": ("w", np.asarray(w, float), _W),
                "offset": ("offset", np.asarray(offsets, float),
                           {"long_name": "offset of both absorber sets from Table 2's distances "
                                         "d1, d2 to the disk centre", "units": "m"})},
        attrs={"title": "Paper C: the absorbers' distance from the disk centre",
               "summary": "D(w) and its peak for Table 2 with both absorber sets moved radially "
                          "(the abstract's distance study)",
               "references": f"{REFERENCE}; abstract"},
    )


def _linear_and_nonlinear(rotor: Rotor, sets, t, rtol: float, atol: float) -> np.ndarray:
    """Responses from rest at resonance, ``[linear (14), nonlinear (8)-(10)]``: (14) solved
    exactly (:func:`linear_response`) for a damped design, (8)-(10) integrated; without
    absorber the two are one equation, ``J theta'' + k_t theta = Gamma``, integrated once
    (undamped at resonance, it has no steady state for the exact solution to use)."""
    nonlinear = simulate(rotor, sets, rotor.omega_n, t, rtol=rtol, atol=atol)
    linear = linear_response(rotor, sets, rotor.omega_n, t) if sets else nonlinear
    return np.stack([linear, nonlinear])


def time_response_dataset(rotor: Rotor, table2, d_single: float, *, t_end: float,
                          samples_per_period: int, rtol: float, atol: float) -> xr.Dataset:
    """Figs 3, 4, 7: responses from rest to Gamma0 cos(omega_n t), linear (14) and nonlinear
    (8)-(10), without absorber, with the Den Hartog single set (ref. [8] stand-in) and with the
    Table 2 dual absorber."""
    t = response_times(rotor.omega_n, t_end, samples_per_period)
    single = den_hartog_single(rotor, m=table2[0].m + table2[1].m, d=d_single)
    cases = {"none": (), "single": (single,), "dual": tuple(table2)}
    data = {}
    for case, sets in cases.items():
        q = _linear_and_nonlinear(rotor, sets, t, rtol, atol)
        data[f"theta_{case}"] = (("model", "t"), q[..., 0],
                                 {"long_name": f"disk twist angle theta, absorber: {case}",
                                  "units": "rad"})
        for j in range(1, q.shape[-1]):
            data[f"s{j}_{case}"] = (("model", "t"), q[..., j],
                                    {"long_name": f"displacement of absorber set {j}, "
                                     f"absorber: {case}", "units": "m"})
    data["theta_none_exact_envelope"] = ("t", undamped_resonance_envelope(rotor, t),
                                         {"long_name": "exact envelope Gamma0 t/(2 J omega_n) of "
                                          "the undamped rotor at resonance", "units": "rad"})
    for name in "mkcd":
        data[f"single_{name}"] = ((), float(getattr(single, name)),
                                  {"long_name": f"Den Hartog single absorber parameter {name}",
                                   "units": _UNITS[name]})
    return xr.Dataset(
        data,
        coords={"t": ("t", t, {"long_name": "time since the start of the forcing", "units": "s"}),
                "model_name": ("model", np.array(["linear eq. (14)", "nonlinear eqs. (8)-(10)"],
                                                 dtype=object),
                               {"long_name": "equations solved",
                                "comment": "eq. (14) in closed form with an absorber, "
                                           "integrated without one (where it is (8)-(10)); "
                                           "(8)-(10) integrated (DOP853)"})},
        attrs={"title": "Paper C: forced time responses at resonance",
               "summary": "theta(t) and absorber displacements from rest under Gamma0 "
                          "cos(omega_n t): no absorber, Den Hartog single absorber, Table 2 dual "
                          "absorber; linear (14) and nonlinear (8)-(10) (Figs 3, 4, 7)",
               "references": f"{REFERENCE}; eqs. (8)-(14), Figs 3, 4, 7",
               "forcing": "Gamma0 cos(omega_n t) from rest",
               "comment": "The paper's kinetic energy (1)-(3) contains only theta', so the mean "
                          "spin Omega never enters; reproduced as printed."},
    )
