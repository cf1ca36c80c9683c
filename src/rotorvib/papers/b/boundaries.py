"""Beyond paper B: the stability boundary of the balanced state, traced by continuation far
beyond the grids of Figs 2-3.

The balanced state turns stable where an eigenvalue ``lambda`` of its linearisation (eqs 27-32,
:func:`rotorvib.papers.b.stability_maps.balanced_eigenvalues`) crosses the imaginary axis:
``Re lambda(p, omega_bar) = 0`` is a curve in the plane of one parameter ``p`` (beta, m_bar or
zeta) and the speed.  It is traced by pseudo-arclength continuation
(:mod:`rotorvib.methods.continuation`) in ``(log10 p, omega_bar)``, following the crossing
eigenvalue by continuity (the nearest one to its last value), so the curve stays smooth where
another eigenvalue takes the lead.  Along it: the crossing's frequency ``Im lambda`` (a Hopf
crossing where it is not zero), whether every other eigenvalue is stable there (then the curve
is the boundary of the stable region), and its folds in ``p`` and ``omega_bar``.

As ``beta -> inf`` the balls follow the rotor quasi-statically: eliminating the rotor from
``M q'' + C q' + K q = 0`` leaves ``mu beta a' = -K_ar K_rr^-1 K_ra a`` for the ball angles,
whose trace is proportional to ``1 - Omega^2`` (Omega on the total-mass scale): the onset tends
to the critical speed ``1 / sqrt(1 + n m_bar)`` of paper B's scale, from above.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from rotorvib.comparison.reproduced import Margin, Reproduced
from rotorvib.io.tables import order_bound
from rotorvib.io.variables import described
from rotorvib.models.balancer import stability
from rotorvib.methods import routh
from rotorvib.methods.continuation import (gradient, refine_turning_point, tangent, trace,
                                           turning_points)
from rotorvib.papers.b.choices import BOUNDARY_CHOICES
from rotorvib.papers.b.boundary_limits import approach_coefficient, lowest_beta, on_boundary
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.stability_maps import balanced_eigenvalues, growth_rate

PLANES = {"beta": "ball damping ratio beta", "m_bar": "ball/disk mass ratio m/M",
          "zeta": "support damping ratio zeta"}


def leading(eig: np.ndarray) -> complex:
    """The eigenvalue of largest real part, of its pair the one with ``Im >= 0``."""
    return eig[np.argmax(np.where(eig.imag >= 0, eig.real, -np.inf))]


class TrackedEigenvalue:
    """``Re lambda`` of one eigenvalue of the balanced state, followed by continuity over
    ``z = (log10 p, omega_bar)``: at every call the eigenvalue nearest the last accepted one.
    Every accepted point records the eigenvalue, the largest real part of the others and the
    speed error ``|Re lambda| / |d Re lambda / d omega_bar|`` of the point (Newton's
    first-order bound)."""

    def __init__(self, plane: str, fixed: dict, n: int, current: complex):
        self.plane, self.fixed, self.n, self.current = plane, fixed, n, current
        self.crossing: list[complex] = []
        self.others: list[float] = []
        self.speed_error: list[float] = []

    def eigenvalues(self, z) -> np.ndarray:
        """The eight eigenvalues at ``z``."""
        return balanced_eigenvalues(**{**self.fixed, self.plane: 10.0 ** z[0]},
                                    omega_bar=z[1], n=self.n)

    def split(self, z) -> tuple[complex, np.ndarray]:
        """The eigenvalue at ``z`` nearest the tracked one, and the others (its conjugate
        left out)."""
        eig = self.eigenvalues(z)
        lam = eig[np.argmin(np.abs(eig - self.current))]
        return lam, eig[(np.abs(eig - lam) > 1e-9) & (np.abs(eig - np.conj(lam)) > 1e-9)]

    def leading_other(self, z) -> complex:
        """The eigenvalue with the largest real part apart from the tracked pair."""
        return leading(self.split(z)[1])

    def __call__(self, z) -> float:
        """``Re lambda`` at ``z``; NaN where the linearisation does not exist: the mass matrix
        is singular (balls so heavy, p ~ 1e17, that mu rounds to 1/2) or not finite -- where a
        corrector step far outside the plane can land (found by the configuration fuzzer), and
        which :func:`rotorvib.methods.continuation.trace` treats as a failed step; also where
        the groups leave the linearisation's domain (rotorvib.models.balancer.stability.groups:
        a ratio beyond 1e100, for one)."""
        try:
            return float(self.split(z)[0].real)
        except (np.linalg.LinAlgError, ValueError):
            return math.nan

    def accept(self, z) -> None:
        """Follow the eigenvalue to the accepted point ``z`` and record it."""
        self.current, others = self.split(z)
        self.crossing.append(self.current)
        self.others.append(float(others.real.max()))
        slope = (self(z + [0.0, 1e-6]) - self(z - [0.0, 1e-6])) / 2e-6
        self.speed_error.append(abs(self.current.real / slope))


def window_edges(plane: str, fixed: dict, p: float, omega_max: float, n: int,
                 samples: int) -> list[float]:
    """The lower edges of the stable windows on the line ``plane = p``: the unstable -> stable
    sign changes of the growth rate on ``samples`` log-spaced speeds from 0.05 to
    ``omega_max``, refined by Brent's method."""
    from scipy.optimize import brentq  # here: the jobs that read the boundaries invert none

    speeds = np.geomspace(0.05, omega_max, samples)
    args = {**fixed, plane: p}
    growth = growth_rate(omega_bar=speeds, n=n, **args)
    rises = np.flatnonzero((growth[:-1] > 0) & (growth[1:] <= 0))
    return [brentq(lambda w: float(growth_rate(omega_bar=w, n=n, **args)), speeds[i],
                   speeds[i + 1], xtol=1e-14) for i in rises]


def onset(plane: str, fixed: dict, p: float, omega_max: float, n: int, samples: int) -> float:
    """The lowest speed at which the balanced state turns stable at ``plane = p``: the first
    of :func:`window_edges`."""
    edges = window_edges(plane, fixed, p, omega_max, n, samples)
    if not edges:
        raise ValueError(f"the balanced state never turns stable below omega_bar = {omega_max} "
                         f"at {plane} = {p}: no boundary to start from")
    return edges[0]


#: The beta of the onsets from which the asymptote ``a`` is extrapolated, and the digits of
#: their arithmetic (:func:`approach_limit`).
ASYMPTOTE_BETAS, ASYMPTOTE_DIGITS = (1e5, 1e6, 1e7), 50
_ASYMPTOTE_METHOD = (f"onsets in {ASYMPTOTE_DIGITS}-digit arithmetic at beta = "
                     + ", ".join(f"{b:.0e}".replace("+0", "") for b in ASYMPTOTE_BETAS))


def exact_onset(fixed: dict, beta: float, n: int, *, digits: int):
    """The onset of stability just above the critical speed ``omega_c`` at a large ``beta``,
    as an ``mpmath.mpf`` good to about ``digits - 10`` digits: bisection between ``omega_c``
    and ``omega_c + 10 / beta`` on Routh's criterion (:mod:`rotorvib.methods.routh`) for the
    characteristic polynomial, its coefficients evaluated in ``digits``-digit arithmetic from
    paper B's groups (eq. 25: ``s = sqrt(1 + n m_bar)``, ``mu = m_bar / s^2``,
    ``rho = m_bar / eps_bar``, ``zeta / s``, ``beta s``, ``omega_bar s``).  No eigenvalue and no
    BLAS call: the result is the same on every machine, where eigenvalues in double precision
    lose the growth rate near ``omega_c`` (about 1e-11 at ``beta = 1e6``) in their round-off.
    ``ValueError`` if the state is not unstable just above ``omega_c`` and stable at the
    bracket's top."""
    import mpmath

    with mpmath.workdps(digits):
        m_bar, eps_bar, zeta = (mpmath.mpf(fixed[k]) for k in ("m_bar", "eps_bar", "zeta"))
        s = mpmath.sqrt(1 + n * m_bar)

        def stable(omega_bar):
            coefficients = stability.exact_characteristic_coefficients(
                m_bar / s**2, m_bar / eps_bar, zeta / s, mpmath.mpf(beta) * s, omega_bar * s)
            return bool(routh.stable(coefficients, dtype=object))

        low, high = 1 / s, 1 / s + mpmath.mpf(10) / beta
        if stable(low + mpmath.mpf(10) ** (10 - digits)) or not stable(high):
            raise ValueError(f"at beta = {beta:g} the balanced state does not turn stable "
                             "between the critical speed and 10 / beta above it")
        while high - low > mpmath.mpf(10) ** (10 - digits):
            middle = (low + high) / 2
            low, high = (low, middle) if stable(middle) else (middle, high)
        return (low + high) / 2


def approach_limit(fixed: dict, n: int, *, betas=ASYMPTOTE_BETAS,
                   digits: int = ASYMPTOTE_DIGITS) -> tuple[float, float]:
    """``a = lim beta (omega_onset - omega_c)`` as ``beta -> inf`` (``omega_c`` the critical
    speed ``1 / sqrt(1 + n m_bar)``): ``beta (onset - omega_c)`` at ``betas`` (onsets in
    ``digits``-digit arithmetic, :func:`exact_onset`), extrapolated as ``a + b / beta`` from the
    last two; the error bound is its distance to the extrapolation from the first two.  Every
    step is exact to far below that bound, so ``a`` is the same on every machine."""
    import mpmath

    with mpmath.workdps(digits):
        critical = 1 / mpmath.sqrt(1 + n * mpmath.mpf(fixed["m_bar"]))
        scaled = [mpmath.mpf(b) * (exact_onset(fixed, b, n, digits=digits) - critical)
                  for b in betas]

        def extrapolate(i):
            (b1, b2), (a1, a2) = betas[i:i + 2], scaled[i:i + 2]
            return (b2 * a2 - b1 * a1) / (b2 - b1)

        a = extrapolate(len(betas) - 2)
        return float(a), float(abs(a - extrapolate(len(betas) - 3)))


def _branches(plane, fixed, z0, *, bounds, step, tol, neutral, n, max_branches=4,
              senses=(-1.0, 1.0)):
    """Trace the crossing curve through ``z0`` in each of ``senses`` (down, up in the
    parameter); where another eigenvalue turns unstable along it (a corner of the stable
    region), switch to that eigenvalue's curve at the corner and go on along it into the side
    where the old eigenvalue is stable.  Yields ``(curve, tracker, points to keep)`` per
    branch."""
    for sense in senses:
        lead = leading(TrackedEigenvalue(plane, fixed, n, 0j).eigenvalues(z0))
        start, direction = z0, np.array([sense, 0.0])
        for _ in range(max_branches):
            tracker = TrackedEigenvalue(plane, fixed, n, lead)
            curve = trace(tracker, start, direction, bounds=bounds, step=step["initial"],
                          min_step=step["min"], max_step=step["max"], tol=tol,
                          accept=tracker.accept)
            others = np.asarray(tracker.others)
            leaves = np.flatnonzero((others[:-1] < -neutral) & (others[1:] >= -neutral))
            if not leaves.size:
                yield curve, tracker, len(curve.points)
                break
            corner = leaves[0] + 1
            yield curve, tracker, corner + 1
            start = curve.points[corner]
            lead = tracker.leading_other(start)
            # the boundary goes on along the new curve into the side where the old
            # eigenvalue is stable
            along = tangent(gradient(TrackedEigenvalue(plane, fixed, n, lead), start, 1e-7),
                            direction)
            direction = along if tracker(start + 1e-4 * along) < tracker(start - 1e-4 * along) \
                else -along


def _crossings_at(x: float, parts: list, reach: float = 1e-3) -> list[float]:
    """The speeds at which the traced parts ending within ``reach`` of ``log10 p = x`` cross
    that line (their last point moved along its tangent onto it)."""
    found = []
    for points, tangents, *_ in parts:
        (px, pw), (tx, tw) = points[-1], tangents[-1]
        if abs(px - x) < reach and abs(tx) > 1e-12:
            found.append(pw + tw / tx * (x - px))
    return found


#: The boundary dataset's variables of fixed names, all dimensionless: (long name, units).
BOUNDARY_VARIABLES = {
    "omega_onset": ("speed ratio omega/omega_n on the curve Re lambda = 0", "1"),
    "branch": ("branch of the traced curves (0, 1, ...: downwards in the parameter from the "
               "start, then upwards, then each window)", "1"),
    "curve": ("traced curve: 0 through the start, 1, 2, ...: a stable window found on the line "
              "at the range's top", "1"),
    "frequency": ("|Im lambda| / omega_n of the crossing eigenvalue (0: a real eigenvalue "
                  "crosses)", "1"),
    "crossing_real": ("Re lambda / omega_n of the crossing eigenvalue (continuation residual)",
                      "1"),
    "omega_error": ("error bound of the speed on the curve, |Re lambda| / |d Re lambda / d "
                    "omega_bar|", "1"),
    "others_growth": ("largest real part of the other eigenvalues / omega_n", "1"),
    "on_boundary": ("the curve bounds the stable region here (every other eigenvalue stable)",
                    "1"),
    "critical_speed": ("undamped critical speed of disk and balls, sqrt(M/(M + n m)) "
                       "(omega_bar)", "1"),
    "asymptote_a": ("a = lim beta (omega_onset - critical speed) as beta grows, extrapolated "
                    f"from {_ASYMPTOTE_METHOD}", "1"),
    "asymptote_error": ("error bound of a: the two extrapolations apart", "1"),
}


def _plane_variables(plane: str, tangents, folds: dict, turns: dict, fixed: dict,
                     start: float) -> dict:
    """The boundary dataset's variables named or described by its plane: the tangent, the
    folds and turning points in each coordinate, the fixed parameters and the start."""
    one = {"units": "1"}
    return {
        "tangent": (("point", "component"), tangents,
                    {"long_name": f"unit tangent in (log10 {plane}, omega_bar), in the "
                                  "branch's sense of tracing", **one}),
        **{f"fold_{name}": (f"fold_{name}", np.asarray(idx, dtype=np.int32),
                            {"long_name": f"index of the point after which the curve turns "
                                          f"back in {name}", **one})
           for name, idx in folds.items()},
        **{f"turn_{name}_{coord}": (f"fold_{name}", np.array(
            [10.0 ** z[0] if coord == plane else z[1] for z, _ in turns[name]], dtype=float),
            {"long_name": f"{coord} where the curve turns back in {name}, located by "
                          "solving Re lambda = 0 with its tangency condition", **one})
           for name in folds for coord in (plane, "omega_bar")},
        **{f"turn_{name}_error": (f"fold_{name}", np.array([e for _, e in turns[name]],
                                                            dtype=float),
                                  {"long_name": f"error bound of that point in (log10 {plane}, "
                                                "omega_bar)", **one})
           for name in folds},
        **{f"fixed_{k}": ((), float(v), {"long_name": PLANES.get(k, k), **one})
           for k, v in fixed.items()},
        "start": ((), float(start), {"long_name": f"{plane} at which tracing starts", **one}),
    }


def boundary_dataset(plane: str, *, fixed: dict, p_range, start: float, omega_max: float,
                     step: dict, tol: float, neutral: float, window_samples: int,
                     n: int = 2) -> xr.Dataset:
    """The stability boundary through the onset of stability at ``plane = start``, traced
    both ways over ``p_range`` (and speeds up to ``omega_max``) as branches of crossing
    curves ``Re lambda = 0`` joined at corners (:func:`_branches`), with each point's
    crossing frequency, the largest real part of the other eigenvalues (the curve bounds the
    stable region where it is below ``-neutral``), the critical speed and the branch's folds.
    Every other stable window on the line ``plane = p_range[1]`` (:func:`window_edges` with
    ``window_samples`` speeds) is traced too, downwards from its lower edge: curve 1, 2, ...
    (curve 0 is the one through the start)."""
    if plane not in PLANES:
        raise ValueError(f"plane must be one of {sorted(PLANES)}, not {plane!r}")
    bounds = (np.log10(p_range), (0.0, omega_max))
    parts, stops, folds = [], [], {plane: [], "omega_bar": []}

    def add(z0, senses, index):
        for curve, tracker, keep in _branches(plane, fixed, z0, bounds=bounds, step=step,
                                              tol=tol, neutral=neutral, n=n, senses=senses):
            k = slice(0, keep)
            offset = sum(len(part[0]) for part in parts)
            for j, name in enumerate((plane, "omega_bar")):
                folds[name] += list(offset + turning_points(curve.tangents[k, j]))
            parts.append((curve.points[k], curve.tangents[k], np.asarray(tracker.crossing)[k],
                          np.asarray(tracker.others)[k], np.asarray(tracker.speed_error)[k],
                          np.full(keep, len(parts), dtype=np.int32),
                          np.full(keep, index, dtype=np.int32)))
            stops.append(curve.stop if keep == len(curve.points) else "corner")

    add(np.array([np.log10(start), onset(plane, fixed, start, omega_max, n, window_samples)]),
        (-1.0, 1.0), 0)
    top = np.log10(p_range[1])
    windows = 0
    for edge in window_edges(plane, fixed, p_range[1], omega_max, n, window_samples):
        if all(abs(edge - w) > 1e-6 * edge for w in _crossings_at(top, parts)):
            windows += 1
            add(np.array([top, edge]), (-1.0,), windows)
    points, tangents, crossing, others, error, branch, curve_of = (
        np.concatenate(c) for c in zip(*parts))
    limit = approach_limit(fixed, n) if plane == "beta" else None
    turns = {name: [refine_turning_point(TrackedEigenvalue(plane, fixed, n, crossing[i]),
                                         points[i], axis=0 if name == plane else 1)
                    for i in idx] for name, idx in folds.items()}
    p, omega = 10.0 ** points[:, 0], points[:, 1]
    m_bar = p if plane == "m_bar" else np.full(p.shape, fixed["m_bar"])
    one = {"units": "1"}
    variables = described({
        "omega_onset": ("point", omega), "branch": ("point", branch),
        "curve": ("point", curve_of), "frequency": ("point", np.abs(crossing.imag)),
        "crossing_real": ("point", crossing.real), "omega_error": ("point", error),
        "others_growth": ("point", others),
        "on_boundary": ("point", (others < -neutral).astype(np.int8)),
        "critical_speed": ("point", 1 / np.sqrt(1 + n * m_bar)),
        **({"asymptote_a": ((), limit[0]), "asymptote_error": ((), limit[1])} if limit else {}),
    }, {k: v for k, v in BOUNDARY_VARIABLES.items() if limit or not k.startswith("asymptote")})
    variables["on_boundary"][2].update(flag_values=np.int8([0, 1]), flag_meanings="no yes")
    return xr.Dataset(
        {**variables, **_plane_variables(plane, tangents, folds, turns, fixed, start)},
        coords={plane: ("point", p, {"long_name": PLANES[plane], **one}),
                "component": ("component", np.array([f"log10 {plane}", "omega_bar"],
                                                    dtype=object),
                              {"long_name": "component of the tangent"})},
        attrs=dataset_attrs(f"stability boundary in ({plane}, omega_bar), beyond Figs 2-3",
                            "The curve Re lambda = 0 of the balanced state's linearisation "
                            "(eqs 27-32) by pseudo-arclength continuation; branches end: "
                            + ", ".join(stops), "Figs 2-3"),
    )


def boundary_rows(planes: dict[str, xr.Dataset]) -> list[Reproduced]:
    """Beyond the paper, on the whole traced boundary: does stability start above the critical
    speed everywhere (Figs 2-3's first claim), and is there a least beta that balances at any
    speed (their "range of parameters")?"""
    edges = {plane: on_boundary(ds) for plane, ds in planes.items()}
    excess = {plane: (e.omega_onset - e.critical_speed).values for plane, e in edges.items()}
    lowest = min(excess, key=lambda plane: excess[plane].min())
    i = int(np.argmin(excess[lowest]))
    error = max(float(e.omega_error.max()) for e in edges.values())
    spans = "; ".join(f"{plane} {float(e[plane].min()):.3g}-{float(e[plane].max()):.3g}"
                      for plane, e in edges.items())
    beta = planes["beta"]
    fitted, top_spread = approach_coefficient(beta)
    a, a_error = float(beta.asymptote_a), float(beta.asymptote_error)
    folds = beta.fold_omega_bar.values
    extremes = ", ".join(f"{w:.6f} at beta = {b:.6g} (+/- {order_bound(e)} in (log10 beta, "
                         "omega_bar), "
                         "located by Re lambda = 0 and d Re lambda / d beta = 0)"
                         for w, b, e in zip(beta.turn_omega_bar_omega_bar.values,
                                            beta.turn_omega_bar_beta.values,
                                            beta.turn_omega_bar_error.values))
    fold_text = (f"the onset has extremes {extremes}" if folds.size
                 else "the onset falls monotonically with beta")
    b_min, at, b_moves = lowest_beta(beta)
    windows = "".join(
        f"; in the ({plane}, omega_bar) plane a second stable window opens for {plane} above "
        f"{float(w[plane].min()):.3g} (its tip, at omega_bar = "
        f"{float(w.omega_onset[int(np.argmin(w[plane].values))]):.3f}), just above the "
        f"critical speed (closest {float((w.omega_onset - w.critical_speed).min()):.1e})"
        for plane, e in edges.items()
        for w in [e.isel(point=e.curve.values > 0)] if w.sizes["point"])
    # The excess tends to 0 as beta grows (onset -> critical speed as a / beta): its least value
    # is set by the traced range's top, not by the balancer. The margin is a, the scale-free
    # excess, unless another plane's onset falls below its critical speed.
    worst_other = min((float(excess[p].min()) for p in excess if p != "beta"), default=np.inf)
    margin = (Margin(worst_other, error, "omega_bar", "continuation; uncertainty: the largest "
                     "speed error bound on the curve") if worst_other < 0 else
              Margin(a, a_error, "beta x omega_bar", "a = lim beta (omega_onset - omega_c), "
                     f"extrapolated from {_ASYMPTOTE_METHOD}; uncertainty: two extrapolations "
                     "apart"))
    return [
        Reproduced.claim(
            "B", "boundary_above_critical", margin,
            f"on the whole boundary traced by continuation ({spans}) the onset lies above the "
            f"critical speed, closest {excess[lowest][i]:.2e} at {lowest} = "
            f"{float(edges[lowest][lowest][i]):.3g}, a distance the traced range sets: as "
            f"beta grows the onset tends to the critical speed from above as a / beta, a = "
            f"{a:.6f} +/- {a_error:.1e} from its limit (a fit over the traced top decade gives "
            f"{fitted:.6f}, beta (omega - omega_c) at the top within {top_spread:.1e} of it), "
            "so the onset's infimum is the critical speed itself and the margin is a, not the "
            "least excess. The balls then follow the rotor "
            "quasi-statically, and the reduced ball equation's trace changes sign exactly at "
            f"the critical speed{windows}", choices=BOUNDARY_CHOICES),
        Reproduced.claim(
            "B", "boundary_lowest_beta",
            Margin(b_min, b_moves, "1", "the least beta on the boundary; uncertainty: how much "
                                        "it moves from half the highest traced speed"),
            f"no speed up to {at:.0f} balances beta below {b_min:.4g}: the boundary rises "
            f"vertically there (beta moves by {b_moves:.1e} over the last half of the speeds), "
            f"so beta = 0 and a band above it never balance; above the least beta every beta up "
            f"to {float(beta.beta.max()):.3g} balances at a high enough speed (no upper end); "
            f"{fold_text}, so between those speeds the beta between the curve's two branches "
            "do not balance", choices=BOUNDARY_CHOICES),
    ]
