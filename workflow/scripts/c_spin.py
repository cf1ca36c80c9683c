"""Rule c_spin: Table 2's absorber on a spinning rotor (beyond paper C)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import numpy as np

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.papers.c.spin import spin_dataset

job.start(snakemake.log[0])
p = snakemake.params
w = np.linspace(p.grid["w_min"], p.grid["w_max"], p.grid["n_points"])
ds = spin_dataset(Rotor(**p.rotor), dual_absorber(**p.table2), n=p.spin["n"],
                  realistic=p.spin["realistic_rpm"] * np.pi / 30, w=w,
                  alternatives=[rpm * np.pi / 30 for rpm in p.spin["alternative_rpm"]])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
