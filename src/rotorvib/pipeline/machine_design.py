"""The design rule for a user's machine, from the command line:
``python -m rotorvib.pipeline.machine_design MACHINE.yaml`` (:func:`main`).  The rule itself is
:mod:`rotorvib.papers.b.design`; this module reads and checks the configuration as the workflow
does (:mod:`rotorvib.pipeline.config`) and prints the answer."""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path

import numpy as np

from rotorvib.io.coords import grid
from rotorvib.models.balancer.outcomes import OUTCOME_TEXT
from rotorvib.papers.b.design import design_rule
from rotorvib.papers.b.setup import Setup
from rotorvib.pipeline.config import ConfigError, check_files

#: The checkout this package runs from (``src/rotorvib/pipeline/`` below it): its configuration
#: and schema are the defaults, whatever the working directory.
CHECKOUT = Path(__file__).resolve().parents[3]


def main(argv=None) -> int:
    """``python -m rotorvib.pipeline.machine_design [--base CONFIG] [--schema SCHEMA]
    [--machine NAME] MACHINE.yaml...``: the design rule for your machine. The files override
    the base configuration's ``paper_b`` keys (``machine``, ``speed``,
    ``initial_conditions``, ``design_rule``, ...) and are checked as the workflow checks its
    own (a bad or out-of-range value names its key, before anything runs); the rule then
    runs under each of ``design_rule.kinematics`` on each machine of
    ``design_rule.machines`` and prints the recommendation, its predicted and integrated
    times, how each initial condition's run ends and what it cost."""
    parser = argparse.ArgumentParser(prog="python -m rotorvib.pipeline.machine_design",
                                     description="The ball mass and damping for a machine: "
                                                 "predicted, then verified by integration.")
    parser.add_argument("--base", default=str(CHECKOUT / "config/config.yaml"))
    parser.add_argument("--schema", default=str(CHECKOUT / "config/schema.yaml"))
    parser.add_argument("--machine", action="append", default=None,
                        help="a machine of design_rule.machines (all unless given; repeatable)")
    parser.add_argument("files", nargs="+", help="YAML files of paper_b keys for your machine")
    args = parser.parse_args(argv)
    try:
        config = check_files([args.base, *args.files], args.schema)
    except ConfigError as error:
        print(error)
        return 1
    b = config["paper_b"]
    rule, ics = b["design_rule"], {n: b["initial_conditions"][n] for n in b["design_rule"]["ics"]}
    setup = Setup.from_paper_b(b)
    masses, betas = grid(rule["mass"]), grid(rule["beta"])
    if unknown := set(args.machine or ()) - set(rule["machines"]):
        print(f"--machine {sorted(unknown)}: not in design_rule.machines "
              f"{sorted(rule['machines'])}")
        return 1
    print(f"machine M = {setup.M:g} kg, k = {setup.k:g} N/m, R = {setup.R:g} m; screened: ball "
          f"mass {masses[0]:g}-{masses[-1]:g} kg, beta {betas[0]:g}-{betas[-1]:g} "
          f"({masses.size} x {betas.size}); the recommendation is integrated, not extrapolated")
    for name in args.machine or rule["machines"]:
        machine = rule["machines"][name]
        here = replace(setup, zeta=machine["zeta"])
        for kin in rule["kinematics"]:
            head = (f"{name} (zeta {machine['zeta']:g}, eps_bar {machine['eps_bar']:g}, "
                    f"{machine['speed']:g} rad/s), {kin} kinematics:")
            try:
                r = design_rule(here, masses=masses, betas=betas, eps_bar=machine["eps_bar"],
                                phi0_deg=list(ics.values()), kinematics=kin,
                                neutral=b["marginal_growth"],
                                share=b["balance_law"]["whirl_share"], verify=rule["verify"],
                                mass_margin=rule["mass_margin"], speed=machine["speed"])
            except ValueError as error:
                print(f"{head} {error}")
                continue
            if not np.isfinite(r.time):
                print(f"{head} none of the {len(r.candidates)} designs integrated balances "
                      f"from every initial condition ({r.seconds:.1f} s)")
                continue
            chosen = (r.candidates == (r.mass, r.beta)).all(axis=1)
            ends = r.verified_outcome[chosen][0]
            print(f"{head} m = {1e3 * r.mass:.4g} g, beta = {r.beta:.3g}: {r.time:.3g} s "
                  f"integrated ({r.predicted:.3g} s predicted); "
                  + ", ".join(f"{ic} {OUTCOME_TEXT[int(e)]}" for ic, e in zip(ics, ends))
                  + f"; {r.verified_time.size} run-ups, {r.seconds:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
