"""Rule b_uncertainty: Sobol indices and bands of one case of paper B (beyond the paper); with
paper_b.shards > 1, a shard of its runs (b_uncertainty_shard) or their gathering."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.comparison.paper_values import paper_values_of
from rotorvib.io.datasets import read_dataset
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.uncertainty import CALIBRATION_KEY, calibrated_band, uncertainty_dataset
from rotorvib.pipeline.shards import run_balancer_study

job.start(snakemake.log[0])
p = snakemake.params
u = p.uncertainty
paper = paper_values_of(snakemake.input.paper_values, "B")
forces = read_dataset(snakemake.input.forces, p.input_producers)
R_band = calibrated_band(forces, [paper[CALIBRATION_KEY.format(row=row)]
                                  for row in forces.case.values],
                         kinematics=p.kinematics)
setup = Setup.from_config(**p.setup)
run_balancer_study(
    snakemake, setup,
    lambda runs: uncertainty_dataset(setup, case=p.case, ranges=u["ranges"],
                                     R_band=R_band, kinematics=p.kinematics,
                                     n_base=u["n_base"], convergence=u["convergence"],
                                     resamples=u["resamples"], seed=u["seed"],
                                     alternatives=u["prior_alternatives"], runs=runs),
    study=f"uncertainty_{snakemake.wildcards.case}", seed=u["seed"])
