"""Rule comparison: join the papers' values with the reproduced ones (results/comparison.*)."""

import sys

from rotorvib.comparison import (build_table, read_paper_values, read_reproduced,
                                 write_table_files)

sys.stderr = open(snakemake.log[0], "w", buffering=1)
reproduced = [row for path in snakemake.input.reproduced for row in read_reproduced(path)]
papers = {row.paper for row in reproduced}
values = [row for row in read_paper_values(snakemake.input.paper_values) if row["paper"] in papers]
table = build_table(values, reproduced)
write_table_files(table, snakemake.output.csv, snakemake.output.md)
