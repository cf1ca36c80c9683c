"""Paper C's library entry points (the absorber model and the paper's own functions) driven
with hostile arguments: NaN, infinities, negative numbers, magnitudes beyond
:data:`rotorvib.checks.MAGNITUDES` and grids or time spans too large to compute. Each raises
``ValueError`` naming the argument before any work (a hostile-input audit found eleven of them
answering silently, with NaN or a number, and a time span of 1e300 s integrating forever); 0,
where a frequency, a time or a speed may be 0, still answers."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from rotorvib.models.absorber import frequency_response as fr
from rotorvib.models.absorber import time_response as tr
from rotorvib.models.absorber.linear import matrices
from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.papers.c import broadband, spin

ROTOR = Rotor(M=2.0, R=0.1, k_t=1e4, Gamma0=1.0)
SETS = dual_absorber(0.05, 0.05, 200.0, 300.0, 1.0, 1.0, 0.05, 0.05)
X = np.array([0.05, 0.05, 200.0, 300.0, 1.0, 1.0, 0.05, 0.05])
W = np.linspace(0.5, 1.5, 5)
T = np.linspace(0.0, 0.01, 3)
HOSTILE = [math.nan, math.inf, -math.inf, -1.0, 1e300, 1e-300]

#: (the argument the message names, the call with that argument's value)
CALLS = [
    ("spin", lambda v: matrices(ROTOR, SETS, spin=v)),
    ("spin", lambda v: fr.amplitude(ROTOR, SETS, W, spin=v)),
    ("omega", lambda v: fr.dynamic_stiffness(ROTOR, SETS, v)),
    ("omega", lambda v: fr.steady_state(ROTOR, SETS, np.array([100.0, v]))),
    ("omega", lambda v: fr.theta_eq20(ROTOR, X, v)),
    ("w", lambda v: fr.amplitude(ROTOR, SETS, np.array([1.0, v]))),
    ("w", lambda v: fr.bare_rotor_amplitude(np.array([0.5, v]))),
    ("t", lambda v: tr.simulate(ROTOR, SETS, 100.0, np.array([v, 0.01]))),
    ("t", lambda v: tr.linear_response(ROTOR, SETS, 100.0, np.array([v, 0.01]))),
    ("t", lambda v: tr.undamped_resonance_envelope(ROTOR, np.array([0.0, v]))),
    ("omega_a", lambda v: spin.tuned_frequency(v, 1.0)),
    ("spin", lambda v: spin.tuned_frequency(10.0, v)),
    ("spin", lambda v: spin.retuned(SETS, v)),
    ("close", lambda v: spin.detuning_limit(v)),
    ("x", lambda v: broadband.added_mass(np.array([v, *X[1:]]))),
    ("omega", lambda v: fr.theta_eq20(ROTOR, X, np.array([v]))),
]


@pytest.mark.parametrize("value", HOSTILE, ids=repr)
@pytest.mark.parametrize("name, call", CALLS, ids=[f"{n}-{i}" for i, (n, _) in enumerate(CALLS)])
def test_a_hostile_argument_is_refused_naming_it(name, call, value):
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        call(value)


#: The calls whose argument may be 0: a frequency, a time, a speed, a spring of 0 (a static
#: load, the start, a rotor at rest). Not a relative tolerance of 0, nor a set's frequency of 0
#: (a lost spring, NaN by definition).
AT_ZERO = [(i, call) for i, (name, call) in enumerate(CALLS) if name not in ("close", "omega_a")]


def _finite(result) -> bool:
    if isinstance(result, tuple):
        return all(_finite(part) for part in result)
    if hasattr(result, "omega_a"):                  # an AbsorberSet, checked on construction
        return True
    return bool(np.all(np.isfinite(np.asarray(result, dtype=complex))))


@pytest.mark.parametrize("call", [c for _, c in AT_ZERO], ids=[str(i) for i, _ in AT_ZERO])
def test_zero_where_it_has_a_meaning_still_answers(call):
    assert _finite(call(0.0))


@pytest.mark.parametrize("call, words", [
    (lambda: tr.simulate(ROTOR, SETS, 100.0, np.array([0.0, 1e9])),
     "t: spans 1e+09 s, 1.59e+11 periods of max(omega, omega_n)"),
    (lambda: tr.simulate(ROTOR, SETS, 100.0, np.array([0.0, 0.02, 0.01])),
     "t: shape (3,); must be 1 to 10000000 increasing times"),
    (lambda: fr.amplitude(ROTOR, SETS, np.zeros(10_000_001)), "w: 10000001 entries; at most"),
    (lambda: spin.spin_dataset(ROTOR, SETS, n=10**9, realistic=10.0, w=W),
     "n = 1000000000: must be an integer >= 2 and <= 100000"),
    (lambda: tr.response_times(100.0, 1e9, 20), "t_end = 1000000000.0: 3.18e+11 samples"),
    (lambda: fr.rotor_peak(ROTOR, SETS, samples=10**9), "samples = 1000000000"),
])
def test_work_is_bounded_before_it_starts(call, words):
    start = time.perf_counter()
    with pytest.raises(ValueError) as error:
        call()
    assert words in str(error.value) and time.perf_counter() - start < 5, str(error.value)
