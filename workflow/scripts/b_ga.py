"""Rule b_ga: genetic algorithm over (beta, m) for every eps_bar x initial condition."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.config import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.balancer.simulate import use_threads
from rotorvib.papers.b.optimise import ga_dataset
from rotorvib.papers.b.setup import Setup

job.start(snakemake.log[0])
use_threads(snakemake.threads)
p = snakemake.params
ga = p.ga
ds = ga_dataset(Setup.from_config(**p.setup), kinematics=p.kinematics, eps_bars=ga["eps_bar"],
                ics=p.ics, beta_bounds=ga["beta"], mass_bounds=ga["mass"], pop_size=ga["pop_size"],
                n_gen=ga["n_gen"], seed=ga["seed"], spread_seeds=ga["spread_seeds"],
                censored_penalty=ga["censored_penalty"])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p), ga["seed"]))
