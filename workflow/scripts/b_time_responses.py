"""Rule b_time_responses: r(t), ball angles and bearing force of Figs 4-7, 11, 15, 16."""

import sys

from rotorvib.abb.studies import Setup, time_response_dataset
from rotorvib.datasets import Provenance, write_dataset

sys.stderr = open(snakemake.log[0], "w", buffering=1)
p = snakemake.params
tr, t2 = p.responses, p.table2
omega = p.setup["speed"]["omega"]
M = p.setup["machine"]["M"]
runs = {}
for fig in ("fig6", "fig7"):
    spec = tr[fig]
    runs[fig] = dict(beta=spec["beta"], m=spec["m_bar"] * M, eps_bar=spec["eps_bar"],
                     phi0=spec["phi0"], speed=omega)
for beta in tr["fig11"]["betas"]:
    spec = tr["fig11"]
    runs[f"fig11_beta{beta:g}"] = dict(beta=beta, m=spec["m_bar"] * M, eps_bar=spec["eps_bar"],
                                       phi0=p.ics[spec["ic"]], speed=omega)
for mass in tr["fig15"]["masses"]:
    spec = tr["fig15"]
    runs[f"fig15_m{mass:g}"] = dict(beta=spec["beta"], m=mass, eps_bar=spec["eps_bar"],
                                    phi0=p.ics[spec["ic"]], speed=omega)
for row, (beta, mass) in enumerate(t2["cases"], start=1):
    runs[f"fig16_row{row}"] = dict(beta=beta, m=mass, eps_bar=t2["eps_bar"],
                                   phi0=p.ics[t2["ic"]], speed=t2["speed"])
ds = time_response_dataset(Setup.from_config(**p.setup), kinematics=p.kinematics, runs=runs)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, dict(p.items())))
