"""Rule c_uncertainty: Sobol indices and band of Table 2's objective (beyond paper C)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.papers.c.uncertainty import uncertainty_dataset

job.start(snakemake.log[0])
p = snakemake.params
u = p.uncertainty
ds = uncertainty_dataset(Rotor(**p.rotor), dual_absorber(**p.table2), tolerance=u["tolerance"],
                         n_base=u["n_base"], convergence=u["convergence"],
                         resamples=u["resamples"], seed=u["seed"])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p), u["seed"]))
