"""Rule c_frequency_response: Fig 5's frequency responses (paper C, eq. 20)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import numpy as np

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, read_dataset, write_dataset
from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.papers.c.studies import frequency_response_dataset

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
p = snakemake.params
w = np.linspace(p.grid["w_min"], p.grid["w_max"], p.grid["n_points"])
x_opt = read_dataset(snakemake.input.ga, producers).x_opt.values
ds = frequency_response_dataset(Rotor(**p.rotor), dual_absorber(**p.table2), x_opt, w)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
