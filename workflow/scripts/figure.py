"""Rule figure: one figure of a paper from its datasets (named inputs) and the paper's values;
the drawing function is ``rotorvib.papers.<paper>.figures.<function>`` (params.module). Under
every figure: the parameters its datasets were made with."""

import importlib
import json
import sys

from rotorvib.comparison import paper_values_of
from rotorvib.io.datasets import read_dataset
from rotorvib.io.plotting import parameters_text, save, state_parameters

sys.stderr = open(snakemake.log[0], "w", buffering=1)
expected_config = snakemake.params.inputs_config_sha256  # each input's producer config
p = snakemake.params
datasets = {name: read_dataset(path, expected_config) for name, path in snakemake.input.items()
            if name != "paper_values"}
paper = paper_values_of(snakemake.input.paper_values, snakemake.wildcards.paper.upper())
draw = getattr(importlib.import_module(p.module), p.function)
fig = draw(**datasets, paper=paper, **p.options)
state_parameters(fig, parameters_text({name: json.loads(ds.attrs["provenance_config"])
                                       for name, ds in datasets.items()}))
save(fig, snakemake.output[0])
