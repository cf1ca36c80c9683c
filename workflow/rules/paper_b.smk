# Paper B: damping ratio and ball mass of a two-ball automatic balancer with a run-up. Its
# figures, tables and the cases its jobs take are declared in rotorvib.papers.b.outputs.
from rotorvib.comparison.paper_values import paper_values_of
from rotorvib.papers.b import batch as paper_b_batch
from rotorvib.papers.b import outputs as paper_b
from rotorvib.papers.b.config_checks import boundary_base

B = config["paper_b"]
B_SETUP = paper_b.setup(B)
B_UNCERTAIN = paper_b.uncertain_cases(B, paper_values_of(PAPER_VALUES, "B"))
B_RUNS = paper_b_batch.runs(B)
B_LAW_SOURCES = {
    name: (dataset("b", name_of_dataset), fixed)
    for name, (name_of_dataset, fixed) in paper_b.law_sources(B).items()
}


rule b_datasets:
    input:
        [f for f in RESULTS["b"] if f.endswith(".nc")],
    localrule: True
    message:
        "Paper B: every dataset"


rule b_derivation_checks:
    output:
        csv=table("b", "derivation_checks", "csv"),
        md=table("b", "derivation_checks", "md"),
    log:
        logs("b_derivation_checks"),
    benchmark:
        benchmarks("b_derivation_checks")
    priority: BESIDE_THE_COMPILE
    localrule: True
    params:
        module="rotorvib.papers.b.derivation",
    message:
        "Paper B: checking the printed equations symbolically"
    script:
        "../scripts/derivation_checks.py"


rule b_stability:
    output:
        dataset("b", "stability_{fig}"),
    log:
        logs("b_stability_{fig}"),
    benchmark:
        benchmarks("b_stability_{fig}")
    wildcard_constraints:
        fig="|".join(B["stability_maps"]),
    priority: LONGEST_CHAIN
    localrule: True
    params:
        zeta=B["machine"]["zeta"],
        n=B["machine"]["n"],
        marginal=B["marginal_growth"],
        map=lambda wc: B["stability_maps"][wc.fig],
    message:
        "Paper B: stability map of {wildcards.fig}"
    script:
        "../scripts/b_stability.py"


rule b_boundary:
    output:
        dataset("b", "boundary_{plane}"),
    log:
        logs("b_boundary_{plane}"),
    benchmark:
        benchmarks("b_boundary_{plane}")
    wildcard_constraints:
        plane="|".join(paper_b.PLANES),
    priority: LONGEST_CHAIN
    # small eigenvalue problems along a curve: runs where Snakemake runs
    localrule: True
    params:
        base=boundary_base(B),
        span=lambda wc: B["boundaries"][wc.plane],
        trace={
            k: B["boundaries"][k]
            for k in ("omega_max", "window_samples", "step", "tol")
        },
        n=B["machine"]["n"],
        neutral=B["marginal_growth"],
    message:
        "Paper B (beyond the paper): the stability boundary in ({wildcards.plane}, omega_bar)"
    script:
        "../scripts/b_boundary.py"


rule b_ross:
    output:
        dataset("b", "ross_check"),
    log:
        logs("b_ross"),
    benchmark:
        benchmarks("b_ross")
    priority: COMPUTES
    localrule: True
    params:
        setup=B_SETUP,
        eps_bar=B["table2"]["eps_bar"],
        check=B["ross_check"],
    message:
        "Paper B (beyond the paper): the rotor without balls by the engine and by ROSS"
    script:
        "../scripts/b_ross.py"


# Paper B's batch studies, by rule (rotorvib.papers.b.batch: its script is
# workflow/scripts/<rule>.py).
B_BATCH = paper_b_batch.batch_studies(B, B_UNCERTAIN)


# Each batch study is two rules: its shards (`<rule>_shard`, shard k of n, sent to a cluster),
# and the study itself, which runs it whole in one job (paper_b.shards = 1) or gathers its
# shards byte-identical (rotorvib.pipeline.shards) where Snakemake runs.
for _rule, _study in B_BATCH.items():
    for _sharded in (True, False):

        rule:
            name:
                f"{_rule}_shard" if _sharded else _rule
            input:
                **{name: dataset("b", name) for name in _study["reads"]},
                **({"paper_values": PAPER_VALUES} if _study["paper_values"] else {}),
                **(
                    {}
                    if _sharded
                    else {
                        "shards": shards_of(
                            "b", _study["dataset"], max(B["shards"], _study["shards"])
                        )
                    }
                ),
            output:
                (shard_file if _sharded else dataset)("b", _study["dataset"]),
            log:
                logs(
                    f"b_{_study['dataset']}"
                    + (".{shard}-of-{shards}" if _sharded else "")
                ),
            benchmark:
                benchmarks(
                    f"b_{_study['dataset']}"
                    + (".{shard}-of-{shards}" if _sharded else "")
                )
            wildcard_constraints:
                **_study["wildcards"],
            priority: BESIDE_THE_COMPILE if _study["first"] else LONGEST_CHAIN
            localrule: not _sharded
            threads: BATCH_THREADS
            resources:
                batch=1,
                runtime=_study["runtime"],
            params:
                **_study["params"],
                # the script's name: a rule's script is read when its job runs, after the
                # loop, so it is named through the rule's parameters, not a loop variable
                script=_rule,
            message:
                _study["message"]
            script:
                "../scripts/{params.script}.py"


rule b_time_responses:
    output:
        dataset("b", "time_responses"),
    log:
        logs("b_time_responses"),
    benchmark:
        benchmarks("b_time_responses")
    priority: LONGEST_CHAIN
    localrule: True
    params:
        **B_RUNS,
        responses=B["time_responses"],
        table2=B["table2"],
    message:
        "Paper B: time responses of Figs 4-7, 11, 15 and 16"
    script:
        "../scripts/b_time_responses.py"


rule b_pareto:
    output:
        dataset("b", "pareto_{kinematics}"),
    log:
        logs("b_pareto_{kinematics}"),
    benchmark:
        benchmarks("b_pareto_{kinematics}")
    wildcard_constraints:
        kinematics="|".join(B["kinematics"]),
    priority: LONGEST_CHAIN
    # one search each, it cannot be split: a cluster job when the batch studies are (common.smk)
    localrule: B["shards"] == 1
    threads: BATCH_THREADS
    resources:
        batch=1,
        runtime=30,
    params:
        setup=B_SETUP,
        kinematics=lambda wc: wc.kinematics,
        pareto=B["pareto"],
        bounds={key: B["ga"][key] for key in ("beta", "mass", "censored_penalty")},
        table2=B["table2"]["cases"],
    message:
        "Paper B (beyond the paper): NSGA-II front of balance time against bearing force"
    script:
        "../scripts/b_pareto.py"


rule b_balance_law:
    input:
        **{name: path for name, (path, _) in B_LAW_SOURCES.items()},
    output:
        dataset("b", "balance_law"),
    log:
        logs("b_balance_law"),
    benchmark:
        benchmarks("b_balance_law")
    priority: LONGEST_CHAIN
    # Reads datasets and solves small eigenvalue problems: runs where Snakemake runs.
    localrule: True
    params:
        setup=B_SETUP,
        neutral=B["marginal_growth"],
        shares=[
            B["balance_law"]["whirl_share"],
            *B["balance_law"]["whirl_share_alternatives"],
        ],
        # each source's parameters that its dataset does not vary
        fixed={name: fixed for name, (_, fixed) in B_LAW_SOURCES.items()},
        ics=B["initial_conditions"],
    message:
        "Paper B (beyond the paper): the balance-time law against every balanced run"
    script:
        "../scripts/b_balance_law.py"


rule b_design_rule:
    output:
        dataset("b", "design_rule"),
    log:
        logs("b_design_rule"),
    benchmark:
        benchmarks("b_design_rule")
    priority: LONGEST_CHAIN
    # A grid of passages and eigenvalues, then a few hundred run-ups on threads (the verified
    # candidates and the check grid): seconds, where Snakemake runs.
    localrule: True
    params:
        setup=B_SETUP,
        rule=B["design_rule"],
        ics=B["initial_conditions"],
        neutral=B["marginal_growth"],
        share=B["balance_law"]["whirl_share"],
    message:
        "Paper B (beyond the paper): a design rule predicted without integrating, verified by integrating"
    script:
        "../scripts/b_design_rule.py"


rule b_ga_law:
    input:
        ga=rules.b_ga.output[0],
    output:
        dataset("b", "ga_law"),
    log:
        logs("b_ga_law"),
    benchmark:
        benchmarks("b_ga_law")
    priority: LONGEST_CHAIN
    localrule: True
    params:
        setup=B_SETUP,
        ics=B["initial_conditions"],
        box={"beta": B["ga"]["beta"], "mass": B["ga"]["mass"]},
        law=B["ga_law"],
        neutral=B["marginal_growth"],
    message:
        "Paper B (beyond the paper): the whirl around the GA's optima and its decay"
    script:
        "../scripts/b_ga_law.py"


rule b_zeta_inversion:
    input:
        paper_values=PAPER_VALUES,
    output:
        dataset("b", "zeta_inversion"),
    log:
        logs("b_zeta_inversion"),
    benchmark:
        benchmarks("b_zeta_inversion")
    priority: LONGEST_CHAIN
    # about two thousand run-ups: seconds, where Snakemake runs
    localrule: True
    threads: BATCH_THREADS
    resources:
        batch=1,
    params:
        **B_RUNS,
        zeta_inversion=B["zeta_inversion"],
        cases={
            key: B[key]
            for key in (
                "machine",
                "speed",
                "initial_conditions",
                "time_responses",
                "table1",
                "table2",
            )
        },
    message:
        "Paper B (beyond the paper): the printed times over the support damping zeta"
    script:
        "../scripts/b_zeta_inversion.py"


rule b_tables:
    input:
        table1=rules.b_table1_runs.output[0],
        forces=rules.b_forces.output[0],
        beta=dataset("b", "balance_beta"),
        mass=dataset("b", "balance_mass"),
        ga=rules.b_ga.output[0],
        paper_values=PAPER_VALUES,
    output:
        table1=table("b", "table1", "csv"),
        table1_md=table("b", "table1", "md"),
        table2=table("b", "table2", "csv"),
        table2_md=table("b", "table2", "md"),
        kinematics=table("b", "kinematics", "md"),
    log:
        logs("b_tables"),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    params:
        R=B["machine"]["R"],
    message:
        "Paper B: Tables 1 and 2 and the kinematics note"
    script:
        "../scripts/b_tables.py"


rule b_reproduced_values:
    input:
        **{
            f"uncertainty_{case}": dataset("b", f"uncertainty_{case}")
            for case in B_UNCERTAIN
        },
        **{f"pareto_{kin}": dataset("b", f"pareto_{kin}") for kin in B["kinematics"]},
        **{
            f"boundary_{plane}": dataset("b", f"boundary_{plane}")
            for plane in paper_b.PLANES
        },
        st2=dataset("b", "stability_fig2"),
        st3=dataset("b", "stability_fig3"),
        tr=rules.b_time_responses.output[0],
        beta=dataset("b", "balance_beta"),
        mass=dataset("b", "balance_mass"),
        ga=rules.b_ga.output[0],
        table1=rules.b_table1_runs.output[0],
        forces=rules.b_forces.output[0],
        basin=rules.b_basin.output[0],
        law=rules.b_balance_law.output[0],
        design_rule=rules.b_design_rule.output[0],
        ga_law=rules.b_ga_law.output[0],
        zeta_inversion=rules.b_zeta_inversion.output[0],
        paper_values=PAPER_VALUES,
    output:
        reproduced_file("b"),
    log:
        logs("b_reproduced_values"),
    priority: LONGEST_CHAIN
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    params:
        R=B["machine"]["R"],
        ga=B["ga"],
        beta_band=B["claims"]["beta_opt_range"],
        typical=B["claims"]["ics_typical_share"],
        time_uncertainty=B["claims"]["time_uncertainty"],
        sample_dt=B["balance"]["sample_dt"],
        r_threshold=B["balance"]["r_threshold"],
        close=CLOSE,
        zeta=B["machine"]["zeta"],
        neutral=B["marginal_growth"],
    message:
        "Paper B: measuring the paper's stated values and claims on the datasets"
    script:
        "../scripts/b_reproduced_values.py"


rule b_discrepancies:
    input:
        reproduced=rules.b_reproduced_values.output[0],
        paper_values=PAPER_VALUES,
    output:
        dataset("b", "discrepancies"),
    log:
        logs("b_discrepancies"),
    benchmark:
        benchmarks("b_discrepancies")
    priority: LONGEST_CHAIN
    localrule: True
    threads: BATCH_THREADS
    resources:
        batch=1,
    params:
        paper_b={
            **B_SETUP,
            **{
                k: B[k]
                for k in (
                    "kinematics",
                    "initial_conditions",
                    "table1",
                    "table2",
                )
            },
            "time_responses": {"fig7": B["time_responses"]["fig7"]},
        },
        parameters=config["discrepancies"]["paper_b"],
        inversion=config["discrepancies"]["inversion"],
    message:
        "Paper B: the printed numbers the reproduction misses, under hypotheses and inverted"
    script:
        "../scripts/b_discrepancies.py"
