"""Rule c_table2: Table 2 beside the optimum the genetic algorithm finds."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.datasets import read_dataset
from rotorvib.io.tables import write_table
from rotorvib.papers.c.claims import table2_side_by_side

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
rows = table2_side_by_side(read_dataset(snakemake.input.ga, producers))
write_table(rows, snakemake.output.csv, snakemake.output.md,
            title="Table 2 of paper C beside the genetic-algorithm optimum")
