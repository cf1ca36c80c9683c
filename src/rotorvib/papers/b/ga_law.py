"""Beyond paper B: what the GA's optimum is, read off the decay of the whirl around it.

After the run-up (``t > t_ramp``) the whirl radius decays on a straight line of a log scale,

    r(t) ~ A exp(-sigma (t - t_ramp)),

``A`` the whirl the critical-speed passage leaves and ``sigma`` its decay rate, so the balance
time (r below ``r_thr`` for good) is ``t_b ~ t_ramp + ln(A / r_thr) / sigma``.  Between the GA's
optimum (``o``) and a neighbour (``n``) of it in (beta, m) the change of this time splits
exactly into

    t_n - t_o = ln(A_n / A_o) / sigma_o                      (amplitude: what the passage leaves)
              + ln(A_n / r_thr) (1 / sigma_n - 1 / sigma_o)   (rate: how fast it then decays).

:func:`ga_law_dataset` integrates the optimum of every GA problem and its neighbours, fits
``A`` and ``sigma`` to the envelope of r (:func:`envelope`, :func:`fit_decay`) and gives both
terms; :func:`ga_law_rows` says which one makes the optimum.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import xarray as xr

from rotorvib.comparison.choices import under_choice
from rotorvib.comparison.reproduced import Margin, Reproduced
from rotorvib.io.coords import label_coord, pick
from rotorvib.io.variables import described
from rotorvib.models.balancer import layout
from rotorvib.models.balancer.simulate import run
from rotorvib.papers.b.choices import FLAT_KEY, GA_LAW_CHOICES
from rotorvib.papers.b.law import balance_time_law, slow_decay_rate
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import Setup

#: neighbour of the optimum -> its factors on (beta, m) in units of the step h
NEIGHBOURS = {"optimum": (0, 0), "beta_low": (-1, 0), "beta_high": (1, 0), "mass_high": (0, 1)}


def envelope(t: np.ndarray, r: np.ndarray, start: float, width: float):
    """The envelope of a whirl whose period is shorter than ``width`` (s): in each of the
    consecutive bins of ``width`` from ``start`` to the last sample, the highest crest (local
    maximum) of r and its time; in a bin where r has no crest (a monotone stretch), its
    largest sample."""
    edges = np.arange(start, t[-1] - width / 2, width)
    if edges.size < 3:
        raise ValueError(f"the window from {start} s to {t[-1]} s holds fewer than three bins "
                         f"of {width} s: nothing to fit a decay to")
    bounds = np.searchsorted(t, np.append(edges, edges[-1] + width))
    crest = np.zeros(r.size, dtype=bool)
    crest[1:-1] = (r[1:-1] >= r[:-2]) & (r[1:-1] >= r[2:])
    highest = []
    for lo, hi in zip(bounds[:-1], bounds[1:]):
        candidates = np.flatnonzero(crest[lo:hi]) + lo
        if candidates.size == 0:
            candidates = np.arange(lo, hi)
        highest.append(candidates[np.argmax(r[candidates])])
    return t[highest], r[highest]


def fit_decay(times: np.ndarray, env: np.ndarray, t0: float):
    """Least-squares line ``ln env = ln A - sigma (t - t0)``: ``(sigma, A, largest |residual|
    of ln env)``."""
    slope, intercept = np.polyfit(times - t0, np.log(env), 1)
    residual = np.log(env) - (intercept + slope * (times - t0))
    return -slope, np.exp(intercept), float(np.abs(residual).max())


def split_change(amplitude, sigma, r_threshold: float):
    """The amplitude and rate terms (s) of each neighbour's change from the optimum, index 0
    of the last axis (module docstring)."""
    a0, s0 = amplitude[..., :1], sigma[..., :1]
    return (np.log(amplitude / a0) / s0,
            np.log(amplitude / r_threshold) * (1 / sigma - 1 / s0))



#: The variables of :func:`ga_law_dataset`: (long name, units).
GA_LAW_VARIABLES = {
    "M": ("disk mass", "kg"),
    "mass_min": ("least ball mass of the GA's box", "kg"),
    "step": ("relative change of beta or m to a neighbour", "1"),
    "r_threshold": ("whirl radius of the balance criterion", "m"),
    "t_ramp": ("end of the run-up, where the line's A is read", "s"),
    "beta": ("ball damping ratio beta", "1"),
    "mass": ("ball mass", "kg"),
    "in_box": ("1 if the point lies in the GA's box (a candidate of the GA)", "1"),
    "balance_time": ("balance time of the integration (NaN if censored)", "s"),
    "sigma_fit": ("decay rate of the whirl's envelope after the run-up (fit)", "s-1"),
    "sigma_eigen": ("slowest non-neutral decay rate of the balanced state (eigenvalues)", "s-1"),
    "amplitude": ("whirl the passage leaves: the envelope's line at the end of the run-up", "m"),
    "fit_residual": ("largest |residual| of the line through ln(envelope)", "1"),
    "line_time": ("balance time by the line, t_ramp + ln(A / r_thr) / sigma (NaN if the whirl "
                  "does not decay)", "s"),
    "peak_law_time": ("balance time by the peak-force law t_pk + ln(F_pk / (k r_thr)) / sigma",
                      "s"),
    "amplitude_term": ("change of the line's time from the optimum through the amplitude, "
                       "ln(A_n / A_o) / sigma_o", "s"),
    "rate_term": ("change of the line's time from the optimum through the decay rate, "
                  "ln(A_n / r_thr) (1 / sigma_n - 1 / sigma_o)", "s"),
    "envelope": ("largest whirl radius r in each bin after the run-up", "m"),
    "envelope_time": ("time of the largest r in each bin", "s"),
}


def ga_law_dataset(setup: Setup, ga: xr.Dataset, ics: dict, beta_bounds, mass_bounds, *,
                   step: float, settle: float, horizon: float, width: float,
                   neutral: float) -> xr.Dataset:
    """The GA's optimum of every (kinematics, eps_bar, ic) of ``ga`` and its neighbours
    (:data:`NEIGHBOURS`, relative ``step``) integrated to ``horizon`` (s); the envelope of r
    from ``t_ramp + settle`` (the balls' own modes decayed) in bins of ``width``, its fitted
    ``A`` and ``sigma``, the balance time by that line and by the integration, the peak-force
    law's (:func:`~rotorvib.papers.b.law.balance_time_law`) and the two terms of the change."""
    criterion = dataclasses.replace(setup.criterion, t_end=horizon)
    t0, wn = setup.t_ramp, np.sqrt(setup.k / setup.M)
    shape = ga.beta_opt.shape + (len(NEIGHBOURS),)
    factors = 1 + step * np.array(list(NEIGHBOURS.values()), dtype=float)
    beta = ga.beta_opt.values[..., None] * factors[:, 0]
    mass = ga.mass_opt.values[..., None] * factors[:, 1]
    fields = ("balance_time", "sigma_fit", "amplitude", "residual", "force_peak", "t_peak")
    out = {k: np.full(shape, np.nan) for k in fields}
    envelopes = times_of = None
    for idx in np.ndindex(shape):
        kin, eps, ic = (ga[c].values[idx[i]] for i, c in enumerate(("kinematics_name", "eps_bar",
                                                                     "ic_name")))
        p, y0 = setup.run_inputs(mass=mass[idx], eps_bar=float(eps), beta=beta[idx],
                                 phi0_deg=ics[str(ic)], kinematics=str(kin))
        tr = run(layout.FIXED, p, y0, criterion, store=True, **setup.tolerances)
        times, env = envelope(tr.t, tr.r, t0 + settle, width)
        if envelopes is None:
            envelopes, times_of = (np.full(shape + times.shape, np.nan) for _ in range(2))
        envelopes[idx], times_of[idx] = env, times
        sigma, amp, residual = fit_decay(times, env, t0)
        result = tr.result
        for key, value in (("balance_time", np.nan if result.censored else result.balance_time),
                           ("sigma_fit", sigma), ("amplitude", amp), ("residual", residual),
                           ("force_peak", result.force_max), ("t_peak", result.force_max_time)):
            out[key][idx] = value
    eps_bar = ga.eps_bar.values[None, :, None, None]
    sigma_eig = slow_decay_rate(mass / setup.M, eps_bar, setup.zeta, beta, setup.omega / wn,
                                neutral=neutral) * wn
    r_thr = setup.criterion.r_threshold
    decaying = np.where(out["sigma_fit"] > 0, out["sigma_fit"], np.nan)   # else no line
    line = t0 + np.log(out["amplitude"] / r_thr) / decaying
    amplitude_term, rate_term = split_change(out["amplitude"], decaying, r_thr)
    in_box = ((beta >= beta_bounds[0]) & (beta <= beta_bounds[1])
              & (mass >= mass_bounds[0]) & (mass <= mass_bounds[1]))
    dims = ("kinematics", "eps_bar", "ic", "neighbour")
    law_time = balance_time_law(out["t_peak"], out["force_peak"], setup.k * r_thr, sigma_eig)
    return xr.Dataset(
        described({
            "M": ((), setup.M), "mass_min": ((), mass_bounds[0]), "step": ((), step),
            "r_threshold": ((), r_thr), "t_ramp": ((), t0),
            "beta": (dims, beta), "mass": (dims, mass), "in_box": (dims, in_box.astype(np.int8)),
            "balance_time": (dims, out["balance_time"]), "sigma_fit": (dims, out["sigma_fit"]),
            "sigma_eigen": (dims, sigma_eig), "amplitude": (dims, out["amplitude"]),
            "fit_residual": (dims, out["residual"]), "line_time": (dims, line),
            "peak_law_time": (dims, law_time), "amplitude_term": (dims, amplitude_term),
            "rate_term": (dims, rate_term), "envelope": (dims + ("bin",), envelopes),
            "envelope_time": (dims + ("bin",), times_of),
        }, GA_LAW_VARIABLES),
        coords={**{c: ga[c] for c in ("eps_bar", "kinematics_name", "ic_name")},
                **label_coord("neighbour", list(NEIGHBOURS), "point around the GA's optimum")},
        attrs=dataset_attrs(
            "what the GA's optimum is: the whirl its passage leaves and its decay",
            f"Beyond the paper: the GA's optimum of every problem and its neighbours (beta and "
            f"m changed by {step:g} of themselves) integrated to {horizon} s; the envelope of "
            f"r in {width} s bins from {settle} s after the run-up, a line through its log",
            "section 9"),
    )


def amplitude_share(ds: xr.Dataset, flat: float, *, resamples: int = 200,
                    seed: int = 0) -> tuple[Margin | None, int]:
    """Over every neighbour of a GA optimum in its box that balances: the share of the change
    of the line's time carried by the amplitude term, ``|amp| / (|amp| + |rate|)``, left out
    where the change is flat (the integrated balance time moves by no more than ``flat``
    seconds: a change the run does not resolve, which two terms cancelling to it share out
    arbitrarily); the :class:`Margin` of its median against 1/2 (uncertainty twice its
    bootstrap standard deviation; None where no neighbour is left) and the number of flat
    neighbours left out."""
    amp, rate = ds.amplitude_term.values[..., 1:], ds.rate_term.values[..., 1:]
    balanced = np.isfinite(ds.balance_time.values)
    candidates = ((ds.in_box.values[..., 1:] == 1) & balanced[..., 1:] & balanced[..., :1]
                  & np.isfinite(amp) & np.isfinite(rate))
    with np.errstate(invalid="ignore"):
        change = ds.balance_time.values[..., 1:] - ds.balance_time.values[..., :1]
        flat_change = candidates & (np.abs(change) <= flat)
    use = candidates & ~flat_change
    if not use.any():
        return None, int(flat_change.sum())
    share = (np.abs(amp) / (np.abs(amp) + np.abs(rate)))[use]
    rng = np.random.default_rng(seed)
    spread = np.std([np.median(rng.choice(share, share.size)) for _ in range(resamples)])
    return (Margin(float(np.median(share)) - 0.5, 2 * float(spread), "share of the change",
                   f"bootstrap over {share.size} neighbours"), int(flat_change.sum()))


def ga_law_rows(ds: xr.Dataset, *, flat: float, flat_alternatives=(), resamples: int = 200,
                seed: int = 0) -> list[Reproduced]:
    """Beyond the paper: is the GA's optimum the point whose passage leaves the least whirl,
    rather than the one whose whirl decays fastest?  The median share of the amplitude term
    (:func:`amplitude_share`) with the flat changes left out below ``flat`` seconds, and below
    each of ``flat_alternatives`` (DEPENDS where they disagree).  The explanation gives how
    often the optimum leaves the least whirl, the fit against the eigenvalues and the
    integration, and the peak-force law there."""
    margin, n_flat = amplitude_share(ds, flat, resamples=resamples, seed=seed)
    holds = under_choice(lambda f: amplitude_share(ds, f, resamples=resamples, seed=seed)[0],
                         FLAT_KEY, flat, flat_alternatives, "s")
    left_out = (f"{n_flat} neighbours whose change is flat, within {flat:g} s, left out: no "
                "term carries it")
    if margin is None:
        why = f"all {left_out}" if n_flat else "no neighbour of a GA optimum balances"
        return [Reproduced.claim("B", "law_explains_ga_optimum", holds, f"undetermined: {why}",
                                 choices=GA_LAW_CHOICES)]
    share = margin.value + 0.5
    optimum = pick(ds, neighbour="optimum")
    least = (ds.amplitude.values[..., :1] <= ds.amplitude.values[..., 1:]).all(axis=-1)
    heavier = (pick(ds, neighbour="mass_high").line_time - optimum.line_time).values
    light = optimum.mass.values <= 1.01 * float(ds.mass_min)
    line_err = np.abs(ds.line_time.values - ds.balance_time.values)
    peak_err = (optimum.peak_law_time - optimum.balance_time).values
    fit_vs_eigen = np.abs(ds.sigma_fit.values / ds.sigma_eigen.values - 1)
    apart = fit_vs_eigen > 0.1
    to_bound = (ds.mass / (ds.M * ds.eps_bar / 2)).values   # 1 on the existence bound (34)
    problems = least.size
    return [Reproduced.claim(
        "B", "law_explains_ga_optimum", holds,
        f"around each of the GA's {problems} optima (beta and m moved by {float(ds.step):.0%}; "
        f"{left_out}) "
        f"the whirl after the run-up decays on a line of the log scale (largest residual "
        f"{np.nanmax(ds.fit_residual.values):.2f} in ln r; its balance time within "
        f"{np.nanmax(line_err):.2f} s of the integration's). The amplitude the passage leaves "
        f"carries {share:.0%} of the change to a neighbour at the median, the decay "
        f"rate the rest: the optimum leaves the least whirl of its neighbours in "
        f"{int(least.sum())} of {problems} problems, while the fitted rate varies little (it "
        f"equals the slowest eigenvalue's within {np.nanmedian(fit_vs_eigen):.1%} at the "
        f"median; {int(apart.sum())} of {apart.size} points differ by more than 10 %"
        + (f", all within {to_bound[apart].max() - 1:.1%} of the existence bound m = M "
           f"eps_bar / 2, where a nearly neutral mode is the slowest but hardly moves r"
           if apart.any() else "") + f"). Heavier balls (+{float(ds.step):.0%}) "
        f"balance later at {int(np.sum(heavier > 0))} of {problems} optima (median "
        f"{np.nanmedian(heavier):+.2f} s), and the GA's mass lies within 1 % of its box's least "
        f"({1e3 * float(ds.mass_min):g} g) at {int(np.sum(light))} of {problems}. "
        f"The peak-force law misses the optimum (median error {np.nanmedian(peak_err):+.2f} s "
        f"there): the peak force of the passage is not the whirl it leaves",
        choices=GA_LAW_CHOICES)]
