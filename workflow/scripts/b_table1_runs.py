"""Rule b_table1_runs: balance time over ball mass for each operating speed (Table 1)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.coords import grid
from rotorvib.pipeline.shards import run_balancer_study
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.studies import table1_dataset

job.start(snakemake.log[0])
p = snakemake.params
t1 = p.table1
masses = grid(t1["mass"])
setup = Setup.from_config(**p.setup)
run_balancer_study(
    snakemake, setup,
    lambda runs: table1_dataset(setup, kinematics=p.kinematics, speeds=t1["speeds"],
                                ics=p.ics, beta=t1["beta"], eps_bar=t1["eps_bar"],
                                masses=masses, runs=runs),
    study="table1")
