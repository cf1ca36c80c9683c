"""Rule b_basin: balance time over all initial ball positions (beyond the paper)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.shards import run_balancer_study
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.studies import basin_dataset

job.start(snakemake.log[0])
p = snakemake.params
setup = Setup.from_config(**p.setup)
run_balancer_study(
    snakemake, setup,
    lambda runs: basin_dataset(setup, kinematics=p.kinematics, cases=p.basin["cases"],
                               n=p.basin["n"], eps_bar=p.basin["eps_bar"], ics=p.ics,
                               runs=runs),
    study="basin")
