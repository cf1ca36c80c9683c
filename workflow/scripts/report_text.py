"""Rule report_text: the report's landing page and every caption, from the comparison table."""

from rotorvib.io import job  # first: the imports below run without the cyclic GC

import csv
from pathlib import Path

from rotorvib import discrepancy, report
from rotorvib.io.config import load_yaml

job.start(snakemake.log[0])


def rows(path):
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


table = rows(snakemake.input.comparison)
discrepancies = rows(snakemake.input.discrepancies)
claims = {(row["paper"], row["quantity"]): row["claim"] for row in rows(snakemake.input.paper_values)}
tables = {Path(path).parent.parent.name.removeprefix("paper_") + "/" + Path(path).stem: rows(path)
          for path in snakemake.input.tables}
out = snakemake.output
figure_captions = {Path(path).stem: path for path in out.figure_captions}
table_captions = {Path(path).stem: path for path in out.table_captions}

report.write(out.landing, report.landing_page(
    table, claims, load_yaml(snakemake.input.papers),
    discrepancy.totals_of_rows(discrepancies)))
for paper, figures in snakemake.params.figures.items():
    for name, entry in figures.items():
        report.write_caption(figure_captions[f"{paper}_{name}"], report.caption(
            f"Paper {paper.upper()}, {report.label(name)}", entry["shows"],
            report.rows_for(table, paper, name, "figure", tuple(entry["items"])), claims))
for paper, entries in snakemake.params.tables.items():
    for name, entry in entries.items():
        if paper == "all":  # the comparison and the discrepancy analysis: their totals
            text = report.caption(report.label(name, "table"), f"{entry['shows']} "
                                  f"{report.comparison_summary(table)} Discrepancy analysis: "
                                  f"{discrepancy.totals_of_rows(discrepancies)}.")
        else:
            text = report.caption(
                f"Paper {paper.upper()}, {report.label(name, 'table')}",
                entry["shows"] + report.check_counts(tables.get(f"{paper}/{name}", [])),
                report.rows_for(table, paper, name, "table", tuple(entry["items"])), claims)
        report.write_caption(table_captions[f"{paper}_{name}"], text)
