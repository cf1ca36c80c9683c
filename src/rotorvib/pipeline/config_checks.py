"""The configuration's checks beyond its schema (:func:`problems`): paper B's studies, Sobol
designs, the existence bound of every ball mass and the engine's limits on a run, each named by
its config key.  The workflow runs them when it reads the configuration, before any job, so
they import numpy, the engine's limits and the integrators' tolerance floor only, not the
compiled engine."""

from __future__ import annotations

import math

import numpy as np

from rotorvib.checks import sobol_design_problem
from rotorvib.methods.integrate import RTOL_MIN
from rotorvib.models.balancer.limits import radians_problem, samples_problem


def study_problem(study: dict) -> str | None:
    """What is wrong with a ``balance_studies`` entry of the config, or None: its axis, ``each``
    and ``fixed`` parameters must name beta, mass and eps_bar, each once."""
    given = [study["axis"], *study.get("each", {}), *study["fixed"]]
    repeated = sorted({name for name in given if given.count(name) > 1})
    missing = sorted({"beta", "mass", "eps_bar"} - set(given))
    if repeated:
        return f"parameter(s) {repeated} given more than once (axis, each, fixed)"
    if missing:
        return f"parameter(s) {missing} missing: give them in 'fixed' or 'each'"
    return None


#: Chosen: the most run-ups one grid study of paper B may ask for. Every job of a study (each
#: shard, and the job that gathers them) keeps some arrays over all its run-ups: measured with
#: tracemalloc, about 0.6 KB a run-up in a job that runs the whole study (the inputs as arrays,
#: the metrics, the grid's indices; the stop certificates of a few thousand runs at a time) and
#: 0.2 KB in a shard (besides its share's inputs) or the gathering. Four million is 2.4 GB in
#: one job, and some 2 CPU-hours (a run-up takes under 2 ms).
MAX_STUDY_RUNS = 4_000_000


def study_size_problems(b: dict) -> list[str]:
    """The grid studies of paper B that ask for more run-ups than :data:`MAX_STUDY_RUNS`, each
    named by the key of its grid with the largest value it allows there: a balance study (its
    points x its ``each`` values x the initial conditions x the kinematics), Table 1's (masses
    x speeds x initial conditions x kinematics) and the basin map (n^2 starting positions x
    cases x kinematics, every one of them held although half are run)."""
    conditions = len(b["initial_conditions"]) * len(b["kinematics"])
    grids = {f"paper_b.balance_studies.{name}.range.n":
             (study["range"]["n"], 1, conditions * math.prod(
                 np.size(values) for values in study.get("each", {}).values()))
             for name, study in b["balance_studies"].items()}
    grids["paper_b.table1.mass.n"] = (b["table1"]["mass"]["n"], 1,
                                      conditions * len(b["table1"]["speeds"]))
    grids["paper_b.basin.n"] = (b["basin"]["n"], 2, len(b["basin"]["cases"]) * len(b["kinematics"]))
    # the zeta inversion: Fig 7's run, Table 1's speeds x ICs and Table 2's rows at each zeta
    printed_runs = 1 + len(b["table1"]["speeds"]) * len(b["initial_conditions"]) \
        + len(b["table2"]["cases"])
    grids["paper_b.zeta_inversion.zeta.n"] = (b["zeta_inversion"]["zeta"]["n"], 1,
                                              printed_runs * len(b["kinematics"]))
    problems = []
    for key, (n, power, times) in grids.items():
        if (runs := n ** power * times) > MAX_STUDY_RUNS:
            allowed = math.floor((MAX_STUDY_RUNS / times) ** (1 / power))
            problems.append(f"config key '{key}': {n} makes {runs} run-ups of its study, more "
                            f"than {MAX_STUDY_RUNS} (every job of a study keeps arrays over all "
                            f"of them; paper_b.shards does not split that): at most {allowed} "
                            "here")
    return problems


def given_values(study: dict) -> dict:
    """The parameters a ``balance_studies`` entry gives besides its axis: its ``fixed`` values
    and its ``each`` lists."""
    return {**study["fixed"], **study.get("each", {})}


def existence_problems(b: dict) -> list[str]:
    """Every ball mass of a paper B study (not of the stability maps, which chart where a
    balanced state exists) below the existence bound (34) ``m >= eps_bar M / 2`` of its
    eccentricity: such a balancer can never balance, so its balance time is not a number."""
    M = b["machine"]["M"]
    problems = []

    def check(key, masses, eps_bars, as_ratio=False):
        scale = 1.0 if as_ratio else M
        for m in np.atleast_1d(masses):
            for eps in np.atleast_1d(eps_bars):
                if m < eps * scale / 2 * (1 - 1e-12):
                    bound = eps * scale / 2
                    problems.append(f"config key 'paper_b.{key}': {m:g} is below the existence "
                                    f"bound (34) {bound:g} for eps_bar = {eps:g} (m/M >= eps_bar/2)")

    ga = b["ga"]
    check("ga.mass", ga["mass"][0], ga["eps_bar"])
    for i, (_, m) in enumerate(b["table2"]["cases"]):
        check(f"table2.cases.{i}", m, b["table2"]["eps_bar"])
    check("table1.mass.min", b["table1"]["mass"]["min"], b["table1"]["eps_bar"])
    for i, (_, m) in enumerate(b["basin"]["cases"]):
        check(f"basin.cases.{i}", m, b["basin"]["eps_bar"])
    tr = b["time_responses"]
    for name in ("fig6", "fig7", "fig11"):
        check(f"time_responses.{name}.m_bar", tr[name]["m_bar"], tr[name]["eps_bar"], True)
    check("time_responses.fig15.masses", tr["fig15"]["masses"], tr["fig15"]["eps_bar"])
    for name, study in b["balance_studies"].items():
        values = given_values(study)
        if study["axis"] in ("mass", "eps_bar"):  # the worst case: least mass, largest eps_bar
            values[study["axis"]] = study["range"]["min" if study["axis"] == "mass" else "max"]
        if "mass" in values and "eps_bar" in values:
            check(f"balance_studies.{name}", np.min(values["mass"]), np.max(values["eps_bar"]))
    return problems


def run_budget_problems(b: dict) -> list[str]:
    """Runs the engine would refuse (:mod:`rotorvib.models.balancer.limits`), named by their
    config keys before any job: more samples than it keeps, or more radians of the fastest
    rate (every disk speed a study asks for, the natural frequency sqrt(k/M), the support's
    damping rate 2 zeta sqrt(k/M) or the balls' drag rate beta sqrt(k/M)) than it integrates."""
    balance, machine = b["balance"], b["machine"]
    t_end = balance["t_end"]
    problems = []
    if problem := samples_problem(t_end, balance["sample_dt"]):
        problems.append(f"config key 'paper_b.balance.sample_dt': {balance['sample_dt']!r} with "
                        f"t_end = {t_end!r}: {problem}")
    omega_n = np.sqrt(machine["k"] / machine["M"])
    rates = {"paper_b.speed.omega": b["speed"]["omega"],
             "paper_b.table1.speeds": max(b["table1"]["speeds"]),
             "paper_b.table2.speed": b["table2"]["speed"],
             "paper_b.pareto.speed": b["pareto"]["speed"],
             "paper_b.machine.k": omega_n,
             "paper_b.machine.zeta": 2 * machine["zeta"] * omega_n,
             "paper_b.zeta_inversion.zeta": 2 * b["zeta_inversion"]["zeta"]["max"] * omega_n,
             "paper_b.uncertainty.ranges.zeta": 2 * max(b["uncertainty"]["ranges"]["zeta"])
             * omega_n,
             "paper_b.ga.beta": max(b["ga"]["beta"]) * omega_n,
             "paper_b.table1.beta": b["table1"]["beta"] * omega_n}
    for name, study in b["balance_studies"].items():
        speeds = [study["range"]["max"]] if study["axis"] == "speed" else []
        speeds += list(np.atleast_1d(given_values(study).get("speed", [])))
        if speeds:
            rates[f"paper_b.balance_studies.{name}"] = max(speeds)
    for key, rate in rates.items():
        if problem := radians_problem(float(rate), t_end):
            problems.append(f"config key '{key}': with paper_b.balance.t_end = {t_end!r}, "
                            f"{problem}")
    return problems


def boundary_base(b: dict) -> dict:
    """The base point of paper B's stability boundaries: Fig 2's m_bar and eps_bar, Fig 3's
    beta and the machine's zeta; each plane varies one of beta, m_bar, zeta from it."""
    maps = b["stability_maps"]
    return {"m_bar": maps["fig2"]["m_bar"], "eps_bar": maps["fig2"]["eps_bar"],
            "beta": maps["fig3"]["beta"], "zeta": b["machine"]["zeta"]}


def boundary_problems(b: dict) -> list[str]:
    """A plane of paper B's stability boundaries whose span misses its base value (tracing
    starts there) or whose m_bar reaches the existence bound (34), and steps out of order."""
    base, spans, found = boundary_base(b), b["boundaries"], []
    for plane in ("beta", "m_bar", "zeta"):
        lo, hi = spans[plane]["min"], spans[plane]["max"]
        if not lo < base[plane] < hi:
            found.append(f"config key 'paper_b.boundaries.{plane}': [{lo:g}, {hi:g}] must "
                         f"contain the base value {base[plane]:g}, where tracing starts")
    if spans["m_bar"]["min"] <= base["eps_bar"] / 2:
        found.append(f"config key 'paper_b.boundaries.m_bar.min': {spans['m_bar']['min']:g} "
                     f"must exceed the existence bound (34) eps_bar/2 = {base['eps_bar'] / 2:g}")
    step = spans["step"]
    if not step["min"] <= step["initial"] <= step["max"]:
        found.append(f"config key 'paper_b.boundaries.step': need min <= initial <= max, got "
                     f"{step['min']:g}, {step['initial']:g}, {step['max']:g}")
    return found


def ga_law_problems(b: dict) -> list[str]:
    """The GA-optimum study (``paper_b.ga_law``) integrating past the balance criterion's
    ``t_end`` (whose run budget is checked) or leaving fewer than three envelope bins after the
    run-up and the settling time to fit a decay to."""
    law, found = b["ga_law"], []
    if law["horizon"] > b["balance"]["t_end"]:
        found.append(f"config key 'paper_b.ga_law.horizon': {law['horizon']:g} s must not "
                     f"exceed paper_b.balance.t_end = {b['balance']['t_end']:g} s")
    start = b["speed"]["t_ramp"] + law["settle"]
    if law["horizon"] - start < 3 * law["width"]:
        found.append(f"config key 'paper_b.ga_law.horizon': {law['horizon']:g} s leaves fewer "
                     f"than three bins of width {law['width']:g} s after the run-up and the "
                     f"settling time ({start:g} s)")
    return found


def fig6_problems(c: dict) -> list[str]:
    """Paper C's Fig 6 claims compare curves of the mass-ratio family: each ratio they name
    (``claims.fig6_mu``) must be one of ``mass_ratio_family.mu``."""
    family = np.asarray(c["mass_ratio_family"]["mu"], float)
    roles = c["claims"]["fig6_mu"]
    return [f"config key 'paper_c.mass_ratio_family.mu': must contain {m:g}, the mass ratio of "
            f"paper_c.claims.fig6_mu.{role} (Fig 6's claims compare it)"
            for role, values in roles.items() for m in np.atleast_1d(values)
            if not np.isclose(family, m).any()]


def distance_problems(c: dict) -> list[str]:
    """The distance study moves both absorber sets of Table 2 by each offset: none may move a
    set to the disk centre or through it."""
    nearest = min(c["table2"]["d1"], c["table2"]["d2"])
    lowest = min(c["distance_study"]["offsets"])
    if nearest + lowest > 0:
        return []
    return [f"config key 'paper_c.distance_study.offsets': {lowest:g} m moves the set at "
            f"{nearest:g} m (paper_c.table2) to or through the disk centre; each offset must "
            f"exceed {-nearest:g} m"]


def spin_problems(c: dict) -> list[str]:
    """Paper C's spin study follows Table 2's absorber up to 99 % of its first spring loss,
    sqrt(2 k / m) of a set: every machine speed the spin claim is evaluated at must lie below."""
    t2 = c["table2"]
    loss = min(np.sqrt(2 * t2[f"k{j}"] / t2[f"m{j}"]) for j in (1, 2)) * 30 / np.pi
    speeds = {"paper_c.spin.realistic_rpm": [c["spin"]["realistic_rpm"]],
              "paper_c.spin.alternative_rpm": c["spin"]["alternative_rpm"]}
    return [f"config key '{key}': {rpm:g} rpm is beyond the spins followed, up to "
            f"{0.99 * loss:.6g} rpm (99 % of Table 2's first spring loss sqrt(2k/m))"
            for key, values in speeds.items() for rpm in values if rpm > 0.99 * loss]


def ross_problems(b: dict) -> list[str]:
    """The ROSS cross-check's steady responses are at speeds above zero (at rest there is no
    unbalance force to respond to; found by the fuzzer: a speed of 0 failed inside b_ross)."""
    lowest = b["ross_check"]["speeds"]["min"]
    return ([] if lowest > 0 else
            [f"config key 'paper_b.ross_check.speeds.min': {lowest!r} must be > 0 (a steady "
             "unbalance response needs a spinning rotor)"])


def tolerance_problems(config: dict) -> list[str]:
    """Every integrator's relative tolerance at or above what double precision can deliver
    (:data:`rotorvib.methods.integrate.RTOL_MIN`, which the integrators refuse below; found by
    the fuzzer: the schema's 1e-14 passed and failed inside paper B's jobs)."""
    return [f"config key '{key}.rtol': {rtol!r} is below {RTOL_MIN:.3g}, the least relative "
            "error double precision can deliver"
            for key, rtol in (("paper_a.rk", config["paper_a"]["rk"]["rtol"]),
                              ("paper_b.balance.integrator",
                               config["paper_b"]["balance"]["integrator"]["rtol"]),
                              ("paper_c.time_response",
                               config["paper_c"]["time_response"]["rtol"]))
            if rtol < RTOL_MIN]


def map_problems(b: dict) -> list[str]:
    """A stability map is drawn over its grid: each axis needs two points at least (found by
    the fuzzer: Fig 3's m_bar with one point failed in its figure)."""
    return [f"config key 'paper_b.stability_maps.{fig}.{axis}.n': {grid['n']} point; a map "
            "needs at least 2 along each axis"
            for fig, axes in b["stability_maps"].items() for axis, grid in axes.items()
            if isinstance(grid, dict) and grid["n"] < 2]


def problems(config: dict) -> list[str]:
    """Every problem of a configuration that satisfies the schema: a paper B study that does
    not name beta, mass and eps_bar once each, a Sobol design (papers B and C) that cannot be
    run, a GA seed repeated among its spread seeds (the spread would shrink), a ball mass
    below the existence bound, a run the engine would refuse, a stability-boundary plane that
    cannot start, a GA-optimum study with nothing to fit, a Fig 6 claim about a curve the
    mass-ratio family does not draw, a distance offset through the disk centre, a machine speed
    beyond the absorbers' spring loss, a ROSS speed
    of zero, a tolerance finer than double precision, a stability map of one point along an
    axis, a grid study of more run-ups than a job can hold."""
    b = config["paper_b"]
    found = [f"config key 'paper_b.balance_studies.{name}': {problem}"
             for name, study in b["balance_studies"].items()
             if (problem := study_problem(study))]
    for key, sample in (("paper_b.uncertainty", b["uncertainty"]),
                        ("paper_b.uncertainty.mean_over_ics", b["uncertainty"]["mean_over_ics"]),
                        ("paper_c.uncertainty", config["paper_c"]["uncertainty"])):
        if problem := sobol_design_problem(sample["n_base"], sample["convergence"]):
            found.append(f"config key '{key}': {problem}")
    for key, ga in (("paper_b.ga", b["ga"]), ("paper_c.broadband.nsga",
                                            config["paper_c"]["broadband"]["nsga"])):
        if ga["seed"] in ga["spread_seeds"]:
            found.append(f"config key '{key}.spread_seeds': must not contain {key}.seed "
                         f"({ga['seed']}), whose result it would count twice")
    return (found + existence_problems(b) + run_budget_problems(b) + study_size_problems(b)
            + boundary_problems(b)
            + ga_law_problems(b) + fig6_problems(config["paper_c"])
            + distance_problems(config["paper_c"]) + spin_problems(config["paper_c"])
            + ross_problems(b)
            + tolerance_problems(config) + map_problems(b))
