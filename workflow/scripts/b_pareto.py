"""Rule b_pareto: NSGA-II front of balance time against peak bearing force (beyond paper B)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.balancer.simulate import use_threads
from rotorvib.papers.b.pareto import pareto_dataset
from rotorvib.papers.b.setup import Setup

job.start(snakemake.log[0])
use_threads(snakemake.threads)
p = snakemake.params
pa = p.pareto
ds = pareto_dataset(Setup.from_config(**p.setup), kinematics=p.kinematics, eps_bar=pa["eps_bar"],
                    speed=pa["speed"], beta_bounds=p.bounds["beta"], mass_bounds=p.bounds["mass"],
                    positions=pa["positions"], seed=pa["seed"], pop_size=pa["pop_size"],
                    n_gen=pa["n_gen"], censored_penalty=p.bounds["censored_penalty"],
                    paper_designs=p.table2)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p), pa["seed"]))
