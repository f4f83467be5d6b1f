"""The functions robot models use, checked by check_dimensions and scaling_symmetries (issue 12)."""

from __future__ import annotations

from fractions import Fraction

import pytest
import sympy

import pitheorem as pt

t, X, Y, l, v, a, n = sympy.symbols("t X Y l v a n")
x = sympy.Function("x")(t)
psi = sympy.Function("psi")
SYSTEM = pt.System({"t": "T", "X": "L", "Y": "L", "l": "L", "v": "L T^-1", "a": "1", "n": "1", "x": "L",
                    "psi": "1", "F": "M L T^-2"})
F = sympy.Symbol("F")


X_, Y_, L_ = sympy.symbols("x y l")


def offending(expr, system=SYSTEM):
    return [(term, str(got), str(want)) for term, got, want in pt.check_dimensions(expr, system).offending]


CONSISTENT = [
    sympy.atan2(Y, X),                       # a ratio of two lengths: an angle
    sympy.sign(x.diff(t)) * v,               # Coulomb friction's direction
    sympy.Heaviside(X - l) * F,              # a contact force switched on past l
    sympy.Heaviside(X - l, sympy.S.Half),    # with the value at zero, dimensionless
    sympy.Abs(X) + Y,
    sympy.Min(X, Y, l) + sympy.Max(X, l),
    sympy.Mod(X, l) + Y,
    sympy.floor(X / l) * l + Y,              # quantised position: floor of a ratio
    X**0.5 * Y**0.5 + l,                     # float powers, read as 1/2
    X**sympy.Float("1.5") / l**0.5,          # ... and 3/2
    a**n,                                    # symbolic power of dimensionless things
    sympy.DiracDelta(X - l) * X * l,         # delta of a length has dimension 1/L
    psi(t) * l + X,
]


@pytest.mark.parametrize("expr", CONSISTENT, ids=str)
def test_consistent_expressions(expr):
    report = pt.check_dimensions(expr, SYSTEM)
    assert report.consistent, str(report)


def test_dimensions_of_functions():
    dim = pt.Dimension.parse
    assert pt.check_dimensions(sympy.atan2(Y, X), SYSTEM).dimension == dim("1")
    assert pt.check_dimensions(sympy.sign(v), SYSTEM).dimension == dim("1")
    assert pt.check_dimensions(sympy.Abs(v), SYSTEM).dimension == dim("L T^-1")
    assert pt.check_dimensions(sympy.Max(X, Y), SYSTEM).dimension == dim("L")
    assert pt.check_dimensions(X**0.5, SYSTEM).dimension == dim("L^(1/2)")
    assert pt.check_dimensions(X**0.1, SYSTEM).dimension == dim("L^(1/10)")
    assert pt.check_dimensions(sympy.DiracDelta(X - l), SYSTEM).dimension == dim("L^-1")


INCONSISTENT = [
    (sympy.atan2(Y, t), [(t, "T", "L"), (Y, "L", "T")]),           # a tie: both listed
    (psi(t + l), [(l, "L", "T"), (t, "T", "L")]),                  # undefined function of a bad sum
    (sympy.Heaviside(X - t), [(-t, "T", "L"), (X, "L", "T")]),
    (sympy.Heaviside(X, l), [(l, "L", "1")]),                      # its value at zero is a number
    (sympy.floor(X), [(X, "L", "1")]),                             # floor is not homogeneous
    (sympy.ceiling(t), [(t, "T", "1")]),
    (X**n, [(X, "L", "1")]),                                       # a symbolic power of a length
    (sympy.Min(X, t, l), [(t, "T", "L")]),                         # outvoted two to one
    (sympy.sin(X), [(X, "L", "1")]),
]


@pytest.mark.parametrize(("expr", "expected"), INCONSISTENT, ids=lambda v: str(v) if isinstance(v, sympy.Basic) else "")
def test_inconsistent_expressions(expr, expected):
    got = offending(expr)
    assert sorted(got, key=str) == sorted(expected, key=str)


def test_outvoted_term_alone_is_blamed():
    # two lengths against one time: the time is wrong, not the lengths
    report = pt.check_dimensions(X + Y + t, SYSTEM)
    assert offending(X + Y + t) == [(t, "T", "L")]
    assert report.ties == ()
    assert report.dimension == pt.Dimension.parse("L")


def test_equation_sides_vote_together():
    # m x'' = -k x - c x' + F with F written wrongly: three forces outvote it
    m, k, c, G = sympy.symbols("m k c G")
    s = pt.System({"m": "M", "k": "M T^-2", "c": "M T^-1", "G": "M L", "x": "L", "t": "T"})
    eq = sympy.Eq(m * x.diff(t, 2), -k * x - c * x.diff(t) + G)
    report = pt.check_dimensions(eq, s)
    assert [(term, str(got)) for term, got, _ in report.offending] == [(G, "M L")]
    assert report.ties == ()


def test_tie_is_stated():
    report = pt.check_dimensions(X + t, SYSTEM)
    assert {term for term, _, _ in report.offending} == {X, t}
    assert len(report.ties) == 1
    assert "L" in report.ties[0]
    assert "T" in report.ties[0]
    assert "tie:" in str(report)


def test_time_may_be_absent():
    xs, ys = sympy.symbols("x y")
    assert pt.check_dimensions(xs + ys, pt.System({"x": "L", "y": "L"})).consistent
    sym = pt.scaling_symmetries([sympy.Eq(xs, ys)], pt.System({"x": "L", "y": "L"}))
    assert sym.variables == ("x", "y")
    with pytest.raises(pt.UnknownVariableError, match="tau"):  # a name other than the default must exist
        pt.check_dimensions(xs + ys, pt.System({"x": "L", "y": "L"}), time="tau")


def test_symmetries_of_the_new_functions():
    s = pt.System({"X": "L", "Y": "L", "l": "L", "t": "T", "F": "M L T^-2", "m": "M"})
    # m x'' = F * Heaviside(X - l) * sign(Y): X and l must scale together; Y is free
    eq = sympy.Eq(sympy.Symbol("m") * X, F * t**2 * sympy.Heaviside(X - l) * sympy.sign(Y))
    sym = pt.scaling_symmetries([eq], s)
    assert sym.contains({"X": 1, "l": 1, "F": 1})
    assert sym.contains({"Y": 1})             # only Y's sign matters
    assert not sym.contains({"X": 1, "F": 1})  # X - l must stay homogeneous
    # atan2(Y, X) is invariant only when Y and X scale together
    sym2 = pt.scaling_symmetries([sympy.Eq(sympy.Symbol("m"), sympy.atan2(Y, X) * sympy.Symbol("m"))], s)
    assert sym2.contains({"X": 1, "Y": 1})
    assert not sym2.contains({"X": 1})
    # floor needs an invariant argument
    sym3 = pt.scaling_symmetries([sympy.Eq(X, l * sympy.floor(X / l))], s)
    assert sym3.contains({"X": 1, "l": 1})
    assert not sym3.contains({"X": 1})
    # float power x**0.5 is read as 1/2
    sym4 = pt.scaling_symmetries([sympy.Eq(Y, X**0.5 * l**0.5)], s)
    assert sym4.contains({"X": 2, "Y": 1})
    assert sym4.contains({"X": 1, "Y": 1, "l": 1})


def test_contains_units_is_false_for_inconsistent_equations():
    # mutation survivor: contains_units forced to True went unnoticed
    xs, ts = sympy.symbols("x t")
    s = pt.System({"x": "L", "t": "T"})
    sym = pt.scaling_symmetries([sympy.Eq(xs, ts)], s)
    assert sym.contains_units is False
    assert "NOT all symmetries" in str(sym)
    assert not sym.contains({"x": 1})  # a change of length unit is not a symmetry of x = t
    vs = sympy.Symbol("v")
    good = pt.scaling_symmetries([sympy.Eq(xs, vs * ts)], pt.System({"x": "L", "t": "T", "v": "L/T"}))
    assert good.contains_units is True


def test_float_exponent_uses_the_number_rule():
    report = pt.check_dimensions(X**(1 / 3), SYSTEM)
    assert report.dimension == pt.Dimension({"L": Fraction(3333333333333333, 10**16)})


def test_symmetries_when_every_variable_is_dimensionless():
    # no base dimension at all: no unit changes, and y = x^2 keeps x -> s x, y -> s^2 y (by hand)
    x, y = sympy.symbols("x y")
    report = pt.scaling_symmetries(sympy.Eq(y, x**2), pt.System({"x": "1", "y": "1"}), time=None)
    assert report.within_units == ()
    assert report.beyond_units == ({"x": 1, "y": 2},)
    assert report.contains_units


def test_reports_are_frozen():
    import dataclasses

    report = pt.check_dimensions(sympy.Symbol("x") + sympy.Symbol("y"), pt.System({"x": "L", "y": "L"}))
    with pytest.raises(dataclasses.FrozenInstanceError):
        report.consistent = False


def test_symmetries_through_abs():
    # y = |x - l|: x and l scale with y (by hand); Abs keeps its argument's weight
    s = pt.System({"x": "L", "l": "L", "y": "L"})
    sym = pt.scaling_symmetries(sympy.Eq(Y_, sympy.Abs(X_ - L_)), s, time=None)
    assert sym.contains({"x": 1, "l": 1, "y": 1})
    assert not sym.contains({"x": 1, "l": 1})
    assert not sym.contains({"y": 1})


def test_symmetries_need_a_system():
    with pytest.raises(pt.InvalidRequestError, match="needs a System"):
        pt.scaling_symmetries(sympy.Eq(Y_, X_), {"x": "L", "y": "L"})
