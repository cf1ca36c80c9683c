"""Paper B's figures, drawn from the datasets only (no model is evaluated here).

Each function takes its datasets and ``paper`` (the paper's values by quantity id) and returns a
matplotlib figure.  Solid lines: the first kinematics of a dataset (the printed one, i.e. the
reproduction); dashed: the consistent kinematics.
"""

from __future__ import annotations

import numpy as np

from rotorvib.io.coords import labels, pick
from rotorvib.papers.b import beyond_figures
from rotorvib.papers.b.claims import printed_values
from rotorvib.papers.b.curves import faster_share
from rotorvib.io.plotting import (PAPER_STYLE, figure, generation_axis, paper_vline,
                                  sensitivity)

STYLES = {0: "-", 1: "--"}
SYMBOLS = {"eps_bar": "eps/R"}
IC_COLORS = {"IC1": "C0", "IC2": "C1", "IC3": "C2"}


def _kinematics(ds):
    return [str(k) for k in ds.kinematics_name.values]


def stability_map(st, paper):
    """Figs 2-3: shaded stable region of the balanced state, boundary and critical speed."""
    fig, ax = figure()
    y_name = "beta" if "beta" in st.dims else "m_bar"
    W, Y = np.meshgrid(st.omega_bar.values, st[y_name].values)
    state = st.state.values
    ax.contourf(W, Y, state == 1, levels=[0.5, 1.5], colors=["#9ecae1"])
    ax.contour(W, Y, np.where(np.isnan(st.growth_rate.values), 1.0, st.growth_rate.values),
               levels=[0.0], colors="k", linewidths=1.2)
    if (state == 2).any():
        ax.contourf(W, Y, state == 2, levels=[0.5, 1.5], colors=["#d9d9d9"])
    ax.plot(st.critical_speed.values, st[y_name].values, "r:", lw=1.2)
    ax.plot(st.stability_onset.values, st[y_name].values, "k.", ms=3,
            label="onset of stability, located exactly")
    if (state == 3).any():
        ax.plot(W[state == 3], Y[state == 3], "x", color="0.35", ms=3,
                label=f"marginal (|growth rate| <= {float(st.marginal_growth):g})")
    ax.plot([], [], color="#9ecae1", lw=8, label="stable balanced state")
    ax.plot([], [], "k", label="stability boundary (growth rate 0)")
    ax.plot([], [], "r:", label="critical speed sqrt(M/(M + 2m))")
    if (state == 2).any():
        ax.plot([], [], color="#d9d9d9", lw=8, label="no balanced state (m/M < eps/2R)")
    ylabel = "ball damping ratio beta" if y_name == "beta" else "mass ratio m/M"
    ax.set(xlabel="speed ratio omega/omega_n", ylabel=ylabel, title=st.attrs["title"])
    ax.legend(loc="upper right", fontsize=8)
    return fig


def speed_profile(tr, paper):
    """Figs 4-5: speed and angular acceleration of the run-up (eqs 37-38)."""
    fig, (a1, a2) = figure(2, 1, sharex=True, figsize=(7.0, 5.6))
    t = tr.t.values
    sel = t <= 1.0
    a1.plot(t[sel], tr.omega.values[sel])
    a2.plot(t[sel], tr.alpha.values[sel])
    a1.set(ylabel="omega (rad/s)", title="Figs 4-5: run-up profile, eq. (37)")
    a2.set(xlabel="time t (s)", ylabel="alpha = d omega/dt (rad/s^2)")
    return fig


def _run(tr, name):
    return tr.isel(run=[str(n) for n in tr.run_name.values].index(name))


def unbalanced_response(tr, paper):
    """Fig 6: r(t) and the ball angles with beta = 0."""
    fig, (a1, a2) = figure(2, 1, sharex=True, figsize=(7.0, 5.6))
    t = tr.t.values
    for i, kin in enumerate(_kinematics(tr)):
        run = _run(pick(tr, kinematics=kin), "fig6")
        a1.plot(t, 1e3 * run.r.values, STYLES[i], lw=0.8, label=f"r(t), {kin}")
        a2.plot(t, run.phi1.values, STYLES[i], color="C0", lw=0.8, label=f"phi1, {kin}")
        a2.plot(t, run.phi2.values, STYLES[i], color="C1", lw=0.8, label=f"phi2, {kin}")
    a1.set(ylabel="r (mm)", title="Fig 6: beta = 0, no ball damping")
    a2.set(xlabel="time t (s)", ylabel="ball angle (deg)")
    a1.legend(fontsize=8)
    a2.legend(fontsize=8, ncol=2)
    return fig


def envelope_peaks(t, r):
    """Local maxima of r(t): the points of the piecewise-linear envelope used for the balance
    time by the paper's method (the same rule as the compiled analyser)."""
    inner = (r[1:-1] > r[:-2]) & (r[1:-1] >= r[2:])
    return t[1:-1][inner], r[1:-1][inner]


def envelope_response(tr, paper):
    """Fig 7: r(t) with the envelope through its peaks and the balance times."""
    fig, ax = figure()
    t = tr.t.values
    run = _run(pick(tr, kinematics=_kinematics(tr)[0]), "fig7")
    ax.plot(t, 1e3 * run.r.values, lw=0.6, label="r(t)")
    tp, rp = envelope_peaks(t, run.r.values)
    ax.plot(tp, 1e3 * rp, "k-", lw=1.0, label="envelope through the peaks")
    ax.axvline(float(run.envelope_time), color="k", ls=":",
               label=f"envelope balance time {float(run.envelope_time):.2f} s")
    ax.axvline(float(run.balance_time), color="C2", ls="-.",
               label=f"threshold balance time {float(run.balance_time):.2f} s")
    paper_vline(ax, paper["fig7_balance_time"], f"{paper['fig7_balance_time']} s")
    ax.set_yscale("log")
    ax.set(xlabel="time t (s)", ylabel="r (mm)", title="Fig 7: response and envelope")
    ax.legend(fontsize=8)
    return fig


#: Units shown on a figure axis instead of the dataset's: unit -> (shown unit, factor).
DISPLAY_UNITS = {"kg": ("g", 1e3)}


def _axis_label(coord) -> tuple[str, float]:
    """Axis label of a coordinate from its long name and units, and the display factor."""
    units, factor = DISPLAY_UNITS.get(coord.attrs["units"], (coord.attrs["units"], 1.0))
    label = coord.attrs["long_name"]
    return (label if units == "1" else f"{label} ({units})"), factor


def balance_against(study, paper, select=None, marks=None):
    """Figs 8-10, 12-14 and the balance-time studies beyond the paper: balance time against the
    study's axis (its last dimension), one curve per initial condition and kinematics, at the
    indices ``select`` of its other parameters; ``marks`` maps a quantity of the paper to the
    label of a vertical line drawn at its value (e.g. the paper's optimum mass)."""
    select, marks = select or {}, marks or {}
    fig, ax = figure()
    axis = study.balance_time.dims[-1]
    xlabel, factor = _axis_label(study[axis])
    x = study[axis].values * factor
    t_end_marker = np.nanmax(study.balance_time.values) * 1.05
    code = dict(zip(study.outcome.attrs["flag_meanings"].split(),
                    study.outcome.attrs["flag_values"]))
    for i, kin in enumerate(_kinematics(study)):
        g = pick(study, kinematics=kin).isel(select)
        for j, ic in enumerate(str(n) for n in g.ic_name.values):
            y = g.balance_time.isel(ic=j).values
            ax.plot(x, y, STYLES[i], color=IC_COLORS.get(ic), label=f"{ic}, {kin}")
            ends = g.outcome.isel(ic=j).values
            for name, marker in (("not_balanced_by_t_end", "x"), ("non_synchronous_whirl", "^")):
                if (hits := ends == code[name]).any():
                    ax.plot(x[hits], np.full(hits.sum(), t_end_marker), marker,
                            color=IC_COLORS.get(ic), mfc="none")
    shown_unit = DISPLAY_UNITS.get(study[axis].attrs["units"], ("",))[0]
    for quantity, label in marks.items():
        value = factor * paper[quantity]
        paper_vline(ax, value, f"{label} = {value:g} {shown_unit}".rstrip())
    where = "".join(f", {SYMBOLS.get(name, name)} = {float(study[name][index]):g}"
                    for name, index in select.items())
    ax.set(xlabel=xlabel, ylabel="balance time (s)",
           title=f"balance time against {axis}{where}\n(x: not balanced by t_end, "
                 "triangle: locked in a non-synchronous whirl)")
    ax.legend(fontsize=8, ncol=2)
    return fig


def responses(tr, paper, prefix):
    """Figs 11 and 15: r(t) of the runs of one figure."""
    fig, ax = figure()
    t = tr.t.values
    for i, kin in enumerate(_kinematics(tr)):
        sel = pick(tr, kinematics=kin)
        for j, name in enumerate(n for n in (str(v) for v in sel.run_name.values)
                                 if n.startswith(prefix)):
            run = _run(sel, name)
            ax.semilogy(t, 1e3 * run.r.values, STYLES[i], color=f"C{j}", lw=0.7,
                        label=f"{name.split('_', 1)[1]}, {kin}")
    ax.set(xlabel="time t (s)", ylabel="r (mm)",
           title=f"Fig {prefix[3:]}: responses (balance threshold 0.1 mm)")
    ax.legend(fontsize=8, ncol=2)
    return fig


def bearing_forces(tr, paper):
    """Fig 16: bearing force at the Table 2 speed for its three rows, with the paper's peaks."""
    fig, ax = figure()
    t = tr.t.values
    sel = pick(tr, kinematics=_kinematics(tr)[0])
    for j, name in enumerate(n for n in (str(v) for v in sel.run_name.values)
                             if n.startswith("fig16")):
        run = _run(sel, name)
        ax.plot(t, run.force.values, color=f"C{j}", lw=0.7,
                label=f"row {j + 1}: beta = {float(run.run_beta):g}, m = "
                      f"{1e3 * float(run.run_m):g} g")
        ax.axhline(paper[f"table2_fmax_{j + 1}"], color=f"C{j}", ls="--", lw=1)
    ax.plot([], [], "k--", label="paper: maximum forces of Table 2")
    ax.set(xlabel="time t (s)", ylabel="bearing force F = k r + c r' (N)",
           title="Fig 16: bearing force")
    ax.legend(fontsize=8)
    return fig


def ga_convergence(ga, paper):
    """Best balance time per generation of every GA (eps_bar x initial condition)."""
    fig, ax = figure()
    g = pick(ga, kinematics=_kinematics(ga)[0])
    for i, eps in enumerate(g.eps_bar.values):
        for j, ic in enumerate(str(n) for n in g.ic_name.values):
            best = g.best_balance_time.values[i, j]
            never = "" if np.isfinite(best).any() else " (no run balanced by t_end)"
            ax.plot(g.generation.values, best, f"C{i}", ls=["-", "--", ":"][j % 3],
                    label=f"eps/R = {eps:g}, {ic}{never}")
    ax.set(ylabel="best balance time (s)",
           title="Genetic algorithm over (beta, m): convergence\n"
                 "(a gap: no run of that generation balanced by t_end)")
    generation_axis(ax)
    ax.legend(fontsize=7, ncol=3)
    return fig


def calibration(forces, paper, R):
    """Table 2's peak forces against the (unprinted) race radius R."""
    fig, ax = figure()
    f = pick(forces, kinematics=_kinematics(forces)[0])
    for j in range(f.case.size):
        ax.plot(f.R.values, f.force_max.isel(case=j).values, color=f"C{j}",
                label=f"row {j + 1}: beta = {float(f.case_beta[j]):g}, "
                      f"m = {1e3 * float(f.case_mass[j]):g} g")
        ax.axhline(paper[f"table2_fmax_{j + 1}"], **{**PAPER_STYLE, "color": f"C{j}"})
    ax.axvline(R, color="k", ls=":", label=f"R = {R} m (configured)")
    ax.plot([], [], "k--", label="paper: Table 2 maximum forces")
    ax.set(xlabel="race radius R (m)", ylabel="maximum bearing force (N)",
           title="Calibration of the unprinted R against Table 2")
    ax.legend(fontsize=8)
    return fig


def basin(basin, paper, ics):
    """Balance time over all initial ball positions, with the paper's three ICs marked."""
    cases = basin.case.size
    fig, axes = figure(1, cases, figsize=(5.2 * cases, 4.6))
    axes = np.atleast_1d(axes)
    kinematics = _kinematics(basin)[0]
    b = pick(basin, kinematics=kinematics)
    fig.suptitle(f"Balance time over the initial ball positions ({kinematics} kinematics, "
                 f"eps/R = {basin.attrs['eps_bar']:g}, run-up as configured)", fontsize=10)
    vmax = np.nanmax(b.balance_time.values)
    for j, ax in enumerate(axes):
        data = np.ma.masked_invalid(b.balance_time.isel(case=j).values.T)
        mesh = ax.pcolormesh(b.phi1.values, b.phi2.values, data, shading="nearest", vmin=0,
                             vmax=vmax, cmap="viridis")
        mesh.cmap.set_bad("lightgrey")
        for name, (p1, p2) in ics.items():
            ax.plot(p1 % 360, p2 % 360, "r*", ms=11)
            ax.annotate(name, (p1 % 360, p2 % 360), color="r", xytext=(4, 4),
                        textcoords="offset points")
        ax.set(xlabel="phi1(0) (deg)", ylabel="phi2(0) (deg)",
               title=f"beta = {float(b.case_beta[j]):g}, m = {1e3 * float(b.case_mass[j]):g} g")
        fig.colorbar(mesh, ax=ax, label="balance time (s); grey: not balanced")
    return fig


def basin_distribution(basin, paper):
    """Beyond the paper: the distribution of the balance time over initial ball positions
    placed at random (the basin map's uniform grid), per (beta, m) case and kinematics, with
    the paper's initial conditions at their percentiles."""
    fig, ax = figure()
    for j in range(basin.case.size):
        color = f"C{j}"
        case = f"beta = {float(basin.case_beta[j]):g}, m = {1e3 * float(basin.case_mass[j]):g} g"
        for kinematics, ls in zip(_kinematics(basin), ("-", "--")):
            b = pick(basin, kinematics=kinematics).isel(case=j)
            times = np.sort(b.balance_time.values.ravel())
            finite = times[np.isfinite(times)]
            share = np.arange(1, finite.size + 1) / times.size
            ax.step(finite, share, where="post", color=color, ls=ls,
                    label=f"{case}, {kinematics} (balanced by t_end: "
                          f"{finite.size / times.size:.0%})")     # 0 % too: none balanced
            for k, (ic, t) in enumerate(zip(labels(b, "ic"), b.ic_balance_time.values)):
                at = faster_share(times, t)
                ax.plot(t, at, "o", color=color, mfc="white" if ls == "--" else color, ms=5)
                if ls == "-":                        # staggered: close ICs stay readable
                    ax.annotate(f"{ic}: {at:.0%}", (t, at), xytext=(6, -12 - 10 * k),
                                textcoords="offset points", fontsize=7, color=color,
                                arrowprops={"arrowstyle": "-", "color": color, "lw": 0.5})
    ax.set(xlabel="balance time (s)", ylabel="share of initial positions balanced by then",
           ylim=(0, 1.02), title="Balance time over random initial ball positions "
           f"(eps/R = {basin.attrs['eps_bar']:g})\ndots: the paper's ICs")
    ax.legend(fontsize=7, loc="upper left")
    return fig


def kinematics_shift(paper, **studies):
    """Balance time under the consistent against the printed kinematics, every run of the
    balance-time studies (one marker colour per study)."""
    fig, ax = figure()
    kins = _kinematics(next(iter(studies.values())))
    if len(kins) < 2:
        ax.text(0.5, 0.5, "only one kinematics was run", ha="center", transform=ax.transAxes)
        return fig
    for name, study in studies.items():
        a = pick(study, kinematics=kins[0]).balance_time.values.ravel()
        b = pick(study, kinematics=kins[1]).balance_time.values.ravel()
        where = study.attrs["references"].rsplit("; ", 1)[-1]
        ax.plot(a, b, ".", ms=3, label=f"{name} grid ({where})")
    lim = [0, np.nanmax([study.balance_time.max() for study in studies.values()])]
    ax.plot(lim, lim, "k:", lw=1, label="equal")
    ax.set(xlabel=f"balance time, {kins[0]} kinematics (s)",
           ylabel=f"balance time, {kins[1]} kinematics (s)",
           title="How much the kinematic convention moves the balance time")
    ax.legend(fontsize=8)
    return fig


def uncertainty(unc, paper):
    """Beyond the paper: Sobol indices and bands of one case (Table 2's optimum row, Fig 7)."""
    return sensitivity(unc, printed_values(unc, paper),
                       f"{unc.attrs['case_title']} (beta = {unc.attrs['design_beta']:g}, m = "
                       f"{1e3 * unc.attrs['design_mass']:g} g)")


# The figures beyond the paper are drawn by rotorvib.papers.b.beyond_figures; the figure jobs
# look every paper B figure up here.
balance_law, pareto = beyond_figures.balance_law, beyond_figures.pareto
boundaries, ross_check = beyond_figures.boundaries, beyond_figures.ross_check
ga_law, zeta_inversion = beyond_figures.ga_law, beyond_figures.zeta_inversion
design_rule = beyond_figures.design_rule
