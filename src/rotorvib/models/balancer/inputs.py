"""Checks of what the compiled engine is handed: every array, flag and size of a run or batch,
before it reaches compiled code, which trusts its arguments (a parameter row of the wrong
length, or a ball count that does not match the state, reads and writes past the end of an
array there).  Each check raises ``ValueError`` naming the argument, what it got and what is
allowed.

Parameter rows (``layout.P_FIXED``, ``layout.P_ROT``) are checked column by column against
:data:`FIXED_COLUMNS` and :data:`ROTATING_COLUMNS`; a state row of ``n`` balls has
``2 (n + 2)`` entries.
"""

from __future__ import annotations

import numbers

import numpy as np

from rotorvib.checks import finite_array
from rotorvib.models.balancer import layout, limits

#: Balls of a balancer at most (a state of 2 (n + 2) entries); paper A and B have two.
MAX_BALLS = 64

_POSITIVE, _NONNEGATIVE = (0.0, False), (0.0, True)
_PROFILES = (layout.CONSTANT, layout.RUNUP)

#: Allowed values of each column of a FIXED-form parameter row: ``(minimum, inclusive)`` for a
#: number, a tuple of codes for a flag, ``"balls"`` for the ball count.
FIXED_COLUMNS = {"M": _POSITIVE, "m": _POSITIVE, "R": _POSITIVE, "eps": _NONNEGATIVE,
                 "k": _POSITIVE, "c": _NONNEGATIVE, "D": _NONNEGATIVE, "n": "balls",
                 "Omega": _POSITIVE, "T_ramp": _POSITIVE, "profile": _PROFILES,
                 "kinematics": (layout.PRINTED, layout.CONSISTENT)}
#: The same for a ROTATING-form row; ``mu = m / M_t`` lies in (0, 1).
ROTATING_COLUMNS = {"mu": _POSITIVE, "rho": _POSITIVE, "zeta": _NONNEGATIVE,
                    "beta": _NONNEGATIVE, "n": "balls", "Omega": _POSITIVE,
                    "T_ramp": _POSITIVE, "profile": _PROFILES}
_COLUMNS = {layout.FIXED: (layout.P_FIXED, FIXED_COLUMNS),
            layout.ROTATING: (layout.P_ROT, ROTATING_COLUMNS)}


def form(value) -> int:
    """``value`` as a form code, ``layout.FIXED`` or ``layout.ROTATING``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value not in _COLUMNS:
        raise ValueError(f"form = {value!r}: must be layout.FIXED ({layout.FIXED}) or "
                         f"layout.ROTATING ({layout.ROTATING})")
    return int(value)


def parameter_rows(form_code: int, params, name: str = "params") -> np.ndarray:
    """``params`` as a C-contiguous float array of rows of the form's layout, every column in
    its range."""
    layout, allowed = _COLUMNS[form_code]
    rows = finite_array(name, params, shape=(None, len(layout)))
    for j, column in enumerate(layout):
        values, rule = rows[:, j], allowed[column]
        if rule == "balls":
            bad = (values != np.round(values)) | (values < 1) | (values > MAX_BALLS)
            want = f"an integer in [1, {MAX_BALLS}]"
        elif isinstance(rule[0], int):
            bad = ~np.isin(values, rule)
            want = f"one of {list(rule)}"
        else:
            minimum, inclusive = rule
            bad = values < minimum if inclusive else values <= minimum
            want = f"{'>=' if inclusive else '>'} {minimum:g}"
            if column == "mu":
                bad |= values >= 1
                want = "in (0, 1)"
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"{name}[{i}, {j}] ({column}) = {values[i].item()!r}: must be "
                             f"{want} ({int(bad.sum())} of {len(values)} rows out of range)")
    return np.ascontiguousarray(rows)


def state_rows(form_code: int, params: np.ndarray, y0s, name: str = "y0s",
               params_name: str = "params") -> np.ndarray:
    """``y0s`` as a C-contiguous float array with one state row per parameter row, each of the
    length its row's ball count gives."""
    states = finite_array(name, y0s, shape=(len(params), None))
    balls = params[:, layout.P_FIXED.index("n") if form_code == layout.FIXED
                   else layout.P_ROT.index("n")]
    width = 2 * (balls.astype(int) + 2)
    wrong = np.flatnonzero(width != states.shape[1])
    if wrong.size:
        i = int(wrong[0])
        raise ValueError(f"{name}: rows of {states.shape[1]} entries, but {params_name}[{i}] "
                         f"has n = {int(balls[i])} balls, a state of {width[i]} entries")
    return np.ascontiguousarray(states)


def samples(t_end: float, sample_dt: float) -> int:
    """The number of samples of a run (:func:`limits.samples`); at most
    :data:`limits.MAX_SAMPLES`."""
    if problem := limits.samples_problem(t_end, sample_dt):
        raise ValueError(f"t_end / sample_dt = {t_end!r} / {sample_dt!r}: {problem}")
    return limits.samples(t_end, sample_dt)


def fastest_rate(form_code: int, params: np.ndarray) -> np.ndarray:
    """The fastest rate (1/time unit of the form) of each parameter row: the disk speed
    ``Omega``, the natural frequency ``sqrt(k / M_t)``, the support's damping rate ``c / M_t``
    and the balls' drag rate ``D / (m R^2)`` (FIXED); ``Omega``, 1, ``2 zeta`` and ``beta``
    (ROTATING, time in ``1 / w_n``)."""
    if form_code == layout.FIXED:
        M, m, R, _, k, c, D, n, omega = params[:, :9].T
        mt = M + n * m
        return np.max([omega, np.sqrt(k / mt), c / mt, D / (m * R**2)], axis=0)
    zeta, beta, omega = params[:, 2], params[:, 3], params[:, 5]
    return np.max([omega, np.ones_like(omega), 2 * zeta, beta], axis=0)


def work(form_code: int, params: np.ndarray, t_end: float, name: str = "params") -> None:
    """``ValueError`` naming the first row whose run would span more than
    :data:`limits.MAX_RADIANS` of its fastest rate by ``t_end``."""
    with np.errstate(over="ignore"):
        rates = fastest_rate(form_code, params)
    for i, rate in enumerate(rates):
        if problem := limits.radians_problem(float(rate), t_end):
            raise ValueError(f"{name}[{i}] with t_end = {t_end!r}: {problem} (speed, natural "
                             "frequency or damping rate)")
