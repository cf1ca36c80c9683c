"""Paper B's machine, initial state, run-up and balance criterion, and the run parameters a study
can vary.

One :class:`Setup` is built from the configuration and handed to every study and to the genetic
algorithm's objective, so that a run is set up in one place: the balancer of eqs (25)-(26) with
the ball mass ``mass``, damping ratio ``beta``, eccentricity ratio ``eps_bar`` (and optionally
another operating ``speed``, race radius ``R`` or support damping ``zeta``), balls at
``phi0_deg``, the disk centre at ``(r0, theta0)`` (eq. 36) and the run-up of eq. (37).
"""

from __future__ import annotations

import inspect
import operator
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Callable

import numpy as np

from rotorvib.io.coords import axis_coord
from rotorvib.models.balancer import layout
from rotorvib.models.balancer.criteria import ATOL, METHOD, RTOL, BalanceCriterion, StopRule
from rotorvib.models.balancer.parameters import (Balancer, SpeedProfile, fixed_parameter_rows,
                                                 fixed_parameters, fixed_state, paper_b_machine)
from rotorvib.models.balancer.simulate import check_batch, run_batch

#: Parameters of one run that a study may vary or fix: long name and units of each.
RUN_PARAMETERS = {
    "beta": ("ball damping ratio beta", "1"),
    "mass": ("ball mass m", "kg"),
    "eps_bar": ("eccentricity ratio eps/R", "1"),
    "speed": ("operating speed", "rad s-1"),
    "R": ("race radius R", "m"),
    "zeta": ("support damping ratio", "1"),
}
#: How a fixed run parameter is written in a summary: symbol and unit suffix.
SYMBOLS = {"mass": ("m", " kg"), "speed": ("omega", " rad/s"), "R": ("R", " m")}

KINEMATICS_LONG_NAME = ("disk-angle kinematics: printed (w t, as in eqs 7-9) or consistent "
                        "(int w dt)")
IC_LONG_NAME = "initial ball angles, eq. (39)"


def parameter_coord(name: str, values) -> dict:
    """Coordinate of run parameter ``name`` (:data:`RUN_PARAMETERS`) over ``values``."""
    return axis_coord(name, values, *RUN_PARAMETERS[name])


def describe(fixed: dict) -> str:
    """``{"mass": 0.01, "beta": 1.0}`` -> ``"m = 0.01 kg, beta = 1.0"``."""
    return ", ".join(f"{SYMBOLS.get(k, (k, ''))[0]} = {v}{SYMBOLS.get(k, (k, ''))[1]}"
                     for k, v in fixed.items())


class LazyInputs(Sequence):
    """The inputs of ``n`` runs, run ``i``'s ``(params, y0)`` built by ``build(i)`` when it is
    asked for, each time.  A study hands its runner these instead of a list: a shard of the
    study builds only its own runs' inputs and the gathering none
    (:mod:`rotorvib.pipeline.shards`), so that the inputs cost each job its share of the study,
    not the whole study."""

    def __init__(self, n: int, build: Callable[[int], tuple]):
        self.n, self.build = operator.index(n), build

    def __len__(self) -> int:
        return self.n

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self.build(j) for j in range(*i.indices(self.n))]
        i = operator.index(i)
        if not -self.n <= i < self.n:
            raise IndexError(f"run {i} of {self.n}")
        return self.build(i % self.n)


def stacked(inputs) -> tuple[np.ndarray, np.ndarray]:
    """The parameter rows and the initial states of ``inputs`` (``(params, y0)`` pairs, at
    least one), as two arrays filled one run at a time: a :class:`LazyInputs` is never held
    whole, only its arrays."""
    n, params, y0s = len(inputs), None, None
    for i, (p, y) in enumerate(inputs):
        if params is None:
            params, y0s = np.empty((n, *np.shape(p))), np.empty((n, *np.shape(y)))
        params[i], y0s[i] = p, y
    if params is None:
        raise ValueError("no runs: a batch needs at least one")
    return params, y0s


@dataclass(frozen=True)
class Setup:
    """Paper B's machine, initial state, speed profile and balance criterion (config)."""

    M: float
    k: float
    R: float
    n: int
    zeta: float
    r0: float
    theta0: float
    omega: float
    t_ramp: float
    criterion: BalanceCriterion
    #: the engine's method and tolerances (``paper_b.balance.integrator``)
    method: str = METHOD
    rtol: float = RTOL
    atol: float = ATOL
    #: when a batch run may end before ``t_end`` (``paper_b.balance.stop``); None: never
    stop: StopRule | None = None

    @classmethod
    def from_config(cls, machine, initial_state, speed, balance, marginal_growth) -> "Setup":
        """From the config sections and key of the same names (``paper_b.*``)."""
        return cls(**machine, **initial_state, **speed, **balance["integrator"],
                   criterion=BalanceCriterion.from_config(balance, machine["k"]),
                   stop=StopRule.from_config(balance["stop"], marginal_growth))

    @classmethod
    def from_paper_b(cls, paper_b: dict) -> "Setup":
        """From the whole ``paper_b`` config section (the keys :meth:`from_config` takes)."""
        return cls.from_config(**{key: paper_b[key]
                                  for key in inspect.signature(cls.from_config).parameters})

    @property
    def tolerances(self) -> dict:
        """The keywords of ``simulate.run`` and ``run_batch`` that choose the integrator."""
        return {"method": self.method, "rtol": self.rtol, "atol": self.atol}

    def balancer(self, *, mass, eps_bar, beta, R=None, zeta=None) -> Balancer:
        return Balancer.from_paper_b(M=self.M, k=self.k, R=self.R if R is None else R,
                                     m_bar=mass / self.M, eps_bar=eps_bar,
                                     zeta=self.zeta if zeta is None else zeta, beta=beta, n=self.n)

    def profile(self, kinematics, speed=None) -> SpeedProfile:
        """The run-up of eq. (37) to ``speed`` (default: the configured ``omega``)."""
        return SpeedProfile(self.omega if speed is None else speed, "runup", self.t_ramp,
                            kinematics)

    def initial_state(self, phi0_deg) -> np.ndarray:
        """The fixed-frame state of eq. (36): the disk centre at ``(r0, theta0)``, the balls at
        ``phi0_deg`` (degrees), at rest."""
        return fixed_state(self.n, r0=self.r0, theta0=self.theta0, phi0=np.radians(phi0_deg))

    def run_inputs(self, *, mass, eps_bar, beta, phi0_deg, kinematics, speed=None, R=None,
                   zeta=None) -> tuple[np.ndarray, np.ndarray]:
        """Engine parameters and initial state of one run (fixed frame)."""
        b = self.balancer(mass=mass, eps_bar=eps_bar, beta=beta, R=R, zeta=zeta)
        return fixed_parameters(b, self.profile(kinematics, speed)), self.initial_state(phi0_deg)

    def batch_inputs(self, *, masses, betas, eps_bar, phi0_deg, kinematics, speed=None, R=None,
                     zeta=None) -> list[tuple[np.ndarray, np.ndarray]]:
        """The inputs of the runs ``(masses[i], betas[i])`` (broadcast together), built at once:
        each bit for bit that of :meth:`run_inputs` (tested), without its checks of one
        machine (the engine checks the batch's rows)."""
        R, zeta = (self.R if R is None else R), (self.zeta if zeta is None else zeta)
        masses, betas = np.broadcast_arrays(np.asarray(masses, float), np.asarray(betas, float))
        m, eps, c, D = paper_b_machine(M=self.M, k=self.k, R=R, m_bar=masses / self.M,
                                       eps_bar=eps_bar, zeta=zeta, beta=betas)
        rows = fixed_parameter_rows(M=self.M, m=m, R=R, eps=eps, k=self.k, c=c, D=D, n=self.n,
                                    profile=self.profile(kinematics, speed))
        y0 = self.initial_state(phi0_deg)
        return [(row, y0) for row in rows]

    def runs(self, inputs, *, progress: bool = True, balance_bounds=None) -> np.ndarray:
        """Metrics of many ``(params, y0)`` runs (a list or :class:`LazyInputs`), in parallel,
        each stopped once its balance time is known to exceed its ``balance_bounds`` entry (if
        given: :func:`~rotorvib.models.balancer.simulate.run_batch`); failures raise."""
        params, y0s = stacked(inputs)
        metrics = run_batch(layout.FIXED, params, y0s, self.criterion, progress=progress,
                            stop=self.stop, balance_bounds=balance_bounds, **self.tolerances)
        check_batch(metrics)
        return metrics
