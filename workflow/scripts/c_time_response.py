"""Rule c_time_response: Figs 3, 4, 7 time responses, linear (14) and nonlinear (8)-(10)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.papers.c.studies import time_response_dataset

job.start(snakemake.log[0])
p = snakemake.params
ds = time_response_dataset(Rotor(**p.rotor), dual_absorber(**p.table2), p.den_hartog["d"],
                           **p.time)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
