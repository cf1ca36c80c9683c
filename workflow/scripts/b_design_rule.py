"""Rule b_design_rule: the ball mass and damping by the balance time predicted without
integrating, and the recommendation integrated (beyond paper B)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.coords import grid
from rotorvib.io.datasets import Provenance, read_dataset, write_dataset
from rotorvib.papers.b.prediction import design_dataset
from rotorvib.papers.b.setup import Setup
from rotorvib.pipeline.job import job_config

job.start(snakemake.log[0])
p = snakemake.params
rule = p.rule
masses, betas = (grid(rule[k]) for k in ("mass", "beta"))
ds = design_dataset(Setup.from_config(**p.setup), read_dataset(snakemake.input.law,
                                                                p.input_producers),
                    masses=masses, betas=betas, eps_bar=rule["eps_bar"],
                    ics={name: p.ics[name] for name in rule["ics"]},
                    kinematics=rule["kinematics"], speed=rule["speed"], neutral=p.neutral,
                    share=p.share, band_percentiles=rule["band"])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
