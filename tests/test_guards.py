"""Fault injection: the public entry points refuse bad arguments with a ValueError that names
the argument, and a failed integration is an IntegrationError, never a number."""

import math

import numpy as np
import pytest

from rotorvib.methods.ga import minimise
from rotorvib.methods.integrate import IntegrationError, integrate
from rotorvib.methods.multiple_scales import MultipleScales
from rotorvib.models.absorber.frequency_response import rotor_peak, steady_state, theta_eq20
from rotorvib.models.absorber.parameters import AbsorberSet, Rotor, dual_from_vector
from rotorvib.models.absorber.time_response import simulate as time_simulate
from rotorvib.models.balancer import layout
from rotorvib.models.balancer.criteria import BalanceCriterion
from rotorvib.models.balancer.parameters import Balancer, SpeedProfile, fixed_parameters
from rotorvib.models.balancer.simulate import run_batch, simulate
from rotorvib.papers.b.optimise import balance_time_objective

B = dict(M=1.0, k=1e4, R=0.1, m_bar=0.01, eps_bar=0.01, zeta=0.01, beta=1.0)
PROFILE = SpeedProfile(200.0, "runup", 0.5, "printed")
PHI0 = np.radians([45.0, 90.0])


@pytest.mark.parametrize("kwargs, named", [
    ({"t_end": -1.0}, "t_end"), ({"t_end": 0.0}, "t_end"), ({"t_end": math.nan}, "t_end"),
    ({"sample_dt": 0.0}, "sample_dt"), ({"sample_dt": 5.0, "t_end": 1.0}, "sample_dt"),
    ({"r_threshold": math.nan}, "r_threshold"), ({"r_threshold": -1e-4}, "r_threshold"),
    ({"rtol": 0.0, "atol": 0.0}, "rtol"), ({"rtol": 1e-16}, "rtol"), ({"atol": -1.0}, "atol"),
    ({"r0": math.inf}, "r0"),
])
def test_simulate_refuses_bad_arguments(kwargs, named):
    args = {"t_end": 2.0, **kwargs}
    with pytest.raises(ValueError, match=named):
        simulate(Balancer.from_paper_b(**B), PROFILE, PHI0, **args)


@pytest.mark.parametrize("field", ["M", "k", "R", "m_bar", "eps_bar", "zeta", "beta"])
def test_a_nan_physical_parameter_is_named(field):
    with pytest.raises(ValueError, match=r"Balancer\.\w+ = nan"):
        Balancer.from_paper_b(**{**B, field: math.nan})


def test_a_nan_ball_angle_is_named():
    with pytest.raises(ValueError, match=r"phi0\[1\]"):
        simulate(Balancer.from_paper_b(**B), PROFILE, [0.1, math.nan], 1.0)


def test_run_batch_names_the_non_finite_row():
    p = fixed_parameters(Balancer.from_paper_b(**B), PROFILE)
    params = np.stack([p, p, p])
    params[2, 0] = math.nan
    y0 = np.zeros((3, 8))
    criterion = BalanceCriterion(1e-4, 1.0, 1.0, 1e-3)
    with pytest.raises(ValueError, match=r"params\[2, 0\] = nan: must be finite"):
        run_batch(layout.FIXED, params, y0, criterion, progress=False)


@pytest.mark.parametrize("make, named", [
    (lambda: Rotor(M=math.nan, R=0.14, k_t=1e4, Gamma0=5.0), "Rotor.M"),
    (lambda: Rotor(M=5.0, R=0.14, k_t=-1.0, Gamma0=5.0), "Rotor.k_t"),
    (lambda: AbsorberSet(m=0.1, k=1e4, c=math.inf, d=0.1), "AbsorberSet.c"),
    (lambda: AbsorberSet(m=0.0, k=1e4, c=1.0, d=0.1), "AbsorberSet.m"),
])
def test_absorber_parameters_are_checked(make, named):
    with pytest.raises(ValueError, match=named):
        make()


def test_a_failed_reference_integration_raises_integration_error():
    """y' = y^2 from y(0) = 1 blows up at t = 1: the solver fails before t = 2."""
    with pytest.raises(IntegrationError, match=r"RK45 failed at t = 1\.0"):
        integrate(lambda t, y: y**2, [1.0], np.linspace(0.0, 2.0, 5), rtol=1e-8, atol=1e-10,
                  method="RK45")


def test_a_non_finite_reference_state_raises_integration_error():
    with pytest.raises(IntegrationError):
        integrate(lambda t, y: np.array([math.nan]), [1.0], [0.0, 1.0], rtol=1e-8, atol=1e-10)


@pytest.mark.parametrize("kwargs, named", [({"rtol": 1e-17}, "rtol"), ({"atol": math.nan}, "atol")])
def test_reference_integration_refuses_tolerances_below_double_precision(kwargs, named):
    with pytest.raises(ValueError, match=named):
        integrate(lambda t, y: -y, [1.0], [0.0, 1.0], **{"rtol": 1e-8, "atol": 1e-10, **kwargs})


# --- the multiple-scales solver -----------------------------------------------------------------

J2 = np.array([[0.0, 1.0], [-1.0, -0.1]])         # a damped oscillator
T2 = np.zeros((2, 2, 2))
T2[1, 0, 0] = -1.0                                  # x'' = ... - x^2


@pytest.mark.parametrize("J, T, named", [
    (np.ones((2, 3)), T2, r"J: shape \(2, 3\)"),
    ([[0.0, math.nan], [-1.0, 0.0]], T2, r"J\[0, 1\] = nan: must be finite \(1 of 4 entries are not\)"),
    (J2, np.zeros((2, 2)), r"T: shape \(2, 2\)"),
    (J2, np.full((2, 2, 2), math.inf), r"T\[0, 0, 0\] = inf: must be finite \(8 of 8"),
])
def test_multiple_scales_refuses_bad_matrices(J, T, named):
    with pytest.raises(ValueError, match=named):
        MultipleScales.at(J, T)


@pytest.mark.parametrize("method", ["one_term", "two_term"])
@pytest.mark.parametrize("x0, tau, named", [
    ([0.1, 0.0, 0.0], [0.0, 1.0], r"x0: shape \(3,\)"),
    ([0.1, math.nan], [0.0, 1.0], r"x0\[1\] = nan"),
    ([0.1, 0.0], [0.0, math.inf], r"tau\[1\] = inf"),
    ([0.1, 0.0], [[0.0, 1.0]], r"tau: shape \(1, 2\)"),
])
def test_multiple_scales_solutions_refuse_bad_states(method, x0, tau, named):
    with pytest.raises(ValueError, match=named):
        getattr(MultipleScales.at(J2, T2), method)(x0, tau)


def test_multiple_scales_guards_leave_the_solution_untouched():
    """The checked call still gives the linear solution x = 0.1 e^{-0.05 t} cos(w t) + ... at
    order one: x(0) = x0 exactly."""
    ms = MultipleScales.at(J2, T2)
    assert ms.one_term([0.1, 0.0], [0.0])[0] == pytest.approx([0.1, 0.0], abs=1e-15)


# --- the genetic algorithm and its objectives ---------------------------------------------------

def sphere(X):
    return np.sum(X**2, axis=1)


@pytest.mark.parametrize("kwargs, named", [
    ({"lower": [0.0, math.nan]}, r"lower\[1\] = nan"),
    ({"upper": [1.0]}, r"upper: shape \(1,\)"),
    ({"lower": [1.0, 0.0]}, "lower < upper"),
    ({"pop_size": 1}, "pop_size = 1"),
    ({"pop_size": 20.0}, "pop_size = 20.0"),
    ({"n_gen": 0}, "n_gen = 0"),
    ({"seed": -1}, "seed = -1"),
    ({"sbx_eta": math.nan}, "sbx_eta"),
])
def test_minimise_refuses_bad_arguments(kwargs, named):
    args = {"lower": [-1.0, -1.0], "upper": [1.0, 1.0], "pop_size": 8, "n_gen": 2, "seed": 1,
            **kwargs}
    with pytest.raises(ValueError, match=named):
        minimise(sphere, args.pop("lower"), args.pop("upper"), **args)


def test_a_non_finite_objective_stops_the_ga_naming_the_point():
    def poisoned(X):
        f = sphere(X)
        f[X[:, 0] > 0.5] = math.nan
        return f

    with pytest.raises(FloatingPointError, match=r"objective: non-finite value at \d+ of 8 "
                                                 r"points, first x = \[0\.[5-9]"):
        minimise(poisoned, [-1.0, -1.0], [1.0, 1.0], pop_size=8, n_gen=3, seed=1)


def test_an_objective_of_the_wrong_shape_is_named():
    with pytest.raises(ValueError, match=r"objective: returned shape \(8, 1\)"):
        minimise(lambda X: sphere(X)[:, None], [-1.0, -1.0], [1.0, 1.0], pop_size=8, n_gen=2,
                 seed=1)


@pytest.mark.parametrize("penalty", [0.5, math.nan])
def test_a_censored_penalty_below_one_is_refused(penalty):
    """A penalty below t_end would let an unbalanced run score as a balance time."""
    with pytest.raises(ValueError, match="censored_penalty"):
        balance_time_objective(None, kinematics="printed", eps_bar=0.01, phi0_deg=(45, 90),
                               censored_penalty=penalty)


# --- paper C's responses -------------------------------------------------------------------------

ROTOR = Rotor(M=5.0, R=0.14, k_t=1e4, Gamma0=5.0)
DESIGN = [0.1, 0.1, 1e3, 1e3, 1.0, 1.0, 0.05, 0.1]


@pytest.mark.parametrize("call, named", [
    (lambda: theta_eq20(ROTOR, DESIGN[:7], 1.0), r"x: shape \(7,\)"),
    (lambda: theta_eq20(ROTOR, [math.nan] + DESIGN[1:], 1.0), r"x\[0\] = nan"),
    (lambda: theta_eq20(ROTOR, DESIGN, [1.0, math.nan]), r"omega\[1\] = nan"),
    (lambda: steady_state(ROTOR, dual_from_vector(DESIGN), math.inf), r"omega = inf: must be finite \(1 of 1"),
    (lambda: rotor_peak(ROTOR, dual_from_vector(DESIGN), samples=2), "samples = 2"),
    (lambda: time_simulate(ROTOR, dual_from_vector(DESIGN), math.nan, [0.0, 1.0]), "omega = nan"),
    (lambda: time_simulate(ROTOR, dual_from_vector(DESIGN), -1.0, [0.0, 1.0]), "omega = -1.0"),
])
def test_absorber_responses_refuse_bad_arguments(call, named):
    with pytest.raises(ValueError, match=named):
        call()
