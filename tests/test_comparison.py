import numpy as np
import pytest

from rotorvib.comparison.choices import NO_CHOICE
from rotorvib.comparison.reproduced import Margin, Reproduced, merge_variants
from rotorvib.comparison.reproduced_csv import read_reproduced, write_reproduced
from rotorvib.comparison.table import build_table, margin_text, with_findings
from rotorvib.comparison.verdicts import claim_verdict, totals, verdict

HOLDS, FAILS = Margin(0.2, 0.01, "s", "test"), Margin(-0.2, 0.01, "s", "test")


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


def test_values_the_paper_does_not_print_are_expected_not_matched():
    assert verdict(2.0, 2.01, source="theory")[1] == "EXPECTED"
    assert verdict(120.0, 110.0, source="chosen")[1] == "UNEXPECTED"
    assert verdict(2.0, 2.01, source="printed")[1] == "MATCH"


def test_a_paper_contradicting_itself_is_paper_inconsistent():
    """Text says 32 %, the paper's own table implies 55.2 %, the reproduction gives 55.0 %."""
    assert verdict(32.0, 55.0, implied=55.2)[1] == "PAPER-INCONSISTENT"
    # the reproduction agrees with neither: an ordinary MAJOR
    assert verdict(32.0, 80.0, implied=55.2)[1] == "MAJOR"
    # the two printed numbers agree: the implied value changes nothing
    assert verdict(55.0, 55.1, implied=55.2)[1] == "MATCH"


def test_claim_verdicts_from_variants():
    assert claim_verdict((("printed", True), ("consistent", True))) == "SUPPORTED"
    assert claim_verdict((("printed", False), ("consistent", False))) == "NOT SUPPORTED"
    assert claim_verdict((("printed", True), ("consistent", False))) == "DEPENDS"
    # a variant that cannot decide counts neither way
    assert claim_verdict((("printed", True), ("consistent", None))) == "SUPPORTED"
    assert claim_verdict((("printed", None), ("consistent", False))) == "NOT SUPPORTED"
    assert claim_verdict((("", None),)) == "UNDETERMINED"
    with pytest.raises(ValueError):
        claim_verdict(())


MIRROR = {"SUPPORTED": "NOT SUPPORTED", "NOT SUPPORTED": "SUPPORTED", "DEPENDS": "DEPENDS",
          "UNDETERMINED": "UNDETERMINED"}


@pytest.mark.parametrize("holds", [(a, b, c) for a in (True, False, None)
                                   for b in (True, False, None) for c in (True, False, None)])
def test_the_claim_verdict_treats_holds_and_fails_alike(holds):
    """Exchanging holds and fails under every variant mirrors the verdict (SUPPORTED <-> NOT
    SUPPORTED; DEPENDS and UNDETERMINED stay): holds + undetermined and fails + undetermined
    are mirror images, not DEPENDS and UNDETERMINED."""
    named = tuple(zip("xyz", holds))
    mirrored = tuple((k, None if h is None else not h) for k, h in named)
    assert claim_verdict(mirrored) == MIRROR[claim_verdict(named)]


def test_a_claim_evaluated_under_two_variants_that_disagree_depends():
    rows = merge_variants({
        "printed": [Reproduced.claim("B", "claim", HOLDS, "0.1 s", choices=()),
                    Reproduced.of("B", "q", 1, "x")],
        "consistent": [Reproduced.claim("B", "claim", FAILS, "never balances", choices=()),
                       Reproduced.of("B", "q", 2, "x")]}, "paper_b.kinematics = printed")
    table = build_table([{"paper": "B", "item": "F", "quantity": "claim", "unit": "",
                          "value": None, "source": "printed"},
                         {"paper": "B", "item": "F", "quantity": "q", "unit": "s", "value": 1.0,
                          "source": "printed"}], rows)
    assert table[0]["verdict"] == "DEPENDS"
    assert table[0]["explanation"].startswith("holds under printed; not under consistent: ")
    assert "never balances" in table[0]["explanation"]
    assert table[1]["verdict"] == "MATCH" and "consistent: 2" in table[1]["explanation"]


def test_reproduced_rows_round_trip(tmp_path):
    rows = [Reproduced.claim("B", "c", {"printed": HOLDS, "consistent": None}, "why, and how", choices=()),
            Reproduced.of("B", "q", 55.0, "x", implied=55.2), Reproduced.claim("A", "d", FAILS, "", choices=()),
            Reproduced.claim("A", "e", Margin(float("inf"), 0.0, "", "no rival"), "x",
                             choices=("paper_a.case (chosen)", "a grid"))]
    write_reproduced(rows, tmp_path / "r.csv")
    assert read_reproduced(tmp_path / "r.csv") == rows


def _values():
    return [{"paper": "C", "item": "T2", "quantity": "q", "unit": "kg", "value": 1.0,
             "source": "printed"},
            {"paper": "C", "item": "F5", "quantity": "claim", "unit": "", "value": None,
             "source": "printed"}]


def test_table_joins_and_requires_explanations():
    rows = build_table(_values(), [Reproduced.of("C", "q", 1.005, ""),
                                   Reproduced.claim("C", "claim", HOLDS, "because", choices=())])
    assert [r["verdict"] for r in rows] == ["MATCH", "SUPPORTED"]
    with pytest.raises(ValueError, match="no explanation"):
        build_table(_values(), [Reproduced.of("C", "q", 2.0, ""),
                                Reproduced.claim("C", "claim", HOLDS, "x", choices=())])
    with pytest.raises(ValueError, match="no reproduced value"):
        build_table(_values(), [Reproduced.of("C", "q", 1.0, "")])
    with pytest.raises(ValueError, match="missing from the paper-values file"):
        build_table(_values(), [Reproduced.of("C", "q", 1.0, ""),
                                Reproduced.claim("C", "claim", HOLDS, "x", choices=()),
                                Reproduced.of("C", "other", 1.0, "x")])


def test_a_finding_is_one_cause_however_many_rows_show_it():
    """Rows of one paper and verdict whose explanations differ only in their numbers are one
    finding; another verdict, paper or wording is another; a row without explanation is its
    own."""
    def row(paper, quantity, verdict, explanation):
        return {"paper": paper, "quantity": quantity, "verdict": verdict,
                "explanation": explanation}

    rows = with_findings([
        row("B", "m1", "MATCH", "GA optimum mass at the lower bound (beta = 0.12, 5.41 s)"),
        row("B", "m2", "MATCH", "GA optimum mass at the lower bound (beta = 0.2, 6.1e-1 s)"),
        row("B", "m3", "MAJOR", "GA optimum mass at the lower bound (beta = 0.3, 5 s)"),
        row("B", "m4", "MATCH", "GA optimum mass inside the bounds (beta = 0.3, 5 s)"),
        row("C", "c1", "MATCH", "GA optimum mass at the lower bound (beta = 0.12, 5.41 s)"),
        row("C", "c2", "MATCH", ""), row("C", "c3", "MATCH", "")])
    assert [r["finding"] for r in rows] == ["B1", "B1", "B2", "B3", "C1", "C2", "C3"]
    table = [{**r, "paper_value": 1.0, "source": "printed"} for r in rows]
    assert totals(table)[0] == ("printed numbers (7 rows, 6 findings): MATCH 6 (5 findings), "
                                "MINOR 0, MAJOR 1 (1 finding), PAPER-INCONSISTENT 0")


@pytest.mark.parametrize("value, uncertainty, holds", [
    (0.5, 0.1, True), (-0.5, 0.1, False),
    (0.05, 0.1, None), (-0.05, 0.1, None), (0.1, 0.1, None),   # inside the noise: undecided
    (0.0, 0.0, True), (-1.0, 0.0, False),                       # exact: an inclusive bound
    (float("nan"), 0.0, None), (float("inf"), 1.0, True), (float("-inf"), 1.0, False),
])
def test_a_margin_decides_only_beyond_its_uncertainty(value, uncertainty, holds):
    assert Margin(value, uncertainty, "s", "test").holds() is holds


def test_a_claim_decided_inside_its_uncertainty_is_undetermined_and_shows_its_margin():
    """A GA pick that wins by 2 ms when its seeds spread by 30 ms decides nothing."""
    values = [{"paper": "B", "item": "GA", "quantity": "claim", "unit": "", "value": None,
               "source": "printed"}]
    inside = Margin(0.002, 0.03, "s", "half the range over 5 seeds")
    row, = build_table(values, [Reproduced.claim("B", "claim", inside, "wins by 2 ms", choices=())])
    assert row["verdict"] == "UNDETERMINED"
    assert (row["margin"], row["uncertainty"], row["margin_unit"]) == (0.002, 0.03, "s")
    assert margin_text(row) == "+0.002 +/- 0.03 (s; half the range over 5 seeds)"
    row, = build_table(values, [Reproduced.claim("B", "claim", Margin(0.04, 0.03, "s", "x"), "y", choices=())])
    assert row["verdict"] == "SUPPORTED"


def test_a_decided_claim_needs_a_margin_and_a_margin_a_nonnegative_uncertainty():
    values = [{"paper": "B", "item": "GA", "quantity": "claim", "unit": "", "value": None,
               "source": "printed"}]
    with pytest.raises(TypeError, match="needs a Margin or None, not bool"):
        Reproduced.claim("B", "claim", True, "x", choices=())
    with pytest.raises(ValueError, match="uncertainty must be >= 0"):
        Margin(1.0, -0.1, "s", "x")
    with pytest.raises(ValueError, match="uncertainty must be >= 0"):
        Margin(1.0, float("nan"), "s", "x")
    # undecidable for want of material: no margin, and UNDETERMINED
    row, = build_table(values, [Reproduced.claim("B", "claim", None, "ref. [8] not given", choices=())])
    assert row["verdict"] == "UNDETERMINED" and row["margin"] is None


def test_an_uncertainty_claim_no_case_could_test_is_undetermined_saying_why():
    """Found by the configuration fuzzer: with Table 2's speed moved, the Table 1 case runs
    where the paper prints no value and its claim row had no reproduction (the comparison
    stopped); it is now UNDETERMINED, and a tested claim is left alone."""
    from rotorvib.papers.b.uncertainty import untested_rows

    paper = {"table1_mean_time_220_within_uncertainty": None,
             "fig7_balance_time_within_uncertainty": None, "table1_mean_time_220": 3.98}
    rows = untested_rows(paper, {"fig7_balance_time_within_uncertainty"})
    assert [r.quantity for r in rows] == ["table1_mean_time_220_within_uncertainty"]
    assert claim_verdict(rows[0].holds) == "UNDETERMINED"
    assert "not tested under this configuration" in rows[0].explanation


def test_a_self_contradicting_paper_is_judged_against_its_own_implied_value():
    """Table 2's forces imply a 33 % decay-time reduction where the text prints 55 % (the text
    swaps its two percentages): the reproduction is judged against 33 %, not 55 %."""
    from rotorvib.comparison.verdicts import verdict

    assert verdict(55.0, 33.5, implied=32.94) == (pytest.approx(abs(33.5 - 32.94) / 32.94),
                                                  "PAPER-INCONSISTENT")
    rel, found = verdict(55.0, 43.0, implied=32.94)
    assert found == "MAJOR" and rel == pytest.approx((43.0 - 32.94) / 32.94)
    assert verdict(55.0, 43.0, implied=54.0)[1] == "MAJOR"       # consistent: judged as printed


def test_an_optimum_the_grid_cannot_resolve_is_undetermined():
    """eq. (41)'s 6 g against a grid optimum of 6.5 g whose neighbours lie within the curve's
    bumps: UNDETERMINED while the interval holds the paper's value, UNEXPECTED once it does
    not (a smoother curve, one choice moved)."""
    from rotorvib.comparison.verdicts import verdict
    from rotorvib.papers.b.curves import argmin_interval, roughness

    masses = 0.0055 + 0.00025 * np.arange(9)                 # 5.5-7.5 g in quarter grams
    smooth = 4.0 + 1e5 * (masses - 0.0065) ** 2
    near = argmin_interval(smooth, masses)                    # a step either side
    assert near == pytest.approx((0.00625, 0.00675))
    assert verdict(0.006, 0.0065, source="theory", interval=near)[1] == "UNEXPECTED"
    bumpy = smooth.copy()
    bumpy[1] += 0.1                                           # 5.75 g: a bump of 0.1 s
    assert roughness(bumpy) > 0.09
    near = argmin_interval(bumpy, masses)
    assert near[0] == pytest.approx(0.006) and near[1] > 0.0065
    assert verdict(0.006, 0.0065, source="theory", interval=near)[1] == "UNDETERMINED"


def test_a_calibrated_row_is_counted_apart_never_as_evidence(tmp_path):
    from rotorvib.comparison.reproduced import Margin, Reproduced
    from rotorvib.comparison.table import build_table
    from rotorvib.comparison.verdicts import CALIBRATED, totals

    values = [{"paper": "B", "item": "Table 2", "quantity": "q", "unit": "", "value": None,
               "source": "theory", "read_off_figure": "no", "claim": "c", "quote_where": "",
               "quote_fa": "", "quote_en": ""}]
    row = Reproduced.claim("B", "q", Margin(1.0, 0.1, "N", "band"), "within the band",
                           calibrated="R was fitted to it", choices=())
    (built,) = build_table(values, [row])
    assert built["verdict"] == CALIBRATED and built["explanation"].startswith("not evidence")
    assert totals([built])[-1] == ("calibrated, not evidence (1 row, 1 finding): "
                                   "CALIBRATED 1 (1 finding)")
    assert all(" 0" in line or "(0 rows" in line for line in totals([built])[:-1])


def test_moving_one_choice_flips_a_constructed_verdict():
    """A claim evaluated under each declared alternative of a choice (here the reading of
    "close"): while every alternative agrees it is decided; declare one across the margin and
    it DEPENDS on the choice, naming the value; the comparison's CSV carries the choice and
    what each alternative gave."""
    from rotorvib.comparison.choices import Close, under_choice
    from rotorvib.comparison.reproduced import Margin, Reproduced
    from rotorvib.comparison.table import build_table

    off = 0.01005                             # the antiresonance's distance from resonance

    def row(close):
        return Reproduced.claim("C", "q", close.margins(lambda c: Margin(c - off, 1e-9, "w", "s")),
                                "why", choices=(close.choice,))

    values = [{"paper": "C", "item": "Fig 5", "quantity": "q", "unit": "", "value": None,
               "source": "printed"}]
    (decided,) = build_table(values, [row(Close(0.1, (0.05, 0.2)))])
    assert decided["verdict"] == "SUPPORTED"
    assert decided["choices"] == ("comparison.close = 0.1 (chosen: the papers' 'close'; "
                                  "alternatives 0.05, 0.2 evaluated)")
    assert decided["alternatives"] == ("comparison.close = 0.1: holds; comparison.close = 0.05: "
                                       "holds; comparison.close = 0.2: holds")
    assert decided["margin"] == pytest.approx(0.1 - off)
    (flipped,) = build_table(values, [row(Close(0.1, (0.01, 0.2)))])
    assert flipped["verdict"] == "DEPENDS"
    assert flipped["alternatives"].split("; ")[1] == "comparison.close = 0.01: fails"
    assert flipped["explanation"].startswith("holds under comparison.close = 0.1, "
                                             "comparison.close = 0.2; not under "
                                             "comparison.close = 0.01: ")
    # one choice inside another variant (kinematics): the names join, the verdicts stay apart
    merged, = merge_variants({"printed": [row(Close(0.1, (0.01,)))],
                              "consistent": [Reproduced.claim("C", "q", Margin(1, 0, "", "x"),
                                                              "", choices=())]},
                             "kinematics = printed")
    assert merged.holds == (("printed & comparison.close = 0.1", True),
                            ("printed & comparison.close = 0.01", False), ("consistent", True))
    assert merged.choices[0] == "kinematics = printed"
    assert under_choice(lambda v: None, "k", "a", ("b",)) == {"k = a": None, "k = b": None}


def test_a_claim_states_its_choices_and_a_choice_cannot_break_the_csv():
    with pytest.raises(TypeError):
        Reproduced.claim("C", "q", Margin(1.0, 0.0, "", "x"), "why")       # no choices
    with pytest.raises(ValueError, match="choice"):
        Reproduced.claim("C", "q", None, "why", choices=("a | b",))
    row = build_table([{"paper": "C", "item": "F", "quantity": "q", "unit": "", "value": None,
                        "source": "printed"}],
                      [Reproduced.claim("C", "q", Margin(1.0, 0.0, "", "x"), "why", choices=())])[0]
    assert row["choices"] == NO_CHOICE and row["alternatives"] == ""


def test_rows_that_name_one_cause_are_one_finding():
    """Paper C's GA optimum on its bounds shows in theta_ga, mu_opt and every Table 2 value
    beside it: one cause, one finding, however their explanations differ; rows naming no cause
    fall back to their explanations."""
    values = [{"paper": "C", "item": "Table 2", "quantity": q, "unit": "", "value": 1.0,
               "source": "printed", "read_off_figure": "no", "claim": "", "quote_where": "",
               "quote_fa": "", "quote_en": ""} for q in ("a", "b", "c")]
    rows = [Reproduced.of("C", "a", 5.0, "m1 at its upper bound", cause="the GA's optimum"),
            Reproduced.of("C", "b", 5.0, "c1 at its lower bound", cause="the GA's optimum"),
            Reproduced.of("C", "c", 5.0, "c1 at its lower bound")]
    table = build_table(values, rows)
    assert [r["finding"] for r in table] == ["C1", "C1", "C2"]


def test_an_infinite_margin_is_said_in_words():
    """A curve censored at one end rises without bound: the margin's text says so, never
    "+inf"."""
    row = {"margin": "inf", "uncertainty": "1e-05", "margin_unit": "s", "margin_basis": "b"}
    assert margin_text(row) == "without bound +/- 1e-05 (s; b)"
    assert margin_text({**row, "margin": "-inf"}).startswith("failing without bound")
