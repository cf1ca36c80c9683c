"""Paper A's figures, drawn from the datasets only."""

from __future__ import annotations

import numpy as np
from matplotlib.ticker import NullLocator

from rotorvib.io.plotting import figure

METHOD_STYLE = {"runge_kutta": ("k", "-", "Runge-Kutta"), "one_term": ("C1", "--", "one term"),
                "two_term": ("C0", ":", "two terms")}


def _methods(ds):
    return [str(m) for m in ds.method_name.values]


def _three_methods(ds, variable, zoom, title, ylabel, i_beta):
    """The three solutions over the whole run, a zoom, and each multiple-scales solution's
    error against Runge-Kutta on a log scale (where the curves above cannot be told apart)."""
    fig, (a1, a2, a3) = figure(3, 1, figsize=(7.0, 8.6))
    tau = ds.tau.values
    inside = (tau >= zoom[0]) & (tau <= zoom[1])
    methods = _methods(ds)
    reference = ds[variable].values[i_beta, methods.index("runge_kutta")]
    errors = []
    for k, method in enumerate(methods):
        color, ls, label = METHOD_STYLE[method]
        y = ds[variable].values[i_beta, k]
        a1.plot(tau, y, color=color, ls=ls, lw=1, label=label)
        a2.plot(tau[inside], y[inside], color=color, ls=ls, lw=1.2, label=label)
        if method != "runge_kutta":
            error = np.abs(y - reference)
            errors.append(error.max())
            a3.semilogy(tau, error, color=color, lw=0.8, label=f"{label}: max {errors[-1]:.2g}")
    a1.set(ylabel=ylabel, title=title)
    a2.set(ylabel=ylabel, title=f"zoom on tau in [{zoom[0]:g}, {zoom[1]:g}]")
    a3.set_ylim(1e-4 * min(errors), 3 * max(errors))     # four decades below the smaller one
    a3.set(xlabel="dimensionless time tau = w_n t", ylabel=f"|error| of {ylabel}",
           title="error against Runge-Kutta (both start exact at tau = 0)")
    a1.legend(fontsize=8)
    a3.legend(fontsize=8)
    return fig


def fig2(resp, paper, zoom, beta):
    """Fig 2: x/R of the geometric centre by one-term and two-term multiple scales and
    Runge-Kutta at the case's ``beta``, with a zoom over ``zoom`` and the errors."""
    i = int(np.argmin(np.abs(resp.beta.values - beta)))
    return _three_methods(resp, "u", zoom, "Fig 2: x of the geometric centre (rotating frame)",
                          "x / R", i)


def fig3(resp, paper, zoom, beta):
    """Fig 3: y/R of the geometric centre, as :func:`fig2`."""
    i = int(np.argmin(np.abs(resp.beta.values - beta)))
    return _three_methods(resp, "v", zoom, "Fig 3: y of the geometric centre (rotating frame)",
                          "y / R", i)


def fig4(resp, paper, beta):
    """Fig 4: the two ball angles by the three methods at the case's ``beta``, with the
    balanced angles +/-arccos(-1/(2 rho))."""
    i = int(np.argmin(np.abs(resp.beta.values - beta)))
    fig, axes = figure(2, 1, sharex=True, figsize=(7.0, 6.0))
    tau = resp.tau.values
    target = float(resp.balanced_angle)
    for ax, name, sign in zip(axes, ("alpha1", "alpha2"), (1, -1)):
        for k, method in enumerate(_methods(resp)):
            color, ls, label = METHOD_STYLE[method]
            ax.plot(tau, resp[name].values[i, k], color=color, ls=ls, lw=1, label=label)
        ax.axhline(sign * target, color="crimson", ls="--", lw=1,
                   label=f"balanced angle {sign * target:.1f} deg")
        ax.set(ylabel=f"{name} (deg)")
        ax.legend(fontsize=8)
    axes[0].set(title="Fig 4: ball angles")
    axes[1].set(xlabel="dimensionless time tau")
    return fig


def _beta_family(resp, betas, names, ylabels, title):
    """Runge-Kutta responses of ``names`` (one row each) for several ball damping ratios, one
    column per beta as in the paper (on one axis the curves hide one another)."""
    fig, axes = figure(len(names), len(betas), sharex=True, sharey="row",
                       figsize=(3.6 * len(betas), 6.0), squeeze=False)
    tau = resp.tau.values
    rk = _methods(resp).index("runge_kutta")
    for j, beta in enumerate(betas):
        i = int(np.argmin(np.abs(resp.beta.values - beta)))
        for row, (name, ylabel) in enumerate(zip(names, ylabels)):
            ax = axes[row, j]
            ax.plot(tau, resp[name].values[i, rk], color=f"C{j}", lw=0.9)
            ax.set(ylabel=ylabel if j == 0 else "")
        axes[0, j].set_title(f"beta = {beta:g}", fontsize=10)
        axes[-1, j].set(xlabel="tau = w_n t (dimensionless)")
    fig.suptitle(title)
    return fig


def fig5(resp, paper, betas):
    """The paper's claim of Fig 5, that ball damping speeds the balancing up to an optimum and
    slows it beyond: the rotor amplitude r/R = sqrt(u^2 + v^2) (Runge-Kutta) on a log scale for
    each beta, beside the decay rate of the slowest mode of the linearised balanced state,
    -max Re(lambda), which sets how fast r/R falls once the transient has passed."""
    fig, (ax, rate) = figure(1, 2, figsize=(10.0, 4.3), width_ratios=(1.6, 1))
    tau = resp.tau.values
    rk = _methods(resp).index("runge_kutta")
    slowest = []
    for j, beta in enumerate(betas):
        i = int(np.argmin(np.abs(resp.beta.values - beta)))
        slowest.append(-float(np.max(resp.eigenvalue_real.values[i])))
        ax.semilogy(tau, np.hypot(resp.u.values[i, rk], resp.v.values[i, rk]), color=f"C{j}",
                    lw=0.9, label=f"beta = {beta:g}")
    ax.set(xlabel="tau = w_n t (dimensionless)", ylabel="rotor amplitude r / R",
           title="Runge-Kutta response")
    ax.legend(fontsize=8)
    labels = [f"{beta:g}" for beta in betas]
    rate.bar(labels, slowest, color=[f"C{j}" for j in range(len(betas))])
    for j, value in enumerate(slowest):
        rate.annotate(f"{value:.3g}\n(1/rate = {1 / value:.0f})", (j, value), ha="center",
                      va="bottom", fontsize=8)
    rate.set(xlabel="ball damping ratio beta", ylim=(0, 1.3 * max(slowest)),
             ylabel="decay rate of the slowest mode, -max Re(lambda)",
             title="slowest mode of the linearisation")
    fig.suptitle("Fig 5: effect of ball damping")
    return fig


def fig6(resp, paper, betas):
    """Fig 6: the ball angles for each of ``betas`` (Runge-Kutta)."""
    return _beta_family(resp, betas, ("alpha1", "alpha2"), ("alpha1 (deg)", "alpha2 (deg)"),
                        "Fig 6: ball angles for three beta (Runge-Kutta)")


def fig7(region, paper):
    """Fig 7: the stable region in the (beta, Omega) plane by multiple scales and by Lyapunov's
    first method, one panel per zeta."""
    n = region.zeta.size
    fig, axes = figure(1, n, figsize=(5.0 * n, 4.4), sharey=True)
    axes = np.atleast_1d(axes)
    W, B = np.meshgrid(region.omega.values, region.beta.values)
    for k, ax in enumerate(axes):
        lyap = region.growth_lyapunov.values[k]
        ax.contourf(W, B, lyap < 0, levels=[0.5, 1.5], colors=["#9ecae1"])
        ax.contour(W, B, region.growth_mms.values[k], levels=[0], colors="k", linewidths=2.5)
        ax.contour(W, B, lyap, levels=[0], colors="C1", linewidths=1.2, linestyles="--")
        ax.plot([], [], color="#9ecae1", lw=8, label="stable (Lyapunov)")
        ax.plot([], [], "k", lw=2.5, label="boundary, multiple scales")
        ax.plot([], [], "C1--", label="boundary, Lyapunov")
        ax.set(xlabel="speed ratio Omega", title=f"Fig 7: zeta = {float(region.zeta[k]):g}")
    axes[0].set(ylabel="ball damping ratio beta")
    axes[0].legend(fontsize=8, loc="upper right")
    return fig


def error_study(err, paper):
    """The error of the one- and two-term solutions against Runge-Kutta over the initial
    distance delta, on log-log axes with the slopes O(delta^2) and O(delta^3)."""
    fig, ax = figure()
    d = err.delta.values
    for name, label, style in (("one_term", "one term", "o-C1"),
                               ("two_term", "two terms, nonlinear constants (eq. 39)", "o-C0"),
                               ("two_term_linear", "two terms, linear constants", "s--C2")):
        ax.loglog(d, err[f"error_{name}"].values, style, mfc="none" if "s" in style else None,
                  label=f"{label}: slope {float(err[f'slope_{name}']):.2f}")
    for order, ls in ((2, ":"), (3, "--")):
        ref = err.error_one_term.values[-1] if order == 2 else err.error_two_term.values[-1]
        ax.loglog(d, ref * (d / d[-1]) ** order, "k", ls=ls, lw=0.8, label=f"delta^{order}")
    ax.set(xlabel="initial distance delta from the balanced state",
           ylabel="max error against Runge-Kutta", title="Error of the multiple-scales solutions")
    ax.set_xticks(d, [f"{x:g}" for x in d])      # the computed distances, not crowded minor
    ax.xaxis.set_minor_locator(NullLocator())   # log ticks
    ax.legend(fontsize=8, loc="upper left")
    return fig


def slow_flow(flow, paper):
    """The small-mu slow flow's stability boundary against the exact one (full linearisation)
    in the (Omega, beta) plane."""
    fig, ax = figure()
    ax.plot(flow.critical_speed_exact.values, flow.beta.values, "k", lw=1.6,
            label="exact (full linearisation)")
    ax.plot(flow.critical_speed_slow_flow.values, flow.beta.values, "C1--", lw=1.4,
            label="small-mu slow flow")
    ax.axvline(1.0, color="grey", ls=":", lw=1, label="Omega = 1")
    ax.set(xlabel="lowest stable speed ratio Omega", ylabel="ball damping ratio beta",
           title="Slow flow against the exact stability boundary")
    ax.legend(fontsize=8)
    return fig
