"""Rule c_table2: Table 2 beside the optimum the genetic algorithm finds."""

import sys

from rotorvib.io.datasets import read_dataset
from rotorvib.io.tables import write_table
from rotorvib.papers.c.claims import table2_side_by_side

sys.stderr = open(snakemake.log[0], "w", buffering=1)
expected_config = snakemake.params.inputs_config_sha256  # each input's producer config
rows = table2_side_by_side(read_dataset(snakemake.input.ga, expected_config))
write_table(rows, snakemake.output.csv, snakemake.output.md,
            title="Table 2 of paper C beside the genetic-algorithm optimum")
