"""Rule b_design_rule: the ball mass and damping predicted without integrating, verified by
integrating, and checked on an integrated grid, under each kinematics on each machine
(beyond paper B)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.coords import grid
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.b.design import design_dataset
from rotorvib.papers.b.setup import Setup
from rotorvib.pipeline.job import job_config

job.start(snakemake.log[0])
p = snakemake.params
rule = p.rule
ds = design_dataset(Setup.from_config(**p.setup), masses=grid(rule["mass"]),
                    betas=grid(rule["beta"]), ics={name: p.ics[name] for name in rule["ics"]},
                    kinematics=rule["kinematics"], machines=rule["machines"], neutral=p.neutral,
                    share=p.share, verify=rule["verify"], mass_margin=rule["mass_margin"],
                    check=rule["check"])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
