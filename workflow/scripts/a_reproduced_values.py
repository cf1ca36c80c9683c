"""Rule a_reproduced_values: paper A's claims measured on the datasets."""

import sys

from rotorvib.comparison import paper_values_of, write_reproduced
from rotorvib.io.datasets import read_dataset
from rotorvib.papers.a.claims import reproduce

sys.stderr = open(snakemake.log[0], "w", buffering=1)
expected_config = snakemake.params.inputs_config_sha256  # each input's producer config
data = {name: read_dataset(path, expected_config) for name, path in snakemake.input.items()
        if name != "paper_values"}
p = snakemake.params
rows = reproduce(**data, case_beta=p.case["beta"], window=p.zoom[1] - p.zoom[0],
                 paper_values=paper_values_of(snakemake.input.paper_values, "A"))
write_reproduced(rows, snakemake.output[0])
