"""Paper B's configuration checks beyond the schema (:func:`problems`): its studies, the
existence bound of every ball mass, the engine's limits on a run, its stability boundaries and
maps, each named by its key within ``paper_b``.  The workflow runs them when it reads the
configuration, before any job (:mod:`rotorvib.pipeline.config_checks`, which writes the
messages), so they import numpy and the engine's limits only, not the compiled engine."""

from __future__ import annotations

import math

import numpy as np

from rotorvib.checks import sobol_design_problem
from rotorvib.papers.config_problems import seed_spread_problem, tolerance_problem
from rotorvib.models.balancer.limits import radians_problem, samples_problem

#: Chosen: the most run-ups one grid study of paper B may ask for. Every job of a study (each
#: shard, and the job that gathers them) keeps some arrays over all its run-ups: measured with
#: tracemalloc, about 0.6 KB a run-up in a job that runs the whole study (the inputs as arrays,
#: the metrics, the grid's indices; the stop certificates of a few thousand runs at a time) and
#: 0.2 KB in a shard (besides its share's inputs) or the gathering. Four million is 2.4 GB in
#: one job, and some 2 CPU-hours (a run-up takes under 2 ms).
MAX_STUDY_RUNS = 4_000_000


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

def study_size_problems(b: dict) -> list[tuple[str, str]]:
    """The grid studies of paper B that ask for more run-ups than :data:`MAX_STUDY_RUNS`, each
    named by the key of its grid with the largest value it allows there: a balance study (its
    points x its ``each`` values x the initial conditions x the kinematics), Table 1's (masses
    x speeds x initial conditions x kinematics) and the basin map (n^2 starting positions x
    cases x kinematics, every one of them held although half are run)."""
    conditions = len(b["initial_conditions"]) * len(b["kinematics"])
    grids = {f"balance_studies.{name}.range.n":
             (study["range"]["n"], 1, conditions * math.prod(
                 np.size(values) for values in study.get("each", {}).values()))
             for name, study in b["balance_studies"].items()}
    grids["table1.mass.n"] = (b["table1"]["mass"]["n"], 1,
                                      conditions * len(b["table1"]["speeds"]))
    grids["basin.n"] = (b["basin"]["n"], 2, len(b["basin"]["cases"]) * len(b["kinematics"]))
    # the zeta inversion: Fig 7's run, Table 1's speeds x ICs and Table 2's rows at each zeta
    printed_runs = 1 + len(b["table1"]["speeds"]) * len(b["initial_conditions"]) \
        + len(b["table2"]["cases"])
    grids["zeta_inversion.zeta.n"] = (b["zeta_inversion"]["zeta"]["n"], 1,
                                              printed_runs * len(b["kinematics"]))
    problems = []
    for key, (n, power, times) in grids.items():
        if (runs := n ** power * times) > MAX_STUDY_RUNS:
            allowed = math.floor((MAX_STUDY_RUNS / times) ** (1 / power))
            problems.append((key, f"{n} makes {runs} run-ups of its study, more "
                            f"than {MAX_STUDY_RUNS} (every job of a study keeps arrays over all "
                            f"of them; paper_b.shards does not split that): at most {allowed} "
                            "here"))
    return problems

def given_values(study: dict) -> dict:
    """The parameters a ``balance_studies`` entry gives besides its axis: its ``fixed`` values
    and its ``each`` lists."""
    return {**study["fixed"], **study.get("each", {})}

def existence_problems(b: dict) -> list[tuple[str, str]]:
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
                    problems.append((key, f"{m:g} is below the existence bound (34) "
                                          f"{bound:g} for eps_bar = {eps:g} (m/M >= eps_bar/2)"))

    ga = b["ga"]
    check("ga.mass", ga["mass"][0], ga["eps_bar"])
    for i, (_, m) in enumerate(b["table2"]["cases"]):
        check(f"table2.cases.{i}", m, b["table2"]["eps_bar"])
    check("table1.mass.min", b["table1"]["mass"]["min"], b["table1"]["eps_bar"])
    for machine in b["design_rule"]["machines"].values():
        check("design_rule.mass.min", b["design_rule"]["mass"]["min"], machine["eps_bar"])
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

def prior_problems(b: dict) -> list[tuple[str, str]]:
    """Alternative priors of the uncertainty study that are not a range ``[low, high]`` with
    ``low <= high`` inside the input's own range (a narrower range is the sample's points
    inside it, so it cannot reach beyond the sample)."""
    u, found = b["uncertainty"], []
    for name, priors in u["prior_alternatives"].items():
        low, high = u["ranges"][name]
        for i, (a, z) in enumerate(priors):
            if not low <= a <= z <= high:
                found.append((f"uncertainty.prior_alternatives.{name}[{i}]",
                              f"{[a, z]} must be [low, high] with {low:g} <= low <= high <= "
                              f"{high:g} (uncertainty.ranges.{name})"))
    return found


def design_rule_problems(b: dict) -> list[tuple[str, str]]:
    """The design rule's initial conditions that ``initial_conditions`` does not name, and a
    machine whose operating speed the run-up reaches without passing the critical speed (no
    passage to predict)."""
    rule, found = b["design_rule"], []
    if unknown := [name for name in rule["ics"] if name not in b["initial_conditions"]]:
        found.append(("design_rule.ics", f"{unknown} are not initial conditions of "
                                         f"paper_b.initial_conditions {list(b['initial_conditions'])}"))
    machine = b["machine"]
    critical = np.sqrt(machine["k"] / machine["M"])
    for name, other in rule["machines"].items():
        if other["speed"] <= critical:
            found.append((f"design_rule.machines.{name}.speed",
                          f"{other['speed']:g} rad/s does not pass the critical speed "
                          f"sqrt(k/M) = {critical:g} rad/s: no passage"))
    return found


def run_budget_problems(b: dict) -> list[tuple[str, str]]:
    """Runs the engine would refuse (:mod:`rotorvib.models.balancer.limits`), named by their
    config keys before any job: more samples than it keeps, or more radians of the fastest
    rate (every disk speed a study asks for, the natural frequency sqrt(k/M), the support's
    damping rate 2 zeta sqrt(k/M) or the balls' drag rate beta sqrt(k/M)) than it integrates."""
    balance, machine = b["balance"], b["machine"]
    t_end = balance["t_end"]
    problems = []
    if problem := samples_problem(t_end, balance["sample_dt"]):
        problems.append(("balance.sample_dt", f"{balance['sample_dt']!r} with t_end = "
                                              f"{t_end!r}: {problem}"))
    omega_n = np.sqrt(machine["k"] / machine["M"])
    rates = {"speed.omega": b["speed"]["omega"],
             "table1.speeds": max(b["table1"]["speeds"]),
             "table2.speed": b["table2"]["speed"],
             "pareto.speed": b["pareto"]["speed"],
             "machine.k": omega_n,
             "machine.zeta": 2 * machine["zeta"] * omega_n,
             "zeta_inversion.zeta": 2 * b["zeta_inversion"]["zeta"]["max"] * omega_n,
             "uncertainty.ranges.zeta": 2 * max(b["uncertainty"]["ranges"]["zeta"]) * omega_n,
             "ga.beta": max(b["ga"]["beta"]) * omega_n,
             "table1.beta": b["table1"]["beta"] * omega_n}
    for name, study in b["balance_studies"].items():
        speeds = [study["range"]["max"]] if study["axis"] == "speed" else []
        speeds += list(np.atleast_1d(given_values(study).get("speed", [])))
        if speeds:
            rates[f"balance_studies.{name}"] = max(speeds)
    for key, rate in rates.items():
        if problem := radians_problem(float(rate), t_end):
            problems.append((key, f"with paper_b.balance.t_end = {t_end!r}, {problem}"))
    return problems

def boundary_base(b: dict) -> dict:
    """The base point of paper B's stability boundaries: Fig 2's m_bar and eps_bar, Fig 3's
    beta and the machine's zeta; each plane varies one of beta, m_bar, zeta from it."""
    maps = b["stability_maps"]
    return {"m_bar": maps["fig2"]["m_bar"], "eps_bar": maps["fig2"]["eps_bar"],
            "beta": maps["fig3"]["beta"], "zeta": b["machine"]["zeta"]}

def boundary_problems(b: dict) -> list[tuple[str, str]]:
    """A plane of paper B's stability boundaries whose span misses its base value (tracing
    starts there) or whose m_bar reaches the existence bound (34), and steps out of order."""
    base, spans, found = boundary_base(b), b["boundaries"], []
    for plane in ("beta", "m_bar", "zeta"):
        lo, hi = spans[plane]["min"], spans[plane]["max"]
        if not lo < base[plane] < hi:
            found.append((f"boundaries.{plane}", f"[{lo:g}, {hi:g}] must contain the base "
                                                 f"value {base[plane]:g}, where tracing starts"))
    if spans["m_bar"]["min"] <= base["eps_bar"] / 2:
        found.append(("boundaries.m_bar.min", f"{spans['m_bar']['min']:g} must exceed the "
                                              "existence bound (34) eps_bar/2 = "
                                              f"{base['eps_bar'] / 2:g}"))
    step = spans["step"]
    if not step["min"] <= step["initial"] <= step["max"]:
        found.append(("boundaries.step", f"need min <= initial <= max, got {step['min']:g}, "
                                         f"{step['initial']:g}, {step['max']:g}"))
    return found

def ga_law_problems(b: dict) -> list[tuple[str, str]]:
    """The GA-optimum study (``paper_b.ga_law``) integrating past the balance criterion's
    ``t_end`` (whose run budget is checked) or leaving fewer than three envelope bins after the
    run-up and the settling time to fit a decay to."""
    law, found = b["ga_law"], []
    if law["horizon"] > b["balance"]["t_end"]:
        found.append(("ga_law.horizon", f"{law['horizon']:g} s must not exceed "
                                        f"paper_b.balance.t_end = {b['balance']['t_end']:g} s"))
    start = b["speed"]["t_ramp"] + law["settle"]
    if law["horizon"] - start < 3 * law["width"]:
        found.append(("ga_law.horizon", f"{law['horizon']:g} s leaves fewer than three bins "
                                        f"of width {law['width']:g} s after the run-up and "
                                        f"the settling time ({start:g} s)"))
    return found

def ross_problems(b: dict) -> list[tuple[str, str]]:
    """The ROSS cross-check's steady responses are at speeds above zero (at rest there is no
    unbalance force to respond to; found by the fuzzer: a speed of 0 failed inside b_ross)."""
    lowest = b["ross_check"]["speeds"]["min"]
    return ([] if lowest > 0 else
            [("ross_check.speeds.min", f"{lowest!r} must be > 0 (a steady unbalance "
                                       "response needs a spinning rotor)")])

def map_problems(b: dict) -> list[tuple[str, str]]:
    """A stability map is drawn over its grid: each axis needs two points at least (found by
    the fuzzer: Fig 3's m_bar with one point failed in its figure)."""
    return [(f"stability_maps.{fig}.{axis}.n", f"{grid['n']} point; a map needs at least 2 "
                                                "along each axis")
            for fig, axes in b["stability_maps"].items() for axis, grid in axes.items()
            if isinstance(grid, dict) and grid["n"] < 2]


def problems(b: dict) -> list[tuple[str, str]]:
    """Every problem of the ``paper_b`` section of a configuration that satisfies the schema,
    as ``(key within paper_b, what is wrong)``: a study that does not name beta, mass and
    eps_bar once each, a Sobol design that cannot be run, a GA seed repeated among its spread
    seeds, a ball mass below the existence bound, a run the engine would refuse, a stability-
    boundary plane that cannot start, a GA-optimum study with nothing to fit, a ROSS speed of
    zero, a tolerance finer than double precision, a stability map of one point along an axis,
    a grid study of more run-ups than a job can hold, an alternative prior beyond its range."""
    found = [(f"balance_studies.{name}", problem)
             for name, study in b["balance_studies"].items()
             if (problem := study_problem(study))]
    for key, sample in (("uncertainty", b["uncertainty"]),
                        ("uncertainty.mean_over_ics", b["uncertainty"]["mean_over_ics"])):
        if problem := sobol_design_problem(sample["n_base"], sample["convergence"]):
            found.append((key, problem))
    if problem := seed_spread_problem(b["ga"], "paper_b.ga"):
        found.append(("ga.spread_seeds", problem))
    if problem := tolerance_problem(b["balance"]["integrator"]["rtol"]):
        found.append(("balance.integrator.rtol", problem))
    return (found + existence_problems(b) + run_budget_problems(b) + study_size_problems(b)
            + boundary_problems(b) + ga_law_problems(b) + ross_problems(b) + map_problems(b)
            + design_rule_problems(b) + prior_problems(b))
