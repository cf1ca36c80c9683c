"""What the papers' configuration checks share (``rotorvib.papers.<p>.config_checks``): a seeded
search whose spread seeds repeat its seed, an integrator's tolerance finer than double precision.
A module of its own, loaded by no job: the checks run when the workflow reads the configuration."""

from __future__ import annotations

from rotorvib.methods.integrate import RTOL_MIN


def seed_spread_problem(search: dict, name: str) -> str | None:
    """Why a seeded search's ``spread_seeds`` cannot give its spread (None if they can): one of
    them is its ``seed``, whose result would count twice (``name``: its config key)."""
    if search["seed"] in search["spread_seeds"]:
        return (f"must not contain {name}.seed ({search['seed']}), whose result it would count "
                "twice")
    return None


def tolerance_problem(rtol: float) -> str | None:
    """Why a configured relative tolerance cannot be met (None if it can): below
    :data:`rotorvib.methods.integrate.RTOL_MIN`, which the integrators refuse."""
    if rtol < RTOL_MIN:
        return (f"{rtol!r} is below {RTOL_MIN:.3g}, the least relative error double precision "
                "can deliver")
    return None
