"""Parameters of the automatic ball balancer (papers A and B) and the maps between them.

:class:`Balancer` holds paper B's dimensional machine (disk mass ``M``, ball mass ``m``, race
radius ``R``, eccentricity ``eps``, support ``k`` and ``c``, ball drag ``D``, ``n`` balls).
:class:`Dimensionless` holds paper A's total-mass-scaled groups (digest A):
``mu = m/M_t``, ``rho = m R/(M eps)``, ``zeta = c/(2 sqrt(k M_t))``, ``beta = D/(m R^2 w_n)``,
``w_n = sqrt(k/M_t)``, ``M_t = M + n m``.  Paper B's own groups (eq. 25) use the disk mass:
``zeta_B = c/(2 sqrt(M k))``, ``m_bar = m/M``, ``eps_bar = eps/R``, ``beta_B = D/(m R^2 w_nB)``,
``w_nB = sqrt(k/M)`` (eq. 26).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorvib.checks import integer, require

from rotorvib.models.balancer import layout

#: Balls in one race at most: a bound on the size of the state (each ball adds two variables),
#: not a physical one; the papers have two.
MAX_BALLS = 64
#: Balls of the linearised balanced state (``stability``) and of the energies it is derived
#: from (``equations``): the papers' two. Defined here, where both import it.
N_BALLS = 2


@dataclass(frozen=True)
class Dimensionless:
    """Paper A's groups on the total-mass scale (time unit ``1/w_n``, length unit ``R``)."""

    mu: float
    rho: float
    zeta: float
    beta: float
    n: int = 2

    def __post_init__(self):
        require(self, positive=("mu", "rho"), nonnegative=("zeta", "beta"))
        if not self.mu < 1:
            raise ValueError(f"Dimensionless.mu = {self.mu!r}: must lie in (0, 1) (m / M_t)")
        object.__setattr__(self, "n", integer("Dimensionless.n", self.n, 2, MAX_BALLS))

    def balanced_angle(self) -> float:
        """Ball angle of the balanced state for two balls, ``arccos(-1/(2 rho))`` (rad)."""
        return balanced_angle(1.0 / self.rho, 1.0, self.n)


@dataclass(frozen=True)
class Balancer:
    """Paper B's dimensional balancer (SI units)."""

    M: float
    m: float
    R: float
    eps: float
    k: float
    c: float
    D: float
    n: int = 2

    def __post_init__(self):
        require(self, positive=("M", "m", "R", "k"), nonnegative=("eps", "c", "D"))
        object.__setattr__(self, "n", integer("Balancer.n", self.n, 2, MAX_BALLS))

    @classmethod
    def from_paper_b(cls, *, M, k, R, m_bar, eps_bar, zeta, beta, n=2) -> "Balancer":
        """From paper B's dimensionless groups (eqs 25-26, :func:`paper_b_machine`)."""
        m, eps, c, D = paper_b_machine(M=M, k=k, R=R, m_bar=m_bar, eps_bar=eps_bar, zeta=zeta,
                                       beta=beta)
        return cls(M=M, m=m, R=R, eps=eps, k=k, c=c, D=D, n=n)

    @property
    def total_mass(self) -> float:
        return self.M + self.n * self.m

    @property
    def omega_n(self) -> float:
        """Paper B's natural frequency sqrt(k/M) (eq. 26), disk mass only."""
        return float(np.sqrt(self.k / self.M))

    @property
    def omega_n_total(self) -> float:
        """Paper A's natural frequency sqrt(k/M_t) on the total mass."""
        return float(np.sqrt(self.k / self.total_mass))

    def dimensionless(self) -> Dimensionless:
        """Paper A's groups of this machine (digest A; :func:`total_mass_groups`)."""
        mu, rho, zeta, beta = total_mass_groups(self.M, self.m, self.R, self.eps, self.k,
                                                self.c, self.D, self.n)
        return Dimensionless(mu=mu, rho=rho, zeta=zeta, beta=beta, n=self.n)

    def balanced_angle(self) -> float:
        """Eq. (33): ``phi_1* = -phi_2* = arccos(-eps M / (2 m R))`` for two balls (rad)."""
        return balanced_angle(self.eps * self.M, self.m * self.R, self.n)

    def can_balance(self) -> bool:
        """Existence bound (34): ``m/M >= eps/(2R)`` (two balls)."""
        return self.m / self.M >= 0.5 * self.eps / self.R


def paper_b_machine(*, M, k, R, m_bar, eps_bar, zeta, beta):
    """The ball mass, eccentricity, support damping and ball drag ``(m, eps, c, D)`` of paper
    B's groups (eqs 25-26), vectorised over arrays of them (unchecked: :class:`Balancer` checks
    one machine)::

        m = m_bar M,   eps = eps_bar R,   c = 2 zeta sqrt(M k),   D = beta m R^2 sqrt(k / M)
    """
    m = m_bar * M
    return m, eps_bar * R, 2 * zeta * np.sqrt(M * k), beta * m * R**2 * np.sqrt(k / M)


def total_mass_groups(M, m, R, eps, k, c, D, n):
    """Paper A's groups ``(mu, rho, zeta, beta)`` of dimensional machines, vectorised over
    arrays of their parameters (unchecked: :class:`Balancer` checks one machine)::

        M_t = M + n m,   w_n = sqrt(k / M_t),
        mu = m / M_t,   rho = m R / (M eps),   zeta = c / (2 sqrt(k M_t)),   beta = D / (m R^2 w_n)
    """
    mt = M + n * m
    wn = np.sqrt(k / mt)
    return m / mt, m * R / (M * eps), c / (2 * np.sqrt(k * mt)), D / (m * R**2 * wn)


def balanced_angle(unbalance: float, ball_moment: float, n: int = 2) -> float:
    """Symmetric balanced angle of two balls, ``arccos(-unbalance / (2 ball_moment))``.

    Raises ``ValueError`` when the balls cannot compensate the unbalance (bound 34)."""
    if n != 2:
        raise ValueError("the closed-form balanced angle (eq. 33) is for two balls")
    arg = -unbalance / (2 * ball_moment)
    if arg < -1:
        raise ValueError(f"no balanced state: the balls' moment {ball_moment:.4g} is below half "
                         f"the unbalance {unbalance:.4g} (existence bound, eq. 34)")
    return float(np.arccos(arg))


@dataclass(frozen=True)
class SpeedProfile:
    """Prescribed disk speed: ``kind`` "constant" or "runup" (eq. 37 scaled to ``omega`` with
    ramp time ``t_ramp``), disk-angle ``kinematics`` "printed" (paper B's ``w t``) or
    "consistent" (``int w dt``).  Units follow the form: rad/s and s, or dimensionless.
    ``omega`` and ``t_ramp`` are finite and > 0: a disk that does not turn has no balancer."""

    omega: float
    kind: str = "constant"
    t_ramp: float = 0.5
    kinematics: str = "consistent"

    def __post_init__(self):
        require(self, positive=("omega", "t_ramp"))
        for name, allowed in (("kind", ("constant", "runup")),
                              ("kinematics", ("printed", "consistent"))):
            value = getattr(self, name)
            if not isinstance(value, str) or value not in allowed:
                raise ValueError(f"SpeedProfile.{name} = {value!r}: must be one of "
                                 f"{list(allowed)}")

    @property
    def profile_code(self) -> int:
        return layout.RUNUP if self.kind == "runup" else layout.CONSTANT


def fixed_parameters(b: Balancer, profile: SpeedProfile) -> np.ndarray:
    """Parameter array of the FIXED form (layout ``layout.P_FIXED``)."""
    return fixed_parameter_rows(M=b.M, m=b.m, R=b.R, eps=b.eps, k=b.k, c=b.c, D=b.D, n=b.n,
                                profile=profile)[0]


def fixed_parameter_rows(*, M, m, R, eps, k, c, D, n, profile: SpeedProfile) -> np.ndarray:
    """Parameter rows of the FIXED form (layout ``layout.P_FIXED``), one per entry of the
    machines' parameters broadcast together (unchecked: the engine checks a batch's rows)."""
    kin = layout.PRINTED if profile.kinematics == "printed" else layout.CONSISTENT
    columns = np.broadcast_arrays(M, m, R, eps, k, c, D, n, profile.omega, profile.t_ramp,
                                  profile.profile_code, kin)
    return np.column_stack(columns).astype(float)


def rotating_parameters(d: Dimensionless, profile: SpeedProfile) -> np.ndarray:
    """Parameter array of the ROTATING form (layout ``layout.P_ROT``)."""
    if profile.kinematics != "consistent":
        raise ValueError("the rotating-frame form exists for the consistent kinematics only")
    return rotating_parameter_rows(mu=d.mu, rho=d.rho, zeta=d.zeta, beta=d.beta, n=d.n,
                                   omega=profile.omega, t_ramp=profile.t_ramp,
                                   profile_code=profile.profile_code)[0]


def rotating_parameter_rows(*, mu, rho, zeta, beta, n, omega, t_ramp, profile_code) -> np.ndarray:
    """Parameter rows of the ROTATING form (layout ``layout.P_ROT``), one per entry of the
    groups and speeds broadcast together (unchecked: the engine checks a batch's rows)."""
    columns = np.broadcast_arrays(mu, rho, zeta, beta, n, omega, t_ramp, profile_code)
    return np.column_stack(columns).astype(float)


def fixed_state(n: int, *, r0: float, theta0: float, phi0, rates=None) -> np.ndarray:
    """FIXED-form state from paper B's polar initial conditions (eq. 36): C at ``(r0, theta0)``
    in the fixed frame, ball angles ``phi0`` (rad), all rates zero unless ``rates`` is given."""
    phi0 = np.asarray(phi0, float)
    if phi0.shape != (n,):
        raise ValueError(f"need {n} initial ball angles, got {phi0.shape}")
    y = np.zeros(2 * (n + 2))
    y[0], y[1] = r0 * np.cos(theta0), r0 * np.sin(theta0)
    y[2:n + 2] = phi0
    if rates is not None:
        y[n + 2:] = rates
    return y


def paper_b_groups(m_bar, eps_bar, zeta, beta, omega_bar, n: int = 2):
    """Paper A's groups ``(mu, rho, zeta_t, beta_t, Omega_t)`` from paper B's (eq. 25),
    vectorised: with ``s = sqrt(1 + n m_bar)``, ``mu = m_bar/(1 + n m_bar)``,
    ``rho = m_bar/eps_bar``, ``zeta_t = zeta/s``, ``beta_t = beta s``, ``Omega_t = omega_bar s``
    (digest A).  Eigenvalues on the total-mass scale are ``s`` times those on paper B's."""
    m_bar, eps_bar, zeta, beta, omega_bar = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (m_bar, eps_bar, zeta, beta, omega_bar)))
    s = np.sqrt(1 + n * m_bar)
    return m_bar / (1 + n * m_bar), m_bar / eps_bar, zeta / s, beta * s, omega_bar * s
