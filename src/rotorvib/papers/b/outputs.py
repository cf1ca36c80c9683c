"""Paper B's outputs (:mod:`rotorvib.papers.outputs`) and the cases its rules hand to their jobs, as
functions of the configuration's ``paper_b`` section: its figures and tables, the rotor setup
every run-up shares, the planes of the stability boundaries, the cases of the uncertainty study
and the sources of the balance-time law."""

from __future__ import annotations

from rotorvib.papers.outputs import figure, table

#: Datasets written that no figure draws (the final files besides the figures' datasets).
UNDRAWN_DATASETS = ("discrepancies", "table1")
#: Markdown notes written beside the tables, not shown in the report.
NOTES = ("kinematics",)
#: The planes of the stability boundaries (beyond the paper): each varies one parameter.
PLANES = ("beta", "m_bar", "zeta")


def setup(b: dict) -> dict:
    """The sections of ``paper_b`` that make a run-up's setup
    (:meth:`rotorvib.papers.b.setup.Setup.from_config`)."""
    return {
        key: b[key] for key in ("machine", "initial_state", "speed", "balance", "marginal_growth")
    }


def uncertain_cases(b: dict, claims=frozenset()) -> dict[str, dict]:
    """The cases of the uncertainty study (beyond the paper), from their sections of
    ``paper_b``: Table 2's optimum row, Fig 7 and Table 1's mean balance time at Table 2's
    speed. Each names the printed values it is set against among ``claims`` (the keys of paper
    B's rows in data/paper_values.csv); Table 1's has one only where its claim row is at this
    speed (found by the configuration fuzzer: at another Table 2 speed there is none)."""
    t2, f7 = b["table2"], b["time_responses"]["fig7"]
    optimum_mass = t2["cases"][-1][1]  # the paper's optimum, also Table 1's at this speed
    table1_key = f"table1_mean_time_{t2['speed']:g}"
    return {
        "table2": {
            "name": "table2",
            "title": "Table 2's optimum row",
            "item": "Table 2",
            "beta": t2["cases"][-1][0],
            "mass": optimum_mass,
            "eps_bar": t2["eps_bar"],
            "phi0_deg": b["initial_conditions"][t2["ic"]],
            "speed": t2["speed"],
            "printed": {"force_max": "table2_fmax_3", "force_decay_time": "table2_decay_3"},
        },
        "fig7": {
            "name": "fig7",
            "title": "Fig 7",
            "item": "Fig 7",
            "beta": f7["beta"],
            "mass": f7["m_bar"] * b["machine"]["M"],
            "eps_bar": f7["eps_bar"],
            "phi0_deg": f7["phi0"],
            "speed": None,
            "printed": {"envelope_time": "fig7_balance_time"},
        },
        "table1": {
            "name": "table1",
            "title": f"Table 1's mean balance time at {t2['speed']:g} rad/s",
            "item": "Table 1",
            "beta": b["table1"]["beta"],
            "mass": optimum_mass,
            "eps_bar": b["table1"]["eps_bar"],
            "ics": list(b["initial_conditions"].values()),
            "speed": t2["speed"],
            "printed": (
                {"balance_time": table1_key} if f"{table1_key}_within_uncertainty" in claims else {}
            ),
        },
    }


def law_sources(b: dict) -> dict[str, tuple[str, dict]]:
    """The balance-time law's sources, ``{source: (dataset, its fixed parameters)}``: every
    balance study of the configuration (its fixed parameters, the run-up's speed), Table 1,
    the basin map and the race-radius calibration (the forces of Table 2's rows over R; the
    runs at the configured R are Table 2's)."""
    return {
        **{
            f"balance_{name}": (f"balance_{name}", {**study["fixed"], "speed": b["speed"]["omega"]})
            for name, study in b["balance_studies"].items()
        },
        "table1": ("table1", {"beta": b["table1"]["beta"], "eps_bar": b["table1"]["eps_bar"]}),
        "basin": ("basin", {"eps_bar": b["basin"]["eps_bar"], "speed": b["speed"]["omega"]}),
        "calibration": (
            "forces",
            {"eps_bar": b["table2"]["eps_bar"], "speed": b["table2"]["speed"],
             "ic": b["table2"]["ic"]},
        ),
    }


def tables(b: dict) -> dict[str, dict]:
    """The symbolic checks and Tables 1-2, by name."""
    return {
        "derivation_checks": table(
            "Equations (2)-(34) re-derived with sympy from the kinetic energy (4), the "
            "potential (5) and the Rayleigh function (6), each compared with the printed "
            "one under three conventions for the disk angle: exactly w(t) t, the paper's "
            "(the w'' t term dropped) and the consistent one (rate w). A FAIL row gives the "
            "difference from the printed equation."
        ),
        "table1": table(
            "Optimum ball mass (least mean balance time over the three initial conditions "
            "of eq. 39) and that mean balance time against the operating speed, beside "
            "the paper's values.",
            items=["eq. 41"],
        ),
        "table2": table(
            "Maximum bearing force and its decay time for the paper's three (beta, m) "
            "cases, with the race radius R inferred from the paper's forces (Fig "
            "calibration R), beside the paper's values."
        ),
    }


def figures(b: dict) -> dict[str, dict]:
    """Figs 2-16, the GA's convergence and the figures beyond the paper, by name."""
    return {
        "fig2": figure(
            "stability_map",
            {"st": "stability_fig2"},
            "Stability of the balanced state in the (beta, speed) plane from the eigenvalues of "
            "the linearised equations, with the critical speed.",
        ),
        "fig3": figure(
            "stability_map",
            {"st": "stability_fig3"},
            "Stability of the balanced state in the (ball mass, speed) plane, with the critical "
            "speed and the existence bound of the balanced state.",
        ),
        "fig4_5": figure(
            "speed_profile",
            {"tr": "time_responses"},
            "The run-up speed profile of eq. (37) and its angular acceleration.",
        ),
        "fig6": figure(
            "unbalanced_response",
            {"tr": "time_responses"},
            "Rotor amplitude r(t) without ball damping (beta = 0).",
        ),
        "fig7": figure(
            "envelope_response",
            {"tr": "time_responses"},
            "Rotor amplitude r(t) of the paper's Fig 7 case with the envelope through its peaks, "
            "the balance threshold and the balance time.",
        ),
        **{
            f"fig{number}": figure(
                "balance_against",
                {"study": "balance_beta"},
                f"Balance time against the ball-damping ratio beta for the three initial ball "
                f"positions, at the {rank} unbalance eps_bar of the study.",
                select={"eps_bar": index},
            )
            for index, (number, rank) in enumerate(((8, "first"), (9, "second"), (10, "third")))
        },
        "fig11": figure(
            "responses",
            {"tr": "time_responses"},
            "Rotor amplitude r(t) for three ball-damping ratios beta.",
            prefix="fig11",
        ),
        **{
            f"fig{number}": figure(
                "balance_against",
                {"study": "balance_mass"},
                f"Balance time against the ball mass m for the three initial ball positions, at "
                f"the {rank} unbalance eps_bar of the study, with the optimum mass marked.",
                select={"eps_bar": index},
                marks={"m_opt": "optimum m"},
            )
            for index, (number, rank) in enumerate(((12, "first"), (13, "second"), (14, "third")))
        },
        "fig15": figure(
            "responses",
            {"tr": "time_responses"},
            "Rotor amplitude r(t) for three ball masses.",
            prefix="fig15",
        ),
        "fig16": figure(
            "bearing_forces",
            {"tr": "time_responses"},
            "Bearing force against time for the three (beta, m) cases of Table 2.",
        ),
        "balance_eps_bar": figure(
            "balance_against",
            {"study": "balance_eps_bar"},
            "Beyond the paper: balance time against the unbalance eps_bar for the three initial "
            "ball positions.",
        ),
        "ga_convergence": figure(
            "ga_convergence",
            {"ga": "ga"},
            "Convergence of the genetic algorithm of section 9 (best balance time per generation) "
            "for each unbalance and initial condition, with its optimum (beta, m).",
            items=["GA", "Section 9"],
        ),
        "calibration_R": figure(
            "calibration",
            {"forces": "forces"},
            "Beyond the paper: the race radius R, which the paper does not state: the Table 2 "
            "peak forces computed "
            "over a range of R, and the R that fits them.",
            items=["Table 2"],
            R=b["machine"]["R"],
        ),
        "basin": figure(
            "basin",
            {"basin": "basin"},
            "Beyond the paper: balance time over all initial positions of the two balls, with "
            "the paper's three initial conditions marked.",
            ics=b["initial_conditions"],
        ),
        "basin_distribution": figure(
            "basin_distribution",
            {"basin": "basin"},
            "Beyond the paper: the balance time as a distribution over initial ball positions "
            "placed at random (the basin map's uniform grid), with the share of positions "
            "balanced by each time, and where the paper's three initial conditions fall in it.",
            items=["Basin"],
        ),
        **{
            f"uncertainty_{case}": figure(
                "uncertainty",
                {"unc": f"uncertainty_{case}"},
                f"Beyond the paper: how sure {spec['title']} is. Sobol indices (first-order and "
                "total, 95 % bootstrap intervals) of its peak bearing force, force decay time, "
                "balance times and whether it balances, over the uncertain inputs (ranges in the "
                "config), their convergence with the sample, and each quantity's distribution "
                "with the printed value.",
                items=[f"Uncertainty of {spec['item']}"],
            )
            for case, spec in uncertain_cases(b).items()
        },
        "boundaries": figure(
            "boundaries",
            {
                "beta": "boundary_beta",
                "m_bar": "boundary_m_bar",
                "zeta": "boundary_zeta",
                "st2": "stability_fig2",
                "st3": "stability_fig3",
            },
            "Beyond the paper: the onset of stability of the balanced state traced by "
            "pseudo-arclength continuation far beyond the grids of Figs 2-3, in (beta, omega_bar), "
            "(m_bar, omega_bar) and (zeta, omega_bar) (stable to the right of the boundary), "
            "with the critical speed and the grids' exact onsets.",
            items=["Stability boundaries"],
        ),
        "ross_check": figure(
            "ross_check",
            {"ross": "ross_check"},
            "Beyond the paper: paper B's rotor without balls (a Jeffcott rotor) by the closed "
            "form, the package's engine (balls of negligible mass) and ROSS, the open "
            "rotordynamics code "
            "(a stiff, nearly massless shaft with the disk at its middle): steady unbalance "
            "response over the speed and the whirl through paper B's run-up. ROSS checks the "
            "rotor's lateral dynamics, not the balls nor paper C's torsional model.",
        ),
        "balance_law": figure(
            "balance_law",
            {"law": "balance_law"},
            "Beyond the paper: the balance time by the law t_pk + ln(F_pk / (k r_thr)) / sigma "
            "(the peak bearing force of the critical-speed passage and the slowest decay rate "
            "of the balanced state) against the integration, on every balanced run of the "
            "balance studies, "
            "Tables 1-2 and the basin map, and the distribution of its relative error.",
            items=["Balance-time law"],
        ),
        "design_rule": figure(
            "design_rule",
            {"design": "design_rule", "law": "balance_law", "ga": "ga"},
            "Beyond the paper: the balance time predicted without integrating (the "
            "critical-speed passage of balls held at their initial angles, Duhamel's integral) "
            "against the integration, its error beside the law's with the integrated passage, "
            "and the design rule on paper B's machine under a user's kinematics: the mean "
            "predicted balance time over the ball mass and damping, the best predicted designs "
            "verified by integration, the recommendation, the integrated check grid's best and "
            "the GA's optima.",
            items=["Balance-time prediction"],
        ),
        "zeta_inversion": figure(
            "zeta_inversion",
            {"zeta_inversion": "zeta_inversion"},
            "Beyond the paper: the support damping zeta, which the paper states for Figs 2-3 and "
            "8-14 only: the printed times of Fig 7, Table 1 and Table 2 rerun over zeta under each "
            "kinematics and balance-time definition, and the zetas at which each is reproduced.",
            items=["Support damping"],
            zeta=b["machine"]["zeta"],
        ),
        "ga_law": figure(
            "ga_law",
            {"ga_law": "ga_law"},
            "Beyond the paper: what the GA's optimum is. After the run-up the whirl decays on a "
            "line of the log scale, r ~ A exp(-sigma (t - t_ramp)); around each GA optimum (beta "
            "and m moved by the config's step) the change of the balance time splits into what the "
            "passage leaves (the amplitude A) and how fast it decays (sigma).",
            items=["GA optimum law"],
        ),
        **{
            ("pareto" if kin == b["kinematics"][0] else f"pareto_{kin}"): figure(
                "pareto",
                {"pareto": f"pareto_{kin}"},
                "Beyond the paper: the ball damping and mass chosen for two goals at once by "
                "NSGA-II, the mean balance time and the worst peak bearing force over a fixed "
                "sample of random initial ball positions, at Table 2's speed and eccentricity; "
                "Table 2's rows (the last is the paper's GA optimum) evaluated on the same "
                "sample; "
                f"{kin} kinematics"
                + (
                    "."
                    if kin == b["kinematics"][0]
                    else " (its comparison row is under the "
                    f"{b['kinematics'][0]} kinematics' figure)."
                ),
                # the comparison row, which quotes every kinematics, under the first figure only
                items=["Pareto"] if kin == b["kinematics"][0] else [],
            )
            for kin in b["kinematics"]
        },
        "kinematics": figure(
            "kinematics_shift",
            {"beta": "balance_beta", "mass": "balance_mass"},
            "Beyond the paper: how much the balance times of Figs 8-14 change between the "
            "printed and the consistent kinematics, and the paper's conclusion that ball mass "
            "matters more than damping.",
            items=["Section 10"],
        ),
    }
