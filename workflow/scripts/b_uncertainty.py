"""Rule b_uncertainty: Sobol indices and bands of one case of paper B (beyond the paper)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.comparison import paper_values_of
from rotorvib.pipeline.config import job_config
from rotorvib.io.datasets import Provenance, read_dataset, write_dataset
from rotorvib.models.balancer.simulate import use_threads
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.uncertainty import calibrated_band, uncertainty_dataset

job.start(snakemake.log[0])
use_threads(snakemake.threads)
p = snakemake.params
u = p.uncertainty
paper = paper_values_of(snakemake.input.paper_values, "B")
forces = read_dataset(snakemake.input.forces, p.input_producers)
R_band = calibrated_band(forces, [paper[f"table2_fmax_{row}"] for row in forces.case.values],
                         kinematics=p.kinematics)
ds = uncertainty_dataset(Setup.from_config(**p.setup), case=p.case, ranges=u["ranges"],
                         R_band=R_band, kinematics=p.kinematics, n_base=u["n_base"],
                         convergence=u["convergence"], resamples=u["resamples"], seed=u["seed"])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p), u["seed"]))
