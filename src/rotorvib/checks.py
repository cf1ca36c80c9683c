"""Argument checks shared by the public entry points: each raises ``ValueError`` naming the
argument, its value and what is allowed, before any work is done, and returns the value as a
Python ``float`` or ``int`` (a numpy scalar of any width is normalised: a ``float16`` mass is
not kept to overflow later, an ``int8`` count not kept to wrap)."""

from __future__ import annotations

import numbers
import sys

import numpy as np

#: The least magnitude of a normal double: a nonzero number below it (subnormal, 5e-324 for one)
#: has lost precision, passes any bound "> 0" and underflows to 0 in a product.
SMALLEST_NORMAL = sys.float_info.min
#: The magnitudes a scalar argument may have (or 0, where 0 is allowed): products and powers
#: of a few of them stay finite and normal in double precision (1e100 cubed is 1e300), and no
#: quantity of a rotor, in SI units, lies outside.
MAGNITUDES = (1e-100, 1e100)


def number(name: str, value, *, minimum: float = 0.0, inclusive: bool = False,
           what: str = "") -> float:
    """``value`` as a float; ``ValueError`` naming ``name`` unless it is finite, above
    ``minimum`` (or equal to it, if ``inclusive``) and 0 or within :data:`MAGNITUDES` in
    magnitude.  ``what`` adds a reason to the message."""
    want = f"must be a finite number {'>=' if inclusive else '>'} {minimum:g}{what}"
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} = {value!r}: {want}")
    ok = np.isfinite(value) and (value >= minimum if inclusive else value > minimum)
    if not ok:
        raise ValueError(f"{name} = {float(value)!r}: {want}")
    if value != 0 and not MAGNITUDES[0] <= abs(value) <= MAGNITUDES[1]:
        raise ValueError(f"{name} = {float(value)!r}: {want}, between {MAGNITUDES[0]:g} and "
                         f"{MAGNITUDES[1]:g} in magnitude (beyond, products underflow or "
                         "overflow; a subnormal number has lost precision already)")
    return float(value)


def require(obj, positive=(), nonnegative=()) -> None:
    """``ValueError`` naming the first field of ``obj`` that is not a finite number > 0 (those in
    ``positive``) or >= 0 (those in ``nonnegative``); each field is then set to its value as a
    Python float (on a frozen dataclass too)."""
    for names, inclusive in ((positive, False), (nonnegative, True)):
        for name in names:
            value = number(f"{type(obj).__name__}.{name}", getattr(obj, name),
                           inclusive=inclusive)
            object.__setattr__(obj, name, value)


def finite_array(name: str, value, *, shape: tuple | None = None, dtype=float) -> np.ndarray:
    """``value`` as an array of ``dtype``; ``ValueError`` unless it holds real numbers (not
    booleans, complex, text or objects), every entry is finite and, where ``shape`` is given,
    the shape matches (``None`` entries match any length)."""
    try:
        given = np.asarray(value)
        if given.dtype.kind not in "iuf" + ("c" if np.dtype(dtype).kind == "c" else ""):
            raise TypeError(f"entries of type {given.dtype}")
        a = given.astype(dtype)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name}: must be an array of real numbers ({error})") from None
    if shape is not None and (a.ndim != len(shape) or any(
            want is not None and got != want for got, want in zip(a.shape, shape))):
        want = "(" + ", ".join("any" if s is None else str(s) for s in shape) + ")"
        raise ValueError(f"{name}: shape {a.shape}, expected {want}")
    finite = np.isfinite(a)
    if not finite.all():
        first = ", ".join(str(i) for i in np.argwhere(~finite)[0])
        where = f"{name}[{first}]" if a.ndim else name
        raise ValueError(f"{where} = {a[~finite][0].item()!r}: must be finite "
                         f"({a.size - int(finite.sum())} of {a.size} entries are not)")
    return a


def in_domain(name: str, values: np.ndarray, holds: np.ndarray, allowed: str) -> np.ndarray:
    """``values`` itself; ``ValueError`` naming ``name`` and its first entry where ``holds`` is
    false (``allowed`` says what is allowed) or that is neither 0 nor within
    :data:`MAGNITUDES` in magnitude."""
    size = np.abs(values)
    holds = holds & ((values == 0) | ((size >= MAGNITUDES[0]) & (size <= MAGNITUDES[1])))
    if not np.all(holds):
        bad = np.broadcast_to(values, np.shape(holds))[~np.broadcast_to(holds, np.shape(holds))]
        raise ValueError(f"{name} = {bad.flat[0].item()!r}: must be {allowed}, and 0 or between "
                         f"{MAGNITUDES[0]:g} and {MAGNITUDES[1]:g} in magnitude")
    return values


#: Entries of an array argument at most (a frequency grid, the times of a response): a million
#: complex matrices of a few sets, or 10 million states of eight doubles, stay below 1 GB.
MAX_ENTRIES = 10_000_000


def nonnegative_array(name: str, value, what: str) -> np.ndarray:
    """``value`` as a float array of at most :data:`MAX_ENTRIES` entries, each finite, >= 0
    and 0 or within :data:`MAGNITUDES` (``what`` names the quantity); ``ValueError`` naming
    ``name`` otherwise (a negative frequency or time has no meaning here, and 1e300 squared is
    no longer a number)."""
    a = finite_array(name, value)
    if a.size > MAX_ENTRIES:
        raise ValueError(f"{name}: {a.size} entries; at most {MAX_ENTRIES}")
    return in_domain(name, a, a >= 0, f"{what} >= 0")


def integer(name: str, value, minimum: int, maximum: int | None = None) -> int:
    """``value`` as an ``int``; ``ValueError`` unless it is an integer (not a float or bool)
    ``>= minimum`` (and ``<= maximum``, when given)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral) or \
            value < minimum or (maximum is not None and value > maximum):
        upper = f" and <= {maximum}" if maximum is not None else ""
        raise ValueError(f"{name} = {value!r}: must be an integer >= {minimum}{upper}")
    return int(value)


def flag(name: str, value) -> bool:
    """``value`` as a bool; ``ValueError`` for anything but ``True`` or ``False``."""
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} = {value!r}: must be True or False")
    return bool(value)


def instance(name: str, value, kind: type, *, optional: bool = False):
    """``value`` itself; ``ValueError`` unless it is a ``kind`` (or None, if ``optional``)."""
    if (value is None and optional) or isinstance(value, kind):
        return value
    raise ValueError(f"{name} = {value!r}: must be a {kind.__name__}"
                     f"{' or None' if optional else ''}")


def sobol_design_problem(n_base, convergence) -> str | None:
    """Why a Saltelli design of ``n_base`` base points, shown at the sizes ``convergence``,
    cannot be run (None if it can): every size a power of 2, none above ``n_base``."""
    for size in [n_base, *convergence]:
        if size < 2 or size & (size - 1):
            return f"{size} base points: must be a power of 2 (a balanced Sobol sequence)"
    if max(convergence) > n_base:
        return f"convergence {list(convergence)}: every size must be at most n_base = {n_base}"
    return None
