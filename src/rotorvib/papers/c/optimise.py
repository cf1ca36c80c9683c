"""Genetic-algorithm tuning of the dual absorber (paper C, section 4)."""

from __future__ import annotations

import numpy as np

from rotorvib.methods.ga import minimise
from rotorvib.methods.optima import GAResult
from rotorvib.models.absorber.frequency_response import theta_eq20
from rotorvib.models.absorber.parameters import Rotor, design_bounds


def resonance_objective(rotor: Rotor, printed_determinant: bool = False):
    """``x[..., 8] -> |Theta(omega_n)|`` (rad), eq. (20) with the correct determinant (or the
    printed one)."""

    def objective(x):
        return np.abs(theta_eq20(rotor, x, rotor.omega_n, printed_determinant=printed_determinant))

    return objective


def tune_dual_absorber(rotor: Rotor, bounds: dict, *, pop_size: int, n_gen: int, seed: int,
                       sbx_eta: float, pm_eta: float, progress=None,
                       printed_determinant: bool = False) -> GAResult:
    """Minimise :func:`resonance_objective` over the paper's bounds."""
    lower, upper = design_bounds(bounds)
    return minimise(resonance_objective(rotor, printed_determinant), lower, upper, pop_size=pop_size, n_gen=n_gen,
                    seed=seed, sbx_eta=sbx_eta, pm_eta=pm_eta, progress=progress)
