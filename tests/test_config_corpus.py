"""A corpus of malformed configurations: every case is rejected before any job, by a message
that names the offending key (the checks ``workflow/rules/common.smk`` and ``paper_b.smk`` run
before the DAG is built)."""

import copy
import math
from pathlib import Path

import pytest

from rotorvib.pipeline import config_checks
from rotorvib.pipeline.config import ConfigError, load_yaml, main, validate_config

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = load_yaml(ROOT / "config/schema.yaml")
CONFIG = load_yaml(ROOT / "config/config.yaml")
NAN, INF = math.nan, math.inf
RANGE_DOWN = {"min": 3.0, "max": 0.5, "n": 10}
DUPLICATE_KEY = "paper_b:\n  machine:\n    zeta: 0.01\n    zeta: 0.02\n"

#: (dotted key, bad value, the key the message must name)
CASES = [
    # paper C
    ("paper_c.rotor.M", -1.0, None), ("paper_c.rotor.M", NAN, None),
    ("paper_c.rotor.R", INF, None), ("paper_c.rotor.k_t", 0, None),
    ("paper_c.rotor.Gamma0", "5", None), ("paper_c.rotor.J_factor", 2.0, None),
    ("paper_c.rotor.extra", 1.0, "paper_c.rotor"), ("paper_c.table2.m1", -0.1, None),
    ("paper_c.table2.d2", NAN, None), ("paper_c.bounds.m", [0.5, 0.05], None),
    ("paper_c.bounds.k", [1e4], None), ("paper_c.bounds.c", [5.0, NAN], "paper_c.bounds.c.1"),
    ("paper_c.ga.pop_size", 200.0, None), ("paper_c.ga.n_gen", 0, None),
    ("paper_c.ga.seed", "x", None), ("paper_c.frequency_response.w_min", 1.5, None),
    ("paper_c.frequency_response.n_points", 2401.5, None),
    ("paper_c.frequency_response.w_max", INF, None), ("paper_c.mass_ratio_family.mu", [], None),
    ("paper_c.mass_ratio_family.constructions", ["bogus"], "paper_c.mass_ratio_family.constructions.0"),
    ("paper_c.broadband.band", [1.3, 0.7], None), ("paper_c.broadband.n_band", 5, None),
    ("paper_c.broadband.den_hartog_d", 0.0, None),
    ("paper_c.broadband.nsga.pop_size", 2, None), ("paper_c.broadband.nsga.seed", -1, None),
    # found by the fuzzer's runs: accepted, then failed inside a job
    ("paper_c.rotor.M", 50.0, "paper_c.frequency_response"),
    ("paper_c.rotor.R", 1.4, "paper_c.frequency_response"),
    ("paper_c.distance_study.offsets", [0.01, 0.02], "paper_c.distance_study.offsets"),
    ("paper_c.den_hartog.d", -0.1, None), ("paper_c.time_response.t_end", 0, None),
    ("paper_c.time_response.rtol", 1e-16, None),
    ("paper_c.time_response.samples_per_period", 4, None),
    ("paper_c.claims.fig3_time", 5.0, None), ("comparison.close", 2.0, None),
    ("paper_c.distance_study.offsets", [0.0], None),
    ("paper_c.spin.n", 1, None), ("paper_c.spin.realistic_rpm", 0.0, None),
    ("paper_c.spin.realistic_rpm", 5000.0, None), ("paper_c.spin.alternative_rpm", [0.0],
                                                    "paper_c.spin.alternative_rpm.0"),
    ("paper_c.spin.alternative_rpm", [1500.0, 4300.0], None),
    ("comparison.close_alternatives", [1.5], "comparison.close_alternatives.0"),
    ("paper_b.zeta_inversion.zeta", RANGE_DOWN, None),
    ("paper_b.zeta_inversion.zeta", {"min": 0.004, "max": 0.016, "n": 100_000},
     "paper_b.zeta_inversion.zeta.n"),
    ("paper_b.uncertainty.ranges.zeta", [0.02, 0.005], None),
    ("paper_b.balance_law.whirl_share", 0.0, None),
    ("paper_b.balance_law.whirl_share_alternatives", [1.5],
     "paper_b.balance_law.whirl_share_alternatives.0"),
    ("paper_c.distance_study.offsets", [0.0, 0.0], None),
    # paper B
    ("paper_b.machine.M", 0, None), ("paper_b.machine.n", 2.0, None),
    ("paper_b.machine.n", 3, None), ("paper_b.machine.zeta", NAN, None),
    ("paper_b.machine.R", 11.0, None), ("paper_b.initial_state.r0", INF, None),
    ("paper_b.initial_conditions.IC1", [40.0], None),
    ("paper_b.initial_conditions.IC2", [400.0, 0.0], "paper_b.initial_conditions.IC2.0"),
    ("paper_b.speed.omega", -200.0, None), ("paper_b.speed.t_ramp", 30.0, None),
    ("paper_b.kinematics", ["wrong"], "paper_b.kinematics.0"),
    ("paper_b.balance.r_threshold", NAN, None), ("paper_b.balance.sample_dt", 0, None),
    ("paper_b.balance.t_end", -1.0, None), ("paper_b.marginal_growth", 0.5, None),
    ("paper_b.balance.integrator.method", "rk4", None),
    ("paper_b.balance.integrator.rtol", 1e-16, None),
    ("paper_b.balance.integrator.atol", 0, None),
    ("paper_b.balance.stop.margin", 1.0, None), ("paper_b.balance.stop.check_dt", NAN, None),
    ("paper_b.balance.stop.check_dt", 1e-4, None),          # finer than the samples
    ("paper_b.balance.stop", {"margin": 0.5}, "paper_b.balance.stop.check_dt"),
    ("paper_b.stability_maps.fig2.beta", {"min": 3.0, "max": 1.0, "n": 10}, None),
    ("paper_b.stability_maps.fig2.omega_bar.n", 100000, "paper_b.stability_maps.fig2"),
    ("paper_b.stability_maps.fig3.m_bar.n", 0, None),
    ("paper_b.stability_maps.fig3.beta", NAN, None),
    ("paper_b.time_responses.fig7.phi0", [45.0], None),
    ("paper_b.time_responses.fig7.m_bar", 0.001, None),
    ("paper_b.time_responses.fig15.masses", [0.001, 0.01], None),
    ("paper_b.time_responses.fig11.ic", "IC9", None),
    ("paper_b.balance_studies.beta.axis", "foo", None),
    ("paper_b.balance_studies.beta.range.n", 2.5, None),
    ("paper_b.balance_studies.mass.range.min", 0.001, "paper_b.balance_studies.mass"),
    ("paper_b.balance_studies.beta.fixed", {}, "paper_b.balance_studies.beta"),
    ("paper_b.ga.pop_size", 1, None), ("paper_b.ga.mass", [0.001, 0.02], None),
    ("paper_b.ga.beta", [1.0, 0.1], None), ("paper_b.ga.censored_penalty", 0.5, None),
    ("paper_b.ga.eps_bar", [NAN], "paper_b.ga.eps_bar.0"),
    ("paper_b.ga.spread_seeds", [1, 2, 3], None), ("paper_b.ga.spread_seeds", [1, 2, 2, 3], None),
    ("paper_b.ga.spread_seeds", [1, 2, 3, 2014], None),
    ("paper_c.broadband.nsga.spread_seeds", [1, 2, 3, 20241114], None), ("paper_b.table1.speeds", [], None),
    ("paper_b.table1.mass.min", 0.003, None),
    ("paper_b.table2.cases", [[1.0, 0.001]], "paper_b.table2.cases.0"),
    ("paper_b.table2.ic", "IC4", None), ("paper_b.calibration.R.n", 1.0, None),
    ("paper_b.basin.n", 1000, None),
    ("paper_b.basin.cases", [[0.2, 0.001]], "paper_b.basin.cases.0"),
    ("paper_b.claims.beta_opt_range", [0.2, 0.1], None),
    ("paper_b.claims.ics_typical_share", [0.9, 0.1], None),
    ("paper_b.uncertainty.ranges.r0", [2e-3, 5e-4], None),
    ("paper_b.uncertainty.ranges.eps_tolerance", [-0.1, 0.1], "paper_b.uncertainty.ranges.eps_tolerance.1"),
    ("paper_b.uncertainty.ranges.overload", 0.0, None),
    # an alternative prior beyond the sample's range, or upside down
    ("paper_b.uncertainty.prior_alternatives.zeta", [[0.004, 0.012]],
     "paper_b.uncertainty.prior_alternatives.zeta[0]"),
    ("paper_b.uncertainty.prior_alternatives.zeta", [[0.012, 0.008]],
     "paper_b.uncertainty.prior_alternatives.zeta[0]"),
    ("paper_b.uncertainty.prior_alternatives.R", [[0.1, 0.1]],
     "paper_b.uncertainty.prior_alternatives"),
    ("paper_b.uncertainty.n_base", 2.5, None), ("paper_b.uncertainty.resamples", 0, None),
    ("paper_b.uncertainty.mean_over_ics.n_base", 0, None),
    ("paper_c.uncertainty.tolerance", 0.0, None), ("paper_c.uncertainty.convergence", [], None),
    ("paper_b.pareto.positions", 1, None), ("paper_b.pareto.seed", -3, None),
    ("paper_b.pareto.speed", NAN, None), ("paper_b.pareto.n_gen", 1.5, None),
    ("paper_b.claims.ics_typical_share", [0.1, 1.5], "paper_b.claims.ics_typical_share.1"),
    # the stability boundaries: a span missing its base value, m_bar at the existence bound,
    # m_bar beyond where it is traced (the fuzzer: a corner's next curve not found at ~195),
    # steps out of order, a span upside down
    ("paper_b.boundaries.beta", {"min": 2.0, "max": 10.0}, None),
    ("paper_b.boundaries.m_bar", {"min": 0.006, "max": 0.5}, "paper_b.boundaries.m_bar.min"),
    ("paper_b.boundaries.m_bar", {"min": 0.00601, "max": 1000.0},
     "paper_b.boundaries.m_bar.max"),
    ("paper_b.boundaries.step", {"initial": 0.6, "min": 1e-7, "max": 0.5}, None),
    ("paper_b.boundaries.zeta", {"min": 10.0, "max": 1e-4}, None),
    ("paper_b.boundaries.omega_max", 1.0, None), ("paper_b.boundaries.tol", 0.0, None),
    ("paper_b.ross_check.m_bar", 0.1, None), ("paper_b.ross_check.dt", 0.0, None),
    ("paper_b.ross_check.shaft.E", -1.0, None), ("paper_b.ross_check.speeds.n", 0, None),
    ("paper_b.shards", 0, None), ("paper_b.shards", 2.5, None),
    # the GA optimum's neighbours: no step, past the criterion's t_end, no three bins to fit
    ("paper_b.ga_shards", 0, None), ("paper_b.ga_shards", 2.5, None),
    ("paper_b.design_rule.ics", ["IC9"], None), ("paper_b.design_rule.verify", 0, None),
    ("paper_b.design_rule.machines", {"slow": {"zeta": 0.01, "eps_bar": 0.012, "speed": 50.0}},
     "paper_b.design_rule.machines.slow.speed"),
    ("paper_b.design_rule.machines", {"Bad name": {"zeta": 0.01, "eps_bar": 0.012,
                                                   "speed": 200.0}}, None),
    ("paper_b.design_rule.check.within", 0.0, None), ("paper_b.design_rule.mass", RANGE_DOWN, None),
    ("paper_b.design_rule.mass", {"min": 0.001, "max": 0.02, "n": 5},
     "paper_b.design_rule.mass.min"),
    ("paper_b.design_rule.kinematics", "exact", None),
    ("paper_b.ga_law.step", 0.0, None), ("paper_b.ga_law.horizon", 25.0, None),
    ("paper_b.ga_law.width", 3.0, "paper_b.ga_law.horizon"),
    # paper A
    ("paper_a.case.mu", -0.01, None), ("paper_a.case.rho", NAN, None),
    ("paper_a.tau_step", 200.0, None), ("paper_a.zoom", [0.0, 500.0], None),
    ("paper_a.zoom", [20.0, 0.0], None), ("paper_a.rk.rtol", 1e-16, None),
    ("paper_a.rk.rtol", "1e-9", None), ("paper_a.rk.method", "rk4", None), ("paper_a.error_study.deltas", [0.01, 0.01], None),
    ("paper_a.fig7.beta.n", 1.0e7, None), ("paper_a.fig5_6.betas", [-1.0], "paper_a.fig5_6.betas.0"),
    ("paper_a.slow_flow.omega", RANGE_DOWN, None),
    # found by the fuzzer (tests/schema_fuzz.py): subnormal numbers pass "> 0" and underflow
    # to 0 inside a job
    ("paper_c.mass_ratio_family.mu", [5e-324], "paper_c.mass_ratio_family.mu.0"),
    ("paper_c.table2.k2", 5e-324, None), ("paper_b.balance.sample_dt", 1e-310, None),
    # found by the fuzzer: a Fig 6 claim about a curve the family does not draw
    ("paper_c.mass_ratio_family.mu", [0.2, 0.06, 0.85, 1.0], None),
    ("paper_c.claims.fig6_mu.others", [0.2, 0.5], "paper_c.mass_ratio_family.mu"),
    ("paper_c.distance_study.offsets", [-0.5, 0.0], None),      # through the disk centre
    ("paper_b.ross_check.speeds.min", 0.0, None),                # a rotor at rest
    ("paper_b.balance.integrator.rtol", 1e-14, "paper_b.balance.integrator.rtol"),
    ("paper_a.rk.rtol", 2e-14, None), ("paper_c.time_response.rtol", 1e-14, None),
    ("paper_b.stability_maps.fig3.m_bar.n", 1, None),
    # more run-ups than a job holds (over 4e6 each); sharding does not split them
    ("paper_b.balance_studies.mass", {"where": "Figs 12-14", "axis": "mass",
                                      "fixed": {"beta": 1.0},
                                      "range": {"min": 0.006, "max": 0.02, "n": 100000},
                                      "each": {"eps_bar": [0.006, 0.007, 0.008, 0.009, 0.01,
                                                           0.011, 0.012]}},
     "paper_b.balance_studies.mass.range.n"),
    ("paper_b.table1", {"speeds": [200.0, 205.0, 210.0, 220.0, 230.0, 240.0, 250.0],
                        "beta": 0.2, "eps_bar": 0.012,
                        "mass": {"min": 0.006, "max": 0.02, "n": 100000}},
     "paper_b.table1.mass.n"),
    ("paper_b.basin", {"n": 720, "eps_bar": 0.012, "cases": [[0.2, 0.006], [1.0, 0.006],
                                                              [0.5, 0.008], [1.0, 0.01]]},
     "paper_b.basin.n"),
    # found by a hostile-input audit: magnitudes the library refuses (they failed inside a job
    # naming a library field or a derived quantity), a study name too long for its file names,
    # separators and bidirectional overrides in a text, a 1 MB text
    ("paper_c.rotor.M", 1e308, None), ("paper_c.table2.k2", 1e-300, None),
    ("paper_b.machine.M", 1e308, None), ("paper_b.ross_check.shaft.E", 1e308, None),
    ("paper_b.balance_studies", {"b" * 250: {"where": "x", "axis": "beta",
                                             "range": {"min": 0.1, "max": 1.0, "n": 3},
                                             "fixed": {"mass": 0.01, "eps_bar": 0.012,
                                                       "speed": 200.0}}}, None),
    ("paper_b.balance_studies.beta.where", "Figs\u20288-10", None),
    ("paper_b.balance_studies.beta.where", "Figs \u202e01-8", None),
    ("paper_b.balance_studies.beta.where", "x" * 1_000_000, None),
    # discrepancy analysis
    ("discrepancies.inversion.range", [10.0, 0.1], None),
    ("discrepancies.inversion.n_scan", 1, None),
    ("discrepancies.paper_b", ["bogus"], "discrepancies.paper_b.0"),
    ("discrepancies.paper_c", ["M", "M"], None),
]


def _set(config: dict, dotted: str, value) -> dict:
    out = copy.deepcopy(config)
    node, *parts = [out, *dotted.split(".")]
    for part in parts[:-1]:
        node = node[int(part)] if isinstance(node, list) else node[part]
    node[parts[-1]] = value
    return out


def problems(config: dict) -> str:
    """The messages of the checks run before any job: the schema and its extensions, then
    every check beyond the schema (rotorvib.pipeline.config_checks)."""
    try:
        filled = validate_config(config, SCHEMA)
    except ConfigError as error:
        return str(error)
    return "\n".join(config_checks.problems(filled))


def test_the_paper_configuration_passes():
    assert problems(CONFIG) == ""


def test_the_corpus_is_large_and_covers_every_section():
    assert len(CASES) >= 70
    assert {key.split(".")[1] for key, _, _ in CASES if key.startswith("paper_")} >= set(
        CONFIG["paper_b"]) - {"n", "initial_state"} | set(CONFIG["paper_c"]) - {"n"}


@pytest.mark.parametrize("key, value, named", CASES,
                         ids=[f"{k}={repr(v)[:80]}" for k, v, _ in CASES])
def test_every_malformed_config_is_rejected_naming_its_key(key, value, named):
    message = problems(_set(CONFIG, key, value))
    assert f"'{named or key}'" in message, message


@pytest.mark.parametrize("key, value, expected", [
    ("paper_b.design_rule.machines", {"Bad name": {"zeta": 0.01, "eps_bar": 0.012,
                                                   "speed": 200.0}},
     ("the name 'Bad name' is not allowed; must be a string of 1 to 31 characters matching the "
      "pattern ^[a-z][a-z0-9_]{0,30}$ (a lowercase letter, then lowercase letters, digits or _")),
    ("results", "../elsewhere", ("must be a string of 1 to 200 characters matching the "
                                 "pattern ^[A-Za-z0-9_]")),
    ("paper_b.balance_studies.beta.where", "x" * 1_000_000,
     ("'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx'... (1000000 characters) is not allowed; "
      "must be a string of 1 to 200 characters")),
    ("paper_c.rotor.M", 1e308, ("1e+308 is not allowed; must be 0 or between 1e-100 and "
                                "1e+100 in magnitude")),
    ("paper_b.balance_studies", {"b" * 250: CONFIG["paper_b"]["balance_studies"]["beta"]},
     "must be a string of 1 to 64 characters matching the pattern ^[a-z][a-z0-9_]{0,63}$"),
])
def test_a_refusal_says_what_is_allowed_in_one_line(key, value, expected):
    """A pattern is stated with its words and its length bounds (it read "must be any value"),
    and a long value is shown by its start: one line a reader can act on."""
    message = problems(_set(CONFIG, key, value))
    assert expected in message and len(message.splitlines()) == 2, message
    assert "any value" not in message and len(message) < 600


@pytest.mark.parametrize("text, expected", [
    (DUPLICATE_KEY, ":4:5: duplicate key 'zeta'"),
    ("paper_b:\n  machine:\n\tzeta: 0.01\n", ":3:1: found character '\\t'"),
    ("paper_b: [1, 2\n", ":2:1:"),
    ("- 1\n- 2\n", "must be a mapping of keys, not list"),
    # YAML 1.1 readings refused with their place (octal, sexagesimal, '_', binary, yes/no/on)
    ("paper_b:\n  ga:\n    seed: 0777\n", ":3:11: '0777' reads differently in YAML 1.1"),
    ("paper_b:\n  balance:\n    t_end: 1:30\n", ":3:12: '1:30' reads differently"),
    ("paper_b:\n  ga:\n    seed: 1_000\n", ":3:11: '1_000' reads differently"),
    ("paper_b:\n  ga:\n    seed: 0b101\n", ":3:11: '0b101' reads differently"),
    ("paper_b:\n  progress: yes\n", ":2:13: 'yes' reads differently"),
    ("paper_b:\n  on: 1\n", ":2:3: 'on' reads differently"),
    # keys that are not text, where Snakemake's validator crashed
    ("paper_b:\n  balance_studies:\n    1: {}\n", ":3:5: key 1 is a int, not text"),
    ("paper_b:\n  balance_studies:\n    true: {}\n", ":3:5: key True is a bool, not text"),
    ("paper_b:\n  balance_studies:\n    ~: {}\n", ":3:5: key None is a NoneType, not text"),
    # a template runs Python: refused
    ("__use_yte__: true\npaper_b: {}\n", ":1:1: '__use_yte__' asks for Snakemake's YTE"),
    ("paper_b:\n  __definitions__: [import os]\n", ":2:3: '__definitions__' asks for"),
    # an alias bomb: nine levels of nine aliases (9^9 values), measured without expanding it
    ("a0: &a0 [1, 2, 3, 4, 5, 6, 7, 8, 9]\n" + "".join(
        f"a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * 9)}]\n" for i in range(1, 9)),
     "its aliases expand to more than 1e+05 values; at most 1e+05"),
])
def test_yaml_errors_name_file_line_and_column(tmp_path, text, expected):
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError) as error:
        load_yaml(path)
    assert str(path) in str(error.value) and expected in str(error.value)


def test_yaml_1_2_numbers_and_quoted_text(tmp_path):
    """YAML 1.2 core schema: 0o and 0x integers, floats with and without exponent, .inf,
    true/false, null; quoted text stays text (never read again as a number)."""
    path = tmp_path / "numbers.yaml"
    path.write_text("a: {o: 0o17, x: 0x1F, i: -12, f: 1., e: 1e-9, g: +2.5E3, inf: -.inf}\n"
                    "b: {t: true, f: False, n: null, e: ~, zero: 0, q: '0777', s: '0.01',"
                    " y: y, 'no': 'no'}\n")
    assert load_yaml(path) == {
        "a": {"o": 15, "x": 31, "i": -12, "f": 1.0, "e": 1e-9, "g": 2500.0, "inf": -INF},
        "b": {"t": True, "f": False, "n": None, "e": None, "zero": 0, "q": "0777", "s": "0.01",
              "y": "y", "no": "no"}}


@pytest.mark.parametrize("make, expected", [
    (lambda p: p.write_bytes(b"paper_b:\n  name: \xff\xfe\n"), "not UTF-8 text"),
    (lambda p: p.write_text("x: [" + "1, " * 400_000 + "1]\n"), "bytes; a configuration file "
                                                                   "may have at most 1000000"),
])
def test_files_that_cannot_be_configurations_are_refused_before_parsing(tmp_path, make,
                                                                         expected):
    path = tmp_path / "bad.yaml"
    make(path)
    with pytest.raises(ConfigError, match=expected):
        load_yaml(path)


def test_exponent_notation_is_a_number(tmp_path):
    path = tmp_path / "exp.yaml"
    path.write_text("paper_a:\n  rk: {rtol: 1e-9, atol: -2E+3}\n")
    assert load_yaml(path) == {"paper_a": {"rk": {"rtol": 1e-9, "atol": -2000.0}}}


@pytest.mark.parametrize("text, named", [
    (DUPLICATE_KEY, "duplicate key 'zeta'"),
    ("paper_b:\n  balance:\n    r_threshold: .nan\n", "'paper_b.balance.r_threshold'"),
    ("paper_b:\n  ga:\n    mass: [0.001, 0.02]\n", "'paper_b.ga.mass'"),
    ("paper_b:\n  ga:\n    seed: 0777\n", "'0777' reads differently in YAML 1.1 and 1.2"),
    ("paper_b:\n  balance_studies:\n    yes: {}\n", "'yes' reads differently"),
    ("paper_b:\n  balance_studies:\n    1: {}\n", "key 1 is a int, not text"),
    ("__use_yte__: true\n", "'__use_yte__' asks for Snakemake's YTE templates"),
    # quoted text in a file is text (Snakemake's reading typed it again): one verdict
    ("paper_b:\n  balance:\n    r_threshold: '0.0001'\n",
     "'paper_b.balance.r_threshold': '0.0001' is a string, not a number"),
    # the same tolerance refused in an override file as in config/config.yaml
    ("paper_b:\n  balance:\n    integrator:\n      rtol: 1e-16\n",
     "'paper_b.balance.integrator.rtol'"),
    # runs the engine would refuse inside a job, refused before any job naming the key
    ("paper_b:\n  balance:\n    sample_dt: 1.0e-6\n", "'paper_b.balance.sample_dt': 1e-06 with "
     "t_end = 20.0: 2e+07 samples, at most 1e+07"),
    ("paper_b:\n  table1:\n    speeds: [200.0, 1.0e+6]\n", "'paper_b.table1.speeds': with "
     "paper_b.balance.t_end = 20.0, the run spans 2e+07 radians"),
    ("paper_b:\n  ga:\n    beta: [0.1, 1.0e+5]\n", "'paper_b.ga.beta': with"),
    ("paper_b:\n  pareto:\n    speed: 1.0e+6\n", "'paper_b.pareto.speed': with"),
    ("paper_b:\n  balance_studies:\n    fast:\n      where: x\n      axis: speed\n"
     "      range: {min: 100.0, "
     "max: 1.0e+6, n: 3}\n      fixed: {beta: 0.3, mass: 0.01, eps_bar: 0.012}\n",
     "'paper_b.balance_studies.fast': with"),
])
def test_snakemake_stops_before_any_job(tmp_path, text, named, snakemake_here):
    bad = tmp_path / "bad.yaml"
    bad.write_text(text)
    run = snakemake_here("-n", "--configfile", "config/config.yaml", str(bad))
    assert run.returncode != 0
    assert named in run.stdout + run.stderr
    assert "Job " not in run.stdout


@pytest.mark.parametrize("entries, named", [
    # a duplicate key inside a value: Snakemake kept the last one and the workflow planned
    (["paper_b={machine: {zeta: 0.01, zeta: 0.02}}"],
     "--config paper_b:1:24: duplicate key 'zeta' (first at line 1)"),
    # a key given twice: Snakemake merged the two values
    (["results=out", "results=other"], "--config 'results=other': duplicate key 'results'"),
    (["paper_c={rotor: {M: 0777}}"], "--config paper_c.rotor.M:1:1: '0777' reads differently"),
    (["paper_c={rotor: {M: 1.0e+308}}"], "config key 'paper_c.rotor.M': 1e+308 is not allowed"),
    (["results=out\u2028x"], "config key 'results': the text 'out\\u2028x' is not allowed"),
])
def test_command_line_entries_are_read_from_their_text(entries, named, snakemake_here):
    """``--config`` is read from the entries as typed (Snakemake's ``config_args``), so a
    command gets the verdict ``python -m rotorvib.pipeline.config`` gives, before any job."""
    run = snakemake_here("-n", "--config", *entries)
    assert run.returncode != 0 and named in run.stdout + run.stderr, run.stdout + run.stderr
    assert "Job " not in run.stdout
    assert main(["config/config.yaml", "--config", *entries]) == 1
