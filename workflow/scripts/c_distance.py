"""Rule c_distance: the abstract's study of the absorbers' distance from the disk centre."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import numpy as np

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.papers.c.studies import distance_dataset

job.start(snakemake.log[0])
p = snakemake.params
w = np.linspace(p.grid["w_min"], p.grid["w_max"], p.grid["n_points"])
ds = distance_dataset(Rotor(**p.rotor), dual_absorber(**p.table2), p.offsets, w)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
