"""Every figure states the parameters its datasets were made with (rotorvib.io.plotting)."""

import json

import matplotlib.pyplot as plt

from rotorvib.io.plotting import parameters_text, save, state_parameters


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


def test_the_statement_is_drawn_under_the_figure(tmp_path):
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    state_parameters(fig, parameters_text({"d": json.loads('{"case": {"mu": 0.01}}')}))
    texts = [t.get_text() for t in fig.texts]
    assert texts == ["Parameters: case: mu = 0.01"]
    assert save(fig, tmp_path / "f.png").stat().st_size > 0
