"""Rule b_balance_law: the balance-time law against every balanced run, with the passage
integrated and in closed form (beyond paper B)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, read_dataset, write_dataset
from rotorvib.papers.b.law import law_dataset
from rotorvib.papers.b.prediction import closed_form_law
from rotorvib.papers.b.setup import Setup

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
p = snakemake.params
sources = {name: (read_dataset(snakemake.input[name], producers), fixed)
           for name, fixed in p.fixed.items()}
setup = Setup.from_config(**p.setup)
ds = closed_form_law(setup, law_dataset(setup, sources, p.ics, neutral=p.neutral,
                                        shares=p.shares))
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
