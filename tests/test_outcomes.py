"""How a run ends (rotorvib.models.balancer.outcomes): a non-synchronous lock reproduced on
paper B's machine, told from a balanced run and from one that is merely not balanced yet."""

import numpy as np
import pytest

from rotorvib.models.balancer.layout import metric
from rotorvib.models.balancer.outcomes import (
    BALANCED,
    NON_SYNCHRONOUS,
    NOT_BALANCED,
    OUTCOMES,
    outcome,
    passage_remnant,
    synchronous_bound,
)
from rotorvib.models.balancer.parameters import fixed_parameters
from rotorvib.models.balancer.simulate import simulate
from rotorvib.papers.b.studies import balance_study_dataset

IC1 = [40.0, 45.0]


def test_light_lightly_damped_balls_lock_into_a_non_synchronous_whirl(setup):
    """Consistent kinematics, 6 g balls at beta = 0.1 from IC1 (8 s): the whirl at the end is
    more than five times the largest synchronous whirl, far above what the passage can
    leave, it turns at about the critical speed (100 rad/s), not at the disk's 200 rad/s,
    and the run is classified as locked; at beta = 1 the same balls balance."""
    inputs = [setup.run_inputs(mass=0.006, eps_bar=0.012, beta=beta, phi0_deg=IC1,
                               kinematics="consistent") for beta in (0.1, 1.0)]
    metrics = setup.runs(inputs, progress=False)
    params = np.array([p for p, _ in inputs])
    bound = synchronous_bound(params)
    assert bound[0] == pytest.approx((1.0 * 1.2e-3 + 2 * 0.006 * 0.1) * 200**2
                                     / abs(1e4 - 1.012 * 200**2 + 2j * 0.01 * 100 * 200),
                                     rel=2e-2)
    assert metric(metrics, "r_end")[0] > 5 * bound[0] > 5 * passage_remnant(metrics, params)[0]
    np.testing.assert_array_equal(outcome(metrics, params), [NON_SYNCHRONOUS, BALANCED])
    np.testing.assert_array_equal(metric(metrics, "outcome"), [NON_SYNCHRONOUS, BALANCED])
    b = setup.balancer(mass=0.006, eps_bar=0.012, beta=0.1)
    trajectory = simulate(b, setup.profile("consistent"), np.radians(IC1), 8.0, r0=setup.r0,
                          theta0=setup.theta0, store=True)
    last = trajectory.t >= 7.0
    angle = np.unwrap(np.arctan2(trajectory.y[last, 1], trajectory.y[last, 0]))
    whirl = np.polyfit(trajectory.t[last], angle, 1)[0]
    assert 90.0 < whirl < 110.0
    assert fixed_parameters(b, setup.profile("consistent"))[8] == 200.0


def test_a_run_cut_short_is_not_balanced_not_locked(setup):
    """The same balanced design stopped at 1.5 s, its whirl still above the synchronous bound
    but within what the passage can leave: not balanced by t_end, not locked."""
    import dataclasses

    short = dataclasses.replace(setup, criterion=dataclasses.replace(setup.criterion,
                                                                     t_end=1.5))
    inputs = [short.run_inputs(mass=0.006, eps_bar=0.012, beta=1.0, phi0_deg=IC1,
                               kinematics="consistent")]
    metrics = short.runs(inputs, progress=False)
    params = np.array([inputs[0][0]])
    assert metric(metrics, "r_end")[0] > synchronous_bound(params)[0]
    assert outcome(metrics, params)[0] == NOT_BALANCED


def test_the_balance_datasets_name_the_outcome(setup):
    """A balance study's dataset carries each run's outcome as a CF flag variable."""
    ds = balance_study_dataset(setup, kinematics=["consistent"], ics={"IC1": IC1}, axis="beta",
                               values=[0.1, 1.0], fixed={"mass": 0.006, "eps_bar": 0.012},
                               where="test")
    assert ds.outcome.attrs["flag_meanings"].split() == list(OUTCOMES)
    np.testing.assert_array_equal(ds.outcome.values.ravel(), [NON_SYNCHRONOUS, BALANCED])
    assert ds.r_end.attrs["units"] == "m"
