"""The library's numeric domain, stated and enforced at each public entry point (hypothesis):
one argument at a time is drawn from a pool of hostile values, each tagged by the documented
domain, not by the checks' code. An invalid value is refused with ``ValueError`` naming the
argument; a valid one, a numpy scalar of any width included, gives the result of its value as a
Python number. Never a result for a boolean, a text, a NaN, an infinity or a subnormal number."""

from __future__ import annotations

import math
import numbers

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rotorvib.methods.multiple_scales import MultipleScales
from rotorvib.models.absorber.parameters import AbsorberSet, Rotor
from rotorvib.models.absorber.time_response import response_times
from rotorvib.models.absorber.tuning import den_hartog_single, mass_ratio_family
from rotorvib.models.balancer import stability
from rotorvib.models.balancer.parameters import Balancer, Dimensionless, SpeedProfile
from rotorvib.pipeline.shards import shard_rows

POOL = [True, np.bool_(False), "5", None, 1 + 0j, math.nan, math.inf, -math.inf, -1.0, -5e-324,
        0.0, 5e-324, 1e-300, 1e-13, 0.25, 0.6, 2.0, 3, 7.5, 2e6, 1e300, np.float16(5.0),
        np.float32(0.3), np.int8(3), np.int64(2), np.uint8(1)]


def is_real(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def real(holds):
    """A domain of real numbers: finite, 0 or between 1e-100 and 1e100 in magnitude
    (rotorvib.checks.MAGNITUDES), and ``holds``."""
    return lambda v: (is_real(v) and math.isfinite(v)
                      and (v == 0 or 1e-100 <= abs(v) <= 1e100) and holds(float(v)))


def whole(lo, hi=math.inf):
    return lambda v: (isinstance(v, numbers.Integral) and not isinstance(v, (bool, np.bool_))
                      and lo <= v <= hi)


POS, NONNEG = real(lambda v: v > 0), real(lambda v: v >= 0)
#: the balanced state's groups, as stability.groups documents them
GROUPS = {"mu": real(lambda v: 0 < v < 0.5), "rho": real(lambda v: v >= 0.5),
          "zeta": NONNEG, "beta": NONNEG, "omega": real(lambda v: True)}
ROTOR = Rotor(M=5.0, R=0.1, k_t=1e4, Gamma0=1.0, J_factor=0.5)
SETS = (AbsorberSet(0.1, 100.0, 1.0, 0.05), AbsorberSet(0.085, 85.0, 1.0, 0.05))
MS = MultipleScales.at(np.array([[0.0, 1.0], [-1.0, -0.1]]), np.zeros((2, 2, 2)))

#: entry point -> (call, valid arguments, each argument's documented domain)
ENTRIES = {
    "SpeedProfile": (lambda a: SpeedProfile(**a).omega, {"omega": 2.0, "t_ramp": 0.5},
                     {"omega": POS, "t_ramp": POS}),
    "Balancer": (lambda a: Balancer(**a).total_mass,
                 {"M": 1.0, "m": 0.01, "R": 0.1, "eps": 1e-3, "k": 1e4, "c": 1.0, "D": 0.1,
                  "n": 2},
                 {**dict.fromkeys(("M", "m", "R", "k"), POS),
                  **dict.fromkeys(("eps", "c", "D"), NONNEG), "n": whole(2, 64)}),
    "Dimensionless": (lambda a: Dimensionless(**a).mu,
                      {"mu": 0.01, "rho": 2.0, "zeta": 0.01, "beta": 0.1},
                      {"mu": real(lambda v: 0 < v < 1), "rho": POS, "zeta": NONNEG,
                       "beta": NONNEG}),
    "Rotor": (lambda a: Rotor(**a).omega_n,
              {"M": 5.0, "R": 0.1, "k_t": 1e4, "Gamma0": 1.0, "J_factor": 0.5},
              {**dict.fromkeys(("M", "k_t", "Gamma0", "J_factor"), POS),
               # J = J_factor M R^2 must be normal: R^2 underflows first
               "R": real(lambda v: v > 0)}),
    "AbsorberSet": (lambda a: AbsorberSet(**a).omega_a, {"m": 0.1, "k": 100.0, "c": 1.0,
                                                         "d": 0.05},
                    {"m": POS, "d": POS, "k": NONNEG, "c": NONNEG}),
    "stability.max_real_part": (
        lambda a: stability.max_real_part(**a),
        {"mu": 0.01, "rho": 2.0, "zeta": 0.01, "beta": 0.1, "omega": 2.0},
        GROUPS),
    "stability.polynomial_roots": (
        lambda a: stability.polynomial_roots(**a),
        {"mu": 0.01, "rho": 2.0, "zeta": 0.01, "beta": 0.1, "omega": 2.0},
        GROUPS),
    "response_times": (lambda a: response_times(**a),
                       {"omega": 2.0, "t_end": 3.0, "samples_per_period": 8},
                       {"omega": POS, "t_end": POS, "samples_per_period": whole(2)}),
    "den_hartog_single": (lambda a: den_hartog_single(ROTOR, **a), {"m": 0.1, "d": 0.05},
                          {"m": real(lambda v: v > 0 and 1e-100 <= 2 * v * 0.05**2 / ROTOR.J),
                           "d": real(lambda v: v > 0 and 2 * 0.1 * v * v / ROTOR.J <= 1e100)}),
    "mass_ratio_family": (lambda a: mass_ratio_family(SETS, **a), {"mu": 0.85}, {"mu": POS}),
    "shard_rows": (lambda a: shard_rows(**a), {"n_runs": 10, "shard": 1, "shards": 3},
                   {"n_runs": whole(0), "shard": whole(0, 2), "shards": whole(1)}),
    "MultipleScales.resonances": (lambda a: MS.resonances(**a), {"tolerance": 0.05},
                                  {"tolerance": NONNEG}),
}


def _finite(result) -> bool:
    """Every number of a result is finite (or the result holds no numbers)."""
    try:
        values = np.asarray(result if not isinstance(result, tuple) else list(result),
                            dtype=float)
    except (TypeError, ValueError):
        return True
    return bool(np.isfinite(values).all())


@pytest.mark.parametrize("entry", sorted(ENTRIES))
def test_each_entry_point_refuses_what_is_outside_its_domain(entry):
    call, valid, domain = ENTRIES[entry]

    @settings(max_examples=len(domain) * len(POOL), deadline=None, derandomize=True)
    @given(name=st.sampled_from(sorted(domain)), value=st.sampled_from(POOL))
    def one_argument(name, value):
        arguments = {**valid, name: value}
        if entry == "shard_rows" and name == "shards" and domain["shards"](value):
            arguments["shard"] = 0          # the shard must lie below the count
        if domain[name](value):
            result = call(arguments)
            plain = call({**arguments, name: value.item() if hasattr(value, "item") else value})
            assert _finite(result) and np.array_equal(np.asarray(result, dtype=object),
                                                      np.asarray(plain, dtype=object))
        else:
            with pytest.raises(ValueError, match=rf"\b{name}\b"):
                call(arguments)

    one_argument()


def test_a_rotor_at_rest_is_not_a_run_up():
    """The audit's case: a subnormal speed passed "> 0" and a rotor at rest was reported
    balanced at 0.996 s."""
    with pytest.raises(ValueError, match="SpeedProfile.omega = 5e-324: .* subnormal"):
        SpeedProfile(5e-324, "runup")


def test_numpy_scalars_become_python_numbers():
    rotor = Rotor(M=np.float16(5.0), R=np.float32(0.1), k_t=1e4, Gamma0=1.0, J_factor=0.5)
    assert type(rotor.M) is float and math.isfinite(rotor.omega_n)
    assert type(Balancer(M=1.0, m=0.01, R=0.1, eps=1e-3, k=1e4, c=1.0, D=0.1,
                         n=np.int8(2)).n) is int


def test_a_response_too_long_to_hold_is_refused_before_it_is_allocated():
    """The hang: ten million periods at a thousand samples each."""
    with pytest.raises(ValueError, match="t_end = .*samples .*at most"):
        response_times(omega=2 * math.pi * 1e4, t_end=1e3, samples_per_period=1000)
