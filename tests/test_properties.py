"""Property tests over random dimension matrices (hypothesis)."""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations
from math import gcd

import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem.linalg import integer_rref, primitive_integer_vector, rank, solve

BASES = ("M", "L", "T", "Theta")

small_exponent = st.integers(-3, 3)
rational_exponent = st.fractions(min_value=-2, max_value=2, max_denominator=3)


@st.composite
def systems(draw, exponent=small_exponent, max_vars=9):
    k = draw(st.integers(1, len(BASES)))
    n = draw(st.integers(1, max_vars))
    columns = draw(st.lists(st.lists(exponent, min_size=k, max_size=k), min_size=n, max_size=n))
    return pt.System({f"x{j}": pt.Dimension(zip(BASES[:k], col, strict=True)) for j, col in enumerate(columns)})


def dimension_of_group(system: pt.System, group: pt.PiGroup) -> pt.Dimension:
    total = pt.Dimension.dimensionless()
    for name, power in group.exponents.items():
        total = total * system.dimension(name) ** power
    return total


def brute_force_bases(system: pt.System) -> list[tuple[str, ...]]:
    columns = [[system.dimension(v).exponent_of(b) for b in system.base_dimensions] for v in system.variables]
    found = []
    for subset in combinations(range(len(system.variables)), system.rank):
        sub = [columns[j] for j in subset]
        if not subset or rank(sub) == system.rank:
            found.append(tuple(system.variables[j] for j in subset))
    return found


def check_groups(system: pt.System):
    groups = system.pi_groups()
    assert len(groups) == len(system.variables) - system.rank == system.n_groups
    for group in groups:
        assert dimension_of_group(system, group).is_dimensionless
        assert group.exponents.get(group.variable, 0) > 0
        assert all(isinstance(p, int) for p in group.exponents.values())
    matrix = groups.exponent_matrix()
    assert not matrix or rank(matrix) == len(groups)  # independent
    return groups


@settings(max_examples=120, deadline=None)
@given(systems())
def test_integer_systems_groups(system):
    check_groups(system)


@settings(max_examples=80, deadline=None)
@given(systems(exponent=rational_exponent))
def test_rational_systems_groups(system):
    check_groups(system)


@settings(max_examples=120, deadline=None)
@given(systems(max_vars=10))
def test_bases_equal_brute_force(system):
    expected = brute_force_bases(system)
    assert system.bases() == expected
    assert system.count_bases() == len(expected)


@settings(max_examples=60, deadline=None)
@given(systems(exponent=rational_exponent, max_vars=8))
def test_rational_bases_equal_brute_force(system):
    assert system.bases() == brute_force_bases(system)


@settings(max_examples=60, deadline=None)
@given(systems(max_vars=8), st.data())
def test_exclude_and_require_filter_brute_force(system, data):
    names = system.variables
    exclude = data.draw(st.lists(st.sampled_from(names), unique=True, max_size=2))
    everything = brute_force_bases(system)
    assert system.bases(exclude=exclude) == [b for b in everything if not set(b) & set(exclude)]
    if everything:
        basis = data.draw(st.sampled_from(everything))
        require = basis[:1]
        assert system.bases(require=require) == [b for b in everything if set(require) <= set(b)]


@settings(max_examples=60, deadline=None)
@given(systems(max_vars=8), st.data())
def test_piset_from_any_two_bases_equivalent(system, data):
    bases = system.bases()
    first = data.draw(st.sampled_from(bases))
    second = data.draw(st.sampled_from(bases))
    assert system.pi_groups(repeating=first).equivalent(system.pi_groups(repeating=second))


@settings(max_examples=60, deadline=None)
@given(st.dictionaries(st.sampled_from(BASES), rational_exponent, max_size=4))
def test_dimension_string_round_trip(powers):
    dim = pt.Dimension(powers)
    assert pt.Dimension.parse(str(dim)) == dim
    assert all(isinstance(p, Fraction) and p != 0 for p in dim.exponents.values())


@settings(max_examples=60, deadline=None)
@given(systems(exponent=st.integers(-(10**6), 10**6), max_vars=8))
def test_huge_exponents_take_the_modular_path_and_stay_exact(system):
    # Hadamard bounds far beyond 2^53: the float path is refused, mod-p + exact fallback decide
    assert system.bases() == brute_force_bases(system)


@settings(max_examples=60, deadline=None)
@given(systems(max_vars=9))
def test_modular_path_equals_brute_force(system):
    import pitheorem.bases as bases_module

    saved = bases_module._EXACT_FLOAT
    bases_module._EXACT_FLOAT = 0.0  # force the modular path on ordinary systems
    try:
        assert system.bases() == brute_force_bases(system)
    finally:
        bases_module._EXACT_FLOAT = saved


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
