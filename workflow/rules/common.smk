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
A = config["paper_a"]
A_DATA = "results/paper_a/datasets"
A_FIG = "results/paper_a/figures"
B = config["paper_b"]
B_DATA = "results/paper_b/datasets"
B_FIG = "results/paper_b/figures"
B_TAB = "results/paper_b/tables"
B_SETUP = {key: B[key] for key in ("machine", "initial_state", "speed", "balance")}

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
    "b_model": (
        "rotorvib.abb.engine",
        "rotorvib.abb.parameters",
        "rotorvib.abb.simulate",
        "rotorvib.abb.stability",
        "rotorvib.abb.optimise",
        "rotorvib.abb.studies",
        "rotorvib.ga",
    ),
    "b_figures": ("rotorvib.plotting", "rotorvib.abb.figures"),
    "a_model": (
        "rotorvib.abb.engine",
        "rotorvib.abb.parameters",
        "rotorvib.abb.simulate",
        "rotorvib.abb.stability",
        "rotorvib.abb.expansion",
        "rotorvib.abb.mms_studies",
        "rotorvib.multiple_scales",
    ),
    "a_figures": ("rotorvib.plotting", "rotorvib.abb.mms_figures"),
    "a_claims": ("rotorvib.comparison", "rotorvib.abb.mms_claims"),
    "b_claims": ("rotorvib.comparison", "rotorvib.tables", "rotorvib.abb.claims"),
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


# Paper B figures: drawing function (rotorvib.abb.figures), datasets, options, caption.
B_FIGURES = {
    "fig2": ("stability_map", {"st": "stability_fig2"}, {}),
    "fig3": ("stability_map", {"st": "stability_fig3"}, {}),
    "fig4_5": ("speed_profile", {"tr": "time_responses"}, {}),
    "fig6": ("unbalanced_response", {"tr": "time_responses"}, {}),
    "fig7": ("envelope_response", {"tr": "time_responses"}, {}),
    "fig8": ("balance_against", {"grid": "balance_beta"}, {"eps_index": 0}),
    "fig9": ("balance_against", {"grid": "balance_beta"}, {"eps_index": 1}),
    "fig10": ("balance_against", {"grid": "balance_beta"}, {"eps_index": 2}),
    "fig11": ("responses", {"tr": "time_responses"}, {"prefix": "fig11"}),
    "fig12": ("balance_against", {"grid": "balance_mass"}, {"eps_index": 0}),
    "fig13": ("balance_against", {"grid": "balance_mass"}, {"eps_index": 1}),
    "fig14": ("balance_against", {"grid": "balance_mass"}, {"eps_index": 2}),
    "fig15": ("responses", {"tr": "time_responses"}, {"prefix": "fig15"}),
    "fig16": ("bearing_forces", {"tr": "time_responses"}, {}),
    "ga_convergence": ("ga_convergence", {"ga": "ga"}, {}),
    "calibration_R": ("calibration", {"forces": "forces"}, {"R": B["machine"]["R"]}),
    "basin": ("basin", {"basin": "basin"}, {"ics": B["initial_conditions"]}),
    "kinematics": (
        "kinematics_shift",
        {"beta": "balance_beta", "mass": "balance_mass"},
        {},
    ),
}
B_DATASETS = [
    "stability_fig2",
    "stability_fig3",
    "time_responses",
    "balance_beta",
    "balance_mass",
    "ga",
    "table1",
    "forces",
    "basin",
]


def paper_b_results():
    return (
        expand(f"{B_FIG}/{{fig}}.png", fig=list(B_FIGURES))
        + expand(f"{B_DATA}/{{name}}.nc", name=B_DATASETS)
        + expand(
            f"{B_TAB}/{{table}}.{{ext}}",
            table=["derivation_checks", "table1", "table2"],
            ext=["csv", "md"],
        )
        + [f"{B_TAB}/kinematics.md", "results/paper_b/reproduced.csv"]
    )


# Paper A figures: drawing function (rotorvib.abb.mms_figures), datasets, options.
A_FIGURES = {
    "fig2": (
        "fig2",
        {"resp": "responses"},
        {"zoom": A["zoom"], "beta": A["case"]["beta"]},
    ),
    "fig3": (
        "fig3",
        {"resp": "responses"},
        {"zoom": A["zoom"], "beta": A["case"]["beta"]},
    ),
    "fig4": ("fig4", {"resp": "responses"}, {"beta": A["case"]["beta"]}),
    "fig5": ("fig5", {"resp": "responses"}, {"betas": A["fig5_6"]["betas"]}),
    "fig6": ("fig6", {"resp": "responses"}, {"betas": A["fig5_6"]["betas"]}),
    "fig7": ("fig7", {"region": "stability_region"}, {}),
    "error_study": ("error_study", {"err": "error_study"}, {}),
    "slow_flow": ("slow_flow", {"flow": "slow_flow"}, {}),
}


def paper_a_results():
    return (
        expand(f"{A_FIG}/{{fig}}.png", fig=list(A_FIGURES))
        + expand(
            f"{A_DATA}/{{name}}.nc",
            name=["responses", "stability_region", "error_study", "slow_flow"],
        )
        + ["results/paper_a/reproduced.csv"]
    )


def all_results():
    return (
        paper_a_results()
        + paper_c_results()
        + paper_b_results()
        + ["results/comparison.csv", "results/comparison.md"]
    )
