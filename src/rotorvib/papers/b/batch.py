"""Paper B's batch studies, as functions of the configuration's ``paper_b`` section: the
studies whose runs one job shares out over threads (:mod:`rotorvib.papers.b.studies`) and a
cluster run splits into shards (``paper_b.shards``, :mod:`rotorvib.pipeline.shards`).

Each study is named by its rule (its script is ``workflow/scripts/<rule>.py``) and gives its
dataset (with its wildcards' patterns), its message, its job's parameters, the datasets it reads,
its wall-time bound in minutes (``runtime``), whether it starts first (beside the engine's
compile: the genetic algorithm) and the least number of shards it is split into.
``workflow/rules/paper_b.smk`` writes two rules of each: the study and its shards.
"""

from __future__ import annotations

from rotorvib.papers.b.outputs import setup


def runs(b: dict) -> dict:
    """The parameters every run-up study of paper B shares: the setup, the kinematics and the
    initial conditions."""
    return {"setup": setup(b), "kinematics": b["kinematics"], "ics": b["initial_conditions"]}


def study(dataset: str, message: str, params: dict, *, reads=(), wildcards=None, runtime=30,
          first=False, shards=1, paper_values=False) -> dict:
    """One batch study: its dataset ``dataset``, the datasets of paper B it ``reads``, and
    whether it reads the papers' values."""
    return {"dataset": dataset, "message": message, "params": params, "reads": tuple(reads),
            "paper_values": paper_values, "wildcards": wildcards or {}, "runtime": runtime,
            "first": first, "shards": shards}


def batch_studies(b: dict, uncertain: dict[str, dict]) -> dict[str, dict]:
    """Paper B's batch studies by rule, for the cases of its uncertainty study ``uncertain``
    (:func:`rotorvib.papers.b.outputs.uncertain_cases`)."""
    shared = runs(b)
    return {
        "b_balance_study": study(
            "balance_{study}", "Paper B: balance time against {wildcards.study}",
            {**shared, "study": lambda wc: b["balance_studies"][wc.study]},
            wildcards={"study": "|".join(b["balance_studies"])}),
        "b_ga": study(
            "ga", "Paper B: genetic algorithm over ball damping and mass",
            {**shared, "ga": b["ga"]}, runtime=60, first=True, shards=b["ga_shards"]),
        "b_table1_runs": study(
            "table1", "Paper B: balance time over ball mass and operating speed (Table 1)",
            {**shared, "table1": b["table1"]}),
        "b_forces": study(
            "forces", "Paper B: bearing forces of Table 2 against the race radius",
            {**shared, "table2": b["table2"], "calibration": b["calibration"]}),
        "b_uncertainty": study(
            "uncertainty_{case}",
            "Paper B (beyond the paper): Sobol indices and bands of the case {wildcards.case}",
            {"setup": shared["setup"], "kinematics": b["kinematics"][0],
             # the case of Table 1 (a mean over the ICs) has its own, smaller sample
             "uncertainty": lambda wc: b["uncertainty"] | (
                 b["uncertainty"]["mean_over_ics"] if "ics" in uncertain[wc.case] else {}),
             "case": lambda wc: uncertain[wc.case]},
            reads=("forces",), paper_values=True, wildcards={"case": "|".join(uncertain)}),
        "b_basin": study(
            "basin", "Paper B: balance time over all initial ball positions",
            {"setup": shared["setup"], "kinematics": b["kinematics"], "basin": b["basin"],
             "ics": b["initial_conditions"]}, runtime=60),
    }
