"""Rules c_fig*: one paper C figure from its datasets (named inputs) and the paper's values."""

import sys

import xarray as xr

from rotorvib.comparison import paper_values_of
from rotorvib.dva import figures
from rotorvib.plotting import save

sys.stderr = open(snakemake.log[0], "w", buffering=1)
datasets = {name: xr.load_dataset(path) for name, path in snakemake.input.items()
            if name != "paper_values"}
paper = paper_values_of(snakemake.input.paper_values, "C")
draw = getattr(figures, snakemake.params.figure)
save(draw(**datasets, paper=paper, **snakemake.params.options), snakemake.output[0])
