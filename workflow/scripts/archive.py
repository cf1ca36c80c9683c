"""Rule archive: one tarball of all results with a SHA-256 manifest and restore notes."""

import sys

from rotorvib.io.archive import make_archive

sys.stderr = open(snakemake.log[0], "w", buffering=1)
make_archive(list(snakemake.input), snakemake.output[0])
