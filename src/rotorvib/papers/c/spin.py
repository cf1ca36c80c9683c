"""Beyond paper C: what its model leaves out -- the rotor's mean spin.

The paper's kinetic energy (eqs 1-3) holds the disk's twist rate theta' alone, so the speed
Omega at which the rotor turns never enters.  With it, the term ``-m u (Omega + theta')^2`` of
eq. (9), linearised, softens each absorber set's springs from ``2 k`` to ``2 k - m Omega^2``
(:func:`rotorvib.models.absorber.frequency_response.matrices`): a set tuned at rest to
``omega_a = sqrt(2 k / m)`` is tuned at speed to

    omega_a(Omega) = sqrt(omega_a^2 - Omega^2),

and loses its spring (the set drifts outwards) at ``Omega = omega_a``.  :func:`spin_dataset`
follows Table 2's absorber over the spin, :func:`spin_rows` says whether it stays tuned at a
realistic speed.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.comparison import Margin, Reproduced
from rotorvib.models.absorber.frequency_response import amplitude
from rotorvib.models.absorber.parameters import Rotor

REFERENCE = ("Paper C: dual dynamic vibration absorber for the torsional vibration of a rotor; "
             "eqs (1)-(14), beyond the paper")


def tuned_frequency(omega_a, spin):
    """``sqrt(omega_a^2 - Omega^2)`` (rad/s), the natural frequency of a set on a locked disk
    spinning at ``spin``; NaN where the spring is lost (``Omega >= omega_a``)."""
    squared = np.asarray(omega_a, float) ** 2 - np.asarray(spin, float) ** 2
    return np.sqrt(np.where(squared > 0, squared, np.nan))


def spin_dataset(rotor: Rotor, table2, *, n: int, realistic: float, w) -> xr.Dataset:
    """Table 2's absorber over ``n`` spins from rest to just below the first spring loss (99 %
    of the smallest ``omega_a``): each set's tuning ``omega_a(Omega) / omega_n`` and D at the
    rotor's resonance (w = 1); and the frequency response over ``w`` at rest and at the
    ``realistic`` spin (rad/s)."""
    loss = min(s.omega_a for s in table2)
    spins = np.linspace(0.0, 0.99 * loss, n)
    tuning = np.stack([tuned_frequency(s.omega_a, spins) / rotor.omega_n for s in table2])
    at_resonance = np.array([float(amplitude(rotor, table2, 1.0, spin)) for spin in spins])
    responses = np.stack([amplitude(rotor, table2, w, spin) for spin in (0.0, realistic)])
    one = {"units": "1"}
    return xr.Dataset(
        {"tuning": (("set", "spin"), tuning, {
            "long_name": "natural frequency of the set on a locked disk over omega_n, "
                         "sqrt(omega_a^2 - Omega^2) / omega_n", **one}),
         "D_resonance": ("spin", at_resonance, {
             "long_name": "dimensionless torsional amplitude D at w = 1 with Table 2's absorber",
             **one}),
         "D": (("case", "w"), responses, {
             "long_name": "dimensionless torsional amplitude D with Table 2's absorber", **one}),
         "spring_loss": ("set", [s.omega_a for s in table2], {
             "long_name": "spin at which the set loses its spring, sqrt(2 k / m)",
             "units": "rad s-1"}),
         "realistic_spin": ((), realistic, {"long_name": "spin of a realistic machine",
                                            "units": "rad s-1"}),
         "omega_n": ((), rotor.omega_n, {"long_name": "natural frequency of the rotor without "
                                                  "absorber", "units": "rad s-1"})},
        coords={"spin": ("spin", spins, {"long_name": "mean spin of the rotor Omega",
                                         "units": "rad s-1"}),
                "set": ("set", np.arange(1, len(table2) + 1, dtype=np.int32),
                        {"long_name": "absorber set", "units": "1"}),
                "case_name": ("case", np.array(["at rest", "realistic spin"], dtype=object),
                              {"long_name": "spin of the frequency response"}),
                "w": ("w", np.asarray(w, float), {"long_name": "forcing frequency ratio "
                                                               "omega/omega_n", **one})},
        attrs={"title": "Paper C, beyond the paper: the rotor's mean spin",
               "summary": "Table 2's absorber with the centrifugal softening 2k - m Omega^2 the "
                          "paper's model leaves out: its tuning and the amplitude at resonance "
                          "over the spin, and the frequency response at a realistic spin",
               "references": REFERENCE},
    )


def spin_rows(ds: xr.Dataset, close: float) -> list[Reproduced]:
    """Beyond the paper: does Table 2's absorber, tuned at rest, stay tuned within the
    comparison's standard for close at the realistic spin?  Closed form, no uncertainty."""
    realistic, wn = float(ds.realistic_spin), float(ds.omega_n)
    rest = ds.spring_loss.values / wn
    at_speed = tuned_frequency(ds.spring_loss.values, realistic) / wn
    detuning = float(np.max(np.abs(at_speed - rest) / rest))
    d0 = float(ds.D.values[0][np.argmin(np.abs(ds.w.values - 1))])
    d1 = float(np.interp(realistic, ds.spin.values, ds.D_resonance.values))
    return [Reproduced.claim(
        "C", "spin_keeps_tuning",
        Margin(close - detuning, 0.0, "relative", "closed form sqrt(omega_a^2 - Omega^2)"),
        f"at Omega = {realistic:.4g} rad/s ({realistic * 30 / np.pi:.0f} rpm) the sets' tuning "
        "moves from " + ", ".join(f"{a:.3f}" for a in rest) + " to "
        + ", ".join(f"{b:.3f}" for b in at_speed) + f" omega_n ({detuning:.0%} off); D at "
        f"resonance rises from {d0:.3g} to {d1:.3g}; the springs are lost at "
        + ", ".join(f"{v:.4g}" for v in ds.spring_loss.values) + " rad/s. Close means within "
        f"{close:.0%}, the comparison's standard")]
