"""Rule b_basin: balance time over all initial ball positions (beyond the paper)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.config import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.balancer.simulate import use_threads
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.studies import basin_dataset

job.start(snakemake.log[0])
use_threads(snakemake.threads)
p = snakemake.params
ds = basin_dataset(Setup.from_config(**p.setup), kinematics=p.kinematics, cases=p.basin["cases"],
                   n=p.basin["n"], eps_bar=p.basin["eps_bar"], ics=p.ics)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
