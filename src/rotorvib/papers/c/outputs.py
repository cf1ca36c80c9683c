"""Paper C's outputs (:mod:`rotorvib.papers.outputs`): its figures and tables, as functions of the
configuration's ``paper_c`` section."""

from __future__ import annotations

from rotorvib.papers.outputs import figure, table

#: Datasets written that no figure draws (the final files besides the figures' datasets).
UNDRAWN_DATASETS = ("discrepancies",)
#: Markdown notes written beside the tables, not shown in the report.
NOTES = ()


def figures(c: dict) -> dict[str, dict]:
    """Figs 3-7, the GA's convergence and the figures beyond the paper, by name."""
    return {
        "fig3": figure(
            "fig3",
            {"tr": "time_response"},
            "Twist of the rotor without absorber driven at its natural frequency from rest "
            "(nonlinear equations (8)-(10), which reduce to J theta'' + k_t theta = Gamma), with "
            "the exact envelope Gamma0 t/(2 J omega_n) and the paper's stated amplitude (red "
            "star).",
            t_at=c["claims"]["fig3_time"],
        ),
        "fig4": figure(
            "fig4",
            {"tr": "time_response"},
            "Response at resonance without absorber, with a classical single absorber of the same "
            "total mass tuned by Den Hartog's rules (stand-in for the unavailable ref. [8] "
            "absorber) and with the Table 2 dual absorber.",
        ),
        "fig5": figure(
            "fig5",
            {"fr": "frequency_response"},
            "Dimensionless amplitude D = |Theta| k_t/Gamma0 against w = omega/omega_n without "
            "absorber, for Table 2 with zero damping and with its damping, for Table 2 with the "
            "printed determinant, and for the optimum our GA finds; each curve's largest peak "
            "marked, the paper's objective as D (red star).",
        ),
        "fig6": figure(
            "fig6",
            {"mr": "mass_ratio"},
            "Frequency response for mass ratios mu = m2/m1 (k2 = mu k1 keeps set 2 tuned as in "
            "Table 2; other parameters from Table 2).",
            w_low=c["claims"]["fig6_w_low"],
        ),
        "distance": figure(
            "distance",
            {"ds": "distance"},
            "The abstract's study of the absorbers' distance from the disk centre (its figure did "
            "not survive extraction): D(w) for Table 2 with both sets moved by the same offset.",
            items=["Abstract"],
        ),
        "spin": figure(
            "spin",
            {"ds": "spin"},
            "Beyond the paper: Table 2's absorber on a rotor spinning at Omega, which the paper's "
            "model leaves out (springs softened to 2k - m Omega^2): each set's tuning and D at "
            "resonance over the spin, and the frequency response at rest and at a realistic spin.",
            items=["Spin"],
        ),
        "fig7": figure(
            "fig7",
            {"tr": "time_response"},
            "Displacements of absorber sets 1 and 2 of the Table 2 design at resonance (nonlinear "
            "equations).",
        ),
        "ga_convergence": figure(
            "ga_convergence",
            {"ga": "ga"},
            "Convergence of the genetic algorithm (best and mean |Theta(omega_n)| per "
            "generation), with Table 2 evaluated by eq. (20) and the paper's reported objective.",
            items=["Section 4"],
        ),
        "linearisation": figure(
            "linearisation",
            {"tr": "time_response"},
            "Beyond the paper: difference between the nonlinear equations (8)-(10) and the "
            "linear set (14) for the three cases of Fig 4 (the paper linearises without showing "
            "the effect).",
        ),
        "uncertainty": figure(
            "uncertainty",
            {"unc": "uncertainty"},
            "Beyond the paper: how sure Table 2's objective is. Sobol indices (first-order and "
            "total, 95 % bootstrap intervals) of |Theta(omega_n)| with every Table 2 value within "
            "its manufacturing tolerance, their convergence with the sample, and the objective's "
            "distribution with the printed value.",
            items=["Uncertainty"],
        ),
        "broadband": figure(
            "broadband",
            {"bb": "broadband"},
            "Beyond the paper: the absorber optimised for the peak of D over a band around "
            "resonance (NSGA-II, two objectives: that peak and the added mass, within the bounds "
            "of section 4), at no more added mass than Table 2, beside Table 2, the GA optimum of "
            "|Theta(omega_n)| and Den Hartog's single absorber of Table 2's mass: frequency "
            "responses, exact linear time responses from rest at resonance, and the Pareto front "
            "with Den Hartog's absorber of each mass.",
            items=["Broadband absorber"],
        ),
    }


def tables(c: dict) -> dict[str, dict]:
    """The symbolic checks, Table 2 and the broadband designs, by name."""
    return {
        "derivation_checks": table(
            "Equations (1)-(20) re-derived with sympy (Lagrange's equations from the kinetic "
            "and potential energies and the generalised forces) and compared with the "
            "printed ones. A FAIL row gives the difference from the printed equation; "
            "every result downstream uses the derived equations.",
            items=["eq. 20"],
        ),
        "table2": table(
            "The paper's optimum dual absorber (Table 2) beside the optimum our genetic "
            "algorithm finds with the paper's bounds, population and generations, both "
            "evaluated with eq. (20).",
            items=["Section 4"],
        ),
        "broadband": table(
            "Beyond the paper: each absorber design with its parameters (m, k, c, d of "
            "each set), added mass, largest D over the band and over all frequencies, and "
            "its largest |theta| over the last forcing period at resonance.",
            items=["Broadband absorber"],
        ),
    }
