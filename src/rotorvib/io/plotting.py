"""Shared figure style and output: readable defaults, the paper's values drawn, deterministic PNGs."""

from __future__ import annotations

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


def save(fig, path: str | Path) -> Path:
    """Save as PNG without timestamps (byte-stable for equal content) and close."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with plt.rc_context(STYLE):
        fig.savefig(path, metadata={"Software": None})
    plt.close(fig)
    return path
