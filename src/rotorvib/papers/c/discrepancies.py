"""Paper C's discrepancy analysis: its printed amplitudes and GA optimum recomputed under the
hypotheses of :mod:`rotorvib.comparison.discrepancy`.

* ``theta_table2``: ``|Theta(omega_n)|`` of eq. (20) at Table 2's design, from Table 1's rotor
  and Table 2's eight values; definition alternative: the determinant as printed.
* ``fig3_theta_2s``: the amplitude of the bare rotor driven at resonance from rest, which is
  proportional to ``Gamma0 t / (2 J omega_n)`` (the exact envelope of the undamped rotor): a
  hypothesis scales the integrated amplitude by the ratio of envelopes, so the analysis is about
  the reproduced number itself, whatever the sampling of the integration.
* The GA's optimum (``theta_ga``, ``mu_opt``, ``table2_*``): variant, the same GA minimising the
  objective with the printed determinant.

Every parameter is a flat name: the rotor's ``M, R, k_t, Gamma0, J_factor``, Table 2's
``m1 ... d2`` and ``fig3_time``.
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np

from rotorvib.comparison.discrepancy import Hypothesis, invert, parameter_slips
from rotorvib.models.absorber.frequency_response import theta_eq20
from rotorvib.models.absorber.parameters import DUAL_NAMES, Rotor
from rotorvib.models.absorber.time_response import undamped_resonance_envelope
from rotorvib.papers.c.optimise import tune_dual_absorber

UNITS = {"M": "kg", "R": "m", "k_t": "N m/rad", "Gamma0": "N m", "J_factor": "1",
         "m1": "kg", "m2": "kg", "k1": "N/m", "k2": "N/m", "c1": "N s/m", "c2": "N s/m",
         "d1": "m", "d2": "m", "fig3_time": "s"}
ROTOR = tuple(f.name for f in fields(Rotor))
PRINTED_DETERMINANT = "determinant of eq. (20) as printed"


def _rotor(p: dict) -> Rotor:
    return Rotor(**{name: p[name] for name in ROTOR})


def theta_table2(p: dict, printed_determinant: bool = False) -> float:
    """``|Theta(omega_n)|`` (rad) of eq. (20) at the design ``p[m1 ... d2]``."""
    rotor = _rotor(p)
    x = [p[name] for name in DUAL_NAMES]
    return float(np.abs(theta_eq20(rotor, x, rotor.omega_n,
                                   printed_determinant=printed_determinant)))


def fig3_amplitude(p: dict) -> float:
    """``Gamma0 t / (2 J omega_n)`` (rad) at ``t = p["fig3_time"]``."""
    return float(undamped_resonance_envelope(_rotor(p), p["fig3_time"]))


#: Quantity -> (model, the parameters it depends on, whether the model is a ratio to apply to
#: the reproduced value).
MODELS = {"theta_table2": (theta_table2, ROTOR + DUAL_NAMES, False),
          "fig3_theta_2s": (fig3_amplitude, ROTOR + ("fig3_time",), True)}


def model_of(name: str, stated: dict, reproduced: float):
    """``(p -> value, parameters)`` of a quantity; a ratio model is scaled so that the stated
    parameters give the reproduced value."""
    model, params, ratio = MODELS[name]
    if not ratio:
        return model, params
    scale = reproduced / model(stated)
    return (lambda p: scale * model(p)), params


def hypotheses(stated: dict, names, parameters,
               reproduced: dict[str, float]) -> tuple[dict, list[Hypothesis]]:
    """Baselines and hypotheses (definitions, slips of ``parameters``) of the quantities
    ``names``."""
    baselines, found = {}, []
    for name in names:
        model, params = model_of(name, stated, reproduced[name])
        baselines[name] = model(stated)
        if name == "theta_table2":
            found.append(Hypothesis(name, PRINTED_DETERMINANT, "definition",
                                    theta_table2(stated, printed_determinant=True)))
        for p in (p for p in params if p in parameters):
            for label, value in parameter_slips(p, UNITS[p], stated[p]):
                found.append(Hypothesis(name, label, "parameter slip",
                                        model({**stated, p: value})))
    return baselines, found


def printed_determinant_ga(stated: dict, bounds: dict, ga: dict) -> list[Hypothesis]:
    """The GA's optimum when it minimises the objective with the printed determinant."""
    result = tune_dual_absorber(_rotor(stated), bounds, **ga, printed_determinant=True)
    name = f"GA minimising |Theta(omega_n)| with the {PRINTED_DETERMINANT}"
    x = result.x
    return ([Hypothesis("theta_ga", name, "variant", float(result.f)),
             Hypothesis("mu_opt", name, "variant", float(x[1] / x[0]))]
            + [Hypothesis(f"table2_{n}", name, "variant", float(v)) for n, v in zip(DUAL_NAMES, x)])


def inversions(name: str, printed: float, stated: dict, parameters, factor_range, n_scan: int,
               reproduced: float):
    """For each of ``parameters`` the quantity depends on, the value in ``stated *
    factor_range`` that reproduces ``printed``."""
    model, params = model_of(name, stated, reproduced)
    out = []
    for p in (p for p in params if p in parameters):
        def evaluate(xs, p=p):
            return np.array([model({**stated, p: float(x)}) for x in xs])

        out.append(invert(evaluate, printed, stated[p], stated[p] * factor_range[0],
                          stated[p] * factor_range[1], quantity=name, parameter=p,
                          n_scan=n_scan))
    return out
