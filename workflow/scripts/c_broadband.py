"""Rule c_broadband: the broadband absorber (beyond paper C), NSGA-II front and comparison; the
searches of its seeds share out the job's threads."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import sys

import numpy as np

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, read_dataset, write_dataset
from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.models.absorber.time_response import response_times
from rotorvib.papers.c.broadband import NoDesignAtMass, broadband_dataset, broadband_fronts

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
p = snakemake.params
rotor = Rotor(**p.rotor)
b, fr, time = p.broadband, p.grid, p.time
band_w = np.linspace(*b["band"], b["n_band"])
nsga = {key: value for key, value in b["nsga"].items() if key not in ("seed", "spread_seeds")}
front, *spread = broadband_fronts(rotor, p.bounds, band_w,
                                  [b["nsga"]["seed"], *b["nsga"]["spread_seeds"]],
                                  workers=snakemake.threads, **nsga)
print(f"NSGA-II: {len(front.f)} designs on the front, {front.n_eval} evaluations",
      file=sys.stderr)
t = response_times(rotor.omega_n, time["t_end"], time["samples_per_period"])
ga = read_dataset(snakemake.input.ga, producers)
try:
    ds = broadband_dataset(rotor, dual_absorber(**p.table2), ga.x_opt.values,
                           b["den_hartog_d"], front, band_w,
                           np.linspace(fr["w_min"], fr["w_max"], fr["n_points"]), t,
                           k_min=p.bounds["k"][0], spread_fronts=spread)
except NoDesignAtMass as error:      # found by tests/schema_fuzz.py: a search too short
    sys.exit(f"config key 'paper_c.broadband.nsga': {error} after {b['nsga']['n_gen']} "
             f"generations of {b['nsga']['pop_size']}; give it more generations (n_gen) or a "
             "larger population (pop_size)")
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p),
                                                  b["nsga"]["seed"]))
