"""pitheorem.family: the minimal points of an affine family, against brute-force enumeration."""

from __future__ import annotations

from pitheorem import family as family_module


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
