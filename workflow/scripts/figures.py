"""Figure rules (figures.smk): the figures of a paper that read the same datasets, each drawn by
``rotorvib.papers.<paper>.figures.<function>`` (params.module) from its datasets (by argument
name) and the paper's values. Under every figure: the parameters its datasets were made with."""

from rotorvib.io import job  # first: the imports below run without the cyclic GC

import importlib
import json

from rotorvib.comparison import paper_values_of
from rotorvib.io.datasets import read_dataset
from rotorvib.io.plotting import parameters_text, save, state_parameters

module = importlib.import_module(snakemake.params.module)  # the figures' own imports too
job.start(snakemake.log[0])
expected_config = snakemake.params.inputs_config_sha256  # each input's producer config
p = snakemake.params
read = {name: read_dataset(path, expected_config) for name, path in snakemake.input.items()
        if name != "paper_values"}
paper = paper_values_of(snakemake.input.paper_values, p.paper.upper())
for name, declared in p.figures.items():
    datasets = {arg: read[dataset] for arg, dataset in declared["datasets"].items()}
    fig = getattr(module, declared["function"])(**datasets, paper=paper, **declared["options"])
    state_parameters(fig, parameters_text({arg: json.loads(ds.attrs["provenance_config"])
                                           for arg, ds in datasets.items()}))
    save(fig, snakemake.output[name])
