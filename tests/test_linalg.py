"""pitheorem.linalg: exact Gauss-Jordan kernels, each against sympy's exact matrices.

sympy's ``rref``, ``rank``, ``nullspace`` and ``gauss_jordan_solve`` are the
oracles: they share no code with pitheorem's fraction-free elimination.
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd

import numpy as np
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from pitheorem.linalg import (
    integer_rows,
    integer_rref,
    nullspace,
    primitive_integer_vector,
    rank,
    row_space_basis,
    rref,
    solve,
)
from tests.conftest import rational_exponent


@st.composite
def matrices(draw, max_rows=4, max_cols=5):
    """Rows of small Fractions (zeros likely, so that ranks fall short)."""
    n_cols = draw(st.integers(1, max_cols))
    entry = st.one_of(st.just(Fraction(0)), rational_exponent)
    return draw(st.lists(st.lists(entry, min_size=n_cols, max_size=n_cols), min_size=1, max_size=max_rows))


def as_sympy(rows) -> sympy.Matrix:
    return sympy.Matrix([[sympy.Rational(x.numerator, x.denominator) for x in row] for row in rows])


def as_fractions(matrix: sympy.Matrix) -> list[list[Fraction]]:
    return [[Fraction(int(x.p), int(x.q)) for x in matrix.row(i)] for i in range(matrix.rows)]


@settings(max_examples=80, deadline=None)
@given(matrices())
def test_rref_rank_and_row_space_are_sympys(rows):
    want, want_pivots = as_sympy(rows).rref()
    got, pivots = rref(rows)
    assert pivots == want_pivots
    assert got == as_fractions(want)
    assert all(type(x) is Fraction for row in got for x in row)
    assert rank(rows) == as_sympy(rows).rank() == len(pivots)
    assert row_space_basis(rows) == as_fractions(want)[: len(want_pivots)]


@settings(max_examples=80, deadline=None)
@given(matrices())
def test_nullspace_is_sympys_canonical_basis(rows):
    # sympy's basis has the same canonical form: 1 at its free column, 0 at the other free columns
    want = [as_fractions(v.T)[0] for v in as_sympy(rows).nullspace()]
    got = nullspace(rows)
    assert got == want
    assert len(got) == len(rows[0]) - rank(rows)


def test_nullspace_of_no_rows_is_the_identity():
    assert nullspace([], n_cols=3) == [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    assert nullspace([[0, 0]]) == [[1, 0], [0, 1]]
    assert nullspace([[1, 2], [3, 4]]) == []


@settings(max_examples=80, deadline=None)
@given(matrices(), st.data())
def test_solve_is_sympys_solution_with_the_free_unknowns_at_zero(rows, data):
    rhs = data.draw(st.lists(rational_exponent, min_size=len(rows), max_size=len(rows)))
    b = as_sympy([[x] for x in rhs])
    try:
        solution, params = as_sympy(rows).gauss_jordan_solve(b)
    except ValueError:  # sympy: no solution
        assert solve(rows, rhs) is None
        return
    want = as_fractions(solution.subs(dict.fromkeys(params, 0)).T)[0]
    assert solve(rows, rhs) == want


def test_int_and_fraction_columns_share_integer_rows():
    assert integer_rows([[Fraction(1, 2), 3, True], [np.int64(2), Fraction(4), 0]]) == [[1, 6, 2], [2, 4, 0]]


@settings(max_examples=150, deadline=None)
@given(st.lists(st.lists(st.integers(-4, 4), min_size=4, max_size=4), min_size=1, max_size=4))
def test_integer_rref_is_sympys_rref_with_positive_coprime_pivots(rows):
    a, pivots = integer_rref(rows)
    want, want_pivots = sympy.Matrix(rows).rref()
    assert pivots == want_pivots
    for i, p in enumerate(pivots):
        assert a[i][p] > 0
        assert gcd(*a[i]) == 1
        assert [sympy.Rational(x, a[i][p]) for x in a[i]] == list(want.row(i))
    assert all(not any(row) for row in a[len(pivots) :])


def test_integer_rref_of_unit_and_negative_pivots():
    assert integer_rref([[1, 2]]) == ([[1, 2]], (0,))
    assert integer_rref([[-1, 2]]) == ([[1, -2]], (0,))
    assert integer_rref([[0, -3, 6], [2, 0, 1]]) == ([[2, 0, 1], [0, 1, -2]], (0, 1))


def test_solve_with_no_equations_has_no_unknowns():
    assert solve([], []) == []


@settings(max_examples=100, deadline=None)
@given(st.lists(rational_exponent, min_size=1, max_size=5))
def test_primitive_integer_vector_is_coprime_and_proportional(v):
    got = primitive_integer_vector(v)
    assert all(isinstance(x, int) for x in got)
    if not any(v):
        assert got == [0] * len(v)
        return
    assert gcd(*got) == 1
    # got = c v for one c > 0
    c = next(Fraction(g) / x for g, x in zip(got, v, strict=True) if x)
    assert c > 0
    assert all(Fraction(g) == c * x for g, x in zip(got, v, strict=True))
