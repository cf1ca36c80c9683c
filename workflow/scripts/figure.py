"""Rules c_fig* and b_fig*: one figure from its datasets (named inputs) and the paper's values."""

import importlib
import sys

import xarray as xr

from rotorvib.comparison import paper_values_of
from rotorvib.plotting import save

sys.stderr = open(snakemake.log[0], "w", buffering=1)
datasets = {name: xr.load_dataset(path) for name, path in snakemake.input.items()
            if name != "paper_values"}
paper = paper_values_of(snakemake.input.paper_values, snakemake.params.paper)
draw = getattr(importlib.import_module(snakemake.params.module), snakemake.params.figure)
save(draw(**datasets, paper=paper, **snakemake.params.options), snakemake.output[0])
