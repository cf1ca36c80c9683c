"""Paper C's claims tested as the paper words them."""

import numpy as np

from rotorvib.comparison import claim_verdict
from rotorvib.models.absorber.frequency_response import bare_rotor_amplitude
from rotorvib.models.absorber.parameters import Rotor, dual_absorber, dual_to_vector
from rotorvib.papers.c.claims import frequency_rows
from rotorvib.papers.c.studies import frequency_response_dataset


def test_better_at_all_frequencies_is_tested_at_every_frequency(config):
    """The conclusion says the damped optimum dual absorber "performs better at all
    frequencies"; on Fig 5's band it is above the bare rotor away from resonance (the
    bare rotor's 1/|1 - w^2| falls below it), so the claim is NOT SUPPORTED, and the row
    names where."""
    c = config["paper_c"]
    grid = c["frequency_response"]
    w = np.linspace(grid["w_min"], grid["w_max"], grid["n_points"])
    table2 = dual_absorber(**c["table2"])
    fr = frequency_response_dataset(Rotor(**c["rotor"]), table2, dual_to_vector(table2), w)
    np.testing.assert_allclose(fr.D_none.values, bare_rotor_amplitude(w), rtol=1e-12)
    (row,) = [r for r in frequency_rows(fr, c["claims"]) if r.quantity == "fig5_damped_best"]
    assert claim_verdict(row.holds) == "NOT SUPPORTED"
    above = w[fr.D_table2.values > fr.D_none.values]
    assert above.min() == w[0] and above.max() == w[-1]        # both ends of the band
    low = above[above < 1].max()
    assert f"above the bare rotor for w in {w[0]:.3f}-{low:.3f}" in row.explanation
