"""The discrepancy analysis: hypotheses, inversion, the join with the comparison table."""

import csv
import math
from dataclasses import replace

import numpy as np
import pytest

from rotorvib.comparison import discrepancy as d
from rotorvib.comparison.reproduced import Reproduced
from rotorvib.io.datasets import check_metadata
from rotorvib.papers.b import discrepancies as b
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.c import discrepancies as c


@pytest.mark.parametrize("text, places", [("9.04", 2), ("4", 0), ("7.5e-4", 5), ("0.006", 3),
                                          ("1e3", 0)])
def test_decimals_of_a_printed_number(text, places):
    assert d.decimals(text) == places


def test_rounding_reproduces_a_number_printed_to_fewer_digits():
    """Table 1 prints 4 s; 3.796 s rounds to it, 3.40 s does not."""
    assert d.reproduces(4.0, d.generic_hypotheses("q", "s", "4", 3.796)[0].value)
    assert not d.reproduces(4.0, d.generic_hypotheses("q", "s", "4", 3.40)[0].value)


def test_slips_of_a_length_cover_decades_and_centimetres():
    slips = dict(d.parameter_slips("R", "m", 0.1))
    assert slips == pytest.approx({"R x 10": 1.0, "R / 10": 0.01, "R read as cm": 1e-3,
                                   "R read as mm": 1e-4, "R cm read as m": 10.0})
    assert dict(d.parameter_slips("zeta", "1", 0.01)) == pytest.approx({"zeta x 10": 0.1,
                                                                        "zeta / 10": 1e-3})


def test_inversion_finds_the_root_nearest_the_stated_value():
    """q(p) = (p - 2)^2 has roots 1 and 3 for the target 1; stated 2.8 picks 3."""
    def q(xs):
        return (np.asarray(xs) - 2.0) ** 2

    inv = d.invert(q, 1.0, 2.8, 0.28, 28.0, quantity="q", parameter="p", n_scan=41)
    assert inv.status == "solved" and inv.needed == pytest.approx(3.0, rel=1e-4)
    assert "+7 %" in inv.text()


def test_inversion_reports_jumps_and_missing_brackets():
    def step(xs):
        return np.where(np.asarray(xs) < 1.0, 0.0, 10.0)

    jump = d.invert(step, 5.0, 0.5, 0.1, 10.0, quantity="q", parameter="p")
    assert jump.status == "jump" and jump.needed == pytest.approx(1.0, rel=1e-3)
    none = d.invert(step, 50.0, 0.5, 0.1, 10.0, quantity="q", parameter="p")
    assert none.status == "none" and math.isnan(none.needed)
    assert "no value in [0.1, 10]" in none.text()


def test_inversion_recovers_a_known_damping_ratio_from_a_simulated_balance_time(config):
    """Synthetic case: Fig 7's balance time computed with zeta = 0.013 is handed to the
    inversion as the 'printed' value; starting from the stated 0.01 it finds 0.013 again."""
    cfg = config["paper_b"]
    setup = Setup.from_paper_b(cfg)
    fig7 = next(q for q in b.quantities(cfg, {}) if q.name == "fig7_balance_time")
    (metrics,) = b.run_all(setup, [(fig7, "printed", {"zeta": 0.013})])
    target = fig7.value(metrics)
    inv = b.inversions(setup, fig7, target, "printed", ["zeta"], (0.5, 2.0), 5)[0]
    assert inv.status == "solved"
    assert inv.needed == pytest.approx(0.013, rel=2e-3)


def test_runs_asked_for_again_come_from_the_memo_unchanged(config, monkeypatch):
    """Two quantities of one Table 2 row are one run: with a memo, a request already made runs
    nothing and gives the same metrics, and a batch holds each distinct run once."""
    cfg = config["paper_b"]
    setup = Setup.from_paper_b(cfg)
    row = {q.name: q for q in b.quantities(cfg, {})}
    force, decay = row["table2_fmax_1"], row["table2_decay_1"]
    made, runs = [], Setup.runs

    def counted(self, inputs, **kw):
        made.append(len(inputs))
        return runs(self, inputs, **kw)

    monkeypatch.setattr(Setup, "runs", counted)
    memo = {}
    first = b.run_all(setup, [(force, "printed", {}), (decay, "printed", {})], memo)
    assert made == [1] and np.array_equal(first[0], first[1], equal_nan=True)
    again = b.run_all(setup, [(decay, "printed", {}), (force, "consistent", {})], memo)
    assert made == [1, 1]                      # only the consistent kinematics is new
    np.testing.assert_array_equal(again[0], first[0])
    np.testing.assert_array_equal(again[1], b.run_all(setup, [(force, "consistent", {})])[0])


def test_paper_c_inversion_of_a_linear_parameter_is_exact(config):
    """|Theta| is proportional to Gamma0: the value that gives 7.5e-4 rad is known exactly."""
    stated = {**config["paper_c"]["rotor"], **config["paper_c"]["table2"], "fig3_time": 2.0}
    baseline = c.theta_table2(stated)
    inv = next(i for i in c.inversions("theta_table2", 7.5e-4, stated, ["Gamma0"], (0.1, 10), 9,
                                       baseline))
    assert inv.needed == pytest.approx(stated["Gamma0"] * 7.5e-4 / baseline, rel=1e-4)


def test_paper_c_fig3_hypotheses_scale_the_integrated_amplitude(config):
    """Gamma0 t / (2 J omega_n) = 0.2259 rad exactly; an integrated amplitude of 0.2248 rad (a
    coarse sampling) is the baseline, and a slip scales it by the ratio of envelopes."""
    stated = {**config["paper_c"]["rotor"], **config["paper_c"]["table2"], "fig3_time": 2.0}
    J = 0.5 * stated["M"] * stated["R"] ** 2
    assert c.fig3_amplitude(stated) == pytest.approx(
        stated["Gamma0"] * 2.0 / (2 * J * math.sqrt(stated["k_t"] / J)), rel=1e-12)
    baselines, found = c.hypotheses(stated, ["fig3_theta_2s"], ["Gamma0", "M"],
                                    {"fig3_theta_2s": 0.2248})
    assert baselines["fig3_theta_2s"] == pytest.approx(0.2248, rel=1e-12)
    by_name = {h.name: h.value for h in found}
    assert by_name["Gamma0 / 10"] == pytest.approx(0.02248, rel=1e-12)
    assert by_name["M x 10"] == pytest.approx(0.2248 / math.sqrt(10), rel=1e-12)


def _row(quantity, printed, reproduced, verdict):
    return {"paper": "B", "quantity": quantity, "unit": "s", "paper_value": printed,
            "reproduced": reproduced, "verdict": verdict, "explanation": "why"}


def test_analysis_joins_rows_hypotheses_and_inversions():
    table = [_row("t1", 9.04, 5.98, "MAJOR"), _row("t2", 4.7, 3.9, "MAJOR"),
             _row("t3", 1.0, 1.0, "MATCH")]
    values = [{"paper": "B", "quantity": q, "value_text": t} for q, t in
              (("t1", "9.04"), ("t2", "4.70"), ("t3", "1.0"))]
    reproduced = [Reproduced("B", "t1", 5.98, "", variants=(("consistent", 6.8),))]
    hyps = [d.Hypothesis("t1", "zeta / 10", "parameter slip", 9.05),
            d.Hypothesis("t2", "zeta / 10", "parameter slip", 7.0)]
    inv = [d.Inversion("t1", "zeta", 0.01, 0.0074, 0.001, 0.1, "solved")]
    ds = d.to_dataset({"t1": 5.98, "t2": 3.9}, hyps, inv, {"title": "t"})
    check_metadata(ds)
    analyses = d.analyse(table, values, reproduced, [d.from_dataset(ds)])
    assert [a.quantity for a in analyses] == ["t1", "t2"]
    t1 = analyses[0]
    assert [h.name for h in t1.reproduced_by] == ["zeta / 10"]
    assert "consistent variant" in [h.name for h in t1.hypotheses]
    assert "it reproduces 1 of the 2 missed numbers it was tried on" in t1.text()
    assert "needs zeta = 0.0074 (-26 %)" in t1.text()
    assert "none of" in analyses[1].text() and "closest: zeta / 10 gives 7" in analyses[1].text()
    assert d.totals(analyses).startswith("discrepancies (2): 1 reproduced by a hypothesis, 1 "
                                         "ruled out")
    annotated = d.annotate(table, analyses)
    assert annotated[0]["explanation"].startswith("why. Discrepancy analysis: 1 of ")
    assert annotated[2]["explanation"] == "why"


def test_a_model_that_does_not_give_the_reproduced_value_is_refused():
    table = [_row("t1", 9.04, 5.98, "MAJOR")]
    values = [{"paper": "B", "quantity": "t1", "value_text": "9.04"}]
    ds = d.to_dataset({"t1": 6.5}, [], [], {"title": "t"})
    with pytest.raises(ValueError, match="t1: the discrepancy model gives 6.5"):
        d.analyse(table, values, [], [d.from_dataset(ds)])


def test_totals_read_back_from_the_csv_equal_those_of_the_analyses(tmp_path):
    """The report reads results/discrepancies.csv: a solved inversion is not a hypothesis, so
    t2 (reproduced only by an inversion) stays ruled out."""
    table = [_row("t1", 9.04, 5.98, "MAJOR"), _row("t2", 4.7, 3.9, "MAJOR")]
    values = [{"paper": "B", "quantity": q, "value_text": t} for q, t in
              (("t1", "9.04"), ("t2", "4.70"))]
    reproduced = [Reproduced("B", "t1", 5.98, "")]
    hyps = [d.Hypothesis("t1", "zeta / 10", "parameter slip", 9.05),
            d.Hypothesis("t2", "zeta / 10", "parameter slip", 7.0),
            d.Hypothesis("t2", "c / 10", "parameter slip", float("nan"))]   # never comes
    inv = [d.Inversion("t2", "zeta", 0.01, 0.0074, 0.001, 0.1, "solved"),
           d.Inversion("t2", "k", 1e4, float("nan"), 1e3, 1e5, "none")]
    ds = d.to_dataset({"t1": 5.98, "t2": 3.9}, hyps, inv, {"title": "t"})
    analyses = d.analyse(table, values, reproduced, [d.from_dataset(ds)])
    d.write_files(analyses, tmp_path / "d.csv", tmp_path / "d.md")
    with open(tmp_path / "d.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert any(r["kind"] == "inversion" and r["reproduces"] == "True" for r in rows)
    # no value: the cell is empty, as a missing relative error is, never 'nan'
    assert [r["value"] for r in rows if r["hypothesis"] in ("c / 10", "k: no value in "
                                                              "[1e+03, 1e+05]")] == ["", ""]
    assert d.totals_of_rows(rows) == d.totals(analyses)
    assert d.totals(analyses).startswith("discrepancies (2): 1 reproduced by a hypothesis, 1 ")


def test_a_self_contradicting_number_is_explained_against_its_implied_value():
    """Paper B's text prints a 55 % reduction its own Table 2 puts at 32.9 %: the row is judged
    against 32.9 %, and so are the hypotheses and inversions that would explain a miss (a
    hypothesis giving 55 % reproduces nothing; one giving 32.9 % does)."""
    values = [{"paper": "B", "quantity": "t", "value": 55.0, "source": "printed",
               "value_text": "55", "unit": "%"}]
    reproduced = [Reproduced.of("B", "t", 20.0, "x", implied=32.9)]
    assert d.misses(values, reproduced) == {"t": (32.9, "MAJOR")}
    table = [{"paper": "B", "quantity": "t", "unit": "%", "paper_value": 55.0,
              "reproduced": 20.0, "verdict": "MAJOR"}]
    (a,) = d.analyse(table, values, reproduced, [])
    assert a.printed == 32.9
    hyps = (d.Hypothesis("t", "swap", "variant", 55.0), d.Hypothesis("t", "fix", "variant", 32.9))
    a = replace(a, hypotheses=hyps)
    assert [h.name for h in a.reproduced_by] == ["fix"]
    # a number the paper states once stays judged against its printed value
    assert d.misses(values, [Reproduced.of("B", "t", 20.0, "x")]) == {"t": (55.0, "MAJOR")}
