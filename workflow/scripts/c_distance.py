"""Rule c_distance: the abstract's study of the absorbers' distance from the disk centre."""

import sys

import numpy as np

from rotorvib.io.config import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.papers.c.studies import distance_dataset

sys.stderr = open(snakemake.log[0], "w", buffering=1)
p = snakemake.params
w = np.linspace(p.grid["w_min"], p.grid["w_max"], p.grid["n_points"])
ds = distance_dataset(Rotor(**p.rotor), dual_absorber(**p.table2), p.offsets, w)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
