"""Rule b_reproduced_values: every stated value and claim of paper B, measured on the datasets."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.comparison.choices import Close

from rotorvib.comparison.reproduced import merge_variants

from rotorvib.comparison.paper_values import paper_values_of
from rotorvib.comparison.reproduced_csv import write_reproduced
from rotorvib.io.datasets import read_dataset
from rotorvib.papers.b.boundaries import boundary_rows
from rotorvib.papers.b.choices import kinematics_choice
from rotorvib.papers.b.claims import reproduce
from rotorvib.papers.b.ga_law import ga_law_rows
from rotorvib.papers.b.law import law_rows, support_damping_rows, trend_rows
from rotorvib.papers.b.pareto import pareto_rows
from rotorvib.papers.b.design import design_rows
from rotorvib.papers.b.prediction import prediction_rows
from rotorvib.papers.b.uncertainty import uncertainty_rows
from rotorvib.papers.b.zeta_inversion import zeta_rows

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
p = snakemake.params
data = {name: read_dataset(path, producers) for name, path in snakemake.input.items()
        if name != "paper_values"}


def take(prefix: str) -> dict:
    """The datasets named ``prefix<variant>``, by variant, out of ``data``."""
    return {name.removeprefix(prefix): data.pop(name)
            for name in [n for n in data if n.startswith(prefix)]}


pareto, uncertainty, boundaries = take("pareto_"), take("uncertainty_"), take("boundary_")
law, ga_law, zeta = data.pop("law"), data.pop("ga_law"), data.pop("zeta_inversion")
design = data.pop("design_rule")
paper = paper_values_of(snakemake.input.paper_values, "B")
rows = reproduce(**data, R=p.R, ga_bounds=p.ga, beta_band=p.beta_band, typical=p.typical,
                 r_threshold=p.r_threshold, time_uncertainty=p.time_uncertainty,
                 paper_values=paper)
rows += merge_variants({kin: pareto_rows(ds) for kin, ds in pareto.items()},
                       kinematics_choice(pareto))
rows += uncertainty_rows(uncertainty, paper) + law_rows(law, Close.from_config(p.close)) + trend_rows(law)
rows += support_damping_rows(law, p.zeta, neutral=p.neutral) + ga_law_rows(
    ga_law, flat=p.sample_dt, flat_alternatives=(p.time_uncertainty,))
rows += boundary_rows(boundaries) + zeta_rows(zeta)
rows += prediction_rows(law, Close.from_config(p.close)) + design_rows(design)
write_reproduced(rows, snakemake.output[0])
