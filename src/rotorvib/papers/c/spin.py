"""Beyond paper C: what its model leaves out -- the rotor's mean spin.

The paper's kinetic energy (eqs 1-3) holds the disk's twist rate theta' alone, so the speed
Omega at which the rotor turns never enters.  With it, the term ``-m u (Omega + theta')^2`` of
eq. (9), linearised, softens each absorber set's springs from ``2 k`` to ``2 k - m Omega^2``
(:func:`rotorvib.models.absorber.frequency_response.matrices`): a set tuned at rest to
``omega_a = sqrt(2 k / m)`` is tuned at speed to

    omega_a(Omega) = sqrt(omega_a^2 - Omega^2),

and loses its spring (the set drifts outwards) at ``Omega = omega_a``: the tuning falls by
more than a relative ``c`` once ``Omega > sqrt(1 - (1 - c)^2) omega_a`` (:func:`detuning_limit`),
whatever the machine.  The remedy is to tune at speed: springs ``k' = k + m Omega^2 / 2`` give
``2 k' - m Omega^2 = 2 k``, the set's tuning at rest (:func:`retuned`).  :func:`spin_dataset`
follows Table 2's absorber over the spin, softened and retuned; :func:`spin_rows` says whether
it stays tuned at the speeds of machines it may run on.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import xarray as xr

from rotorvib.checks import integer, nonnegative_array, number
from rotorvib.comparison.choices import VARIANT_JOIN, Close

from rotorvib.comparison.reproduced import Margin, Reproduced
from rotorvib.io.coords import label_coord, labels
from rotorvib.models.absorber.frequency_response import amplitude
from rotorvib.models.absorber.parameters import Rotor

REFERENCE = ("Paper C: dual dynamic vibration absorber for the torsional vibration of a rotor; "
             "eqs (1)-(14), beyond the paper")


def tuned_frequency(omega_a, spin):
    """``sqrt(omega_a^2 - Omega^2)`` (rad/s), the natural frequency of a set on a locked disk
    spinning at ``spin``; NaN where the spring is lost (``Omega >= omega_a``), the one NaN it
    returns: ``omega_a`` and ``spin`` finite and >= 0 (rad/s)."""
    omega_a = nonnegative_array("omega_a", omega_a, "a frequency (rad/s)")
    squared = omega_a**2 - nonnegative_array("spin", spin, "a rotor speed (rad/s)") ** 2
    return np.sqrt(np.where(squared > 0, squared, np.nan))


def detuning_limit(close: float) -> float:
    """The spin, as a fraction of a set's ``omega_a``, above which its tuning
    ``sqrt(omega_a^2 - Omega^2)`` is more than ``close`` (relative) below ``omega_a``:
    ``sqrt(1 - (1 - close)^2)``; ``close`` a fraction in (0, 1]."""
    close = number("close", close, what=" (a relative tolerance)")
    if close > 1:
        raise ValueError(f"close = {close!r}: must be a fraction <= 1 (a relative tolerance)")
    return float(np.sqrt(1.0 - (1.0 - close) ** 2))


def retuned(sets, spin: float):
    """The sets with springs ``k + m Omega^2 / 2``: tuned at ``spin`` as they were at rest;
    ``spin`` finite and >= 0 (rad/s)."""
    spin = number("spin", spin, inclusive=True, what=" (rotor speed, rad/s)")
    return tuple(replace(s, k=s.k + s.m * spin**2 / 2) for s in sets)


def spin_dataset(rotor: Rotor, table2, *, n: int, realistic: float, w,
                 alternatives=()) -> xr.Dataset:
    """Table 2's absorber over ``n`` spins from rest to just below the first spring loss (99 %
    of the smallest ``omega_a``): each set's tuning ``omega_a(Omega) / omega_n`` and D at the
    rotor's resonance (w = 1), as built and tuned at each spin (:func:`retuned`); the
    frequency response over ``w`` at rest and at the ``realistic`` spin (rad/s); and the
    machine speeds the claim is evaluated at, ``realistic`` and the ``alternatives`` (rad/s,
    each below the spring loss). ``n`` is 2 to 100 000 (the configuration's bound: each spin
    is two frequency responses)."""
    n = integer("n", n, 2, 100_000)
    loss = min(s.omega_a for s in table2)
    spins = np.linspace(0.0, 0.99 * loss, n)
    machines = np.array([realistic, *alternatives], float)
    if machines.max() > spins[-1]:
        raise ValueError(f"paper_c.spin: a machine speed of {machines.max() * 30 / np.pi:g} rpm "
                         f"is beyond the spins followed, up to {spins[-1] * 30 / np.pi:g} rpm "
                         "(99 % of the first spring loss)")
    tuning = np.stack([tuned_frequency(s.omega_a, spins) / rotor.omega_n for s in table2])
    at_resonance = np.array([float(amplitude(rotor, table2, 1.0, spin)) for spin in spins])
    at_resonance_retuned = np.array([float(amplitude(rotor, retuned(table2, spin), 1.0, spin))
                                     for spin in spins])
    responses = np.stack([amplitude(rotor, table2, w, spin) for spin in (0.0, realistic)])
    one = {"units": "1"}
    return xr.Dataset(
        {"tuning": (("set", "spin"), tuning, {
            "long_name": "natural frequency of the set on a locked disk over omega_n, "
                         "sqrt(omega_a^2 - Omega^2) / omega_n", **one}),
         "D_resonance": ("spin", at_resonance, {
             "long_name": "dimensionless torsional amplitude D at w = 1 with Table 2's absorber",
             **one}),
         "D_resonance_retuned": ("spin", at_resonance_retuned, {
             "long_name": "D at w = 1 with Table 2's absorber tuned at the spin, springs "
                          "k + m Omega^2 / 2", **one}),
         "D": (("case", "w"), responses, {
             "long_name": "dimensionless torsional amplitude D with Table 2's absorber", **one}),
         "spring_loss": ("set", [s.omega_a for s in table2], {
             "long_name": "spin at which the set loses its spring, sqrt(2 k / m)",
             "units": "rad s-1"}),
         "realistic_spin": ((), realistic, {"long_name": "spin of a realistic machine",
                                            "units": "rad s-1"}),
         "machine_spin": ("machine", machines, {"long_name": "speeds of the machines the claim "
                                                             "is evaluated at",
                                                "units": "rad s-1"}),
         "omega_n": ((), rotor.omega_n, {"long_name": "natural frequency of the rotor without "
                                                  "absorber", "units": "rad s-1"})},
        coords={"spin": ("spin", spins, {"long_name": "mean spin of the rotor Omega",
                                         "units": "rad s-1"}),
                **label_coord("machine", ["paper_c.spin.realistic_rpm"]
                              + ["paper_c.spin.alternative_rpm"] * len(alternatives),
                              "the configuration key of each machine speed"),
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


def spin_rows(ds: xr.Dataset, close: Close) -> list[Reproduced]:
    """Beyond the paper: does Table 2's absorber, tuned at rest, stay tuned within the
    comparison's standard for close at the speeds of the machines it may run on (the paper
    gives none: each is evaluated, and the row depends on the speed where they differ)?  The
    text gives the speed-free result (:func:`detuning_limit`) and the remedy's amplitude.
    Closed form, no uncertainty."""
    wn, omega_a = float(ds.omega_n), ds.spring_loss.values
    d_rest = float(ds.D_resonance.values[0])

    def detuning(spin):          # a lost spring (NaN) is detuned entirely
        return float(np.max(np.nan_to_num(1 - tuned_frequency(omega_a, spin) / omega_a,
                                          nan=1.0)))

    holds, said = {}, []
    for key, spin in zip(labels(ds, "machine"), ds.machine_spin.values):
        choice = f"{key} = {spin * 30 / np.pi:g} rpm"
        for name, margin in close.margins(
                lambda c: Margin(c - detuning(spin), 0.0, "relative",
                                 "closed form sqrt(omega_a^2 - Omega^2)")).items():
            holds[f"{choice}{VARIANT_JOIN}{name}"] = margin
        soft = float(np.interp(spin, ds.spin.values, ds.D_resonance.values))
        tuned = float(np.interp(spin, ds.spin.values, ds.D_resonance_retuned.values))
        said.append(f"{choice}: {detuning(spin):.0%} off, D at resonance {soft:.3g} "
                    f"(tuned at speed {tuned:.3g})")
    limits = ", ".join(f"{detuning_limit(c):.3g} omega_a for {c:g}"
                       for c in (close.value, *close.alternatives))
    return [Reproduced.claim(
        "C", "spin_keeps_tuning", holds,
        f"whatever the machine, a set's tuning sqrt(omega_a^2 - Omega^2) falls more than a "
        f"relative c below omega_a once Omega exceeds sqrt(1 - (1 - c)^2) omega_a: {limits} "
        f"(Table 2's sets: omega_a = " + ", ".join(f"{v:.4g}" for v in omega_a)
        + " rad/s = " + ", ".join(f"{v / wn:.3f}" for v in omega_a) + " omega_n). At rest D "
        f"at resonance is {d_rest:.3g}; " + "; ".join(said) + ". The remedy, springs "
        "k + m Omega^2 / 2 (tuned at speed), restores the tuning at rest exactly; the springs "
        "are lost at Omega = omega_a",
        choices=("paper_c.spin.realistic_rpm, alternative_rpm (machine speeds, assumed: the "
                 "paper gives none)", close.choice))]
