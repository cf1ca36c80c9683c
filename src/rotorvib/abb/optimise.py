"""Genetic-algorithm search of the ball damping and mass for the shortest balance time
(paper B, section 9)."""

from __future__ import annotations

import numpy as np

from ..ga import GAResult, minimise
from . import engine
from .parameters import Balancer, SpeedProfile, fixed_parameters, fixed_state
from .simulate import check_batch, run_batch


def balance_time_objective(M, k, R, zeta, eps_bar, profile: SpeedProfile, phi0, *, r0, theta0,
                           t_end, sample_dt, r_threshold, censored_penalty):
    """``X[:, (beta, m)] -> balance time`` (s), one batch of runs per population; a censored
    run (not balanced by ``t_end``) scores ``censored_penalty * t_end``."""
    y0 = fixed_state(2, r0=r0, theta0=theta0, phi0=phi0)

    def objective(X):
        params = np.stack([fixed_parameters(Balancer.from_paper_b(
            M=M, k=k, R=R, m_bar=m / M, eps_bar=eps_bar, zeta=zeta, beta=beta), profile)
            for beta, m in X])
        metrics = run_batch(engine.FIXED, params, np.repeat(y0[None], len(X), axis=0), t_end,
                            sample_dt=sample_dt, r_threshold=r_threshold,
                            f_threshold=k * r_threshold, progress=False)
        check_batch(metrics)
        return np.where(metrics[:, 3] == 1, metrics[:, 2], censored_penalty * t_end)

    return objective


def tune_balancer(objective, beta_bounds, mass_bounds, *, pop_size, n_gen, seed) -> GAResult:
    lower = np.array([beta_bounds[0], mass_bounds[0]])
    upper = np.array([beta_bounds[1], mass_bounds[1]])
    return minimise(objective, lower, upper, pop_size=pop_size, n_gen=n_gen, seed=seed)
