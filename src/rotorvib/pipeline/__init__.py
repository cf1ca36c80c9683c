"""The workflow's own machinery, above the science: reading and checking the configuration,
code fingerprints, a job's start-up, the report's words and pages, the archive and its
RO-Crate.  Nothing below it (``models``, ``methods``, ``papers``, ``io``, ``comparison``)
imports it, and it never imports Snakemake: the Snakefile hands it what it needs."""
