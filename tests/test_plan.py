"""The workflow's plan (rotorvib.pipeline.plan) without Snakemake: its paths, the report's entries,
the figure grouping over a rule graph handed to it, and the rules for rule authors."""

from pathlib import Path

import pytest

from rotorvib.papers.outputs import figure
from rotorvib.pipeline.plan import COMPUTES, LONGEST_CHAIN, Maker, Plan, rule_problems

#: A toy rule graph: a quick dataset, a batch study, a dataset computed from the study's, and
#: a rule that takes an input function without being a batch rule.
GRAPH = {
    "out/paper_t/datasets/quick.nc": Maker("t_quick"),
    "out/paper_t/datasets/study.nc": Maker("t_study", inputs=(None,), batch=True),
    "out/paper_t/datasets/law.nc": Maker("t_law", inputs=("out/paper_t/datasets/study.nc",
                                                          "data/values.csv")),
    "out/paper_t/datasets/odd.nc": Maker("t_odd", inputs=(None,)),
    "out/paper_t/tables/t1.csv": Maker("t_tables", script="workflow/scripts/t_tables.py"),
}


def maker(path):
    return GRAPH.get(path)


@pytest.fixture
def plan(config, tmp_path):
    """Paper C's plan under ``out``, its figures replaced by four toy ones of a paper t."""
    plan = Plan({"c": config["paper_c"]}, "out", tmp_path)
    plan.figures = {"t": {
        "f1": figure("f1", {"d": "quick"}, "The quick one."),
        "f2": figure("f2", {"d": "study"}, "The study."),
        "f3": figure("f3", {"d": "law", "e": "quick"}, "The law against Fig 1."),
        "f4": figure("f4", {"d": "quick"}, "The quick one again."),
    }}
    plan.tables["t"] = {"t1": {"shows": "A table.", "items": [],
                               "csv": "out/paper_t/tables/t1.csv"}}
    return plan


def test_figures_are_grouped_by_the_batch_rules_they_wait_for(plan):
    """Figures of datasets made in seconds are one job; a figure that waits for a batch study,
    directly or through a rule that reads its dataset, is drawn with that study's others."""
    groups = plan.figure_groups(maker)
    assert groups == {("t", ()): ["f1", "f4"], ("t", ("t_study",)): ["f2", "f3"]}
    assert plan.figure_rule(groups, "t", "f3") == "figures_t_f2"
    assert plan.figure_datasets("t", ["f3", "f1"]) == ["law", "quick"]
    assert plan.outputs_named("t", "f3") == ["f3", "fig1"]


def test_an_input_function_is_followed_only_to_a_batch_rule(plan):
    plan.figures["t"]["f5"] = figure("f5", {"d": "odd"}, "The odd one.")
    with pytest.raises(ValueError, match="t_odd takes an input function but is no batch rule"):
        plan.figure_groups(maker)


def test_made_by_names_the_rules_script_function_and_datasets(plan):
    groups = plan.figure_groups(maker)
    assert plan.made_by(maker, groups, "t", "t1", "table") == {
        "rule": "t_tables", "script": "workflow/scripts/t_tables.py"}
    assert plan.made_by(maker, groups, "t", "f3", "figure") == {
        "rule": "figures_t_f2", "script": "workflow/scripts/figures.py",
        "function": "rotorvib.papers.t.figures.f3",
        "datasets": {"law": "t_law", "quick": "t_quick"}}


def test_paths_and_shards(plan):
    assert plan.dataset("b", "ga") == "out/paper_b/datasets/ga.nc"
    assert plan.benchmarks("b_ga") == "out/benchmarks/b_ga.tsv"
    assert plan.shards_of("b", "balance_{study}", 1)({"study": "beta"}) == []

    class Wildcards(dict):
        pass

    files = plan.shards_of("b", "balance_{study}", 3)(Wildcards(study="beta"))
    assert files == [f"out/paper_b/shards/balance_beta.{k}-of-3.nc" for k in range(3)]


def test_every_declared_output_is_a_final_file_and_every_shown_one_has_its_caption(config,
                                                                                   tmp_path):
    plan = Plan({"c": config["paper_c"]}, "out", tmp_path)
    figures, tables = plan.figures["c"], plan.tables["c"]
    final = set(plan.all_results())
    assert {plan.figure_file("c", name) for name in figures} <= final
    assert {plan.table("c", name, "md") for name in tables} <= final
    assert plan.reproduced_file("c") in final
    entries = plan.report_entries()
    assert len(entries) == 1 + len(figures) + len(tables)
    for source, arguments in entries.values():
        if "caption" in arguments:
            caption = Path(arguments["caption"])
            assert caption.is_absolute() and caption.is_relative_to(tmp_path), caption
            assert str(caption.relative_to(tmp_path)) in plan.report_text_files()
    assert len(plan.figure_companions()) == 2 * len(figures)


GOOD = [
    Maker("compute", outputs=("d.nc",), benchmark=True, priority=COMPUTES),
    Maker("chain", outputs=("r.csv",), priority=LONGEST_CHAIN),
    Maker("figure", inputs=("d.nc",), outputs=("f.png",)),
    Maker("study", inputs=(None,), outputs=("s.nc",), batch=True, benchmark=True,
          priority=LONGEST_CHAIN),
    Maker("study_shard", outputs=("s.0-of-2.nc",), batch=True, local=False, benchmark=True,
          priority=LONGEST_CHAIN),
]


@pytest.mark.parametrize("broken, problem", [
    (Maker("x", outputs=("d.nc",), priority=LONGEST_CHAIN), "writes a dataset but no benchmark"),
    (Maker("x", benchmark=True), "has a benchmark: but no priority"),
    (Maker("x", priority=COMPUTES), "but has a priority other than LONGEST_CHAIN"),
    (Maker("x", inputs=(None,)), "takes an input function but is no batch rule"),
    (Maker("x", local=False), "is a cluster job but no batch rule"),
])
def test_each_rule_for_rule_authors_is_enforced(broken, problem):
    assert rule_problems(GOOD) == []
    found = rule_problems([*GOOD, broken])
    assert len(found) == 1 and problem in found[0] and found[0].startswith("rule x ")
