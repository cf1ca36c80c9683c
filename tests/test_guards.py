"""Fault injection: the public entry points refuse bad arguments with a ValueError that names
the argument, and a failed integration is an IntegrationError, never a number."""

import math

import numpy as np
import pytest

from rotorvib.methods.integrate import IntegrationError, integrate
from rotorvib.models.absorber.parameters import AbsorberSet, Rotor
from rotorvib.models.balancer import engine
from rotorvib.models.balancer.parameters import Balancer, SpeedProfile, fixed_parameters
from rotorvib.models.balancer.simulate import BalanceCriterion, run_batch, simulate

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
    with pytest.raises(ValueError, match=r"p: non-finite entries in row\(s\)/index\(es\) \[2\]"):
        run_batch(engine.FIXED, params, y0, criterion, progress=False)


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
