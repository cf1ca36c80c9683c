"""Rule b_ross: paper B's rotor without balls by the closed form, the engine and ROSS."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.coords import grid
from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.b import ross_model
from rotorvib.papers.b.jeffcott import ballless, jeffcott_dataset
from rotorvib.papers.b.setup import Setup

job.start(snakemake.log[0])
p = snakemake.params
setup = Setup.from_config(**p.setup)
rotor = ballless(setup, p.eps_bar, p.check["m_bar"])
model = ross_model.rotor(rotor.M, rotor.k, rotor.c, p.check["shaft"])
unbalance = rotor.M * rotor.eps
ds = jeffcott_dataset(
    setup, eps_bar=p.eps_bar, m_bar=p.check["m_bar"],
    speeds=grid(p.check["speeds"]), settle=p.check["settle"],
    t_end=p.check["t_end"], dt=p.check["dt"],
    ross_steady=lambda speeds: ross_model.steady(model, unbalance, speeds),
    ross_runup=lambda t, kinematics: ross_model.runup(model, unbalance, t, kinematics))
ds["shaft_compliance"] = ((), setup.k / ross_model.shaft_stiffness(p.check["shaft"]),
                          {"long_name": "k / k_shaft: the relative compliance the ROSS model's "
                                        "shaft adds", "units": "1"})
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
