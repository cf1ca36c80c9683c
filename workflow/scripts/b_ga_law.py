"""Rule b_ga_law: the whirl the passage leaves around each GA optimum, and its decay."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, read_dataset, write_dataset
from rotorvib.papers.b.ga_law import ga_law_dataset
from rotorvib.papers.b.setup import Setup

job.start(snakemake.log[0])
p = snakemake.params
ga = read_dataset(snakemake.input.ga, p.input_producers)
ds = ga_law_dataset(Setup.from_config(**p.setup), ga, p.ics, p.box["beta"], p.box["mass"],
                    **p.law, neutral=p.neutral)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
