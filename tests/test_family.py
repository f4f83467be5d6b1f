"""pitheorem.family: the minimal points of an affine family, against brute-force enumeration."""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pitheorem import family as family_module
from tests.conftest import qq_matrix


def brute_force_minimal_points(a0, dirs, free):
    """Every distinct point of a0 + span(dirs) vanishing on len(dirs) free positions of independent columns,
    fewest nonzero entries first, then by their positions; each solved by sympy."""
    d = len(dirs)
    points = set()
    for subset in combinations(free, d):
        minor = qq_matrix([[v[j] for j in subset] for v in dirs])  # d x d
        if minor.det() == 0:
            continue
        # sum_i c_i v_i[j] = -a0[j] on the subset
        solved = minor.transpose().lu_solve(qq_matrix([[-a0[j]] for j in subset]))
        coords = [Fraction(int(c.numerator), int(c.denominator)) for c in (solved[i, 0].element for i in range(d))]
        points.add(
            tuple(Fraction(a) + sum(c * v[j] for c, v in zip(coords, dirs, strict=True)) for j, a in enumerate(a0))
        )
    support = {p: [j for j, x in enumerate(p) if x] for p in points}
    return sorted(points, key=lambda p: (len(support[p]), support[p]))


@settings(max_examples=150, deadline=None)
@given(st.integers(2, 6), st.integers(1, 2), st.data())
def test_minimal_points_equal_brute_force_in_order(n, d, data):
    free = sorted(data.draw(st.sets(st.integers(0, n - 1), min_size=1, max_size=n)))
    constrained = [j for j in range(n) if j not in free]
    a0 = data.draw(st.lists(st.integers(-3, 3), min_size=n, max_size=n))
    # the directions of a family never move a prescribed or fixed position
    dirs = [
        [0 if j in constrained else x for j, x in enumerate(v)]
        for v in data.draw(st.lists(st.lists(st.integers(-3, 3), min_size=n, max_size=n), min_size=d, max_size=d))
    ]
    keys, _weights = family_module.minimal_points(a0, dirs, free, constrained)
    got = [tuple(Fraction(p, key[0]) for p in key[1:]) for key in keys.tolist()]
    assert got == brute_force_minimal_points(a0, dirs, free)
    assert all(key[0] > 0 for key in keys.tolist())


def test_minimal_points_can_be_indexed_before_they_are_iterated():
    # a0 = (1, 1, 0), one direction (0, 1, -1), free positions 1 and 2: the minimal points are
    # a0 (zero at 2, coordinate 0) and a0 - direction (zero at 1, coordinate -1), by hand
    keys, weights = family_module.minimal_points([1, 1, 0], [[0, 1, -1]], [1, 2], [0])
    expected = [((1, 1, 0), (0,)), ((1, 0, 1), (-1,))]
    assert family_module.MinimalPoints(keys, weights, 1, (0,), [[1]])[1] == expected[1]
    assert family_module.MinimalPoints(keys, weights, 1, (0,), [[1]])[-2] == expected[0]
    assert family_module.MinimalPoints(keys, weights, 1, (0,), [[1]])[0:2] == expected
    points = family_module.MinimalPoints(keys, weights, 1, (0,), [[1]])
    assert list(points) == expected
    assert points[1] == expected[1]


def test_minimal_points_of_directions_dependent_on_the_free_variables():
    # both directions vanish off position 1: no two free positions carry an independent minor,
    # so there is no minimal point; the arrays keep their documented widths (n + 1 and d + 1)
    keys, weights = family_module.minimal_points([1, 1, 0, 0], [[0, 1, 0, 0], [0, 2, 0, 0]], [1, 2, 3], [0])
    assert keys.shape == (0, 5)
    assert weights.shape == (0, 3)


def test_no_minimal_point_keeps_integer_arrays():
    # no two free positions with an independent minor, and no free position at all: no point either way
    for a0, dirs, free, constrained in (
        ([1, 1, 0, 0], [[0, 1, 0, 0], [0, 2, 0, 0]], [1, 2, 3], [0]),
        ([1, 1], [[1, -1]], [], []),
    ):
        keys, weights = family_module.minimal_points(a0, dirs, free, constrained)
        assert keys.shape == (0, len(a0) + 1)
        assert weights.shape == (0, len(dirs) + 1)
        assert keys.dtype == weights.dtype == np.int64


def test_a_batch_without_independent_subsets_does_not_end_the_search():
    # 50 free positions: the descent takes its prefixes in chunks of 2048 // 50 = 40, so the pairs
    # starting at positions 0 to 39 come in a batch of their own.  The directions vanish there, so
    # none of those pairs is independent; the points come from the pairs among positions 40 to 49
    n = 50
    v1 = [0] * 40 + [1] * 10
    v2 = [0] * 40 + list(range(1, 11))
    a0 = [1] * 40 + [(-1) ** j * (j + 2) for j in range(10)]
    keys, _weights = family_module.minimal_points(a0, [v1, v2], list(range(n)), [])
    got = [tuple(Fraction(p, key[0]) for p in key[1:]) for key in keys.tolist()]
    expected = brute_force_minimal_points(a0, [v1, v2], list(range(40, n)))
    assert len(expected) > 1
    assert got == expected


@settings(max_examples=60, deadline=None)
@given(st.integers(3, 6), st.integers(1, 2), st.data())
def test_merging_repeats_along_the_way_keeps_the_answer(n, d, data):
    # with the merge threshold lowered from 65,536 points to 2, the repeats are merged after nearly
    # every batch: the answer is still brute force's
    a0 = data.draw(st.lists(st.integers(-3, 3), min_size=n, max_size=n))
    dirs = data.draw(st.lists(st.lists(st.integers(-3, 3), min_size=n, max_size=n), min_size=d, max_size=d))
    free = list(range(n))
    saved = family_module._MERGE_EVERY
    family_module._MERGE_EVERY = 2
    try:
        keys, _weights = family_module.minimal_points(a0, dirs, free, [])
    finally:
        family_module._MERGE_EVERY = saved
    got = [tuple(Fraction(p, key[0]) for p in key[1:]) for key in keys.tolist()]
    assert got == brute_force_minimal_points(a0, dirs, free)


def test_a_point_reached_from_two_batches_is_listed_once():
    # 50 free positions, prefixes in chunks of 40 (as above): a0 itself vanishes on positions 5, 41
    # and 45, so the pairs (5, 41) and (5, 45) of the first batch and (41, 45) of the second all give it
    n = 50
    v1 = [(7 * j) % 11 - 5 for j in range(n)]
    v2 = [(j * j) % 13 - 6 for j in range(n)]
    a0 = [0 if j in (5, 41, 45) else (j % 5) - 2 or 3 for j in range(n)]
    keys, _weights = family_module.minimal_points(a0, [v1, v2], list(range(n)), [])
    got = [tuple(Fraction(p, key[0]) for p in key[1:]) for key in keys.tolist()]
    expected = brute_force_minimal_points(a0, [v1, v2], list(range(n)))
    assert tuple(Fraction(x) for x in a0) in expected
    assert got == expected


def test_a_direction_that_moves_a_constrained_position_fails_the_confirmation():
    # the integer confirmation checks that every point keeps a0 on the constrained positions; a
    # direction moving position 2 breaks that, and the answer is left to the exact code (None)
    assert family_module.minimal_points([1, 1, 1], [[1, -1, 1]], [0, 1], [2]) is None
    keys, _weights = family_module.minimal_points([1, 1, 1], [[1, -1, 0]], [0, 1], [2])
    # a0 + v (support 0, 2) before a0 - v (support 1, 2), by hand
    assert keys.tolist() == [[1, 2, 0, 1], [1, 0, 2, 1]]
