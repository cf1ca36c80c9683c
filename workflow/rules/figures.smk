# Every figure of every paper, driven by the FIGURES declarations of the papers' .smk files. The
# figures of a paper whose datasets come from the same rules are drawn by one job, in one
# process (its start-up, about half a second, is paid once): a change to those rules'
# configuration reruns their jobs and redraws all of them in any case (but a value of one
# wildcard alone, such as one balance study's range, redraws its group's other figures too),
# and a figure alone is still built or redrawn by naming its file. A figure reads datasets only
# (and the papers' values); nothing is recomputed here.

# A figure job is named for the first figure it draws (figures_b_fig8 draws Figs 8-10 and 12-14
# and the other figures of the balance studies).
for (_paper, _makers), _names in figure_groups().items():
    _rule = figure_rule(_paper, _names[0])
    _datasets = figure_datasets(_paper, _names)

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
                | {"keep": outputs_named(_paper, name)}
                for name in _names
            },
        message:
            f"Paper {_paper.upper()}: drawing {', '.join(_names)} from {', '.join(_datasets)}"
        script:
            "../scripts/figures.py"
