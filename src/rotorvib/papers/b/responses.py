"""Paper B's time responses: sampled r(t), ball angles and bearing force of the named runs of
Figs 4-7, 11, 15 and 16."""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.io.coords import label_coord
from rotorvib.models.balancer import layout
from rotorvib.models.balancer.kinematics import profile_speed
from rotorvib.models.balancer.simulate import run
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import KINEMATICS_LONG_NAME, Setup
from rotorvib.papers.b.studies import metric_attrs


def figure_runs(responses: dict, table2: dict, ics: dict, omega: float, M: float) -> dict:
    """The named runs of Figs 6-7, 11, 15 and 16 from the ``time_responses`` and ``table2``
    config sections: name -> ``dict(beta, m, eps_bar, phi0, speed)``."""
    runs = {}
    for fig in ("fig6", "fig7"):
        spec = responses[fig]
        runs[fig] = dict(beta=spec["beta"], m=spec["m_bar"] * M, eps_bar=spec["eps_bar"],
                         phi0=spec["phi0"], speed=omega)
    spec = responses["fig11"]
    for beta in spec["betas"]:
        runs[f"fig11_beta{beta:g}"] = dict(beta=beta, m=spec["m_bar"] * M,
                                           eps_bar=spec["eps_bar"], phi0=ics[spec["ic"]],
                                           speed=omega)
    spec = responses["fig15"]
    for mass in spec["masses"]:
        runs[f"fig15_m{mass:g}"] = dict(beta=spec["beta"], m=mass, eps_bar=spec["eps_bar"],
                                        phi0=ics[spec["ic"]], speed=omega)
    for row, (beta, mass) in enumerate(table2["cases"], start=1):
        runs[f"fig16_row{row}"] = dict(beta=beta, m=mass, eps_bar=table2["eps_bar"],
                                       phi0=ics[table2["ic"]], speed=table2["speed"])
    return runs


def time_response_dataset(setup: Setup, *, kinematics, runs: dict) -> xr.Dataset:
    """Sampled r(t), ball angles and bearing force of named runs (Figs 4-7, 11, 15, 16).

    ``runs`` maps a name to ``dict(beta, m, eps_bar, phi0, speed)``."""
    t = setup.criterion.times
    names = list(runs)
    shape = (len(kinematics), len(names), len(t))
    r, phi1, phi2, force = (np.empty(shape) for _ in range(4))
    bal, env = np.empty(shape[:2]), np.empty(shape[:2])
    for i, kin in enumerate(kinematics):
        for j, name in enumerate(names):
            spec = runs[name]
            b = setup.balancer(mass=spec["m"], eps_bar=spec["eps_bar"], beta=spec["beta"])
            p, y0 = setup.run_inputs(mass=spec["m"], eps_bar=spec["eps_bar"], beta=spec["beta"],
                                     phi0_deg=spec["phi0"], kinematics=kin, speed=spec["speed"])
            traj = run(layout.FIXED, p, y0, setup.criterion, store=True, **setup.tolerances)
            r[i, j], force[i, j] = traj.r, traj.bearing_force(b.k, b.c)
            phi1[i, j], phi2[i, j] = np.degrees(traj.y[:, 2]), np.degrees(traj.y[:, 3])
            bal[i, j], env[i, j] = traj.result.balance_time, traj.result.envelope_time
    speed = profile_speed(setup.profile("consistent"), t)
    dims = ("kinematics", "run", "t")
    spec_var = {key: ("run", np.array([runs[nm][key] for nm in names], float),
                      {"long_name": long_name, "units": units})
                for key, long_name, units in (("beta", "ball damping ratio beta", "1"),
                                              ("m", "ball mass", "kg"),
                                              ("eps_bar", "eccentricity ratio eps/R", "1"),
                                              ("speed", "operating speed", "rad s-1"))}
    return xr.Dataset(
        {"r": (dims, r, {"long_name": "whirl radius of the geometric centre", "units": "m"}),
         "phi1": (dims, phi1, {"long_name": "angle of ball 1 on the disk", "units": "degree"}),
         "phi2": (dims, phi2, {"long_name": "angle of ball 2 on the disk", "units": "degree"}),
         "force": (dims, force, {"long_name": "bearing force F = k r + c r' (eq. 40)",
                                 "units": "N"}),
         "balance_time": (dims[:2], bal, metric_attrs("balance_time")),
         "envelope_time": (dims[:2], env, metric_attrs("envelope_time")),
         "omega": ("t", speed[0], {"long_name": "disk speed of the run-up at the configured "
                                                "operating speed (eq. 37)", "units": "rad s-1"}),
         "alpha": ("t", speed[1], {"long_name": "angular acceleration d omega/dt (eq. 38)",
                                   "units": "rad s-2"}),
         **{f"run_{k}": v for k, v in spec_var.items()}},
        coords={**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
                **label_coord("run", names, "named run (figure)"),
                "t": ("t", t, {"long_name": "time", "units": "s"})},
        attrs=dataset_attrs("time responses", "r(t), ball angles and bearing force of the runs "
                            "of Figs 4-7, 11, 15, 16", "Figs 4-7, 11, 15, 16"),
    )
