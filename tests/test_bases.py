"""pitheorem.bases: every independent column subset, in lexicographic order, exactly.

The oracles loop over every subset (itertools) and decide independence by
sympy's exact rank or by a determinant written out in Python integers:
nothing of the float, residue and Laplace paths under test.  The
enumeration through ``System.bases`` is checked here too; the property that
it equals brute force on any system is in test_properties.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations
from math import comb, prod
from unittest import mock

import numpy as np
import pytest
import sympy
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem import bases as bases_module
from pitheorem import system as system_module
from pitheorem.bases import count_independent_subsets, independent_chunks, independent_subsets
from tests.conftest import PRIMES, columns_of, oracle_bases, sympy_rank, systems


def det2(a, b, c, d):
    return a * d - b * c


@settings(max_examples=100, deadline=None)
@given(st.integers(1, 3), st.integers(1, 7), st.data())
def test_independent_subsets_of_candidates_with_required_columns_equal_brute_force(size, n_cols, data):
    rows = data.draw(
        st.lists(st.lists(st.integers(-3, 3), min_size=n_cols, max_size=n_cols), min_size=size, max_size=size)
    )
    assume(sympy.Matrix(rows).rank() == size)  # the functions take a matrix of full row rank
    roles = data.draw(
        st.lists(st.sampled_from(["candidate", "required", "left out"]), min_size=n_cols, max_size=n_cols)
    )
    candidates = [j for j, role in enumerate(roles) if role == "candidate"]
    required = [j for j, role in enumerate(roles) if role == "required"]
    assume(len(required) <= size)  # System refuses more required variables than the rank before this
    expected = []
    for extra in combinations(candidates, size - len(required)):
        subset = tuple(sorted((*required, *extra)))
        if sympy.Matrix([[row[j] for j in subset] for row in rows]).rank() == size:
            expected.append(subset)
    expected.sort()
    assert list(independent_subsets(rows, candidates, required, size)) == expected
    assert count_independent_subsets(rows, candidates, required, size) == len(expected)
    assert [tuple(c) for chunk in independent_chunks(rows, candidates, required, size) for c in chunk.tolist()] == (
        expected
    )


def test_determinant_two_to_the_64_is_not_zero():
    # was: rank 2 but no basis (float cancellation of 2^118-sized products); System refuses such exponents
    a, b, c = (2**27 + 1) * 2**32, (2**27 + 2) * 2**32, 2**59
    rows = [[a, c], [b, a]]
    assert det2(a, c, b, a) == 2**64
    assert sympy.Matrix(rows).det() == 2**64  # the oracle: exact, and nonzero
    assert count_independent_subsets(rows, [0, 1], [], 2) == 1
    assert list(independent_subsets(rows, [0, 1], [], 2)) == [(0, 1)]


@pytest.mark.parametrize("big", [3_100_000_000, 2**40, 2**62 + 1, 2**70, 10**30])
def test_entries_beyond_int64_safe_range(big):
    # was: (columns**2).sum() wrapped (math domain error) or OverflowError building int64 arrays
    rows = [[big, big + 1, 1], [1, 1, 0]]
    expected = [
        (i, j) for i, j in [(0, 1), (0, 2), (1, 2)] if det2(rows[0][i], rows[0][j], rows[1][i], rows[1][j]) != 0
    ]
    assert list(independent_subsets(rows, [0, 1, 2], [], 2)) == expected
    assert count_independent_subsets(rows, [0, 1, 2], [], 2) == len(expected)


def test_dependent_columns_with_huge_entries_stay_dependent():
    big = 2**80 + 7
    rows = [[big, 2 * big, 1], [3, 6, 1]]  # columns 0 and 1 are parallel
    assert list(independent_subsets(rows, [0, 1, 2], [], 2)) == [(0, 2), (1, 2)]


huge = st.integers(-(2**70), 2**70)
reciprocal_primes = st.sampled_from([Fraction(s, p) for p in PRIMES for s in (1, -1)] + [Fraction(0)])


@settings(max_examples=150, deadline=None)
@given(systems(), st.data())
def test_bases_equal_brute_force_in_order(system, data):
    exclude = tuple(data.draw(st.lists(st.sampled_from(system.variables), unique=True, max_size=2)))
    require = tuple(
        n for n in data.draw(st.lists(st.sampled_from(system.variables), unique=True, max_size=2)) if n not in exclude
    )
    try:
        got = system.bases(exclude=exclude, require=require)
    except (pt.DependentRepeatingSetError, pt.RepeatingCountError):
        assert sympy_rank([columns_of(system)[system.index(n)] for n in require]) < len(require)
        return
    expected = oracle_bases(system, exclude, require)
    assert got == expected
    assert list(got) == expected
    assert list(system.iter_bases(exclude=exclude, require=require)) == expected
    assert system.count_bases(exclude=exclude, require=require) == len(expected)


def brute_force_subsets(rows, size):
    """Every size-subset of columns, in lex order, whose submatrix sympy finds of full rank."""
    return [
        s
        for s in combinations(range(len(rows[0])), size)
        if sympy.Matrix([[row[j] for j in s] for row in rows]).rank() == size
    ]


@pytest.mark.parametrize(
    ("entry", "max_cols"),
    [
        (huge, 6),  # entries far beyond 2^53 and int64: the float path must step aside, residues and exact rank decide
        (st.integers(-(10**6), 10**6), 8),
    ],
    ids=["huge", "millions"],
)
@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_subsets_exact_with_extreme_entries(entry, max_cols, data):
    # a System keeps its exponents within 1000 (pitheorem.exact's limits), so entries this large reach the
    # enumeration only as integer rows: after clearing denominators such as 1/p, or through this function
    size = data.draw(st.integers(1, 3))
    n_cols = data.draw(st.integers(size, max_cols))
    rows = data.draw(st.lists(st.lists(entry, min_size=n_cols, max_size=n_cols), min_size=size, max_size=size))
    assume(sympy.Matrix(rows).rank() == size)
    expected = brute_force_subsets(rows, size)
    assert list(independent_subsets(rows, range(n_cols), [], size)) == expected
    assert count_independent_subsets(rows, range(n_cols), [], size) == len(expected)


@settings(max_examples=60, deadline=None)
@given(systems(exponent=reciprocal_primes, max_vars=7, max_bases=3))
def test_bases_exact_with_reciprocal_prime_exponents(system):
    expected = oracle_bases(system)
    assert system.bases() == expected
    assert system.count_bases() == len(expected)


@settings(max_examples=40, deadline=None)
@given(systems(max_vars=9), st.integers(1, 5))
def test_small_chunks_keep_answers_and_order(system, chunk):
    # the depth-first descent in chunks of `chunk` rows visits subsets in the same order
    with mock.patch.object(bases_module, "_CHUNK", chunk):
        assert system.bases() == oracle_bases(system)
        assert system.count_bases() == len(oracle_bases(system))
    # iter_bases names a chunk's rows a few at a time: every row once, in order, across the slices
    with mock.patch.object(system_module, "_ROWS_AT_A_TIME", chunk):
        assert list(system.iter_bases()) == oracle_bases(system)


@settings(max_examples=40, deadline=None)
@given(systems(max_vars=8))
def test_residue_path_equals_float_path(system):
    expected = oracle_bases(system)
    with mock.patch.object(bases_module, "float_is_exact", return_value=False):
        assert system.bases() == expected
        assert system.count_bases() == len(expected)


def test_hadamard_bound_is_computed_in_python_integers():
    big = [[2**62, 1], [1, 2**62]]
    assert bases_module.hadamard_squared(big, 2) == (2**124 + 1) ** 2
    assert not bases_module.float_is_exact(big, 2)
    assert bases_module.float_is_exact([[3, 0], [0, 4]], 2)
    assert all(sympy.isprime(p) and p < 2**31 for p in bases_module._PRIMES)


def test_reciprocal_prime_exponents():
    variables = {
        f"x{p}": {"L": Fraction(1, p), "T": Fraction(1, q)} for p, q in zip(PRIMES, (*PRIMES[1:], 2), strict=True)
    }
    system = pt.System({**variables, "m": "M"})
    assert system.bases() == oracle_bases(system)
    assert system.count_bases() == len(oracle_bases(system))


def test_rank_zero_system_has_the_empty_basis():
    system = pt.System({"a": "1", "b": "1"})
    assert system.bases() == [()]
    assert list(system.bases()) == [()]
    assert system.count_bases() == 1
    assert system.bases().indices.shape == (1, 0)


@pytest.mark.parametrize("m", range(7))
@pytest.mark.parametrize("k", range(8))
def test_lex_combinations_are_itertools_combinations(m, k):
    got = bases_module.lex_combinations(m, k)
    expected = [list(c) for c in combinations(range(m), k)]
    assert got.shape == (len(expected), k)
    assert got.tolist() == expected


@settings(max_examples=60, deadline=None)
@given(
    systems(
        exponent=st.sampled_from([Fraction(s * n, p) for p in (997, 991, 983) for n in (1, 500, 999) for s in (1, -1)]),
        max_vars=8,
    )
)
def test_exponents_at_the_limits_take_the_modular_path_and_stay_exact(system):
    # exponents n/p with primes near 1000: integer rows up to about 10^9, and with three or four base
    # dimensions Hadamard bounds beyond 2^53, where the float path steps aside for the residues
    assert system.bases() == oracle_bases(system)


@settings(max_examples=60, deadline=None)
@given(systems(max_vars=9))
def test_modular_path_equals_brute_force(system):
    import pitheorem.bases as bases_module

    saved = bases_module._EXACT_FLOAT
    bases_module._EXACT_FLOAT = 0.0  # force the modular path on ordinary systems
    try:
        assert system.bases() == oracle_bases(system)
    finally:
        bases_module._EXACT_FLOAT = saved


# -- every enumeration path against brute force (issue 23): the chunked candidate lists, entries beyond
# float64's exact range, minors that are multiples of the residue primes, and the exact fallback.
# Oracles: itertools.combinations, and determinants of small integer matrices (numpy's, rounded: exact
# for entries this small) or sympy's, never the code under test.


def _small_independent(small, k):
    """Lex-ordered k-subsets of the columns of a small integer matrix with nonzero determinant."""
    small = np.array(small, dtype=float)
    subsets = list(combinations(range(small.shape[1]), k))
    dets = np.round(np.linalg.det(np.stack([small[:, list(s)] for s in subsets])))
    return [s for s, d in zip(subsets, dets, strict=True) if d != 0]


@pytest.mark.parametrize(("m", "k", "limit"), [(7, 3, 4), (9, 4, 10), (6, 6, 1), (8, 1, 3), (10, 5, 100), (5, 0, 1)])
def test_chunked_lex_combinations_are_itertools_combinations(m, k, limit):
    chunks = list(bases_module._lex_combination_chunks(m, k, limit))
    assert all(len(c) <= max(limit, 1) or k == 0 for c in chunks)
    assert [tuple(row) for c in chunks for row in c.tolist()] == list(combinations(range(m), k))


def test_more_than_65536_candidates_on_the_residue_path_equal_brute_force():
    # 40 columns, rank 4: 91,390 candidate subsets, listed in chunks; each column times a factor near 2^40
    # (which keeps independence) puts the entries beyond float64's exact range, so residues decide
    rng = np.random.default_rng(23)
    small = rng.integers(-2, 3, size=(4, 40))
    small[:, 0] = [1, 0, 0, 0]  # no zero column, full row rank
    small[:, (small == 0).all(axis=0)] = 1
    assert comb(40, 4) > 1 << 16
    rows = [[int(x) * (2**40 + j) for j, x in enumerate(row)] for row in small.tolist()]
    assert not bases_module.float_is_exact(rows, 4)
    expected = _small_independent(small, 4)
    assert list(independent_subsets(rows, range(40), [], 4)) == expected
    assert count_independent_subsets(rows, range(40), [], 4) == len(expected)


def test_a_determinant_float64_cannot_hold_is_decided_exactly():
    # det [[2^30+1, 2^30], [2^30, 2^30-1]] = -1, but in float64 (2^30+1)(2^30-1) rounds to 2^60: a
    # weakened guard ((k/biggest)^2, a bound of 2^159, the smallest norms instead of the largest ones,
    # which the two unit columns make tiny) would take the float path and lose that basis
    # (a zero column, never in a basis, must not shrink the bound to zero: it takes the k largest norms)
    a = 2**30
    rows = [[1, 0, a + 1, a, 0], [0, 1, a, a - 1, 0]]
    assert sympy.Matrix([[a + 1, a], [a, a - 1]]).det() == -1
    assert float(a + 1) * float(a - 1) - float(a) * float(a) == 0  # what float64 would say
    assert not bases_module.float_is_exact(rows, 2)
    assert list(independent_subsets(rows, range(5), [], 2)) == list(combinations(range(4), 2))
    assert count_independent_subsets(rows, range(5), [], 2) == 6


def test_a_minor_that_is_a_multiple_of_the_first_residue_prime_is_not_zero():
    # the row L^(1/p), L over integers: [1, p]; y's 1x1 minor is p itself, zero modulo the first prime,
    # so a second prime must decide: the Hadamard bound 2p + 2 exceeds p, which a shrunken bound would not
    p = bases_module._PRIMES[0]
    system = pt.System({"x": f"L^(1/{p})", "y": "L"})
    assert system.bases() == [("x",), ("y",)]
    assert system.count_bases() == 2


@pytest.mark.parametrize("primes", [1, 2, 3, 5])
def test_minors_that_are_multiples_of_several_residue_primes(primes):
    # every entry a multiple of the first `primes` residue primes: every minor vanishes modulo them,
    # and only the primes after them (as many as the bound asks for) can tell zero from nonzero
    # (and a zero column, which must not shrink the Hadamard bound to zero)
    factor = prod(bases_module._PRIMES[:primes])
    small = [[1, 2, 0, 1, 3, 0], [0, 0, 1, 1, -1, 0]]
    rows = [[x * factor for x in row] for row in small]
    expected = _small_independent(small, 2)
    assert expected != list(combinations(range(5), 2))  # (0, 1) is dependent: the test has both kinds
    assert list(independent_subsets(rows, range(6), [], 2)) == expected
    assert count_independent_subsets(rows, range(6), [], 2) == len(expected)
    # with a required column, on the same residue path
    with_0 = [s for s in expected if 0 in s]
    assert list(independent_subsets(rows, range(1, 6), [0], 2)) == with_0
    assert count_independent_subsets(rows, range(1, 6), [0], 2) == len(with_0)


def test_column_indices_beyond_255_are_kept():
    # subsets are stored in the smallest integer type that holds every column index: 256 needs 16 bits
    rows = [[1] * 257]
    assert list(independent_subsets(rows, range(257), [], 1))[-3:] == [(254,), (255,), (256,)]
    assert list(independent_subsets([[1] * 256], range(256), [], 1))[-1] == (255,)


def test_the_exact_fallback_decides_when_every_residue_prime_divides_every_minor():
    # entries multiples of the product of all eight primes: every minor is zero modulo each, and the
    # Hadamard bound exceeds their product, so exact rank decides each subset
    factor = prod(bases_module._PRIMES)
    small = [[1, 2, 0, 1], [0, 0, 1, 1], [1, 2, 1, 0]]
    rows = [[x * factor for x in row] for row in small]
    expected = [s for s in combinations(range(4), 3) if sympy.Matrix([[row[j] for j in s] for row in small]).det() != 0]
    assert 0 < len(expected) < 4
    with mock.patch.object(bases_module, "rank", wraps=bases_module.rank) as exact_rank:
        assert list(independent_subsets(rows, range(4), [], 3)) == expected
    assert exact_rank.call_count >= 4  # every subset went to the exact fallback


def test_dependent_required_columns_give_no_subset():
    # System refuses such a request before; the enumeration itself also yields nothing
    rows = [[1, 2, 0], [0, 0, 1]]
    assert list(independent_subsets(rows, [2], [0, 1], 2)) == []
    assert list(independent_subsets([[1, 2, 0, 1], [0, 0, 1, 1], [1, 2, 0, 0]], [2, 3], [0, 1], 3)) == []
