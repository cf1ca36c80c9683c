"""Rule b_boundary: the stability boundary in one parameter plane, by continuation (beyond
paper B's Figs 2-3)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.b.boundaries import boundary_dataset

job.start(snakemake.log[0])
p = snakemake.params
plane = snakemake.wildcards.plane
ds = boundary_dataset(plane, fixed={k: v for k, v in p.base.items() if k != plane},
                      p_range=(p.span["min"], p.span["max"]), start=p.base[plane],
                      neutral=p.neutral, n=p.n, **p.trace)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
