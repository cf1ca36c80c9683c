"""Rule c_reproduced_values: every stated value and claim of paper C, measured on the datasets."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.comparison.choices import Close

from rotorvib.comparison.paper_values import paper_values_of
from rotorvib.comparison.reproduced_csv import write_reproduced
from rotorvib.io.datasets import read_dataset
from rotorvib.models.absorber.parameters import Rotor
from rotorvib.papers.c.broadband import broadband_rows
from rotorvib.papers.c.claims import reproduce
from rotorvib.papers.c.spin import spin_rows
from rotorvib.papers.c.uncertainty import uncertainty_rows

job.start(snakemake.log[0])
producers = snakemake.params.input_producers  # each input dataset's rule and configuration
p = snakemake.params
close = Close.from_config(p.close)
rotor = Rotor(**p.rotor)
data = {name: read_dataset(snakemake.input[name], producers) for name in ("ga", "fr", "mr", "distance", "tr")}
paper = paper_values_of(snakemake.input.paper_values, "C")
rows = reproduce(**data, J=rotor.J, static=rotor.Gamma0 / rotor.k_t, claims=p.claims,
                 close=close, rtol=p.rtol, paper_values=paper)
rows += broadband_rows(read_dataset(snakemake.input.bb, producers))
rows += uncertainty_rows(read_dataset(snakemake.input.uncertainty, producers), paper)
rows += spin_rows(read_dataset(snakemake.input.spin, producers), close)
write_reproduced(rows, snakemake.output[0])
