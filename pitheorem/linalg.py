"""Exact linear algebra over the rationals.

Small, dependency-free kernels on matrices given as lists of rows of
``int`` or :class:`fractions.Fraction`.  Dimension matrices are tiny (a few
rows, tens of columns), so plain Gauss-Jordan elimination with exact
fractions (computed fraction-free, in Python integers) is simple and fast enough; the only hot loop, testing
millions of column subsets for independence, lives in :mod:`pitheorem.bases`.
No sympy in here: sympy objects are built at the edges, for display.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from math import gcd, lcm

__all__ = [
    "Matrix",
    "integer_rows",
    "integer_rref",
    "nullspace",
    "primitive_integer_vector",
    "rank",
    "row_space_basis",
    "rref",
    "solve",
]

Matrix = list[list[Fraction]]


def rref(rows: Sequence[Sequence]) -> tuple[Matrix, tuple[int, ...]]:
    """Reduced row echelon form and pivot columns.

    Examples
    --------
    >>> from pitheorem.linalg import rref
    >>> rref([[2, 4], [1, 3]])[1]
    (0, 1)
    """
    a, pivots = integer_rref(rows)
    # divide each pivot row by its pivot; the rows past the rank are zero
    scaled = [[Fraction(x, row[p]) for x in row] for row, p in zip(a, pivots, strict=False)]
    return scaled + [[Fraction(0)] * len(row) for row in a[len(pivots) :]], pivots


def integer_rows(rows: Sequence[Sequence]) -> list[list[int]]:
    """Each row times the lcm of its denominators: integers, same row space.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.linalg import integer_rows
    >>> integer_rows([[Fraction(1, 2), Fraction(1, 3)], [2, 0]])
    [[3, 2], [2, 0]]
    """
    out = []
    for row in rows:
        # ints and Fractions already have numerator and denominator: no new objects for them
        fr = [x if isinstance(x, int | Fraction) else Fraction(x) for x in row]
        den = lcm(*(x.denominator for x in fr)) if fr else 1
        out.append([x.numerator * (den // x.denominator) for x in fr] if den > 1 else [x.numerator for x in fr])
    return out


def integer_rref(rows: Sequence[Sequence]) -> tuple[list[list[int]], tuple[int, ...]]:
    """Fraction-free reduced echelon form: integer rows and pivot columns.

    Like :func:`rref`, except that each pivot row is scaled to coprime
    integers with a positive pivot instead of a pivot of 1: the RREF
    entry ``(i, j)`` is ``a[i][j] / a[i][pivots[i]]``.  Only Python
    integers are used, which is several times faster than fractions.

    Examples
    --------
    >>> from pitheorem.linalg import integer_rref
    >>> integer_rref([[2, 4, 1], [1, 3, 0]])
    ([[2, 0, 3], [0, 2, -1]], (0, 1))
    """
    a = integer_rows(rows)
    n_rows = len(a)
    n_cols = len(a[0]) if a else 0
    pivots: list[int] = []
    r = 0
    for c in range(n_cols):
        p = next((i for i in range(r, n_rows) if a[i][c]), None)
        if p is None:
            continue
        a[r], a[p] = a[p], a[r]
        # make the pivot positive first: eliminating with t > 0 keeps the
        # earlier pivots positive too (a negative t would flip their rows)
        g = gcd(*a[r])
        top = a[r] = [x // g for x in a[r]] if a[r][c] > 0 else [-x // g for x in a[r]]
        t = top[c]
        for i in range(n_rows):
            f = a[i][c]
            if i != r and f:
                row = [t * x - f * y for x, y in zip(a[i], top, strict=True)]
                g = gcd(*row)
                a[i] = [x // g for x in row] if g > 1 else row
        pivots.append(c)
        r += 1
        if r == n_rows:
            break
    return a, tuple(pivots)


def rank(rows: Sequence[Sequence]) -> int:
    """Exact rank over the rationals.

    Examples
    --------
    >>> from pitheorem.linalg import rank
    >>> rank([[1, 2], [2, 4]])
    1
    """
    return len(integer_rref(rows)[1])


def row_space_basis(rows: Sequence[Sequence]) -> Matrix:
    """The nonzero rows of the RREF: a basis of the row space.

    Examples
    --------
    >>> from pitheorem.linalg import row_space_basis
    >>> row_space_basis([[1, 1], [2, 2]])
    [[Fraction(1, 1), Fraction(1, 1)]]
    """
    a, pivots = rref(rows)
    return a[: len(pivots)]


def nullspace(rows: Sequence[Sequence], n_cols: int | None = None) -> Matrix:
    """A basis of the right null space, one vector per free column.

    The vector for free column ``j`` has a 1 in position ``j`` and zeros
    in the other free positions, so the basis is canonical.

    Examples
    --------
    >>> from pitheorem.linalg import nullspace
    >>> [[int(x) for x in v] for v in nullspace([[1, 1, 0]])]
    [[-1, 1, 0], [0, 0, 1]]
    """
    if n_cols is None:
        n_cols = len(rows[0])
    if not rows:
        return [[Fraction(int(i == j)) for i in range(n_cols)] for j in range(n_cols)]
    a, pivots = rref(rows)
    free = [j for j in range(n_cols) if j not in pivots]
    basis = []
    for j in free:
        v = [Fraction(0)] * n_cols
        v[j] = Fraction(1)
        for i, p in enumerate(pivots):
            v[p] = -a[i][j]
        basis.append(v)
    return basis


def solve(rows: Sequence[Sequence], rhs: Sequence) -> list[Fraction] | None:
    """One exact solution x of A x = b, or None when there is none.

    Free variables are set to zero.

    Examples
    --------
    >>> from pitheorem.linalg import solve
    >>> solve([[1, 1], [0, 2]], [3, 2])
    [Fraction(2, 1), Fraction(1, 1)]
    >>> solve([[1, 1], [2, 2]], [1, 3]) is None
    True
    """
    n_cols = len(rows[0]) if rows else 0
    aug = [[*row, b] for row, b in zip(rows, rhs, strict=True)]
    a, pivots = rref(aug)
    if n_cols in pivots:
        return None
    x = [Fraction(0)] * n_cols
    for i, p in enumerate(pivots):
        x[p] = a[i][n_cols]
    return x


def primitive_integer_vector(v: Sequence) -> list[int]:
    """Scale a rational vector to coprime integers, first nonzero entry kept in sign.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.linalg import primitive_integer_vector
    >>> primitive_integer_vector([Fraction(1, 2), Fraction(-3, 4), 0])
    [2, -3, 0]
    """
    fr = [Fraction(x) for x in v]
    den = lcm(*(x.denominator for x in fr)) if fr else 1
    ints = [int(x * den) for x in fr]
    g = 0
    for x in ints:
        g = gcd(g, x)
    return [x // g for x in ints] if g else ints
