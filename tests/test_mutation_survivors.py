"""Tests that kill the five mutations which once survived the whole suite (issue 12).

1. the certificate's fewest-variables choice (``min`` -> ``max``) in search;
2. ``PiSet.equivalent`` without its joint-rank check;
3. the dimension parser reading ``--2`` as 2 (see tests/test_edges.py::test_double_sign_is_a_syntax_error);
4. ``solve_ivp`` tolerances not scaled per state in verify_similarity;
5. ``SymmetryReport.contains_units`` always True
   (see tests/test_equation_functions.py::test_contains_units_is_false_for_inconsistent_equations).
"""

from __future__ import annotations

from itertools import product

import pytest

import pitheorem as pt


def support(group) -> set[str]:
    return {n for n, p in group.exponents.items() if p}


@pytest.mark.parametrize(("variables", "expected"), [
    # four lengths: every pair is a certificate; the first pair in system order is chosen
    ({"a": "L", "b": "L", "c": "L", "d": "L"}, {"a", "b"}),
    # a/d (two variables) beats a*b/c (three)
    ({"c": "L M", "b": "M", "a": "L", "d": "L"}, {"a", "d"}),
    ({"d": "L", "c": "L M", "b": "M", "a": "L"}, {"a", "d"}),
])
def test_certificate_has_fewest_variables(variables, expected):
    res = pt.search(pt.System(variables), scale={"a": 1}, fixed=tuple(n for n in variables if n != "a"))
    assert not res.feasible
    assert support(res.certificate) == expected


def test_certificate_is_as_small_as_any_changing_product():
    # oracle: brute force over small integer exponent vectors of the fixed and scaled variables
    names = ("m", "l", "g", "k", "t")
    dims = {"m": (1, 0, 0), "l": (0, 1, 0), "g": (0, 1, -2), "k": (1, 2, -2), "t": (0, 0, 1)}
    system = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k": "M L^2 T^-2", "t": "T"})
    res = pt.search(system, scale={"g": 1}, fixed=("m", "k", "t"))
    smallest = min(
        sum(1 for e in vec if e)
        for vec in product(range(-2, 3), repeat=len(names))
        if vec[names.index("g")] != 0 and vec[names.index("l")] == 0
        and all(sum(e * dims[n][i] for e, n in zip(vec, names, strict=True)) == 0 for i in range(3))
    )
    assert len(support(res.certificate)) == smallest == 4  # g^2 t^2 m / k, as in the paper


def test_equivalent_needs_the_same_span_not_just_the_same_rank():
    one = pt.System({"a": "L", "b": "L", "c": "T"}).pi_groups()  # b/a
    other = pt.System({"a": "L", "b": "T", "c": "T"}).pi_groups()  # c/b
    assert len(one) == len(other) == 1
    assert not one.equivalent(other)
    assert not other.equivalent(one)
    assert one.equivalent(pt.System({"a": "L", "b": "L", "c": "T"}).pi_groups(repeating=("b", "c")))


@pytest.mark.parametrize("s", [1e-6, 1e-9])
def test_tolerances_scale_with_each_state(s):
    # with one atol for every state, the shrunken positions are integrated to a tolerance
    # far coarser than theirs, and the mapped-back run drifts (about 2e-6 at s = 1e-6)
    model = pt.models.spring_mass_damper()
    sc = pt.Scaling.from_unit_change(model.system, {"L": 1})
    rep = pt.verify_similarity(model, sc, s=s, t_final=5)
    assert rep.max_deviation < 1e-9
