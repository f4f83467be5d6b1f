"""Dimensional consistency and scaling symmetries of equations (issue 6, parts 1-2)."""

from __future__ import annotations

import random
from fractions import Fraction

import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem.linalg import primitive_integer_vector
from tests.conftest import systems

t = sympy.Symbol("t")


m, l, g, k, c, x_r, th_r, k_th, c_th = sympy.symbols("m l g k c x_r theta_r k_theta c_theta")


theta = sympy.Function("theta")(t)
ROD_DIMS = {
    "m": "M",
    "l": "L",
    "g": "L T^-2",
    "k_theta": "M L^2 T^-2",
    "c_theta": "M L^2 T^-1",
    "theta_r": "1",
    "t": "T",
    "theta": "1",
}


def test_paper_eq1_is_consistent_with_either_sign():
    rodx = pt.System(ROD_DIMS)
    for sign in (+1, -1):  # the paper prints +k theta; the code uses -k theta: both are consistent
        rhs = 3 / (m * l**2) * (m * g * l / 2 * sympy.cos(theta) + sign * k_th * (theta - th_r) - c_th * theta.diff(t))
        report = pt.check_dimensions(sympy.Eq(theta.diff(t, 2), rhs), rodx)
        assert report.consistent
        assert report.dimension == pt.Dimension.parse("T^-2")


def longitudinal_system(damper_dimension: str) -> pt.System:
    return pt.System(
        {"m": "M", "l": "L", "g": "L T^-2", "k": "M T^-2", "c": damper_dimension, "x_r": "L", "t": "T", "theta": "1"}
    )


def test_longitudinal_variant_with_longitudinal_damper_is_flagged():
    # matlab_ports.rod_hinge_dynamics.rod_hinge_dynamics_longitudinal, as written in the original
    damping = c * l * theta.diff(t) * sympy.sin(theta) ** 2
    bracket = (
        m * g * l / 2 * sympy.cos(theta)
        - damping
        + k * l**2 * sympy.sin(theta) * sympy.cos(theta)
        - k * x_r * l * sympy.sin(theta)
    )
    rhs = 3 / (m * l**3) * bracket
    report = pt.check_dimensions(sympy.Eq(theta.diff(t, 2), rhs), longitudinal_system("M T^-1"))
    assert not report.consistent
    assert [(term, str(got), str(want)) for term, got, want in report.offending] == [
        (-damping, "M L T^-2", "M L^2 T^-2"),  # one length short of a torque
        # one term on each side: a tie, so both are listed (the 3/(m l^3) prefactor is the mistake)
        (theta.diff(t, 2), "T^-2", "L^-1 T^-2"),
        (rhs, "L^-1 T^-2", "T^-2"),
    ]
    assert len(report.ties) == 1
    assert "T^-2 and L^-1 T^-2" in report.ties[0]


def test_longitudinal_variant_with_rotational_damper_is_flagged_for_its_prefactor():
    bracket = (
        m * g * l / 2 * sympy.cos(theta)
        - c * theta.diff(t)
        + k * l**2 * sympy.sin(theta) * sympy.cos(theta)
        - k * x_r * l * sympy.sin(theta)
    )
    rhs = 3 / (m * l**3) * bracket
    report = pt.check_dimensions(sympy.Eq(theta.diff(t, 2), rhs), longitudinal_system("M L^2 T^-1"))
    assert [(term, str(got), str(want)) for term, got, want in report.offending] == [
        (theta.diff(t, 2), "T^-2", "L^-1 T^-2"),
        (rhs, "L^-1 T^-2", "T^-2"),
    ]
    assert "tie:" in str(report)


def test_transcendental_arguments_must_be_dimensionless():
    s = pt.System({"x": "L", "l": "L", "t": "T"})
    x, ll = sympy.symbols("x l")
    assert pt.check_dimensions(sympy.exp(x / ll) + sympy.log(x / ll), s).consistent
    report = pt.check_dimensions(sympy.sin(x) + sympy.cos(x / ll), s)
    assert [(term, str(got)) for term, got, _ in report.offending] == [(x, "L")]


@pytest.mark.parametrize("model", ["hinged_rod", "hinged_rod_longitudinal", "spring_mass_damper", "projectile"])
def test_shipped_models_are_consistent(model):
    mdl = getattr(pt.models, model)()
    for eq in mdl.equations:
        assert pt.check_dimensions(eq, mdl.system).consistent


def _beyond_the_limits(term, system) -> bool:
    """Whether a power in a monomial term, or the term, has a base exponent beyond 1000, multiplied out here."""
    powers = [(str(s), int(p)) for s, p in term.as_powers_dict().items() if isinstance(s, sympy.Symbol)]
    for b in system.base_dimensions:
        each = [p * system.dimension(n).exponent_of(b) for n, p in powers]
        if any(abs(e) > 1000 for e in each) or abs(sum(each)) > 1000:
            return True
    return False


@settings(max_examples=60, deadline=None)
@given(systems(max_vars=6), st.integers(0, 2**32 - 1))
def test_random_consistent_equations_pass_and_perturbed_fail(system, seed):
    rng = random.Random(seed)
    names = system.variables
    symbols = [sympy.Symbol(n) for n in names]
    null = [primitive_integer_vector(v) for v in system.dimensionless_products()]
    base = [rng.randint(-2, 2) for _ in names]

    def monomial(vec):
        return sympy.Mul(*(s**e for s, e in zip(symbols, vec, strict=True)))

    terms = []
    for _ in range(rng.randint(1, 4)):
        vec = list(base)
        for nv in null:
            coef = rng.randint(-2, 2)
            vec = [a + coef * b for a, b in zip(vec, nv, strict=True)]
        terms.append(rng.randint(1, 5) * monomial(vec))
    equation = sympy.Eq(monomial(base), sympy.Add(*terms), evaluate=False)
    # a term whose dimension passes the limits (|e| <= 1000, issue 33) is refused by name
    if any(_beyond_the_limits(term, system) for term in (monomial(base), *terms)):
        with pytest.raises(pt.LimitError, match="in the dimension of"):
            pt.check_dimensions(equation, system, time=None)
        return
    assert pt.check_dimensions(equation, system, time=None).consistent
    dimensional = [s for s in symbols if not system.dimension(s.name).is_dimensionless]
    if dimensional:
        culprit = rng.choice(dimensional)
        perturbed = sympy.Eq(monomial(base), sympy.Add(*terms[1:]) + terms[0] * culprit, evaluate=False)
        if _beyond_the_limits(terms[0] * culprit, system):
            with pytest.raises(pt.LimitError, match="in the dimension of"):
                pt.check_dimensions(perturbed, system, time=None)
            return
        report = pt.check_dimensions(perturbed, system, time=None)
        assert not report.consistent
        assert all(got != want for _, got, want in report.offending)


def vec(d):
    return {k_: v for k_, v in d.items() if v}


@pytest.mark.parametrize(
    ("model", "dimension", "units"),
    [("hinged_rod", 3, 3), ("hinged_rod_longitudinal", 3, 3), ("spring_mass_damper", 3, 3), ("projectile", 3, 2)],
)
def test_symmetry_subspace_of_each_shipped_model(model, dimension, units):
    mdl = getattr(pt.models, model)()
    sym = pt.scaling_symmetries(mdl.equations, mdl.system)
    assert sym.n_symmetries == dimension
    assert len(sym.within_units) == units
    assert sym.contains_units
    for u in sym.within_units:
        assert sym.contains(u)


def test_spring_mass_damper_has_no_symmetry_beyond_units():
    # Section 5: "scale gravity with lengths" is the change of length unit, not superposition magic
    smd = pt.models.spring_mass_damper()
    sym = pt.scaling_symmetries(smd.equations, smd.system)
    assert sym.beyond_units == ()
    assert sym.contains({"g": 1, "y_rest": 1, "y": 1, "v": 1})  # L -> s L


def test_small_angle_rod_without_gravity_has_amplitude_scaling():
    s = pt.System(
        {
            "m": "M",
            "l": "L",
            "k_theta": "M L^2 T^-2",
            "c_theta": "M L^2 T^-1",
            "theta_r": "1",
            "t": "T",
            "theta": "1",
            "omega": "T^-1",
        }
    )
    omega = sympy.Function("omega")(t)
    eqs = [
        sympy.Eq(theta.diff(t), omega),
        sympy.Eq(omega.diff(t), 3 / (m * l**2) * (-c_th * omega - k_th * (theta - th_r))),
    ]
    sym = pt.scaling_symmetries(eqs, s)
    amplitude = {"theta_r": 1, "theta": 1, "omega": 1}
    assert [vec(v) for v in sym.beyond_units] == [amplitude]  # the fewest-support form, not any complement
    assert sym.contains(amplitude)
    assert not pt.search(s, scale={"theta": 1}).feasible  # no change of units moves an angle


def test_full_rod_has_no_symmetry_beyond_units():
    rod = pt.models.hinged_rod()
    sym = pt.scaling_symmetries(rod.equations, rod.system)
    assert sym.beyond_units == ()
    assert not sym.contains({"theta": 1, "theta_r": 1, "omega": 1})  # cos(theta) forbids it


def test_projectile_lengths_scale_independently():
    proj = pt.models.projectile()
    sym = pt.scaling_symmetries(proj.equations, proj.system)
    assert [vec(v) for v in sym.beyond_units] == [{"x": 1, "vx": 1}]
    assert sym.contains({"x": 1, "vx": 1})
    assert sym.contains({"y": 1, "vy": 1, "g": 1})
    # search within the symmetries: stretch x alone, time and gravity fixed
    res = pt.search(proj.system, scale={"x": 1}, fixed=("t", "g"), within=sym)
    assert [vec(sc.exponents) for sc in res.scalings] == [{"x": 1, "vx": 1}]
    assert res.scalings[0].is_unit_change is False
    # m is not in the equations
    assert pt.SearchNote("outside_equations", ("m",)) in res.notes
    assert "m does not appear in the equations" in str(res)
    with pytest.raises(pt.InvalidRequestError, match="not a change of units"):
        _ = res.scalings[0].unit_change
    # with changes of units only, the same request is impossible
    assert not pt.search(proj.system, scale={"x": 1}, fixed=("t", "g")).feasible


def test_symmetry_search_agrees_with_unit_search_when_nothing_beyond():
    smd = pt.models.spring_mass_damper()
    sym = pt.scaling_symmetries(smd.equations, smd.system)
    a = pt.search(smd.system, scale={"g": 1}, within=sym)
    b = pt.search(smd.system, scale={"g": 1})
    assert {s.vector for s in a.scalings} == {s.vector for s in b.scalings}


def test_bad_equation_inputs():
    s = pt.System({"x": "L", "t": "T"})
    x, q = sympy.symbols("x q")
    with pytest.raises(pt.UnknownVariableError, match="'q'"):
        pt.check_dimensions(x + q, s)
    with pytest.raises(pt.InvalidRequestError, match="strings"):
        pt.check_dimensions("x + 1", s)
    with pytest.raises(pt.UnknownVariableError, match="'tau'"):
        pt.check_dimensions(x, s, time="tau")
    with pytest.raises(pt.InvalidRequestError, match="at least one equation"):
        pt.scaling_symmetries([], s)
    with pytest.raises(pt.UnknownVariableError, match="'q'"):
        pt.scaling_symmetries([sympy.Eq(x, q)], s)
    with pytest.raises(pt.InvalidRequestError, match="System"):
        pt.check_dimensions(x, {"x": "L"})
    sym = pt.scaling_symmetries([sympy.Eq(x, 0)], s)
    with pytest.raises(pt.InvalidRequestError, match="SymmetryReport"):
        pt.search(s, scale={"x": 1}, within="symmetries")
    with pytest.raises(pt.InvalidRequestError, match="'t' does not appear"):
        pt.search(
            pt.System({"x": "L", "t": "T", "u": "T"}),
            scale={"t": 1},
            within=pt.scaling_symmetries([sympy.Eq(x, 0)], pt.System({"x": "L", "t": "T", "u": "T"}), time=None),
        )
    assert sym.variables == ("x", "t")
    with pytest.raises(pt.InvalidRequestError, match="no equation holds the time derivative of a state"):
        pt.Model(s, [sympy.Eq(x, 0)])  # equations without a state define no model


def test_symmetries_beyond_units_are_exact():  # the reports' text: tests/test_formatting.py
    proj = pt.models.projectile()
    assert Fraction(1) in pt.scaling_symmetries(proj.equations, proj.system).beyond_units[0].values()


@pytest.mark.parametrize("model", ["hinged_rod", "spring_mass_damper", "projectile"])
def test_vectors_beyond_units_are_symmetries_that_no_unit_change_gives(model):
    mdl = getattr(pt.models, model)()
    sym = pt.scaling_symmetries(mdl.equations, mdl.system)
    units = [[u[n] for n in sym.variables] for u in sym.within_units]
    for v in sym.beyond_units:
        assert sym.contains(v)
        assert pt.linalg.rank([*units, [v[n] for n in sym.variables]]) == len(units) + 1
    assert sym.n_symmetries == len(sym.within_units) + len(sym.beyond_units)


# the symbols of the functions robot models use (check_dimensions and scaling_symmetries, issue 12)
X, Y, v, a, n = sympy.symbols("X Y v a n")
X_, Y_, L_ = sympy.symbols("x y l")
x = sympy.Function("x")(t)


psi = sympy.Function("psi")
SYSTEM = pt.System(
    {"t": "T", "X": "L", "Y": "L", "l": "L", "v": "L T^-1", "a": "1", "n": "1", "x": "L", "psi": "1", "F": "M L T^-2"}
)


F = sympy.Symbol("F")


def offending(expr, system=SYSTEM):
    return [(term, str(got), str(want)) for term, got, want in pt.check_dimensions(expr, system).offending]


CONSISTENT = [
    sympy.atan2(Y, X),  # a ratio of two lengths: an angle
    sympy.sign(x.diff(t)) * v,  # Coulomb friction's direction
    sympy.Heaviside(X - l) * F,  # a contact force switched on past l
    sympy.Heaviside(X - l, sympy.S.Half),  # with the value at zero, dimensionless
    sympy.Abs(X) + Y,
    sympy.Min(X, Y, l) + sympy.Max(X, l),
    sympy.Mod(X, l) + Y,
    sympy.floor(X / l) * l + Y,  # quantised position: floor of a ratio
    X**0.5 * Y**0.5 + l,  # float powers, read as 1/2
    X ** sympy.Float("1.5") / l**0.5,  # ... and 3/2
    a**n,  # symbolic power of dimensionless things
    sympy.DiracDelta(X - l) * X * l,  # delta of a length has dimension 1/L
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
    (sympy.atan2(Y, t), [(t, "T", "L"), (Y, "L", "T")]),  # a tie: both listed
    (psi(t + l), [(l, "L", "T"), (t, "T", "L")]),  # undefined function of a bad sum
    (sympy.Heaviside(X - t), [(-t, "T", "L"), (X, "L", "T")]),
    (sympy.Heaviside(X, l), [(l, "L", "1")]),  # its value at zero is a number
    (sympy.floor(X), [(X, "L", "1")]),  # floor is not homogeneous
    (sympy.ceiling(t), [(t, "T", "1")]),
    (X**n, [(X, "L", "1")]),  # a symbolic power of a length
    (sympy.Min(X, t, l), [(t, "T", "L")]),  # outvoted two to one
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
    assert sym.contains({"Y": 1})  # only Y's sign matters
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
    report = pt.check_dimensions(X ** (1 / 3), SYSTEM)
    assert report.dimension == pt.Dimension({"L": Fraction(1, 3)})  # a computed float: the simplest fraction


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


@pytest.mark.parametrize("bad", [3, "x = 2", None])
def test_scaling_symmetries_names_equations_that_are_no_list(bad):
    with pytest.raises(pt.InvalidRequestError, match="needs sympy equations"):
        pt.scaling_symmetries(bad, pt.System({"x": "L", "t": "T"}))


def test_a_term_beyond_the_exponent_limits_is_named_and_one_within_them_is_checked():
    # issue 33: a term's dimension is held to the limits once, as a whole
    s = pt.System({"x": "L", "y": "L", "z": "L", "r": "1"})
    x, y, z, r = sympy.symbols("x y z r")
    assert str(pt.check_dimensions(x**1000 * y**1000 / z**1000, s).dimension) == "L^1000"
    assert pt.check_dimensions(r**5000, s).dimension.is_dimensionless
    with pytest.raises(pt.LimitError, match=r"the exponent of 'L' in the dimension of x\*\*1001 is 1001"):
        pt.check_dimensions(x**1001 + y, s)
    with pytest.raises(pt.LimitError, match="in the dimension of x\\*\\*600\\*y\\*\\*600"):
        pt.check_dimensions(x**600 * y**600, s)
    with pytest.raises(pt.NumberError, match="an exponent in the equation must be a rational number"):
        pt.check_dimensions(x ** sympy.Float(2**0.5), s)
