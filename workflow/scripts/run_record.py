"""Rule run_record: the run's whole (validated) configuration and the commit of the library
that ran it (rotorvib.io.provenance.code_state), as files."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from pathlib import Path

import yaml

job.start(snakemake.log[0])

commit, dirty, origin = snakemake.params.commit
Path(snakemake.output.config).write_text(
    "# The whole configuration of this run (config files and overrides merged, validated)\n"
    + yaml.safe_dump(dict(snakemake.params.config), sort_keys=True), encoding="utf-8")
Path(snakemake.output.commit).write_text(
    f"commit {commit}\nuncommitted changes {'yes' if dirty else 'no'}\ncode {origin}\n",
    encoding="utf-8")
