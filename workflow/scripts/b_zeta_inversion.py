"""Rule b_zeta_inversion: the printed times of Fig 7, Table 1 and Table 2 over the support
damping zeta, and which zeta (if any) reproduces them together."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.coords import grid
from rotorvib.comparison.paper_values import paper_value_texts_of
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.balancer.simulate import use_threads
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.zeta_inversion import inversion_dataset, printed_cases
from rotorvib.pipeline.job import job_config

job.start(snakemake.log[0])
use_threads(snakemake.threads)
p = snakemake.params
cases = printed_cases(p.cases, paper_value_texts_of(snakemake.input.paper_values, "B"))
ds = inversion_dataset(Setup.from_config(**p.setup), cases, kinematics=p.kinematics,
                       zetas=grid(p.zeta_inversion["zeta"]))
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
