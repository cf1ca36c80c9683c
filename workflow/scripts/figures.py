"""Figure rules (figures.smk): the figures of a paper whose datasets come from the same rules,
each drawn by ``rotorvib.papers.<paper>.figures.<function>`` (params.module) from its datasets
(by argument name) and the paper's values, and saved as PNG and SVG; beside each, what it
draws and the parameters it depends on (JSON), which its caption states (rule report_text)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import importlib
import json
from pathlib import Path

from rotorvib.comparison.paper_values import paper_values_of
from rotorvib.io.datasets import read_dataset
from rotorvib.io.plotting import drawn_key, parameters_text, save

module = importlib.import_module(snakemake.params.module)  # the figures' own imports too
job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
p = snakemake.params
read = {name: read_dataset(path, producers) for name, path in snakemake.input.items()
        if name != "paper_values"}
paper = paper_values_of(snakemake.input.paper_values, p.paper.upper())
for name, declared in p.figures.items():
    datasets = {arg: read[dataset] for arg, dataset in declared["datasets"].items()}
    fig = getattr(module, declared["function"])(**datasets, paper=paper, **declared["options"])
    drawn = {"key": drawn_key(fig), "parameters": parameters_text(
        {arg: json.loads(ds.attrs["provenance_config"]) for arg, ds in datasets.items()},
        keep=set(declared["keep"]))}
    save(fig, snakemake.output[name])
    Path(snakemake.output[f"{name}_drawn"]).write_text(json.dumps(drawn, indent=1) + "\n")
