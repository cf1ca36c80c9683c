"""The comparison of the papers' values with the reproduced ones, and what it rests on: the
papers' values (:mod:`~rotorvib.comparison.paper_values`), the project's choices a row rests on
(:mod:`~rotorvib.comparison.choices`), the comparison itself (:mod:`~rotorvib.comparison.table`),
the reproduced values' CSV each paper writes (:mod:`~rotorvib.comparison.reproduced_csv`) and
the discrepancy analysis of the numbers missed (:mod:`~rotorvib.comparison.discrepancy`).
Nothing here imports the workflow's machinery (``rotorvib.pipeline``) or a paper."""
