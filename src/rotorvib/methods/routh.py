"""Routh's stability criterion: whether every root of a real polynomial has a negative real part,
without computing the roots.

For ``p(s) = a_0 s^n + a_1 s^(n-1) + ... + a_n`` the Routh array starts from the rows
``(a_0, a_2, a_4, ...)`` and ``(a_1, a_3, ...)``; each further row follows from the two above it,

    r[k, j] = (r[k-1, 0] r[k-2, j+1] - r[k-2, 0] r[k-1, j+1]) / r[k-1, 0],

and the number of sign changes down its first column is the number of roots in the right
half-plane (Routh 1877; e.g. Ogata, *Modern Control Engineering*, section 5-6). Every root lies
in the open left half-plane exactly when the n + 1 entries of the first column share the sign of
``a_0``; a zero entry (a root on the imaginary axis, or a pair symmetric about it) counts as not
stable. Each entry costs four operations (two products, a difference, a quotient): about
``n^2`` for the whole array against about ``10 n^3`` for the eigenvalues of an ``n x n`` matrix
by the Hessenberg QR algorithm (Golub and Van Loan, *Matrix Computations*, 4th ed., 7.5.6), the
cost of finding the roots through a companion matrix.
"""

from __future__ import annotations

import math

import numpy as np

#: Operations of the eigenvalues of an n x n real matrix, Hessenberg QR: about 10 n^3.
EIGENVALUE_OPERATIONS_PER_N3 = 10


def first_column(coefficients, dtype=float) -> np.ndarray:
    """The first column of the Routh array of each polynomial (coefficients highest power
    first along the last axis), shape ``(..., n + 1)``; NaN or infinite past a zero entry.
    ``dtype=object`` keeps the coefficients' own numbers (``mpmath.mpf``: the array in their
    precision)."""
    a = np.asarray(coefficients, dtype=dtype)
    n = a.shape[-1] - 1
    if n < 1:
        raise ValueError(f"a polynomial of degree >= 1 is needed, not {n}")
    width = n // 2 + 1

    def padded(row):
        zeros = np.zeros(row.shape[:-1] + (width - row.shape[-1],), dtype=dtype)
        return np.concatenate([row, zeros], -1)

    above, row = padded(a[..., 0::2]), padded(a[..., 1::2])
    column = [above[..., 0], row[..., 0]]
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(n - 1):
            lead = row[..., :1]
            above, row = row, padded((lead * above[..., 1:] - above[..., :1] * row[..., 1:])
                                     / lead)
            column.append(row[..., 0])
    return np.stack(column, axis=-1)


def stable(coefficients, dtype=float) -> np.ndarray:
    """True where every root of the polynomial has a negative real part (module docstring);
    ``dtype`` as in :func:`first_column`."""
    column = first_column(coefficients, dtype)
    return np.all(column * np.sign(column[..., :1]) > 0, axis=-1)


def operations(degree: int) -> int:
    """Operations of the Routh array of a polynomial of ``degree``: four for each entry below
    its first two rows (row k holds ceil((degree + 1 - k) / 2) entries)."""
    return 4 * sum(math.ceil((degree + 1 - k) / 2) for k in range(2, degree + 1))


def eigenvalue_operations(n: int) -> int:
    """Operations of the eigenvalues of an ``n x n`` matrix (:data:`EIGENVALUE_OPERATIONS_PER_N3`
    n^3): the roots of a degree-n polynomial through its companion matrix."""
    return EIGENVALUE_OPERATIONS_PER_N3 * n**3
