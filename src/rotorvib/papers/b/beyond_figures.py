"""Paper B's figures beyond the paper: the balance-time law, the whirl around the GA's optima,
the Pareto front, the stability boundaries by continuation and the rotor without balls against
ROSS, drawn from the datasets only (exposed to the figure jobs by
:mod:`rotorvib.papers.b.figures`)."""

from __future__ import annotations

import numpy as np

from rotorvib.io.coords import labels
from rotorvib.io.plotting import figure
from rotorvib.papers.b.boundary_limits import approach_coefficient, lowest_beta


def balance_law(law, paper):
    """Beyond the paper: the balance-time law against the integration, each balanced run a
    point (colour: study), and the distribution of the relative error with its median and
    90th percentile; the rate is that of the slowest mode carrying the law's whirl share (the
    dataset's first)."""
    law = law.isel(share=0) if "share" in law.dims else law
    errors = law.relative_error.values
    fig, (ax1, ax2) = figure(1, 2, figsize=(11.0, 4.6))
    ax1.set(xlabel="balance time, integration (s)", ylabel="balance time, law (s)",
            title="t_pk + ln(F_pk / (k r_thr)) / sigma,\nsigma of the slowest mode carrying "
                  "the whirl")
    ax2.set(xlabel="relative error of the law (%)", ylabel="runs",
            title="error of the law over the balanced runs")
    if not np.isfinite(errors).any():    # e.g. a support without damping, a huge threshold
        why = ("no run balanced by t_end" if not np.isfinite(law.balance_time.values).any()
               else "the law predicts none of the balanced runs")
        for ax in (ax1, ax2):
            ax.text(0.5, 0.5, f"{why}:\nno balance time to compare with", ha="center",
                    va="center", transform=ax.transAxes)
            ax.set(xticks=[], yticks=[])
        return fig
    for i, source in enumerate(dict.fromkeys(law.source.values)):
        sel = law.source.values == source
        ax1.plot(law.balance_time.values[sel], law.predicted.values[sel], ".", ms=2.5,
                 color=f"C{i}", alpha=0.5, label=f"{source} ({sel.sum()} runs)")
    span = [float(np.nanmin(law.balance_time)), float(np.nanmax(law.balance_time))]
    ax1.plot(span, span, "k", lw=1, label="law = integration")
    ax1.legend(fontsize=7, markerscale=3)
    shown = errors[np.isfinite(errors)]
    ax2.hist(100 * shown, bins=80, color="0.6", label=f"{shown.size} balanced runs")
    for q, style in ((50, "-"), (90, "--")):
        value = 100 * np.percentile(np.abs(shown), q)
        ax2.axvline(value, color="C3", ls=style, lw=1.2, label=f"|error| {q}th percentile: "
                                                               f"{value:.1f} %")
        ax2.axvline(-value, color="C3", ls=style, lw=1.2)
    ax2.legend(fontsize=7)
    return fig


def design_rule(design, law, ga, paper):
    """Beyond the paper: the closed-form law's relative errors beside the integrated passage's
    over every balanced run (medians and 90th percentiles marked), and, on paper B's machine
    under the rule's first kinematics (a user's), the map of the mean predicted balance time
    over (beta, m) with the verified candidates, the recommendation, the check grid's
    integrated best and the GA's optima at that eccentricity and kinematics."""
    fig, (ax1, ax2) = figure(1, 2, figsize=(12.0, 4.8))
    closed = law.relative_error_closed.values
    integrated = law.relative_error.values
    integrated = integrated[0] if integrated.ndim == 2 else integrated
    bins = np.linspace(-100, 150, 101)
    for i, (errors, name) in enumerate(((integrated, "passage integrated"),
                                        (closed, "passage of frozen balls, not integrated"))):
        shown = errors[np.isfinite(errors)]
        if not shown.size:
            continue
        med, p90 = (100 * np.percentile(np.abs(shown), q) for q in (50, 90))
        ax1.hist(np.clip(100 * shown, bins[0], bins[-1]), bins=bins, histtype="step", lw=1.4,
                 color=f"C{i}", label=f"{name}: |error| median {med:.1f} %, 90th pct. "
                                      f"{p90:.1f} % ({shown.size} runs)")
    ax1.set(xlabel="relative error of the predicted balance time (%)", ylabel="runs",
            title="balance time t_pk + ln(F_pk / (k r_thr)) / σ\nagainst the integration")
    ax1.legend(fontsize=7, loc="upper right")
    d = design.isel(machine=0, kinematics=0)
    kinematics, eps_bar = str(d.kinematics.values), float(d.eps_bar_of_machine)
    beta, mass = design.beta.values, 1e3 * design.mass.values
    shading = ax2.pcolormesh(beta, mass, d.mean_time.values, shading="nearest", cmap="viridis")
    fig.colorbar(shading, ax=ax2, label="mean predicted balance time (s)")
    masses = np.unique(d.candidate_mass.values[np.isfinite(d.candidate_mass.values)])
    ax2.plot(d.candidate_beta.values, 1e3 * d.candidate_mass.values, "x", color="0.4", ms=5,
             label=f"integrated: the {masses.size} masses of least predicted time "
                   f"({', '.join(f'{1e3 * m:.3g}' for m in masses)} g), every β")
    check = d.check_time.values
    means = np.where(np.isfinite(check).all(axis=-1), check.mean(axis=-1), np.nan)
    if np.isfinite(means).any():
        i, j = np.unravel_index(np.nanargmin(means), means.shape)
        ax2.plot(float(d.check_beta[j]), 1e3 * float(d.check_mass[i]), "s", mfc="none",
                 mec="C1", ms=11, mew=2, label=f"check grid's best: {means[i, j]:.2f} s "
                                               "integrated")
    if np.isfinite(float(d.recommended_time)):
        ax2.plot(float(d.recommended_beta), 1e3 * float(d.recommended_mass), "*", color="C3",
                 ms=14, mec="w", label=f"recommended: {float(d.recommended_time):.2f} s "
                                       f"integrated ({float(d.recommended_predicted):.2f} s "
                                       "predicted)")
    else:
        ax2.plot([], [], " ", label="recommended: none (no candidate balances from every "
                                    "initial condition)")
    at = (ga.kinematics_name == kinematics).values
    if at.any() and eps_bar in ga.eps_bar.values:
        opt = ga.isel(kinematics=int(np.flatnonzero(at)[0])).sel(eps_bar=eps_bar)
        ax2.plot(opt.beta_opt.values, 1e3 * opt.mass_opt.values, "o", mfc="none", mec="C2",
                 ms=8, mew=1.5, label="GA optima, one per initial condition (integrated)")
    ax2.set(xlabel="ball damping ratio β", ylabel="ball mass m (g)",
            title=f"design rule on {d.machine.values}: ε̄ = {eps_bar:g}, "
                  f"{float(d.speed_of_machine):g} rad/s, {kinematics} kinematics,\nmean over "
                  + ", ".join(design.ic_name.values))
    ax2.legend(fontsize=7, loc="upper right")
    return fig


def pareto(pareto, paper):
    """Beyond the paper: the front of mean balance time against worst peak bearing force, with
    Table 2's rows, and where the front lies in (beta, m)."""
    fig, (ax1, ax2) = figure(1, 2, figsize=(12.0, 4.8))
    order = np.argsort(pareto.front_force.values)
    t, f = pareto.front_balance_time.values[order], pareto.front_force.values[order]
    censored = int((pareto.front_censored > 0).sum())
    ax1.plot(f, t, "o-", color="C0", ms=4, lw=0.8,
             label="NSGA-II front" + (f" ({censored} designs with a run not balanced by "
                                      "t_end: no mean, not drawn)" if censored else ""))
    for i, row in enumerate(pareto.design.values):
        label = (f"Table 2 row {int(row)}: beta = {float(pareto.design_beta[i]):g}, "
                 f"m = {1e3 * float(pareto.design_mass[i]):g} g")
        ax1.plot(float(pareto.design_force[i]), float(pareto.design_balance_time[i]), "s",
                 color=f"C{i + 1}", ms=8, mfc="none", mew=1.5, label=label)
    ax1.set(xlabel="worst peak bearing force over the sample (N)",
            ylabel="mean balance time over the sample (s)",
            title=f"{pareto.sizes['position']} random initial ball positions, "
                  f"{pareto.attrs['kinematics']} kinematics")
    ax1.legend(fontsize=7)
    points = ax2.scatter(pareto.front_beta.values, 1e3 * pareto.front_mass.values,
                         c=pareto.front_force.values, cmap="viridis", s=25, label="front")
    fig.colorbar(points, ax=ax2, label="worst peak bearing force (N)")
    for i in range(pareto.design.size):
        ax2.plot(float(pareto.design_beta[i]), 1e3 * float(pareto.design_mass[i]), "s",
                 color=f"C{i + 1}", ms=8, mfc="none", mew=1.5)
    ax2.set(xlabel="ball damping ratio beta", ylabel="ball mass m (g)",
            title="the front's designs (squares: Table 2's rows)")
    return fig


def boundaries(beta, m_bar, zeta, st2, st3, paper):
    """Beyond the paper: the stability boundary traced by continuation in each plane (stable
    to its right), the critical speed, the grids' exact onsets of Figs 2-3 on it, its folds,
    and the curve's branches where another eigenvalue is unstable (not the boundary)."""
    fig, axes = figure(1, 3, figsize=(15.0, 4.8))
    grids = {"beta": st2, "m_bar": st3}
    for ax, (plane, ds) in zip(axes, (("beta", beta), ("m_bar", m_bar), ("zeta", zeta))):
        on = ds.on_boundary.values == 1
        for b in np.unique(ds.branch.values):
            sel = ds.branch.values == b
            window = int(ds.curve.values[sel][0])
            ax.plot(np.where(on, ds.omega_onset, np.nan)[sel], ds[plane].values[sel],
                    "-", color="C2" if window else "k", lw=1.4,
                    label="boundary (continuation)" if b == 0 else
                    "another stable window (traced from the top)"
                    if window == 1 and b == ds.branch.values[ds.curve.values == 1].min()
                    else None)
            ax.plot(np.where(on, np.nan, ds.omega_onset)[sel], ds[plane].values[sel], ":",
                    color="0.5", lw=1, label="Re lambda = 0, another eigenvalue unstable"
                    if b == 0 and (~on).any() else None)
        ax.plot(ds.critical_speed, ds[plane], "r:", lw=1.2, label="critical speed")
        folds = ds.fold_omega_bar.values
        if folds.size:
            ax.plot(ds.omega_onset.values[folds], ds[plane].values[folds], "o", mfc="none",
                    color="C1", ms=7, label="extreme of the onset speed")
        if (ds.curve.values > 0).any():
            _window_inset(ax, ds, plane)
        if plane in grids:
            st = grids[plane]
            ax.plot(st.stability_onset, st[plane], ".", color="C0", ms=4,
                    label=f"Fig {2 if plane == 'beta' else 3} grid: exact onsets")
        ax.set(xscale="log", yscale="log", xlabel="speed ratio omega/omega_n",
               ylabel=ds[plane].attrs["long_name"],
               title=", ".join(f"{k.removeprefix('fixed_')} = {float(ds[k]):g}"
                               for k in ds.data_vars if k.startswith("fixed_")))
        ax.legend(fontsize=7, loc="upper right")
    a, _ = approach_coefficient(beta)
    b_min, _, _ = lowest_beta(beta)
    axes[0].text(0.3, 0.3, f"beta -> inf: omega - omega_c ~ {a:.3f} / beta\n"
                             f"least beta balancing: {b_min:.3g}",
                 transform=axes[0].transAxes, fontsize=8, va="bottom",
                 bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
    return fig


def _window_inset(ax, ds, plane):
    """An inset of ``ax`` zoomed on the stable windows (curves 1, 2, ...) of a boundary dataset
    ``ds``, with the critical speed: the windows lie just above it."""
    w = ds.isel(point=ds.curve.values > 0)
    inset = ax.inset_axes([0.6, 0.08, 0.36, 0.3])
    for b in np.unique(w.branch.values):
        sel = w.branch.values == b
        inset.plot(w.omega_onset.values[sel], w[plane].values[sel], "-", color="C2", lw=1.2)
    inset.plot(w.critical_speed, w[plane], "r:", lw=1.2)
    inset.set(yscale="log", title="stable windows (zoom)")
    inset.tick_params(which="both", labelsize=6)
    inset.title.set_fontsize(7)


def ross_check(ross, paper):
    """Beyond the paper: paper B's rotor without balls by the closed form, the engine and ROSS:
    steady amplitude and phase over the speed, and the whirl radius through the run-up."""
    fig, (ax1, ax2, ax3) = figure(1, 3, figsize=(15.0, 4.6))
    speed = ross.speed.values
    for key, style in (("closed_form", "k-"), ("engine", "C0o"), ("ross", "C3x")):
        label = ross[f"amplitude_{key}"].attrs["long_name"].split(", ", 1)[1]
        ax1.plot(speed, 1e3 * ross[f"amplitude_{key}"], style, ms=5, mfc="none", label=label)
        ax2.plot(speed, np.degrees(ross[f"phase_{key}"]), style, ms=5, mfc="none", label=label)
    worst = max(float(np.max(np.abs(ross[f"amplitude_{k}"] / ross.amplitude_closed_form - 1)))
                for k in ("engine", "ross"))
    for ax in (ax1, ax2):
        ax.axvline(float(ross.omega_n), color="0.6", ls=":", lw=1, label="omega_n")
        ax.set(xlabel="disk speed (rad/s)")
        ax.legend(fontsize=7)
    ax1.set(yscale="log", ylabel="steady whirl amplitude (mm)",
            title=f"largest relative difference from the closed form: {worst:.1e}")
    ax2.set(ylabel="phase behind the unbalance (deg)",
            title=f"zeta = {float(ross.zeta):g}, eps = {1e3 * float(ross.eps):g} mm")
    t = ross.t.values
    ax3.plot(t, 1e3 * ross.r_engine, "C0", lw=1.2, label="engine")
    ax3.plot(t, 1e3 * ross.r_ross, "C3--", lw=1, label="ROSS (Newmark)")
    gap = float(np.max(np.abs(ross.r_ross - ross.r_engine)) / np.max(ross.r_engine))
    ax3.set(xlabel="time (s)", ylabel="whirl radius (mm)",
            title=f"run-up to {float(ross.speed_runup[-1]):g} rad/s; largest gap "
                  f"{gap:.1e} of the peak")
    ax3.legend(fontsize=7)
    return fig


def ga_law(ga_law, paper):
    """Beyond the paper: the whirl's envelope after the run-up at the GA optimum that beats its
    neighbours most and at those neighbours, with the fitted lines; and, for every neighbour of
    every optimum, the change of the balance time through the amplitude against that through
    the decay rate."""
    fig, (ax1, ax2) = figure(1, 2, figsize=(12.0, 4.8))
    others = ga_law.isel(neighbour=slice(1, None))
    gain = (others.line_time - ga_law.line_time.isel(neighbour=0)).where(
        others.in_box == 1).min("neighbour")
    best = np.unravel_index(int(np.argmax(np.nan_to_num(gain.values, nan=-np.inf))),
                            gain.shape)
    case = ga_law.isel(dict(zip(gain.dims, best)))
    t0 = float(ga_law.t_ramp)
    for j, name in enumerate(labels(ga_law, "neighbour")):
        point = case.isel(neighbour=j)
        t = point.envelope_time.values
        label = (f"{name}: beta = {float(point.beta):.3g}, m = {1e3 * float(point.mass):.3g} g, "
                 f"t_b = {float(point.balance_time):.2f} s"
                 + ("" if point.in_box else " (outside the GA's box)"))
        ax1.semilogy(t, point.envelope, "o", color=f"C{j}", ms=3, label=label)
        ax1.semilogy(t, float(point.amplitude) * np.exp(-float(point.sigma_fit) * (t - t0)),
                     color=f"C{j}", lw=0.8)
    ax1.axhline(float(ga_law.r_threshold), color="k", ls="--", lw=1, label="r_thr")
    ax1.set(xlabel="time (s)", ylabel="largest whirl radius r in each bin (m)",
            title=f"GA optimum, {case.kinematics_name.item()} kinematics, eps_bar = "
                  f"{float(case.eps_bar):g}, {case.ic_name.item()}\n"
                  f"lines: A exp(-sigma (t - {t0:g} s)) fitted to the envelope")
    ax1.legend(fontsize=7)
    names = labels(ga_law, "neighbour")
    for j in range(1, len(names)):
        nb = ga_law.isel(neighbour=j)
        use = (nb.in_box == 1).values
        ax2.plot(nb.amplitude_term.values[use], nb.rate_term.values[use], "o", color=f"C{j}",
                 ms=5, mfc="none", label=f"{names[j]} ({int(use.sum())} optima)")
    span = float(np.nanmax(np.abs(ga_law.amplitude_term.values)))
    ax2.plot([-span, span], [-span, span], "k:", lw=0.8, label="|amplitude| = |rate|")
    ax2.plot([-span, span], [span, -span], "k:", lw=0.8)
    ax2.axhline(0, color="0.7", lw=0.6)
    ax2.axvline(0, color="0.7", lw=0.6)
    ax2.set(xlabel="through the amplitude, ln(A_n / A_o) / sigma_o (s)",
            ylabel="through the decay rate (s)",
            title=f"change of the balance time from each optimum (step {float(ga_law.step):g})")
    ax2.legend(fontsize=7)
    return fig


def zeta_inversion(zeta_inversion, paper, zeta):
    """Beyond the paper: for each printed time of Fig 7 and Tables 1-2, the support damping
    ratios zeta at which each model (kinematics, balance-time definition) reproduces it
    (bars), the stated zeta and each model's zeta of least worst error; one zeta reproduces
    them all where a vertical line crosses every bar of one colour; ``zeta`` is the configured
    (stated) value."""
    ds = zeta_inversion
    cases = labels(ds, "case")
    models = [(k, d) for k in labels(ds, "kinematics") for d in labels(ds, "definition")]
    fig, ax = figure(figsize=(9.0, 0.6 * len(cases) + 1.8))
    zetas = ds.zeta.values
    half = float(np.min(np.diff(zetas))) / 2 if zetas.size > 1 else 0.0
    height = 0.8 / len(models)
    for j, (kin, definition) in enumerate(models):
        error = ds.error.sel(kinematics_name=kin, definition_name=definition)
        for i, case in enumerate(cases):
            ok = zetas[error.sel(case_name=case).values <= 1.0]
            y = i + (j - (len(models) - 1) / 2) * height
            ax.barh([y] * ok.size, 2 * half, left=ok - half, height=0.9 * height,
                    color=f"C{j}", label=None)
        best = float(ds.best_zeta.sel(kinematics_name=kin, definition_name=definition))
        worst = float(ds.least_worst_error.sel(kinematics_name=kin, definition_name=definition))
        ax.axvline(best, color=f"C{j}", ls=":", lw=1)
        ax.plot([], [], "s", color=f"C{j}",
                label=f"{kin}, {definition}: least worst error {worst:.2g} tol at "
                      f"zeta = {best:.4g}")
    ax.axvline(zeta, color="k", ls="--", lw=1,
               label=f"zeta = {zeta:g} (stated for Figs 2-3, 8-14; configured)")
    ax.set_yticks(range(len(cases)), [f"{c} ({float(p):g} s)"
                                      for c, p in zip(cases, ds.printed.values)])
    ax.invert_yaxis()
    ax.set(xlabel="support damping ratio zeta (1)", xlim=(zetas[0] - half, zetas[-1] + half),
           title="zeta at which each printed time is reproduced\n(within max(1 %, half its "
                 "last printed digit); no bar: at no zeta of the grid)")
    ax.legend(fontsize=7, loc="lower right")
    return fig
