import numpy as np
import pytest

from rotorvib.methods.ga import minimise, minimise_many, pareto_front
from rotorvib.models.absorber.parameters import design_bounds, dual_to_vector
from rotorvib.papers.c.optimise import resonance_objective, tune_dual_absorber


def _shifted_sphere(x):
    return np.sum((x - 0.3) ** 2, axis=1)


def test_ga_finds_a_known_minimum():
    res = minimise(_shifted_sphere, [-1.0] * 3, [1.0] * 3, pop_size=40, n_gen=60, seed=3)
    np.testing.assert_allclose(res.x, 0.3, atol=2e-2)
    assert res.f == pytest.approx(_shifted_sphere(res.x[None])[0])
    assert np.all(np.diff(res.history["best_f"]) <= 0)        # elitist: never gets worse
    assert len(res.history["best_f"]) == 60


def test_ga_is_deterministic_for_a_seed():
    a, b, c = (minimise(_shifted_sphere, [-1.0] * 3, [1.0] * 3, pop_size=20, n_gen=10, seed=s)
               for s in (5, 5, 6))
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.history["best_x"], b.history["best_x"])
    assert not np.array_equal(a.x, c.x)


def test_dual_absorber_ga_beats_table2_within_bounds(rotor, table2, config):
    bounds = config["paper_c"]["bounds"]
    res = tune_dual_absorber(rotor, bounds, pop_size=30, n_gen=15, seed=1, sbx_eta=15, pm_eta=20)
    lower, upper = design_bounds(bounds)
    assert np.all(res.x >= lower) and np.all(res.x <= upper)
    assert res.f < resonance_objective(rotor)(dual_to_vector(table2)[None])[0]


def test_non_finite_objective_is_an_error():
    with pytest.raises(FloatingPointError):
        minimise(lambda x: np.full(len(x), np.nan), [0.0], [1.0], pop_size=4, n_gen=2, seed=0)


def test_problems_in_lockstep_equal_separate_runs():
    """minimise_many evaluates every generation of all problems in one call, yet each problem's
    GA draws from its own generator: the results equal separate runs, bit for bit."""
    centres = [0.3, -0.5, 0.1]
    calls = []

    def objectives(xs, worst):
        calls.append([len(x) for x in xs])
        return [np.sum((x - c) ** 2, axis=1) for x, c in zip(xs, centres)]

    together = minimise_many(objectives, 3, [-1.0] * 2, [1.0] * 2, pop_size=12, n_gen=8, seed=7)
    assert len(calls) == 8 and all(len(c) == 3 for c in calls)
    for c, res in zip(centres, together):
        alone = minimise(lambda x, c=c: np.sum((x - c) ** 2, axis=1), [-1.0] * 2, [1.0] * 2,
                         pop_size=12, n_gen=8, seed=7)
        np.testing.assert_array_equal(res.x, alone.x)
        np.testing.assert_array_equal(res.history["best_f"], alone.history["best_f"])
        np.testing.assert_array_equal(res.history["n_eval"], alone.history["n_eval"])


def test_a_point_worse_than_its_whole_population_may_score_inf():
    """Fitness survival keeps the pop_size best of a population and its offspring, so an
    offspring worse than the population's worst never survives: scoring it inf instead of its
    value leaves every search as it was, bit for bit. Before the first population there is
    no worst, and inf is an error there, as NaN and -inf always are."""
    centres = [0.3, -0.5, 0.1]
    worsts, skipped = [], []

    def values(xs):
        return [np.sum((x - c) ** 2, axis=1) for x, c in zip(xs, centres)]

    def bounded(xs, worst):
        worsts.append(worst)
        skipped.append(sum(int((f > w).sum()) for f, w in zip(values(xs), worst)))
        return [np.where(f > w, np.inf, f) for f, w in zip(values(xs), worst)]

    kw = dict(pop_size=12, n_gen=10, seed=[7, 8, 9])
    full = minimise_many(lambda xs, worst: values(xs), 3, [-1.0] * 2, [1.0] * 2, **kw)
    cut = minimise_many(bounded, 3, [-1.0] * 2, [1.0] * 2, **kw)
    assert np.isinf(worsts[0]).all() and np.isfinite(worsts[1:]).all()
    assert sum(skipped) > 0.3 * 12 * 9 * 3              # most offspring lose to every parent
    for a, b in zip(full, cut):
        np.testing.assert_array_equal(a.x, b.x)
        assert a.f == b.f
        for name in a.history:
            np.testing.assert_array_equal(a.history[name], b.history[name], err_msg=name)
    for bad in (np.inf, -np.inf, np.nan):
        with pytest.raises(FloatingPointError):
            minimise(lambda x, bad=bad: np.full(len(x), bad), [0.0], [1.0], pop_size=4, n_gen=2,
                     seed=0)


def _two_centres(x):
    """Schaffer-type problem: distances squared to (0, 0) and (2, 0); the Pareto set is the
    segment x1 = 0, 0 <= x0 <= 2, the front f2 = (2 - sqrt(f1))^2."""
    return np.column_stack([np.sum(x**2, axis=1), (x[:, 0] - 2) ** 2 + x[:, 1] ** 2])


def test_nsga2_recovers_an_analytic_pareto_front():
    front = pareto_front(_two_centres, 2, [-3.0, -3.0], [3.0, 3.0], pop_size=40, n_gen=80,
                         seed=2)
    f1, f2 = front.f.T
    gap = f2 - (2 - np.sqrt(f1)) ** 2             # >= 0: nothing beats the true front
    assert gap.min() > -1e-12 and np.median(gap) < 1e-3
    np.testing.assert_allclose(front.f, _two_centres(front.x))
    assert np.all(np.diff(f1) >= 0) and f1[0] < 0.01 and f2[-1] < 0.01     # spans the front
    assert front.n_eval == 40 * 80
    again = pareto_front(_two_centres, 2, [-3.0, -3.0], [3.0, 3.0], pop_size=40, n_gen=80,
                         seed=2)
    np.testing.assert_array_equal(front.x, again.x)


def test_nsga2_refuses_a_wrong_objective_shape():
    with pytest.raises(ValueError, match=r"expected \(8, 2\)"):
        pareto_front(lambda x: x[:, 0], 2, [0.0, 0.0], [1.0, 1.0], pop_size=8, n_gen=2, seed=0)
