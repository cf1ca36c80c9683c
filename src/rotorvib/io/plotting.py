"""Shared figure style and output: readable defaults, the paper's values drawn, deterministic PNGs."""

from __future__ import annotations

import textwrap
from pathlib import Path

import matplotlib

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
