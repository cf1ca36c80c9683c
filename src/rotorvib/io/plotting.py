"""Shared figure style and output: readable defaults, the paper's values drawn, deterministic PNGs."""

from __future__ import annotations

import textwrap
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "figure.figsize": (7.0, 4.3),
    "figure.dpi": 110,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.titlesize": 11,
    "axes.labelsize": 10,
    "legend.fontsize": 8.5,
    "savefig.bbox": "tight",
    "figure.constrained_layout.use": True,
}
PAPER_STYLE = {"color": "crimson", "linestyle": "--", "linewidth": 1.2}


def figure(nrows: int = 1, ncols: int = 1, **kwargs):
    with plt.rc_context(STYLE):
        return plt.subplots(nrows, ncols, **kwargs)


def paper_hline(ax, value: float, label: str) -> None:
    """Draw the paper's stated value as a dashed horizontal line."""
    ax.axhline(value, **PAPER_STYLE, label=f"paper: {label}")


def paper_vline(ax, value: float, label: str) -> None:
    ax.axvline(value, **PAPER_STYLE, label=f"paper: {label}")


def paper_point(ax, x: float, y: float, label: str) -> None:
    ax.plot([x], [y], marker="*", markersize=13, color=PAPER_STYLE["color"], linestyle="none",
            label=f"paper: {label}")


def _value(value) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, list):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    if isinstance(value, dict) and set(value) == {"min", "max", "n"}:
        return f"{_value(value['min'])}..{_value(value['max'])} ({value['n']} points)"
    if isinstance(value, dict):
        return ", ".join(f"{k} ({_value(v)})" if isinstance(v, dict) and set(v) != {"min", "max", "n"}
                         else f"{k} = {_value(v)}" for k, v in value.items())
    return str(value)


def parameters_text(configs: dict[str, dict], skip=("code",)) -> str:
    """The parameters the datasets were made with (each one's recorded job configuration,
    ``provenance_config``), one ``key: values`` group per top-level key; a key whose value
    differs between datasets is given once per dataset, ``key (dataset)``."""
    groups = {}
    for name, config in configs.items():
        for key, value in config.items():
            if key not in skip:
                groups.setdefault(key, {})[name] = value
    parts = []
    for key, values in groups.items():
        distinct = {repr(v) for v in values.values()}
        if len(distinct) == 1:
            parts.append(f"{key}: {_value(next(iter(values.values())))}")
        else:
            parts += [f"{key} ({name}): {_value(v)}" for name, v in values.items()]
    return "; ".join(parts)


def state_parameters(fig, text: str, width: int = 150) -> None:
    """Write ``text`` under the figure in small grey type, wrapped to ``width`` characters."""
    fig.text(0.0, 0.0, "Parameters: " + "\n".join(textwrap.wrap(text, width)),
             fontsize=6, color="0.35", ha="left", va="top", transform=fig.transFigure)


def save(fig, path: str | Path) -> Path:
    """Save as PNG without timestamps (byte-stable for equal content) and close."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with plt.rc_context(STYLE):
        fig.savefig(path, metadata={"Software": None})
    plt.close(fig)
    return path


def sensitivity(ds, printed: dict[str, float], title: str):
    """One row per quantity of a sensitivity study (rotorvib.methods.sensitivity): first-order
    and total Sobol indices with their 95 % intervals at the largest sample, the total indices
    against the sample size (convergence), and the quantity's distribution over the input
    ranges with its 5-95 % band, its nominal value and the paper's (``printed``, by quantity)."""
    names = [str(n) for n in ds.input_name.values]
    quantities = [str(q) for q in ds.quantity_name.values]
    fig, axes = figure(len(quantities), 3, figsize=(15.0, 2.9 * len(quantities)), squeeze=False)
    position = range(len(names))
    for q, quantity in enumerate(quantities):
        units = str(ds.quantity_units.values[q])
        ax = axes[q, 0]
        for shift, key, color in ((-0.2, "S1", "C0"), (0.2, "ST", "C1")):
            ax.bar([i + shift for i in position], ds[key].values[q, -1], width=0.4, color=color,
                   yerr=ds[f"{key}_conf"].values[q, -1], capsize=2,
                   label={"S1": "first-order", "ST": "total"}[key])
        ax.set_xticks(list(position), names, rotation=30, fontsize=8)
        constant = bool(np.all(np.isnan(ds.ST.values[q, -1])))
        ax.set(ylabel=f"Sobol index of {quantity}", ylim=(-0.1, 1.1),
               title=f"{int(ds.n_base[-1])} base points ({ds.sizes['sample']} input points)"
               + (": constant, indices undefined" if constant else ""))
        ax.legend(fontsize=7)
        ax = axes[q, 1]
        for i, name in enumerate(names):
            ax.errorbar(ds.n_base.values, ds.ST.values[q, :, i], ds.ST_conf.values[q, :, i],
                        marker="o", ms=3, capsize=2, lw=1, label=name)
        ax.set_xscale("log", base=2)
        ax.set(xlabel="base points of the sample", ylabel="total Sobol index",
               title="convergence")
        ax.legend(fontsize=6, ncol=2)
        ax = axes[q, 2]
        ax.hist(ds.y.values[q], bins=40, color="0.7")
        lo, hi = ds.band.values[q, 0], ds.band.values[q, -1]
        ax.axvspan(lo, hi, color="C0", alpha=0.15, label=f"{ds.percentile.values[0]:g}-"
                   f"{ds.percentile.values[-1]:g} % band")
        ax.axvline(float(ds.nominal[q]), color="k", lw=1.2, label="reproduction (nominal)")
        if quantity in printed:
            paper_vline(ax, printed[quantity], f"{printed[quantity]:g} {units}")
        ax.set(xlabel=f"{quantity} ({units})", ylabel="input points")
        ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 4))
        ax.legend(fontsize=7)
    fig.suptitle(title)
    return fig
