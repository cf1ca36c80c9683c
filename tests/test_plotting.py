"""Figures (rotorvib.io.plotting): the parameters a figure depends on, what it draws read off
its artists, and its PNG and SVG files, byte-stable."""

import re

import numpy as np
import xarray as xr
from matplotlib.layout_engine import ConstrainedLayoutEngine
from PIL import Image

from rotorvib.io.plotting import (
    STYLE,
    drawn_key,
    figure,
    paper_vline,
    parameters_text,
    save,
    sensitivity,
)


def test_parameters_are_grouped_and_differences_named_by_dataset():
    text = parameters_text({
        "beta": {"code": "abc", "setup": {"machine": {"M": 1.0, "k": 10000.0}},
                 "study": {"range": {"min": 0.1, "max": 1.0, "n": 46}, "fixed": {"mass": 0.01}}},
        "mass": {"code": "def", "setup": {"machine": {"M": 1.0, "k": 10000.0}},
                 "study": {"range": {"min": 0.006, "max": 0.02, "n": 15}}}})
    assert "code" not in text
    assert text.startswith("setup: machine (M = 1, k = 10000); ")  # shared: stated once
    assert "study (beta): range = 0.1..1 (46 points), fixed (mass = 0.01)" in text
    assert "study (mass): range = 0.006..0.02 (15 points)" in text


def test_a_figure_states_its_own_cases_and_none_of_the_other_outputs():
    """A dataset made for several figures records each one's case: Fig 7 states its own, and
    the Table 2 cases only where it names Table 2."""
    config = {"responses": {"fig6": {"beta": 0.0}, "fig7": {"beta": 1.0}},
              "table2": {"speed": 220.0}, "machine": {"k": 1e4}}
    assert parameters_text({"tr": config}, keep={"fig7"}) == \
        "responses: fig7 (beta = 1); machine: k = 10000"
    assert parameters_text({"tr": config}, keep={"fig16", "table2"}) == \
        "table2: speed = 220; machine: k = 10000"


def test_the_key_says_what_is_drawn_and_nothing_that_is_not():
    fig, ax = figure()
    ax.plot([0, 1], [0, 1], "-", label="IC1, printed")
    ax.plot([0, 1], [1, 0], "--", label="IC1, consistent")
    ax.legend(loc="center")              # over the lines
    assert drawn_key(fig) == ["Solid lines: the paper's printed kinematics (the reproduction); "
                              "dashed: the consistent kinematics."]
    paper_vline(ax, 0.5, "9.04 s")
    ax.legend(loc="center")              # over the lines
    assert drawn_key(fig)[0] == "The paper's values drawn (legend \"paper\"): 9.04 s."
    bare, ax = figure()
    ax.plot([0, 1], [0, 1], "--", label="IC1, printed")   # not the styles the key would claim
    ax.plot([0, 1], [1, 0], "--", label="IC1, consistent")
    ax.legend(loc="center")              # over the lines
    assert drawn_key(bare) == []


def _drawn(title="t"):
    fig, ax = figure()
    ax.plot([0, 1], [0, 1])
    ax.set(title=title, xlabel="x (m)")
    return fig, ax


def test_a_figure_is_written_as_png_and_svg_byte_stable(tmp_path):
    path = save(_drawn()[0], tmp_path / "f.png")
    with Image.open(path) as png:
        assert png.size == (round(STYLE["figure.figsize"][0] * STYLE["figure.dpi"]),
                            round(STYLE["figure.figsize"][1] * STYLE["figure.dpi"]))
    assert STYLE["figure.dpi"] >= 150
    svg = path.with_suffix(".svg").read_text()
    assert svg.startswith("<?xml") and "<dc:date>" not in svg
    again = save(_drawn()[0], tmp_path / "g.png")
    assert again.read_bytes() == path.read_bytes()
    assert again.with_suffix(".svg").read_bytes() == path.with_suffix(".svg").read_bytes()


def test_a_figure_is_laid_out_once_and_its_svg_keeps_the_png_layout(tmp_path, monkeypatch):
    """One constrained-layout pass per figure, as its PNG canvas is drawn; the SVG's axes stand
    where the PNG's do (savefig alone lays the figure out again, at the SVG's 72 dpi)."""
    passes = []
    execute = ConstrainedLayoutEngine.execute
    monkeypatch.setattr(ConstrainedLayoutEngine, "execute",
                        lambda engine, fig: passes.append(fig) or execute(engine, fig))
    fig, ax = _drawn()
    position = ax.get_position()
    width, height = fig.get_figwidth() * 72, fig.get_figheight() * 72
    path = save(fig, tmp_path / "f.png")
    assert len(passes) == 1 and position.bounds != ax.get_position().bounds
    laid_out = ax.get_position()
    corners = re.search(r'<g id="patch_2">\s*<path d="M ([\d.]+) ([\d.]+)\s+L ([\d.]+) ',
                        path.with_suffix(".svg").read_text())
    x0, y0, x1 = (float(v) for v in corners.groups())
    assert np.allclose([x0 / width, x1 / width, 1 - y0 / height],
                       [laid_out.x0, laid_out.x1, laid_out.y0], atol=1e-8)


def test_a_title_wider_than_the_figure_is_kept_whole(tmp_path):
    """A text beyond the canvas is not cut off: the figure is saved cropped to all it draws."""
    fig, _ = _drawn(title="a title far wider than the figure it stands over " * 3)
    width = fig.bbox.width
    with Image.open(save(fig, tmp_path / "f.png")) as png:
        assert png.size[0] > width


def _study(balanced, times, conf):
    """A sensitivity dataset of two quantities (a time, whether it balances) over 2 inputs."""
    n = len(times)
    return xr.Dataset(
        {"y": (("quantity", "sample"), np.array([times, balanced], float)),
         "ST": (("quantity", "n", "input"), np.full((2, 1, 2), 0.4)),
         "ST_conf": (("quantity", "n", "input"), np.array([[conf], [conf]], float)),
         "band": (("quantity", "percentile"), np.array([[1.0, 9.0], [0.0, 1.0]])),
         "nominal": ("quantity", [3.0, 1.0]),
         "n_valued": ("quantity", [int(np.isfinite(times).sum()), n])},
        coords={"input_name": ("input", ["a", "b"]),
                "quantity_name": ("quantity", ["balance_time", "balanced"]),
                "quantity_units": ("quantity", ["s", "1"]), "n_base": ("n", [8]),
                "percentile": ("percentile", [5.0, 95.0]), "sample": np.arange(n)},
        attrs={"sobol_resolved_half_width": 0.1})


def test_the_uncertainty_figure_counts_runs_without_a_time_apart_and_draws_resolved_indices():
    """A run without a time (NaN) is not drawn: the distribution holds the runs with one, the
    others are counted in its title; an index whose interval is wider than +/- 0.1 is named as
    unresolved instead of drawn."""
    ds = _study([1, 1, 1, 0], [2.0, 3.0, 4.0, np.nan], [0.05, 0.15])
    fig = sensitivity(ds, {"balance_time": 5.0}, "title")
    indices, times = fig.axes[0], fig.axes[1]
    assert len(indices.patches) == 1                       # input a only
    assert [t.get_text() for t in indices.texts] == ["unresolved (interval wider than +/- 0.1)"]
    assert sum(bar.get_height() for bars in times.containers for bar in bars) == 3
    assert times.get_title() == "no time by t_end: 1 of 4"
    assert fig.axes[3].get_title() == "3 of 4 input points balance"


def test_a_saved_figure_shows_symbols_plain_log_labels_and_its_legend_off_the_data(tmp_path):
    """save() writes the words' symbols as mathtext (the caption keeps the words), labels a
    short log axis's minor ticks as plain numbers, and moves below the axes a legend that
    covers a drawn line, so that no point of any line lies under it."""
    from rotorvib.io.plotting import figure, save, symbols

    assert symbols("frequency ratio w = omega/omega_n") == (
        r"frequency ratio w = $\omega$/$\omega_n$")
    assert symbols("eps/R = 0.007, beta = 0.2") == r"$\varepsilon$/R = 0.007, $\beta$ = 0.2"
    assert symbols("multiple-scales, betas, $x$ beta") == "multiple-scales, betas, $x$ beta"
    fig, ax = figure()
    x = np.linspace(0, 1, 200)
    for k in range(6):                       # lines everywhere: the legend covers some
        ax.semilogy(x, 20 + 50 * x ** (k + 1), label=f"beta = {k}")
    ax.set_xlabel("omega/omega_n")
    ax.legend(loc="center")              # over the lines
    save(fig, tmp_path / "f.png")
    assert ax.xaxis.label.get_text() == r"$\omega$/$\omega_n$"
    assert [t.get_text() for t in ax.get_legend().get_texts()][0] == r"$\beta$ = 0"
    minor = [t.get_text() for t in ax.yaxis.get_ticklabels(minor=True) if t.get_text()]
    assert minor and all(re.fullmatch(r"\d+", t) for t in minor), minor
    box = ax.get_legend().get_window_extent()
    assert not any(box.contains(px, py) for line in ax.get_lines()
                   for px, py in line.get_transform().transform(line.get_xydata()))
