"""Rule b_stability: stability of the balanced state on paper B's grids (Figs 2-3)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.coords import grid
from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.b.stability_maps import stability_dataset

job.start(snakemake.log[0])
p = snakemake.params
axes = {key: grid(v) if isinstance(v, dict) else v for key, v in p.map.items()}
ds = stability_dataset(zeta=p.zeta, n=p.n, where=f"Fig {snakemake.wildcards.fig[3:]}",
                       marginal=p.marginal, **axes)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
