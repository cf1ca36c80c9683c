"""What a balancer run is asked, importable without numba: the balance criterion it is observed
under, the rule by which a batch run may stop early (:mod:`settling`), and the integrator's
default method and tolerances."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorvib.checks import number
from rotorvib.models.balancer import inputs

#: Default tolerances, chosen from the convergence study
#: ``python -m benchmarks.balancer --convergence`` (paper B run-up: balance time within 1e-6 s
#: and peak force within 2e-7 of rtol = 1e-12).
RTOL, ATOL = 1e-8, 1e-11
#: Default method: the integrator the tolerances above were chosen for.
METHOD = "dopri5"


@dataclass(frozen=True)
class BalanceCriterion:
    """When a run counts as balanced, and how long and how finely it is observed.

    A run is balanced at the time after which the whirl radius stays below ``r_threshold``
    (paper B, section 7) and its bearing force has decayed at the time after which
    ``F = k r + c r'`` stays below ``f_threshold``; both are read on samples every ``sample_dt``
    of a run that ends at ``t_end``.
    """

    r_threshold: float
    f_threshold: float
    t_end: float
    sample_dt: float

    def __post_init__(self):
        for name in ("r_threshold", "f_threshold", "t_end", "sample_dt"):
            object.__setattr__(self, name, number(name, getattr(self, name)))
        if self.sample_dt > self.t_end:
            raise ValueError(f"sample_dt = {self.sample_dt!r}: must not exceed t_end = "
                             f"{self.t_end!r}")
        inputs.samples(self.t_end, self.sample_dt)

    @classmethod
    def from_config(cls, balance: dict, k: float) -> "BalanceCriterion":
        """From the ``balance`` config section; the force threshold is the force of a support of
        stiffness ``k`` at the radius threshold, ``f_threshold = k r_threshold``."""
        return cls(r_threshold=balance["r_threshold"], f_threshold=k * balance["r_threshold"],
                   t_end=balance["t_end"], sample_dt=balance["sample_dt"])

    @property
    def n_samples(self) -> int:
        """Number of samples ``t = 0, sample_dt, ...`` up to ``t_end``."""
        return inputs.samples(self.t_end, self.sample_dt)

    @property
    def times(self) -> np.ndarray:
        return np.arange(self.n_samples) * self.sample_dt


@dataclass(frozen=True)
class StopRule:
    """When a batch run may stop before ``t_end``: bounds within ``margin`` of the thresholds,
    checked every ``check_dt`` (s); a growth rate within ``neutral`` (in ``w_n``) of zero is a
    neutral mode."""

    margin: float
    check_dt: float
    neutral: float

    def __post_init__(self):
        if not 0.0 < self.margin < 1.0:
            raise ValueError(f"margin = {self.margin!r}: must lie in (0, 1)")
        for name in ("check_dt", "neutral"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"{name} = {getattr(self, name)!r}: must be > 0")

    @classmethod
    def from_config(cls, stop: dict, neutral: float) -> "StopRule":
        """From ``paper_b.balance.stop`` and ``paper_b.marginal_growth``."""
        return cls(margin=stop["margin"], check_dt=stop["check_dt"], neutral=neutral)

    def check_every(self, sample_dt: float) -> int:
        """Samples from one check of a run to the next."""
        return max(1, round(self.check_dt / sample_dt))
