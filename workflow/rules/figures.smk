# Every figure of every paper, as the papers' packages declare them (FIGURES). The figures of a
# paper that wait for the same batch rules (resources: batch=1) are drawn by one job, in one
# process: its start-up, about half a second, is paid once (Plan.figure_groups). So
# each paper's figures of datasets made in seconds, which wait for no batch study, are one job;
# a figure of a batch study is drawn as soon as that study ends, beside the others. A change to
# one of the quick studies redraws its paper's other quick figures too (a few seconds), and
# naming a figure's file builds the figures of its job and the datasets they read.
# A figure reads datasets only (and the papers' values); nothing is recomputed here.

# A figure job is named for the first figure it draws (figures_b_fig8 draws Figs 8-10 and 12-14
# and the other figures of the balance studies).
FIGURE_GROUPS = PLAN.figure_groups(rule_making)

for (_paper, _studies), _names in FIGURE_GROUPS.items():
    _rule = PLAN.figure_rule(FIGURE_GROUPS, _paper, _names[0])
    _datasets = PLAN.figure_datasets(_paper, _names)

    rule:
        name:
            _rule
        input:
            **{name: dataset(_paper, name) for name in _datasets},
            paper_values=PAPER_VALUES,
        output:
            **{
                f"{name}{suffix}": figure_file(_paper, name, ext)
                for name in _names
                for suffix, ext in (("", "png"), ("_svg", "svg"), ("_drawn", "json"))
            },
        log:
            logs(_rule),
        # Reads datasets only: runs where Snakemake runs, never as a cluster job.
        localrule: True
        params:
            paper=_paper,
            module=f"rotorvib.papers.{_paper}.figures",
            figures={
                name: {
                    key: FIGURES[_paper][name][key]
                    for key in ("function", "datasets", "options")
                }
                | {"keep": PLAN.outputs_named(_paper, name)}
                for name in _names
            },
        message:
            f"Paper {_paper.upper()}: drawing {', '.join(_names)} from {', '.join(_datasets)}"
        script:
            "../scripts/figures.py"
