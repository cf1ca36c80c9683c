"""Rule archive: one tarball of all results with a SHA-256 manifest, restore notes and an
RO-Crate describing the run."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from pathlib import Path

import snakemake as snakemake_package

from rotorvib.pipeline.archive import CRATE, make_archive
from rotorvib.pipeline.crate import crate_metadata
from rotorvib.io.provenance import git_date

job.start(snakemake.log[0])
inputs = snakemake.input
crate = crate_metadata(
    results=list(inputs.results), configuration=list(inputs.configuration),
    code=list(inputs.code), date=git_date(),
    title="rotorvib: reproductions of three rotor-dynamics papers",
    description="Every dataset (CF-1.11 netCDF), table and figure of one run of the rotorvib "
                "workflow, the words and pages of its report, the run's configuration and commit.",
    snakemake_version=snakemake_package.__version__,
    results_dir=Path(snakemake.output.archive).parents[1].as_posix())  # <results>/archive/...
make_archive(list(inputs.results) + list(inputs.configuration) + list(inputs.code),
             snakemake.output.archive, generated={CRATE: crate})
print(f"archive SHA-256 (publish it with the archive): {Path(snakemake.output.digest).read_text()}")
