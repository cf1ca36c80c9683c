"""Beyond paper B: a law for the balance time, from quantities known before the end of a run.

After the run-up passes the critical speed, the whirl radius decays towards the balanced state
at the rate of the slowest mode of the linearised balanced state (eqs 27-32) that carries the
whirl: a straight line on a log scale.  With the bearing force peaking at ``F_pk`` at time
``t_pk`` during the passage, the radius there is about ``F_pk / k``, and it falls below the
threshold ``r_thr`` of the balance criterion when

    t_b = t_pk + ln(F_pk / (k r_thr)) / sigma,    sigma = -max Re(lambda) omega_n,

``lambda`` over the eigenvalues of the balanced state at the operating speed that are not
neutral (at the existence bound m/M = eps_bar/2, eq. 34, one mode is neutral) and whose mode
moves r: its share of the whirl (:func:`~rotorvib.papers.b.stability_maps.balanced_modes`) at
least ``share``.  A mode of the balls alone (share a few hundredths) can be the slowest, near
the existence bound and for balls heavy against the unbalance, but it decays unseen in r.
:func:`law_dataset` evaluates the law on every balanced run of paper B's studies against the
balance time the integration gives, under each share of the whirl asked for (and with the
slowest mode of all, for comparison); :func:`law_rows` states how well it does, study by
study, and where it fails.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.comparison.choices import VARIANT_JOIN, Close
from rotorvib.comparison.reproduced import Margin, Reproduced
from rotorvib.io.variables import described
from rotorvib.methods.bands import percentile_spread
from rotorvib.papers.b.choices import LAW_CHOICES
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.stability_maps import balanced_modes

#: coordinate of a study dataset -> the run parameter it holds
_PARAMETER_COORDS = {"mass": "mass", "case_mass": "mass", "beta": "beta", "case_beta": "beta",
                     "eps_bar": "eps_bar", "speed": "speed", "zeta": "zeta", "R": "R"}
_RUN_PARAMETERS = ("mass", "beta", "eps_bar", "speed", "zeta", "R")
#: The law dataset's variables: (long name, units); its relative errors share one.
LAW_VARIABLES = {
    "m_bar": ("ball mass ratio m/M", "1"),
    "eps_bar": ("eccentricity ratio eps/R", "1"),
    "beta": ("ball damping ratio beta", "1"),
    "omega_bar": ("operating speed / omega_n", "1"),
    "zeta": ("support damping ratio", "1"),
    "R": ("race radius R", "m"),
    "phi0": ("initial ball angle, disk frame", "degree"),
    "sigma": ("decay rate of the slowest non-neutral mode carrying at least the share of the "
              "whirl", "s-1"),
    "sigma_slowest": ("decay rate of the slowest non-neutral mode of all", "s-1"),
    "t_peak": ("time of the peak bearing force (the critical-speed passage)", "s"),
    "force_peak": ("peak bearing force", "N"),
    "predicted": ("balance time by the law t_pk + ln(F_pk / (k r_thr)) / sigma", "s"),
    "predicted_slowest": ("balance time by the law with the slowest mode of all", "s"),
    "balance_time": ("balance time of the integration (threshold criterion)", "s"),
}


def slow_decay_rate(m_bar, eps_bar, zeta, beta, omega_bar, *, neutral: float, n: int = 2,
                    share: float = 0.0):
    """``sigma / omega_n``: minus the largest real part of the balanced state's eigenvalues
    (:func:`~rotorvib.papers.b.stability_maps.balanced_modes`) that are not neutral
    (``Re lambda < -neutral``) and whose share of the whirl is at least ``share`` (0: the
    slowest mode of all; a ball mode that hardly moves r decays unseen in r), in units of paper
    B's ``omega_n``; NaN where no balanced state exists (m_bar/eps_bar < 1/2) or no such mode
    decays.  Vectorised over broadcast arguments."""
    eig, whirl = balanced_modes(m_bar, eps_bar, zeta, beta, omega_bar, n)
    with np.errstate(invalid="ignore"):
        carries = (eig.real < -neutral) & (whirl >= share)
        slowest = np.where(carries, eig.real, -np.inf).max(axis=-1)
    return np.where(np.isfinite(slowest), -slowest, np.nan)


def balance_time_law(t_peak, force_peak, f_threshold: float, sigma):
    """``t_pk + ln(F_pk / f_thr) / sigma`` (s), ``f_thr = k r_thr`` the force of the balance
    criterion and ``sigma`` the slowest decay rate (1/s); broadcast."""
    return np.asarray(t_peak) + np.log(np.asarray(force_peak) / f_threshold) / np.asarray(sigma)


def run_parameters(ds: xr.Dataset, fixed: dict) -> dict[str, xr.DataArray]:
    """Each run's ``mass``, ``beta``, ``eps_bar``, ``speed`` (and ``zeta`` where a coordinate or
    ``fixed`` gives it) over the dimensions of the dataset's balance times: from its
    coordinates where it varies them, else from ``fixed``."""
    values = dict(fixed)
    for coord, name in _PARAMETER_COORDS.items():
        if coord in ds.coords:
            values[name] = ds[coord]
    missing = set(_RUN_PARAMETERS) - {"zeta", "R"} - set(values)
    if missing:
        raise ValueError(f"the parameters {sorted(missing)} are neither coordinates nor fixed")
    return {name: _over_runs(xr.DataArray(v) if np.isscalar(v) else v, ds)
            for name, v in values.items() if name in _RUN_PARAMETERS}


def _over_runs(values: xr.DataArray, ds: xr.Dataset) -> xr.DataArray:
    """``values`` broadcast over the dimensions of ``ds.balance_time``, in their order."""
    return xr.broadcast(values, ds.balance_time)[0].transpose(*ds.balance_time.dims)


def at_the_law(ds: xr.Dataset) -> xr.Dataset:
    """The law's view of its dataset: the rate and prediction at the law's whirl share (the
    first); a dataset without shares as it is."""
    return ds.isel(share=0) if "share" in ds.dims else ds


def initial_ball_angles(ds: xr.Dataset, fixed: dict, ics: dict) -> np.ndarray:
    """Each run's initial ball angles (degrees), shape ``balance_time.shape + (balls,)``: the
    ``phi1``, ``phi2``, ... coordinates where the dataset varies them (the basin map), else
    the initial conditions of ``ics`` named along its ``ic`` dimension, else the one named
    ``fixed["ic"]``."""
    if "phi1" in ds.coords:
        balls = sorted((c for c in ds.coords if c.startswith("phi") and c[3:].isdigit()),
                       key=lambda c: int(c[3:]))
        return np.stack([_over_runs(ds[c], ds).values for c in balls], axis=-1)
    names = (_over_runs(ds.ic_name, ds).values if "ic" in ds.balance_time.dims
             else np.full(ds.balance_time.shape, fixed["ic"], dtype=object))
    return np.array([ics[str(n)] for n in names.ravel()],
                    dtype=float).reshape(*names.shape, -1)


def law_dataset(setup: Setup, sources: dict[str, tuple[xr.Dataset, dict]], ics: dict, *,
                neutral: float, shares) -> xr.Dataset:
    """The law against the integration on every balanced run of ``sources`` (name ->
    ``(dataset, fixed parameters)``, :func:`run_parameters`; the support damping and race
    radius default to the machine's), one ``run`` dimension: the source, the kinematics, the
    parameters and initial ball angles (:func:`initial_ball_angles`, ``ics`` the initial
    conditions by name), the peak force and its time, the integrated balance time, and for
    each whirl share of ``shares`` (the first is the law's) the decay rate ``sigma`` and the
    predicted balance time; with the slowest mode of all, ``sigma_slowest`` and
    ``predicted_slowest``."""
    wn = np.sqrt(setup.k / setup.M)
    f_threshold = setup.k * setup.criterion.r_threshold
    shares = tuple(float(s) for s in shares)
    columns = {key: [] for key in ("source", "kinematics", "m_bar", "eps_bar", "beta",
                                   "omega_bar", "zeta", "R", "phi0", "sigma", "sigma_slowest",
                                   "t_peak", "force_peak", "balance_time")}
    for name, (ds, fixed) in sources.items():
        p = run_parameters(ds, {"zeta": setup.zeta, "R": setup.R, **fixed})
        kin = _over_runs(ds.kinematics_name, ds)
        balanced = (ds.balanced == 1).values
        m_bar, eps, beta = (p["mass"].values / setup.M, p["eps_bar"].values, p["beta"].values)
        omega_bar, zeta = p["speed"].values / wn, p["zeta"].values

        def rate(share):
            return slow_decay_rate(m_bar, eps, zeta, beta, omega_bar, neutral=neutral,
                                   share=share) * wn

        for key, values in (("source", np.full(balanced.shape, name, dtype=object)),
                            ("kinematics", kin.values.astype(object)), ("m_bar", m_bar),
                            ("eps_bar", eps), ("beta", beta), ("omega_bar", omega_bar),
                            ("zeta", zeta), ("R", p["R"].values),
                            ("phi0", initial_ball_angles(ds, fixed, ics)),
                            ("sigma", np.stack([rate(s) for s in shares], axis=-1)),
                            ("sigma_slowest", rate(0.0)),
                            ("t_peak", ds.force_max_time.values),
                            ("force_peak", ds.force_max.values),
                            ("balance_time", ds.balance_time.values)):
            columns[key].append(np.asarray(values)[balanced])
    data = {key: np.concatenate(v) for key, v in columns.items()}

    def law(sigma):
        return balance_time_law(data["t_peak"], data["force_peak"], f_threshold, sigma)

    predicted = law(data["sigma"].T)
    slowest = law(data["sigma_slowest"])
    error = ("relative error of the law, (law - integration) / integration (NaN where the law "
             "has no rate)", "1")
    return xr.Dataset(
        described({
            **{k: ("run", data[k]) for k in ("m_bar", "eps_bar", "beta", "omega_bar", "zeta",
                                             "R")},
            "phi0": (("run", "ball"), data["phi0"]),
            "sigma": (("share", "run"), data["sigma"].T),
            **{k: ("run", data[k]) for k in ("sigma_slowest", "t_peak", "force_peak")},
            "predicted": (("share", "run"), predicted),
            "predicted_slowest": ("run", slowest),
            "balance_time": ("run", data["balance_time"]),
            "relative_error": (("share", "run"),
                               (predicted - data["balance_time"]) / data["balance_time"]),
            "relative_error_slowest": ("run", (slowest - data["balance_time"])
                                       / data["balance_time"]),
        }, {**LAW_VARIABLES, "relative_error": error, "relative_error_slowest": error}),
        coords={"whirl_share": ("share", np.asarray(shares), {
                    "long_name": "least share of the whirl of the mode whose rate the law "
                                 "takes (the first is the law's)", "units": "1"}),
                "source": ("run", data["source"], {"long_name": "study the run belongs to"}),
                "kinematics_name": ("run", data["kinematics"], {"long_name": "kinematics"})},
        attrs=dataset_attrs("a law for the balance time",
                            "Beyond the paper: the balance time predicted from the peak bearing "
                            "force of the critical-speed passage and the decay rate of the "
                            "slowest mode of the balanced state that carries the whirl, "
                            "against the integration, on every balanced run of "
                            + ", ".join(sources), "Figs 7-15, Tables 1-2"),
    )


def error_text(errors: np.ndarray) -> str:
    """``"6.2 % at the median, 90 % within 15.7 % (513 runs)"`` of the relative errors' absolute
    values (NaN: no rate, left out)."""
    e = np.abs(errors[np.isfinite(errors)])
    if not e.size:
        return "no run with a rate"
    return (f"{np.median(e):.1%} at the median, 90 % within {np.percentile(e, 90):.1%} "
            f"({e.size} runs)")


def domain_text(ds: xr.Dataset, close: float) -> str:
    """Where the law (the first share) holds and where it fails, from its errors: study by
    study (within ``close`` at the median or not), near the existence bound (m_bar/eps_bar
    at most 0.55) against beyond it, by quarter of the integrated balance time, and against
    the law with the slowest mode of all."""
    errors = np.abs(ds.relative_error.values[0])
    source = ds.source.values
    studies = {s: float(np.nanmedian(errors[source == s])) for s in dict.fromkeys(source)}
    holds = [s for s, m in studies.items() if m <= close]
    fails = [s for s, m in studies.items() if not m <= close]
    ratio = ds.m_bar.values / ds.eps_bar.values
    t = ds.balance_time.values
    quarters = np.nanpercentile(t, [25, 50, 75])
    bins = np.digitize(t, quarters)
    signed = ds.relative_error.values[0]
    slowest = np.abs(ds.relative_error_slowest.values)
    return ("by study: " + "; ".join(f"{s}: {error_text(errors[source == s])}"
                                     for s in studies)
            + f". Within {close:.0%} at the median for {', '.join(holds) or 'no study'}"
            + (f"; not for {', '.join(fails)}" if fails else "")
            + f". Near the existence bound (m_bar/eps_bar <= 0.55): "
              f"{error_text(errors[ratio <= 0.55])}; beyond it: "
              f"{error_text(errors[ratio > 0.55])}. By quarter of the balance time (from the "
              "fastest): " + ", ".join(f"{np.nanmedian(signed[bins == q]):+.1%}"
                                       for q in range(4))
            + " median signed error: the fastest runs balance before the whirl the passage's "
              "peak force implies has decayed, and the law over-predicts them. With the "
              f"slowest mode of all instead of the one carrying the whirl: "
              f"{error_text(slowest)}; near the bound {error_text(slowest[ratio <= 0.55])}, "
              f"for balls heavy against the unbalance (m_bar/eps_bar >= 2) "
              f"{error_text(slowest[ratio >= 2])} against "
              f"{error_text(errors[ratio >= 2])}")


def law_rows(ds: xr.Dataset, close: Close, *, resamples: int = 200,
             seed: int = 0) -> list[Reproduced]:
    """Beyond the paper: does the law predict the balance time of the median balanced run
    within the comparison's standard for "close"?  Evaluated under each whirl share of the
    dataset (the least share of the mode whose rate it takes, a choice) and each reading of
    "close"; the margin is ``close`` less the median absolute relative error, its uncertainty
    twice the bootstrap standard deviation of that median.  The explanation states the domain
    (:func:`domain_text`)."""
    choices = LAW_CHOICES + (
        f"paper_b.balance_law.whirl_share = {float(ds.whirl_share[0]):g} (the least share of the "
        "whirl of the mode whose rate the law takes, chosen; alternatives "
        + ", ".join(f"{v:g}" for v in ds.whirl_share.values[1:]) + " evaluated)", close.choice)
    errors = np.abs(ds.relative_error.values)
    if not np.isfinite(errors).any():
        return [Reproduced.claim("B", "balance_law_close", None,
                                 "undetermined: no balanced run with a decaying mode to test "
                                 "the law on", choices=choices)]
    holds = {}
    for i, share in enumerate(ds.whirl_share.values):
        e = errors[i][np.isfinite(errors[i])]
        median = float(np.median(e))
        spread = float(percentile_spread(e, [50.0], resamples=resamples, seed=seed)[0])
        for name, margin in close.margins(
                lambda c: Margin(c - median, 2 * spread, "relative",
                                 f"bootstrap of the median over {e.size} runs")).items():
            holds[f"paper_b.balance_law.whirl_share = {share:g}{VARIANT_JOIN}{name}"] = margin
    return [Reproduced.claim(
        "B", "balance_law_close", holds,
        f"over {int(np.isfinite(errors[0]).sum())} balanced runs of every study the law's "
        f"error is {error_text(errors[0])}; " + domain_text(ds, close.value)
        + f". Close means within {close:.0%}, the comparison's standard", choices=choices)]


FACTORS = ("sigma", "force", "t_peak")


def factor_shares(ds: xr.Dataset, sel: np.ndarray) -> dict[str, float]:
    """How much of the balance times' variance over the runs ``sel`` each factor of the law
    ``t_b = t_pk + L / sigma`` (``L = ln(F_pk / (k r_thr))``) explains alone: the squared
    correlation with the integrated times of the law with the other two factors held at their
    medians ("sigma", "force", "t_peak"), and of the whole law ("law")."""
    t, tp, sigma = (ds[k].values[sel] for k in ("balance_time", "t_peak", "sigma"))
    log_force = (ds.predicted.values[sel] - tp) * sigma
    mt, ml, ms = np.median(tp), np.median(log_force), np.median(sigma)
    alone = {"law": ds.predicted.values[sel], "sigma": mt + ml / sigma,
             "force": mt + log_force / ms, "t_peak": tp + ml / ms}
    return {k: float(np.corrcoef(v, t)[0, 1] ** 2) if np.ptp(v) > 0 else 0.0
            for k, v in alone.items()}


#: The trends the law explains: row -> (the study's source, its axis in the law's dataset).
TRENDS = {"law_explains_mass": ("balance_mass", "m_bar"),
          "law_explains_beta": ("balance_beta", "beta")}


def trend_rows(ds: xr.Dataset, *, resamples: int = 200, seed: int = 0) -> list[Reproduced]:
    """Beyond the paper: does the balance time rise along each study of :data:`TRENDS` (heavier
    balls, more ball damping) because the balanced state's slowest decay rate falls along it?
    Under each kinematics, over the study's balanced runs: the margin is the share explained by
    sigma alone less the larger of the other two factors' (:func:`factor_shares`), its
    uncertainty twice its bootstrap standard deviation; it holds only if sigma also falls along
    the axis.  The first row's explanation gives every source's shares.  The law is taken at
    its whirl share (the dataset's first)."""
    ds = at_the_law(ds)
    valued = np.isfinite(ds.predicted.values)
    rng = np.random.default_rng(seed)
    shares_text = []
    for kin in dict.fromkeys(ds.kinematics_name.values):
        for source in dict.fromkeys(ds.source.values):
            sel = np.flatnonzero(valued & (ds.kinematics_name.values == kin)
                                 & (ds.source.values == source))
            if sel.size > 2:
                shares = factor_shares(ds, sel)
                first = max(FACTORS, key=shares.get)
                shares_text.append(f"{source} ({kin}): " + ", ".join(
                    f"{k} {v:.2f}" for k, v in shares.items()) + f" -> {first} leads")

    def lead(idx):
        s = factor_shares(ds, idx)
        return s["sigma"] - max(s["force"], s["t_peak"])

    rows = []
    for quantity, (source, axis) in TRENDS.items():
        holds = {}
        for kin in dict.fromkeys(ds.kinematics_name.values):
            sel = np.flatnonzero(valued & (ds.kinematics_name.values == kin)
                                 & (ds.source.values == source))
            if sel.size < 3:
                holds[str(kin)] = None
                continue
            spread = np.std([lead(rng.choice(sel, sel.size)) for _ in range(resamples)])
            falls = (np.ptp(ds.sigma.values[sel]) > 0
                     and np.corrcoef(ds[axis].values[sel], ds.sigma.values[sel])[0, 1] < 0)
            margin = lead(sel) if falls else -abs(lead(sel))
            holds[str(kin)] = Margin(margin, 2 * float(spread), "share of variance",
                                     f"bootstrap over {sel.size} runs")
        rows.append(Reproduced.claim(
            "B", quantity, holds or None,       # no run balanced: nothing to decide
            "shares of the balance times' variance that each factor of the law explains alone "
            "(sigma: the decay rate of the slowest mode carrying the whirl; force: the "
            "passage's peak force; t_peak: its time; "
            "law: all three): " + "; ".join(shares_text), choices=LAW_CHOICES))
    return rows


def decay_elasticities(ds: xr.Dataset, zeta: float, *, neutral: float,
                       step: float = 1e-4) -> dict[str, np.ndarray]:
    """``d ln sigma / d ln p`` of the law's decay rate (the slowest mode carrying the law's
    whirl share) for ``p`` = zeta, beta and m_bar at every distinct parameter point of the
    law's runs (central differences of relative width ``2 step``); NaN where sigma is
    undefined on either side."""
    share = float(ds.whirl_share.values.flat[0]) if "whirl_share" in ds.coords else 0.0
    points = np.unique(np.stack([ds[k].values for k in ("m_bar", "eps_bar", "beta",
                                                        "omega_bar")], axis=1), axis=0)
    base = {"m_bar": points[:, 0], "eps_bar": points[:, 1], "zeta": np.full(len(points), zeta),
            "beta": points[:, 2], "omega_bar": points[:, 3]}

    def log_sigma(name, factor):
        args = {**base, name: base[name] * factor}
        return np.log(slow_decay_rate(args["m_bar"], args["eps_bar"], args["zeta"],
                                      args["beta"], args["omega_bar"], neutral=neutral,
                                      share=share))

    return {name: (log_sigma(name, 1 + step) - log_sigma(name, 1 - step)) / (2 * step)
            for name in ("zeta", "beta", "m_bar")}


def support_damping_rows(ds: xr.Dataset, zeta: float, *, neutral: float) -> list[Reproduced]:
    """Beyond the paper: after the passage the balance time is set by the slowest decay rate
    sigma; does the support damping move it more than the balls' damping and mass?  The margin
    is the median over the runs' parameter points of ``|E_zeta| - max(|E_beta|, |E_m|)``
    (elasticities of sigma, :func:`decay_elasticities`; exact, no uncertainty)."""
    e = decay_elasticities(ds, zeta, neutral=neutral)
    valid = np.all([np.isfinite(v) for v in e.values()], axis=0)
    if not valid.any():
        return [Reproduced.claim("B", "law_support_damping", None,
                                 "undetermined: no parameter point with a decay rate",
                                 choices=LAW_CHOICES)]
    lead = np.abs(e["zeta"]) - np.maximum(np.abs(e["beta"]), np.abs(e["m_bar"]))
    med = {k: float(np.median(v[valid])) for k, v in e.items()}
    return [Reproduced.claim(
        "B", "law_support_damping",
        Margin(float(np.median(lead[valid])), 0.0, "elasticity",
               f"median over {int(valid.sum())} parameter points (exact)"),
        f"elasticities d ln sigma / d ln p of the law's decay rate at the "
        f"{int(valid.sum())} parameter points of the balanced runs, medians: zeta "
        f"{med['zeta']:.2f}, m_bar {med['m_bar']:.2f}, beta {med['beta']:.3f}; zeta's is the "
        f"largest at {np.mean(lead[valid] > 0):.1%} of them. So the support damping sets how "
        f"fast the whirl decays once the balls have settled, and the ball damping hardly does "
        f"(tenfold beta moves sigma by a factor {10 ** abs(med['beta']):.2f} at the median): "
        "beta's effect on the balance time comes mostly through the passage (row "
        "law_explains_beta)", choices=LAW_CHOICES)]
