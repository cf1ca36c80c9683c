"""Rule b_tables: Tables 1 and 2 of paper B regenerated, and the kinematics note."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from pathlib import Path

from rotorvib.io.datasets import read_dataset
from rotorvib.io.tables import write_table
from rotorvib.comparison.paper_values import paper_value_texts_of
from rotorvib.papers.b.row_values import beside_printed, table1_rows, table2_rows
from rotorvib.papers.b.kinematics_note import kinematics_note

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
data = {name: read_dataset(path, producers) for name, path in snakemake.input.items()
        if name != "paper_values"}
printed = paper_value_texts_of(snakemake.input.paper_values, "B")
kin = str(data["table1"].kinematics_name.values[0])
write_table(beside_printed(table1_rows(data["table1"], kin), "table1", printed),
            snakemake.output.table1, snakemake.output.table1_md,
            title=f"Paper B, Table 1: optimum ball mass against operating speed ({kin} kinematics)")
write_table(beside_printed(table2_rows(data["forces"], snakemake.params.R, kin), "table2",
                           printed), snakemake.output.table2,
            snakemake.output.table2_md,
            title=f"Paper B, Table 2: bearing forces at the operating speed ({kin} kinematics, "
                  f"R = {snakemake.params.R} m)")
Path(snakemake.output.kinematics).write_text(
    kinematics_note(data["beta"], data["mass"], data["table1"], data["forces"], data["ga"],
                    snakemake.params.R), encoding="utf-8")
