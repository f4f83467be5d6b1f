"""TODO"""

from __future__ import annotations

from fractions import Fraction
from math import gcd

import numpy as np
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from pitheorem.linalg import integer_rref, primitive_integer_vector, solve
from tests.conftest import rational_exponent


def test_int_and_fraction_columns_share_integer_rows():
    from pitheorem.linalg import integer_rows

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
    assert all(not any(row) for row in a[len(pivots):])


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
