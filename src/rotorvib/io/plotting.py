"""Shared figure style and output: readable defaults, the paper's values drawn, deterministic PNGs."""

from __future__ import annotations

import textwrap
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.font_manager import FontProperties  # noqa: E402
from matplotlib.image import imsave  # noqa: E402
from matplotlib.legend import Legend  # noqa: E402
from matplotlib.text import Text  # noqa: E402

STYLE = {
    "figure.figsize": (7.0, 4.3),
    "figure.dpi": 110,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.titlesize": 11,
    "axes.labelsize": 10,
    "legend.fontsize": 8.5,
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


def state_parameters(fig, text: str, fontsize: float = 6.0, pad: float = 0.05) -> None:
    """Write ``text`` under the figure's contents in small grey type: the figure grows by a band
    ``pad`` inches above and below the text, and its layout (constrained, as :func:`figure`
    makes it) keeps to the area above. The text is wrapped at word boundaries to the figure's
    width: at the mean width of its characters as drawn, then narrower until every line fits."""
    renderer = fig.canvas.get_renderer()
    props = FontProperties(size=fontsize)
    text = "Parameters: " + text

    def width(line):
        return renderer.get_text_width_height_descent(line, props, ismath=False)[0]

    room = (fig.get_figwidth() - 2 * pad) * fig.dpi
    chars = int(len(text) * room / width(text)) + 1
    lines = [text]
    while max(map(width, lines)) > room:
        chars -= 1 + chars // 20
        lines = textwrap.wrap(text, chars)
    label = fig.text(pad / fig.get_figwidth(), 0.0, "\n".join(lines), fontproperties=props,
                     color="0.35", ha="left", va="top")
    band = label.get_window_extent(renderer).height / fig.dpi + 2 * pad
    height = fig.get_figheight() + band
    fig.set_figheight(height)
    label.set_y((band - pad) / height)
    fig.get_layout_engine().set(rect=(0.0, band / height, 1.0, 1.0 - band / height))


def _texts_on_canvas(fig) -> bool:
    """Whether the figure's texts and legends, and its axes' titles, labels, annotations and
    legends, lie within its canvas once drawn (the tick labels are the layout's own)."""
    shown = [*fig.texts, *fig.legends]
    for ax in fig.axes:
        shown += [a for a in ax.get_children() if isinstance(a, (Text, Legend))]
        shown += [ax.xaxis.label, ax.yaxis.label]
    canvas = fig.bbox.padded(0.5)
    for artist in shown:
        if not artist.get_visible() or (isinstance(artist, Text) and not artist.get_text()):
            continue
        box = artist.get_window_extent()
        if not (canvas.contains(box.x0, box.y0) and canvas.contains(box.x1, box.y1)):
            return False
    return True


def save(fig, path: str | Path) -> Path:
    """Save as PNG without timestamps (byte-stable for equal content) and close. The figure is
    laid out and drawn once and its canvas written (``savefig`` would lay it out in a pass of
    its own first); a figure with a text beyond its canvas (a title wider than the figure) is
    saved by ``savefig`` cropped to all it draws (``bbox_inches="tight"``) instead."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with plt.rc_context(STYLE):
        fig.canvas.draw()
        if _texts_on_canvas(fig):
            imsave(path, np.asarray(fig.canvas.buffer_rgba()), format="png", dpi=fig.dpi,
                   metadata={"Software": None})
        else:
            fig.savefig(path, bbox_inches="tight", metadata={"Software": None})
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
