"""pitheorem.family: the minimal points of an affine family, against brute-force enumeration."""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations

import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from pitheorem import family as family_module


def brute_force_minimal_points(a0, dirs, free):
    """Every distinct point of a0 + span(dirs) vanishing on len(dirs) free positions of independent columns,
    fewest nonzero entries first, then by their positions; each solved by sympy."""
    d = len(dirs)
    points = set()
    for subset in combinations(free, d):
        minor = sympy.Matrix([[v[j] for j in subset] for v in dirs])  # d x d
        if minor.det() == 0:
            continue
        coords = minor.T.solve(sympy.Matrix([-a0[j] for j in subset]))  # sum_i c_i v_i[j] = -a0[j] on the subset
        points.add(tuple(Fraction(a) + sum(Fraction(int(c.p), int(c.q)) * v[j] for c, v in zip(coords, dirs,
                                                                                               strict=True))
                         for j, a in enumerate(a0)))
    support = {p: [j for j, x in enumerate(p) if x] for p in points}
    return sorted(points, key=lambda p: (len(support[p]), support[p]))


@settings(max_examples=150, deadline=None)
@given(st.integers(2, 6), st.integers(1, 2), st.data())
def test_minimal_points_equal_brute_force_in_order(n, d, data):
    free = sorted(data.draw(st.sets(st.integers(0, n - 1), min_size=1, max_size=n)))
    constrained = [j for j in range(n) if j not in free]
    a0 = data.draw(st.lists(st.integers(-3, 3), min_size=n, max_size=n))
    # the directions of a family never move a prescribed or fixed position
    dirs = [[0 if j in constrained else x for j, x in enumerate(v)]
            for v in data.draw(st.lists(st.lists(st.integers(-3, 3), min_size=n, max_size=n), min_size=d, max_size=d))]
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
