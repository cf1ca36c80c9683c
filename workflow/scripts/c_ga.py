"""Rule c_ga: genetic-algorithm tuning of the dual absorber (paper C, section 4)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import sys

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.papers.c.optimise import tune_dual_absorber
from rotorvib.papers.c.studies import ga_dataset

job.start(snakemake.log[0])
p = snakemake.params
rotor = Rotor(**p.rotor)


def progress(generation, best):
    if generation % 10 == 0 or generation == p.ga["n_gen"]:
        print(f"generation {generation}/{p.ga['n_gen']}: best |Theta| = {best:.4g} rad",
              file=sys.stderr)


result = tune_dual_absorber(rotor, p.bounds, **p.ga, progress=progress)
ds = ga_dataset(rotor, result, dual_absorber(**p.table2), p.bounds)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p), p.ga["seed"]))
