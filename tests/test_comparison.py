import pytest

from rotorvib.comparison import Reproduced, build_table, verdict


@pytest.mark.parametrize("paper, reproduced, rel, word", [
    (100.0, 100.9, 0.009, "MATCH"),
    (100.0, 101.1, 0.011, "MINOR"),
    (100.0, 90.0, 0.10, "MINOR"),
    (-100.0, -115.0, 0.15, "MAJOR"),
    (0.03, 0.2258, 6.5267, "MAJOR"),
])
def test_verdict_thresholds(paper, reproduced, rel, word):
    got_rel, got_word = verdict(paper, reproduced)
    assert got_rel == pytest.approx(rel, rel=1e-3)
    assert got_word == word


def test_qualitative_and_nonfinite():
    assert verdict(None, None) == (None, "QUALITATIVE")
    with pytest.raises(ValueError):
        verdict(1.0, float("nan"))


def _values():
    return [{"paper": "C", "item": "T2", "quantity": "q", "unit": "kg", "value": 1.0},
            {"paper": "C", "item": "F5", "quantity": "claim", "unit": "", "value": None}]


def test_table_joins_and_requires_explanations():
    rows = build_table(_values(), [Reproduced("C", "q", 1.005, ""),
                                   Reproduced("C", "claim", None, "supported: because")])
    assert [r["verdict"] for r in rows] == ["MATCH", "QUALITATIVE"]
    with pytest.raises(ValueError, match="no explanation"):
        build_table(_values(), [Reproduced("C", "q", 2.0, ""), Reproduced("C", "claim", None, "x")])
    with pytest.raises(ValueError, match="no reproduced value"):
        build_table(_values(), [Reproduced("C", "q", 1.0, "")])
    with pytest.raises(ValueError, match="missing from the paper-values file"):
        build_table(_values(), [Reproduced("C", "q", 1.0, ""), Reproduced("C", "claim", None, "x"),
                                Reproduced("C", "other", 1.0, "x")])
