"""Rule b_balance_study: balance time against one run parameter (config paper_b.balance_studies),
for every kinematics and initial condition."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.coords import grid
from rotorvib.pipeline.shards import run_balancer_study
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.studies import balance_study_dataset

job.start(snakemake.log[0])
p = snakemake.params
study = p.study
values = grid(study["range"])
setup = Setup.from_config(**p.setup)
run_balancer_study(
    snakemake, setup,
    lambda runs: balance_study_dataset(setup, kinematics=p.kinematics, ics=p.ics,
                                       axis=study["axis"], values=values,
                                       each=study.get("each"), fixed=study["fixed"],
                                       where=study["where"], runs=runs),
    study=f"balance_{snakemake.wildcards.study}")
