"""Rules b_balance_beta / b_balance_mass: balance time over beta (Figs 8-10) or ball mass
(Figs 12-14) for every eps_bar and initial condition, under each kinematics."""

import sys

import numpy as np

from rotorvib.abb.studies import Setup, balance_grid_dataset
from rotorvib.abb.simulate import use_threads
from rotorvib.datasets import Provenance, write_dataset

sys.stderr = open(snakemake.log[0], "w", buffering=1)
use_threads(snakemake.threads)
p = snakemake.params
g = p.grids
axis = snakemake.wildcards.axis
values = np.linspace(g[axis]["min"], g[axis]["max"], g[axis]["n"])
fixed = ({"m": g["m_bar_for_beta"] * p.setup["machine"]["M"]} if axis == "beta"
         else {"beta": g["beta_for_mass"]})
ds = balance_grid_dataset(Setup.from_config(**p.setup), kinematics=p.kinematics,
                          eps_bars=g["eps_bar"], ics=p.ics, axis=axis, values=values, **fixed)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, dict(p.items())))
