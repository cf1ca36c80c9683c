"""Every figure states the parameters its datasets were made with (rotorvib.io.plotting)."""

from PIL import Image

from rotorvib.io.plotting import STYLE, figure, parameters_text, save, state_parameters


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


def _drawn(title="t", text="case: mu = 0.01"):
    fig, ax = figure()
    ax.plot([0, 1], [0, 1])
    ax.set(title=title, xlabel="x (m)")
    state_parameters(fig, text)
    return fig, ax


def test_the_statement_is_drawn_under_the_axes_on_the_canvas(tmp_path):
    """The figure grows by the statement's band, the axes (their labels included) keep above
    it, and the canvas is written as it was drawn, byte-stable."""
    fig, ax = _drawn()
    assert [t.get_text() for t in fig.texts] == ["Parameters: case: mu = 0.01"]
    height = fig.get_figheight()
    assert height > STYLE["figure.figsize"][1]
    path = save(fig, tmp_path / "f.png")
    label = fig.texts[0].get_window_extent()
    assert 0 <= label.y0 and label.y1 <= ax.get_tightbbox().y0 and label.x1 <= fig.bbox.x1
    with Image.open(path) as png:
        assert png.size == (round(STYLE["figure.figsize"][0] * STYLE["figure.dpi"]),
                            round(height * STYLE["figure.dpi"]))
    assert save(_drawn()[0], tmp_path / "g.png").read_bytes() == path.read_bytes()


def test_a_long_statement_is_wrapped_to_the_width_of_the_figure():
    fig, _ = _drawn(text="; ".join(f"parameter_{i}: {i / 7:.6f}" for i in range(60)))
    lines = fig.texts[0].get_text().split("\n")
    renderer = fig.canvas.get_renderer()
    widths = [renderer.get_text_width_height_descent(line, fig.texts[0].get_fontproperties(),
                                                     ismath=False)[0] for line in lines]
    assert len(lines) > 3 and max(widths) <= fig.bbox.width
    assert min(widths[:-1]) > 0.8 * fig.bbox.width        # lines filled, not cut short


def test_a_title_wider_than_the_figure_is_kept_whole(tmp_path):
    """A text beyond the canvas is not cut off: the figure is saved cropped to all it draws."""
    fig, _ = _drawn(title="a title far wider than the figure it stands over " * 3)
    width = fig.bbox.width
    with Image.open(save(fig, tmp_path / "f.png")) as png:
        assert png.size[0] > width
