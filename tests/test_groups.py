"""The paper's Pi groups come out of the code (white paper, Sections 2 and 4)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy

import pitheorem as pt


def group_of(pi_set: pt.PiSet, name: str) -> dict[str, int]:
    return pi_set[name].exponents


def same_up_to_reciprocal(got: dict[str, int], want: dict[str, int]) -> bool:
    return got == want or got == {k: -v for k, v in want.items()}


def test_rod_groups_match_paper(rod):
    groups = rod.pi_groups(repeating=("m", "l", "k_theta"))
    assert len(groups) == rod.n_groups == 6
    # Pi_g = g m l / k_theta ; Pi_c = c^2 / (m l^2 k) ; Pi_t = t^2 k / (m l^2)
    assert same_up_to_reciprocal(group_of(groups, "g"), {"g": 1, "m": 1, "l": 1, "k_theta": -1})
    assert same_up_to_reciprocal(group_of(groups, "c_theta"), {"c_theta": 2, "m": -1, "l": -2, "k_theta": -1})
    assert same_up_to_reciprocal(group_of(groups, "t"), {"t": 2, "k_theta": 1, "m": -1, "l": -2})
    # the dimensionless rest angle is a group of its own
    assert group_of(groups, "theta_r") == {"theta_r": 1}
    # force and torque, the paper's "invisible" terms, have groups too
    assert group_of(groups, "tau") == {"tau": 1, "k_theta": -1}
    assert group_of(groups, "F") == {"F": 1, "l": 1, "k_theta": -1}


SUPERBALL_PAPER = {
    # Section 4, repeaters (m, l, k); Pi_v corrected: the paper prints a stray "d"
    "x_r": {"x_r": 1, "l": -1},
    "g": {"g": 1, "m": 1, "k": -1, "l": -1},
    "c": {"k": 1, "m": 1, "c": -2},
    "F": {"F": 1, "k": -1, "l": -1},
    "t": {"t": 2, "k": 1, "m": -1},
    "G": {"G": 1, "l": 1, "k": -1},
    "E": {"E": 1, "l": 1, "k": -1},
    "v": {"v": 2, "m": 1, "k": -1, "l": -2},
    "rho": {"rho": 1, "l": 3, "m": -1},
}


@pytest.mark.parametrize("variable", sorted(SUPERBALL_PAPER))
def test_superball_groups_match_paper(superball, variable):
    groups = superball.pi_groups(repeating=("m", "l", "k"))
    assert same_up_to_reciprocal(group_of(groups, variable), SUPERBALL_PAPER[variable])


def test_group_canonical_form_positive_on_own_variable(superball):
    for group in superball.pi_groups(repeating=("m", "l", "k")):
        assert group.exponents[group.variable] > 0


def test_group_latex_and_evaluate(rod):  # its text and notebook display: tests/test_formatting.py
    pi_g = rod.pi_groups(repeating=("m", "l", "k_theta"))["g"]
    assert pi_g.latex == r"\frac{g l m}{k_{\theta}}"
    values = {"m": Fraction(3, 2), "l": 2, "g": Fraction(981, 100), "k_theta": 100}
    exact = pi_g.evaluate(values)
    assert exact == Fraction(2943, 10000)
    assert type(exact) is Fraction
    inexact = pi_g.evaluate({k: float(v) for k, v in values.items()})
    assert inexact == pytest.approx(0.2943)
    assert type(inexact) is float
    assert eval(repr(pi_g), {"PiGroup": pt.PiGroup}) == pi_g


def test_equivalent_across_bases(rod):
    first = rod.pi_groups(repeating=("m", "l", "k_theta"))
    for basis in rod.bases():
        assert first.equivalent(rod.pi_groups(repeating=basis))


def test_not_equivalent_when_groups_differ():
    a = pt.System({"x": "L", "y": "L", "z": "L"})
    groups = a.pi_groups(repeating=("x",))
    partial = pt.PiSet(groups[:1], a.variables)
    assert not groups.equivalent(partial)


def test_constructor_takes_integer_exponents_as_given():
    group = pt.PiGroup({"t": 2, "l": Fraction(-4, 2), "g": 0, "m": np.int64(1)}, "t")
    assert list(group.exponents.items()) == [("t", 2), ("l", -2), ("m", 1)]  # zeros dropped, order kept
    assert all(type(p) is int for p in group.exponents.values())
    assert pt.PiGroup((("t", 2), ("l", -1))) == pt.PiGroup({"t": 2, "l": -1})  # pairs or a mapping
    with pytest.raises(pt.InvalidRequestError, match="from_exponents") as info:
        pt.PiGroup({"t": Fraction(1, 2)})
    assert info.value.culprit == Fraction(1, 2)
    with pytest.raises(pt.NumberError):
        pt.PiGroup({"t": "two"})


def test_from_exponents_puts_zero_for_variables_only_in_the_order():
    group = pt.PiGroup.from_exponents({"a": 1, "b": -1}, order=("b", "c", "a"))
    # order b, c, a: the first nonzero (b) is made positive; c is absent, not an exponent
    assert list(group.exponents.items()) == [("b", 1), ("a", -1)]


def test_groups_are_immutable_and_hashable(rod):
    import dataclasses

    groups = rod.pi_groups()
    with pytest.raises(dataclasses.FrozenInstanceError):
        groups[0].variable = "x"
    assert len({groups, rod.pi_groups()}) == 1
    assert len({*groups}) == len(groups)


def test_sets_with_different_groups_are_not_equal():
    s = pt.System({"a": "L", "b": "L", "c": "L"})
    one, other = s.pi_groups(repeating=("a",)), s.pi_groups(repeating=("c",))
    assert one.equivalent(other)
    assert one != other  # equivalent, but not the same groups
    assert one == s.pi_groups(repeating=("a",))
    assert one != list(one)


def test_empty_sets_are_equivalent():
    # a system of independent variables has no groups; the empty set spans the zero space
    empty = pt.System({"l": "L", "t": "T"}).pi_groups()
    assert len(empty) == 0
    assert empty.equivalent(pt.System({"l": "L", "t": "T"}).pi_groups(repeating=("l", "t")))
    assert not empty.equivalent(pt.PiSet([pt.PiGroup((("l", 1),))], ("l", "t")))


def test_is_power_of_needs_the_same_variables():
    x, xy = pt.PiGroup((("x", 1),)), pt.PiGroup((("x", 1), ("y", 1)))
    assert not x.is_power_of(xy)
    assert not xy.is_power_of(x)
    assert xy.is_power_of(pt.PiGroup((("x", -2), ("y", -2))))


def test_group_symbols_are_positive(rod):
    group = rod.pi_groups()[0]
    assert all(symbol.is_positive for symbol in group.expr.free_symbols)
    assert sympy.sqrt(group.expr**2) == group.expr  # true only for positive symbols


def test_equivalent_needs_the_same_span_not_just_the_same_rank():
    one = pt.System({"a": "L", "b": "L", "c": "T"}).pi_groups()  # b/a
    other = pt.System({"a": "L", "b": "T", "c": "T"}).pi_groups()  # c/b
    assert len(one) == len(other) == 1
    assert not one.equivalent(other)
    assert not other.equivalent(one)
    assert one.equivalent(pt.System({"a": "L", "b": "L", "c": "T"}).pi_groups(repeating=("b", "c")))


def test_bad_evaluate_and_group_lookup(rod):
    pi_g = rod.pi_groups(repeating=("m", "l", "k_theta"))["g"]
    with pytest.raises(pt.InvalidRequestError, match="'k_theta'"):
        pi_g.evaluate({"m": 1, "l": 1, "g": 1})
    with pytest.raises(pt.InvalidRequestError, match="'l' = 0"):
        rod.pi_groups(repeating=("m", "l", "k_theta"))["t"].evaluate({"l": 0, "m": 1, "t": 1, "k_theta": 1})
    with pytest.raises(pt.InvalidRequestError, match="'zzz'"):
        rod.pi_groups()["zzz"]


# -- evaluate beyond floating point (issue 23)


def test_evaluate_names_a_float_value_beyond_floating_point():
    with pytest.raises(pt.LimitError, match="beyond the range of floating point"):
        pt.PiGroup({"x": 1, "y": -2}).evaluate({"x": 1.0, "y": 1e-200})


def test_evaluate_names_a_sympy_float_beyond_doubles():
    with pytest.raises(pt.LimitError, match="beyond the range of floating point"):
        pt.PiGroup({"x": 1, "y": -2}).evaluate({"x": sympy.Float("1e400"), "y": 2})


def test_evaluate_survives_an_overflow_on_the_way_to_a_finite_value():
    # 1e200**2 overflows a float, yet x^2/y^2 is 1/4 exactly: the floats' exact product, rounded once
    assert pt.PiGroup({"x": 2, "y": -2}).evaluate({"x": 1e200, "y": 2e200}) == 0.25
    assert pt.PiGroup({"x": 1, "y": -2}).evaluate({"x": 1, "y": Fraction(1, 10**200)}) == Fraction(10**400)


def test_a_groups_variables_are_names():
    with pytest.raises(pt.InvalidRequestError, match="variables are names") as caught:
        pt.PiGroup({1: 2})
    assert caught.value.culprit == 1


def test_sets_over_other_variables_are_not_equivalent_and_a_set_repr_names_its_parts():
    a = pt.System({"a": "L", "b": "L"}).pi_groups(repeating=("a",))
    c = pt.System({"a": "L", "c": "L"}).pi_groups(repeating=("a",))
    assert not a.equivalent(c)
    assert repr(a).startswith("PiSet([")
    assert "variables=('a', 'b')" in repr(a)
    assert "repeating=('a',)" in repr(a)


def test_evaluate_with_a_value_whose_float_is_zero_uses_the_exact_values():
    # Fraction(1, 10**400) is 0.0 as a float; the float path would divide by zero, the exact one does not
    group = pt.PiGroup({"x": 1, "y": -1})
    assert group.evaluate({"x": 1e-300, "y": Fraction(1, 10**400)}) == pytest.approx(1e100, rel=1e-15)
    with pytest.raises(pt.LimitError, match="value of 'y'"):  # a sympy Float 1e-400 would become 0.0 itself
        group.evaluate({"x": 1.0, "y": sympy.Float("1e-400")})


def test_reciprocal_negates_every_exponent_and_keeps_the_variable():
    group = pt.PiGroup({"a": 1, "b": -2, "c": 3}, variable="c")
    inverse = group.reciprocal()
    assert inverse.exponents == {"a": -1, "b": 2, "c": -3}
    assert inverse.variable == "c"
    assert inverse.evaluate({"a": 2, "b": 3, "c": 5}) == Fraction(9, 2 * 125)
    assert pt.PiGroup({"x": 1}).reciprocal().variable is None


def test_from_exponents_makes_the_named_variable_positive():
    # the variable's exponent is made positive even where the first variable's then is negative
    assert pt.PiGroup.from_exponents({"a": 1, "b": -1}, variable="b").exponents == {"a": -1, "b": 1}
    assert pt.PiGroup.from_exponents({"a": Fraction(-1, 2), "b": 1}, variable="b").exponents == {"a": -1, "b": 2}
    # without one (or with one the group does not use), the first variable used is made positive
    assert pt.PiGroup.from_exponents({"a": 0, "b": -2, "c": 4}, variable="a").exponents == {"b": 1, "c": -2}
    assert pt.PiGroup.from_exponents({"a": 0, "b": -2, "c": 4}).exponents == {"b": 1, "c": -2}


def test_from_exponents_of_zeros_is_the_trivial_group():
    group = pt.PiGroup.from_exponents({"a": 0, "b": Fraction(0)}, variable="a")
    assert group.is_trivial
    assert group.exponents == {}


def test_group_messages_in_full():
    with pytest.raises(pt.InvalidRequestError) as caught:
        pt.PiGroup({"x": Fraction(1, 2)})
    assert str(caught.value) == (
        "the exponent of 'x' in a Pi group is 1/2: PiGroup takes integer exponents; "
        "PiGroup.from_exponents normalises rational ones"
    )
    with pytest.raises(pt.PiTheoremError) as caught:
        pt.PiGroup({"x": "abc"})
    assert str(caught.value).startswith("the exponent of 'x' in a Pi group must be a finite real number")
    group = pt.PiGroup({"x": 1, "y": -2})
    with pytest.raises(pt.InvalidRequestError) as caught:
        group.evaluate({})
    assert str(caught.value) == "evaluate needs a value for 'x', 'y' of Pi = x/y**2"
    with pytest.raises(pt.LimitError) as caught:
        group.evaluate({"x": 1e300, "y": 1e-300})  # 1e900
    assert str(caught.value) == (
        "the value of the group is Pi = x/y**2: it is beyond the range of floating point (about 1.8e308)"
    )
    assert caught.value.culprit == "Pi = x/y**2"
    groups = pt.System({"m": "M", "l": "L", "g": "L/T^2", "t": "T", "v": "L/T"}).pi_groups(["m", "l", "g"])
    with pytest.raises(pt.InvalidRequestError) as caught:
        groups["q"]
    assert str(caught.value) == "no group for 'q'; groups exist for t, v"


def test_repr_names_the_variable_only_when_there_is_one():
    assert repr(pt.PiGroup({"a": 1, "b": -1})) == "PiGroup.from_exponents({'a': 1, 'b': -1})"
    assert (
        repr(pt.PiGroup({"a": 1, "b": -1}, variable="b")) == "PiGroup.from_exponents({'a': 1, 'b': -1}, variable='b')"
    )


def test_different_pi_sets_hash_apart():
    system = pt.System({"m": "M", "l": "L", "g": "L/T^2", "t": "T", "v": "L/T", "c": "M/T"})
    sets = [system.pi_groups(basis) for basis in system.bases()]
    distinct = set(sets)
    assert len(distinct) > 1
    assert len({hash(s) for s in distinct}) == len(distinct)  # equal sets hash alike; these differ
    for s in sets:
        assert hash(s) == hash(system.pi_groups(s.repeating))
