# Helpers shared by all rules: configuration validation (before any job), code fingerprints,
# and the lists of final results.
from snakemake.exceptions import WorkflowError

from rotorvib.config import ConfigError, load_yaml, validate_config
from rotorvib.provenance import source_fingerprint

try:
    config.update(validate_config(config, load_yaml("config/schema.yaml")))
except ConfigError as error:
    raise WorkflowError(str(error)) from None

PAPER_VALUES = "data/paper_values.csv"
C = config["paper_c"]
C_DATA = "results/paper_c/datasets"
C_FIG = "results/paper_c/figures"
C_TAB = "results/paper_c/tables"

# Library modules each kind of job runs; their source hash is a rule parameter, so editing
# them reruns exactly those jobs.
CODE = {
    "io": ("rotorvib.datasets", "rotorvib.provenance", "rotorvib.config"),
    "c_model": (
        "rotorvib.dva.parameters",
        "rotorvib.dva.frequency_response",
        "rotorvib.dva.time_response",
        "rotorvib.dva.tuning",
        "rotorvib.dva.studies",
        "rotorvib.integrate",
    ),
    "c_ga": ("rotorvib.ga", "rotorvib.dva.optimise"),
    "c_derivation": ("rotorvib.derivation", "rotorvib.dva.derivation"),
    "c_figures": ("rotorvib.plotting", "rotorvib.dva.figures"),
    "c_claims": ("rotorvib.comparison", "rotorvib.dva.claims"),
    "b_derivation": ("rotorvib.derivation", "rotorvib.abb.derivation"),
    "comparison": ("rotorvib.comparison",),
    "archive": ("rotorvib.archive",),
}


def code(*kinds):
    """Fingerprint of the library source used by a job of the given kinds."""
    return source_fingerprint(*(module for kind in kinds for module in CODE[kind]))


C_FIGURES = ["fig3", "fig4", "fig5", "fig6", "fig7", "ga_convergence", "linearisation"]


def paper_c_results():
    return (
        expand(f"{C_FIG}/{{fig}}.png", fig=C_FIGURES)
        + expand(
            f"{C_TAB}/{{table}}.{{ext}}",
            table=["derivation_checks", "table2"],
            ext=["csv", "md"],
        )
        + [
            f"{C_DATA}/{name}.nc"
            for name in ("ga", "frequency_response", "mass_ratio", "time_response")
        ]
    )


def paper_b_results():
    return expand("results/paper_b/tables/derivation_checks.{ext}", ext=["csv", "md"])


def all_results():
    return (
        paper_c_results()
        + paper_b_results()
        + ["results/comparison.csv", "results/comparison.md"]
    )
