"""Test oracle: record what each Snakemake script job actually loaded.

On the ``PYTHONPATH`` of a workflow test with ``ROTORVIB_JOB_RECORDS`` set, every Python process
that ran a Snakemake script writes, when it exits, one JSON file: the rule, the job's input and
output files, the ``rotorvib`` modules its results rest on (those in ``sys.modules``, and those
whose source keyed the generated code it ran: ``rotorvib.methods.codegen.KEYED``), the
top-level packages it loaded and whether Snakemake benchmarked the job.  This is the independent record
against which the derived code fingerprints are tested: it comes from the interpreter, not from
reading imports.
"""

import atexit
import hashlib
import json
import os
import sys
from pathlib import Path


def _module_name(path: Path) -> str:
    parts = path.with_suffix("").parts
    parts = parts[len(parts) - 1 - parts[::-1].index("rotorvib"):]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _record():
    job = getattr(sys.modules.get("__main__"), "snakemake", None)
    if job is None:
        return
    outputs = sorted(str(f) for f in job.output)
    keyed = getattr(sys.modules.get("rotorvib.methods.codegen"), "KEYED", ())
    record = {"rule": job.rule, "output": outputs, "input": sorted(str(f) for f in job.input),
              "modules": sorted({m for m in sys.modules if m.split(".")[0] == "rotorvib"}
                                | {_module_name(Path(f)) for f in keyed
                                   if "rotorvib" in Path(f).parts}),
              "packages": sorted({m.split(".")[0] for m in sys.modules}),
              "benchmarked": job.bench_iteration is not None}
    key = hashlib.sha256("\n".join(outputs).encode()).hexdigest()[:16]
    target = Path(os.environ["ROTORVIB_JOB_RECORDS"]) / f"{job.rule}-{key}.json"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(record, indent=1))


if os.environ.get("ROTORVIB_JOB_RECORDS"):
    atexit.register(_record)
