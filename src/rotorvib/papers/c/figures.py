"""Paper C's figures, drawn from the datasets only (no model is evaluated here).

Each function takes the datasets it needs and ``paper``, the paper's stated values by quantity
id (``data/paper_values.csv``), and returns a matplotlib figure.
"""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from rotorvib.io.coords import labels, pick
from rotorvib.io.plotting import (figure, generation_axis, paper_hline, paper_point, paper_vline,
                                  sensitivity)
from rotorvib.papers.c.claims import undamped_peaks

NONLINEAR = 1  # index of "nonlinear eqs. (8)-(10)" on the model axis of the time responses
CASES = {"none": "no absorber", "single": "single absorber, Den Hartog (stand-in for ref. [8])",
         "dual": "dual absorber, Table 2"}
COLORS = {"none": "C0", "single": "C1", "dual": "C2"}
FLOOR = 1e-18     # where a zero difference is drawn on a log axis


def fig3(tr, paper, t_at: float):
    """Fig 3: rotor without absorber driven at omega_n; the paper's amplitude at ``t_at``."""
    fig, ax = figure()
    t = tr.t.values
    ax.plot(t, tr.theta_none.values[NONLINEAR], lw=0.5, label="theta(t), eqs. (8)-(10)")
    env = tr.theta_none_exact_envelope.values
    ax.plot(t, env, "k:", lw=1.2, label="exact envelope Gamma0 t/(2 J omega_n)")
    ax.plot(t, -env, "k:", lw=1.2)
    paper_point(ax, t_at, paper["fig3_theta_2s"], f"{paper['fig3_theta_2s']} rad at t = {t_at:g} s")
    ax.set(xlabel="time t (s)", ylabel="disk twist theta (rad)",
           title="Fig 3: rotor without absorber at resonance,\nGamma0 cos(omega_n t) from rest")
    ax.legend(loc="upper left")
    return fig


def fig4(tr, paper):
    """Fig 4: no absorber, Den Hartog single absorber, Table 2 dual absorber at resonance."""
    fig, (ax1, ax2) = figure(2, 1, figsize=(7.0, 6.2), sharex=True)
    t = tr.t.values
    labels = {**CASES, "single": f"{CASES['single']}, d = {float(tr.single_d):g} m"}
    for case, label in labels.items():
        ax1.plot(t, tr[f"theta_{case}"].values[NONLINEAR], lw=0.5, color=COLORS[case], label=label)
    for case in ("dual", "single"):
        ax2.plot(t, tr[f"theta_{case}"].values[NONLINEAR], lw=0.5, color=COLORS[case],
                 label=labels[case])
    ax1.set(ylabel="theta (rad)", title="Fig 4: torsional response at omega_n, eqs. (8)-(10)")
    ax2.set(xlabel="time t (s)", ylabel="theta (rad)", title="zoom on the absorbers")
    top = max(np.abs(tr[f"theta_{case}"].values[NONLINEAR]).max() for case in ("dual", "single"))
    ax2.set_ylim(-1.15 * top, 1.8 * top)          # room for the legend above the data
    ax1.legend(loc="upper left")
    ax2.legend(loc="upper right", ncol=2, fontsize=8)
    return fig


def linearisation(tr, paper):
    """Difference between the nonlinear (8)-(10) and the linear (14) responses."""
    fig, ax = figure()
    t = tr.t.values
    for case, label in CASES.items():
        gap = np.abs(np.diff(tr[f"theta_{case}"].values, axis=0)[0])
        if case == "none":       # both sets reduce to J theta'' + k_t theta = Gamma
            label += " (same equations: the integrations' round-off)"
        ax.semilogy(t[1:], np.maximum(gap[1:], FLOOR), lw=0.6, color=COLORS[case], label=label)
    ax.set(xlabel="time t (s)",
           ylabel=f"|theta_nonlinear - theta_linear| (rad; 0 drawn at {FLOOR:g})",
           title="Effect of linearisation: eqs. (8)-(10) against eq. (14)")
    ax.legend(loc="center right", fontsize=8)
    return fig


def fig5(fr, paper):
    """Fig 5: frequency response without absorber, Table 2 undamped and damped, GA optimum."""
    fig, ax = figure(figsize=(7.4, 7.4))      # tall enough for the legend's column below
    w = fr.w.values
    ax.semilogy(w, fr.D_none.values, "k", lw=1, label="no absorber")
    undamped = ax.semilogy(w, fr.D_table2_undamped.values, lw=1, label="Table 2, zero damping")
    poles = undamped_peaks(fr)[1]  # unbounded there: the sampled peaks are where the grid falls
    for x in poles:
        ax.axvline(x, color=undamped[0].get_color(), ls=":", lw=1.2)
    ax.plot([], [], color=undamped[0].get_color(), ls=":", lw=1.2,
            label=f"zero damping: D unbounded at w = {poles[0]:.4f}, {poles[1]:.4f}")
    ax.semilogy(w, fr.D_table2.values, lw=1.6, label="Table 2 (optimum of the paper)")
    ax.semilogy(w, fr.D_table2_printed_det.values, ":", lw=1.2,
                label="Table 2 with the printed det(A)")
    ax.semilogy(w, fr.D_ga.values, lw=1.2, label="optimum found by the GA (this work)")
    paper_vline(ax, paper["undamped_peak_low"], f"undamped peaks w = {paper['undamped_peak_low']}"
                f" and {paper['undamped_peak_high']} (read off Fig 5)")
    ax.axvline(paper["undamped_peak_high"], color="crimson", ls="--", lw=1.2)
    paper_point(ax, 1.0, paper["theta_table2"] / float(fr.static_deflection),
                f"Table 2 objective {paper['theta_table2']:g} rad")
    ax.set(xlabel="frequency ratio w = omega/omega_n", ylabel="D = |Theta| k_t / Gamma0",
           title="Fig 5: frequency response", ylim=(1e-2, 1e4))
    designs = labels(fr, "design")
    for design, color, name in (("table2", "C1", "Table 2"), ("ga", "C3", "GA design")):
        pw, pd = (float(fr[v].isel(design=designs.index(design))) for v in ("peak_w", "peak_D"))
        text = f"{name}'s largest peak over all w: D = {pd:.3g} at w = {pw:.3g}"
        if w[0] <= pw <= w[-1]:
            ax.plot(pw, pd, "v", color=color, ms=7, label=text)
        else:                                    # outside the plotted band: an arrow to it
            edge = w[0] if pw < w[0] else w[-1]
            ax.annotate("", xy=(edge, pd), xytext=(edge + (0.06 if pw < w[0] else -0.06), pd),
                        arrowprops={"arrowstyle": "->", "color": color})
            ax.plot([], [], "v", color=color, label=text + " (outside the band)")
    # one column: two would be wider than the axes, which the layout would narrow to fit them
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1, fontsize=8)
    return fig


def fig6(mr, paper, w_low: float):
    """Fig 6: frequency response for the mass-ratio family under its first construction (the
    reproduction); the paper's claim location ``w_low``."""
    fig, ax = figure()
    construction = labels(mr, "construction")[0]
    mr = pick(mr, construction=construction)
    for mu in mr.mu.values:
        best = np.isclose(mu, paper["mu_opt"])
        ax.plot(mr.w.values, mr.D.sel(mu=mu).values, lw=2.0 if best else 1.0,
                label=f"mu = {mu:g}" + (" (paper's optimum)" if best else ""))
    paper_vline(ax, w_low, f"equal masses better at w = {w_low:g}")
    ax.set(xlabel="frequency ratio w = omega/omega_n", ylabel="D = |Theta| k_t / Gamma0",
           title=f"Fig 6: mass ratio m2/m1 ({construction} construction, rest as Table 2)")
    ax.legend()
    return fig


def distance(ds, paper):
    """The abstract's distance study: D(w) with both absorber sets moved from Table 2's radii."""
    fig, ax = figure()
    for off in ds.offset.values:
        ax.plot(ds.w.values, ds.D.sel(offset=off).values, lw=2.0 if off == 0 else 1.0,
                label=f"{100 * off:+.0f} cm" + (" (Table 2: d1 = 10, d2 = 8 cm)" if off == 0
                                                 else ""))
    ax.set(xlabel="frequency ratio w = omega/omega_n", ylabel="D = |Theta| k_t / Gamma0",
           title="Distance of both absorber sets from the disk centre (rest as Table 2)")
    ax.legend(title="offset of d1 and d2")
    return fig


def spin(ds, paper):
    """Beyond the paper: Table 2's absorber on a spinning rotor -- each set's tuning
    sqrt(omega_a^2 - Omega^2) / omega_n with the comparison's 10 % band around its value at
    rest, D at resonance over the spin, and D(w) at rest and at the realistic spin."""
    fig, (ax1, ax2) = figure(1, 2, figsize=(11.0, 4.4))
    rpm = ds.spin.values * 30 / np.pi
    realistic = float(ds.realistic_spin) * 30 / np.pi
    for j, set_tuning in enumerate(ds.tuning.values, start=1):
        ax1.plot(rpm, set_tuning, lw=1.6 if j == 1 else 1.0, ls="-" if j == 1 else "--",
                 label=f"set {j}: tuning / omega_n")
    rest = float(ds.tuning.values[0, 0])
    ax1.axhspan(0.9 * rest, 1.1 * rest, color="C0", alpha=0.1, label="within 10 % of rest")
    ax1.axvline(realistic, color="0.3", ls=":", label=f"realistic spin, {realistic:.0f} rpm")
    twin = ax1.twinx()
    twin.plot(rpm, ds.D_resonance.values, color="C3", lw=1.2, label="D at resonance (right)")
    twin.set_ylabel("D at w = 1", color="C3")
    ax1.set(xlabel="rotor spin Omega (rpm)", ylabel="absorber tuning / omega_n",
            title="tuning and resonance amplitude over the spin")
    lines = ax1.get_legend_handles_labels()
    more = twin.get_legend_handles_labels()
    ax1.legend(lines[0] + more[0], lines[1] + more[1], fontsize=7, loc="lower left")
    for i, name in enumerate(ds.case_name.values):
        ax2.plot(ds.w.values, ds.D.values[i], lw=1.4, label=str(name))
    ax2.set(xlabel="frequency ratio w = omega/omega_n", ylabel="D = |Theta| k_t / Gamma0",
            yscale="log", title="Table 2's absorber at rest and at the realistic spin")
    ax2.legend(fontsize=8)
    return fig


def fig7(tr, paper):
    """Fig 7: absorber displacements of the Table 2 dual absorber at resonance."""
    fig, ax = figure()
    t = tr.t.values
    for j in (1, 2):
        ax.plot(t, 1e3 * tr[f"s{j}_dual"].values[NONLINEAR], lw=0.5, label=f"absorber set {j}")
    ax.set(xlabel="time t (s)", ylabel="absorber displacement (mm)",
           title="Fig 7: absorber amplitudes at omega_n, Table 2, eqs. (8)-(10)")
    ax.legend(loc="upper right")
    return fig


def ga_convergence(ga, paper):
    """Best and mean objective per generation, with Table 2's value and the paper's."""
    fig, ax = figure()
    g = ga.generation.values
    ax.semilogy(g, ga.best_objective.values, lw=1.6, label="best of generation")
    ax.semilogy(g, ga.mean_objective.values, lw=1.0, label="population mean")
    ax.axhline(float(ga.theta_table2), color="grey", ls="-.",
               label="Table 2 evaluated with eq. (20)")
    paper_hline(ax, paper["theta_ga"], f"objective {paper['theta_ga']:g} rad")
    shown = [*ga.best_objective.values, *ga.mean_objective.values, float(ga.theta_table2),
             paper["theta_ga"]]
    ax.set_ylim(min(shown) / 1.5, max(shown) * 1.5)      # no line on the frame
    ax.set(ylabel="|Theta(omega_n)| (rad)",
           title="Genetic algorithm: convergence of the objective")
    generation_axis(ax)
    ax.legend()
    return fig


def broadband(bb, paper):
    """Beyond the paper: the broadband optimum beside Table 2, the single-frequency optimum and
    Den Hartog's absorber; frequency responses, time responses at resonance, Pareto front."""
    fig, axes = figure(1, 3, figsize=(15.0, 4.8))
    names = [_with_radius(bb, i) for i in range(bb.sizes["design"])]
    ax = axes[0]
    ax.semilogy(bb.w.values, bb.D_none.values, "k", lw=0.8, label="no absorber")
    for i, name in enumerate(names):
        ax.semilogy(bb.w.values, bb.D.values[i], color=f"C{i}", lw=1.2,
                    label=f"{name}: peak {float(bb.peak[i]):.3g}")
    for edge in (float(bb.band_w[0]), float(bb.band_w[-1])):
        ax.axvline(edge, color="0.5", ls="--", lw=0.8,
                   label="band of the objective" if edge == float(bb.band_w[0]) else None)
    ax.set_ylim(0.5, 20 * float(bb.peak.max()))
    ax.set(xlabel="frequency ratio w = omega/omega_n", ylabel="D = |Theta| k_t / Gamma0",
           title="frequency responses, eq. (20)")
    ax.legend(fontsize=7, loc="upper left")
    ax = axes[1]
    t = bb.t.values
    per_period = max(int(round(2 * np.pi / float(bb.omega_n) / (t[1] - t[0]))), 1)
    for i, name in enumerate(names):
        envelope = sliding_window_view(np.abs(bb.theta.values[i]), per_period).max(axis=1)
        ax.plot(t[per_period - 1:], envelope, color=f"C{i}", lw=1.2, label=name)
    ax.set(xlabel="time t (s)", ylabel="largest |theta| over the last period (rad)",
           title="from rest under Gamma0 cos(omega_n t), eq. (14) exactly")
    ax.legend(fontsize=7, loc="upper right")
    ax = axes[2]
    mass = bb.front_added_mass.values
    ax.plot(mass, bb.front_band_peak.values, "o", ms=3, color="C3", label="NSGA-II front (dual)")
    order = np.argsort(mass)
    ax.plot(mass[order], bb.front_den_hartog_peak.values[order], color="C2", lw=1,
            label=f"Den Hartog single absorber, same mass (d = {_radius(bb):g} m)")
    for i, name in enumerate(names):
        ax.plot(float(bb.added_mass[i]), float(bb.band_peak[i]), "s", color=f"C{i}", ms=7,
                mfc="none", mew=1.5, label=name)
    ax.set_yscale("log")
    ax.set(xlabel="added mass 2 (m1 + m2) (kg)", ylabel="largest D over the band",
           title="Pareto front within the bounds of section 4")
    ax.legend(fontsize=7)
    return fig


def _radius(bb) -> float:
    """Radius d of the Den Hartog absorber of the broadband study (its own, chosen in the
    config, paper_c.broadband.den_hartog_d; Fig 4's stand-in has paper_c.den_hartog.d)."""
    keys = [str(k) for k in bb.design_key.values]
    names = [str(n) for n in bb.parameter_name.values]
    return float(bb.parameters.values[keys.index("den_hartog"), names.index("d1")])


def _with_radius(bb, i: int) -> str:
    """A broadband design's name, with the radius where it is Den Hartog's absorber."""
    name = str(bb.design_name.values[i])
    return f"{name} (d = {_radius(bb):g} m)" if str(bb.design_key.values[i]) == "den_hartog" \
        else name


def uncertainty(unc, paper):
    """Beyond the paper: Sobol indices and band of Table 2's objective ``|Theta(omega_n)|``."""
    return sensitivity(unc, {"theta": paper["theta_table2"]},
                       "Table 2's objective with every value within its tolerance")
