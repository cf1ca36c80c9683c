"""Rule a_reproduced_values: paper A's claims measured on the datasets."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.comparison.choices import Close

from rotorvib.comparison.paper_values import paper_values_of
from rotorvib.comparison.reproduced_csv import write_reproduced
from rotorvib.io.datasets import read_dataset
from rotorvib.papers.a.claims import reproduce

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
data = {name: read_dataset(path, producers) for name, path in snakemake.input.items()
        if name != "paper_values"}
p = snakemake.params
rows = reproduce(**data, case_beta=p.case["beta"], window=p.zoom[1] - p.zoom[0],
                 close=Close.from_config(p.close), rk=p.rk, paper_values=paper_values_of(snakemake.input.paper_values, "A"))
write_reproduced(rows, snakemake.output[0])
