"""Rule report_text: the report's landing page, summary page, every caption and every table's
HTML page, from the comparison table."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import csv
import json
from pathlib import Path

from rotorvib.comparison import discrepancy
from rotorvib.pipeline import report, report_pages, report_tables

job.start(snakemake.log[0])


def rows(path):
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


table = rows(snakemake.input.comparison)
discrepancies = rows(snakemake.input.discrepancies)
claims = {(row["paper"], row["quantity"]): row["claim"] for row in rows(snakemake.input.paper_values)}
# the papers of the run (config key papers, data/papers.yaml read when the rules are): those the
# comparison holds rows of
papers = {letter: entry for letter, entry in snakemake.params.papers.items()
          if letter in {row["paper"] for row in table}}
out = snakemake.output
figure_captions = {Path(path).stem: path for path in out.figure_captions}
table_captions = {Path(path).stem: path for path in out.table_captions}
table_pages = {Path(path).stem: path for path in out.table_pages}
discrepancy_totals = discrepancy.totals_of_rows(discrepancies)

report.write(out.landing, report.landing_page(table, papers))
report.write(out.summary, report_pages.rst_to_html(
    report.summary_text(table, claims, papers, discrepancy_totals)))
drawn = {f"{Path(path).parent.parent.name.removeprefix('paper_')}_{Path(path).stem}":
         json.loads(Path(path).read_text()) for path in snakemake.input.drawn}
for paper, figures in snakemake.params.figures.items():
    for name, entry in figures.items():
        report.write_caption(figure_captions[f"{paper}_{name}"], report.caption(
            f"Paper {paper.upper()}, {report.label(name)}", entry["shows"],
            report.rows_for(table, paper, name, "figure", tuple(entry["items"])), claims,
            made=snakemake.params.made_by["figure"][paper][name], **drawn[f"{paper}_{name}"]))
for paper, entries in snakemake.params.tables.items():
    for name, entry in entries.items():
        made = snakemake.params.made_by["table"][paper][name]
        csv_text = Path(entry["csv"]).read_text(encoding="utf-8")
        if paper == "all":  # the comparison and the discrepancy analysis: their totals
            title = report.label(name, "table").capitalize()
            text = report.caption(title, f"{entry['shows']} "
                                  f"{report.comparison_summary(table)} Discrepancy analysis: "
                                  f"{discrepancy_totals}.", made=made)
        else:
            title = f"Paper {paper.upper()}, {report.label(name, 'table')}"
            text = report.caption(title, entry["shows"] + report.check_counts(rows(entry["csv"])),
                                  report.rows_for(table, paper, name, "table",
                                                  tuple(entry["items"])), claims, made=made)
        report.write_caption(table_captions[f"{paper}_{name}"], text)
        report.write(table_pages[f"{paper}_{name}"], report_tables.table_page(
            title, report_pages.rst_fragment(text), csv_text, Path(entry["csv"]).name))
