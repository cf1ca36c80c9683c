"""Paper B's discrepancy analysis: the printed balance and decay times the reproduction misses,
recomputed under the hypotheses of :mod:`rotorvib.comparison.discrepancy`.

A quantity is a few runs of the balancer (keywords of :meth:`Setup.run_inputs`) reduced to one
number: the mean of a metric over the runs (Fig 7's balance time, Table 2's decay times, Table
1's mean over the initial conditions) or the reduction ``100 (1 - q_last / q_first)`` of Table
2's text.  Its definitions are the engine's metrics the paper's wording allows (threshold or
envelope balance time, force decay); its variants the kinematics; its parameters the setup's
(``zeta``, ``R``, ``r0``, ``t_ramp``, ``r_threshold``) and the runs' (``beta``, ``mass``,
``eps_bar``, ``speed``).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from rotorvib.comparison.discrepancy import Hypothesis, Inversion, invert, parameter_slips
from rotorvib.models.balancer.layout import metric
from rotorvib.papers.b.setup import Setup

#: Parameters of the setup and of a run, with their units (for the unit slips).
SETUP_UNITS = {"zeta": "1", "R": "m", "r0": "m", "t_ramp": "s", "r_threshold": "m"}
RUN_UNITS = {"beta": "1", "mass": "kg", "eps_bar": "1", "speed": "rad/s"}
#: Engine metrics a printed time may stand for.
DEFINITIONS = {"balance_time": "threshold balance time", "envelope_time":
               "envelope through the peaks of r(t)", "force_decay_time":
               "bearing force below k r_threshold", "force_max": "peak bearing force"}


@dataclass(frozen=True)
class Quantity:
    """A printed number as runs of the balancer, a metric and how the runs combine."""

    name: str
    runs: tuple[dict, ...]
    metric: str
    definitions: tuple[str, ...] = ()
    combine: str = "mean"

    def value(self, metrics: np.ndarray, name: str | None = None) -> float:
        """The quantity from the metrics of its runs (rows in the order of ``runs``)."""
        v = metric(metrics, name or self.metric)
        if self.combine == "reduction":
            return float(100 * (1 - v[-1] / v[0]))
        return float(np.mean(v))

    def stated(self, setup: Setup, name: str) -> float | None:
        """The stated value of a parameter, None for a run parameter that differs between runs."""
        if name == "r_threshold":
            return setup.criterion.r_threshold
        if name in SETUP_UNITS:
            return getattr(setup, name)
        values = {run[name] for run in self.runs}
        return values.pop() if len(values) == 1 else None


def quantities(config: dict, m_opt: dict[int, float]) -> list[Quantity]:
    """Fig 7's balance time, Table 2's decay times and reductions and Table 1's mean times
    (at the reproduced optimum mass ``m_opt[speed]``) from the ``paper_b`` config."""
    ics, M, speed = config["initial_conditions"], config["machine"]["M"], config["speed"]["omega"]
    f7 = config["time_responses"]["fig7"]
    fig7 = {"beta": f7["beta"], "mass": f7["m_bar"] * M, "eps_bar": f7["eps_bar"],
            "phi0_deg": tuple(f7["phi0"]), "speed": speed}
    t2 = config["table2"]
    rows = [{"beta": b, "mass": m, "eps_bar": t2["eps_bar"], "phi0_deg": tuple(ics[t2["ic"]]),
             "speed": t2["speed"]} for b, m in t2["cases"]]
    times = ("balance_time", "envelope_time")
    out = [Quantity("fig7_balance_time", (fig7,), "envelope_time", times)]
    for i, row in enumerate(rows, 1):
        out.append(Quantity(f"table2_fmax_{i}", (row,), "force_max"))
        out.append(Quantity(f"table2_decay_{i}", (row,), "force_decay_time", times))
    out.append(Quantity("table2_reduction_force", (rows[0], rows[-1]), "force_max",
                        combine="reduction"))
    out.append(Quantity("table2_reduction_time", (rows[0], rows[-1]), "force_decay_time", times,
                        combine="reduction"))
    t1 = config["table1"]
    for s, m in m_opt.items():
        runs = tuple({"beta": t1["beta"], "mass": m, "eps_bar": t1["eps_bar"],
                      "phi0_deg": tuple(phi), "speed": float(s)} for phi in ics.values())
        out.append(Quantity(f"table1_mean_time_{s}", runs, "balance_time", times[1:]))
    return out


def _with(setup: Setup, overrides: dict) -> Setup:
    fields = {k: v for k, v in overrides.items() if k in SETUP_UNITS and k != "r_threshold"}
    if "r_threshold" in overrides:
        r = overrides["r_threshold"]
        fields["criterion"] = replace(setup.criterion, r_threshold=r, f_threshold=setup.k * r)
    return replace(setup, **fields)


def run_all(setup: Setup, requests, memo: dict | None = None) -> list[np.ndarray]:
    """Metrics of the runs of each ``(quantity, kinematics, overrides)`` request, batched by
    balance criterion (one parallel batch per distinct criterion).

    A run already in ``memo`` (kept by the caller across calls, keyed by criterion, parameters
    and initial state) is not made again: the analysis asks for about a fifth of its runs twice
    (a Table 2 row's peak force and decay time are one run, and so are their scans)."""
    memo = {} if memo is None else memo
    keys, pending = [], {}
    for q, kinematics, overrides in requests:
        s = _with(setup, overrides)
        run_over = {k: v for k, v in overrides.items() if k in RUN_UNITS}
        inputs = [s.run_inputs(**{**run, **run_over}, kinematics=kinematics) for run in q.runs]
        keys.append([(s.criterion, p.tobytes(), y0.tobytes()) for p, y0 in inputs])
        pending.update((k, run) for k, run in zip(keys[-1], inputs) if k not in memo)
    for criterion in dict.fromkeys(k[0] for k in pending):
        mine = [k for k in pending if k[0] == criterion]
        metrics = replace(setup, criterion=criterion).runs([pending[k] for k in mine],
                                                           progress=False)
        memo.update(zip(mine, metrics))
    return [np.array([memo[k] for k in request]) for request in keys]


def hypotheses(setup: Setup, quantity_list, kinematics: list[str], parameters: list[str],
               memo: dict | None = None) -> tuple[dict, list[Hypothesis]]:
    """Each quantity's baseline (first kinematics, its own metric, stated parameters) and its
    value under every other definition and kinematics and every slip of ``parameters``
    (``memo``: runs already made, :func:`run_all`)."""
    base_kin = kinematics[0]
    requests, labels = [], []
    for q in quantity_list:
        for kin in kinematics:
            requests.append((q, kin, {}))
            labels.append((q, kin, None))
        for name in parameters:
            stated = q.stated(setup, name)
            if stated is None:
                continue
            unit = SETUP_UNITS.get(name) or RUN_UNITS[name]
            for label, value in parameter_slips(name, unit, stated):
                requests.append((q, base_kin, {name: value}))
                labels.append((q, base_kin, label))
    baselines, found = {}, []
    for (q, kin, slip), metrics in zip(labels, run_all(setup, requests, memo)):
        if slip is not None:
            found.append(Hypothesis(q.name, slip, "parameter slip", q.value(metrics)))
            continue
        for d in (q.metric, *q.definitions):
            if kin == base_kin and d == q.metric:
                baselines[q.name] = q.value(metrics)
                continue
            name = DEFINITIONS[d] + ("" if kin == base_kin else f", {kin} kinematics")
            found.append(Hypothesis(q.name, name, "definition" if kin == base_kin else "variant",
                                    q.value(metrics, d)))
    return baselines, found


def inversions(setup: Setup, quantity: Quantity, printed: float, kinematics: str,
               parameters: list[str], factor_range, n_scan: int,
               memo: dict | None = None) -> list[Inversion]:
    """For each parameter, the value in ``stated * factor_range`` that reproduces ``printed``
    (``memo``: runs already made, :func:`run_all`)."""
    out = []
    for name in parameters:
        stated = quantity.stated(setup, name)
        if stated is None or stated <= 0:
            continue

        def evaluate(xs, name=name):
            runs = run_all(setup, [(quantity, kinematics, {name: float(x)}) for x in xs], memo)
            return np.array([quantity.value(m) for m in runs])

        out.append(invert(evaluate, printed, stated, stated * factor_range[0],
                          stated * factor_range[1], quantity=quantity.name, parameter=name,
                          n_scan=n_scan))
    return out
