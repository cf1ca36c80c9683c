"""The balancer's public API driven with hostile values (hypothesis): every call either raises
``ValueError`` naming an argument that is out of range, or, when every argument is valid,
returns the result of the same runs made one at a time.  Never an abort of the process (a
worker that dies fails the run), a hang (every valid run is short) or a result for invalid
input.

The oracle (``_invalid``) is written from the documented ranges, not from the checks'
code: each argument is tried from a pool of values tagged valid or invalid.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rotorvib.methods.integrate import IntegrationError
from rotorvib.models.balancer import layout
from rotorvib.models.balancer.criteria import BalanceCriterion, StopRule
from rotorvib.models.balancer.layout import metric
from rotorvib.models.balancer.parameters import (
    Balancer,
    Dimensionless,
    SpeedProfile,
    fixed_parameters,
    fixed_state,
    rotating_parameters,
)
from rotorvib.models.balancer.simulate import run, run_batch, simulate

B = Balancer.from_paper_b(M=1.0, k=1e4, R=0.1, m_bar=0.01, eps_bar=0.012, zeta=0.01, beta=2.0)
PROFILE = SpeedProfile(200.0, "runup", t_ramp=0.02)
P = fixed_parameters(B, PROFILE)
Y0 = fixed_state(2, r0=1e-3, theta0=0.0, phi0=[0.3, -0.4])
CRITERION = BalanceCriterion(r_threshold=1e-4, f_threshold=1.0, t_end=0.04, sample_dt=1e-3)
ROT = rotating_parameters(B.dimensionless(), SpeedProfile(2.0, "constant"))
SETTINGS = settings(max_examples=150, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])

# Hostile numbers for one column of a parameter row, and the columns' allowed ranges
# (layout.P_FIXED, layout.P_ROT as documented).
NUMBERS = [math.nan, math.inf, -math.inf, -1.0, 0.0, 1e-300, 0.5, 1.0, 1.5, 2.0, 3.0, 65.0,
           1e9, 1e300]
FIXED_OK = {"M": "pos", "m": "pos", "R": "pos", "eps": "nonneg", "k": "pos", "c": "nonneg",
            "D": "nonneg", "n": "balls", "Omega": "pos", "T_ramp": "pos", "profile": {0, 1},
            "kinematics": {0, 1}}


def _column_ok(rule, value) -> bool:
    if not math.isfinite(value):
        return False
    if rule == "pos":
        return value > 0
    if rule == "nonneg":
        return value >= 0
    if rule == "balls":
        return value == 2       # the state of Y0 has two balls
    return value in rule


@st.composite
def parameter_rows(draw):
    """A FIXED-form parameter array (two runs) with one column, its shape or its type spoiled,
    and whether it is valid."""
    params = np.stack([P, P])
    kind = draw(st.sampled_from(["column", "column", "column", "shape", "type", "none"]))
    if kind == "none":
        return params, True
    if kind == "column":
        j = draw(st.integers(0, len(layout.P_FIXED) - 1))
        value = draw(st.sampled_from(NUMBERS))
        params[draw(st.integers(0, 1)), j] = value
        return params, _column_ok(FIXED_OK[layout.P_FIXED[j]], value)
    if kind == "shape":
        return draw(st.sampled_from([params[:, :-1], np.hstack([params, params[:, :1]]),
                                     params[0], params[None], np.empty((0,))])), False
    return draw(st.sampled_from([params.astype(complex), params.astype(str), None, "params",
                                 [[1, "a"]], params.tolist() + [[None] * 12]])), False


VALUES = {   # argument -> [(value, valid)]
    "form": [(layout.FIXED, True), (2, False), (-1, False),
             (True, False), ("0", False), (None, False), (0.0, False)],
    "chunk": [(1, True), (3, True), (256, True), (0, False), (-5, False), (1.5, False),
              ("2", False), (None, False), (True, False)],
    "seed": [(0, True), (7, True), (-1, False), (2.5, False), ("a", False), (None, False)],
    "progress": [(False, True), (True, True), (0, False), ("yes", False), (None, False)],
    "stop": [(None, True), (StopRule(0.5, 0.01, 1e-3), True), ("stop", False), (1, False)],
    "method": [("dopri5", True), ("dop853", True), ("rk45", False), (None, False),
               (["dopri5"], False)],
    "rtol": [(1e-8, True), (1e-3, True), (0.0, False), (-1.0, False), (math.nan, False),
             (2.0, False), ("1e-8", False), (None, False)],
    "atol": [(1e-11, True), (0.0, True), (-1.0, False), (math.inf, False), ("0", False)],
}


@st.composite
def states(draw):
    y0s = np.stack([Y0, Y0])
    kind = draw(st.sampled_from(["ok", "ok", "width", "rows", "nan", "type"]))
    if kind == "ok":
        return y0s, True
    if kind == "width":
        return draw(st.sampled_from([y0s[:, :-1], y0s[:, :6], np.hstack([y0s, y0s]),
                                     y0s[:, :0]])), False
    if kind == "rows":
        return draw(st.sampled_from([y0s[:1], np.vstack([y0s, y0s]), y0s[0]])), False
    if kind == "nan":
        y0s[1, draw(st.integers(0, 7))] = draw(st.sampled_from([math.nan, math.inf]))
        return y0s, False
    return draw(st.sampled_from([y0s.astype(complex), "y0s", None])), False


def _one_at_a_time(params, y0s, method, rtol, atol) -> list[tuple[bool, float]]:
    """Whether each run of the batch succeeds, and its peak force, made one at a time
    (``run`` raises where a batch flags a failed run)."""
    answers = []
    for p, y in zip(params, y0s):
        try:
            answers.append((True, run(layout.FIXED, p, y, CRITERION, method=method, rtol=rtol,
                                      atol=atol).force_max))
        except IntegrationError:
            answers.append((False, math.nan))
    return answers


EXTREME = {1e9, 1e300, 1e-300}


@st.composite
def batch_calls(draw):
    """The arguments of a ``run_batch`` call with one or two of them drawn from their hostile
    pools (the rest valid), and the names of those that are invalid."""
    spoiled = set(draw(st.lists(st.sampled_from(["params", "y0s", *VALUES]), max_size=2)))
    args, invalid = {}, set()
    for name, pool in VALUES.items():
        value, ok = draw(st.sampled_from(pool if name in spoiled else
                                         [v for v in pool if v[1]]))
        args[name] = value
        invalid |= set() if ok else {name}
    args["params"], ok = draw(parameter_rows()) if "params" in spoiled else (np.stack([P, P]),
                                                                             True)
    invalid |= set() if ok else {"params"}
    args["y0s"], ok = draw(states()) if "y0s" in spoiled else (np.stack([Y0, Y0]), True)
    invalid |= set() if ok else {"y0s"}
    return args, invalid


@SETTINGS
@given(call=batch_calls())
def test_run_batch_refuses_naming_the_argument_or_answers_as_single_runs(call):
    kwargs, invalid = call
    form, params, y0s = kwargs.pop("form"), kwargs.pop("params"), kwargs.pop("y0s")
    if invalid:
        with pytest.raises(ValueError) as refused:
            run_batch(form, params, y0s, CRITERION, **kwargs)
        message = str(refused.value)
        assert any(name in message for name in invalid), (invalid, message)
        return
    try:
        metrics = run_batch(form, params, y0s, CRITERION, **kwargs)
    except ValueError as refused:   # a valid row too long to run: only an extreme value
        assert "radians of its fastest rate" in str(refused), str(refused)
        assert EXTREME & set(params.ravel().tolist())
        return
    if kwargs["stop"] is not None:      # an early stop changes only how long a run lasts
        return
    singles = _one_at_a_time(params, y0s, kwargs["method"], kwargs["rtol"], kwargs["atol"])
    ok = metric(metrics, "status") == layout.OK
    assert ok.tolist() == [done for done, _ in singles]
    assert metric(metrics, "force_max")[ok].tolist() == [f for done, f in singles if done]


@SETTINGS
@given(field=st.sampled_from(["omega", "t_ramp", "kind", "kinematics"]),
       value=st.sampled_from([math.nan, math.inf, -1.0, 0.0, 1e-9, 200.0, "constant",
                              "runup", "printed", "consistent", "other", None, [1.0]]))
def test_speed_profiles_validate_every_field(field, value):
    base = {"omega": 200.0, "kind": "runup", "t_ramp": 0.5, "kinematics": "consistent"}
    allowed = {"omega": lambda v: _positive(v), "t_ramp": lambda v: _positive(v),
               "kind": lambda v: v in ("constant", "runup") if isinstance(v, str) else False,
               "kinematics": lambda v: v in ("printed", "consistent")
               if isinstance(v, str) else False}
    if allowed[field](value):
        assert getattr(SpeedProfile(**{**base, field: value}), field) == value
    else:
        with pytest.raises(ValueError, match=f"SpeedProfile.{field}"):
            SpeedProfile(**{**base, field: value})


def _positive(v) -> bool:
    return isinstance(v, float) and math.isfinite(v) and v > 0


@SETTINGS
@given(field=st.sampled_from(["mu", "rho", "zeta", "beta", "n"]),
       value=st.sampled_from([math.nan, -1.0, 0.0, 0.5, 1.0, 2, 3, 2.5, "2", None]))
def test_dimensionless_groups_validate_every_field(field, value):
    base = {"mu": 0.01, "rho": 0.8, "zeta": 0.01, "beta": 1.0, "n": 2}
    ok = {"mu": lambda v: _real(v) and 0 < v < 1, "rho": lambda v: _real(v) and v > 0,
          "zeta": lambda v: _real(v) and v >= 0, "beta": lambda v: _real(v) and v >= 0,
          "n": lambda v: isinstance(v, int) and v >= 2}[field](value)
    if ok:
        assert getattr(Dimensionless(**{**base, field: value}), field) == value
    else:
        with pytest.raises(ValueError, match=f"Dimensionless.{field}"):
            Dimensionless(**{**base, field: value})


def _real(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


@SETTINGS
@given(t_end=st.sampled_from([0.04, 1e-3, 0.0, -1.0, math.inf, math.nan, 1e7, "1"]),
       sample_dt=st.sampled_from([1e-3, 1e-12, 0.0, 1.0, math.nan, None]))
def test_criteria_refuse_unbounded_or_invalid_sampling(t_end, sample_dt):
    valid = (_real(t_end) and _real(sample_dt) and t_end > 0 and sample_dt > 0
             and sample_dt <= t_end and t_end / sample_dt < 1e7)
    if valid:
        c = BalanceCriterion(1e-4, 1.0, t_end, sample_dt)
        assert c.times[-1] == pytest.approx(t_end, abs=sample_dt)
    else:
        with pytest.raises(ValueError, match="t_end|sample_dt"):
            BalanceCriterion(1e-4, 1.0, t_end, sample_dt)


def test_a_run_longer_than_its_budget_is_refused_before_it_starts():
    """A disk at 1e9 rad/s for 0.04 s is 4e7 radians: refused at once, not run for minutes."""
    fast = fixed_parameters(B, SpeedProfile(1e9, "constant"))
    with pytest.raises(ValueError, match=r"p\[0\] with t_end = 0.04: the run spans 4e\+07"):
        run(layout.FIXED, fast, Y0, CRITERION)


def test_the_rotating_form_checks_its_own_layout():
    """mu = m/M_t must lie below 1, and a rotating row is not a fixed one."""
    bad = ROT.copy()
    bad[0] = 1.0
    with pytest.raises(ValueError, match=r"p\[0, 0\] \(mu\) = 1.0: must be in \(0, 1\)"):
        run(layout.ROTATING, bad, Y0, CRITERION)
    with pytest.raises(ValueError, match=r"p: shape \(1, 8\), expected \(any, 12\)"):
        run(layout.FIXED, ROT, Y0, CRITERION)


def test_simulate_names_its_own_arguments():
    for kwargs, named in (({"r0": -1.0}, "r0"), ({"theta0": math.nan}, "theta0"),
                          ({"phi0": [0.1]}, "phi0"), ({"store": "yes"}, "store")):
        args = {"phi0": [0.3, -0.4], **kwargs}
        with pytest.raises(ValueError, match=named):
            simulate(B, PROFILE, args.pop("phi0"), 0.04, **args)
