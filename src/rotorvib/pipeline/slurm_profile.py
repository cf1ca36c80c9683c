"""The SLURM profile's threads, written from the rules' own declarations.

Paper B's batch rules declare ``threads: BATCH_THREADS`` (half of Snakemake's cores, at least
one: workflow/rules/common.smk). A cluster job's step evaluates a rule's threads again, with the
step's own cores, and only a ``--set-threads`` crosses into it, so the profile must carry the
threads of every batch rule. This module finds those rules in the rule files (:func:`batch_rules`)
and rewrites the profile's ``set-threads`` block from them, never typed::

    python -m rotorvib.pipeline.slurm_profile [workflow]

``tests/test_makespan.py`` checks that the shipped profile is what this writes.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

#: Threads each batch rule asks for on a cluster: the GA's serial share, 0.10 (docs/developer.md),
#: makes a second thread worth 1.8x; more wait longer in the queue.
CLUSTER_THREADS = 2
BEGIN = "set-threads:  # written by python -m rotorvib.pipeline.slurm_profile, from the rules"
END = "# end of set-threads"


def batch_rules(rules: Path) -> list[str]:
    """The rules of the rule files in ``rules`` that declare ``threads: BATCH_THREADS``: each
    ``rule X:`` block that says so, and both rules of each batch study of paper B's table
    (``"X": batch_study(...)``: its rules ``X`` and ``X_shard``, paper_b.smk), sorted."""
    text = "".join(p.read_text() for p in sorted(rules.glob("*.smk")))
    blocks = re.split(r"^(?=\S)", text, flags=re.M)      # each top-level statement
    batch = {re.match(r"rule (\w+)", b).group(1) for b in blocks
             if b.startswith("rule ") and "threads: BATCH_THREADS" in b}
    studies = re.findall(r'^\s+"(\w+)": batch_study\(', text, flags=re.M)
    return sorted(batch | {name + suffix for name in studies for suffix in ("", "_shard")})


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
    workflow = Path((argv if argv is not None else sys.argv[1:] or ["workflow"])[0])
    profile = workflow.resolve().parent / "profiles/slurm/config.yaml"
    profile.write_text(written(profile.read_text(), batch_rules(workflow / "rules")))


if __name__ == "__main__":
    main()
