"""Shared figure style and output: readable defaults, the paper's values drawn, what a figure
draws and the parameters it depends on (for its caption), and deterministic PNG and SVG files."""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.image import imsave  # noqa: E402
from matplotlib.legend import Legend  # noqa: E402
from matplotlib.text import Text  # noqa: E402
from matplotlib.ticker import LogFormatter, LogFormatterSciNotation, MaxNLocator  # noqa: E402

STYLE = {
    "figure.figsize": (7.0, 4.3),
    "figure.dpi": 150,
    "svg.hashsalt": "rotorvib",     # the SVG's element ids, and so its bytes, are stable
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.titlesize": 11,
    "axes.labelsize": 10,
    "legend.fontsize": 8.5,
    "figure.constrained_layout.use": True,
}
PAPER_STYLE = {"color": "crimson", "linestyle": "--", "linewidth": 1.2}
#: The symbols the figures' texts name in words, and how a saved figure shows them (mathtext).
#: A figure is drawn with the words, which its caption quotes (:func:`drawn_key`); :func:`save`
#: sets the symbols.
SYMBOLS = {"omega_bar": r"\bar\omega", "omega_n": r"\omega_n", "omega_c": r"\omega_c",
           "Omega": r"\Omega",
           "omega": r"\omega", "eps_bar": r"\bar\varepsilon", "m_bar": r"\bar m",
           "Gamma0": r"\Gamma_0", "Theta": r"\Theta", "theta": r"\theta", "beta": r"\beta",
           "sigma": r"\sigma", "zeta": r"\zeta", "mu": r"\mu", "rho": r"\rho",
           "lambda": r"\lambda", "eps": r"\varepsilon", "phi": r"\phi", "k_t": "k_t",
           "inf": r"\infty", "tau": r"\tau", "w_n": r"\omega_n"}
_SYMBOL = re.compile(r"(?<![\w$\\])(" + "|".join(sorted(SYMBOLS, key=len, reverse=True))
                     + r")(?!\w)")


def figure(nrows: int = 1, ncols: int = 1, **kwargs):
    """``plt.subplots(nrows, ncols, **kwargs)`` in the project's style (:data:`STYLE`)."""
    with plt.rc_context(STYLE):
        return plt.subplots(nrows, ncols, **kwargs)


def generation_axis(ax) -> None:
    """Label the x axis of a genetic algorithm's convergence plot: whole generations only."""
    ax.set_xlabel("generation")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))


def paper_hline(ax, value: float, label: str) -> None:
    """Draw the paper's stated value as a dashed horizontal line."""
    ax.axhline(value, **PAPER_STYLE, label=f"paper: {label}")


def paper_vline(ax, value: float, label: str) -> None:
    """A vertical line at the paper's ``value``, labelled ``paper: label`` in the legend."""
    ax.axvline(value, **PAPER_STYLE, label=f"paper: {label}")


def paper_point(ax, x: float, y: float, label: str) -> None:
    """A star at the paper's point ``(x, y)``, labelled ``paper: label`` in the legend."""
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


_OUTPUT_NAME = re.compile(r"(?:fig|table)\d+(?:_\d+)*")


def _only(value, keep: set[str]):
    """``value`` without the entries of mappings keyed by a paper output's name ("fig6",
    "table2") that is not in ``keep``: a dataset made for several figures records each one's
    case, and a figure depends on its own."""
    if not isinstance(value, dict):
        return value
    return {k: _only(v, keep) for k, v in value.items()
            if not _OUTPUT_NAME.fullmatch(str(k)) or k in keep}


def parameters_text(configs: dict[str, dict], keep: set[str] = frozenset(),
                    skip=("code",)) -> str:
    """The parameters a figure depends on: the configuration each of its datasets was made
    with (``provenance_config``), one ``key: values`` group per top-level key, without the
    cases of other outputs (those not in ``keep``, :func:`_only`); a key whose value differs
    between datasets is given once per dataset, ``key (dataset)``."""
    groups = {}
    for name, config in configs.items():
        for key, value in _only(config, set(keep)).items():
            if key not in skip and value != {}:
                groups.setdefault(key, {})[name] = value
    parts = []
    for key, values in groups.items():
        distinct = {repr(v) for v in values.values()}
        if len(distinct) == 1:
            parts.append(f"{key}: {_value(next(iter(values.values())))}")
        else:
            parts += [f"{key} ({name}): {_value(v)}" for name, v in values.items()]
    return "; ".join(parts)


def _legend_entries(fig) -> list[tuple[str, str]]:
    """(label, line style) of every entry of the figure's legends, in order."""
    legends = [ax.get_legend() for ax in fig.axes] + list(fig.legends)
    entries = []
    for legend in filter(None, legends):
        for handle, text in zip(legend.legend_handles, legend.get_texts()):
            style = handle.get_linestyle() if hasattr(handle, "get_linestyle") else ""
            entries.append((text.get_text(), style if isinstance(style, str) else ""))
    return entries


def drawn_key(fig) -> list[str]:
    """Sentences that say what the figure draws beyond its legend's words, read off the drawn
    artists: the paper's values (artists labelled "paper: ...", as :func:`paper_hline`,
    :func:`paper_vline` and :func:`paper_point` draw them), and the line style of each kinematics where every legend entry of the printed one
    is solid and every entry of the consistent one dashed."""
    said = []
    paper = [artist.get_label().removeprefix("paper: ") for ax in fig.axes
             for artist in ax.get_children()
             if str(artist.get_label()).startswith("paper: ")]
    if paper:
        said.append("The paper's values drawn (legend \"paper\"): "
                    + "; ".join(dict.fromkeys(paper)) + ".")
    styles = {kinematics: {style for label, style in _legend_entries(fig)
                           if label.endswith(f", {kinematics}")}
              for kinematics in ("printed", "consistent")}
    if styles == {"printed": {"-"}, "consistent": {"--"}}:
        said.append("Solid lines: the paper's printed kinematics (the reproduction); dashed: "
                    "the consistent kinematics.")
    return said


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


def _fix_layout(fig) -> None:
    """Keep the figure's layout as last drawn: no layout engine, so that ``savefig`` neither
    draws the figure once more to lay it out nor lays it out again (it does both for a figure
    with a layout engine)."""
    with plt.rc_context({"figure.autolayout": False, "figure.constrained_layout.use": False}):
        fig.set_layout_engine(None)


def symbols(text: str) -> str:
    """``text`` with each symbol's name as the symbol (:data:`SYMBOLS`): "omega/omega_n" ->
    "$\\omega$/$\\omega_n$"; a text that holds mathtext already is left as it is."""
    if "$" in text:
        return text
    return _SYMBOL.sub(lambda m: f"${SYMBOLS[m.group(1)]}$", text)


def _texts(fig) -> list[Text]:
    """Every text of a figure: titles, axis labels, legends, annotations (tick labels too,
    which their formatters write again as the figure is drawn)."""
    return fig.findobj(match=Text)


def _plain_log_ticks(fig) -> None:
    """A log axis's minor labels as plain numbers ("40"), not "4x10^1"; its decades keep
    their powers of ten. Insets included."""
    for ax in fig.axes + [inset for ax in fig.axes for inset in ax.child_axes]:
        for axis in (ax.xaxis, ax.yaxis):
            if (axis.get_scale() == "log"
                    and isinstance(axis.get_minor_formatter(), LogFormatterSciNotation)):
                axis.set_minor_formatter(LogFormatter(labelOnlyBase=False))


def _covers(box, line) -> bool:
    """Whether window box ``box`` holds a point of ``line`` (in display coordinates)."""
    x, y = line.get_transform().transform(line.get_xydata()).T
    return bool(np.any((x >= box.x0) & (x <= box.x1) & (y >= box.y0) & (y <= box.y1)))


def _legends_off_the_data(fig) -> bool:
    """Move below its axes each legend that covers a point of a drawn line, in as many columns
    (at most three) as its axes' width holds, the figure made taller by the legend's height
    so that the axes keep theirs; whether one moved (the figure must be drawn again)."""
    moved = False
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None or legend.get_bbox_to_anchor() is not ax.bbox:
            continue                                # placed on purpose: left where it is
        box = legend.get_window_extent()
        if not any(_covers(box, line) for line in ax.get_lines() if line.get_visible()):
            continue
        handles, labels = ax.get_legend_handles_labels()
        ncol = max(1, min(3, len(labels), int(ax.bbox.width // box.width)))
        rows = -(-len(labels) // ncol)
        width, height = fig.get_size_inches()
        fig.set_size_inches(width, height + box.height * rows / len(labels) / fig.dpi + 0.3)
        ax.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=ncol)
        moved = True
    return moved


def save(fig, path: str | Path) -> Path:
    """Save as PNG and, beside it, as SVG (a vector copy for papers), both without timestamps
    (byte-stable for equal content), and close. The figure is laid out once, as the PNG's
    canvas is drawn; the PNG is that canvas and the SVG keeps its layout (``savefig`` would
    lay the figure out in a pass of its own first, each time). A figure with a text beyond its
    canvas (a title wider than the figure) is saved cropped to all it draws
    (``bbox_inches="tight"``) instead, in both formats. What a reader reads shows the symbols
    (:func:`symbols`), a log axis's minor labels plain numbers, and a legend that covers a drawn
    line moves below its axes."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with plt.rc_context(STYLE):
        for text in _texts(fig):
            text.set_text(symbols(text.get_text()))
        _plain_log_ticks(fig)
        fig.canvas.draw()
        if _legends_off_the_data(fig):
            for text in _texts(fig):
                text.set_text(symbols(text.get_text()))
            fig.canvas.draw()
        crop = {} if _texts_on_canvas(fig) else {"bbox_inches": "tight"}
        if crop:
            fig.savefig(path, metadata={"Software": None}, **crop)
        else:
            imsave(path, np.asarray(fig.canvas.buffer_rgba()), format="png", dpi=fig.dpi,
                   metadata={"Software": None})
        _fix_layout(fig)
        fig.savefig(path.with_suffix(".svg"), format="svg", metadata={"Date": None}, **crop)
    plt.close(fig)
    return path




def sensitivity(ds, printed: dict[str, float], title: str):
    """One row per quantity of a sensitivity study (rotorvib.methods.sensitivity), two panels:

    - left, the total Sobol index of each input with its 95 % interval at the largest sample,
      where that interval's half-width is at most the study's ``sobol_resolved_half_width``;
      an input whose interval is wider is named as unresolved (estimates clipped to [0, 1]);
      the title shows the convergence: the widest half-width at each sample size;
    - right, the quantity's distribution over the input points, its 5-95 % band (that of the
      comparison rows), its nominal value and the paper's (``printed``, by quantity). Where the
      study records whether a run balances (quantity ``balanced``), a time (unit s) is drawn
      for the balanced runs only, the others counted apart (they have no time), and the
      ``balanced`` row is the share of runs that balance."""
    names = [str(n) for n in ds.input_name.values]
    quantities = [str(q) for q in ds.quantity_name.values]
    balanced = (ds.y.values[quantities.index("balanced")] == 1) if "balanced" in quantities \
        else np.ones(ds.sizes["sample"], bool)
    fig, axes = figure(len(quantities), 2, figsize=(11.0, 2.6 * len(quantities) + 0.6),
                       squeeze=False, width_ratios=(1, 1.3))
    position = np.arange(len(names))
    for q, quantity in enumerate(quantities):
        units = str(ds.quantity_units.values[q])
        ax = axes[q, 0]
        st, conf = ds.ST.values[q, -1], ds.ST_conf.values[q, -1]
        valued = int(ds.n_valued[q]) == ds.sizes["sample"] if "n_valued" in ds else True
        limit = float(ds.attrs["sobol_resolved_half_width"])
        why = (f"unresolved (interval wider than +/- {limit:g})" if not np.all(np.isnan(st))
               else "constant output" if valued else "no index: some runs have no value")
        decided = ~np.isnan(conf) & (conf <= limit)
        ax.barh(position[decided], np.clip(st[decided], 0, 1), xerr=conf[decided], color="C1",
                capsize=2, label="total index, 95 % interval")
        for i in np.flatnonzero(~decided):
            ax.text(0.01, i, why, va="center", fontsize=7, color="0.45")
        ax.set_yticks(position, names, fontsize=8)
        ax.invert_yaxis()
        widest = [np.nanmax(c) if np.isfinite(c).any() else np.nan for c in ds.ST_conf.values[q]]
        converging = ", ".join(f"{int(n)}: {w:.2f}" for n, w in zip(ds.n_base.values, widest)
                               if np.isfinite(w))
        ax.set(xlim=(0, 1.05), xlabel=f"total Sobol index of {quantity}",
               title=f"{int(ds.n_base[-1])} base points ({ds.sizes['sample']} input points)"
               + (f"\nwidest +/- by base points, {converging}" if converging else ""))
        if decided.any():
            ax.legend(fontsize=7, loc="lower right")
        ax = axes[q, 1]
        y = ds.y.values[q]
        lo, hi = ds.band.values[q, 0], ds.band.values[q, -1]
        if quantity == "balanced":
            share = balanced.mean()
            ax.barh([0, 1], [share, 1 - share], color=["C0", "0.6"])
            ax.set_yticks([0, 1], ["balances by t_end", "does not"], fontsize=8)
            ax.set(xlim=(0, 1), xlabel="share of input points",
                   title=f"{balanced.sum()} of {balanced.size} input points balance")
            continue
        timed = units == "s" and not np.isfinite(y).all()
        shown = y[np.isfinite(y)]
        ax.hist(shown, bins=30, color="0.6",
                label=f"balanced runs ({shown.size})" if timed else "input points")
        ax.axvspan(lo, hi, color="C0", alpha=0.12, label=f"{ds.percentile.values[0]:g}-"
                   f"{ds.percentile.values[-1]:g} % band of the "
                   + ("balanced runs" if timed else "input points"))
        ax.axvline(float(ds.nominal[q]), color="k", lw=1.2, label="reproduction (nominal)")
        if quantity in printed:
            paper_vline(ax, printed[quantity], f"{printed[quantity]:g} {units}")
        ax.set(xlabel=f"{quantity} ({units})", ylabel="input points",
               title=f"no time by t_end: {(~np.isfinite(y)).sum()} of {y.size}"
               if timed else "distribution over the input ranges")
        ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 4))
        ax.legend(fontsize=7)
    fig.suptitle(title)
    return fig
