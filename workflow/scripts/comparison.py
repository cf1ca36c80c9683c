"""Rule comparison: join the papers' values with the reproduced ones (results/comparison.*) and
explain every number missed by the discrepancy analysis (results/discrepancies.*)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.comparison import discrepancy
from rotorvib.comparison.table import build_table, write_table_files
from rotorvib.comparison.paper_values import read_paper_values
from rotorvib.io.datasets import read_dataset
from rotorvib.comparison.reproduced_csv import read_reproduced

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
reproduced = [row for path in snakemake.input.reproduced for row in read_reproduced(path)]
papers = {row.paper for row in reproduced}
values = [row for row in read_paper_values(snakemake.input.paper_values) if row["paper"] in papers]
table = build_table(values, reproduced)
analyses = discrepancy.analyse(
    table, values, reproduced,
    [discrepancy.from_dataset(read_dataset(path, producers)) for path in snakemake.input.discrepancies])
discrepancy.write_files(analyses, snakemake.output.discrepancies_csv,
                        snakemake.output.discrepancies_md)
write_table_files(discrepancy.annotate(table, analyses), snakemake.output.csv,
                  snakemake.output.md, more_totals=(discrepancy.totals(analyses),))
