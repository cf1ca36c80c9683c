"""Rule c_broadband_table: the broadband absorber beside the other designs (beyond paper C)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.datasets import read_dataset
from rotorvib.io.tables import write_table
from rotorvib.papers.c.broadband import comparison_table

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
rows = comparison_table(read_dataset(snakemake.input.bb, producers))
write_table(rows, snakemake.output.csv, snakemake.output.md,
            title="Paper C, beyond the paper: the broadband absorber beside the other designs")
