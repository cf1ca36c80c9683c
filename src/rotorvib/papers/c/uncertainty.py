"""Beyond paper C: how sure is the objective of Table 2?

``|Theta(omega_n)|`` of eq. (20) at Table 2 depends on eight design values that a built absorber
meets only within a manufacturing tolerance.  Each value is drawn uniformly within a relative
tolerance of its printed value (config); Sobol indices say which drives the objective, and its
5-95 % band says whether the printed 7.5e-4 rad lies within that uncertainty of the reproduction.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.comparison.reproduced import Reproduced, within_band
from rotorvib.methods.bands import band_statement
from rotorvib.methods.sensitivity import problem, sample, study_dataset
from rotorvib.models.absorber.frequency_response import theta_eq20
from rotorvib.models.absorber.parameters import DUAL_NAMES, Rotor, dual_to_vector

QUANTITIES = {"theta": "rad"}


def uncertainty_dataset(rotor: Rotor, table2, *, tolerance: float, n_base: int, convergence,
                        resamples: int, seed: int) -> xr.Dataset:
    """Sobol indices and band of ``|Theta(omega_n)|`` with every Table 2 value uniform within
    ``+/- tolerance`` (relative) of its printed value."""
    nominal_x = dual_to_vector(table2)
    spec = problem({name: (v * (1 - tolerance), v * (1 + tolerance))
                    for name, v in zip(DUAL_NAMES, nominal_x)})
    x = sample(spec, n_base, seed)

    def outputs(designs):
        return {"theta": np.abs(theta_eq20(rotor, designs, rotor.omega_n))}

    nominal = {q: float(v[0]) for q, v in outputs(nominal_x[None]).items()}
    ds = study_dataset(spec, x, outputs(x), nominal, QUANTITIES, n_bases=convergence,
                       resamples=resamples, seed=seed)
    return ds.assign_attrs(
        title="Paper C, beyond the paper: uncertainty of Table 2's objective",
        summary=f"Sobol indices ({n_base} base points) and 5-95 % bands of |Theta(omega_n)| "
                f"with each Table 2 value within +/- {tolerance:.0%}",
        references="Paper C: dual dynamic vibration absorber; eq. (20), Table 2")


def uncertainty_rows(ds: xr.Dataset, paper: dict) -> list[Reproduced]:
    """Is the printed objective of Table 2 within manufacturing uncertainty of its
    reproduction?"""
    margin, text = band_statement(ds, "theta", paper["theta_table2"])
    return [Reproduced.claim("C", "theta_table2_within_uncertainty", within_band(ds, "theta", margin),
                             f"printed {text}",
                             choices=("paper_c.uncertainty.tolerance (the manufacturing "
                                      "tolerance of each Table 2 value, chosen)",
                                      "paper_c.uncertainty.n_base (the sample, chosen)"))]
