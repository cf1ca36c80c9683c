"""The SLURM profile's threads, written from the rules' own declarations.

A batch rule declares ``resources: batch=1`` and ``threads: BATCH_THREADS`` (half of Snakemake's
cores, at least one: workflow/rules/common.smk). A cluster job's step evaluates a rule's threads
again, with the step's own cores, and only a ``--set-threads`` crosses into it, so the profile
must carry the threads of every batch rule. This module asks Snakemake for the rules as it
reads them (:func:`declared_rules`: the rule objects, as the plan reads them) and rewrites the
profile's ``set-threads`` block from the batch rules, never typed::

    python -m rotorvib.pipeline.slurm_profile [workflow]

``tests/test_makespan.py`` checks that the shipped profile is what this writes.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from rotorvib.pipeline.plan import Maker

#: Threads each batch rule asks for on a cluster: the GA's serial share, 0.10 (docs/developer.md),
#: makes a second thread worth 1.8x; more wait longer in the queue.
CLUSTER_THREADS = 2
BEGIN = "set-threads:  # written by python -m rotorvib.pipeline.slurm_profile, from the rules"
END = "# end of set-threads"


def declared_rules(root: Path, *options: str) -> list[Maker]:
    """Every rule of the workflow in ``root`` (the folder of its Snakefile), as Snakemake reads
    it with the default configuration (or as Snakemake's ``options`` say, ``--configfile`` ...):
    ``snakemake --list-rules`` with ``ROTORVIB_RULES_JSON``
    naming a file, where the workflow writes its rules once it has read them
    (workflow/rules/common.smk, ``check_rules``)."""
    with tempfile.TemporaryDirectory() as folder:
        written = Path(folder) / "rules.json"
        run = subprocess.run(
            [sys.executable, "-m", "snakemake", "--snakefile", str(root / "Snakefile"),
             "--directory", str(root), "--list-rules", *options],
            cwd=root, capture_output=True, text=True,
            env=os.environ | {"ROTORVIB_RULES_JSON": str(written)})
        if run.returncode or not written.exists():
            raise RuntimeError(f"snakemake --list-rules failed in {root}:\n{run.stderr}")
        return [Maker(**{k: tuple(v) if isinstance(v, list) else v for k, v in rule.items()})
                for rule in json.loads(written.read_text())]


def batch_rules(root: Path) -> list[str]:
    """The batch rules of the workflow in ``root`` (``resources: batch=1``), sorted."""
    return sorted(rule.name for rule in declared_rules(root) if rule.batch)


def set_threads(rules: list[str]) -> str:
    """The profile's ``set-threads`` block for ``rules``, between its markers."""
    return "\n".join([BEGIN, *(f"  {rule}: {CLUSTER_THREADS}" for rule in rules), END])


def written(profile_text: str, rules: list[str]) -> str:
    """``profile_text`` with its ``set-threads`` block replaced by :func:`set_threads`."""
    pattern = re.compile(re.escape(BEGIN) + r".*?" + re.escape(END), re.S)
    if not pattern.search(profile_text):
        raise ValueError("the profile has no set-threads block between the markers")
    return pattern.sub(lambda _: set_threads(rules), profile_text)


def main(argv: list[str] | None = None) -> None:
    """Rewrite the SLURM profile (``profiles/slurm`` beside the workflow folder given,
    ``workflow`` by default)."""
    root = Path((argv if argv is not None else sys.argv[1:] or ["workflow"])[0]).resolve().parent
    profile = root / "profiles/slurm/config.yaml"
    profile.write_text(written(profile.read_text(), batch_rules(root)))


if __name__ == "__main__":
    main()
