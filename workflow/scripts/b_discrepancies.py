"""Rule b_discrepancies: paper B's printed numbers the reproduction misses, recomputed under the
hypotheses of rotorvib.papers.b.discrepancies, and the parameter values that would reproduce
the ones missed by more than 10 %."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import sys

from rotorvib.comparison.paper_values import read_paper_values
from rotorvib.comparison.reproduced_csv import read_reproduced
from rotorvib.comparison.discrepancy import misses, to_dataset
from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.io.progress import Progress
from rotorvib.models.balancer.simulate import use_threads
from rotorvib.papers.b.discrepancies import hypotheses, inversions, quantities
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import Setup

job.start(snakemake.log[0])
use_threads(snakemake.threads)
p = snakemake.params
b = p.paper_b
setup = Setup.from_paper_b(b)
reproduced = read_reproduced(snakemake.input.reproduced)
missed = misses(read_paper_values(snakemake.input.paper_values), reproduced)
prefix = "table1_m_opt_"
m_opt = {int(r.quantity[len(prefix):]): r.reproduced for r in reproduced
         if r.quantity.startswith(prefix)}
analysed = [q for q in quantities(b, m_opt) if q.name in missed]
memo = {}  # runs made once, whichever hypothesis or inversion asks for them again
baselines, found = hypotheses(setup, analysed, b["kinematics"], p.parameters, memo)
major = [q for q in analysed if missed[q.name][1] == "MAJOR"]
progress = Progress("inversions of the quantities missed by more than 10 %", len(major))
inverted = []
for done, q in enumerate(major, 1):
    for inv in inversions(setup, q, missed[q.name][0], b["kinematics"][0], p.parameters,
                          p.inversion["range"], p.inversion["n_scan"], memo):
        print(f"{inv.quantity}: {inv.text()}", file=sys.stderr)
        inverted.append(inv)
    progress(done, q.name)
ds = to_dataset(baselines, found, inverted, dataset_attrs(
    "discrepancy analysis", "The printed numbers the reproduction misses by more than 1 %, "
    "recomputed under other definitions, kinematics and parameter slips, and the parameter "
    "values that reproduce those missed by more than 10 %", "Fig 7, Tables 1-2"))
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
