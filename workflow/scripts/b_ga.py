"""Rule b_ga: genetic algorithm over (beta, m) for every eps_bar x initial condition; split in
paper_b.ga_shards (or paper_b.shards, if larger) jobs, a shard of its searches (b_ga_shard) or
their results gathered (rotorvib.pipeline.shards)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.models.balancer.simulate import use_threads
from rotorvib.papers.b.optimise import ga_searches, results_dataset, solve
from rotorvib.papers.b.setup import Setup
from rotorvib.pipeline.shards import run_search

job.start(snakemake.log[0])
use_threads(snakemake.threads)
p = snakemake.params
ga = p.ga
setup = Setup.from_config(**p.setup)
searches = ga_searches(p.kinematics, ga["eps_bar"], p.ics, [ga["seed"], *ga["spread_seeds"]])
search = {"pop_size": ga["pop_size"], "n_gen": ga["n_gen"],
          "censored_penalty": ga["censored_penalty"]}
run_search(snakemake, len(searches),
           lambda indices: solve(setup, [searches[i] for i in indices], beta_bounds=ga["beta"],
                                 mass_bounds=ga["mass"], **search),
           lambda results: results_dataset(setup, results, kinematics=p.kinematics,
                                           eps_bars=ga["eps_bar"], ics=p.ics, seed=ga["seed"],
                                           spread_seeds=ga["spread_seeds"], **search),
           study="ga", seed=ga["seed"])
