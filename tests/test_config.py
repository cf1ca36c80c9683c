import copy

import pytest
import yaml

from conftest import ROOT
from rotorvib.io.provenance import config_hash
from rotorvib.pipeline import strict_yaml
from rotorvib.pipeline.config import ConfigError, main, merge, validate_config


def _broken(config, mutate):
    bad = copy.deepcopy(config)
    mutate(bad)
    return bad


def test_repository_config_is_valid_and_defaults_are_filled(config, schema):
    raw = copy.deepcopy(config)
    del raw["paper_c"]["ga"]["sbx_eta"]
    filled = validate_config(raw, schema)
    assert filled["paper_c"]["ga"]["sbx_eta"] == schema["properties"]["paper_c"]["properties"][
        "ga"]["properties"]["sbx_eta"]["default"]


@pytest.mark.parametrize("mutate, expected", [
    (lambda c: c["paper_c"]["rotor"].update(M=-1.0),
     ["'paper_c.rotor.M'", "-1.0", "> 0", "disk mass, kg"]),
    (lambda c: c["paper_c"]["ga"].update(pop_size="many"),
     ["'paper_c.ga.pop_size'", "'many'", "an integer", ">= 4"]),
    (lambda c: c["paper_c"]["ga"].update(pop_size=2.5), ["'paper_c.ga.pop_size'", "an integer"]),
    (lambda c: c["paper_c"]["rotor"].update(mass=5.0),
     ["'paper_c.rotor'", "unknown key(s) 'mass'", "allowed keys: Gamma0, J_factor, M, R, k_t"]),
    (lambda c: c["paper_c"]["rotor"].pop("k_t"), ["'paper_c.rotor.k_t' is missing", "N m/rad"]),
    (lambda c: c["paper_c"]["bounds"].update(m=[0.5, 0.05]),
     ["'paper_c.bounds.m'", "lower < upper"]),
    (lambda c: c["paper_c"]["bounds"].update(m=[0.5]), ["'paper_c.bounds.m'", "a list of 2 items"]),
    (lambda c: c["paper_c"]["frequency_response"].update(w_min=1.5),
     ["'paper_c.frequency_response.w_min'", "smaller than 'w_max'"]),
    (lambda c: c["paper_c"]["time_response"].update(t_end=1.0),
     ["'paper_c.claims.fig3_time'", "<= 'paper_c.time_response.t_end'"]),
    (lambda c: c.update(results="results\n"),
     ["'results': the text 'results\\n' is not allowed", "without control characters"]),
    (lambda c: c["paper_b"]["balance_studies"]["beta"].update(where="Figs 8-10\x1b[2J"),
     ["'paper_b.balance_studies.beta.where'", "control characters"]),
    (lambda c: c["paper_b"]["balance_studies"].update({"beta ": {}}),
     ["'paper_b.balance_studies': the key 'beta ' is not allowed"]),
])
def test_malformed_config_names_key_and_allowed_values(config, schema, mutate, expected):
    with pytest.raises(ConfigError) as err:
        validate_config(_broken(config, mutate), schema)
    for fragment in expected:
        assert fragment in str(err.value)


def test_config_hash_is_canonical():
    assert config_hash({"a": 1, "b": [1, 2]}) == config_hash({"b": [1, 2], "a": 1})
    assert config_hash({"a": 1}) != config_hash({"a": 1.5})


@pytest.mark.parametrize("mutate, expected", [
    (lambda c: c["paper_b"]["balance_studies"]["beta"]["range"].update(min=2.0),
     "'paper_b.balance_studies.beta.range': min 2.0 must be below max 1.0"),
    (lambda c: c["paper_b"]["ga"].update(mass=[0.02, 0.006]),
     "'paper_b.ga.mass': interval [0.02, 0.006] must have lower < upper"),
    (lambda c: c["paper_b"]["kinematics"].append("exact"),
     "'paper_b.kinematics.2': 'exact' is not allowed; must be a string one of 'printed', "
     "'consistent'"),
    (lambda c: c["paper_b"]["table2"].update(ic="IC4"), "'paper_b.table2.ic'"),
    (lambda c: c["paper_b"]["machine"].update(n=3), "'paper_b.machine.n': 3 is not allowed"),
])
def test_paper_b_config_errors(config, schema, mutate, expected):
    with pytest.raises(ConfigError) as err:
        validate_config(_broken(config, mutate), schema)
    assert expected in str(err.value)


def test_merge_overrides_at_every_depth_like_snakemake():
    base = {"a": {"b": 1, "c": [1, 2]}, "d": 0}
    assert merge(base, {"a": {"c": [3]}}) == {"a": {"b": 1, "c": [3]}, "d": 0}
    assert base == {"a": {"b": 1, "c": [1, 2]}, "d": 0}          # not modified


def test_config_check_command_gives_file_line_and_column(tmp_path, capsys):
    """Snakemake's own message for a broken --configfile has no place; the check command has."""
    tab = tmp_path / "tab.yaml"
    tab.write_text("paper_c:\n\trotor:\n    M: 5\n")
    assert main(["--schema", str(ROOT / "config/schema.yaml"), str(ROOT / "config/config.yaml"),
                 str(tab)]) == 1
    assert f"{tab}:2:1: found character '\\t'" in capsys.readouterr().out
    override = tmp_path / "override.yaml"
    override.write_text("paper_c:\n  rotor:\n    M: -5.0\n")
    assert main(["--schema", str(ROOT / "config/schema.yaml"), str(ROOT / "config/config.yaml"),
                 str(override)]) == 1
    assert "config key 'paper_c.rotor.M': -5.0 is not allowed" in capsys.readouterr().out
    assert main(["--schema", str(ROOT / "config/schema.yaml"), str(ROOT / "config/config.yaml"),
                 str(ROOT / "config/test/config.yaml")]) == 0


@pytest.mark.parametrize("name", sorted(str(p.relative_to(ROOT)) for folder in
                                         ("config", "data", "workflow")
                                         for p in (ROOT / folder).glob("**/*.y*ml")))
def test_libyaml_parser_reads_every_yaml_file_as_pyyaml_does(name):
    """The fast loader (libyaml's parser) and PyYAML's own give the same data, value and type
    (``1e-9`` a float in both)."""
    text = strict_yaml.read_text(ROOT / name)
    fast, own = (strict_yaml._load(strict_yaml._named(text, name), loader) for loader in
                 (strict_yaml.FastStrictLoader, strict_yaml.StrictLoader))
    assert repr(fast) == repr(own)
    assert issubclass(strict_yaml.FastStrictLoader, yaml.CSafeLoader)


def test_both_parsers_refuse_a_duplicate_key_at_its_place(tmp_path):
    twice = tmp_path / "twice.yaml"
    twice.write_text("paper_b:\n  machine:\n    zeta: 0.01\n    zeta: 1e-2\n")
    for loader in (strict_yaml.FastStrictLoader, strict_yaml.StrictLoader):
        with pytest.raises(ConfigError,
                           match=r"twice.yaml:4:5: duplicate key 'zeta' \(first at line 3\)"):
            strict_yaml._load(strict_yaml._named(twice.read_text(), str(twice)), loader)


def test_nested_command_line_overrides_are_read_as_yaml():
    """Snakemake leaves the values inside `--config paper_c='{den_hartog: {d: 0.09}}'` as
    text; they are typed as a configuration file would type them."""
    from rotorvib.pipeline.config_sources import typed_overrides

    given = {"paper_c": {"den_hartog": {"d": "0.09"}, "ga": {"seed": "7", "tol": "1e-9"}},
             "paper_b": {"kinematics": ["printed", "consistent"]}, "top": 3}
    assert typed_overrides(given) == {
        "paper_c": {"den_hartog": {"d": 0.09}, "ga": {"seed": 7, "tol": 1e-9}},
        "paper_b": {"kinematics": ["printed", "consistent"]}, "top": 3}
    assert typed_overrides({"a": {"b": "[unclosed"}}) == {"a": {"b": "[unclosed"}}


def test_every_shipped_configuration_reads_the_same_under_yaml_1_1():
    """A workflow deployed by snakedeploy reads its copy of config/config.yaml with
    Snakemake's loader (YAML 1.1, which reads 1.0e3 as text: it wants 1.0e+3); every shipped
    configuration file gives the same values there as under this package's YAML 1.2 reading."""
    import yaml

    from rotorvib.pipeline.strict_yaml import load_yaml as strict

    for path in sorted((ROOT / "config").rglob("*.yaml")):
        assert yaml.safe_load(path.read_text()) == strict(path), path
