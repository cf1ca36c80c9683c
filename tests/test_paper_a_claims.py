"""Paper A's claim rows on constructed datasets: what each can decide."""

import numpy as np
import xarray as xr

from rotorvib.comparison.choices import Close
from rotorvib.comparison.verdicts import claim_verdict
from rotorvib.papers.a.claims import two_term_row

RK = {"method": "dop853", "rtol": 1e-11}


def errors(one, two, deltas=(0.32, 0.16, 0.08)):
    d = np.asarray(deltas)
    return xr.Dataset({"error_one_term": ("delta", np.asarray(one) * d),
                       "error_two_term": ("delta", np.asarray(two) * d)},
                      coords={"delta": d})


def test_the_two_term_claim_is_decided_only_where_one_term_is_not_close():
    """Where one term is within 'close' at every distance, no case tells the two solutions
    apart: undecided; where it is not, the two-term error there decides, at the least such
    distance."""
    close = Close(0.1)
    row = two_term_row(errors([0.05, 0.02, 0.01], [0.01, 0.004, 0.001]), 0.01, 0.001, close, RK)
    assert claim_verdict(row.holds) == "UNDETERMINED"
    row = two_term_row(errors([0.13, 0.12, 0.03], [0.05, 0.02, 0.003]), 0.01, 0.001, close, RK)
    assert claim_verdict(row.holds) == "SUPPORTED"
    assert row.margin.value == 0.1 - 0.02 and "delta = 0.16" in row.margin.basis
    row = two_term_row(errors([0.13, 0.12, 0.03], [0.05, 0.11, 0.003]), 0.01, 0.001, close, RK)
    assert claim_verdict(row.holds) == "NOT SUPPORTED"
    # a reading of 'close' at which no distance tells them apart leaves that variant undecided
    row = two_term_row(errors([0.13, 0.12, 0.03], [0.05, 0.02, 0.003]), 0.01, 0.001,
                       Close(0.1, (0.2,)), RK)
    assert dict(row.holds) == {"comparison.close = 0.1": True, "comparison.close = 0.2": None}
    assert claim_verdict(row.holds) == "SUPPORTED"       # an undecided variant counts neither way
