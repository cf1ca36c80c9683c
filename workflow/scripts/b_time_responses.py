"""Rule b_time_responses: r(t), ball angles and bearing force of Figs 4-7, 11, 15, 16."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.b.responses import figure_runs, time_response_dataset
from rotorvib.papers.b.setup import Setup

job.start(snakemake.log[0])
p = snakemake.params
setup = Setup.from_config(**p.setup)
runs = figure_runs(p.responses, p.table2, p.ics, omega=setup.omega, M=setup.M)
ds = time_response_dataset(setup, kinematics=p.kinematics, runs=runs)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
