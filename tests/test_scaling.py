"""Scaling algebra and apply: composing, powers, and what apply accepts.

Oracles are worked by hand: a change of units L -> s^a L, T -> s^b T moves
a variable of dimension L^p T^q by s^(a p + b q).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy

import pitheorem as pt

LT = pt.System({"l": "L", "t": "T", "v": "L/T"})


def test_composition_adds_exponents_and_unit_changes():
    length = pt.Scaling.from_unit_change(LT, {"L": 1})
    time = pt.Scaling.from_unit_change(LT, {"T": 2})
    both = length * time
    assert both.exponents == {"l": 1, "t": 2, "v": -1}
    assert both.unit_change == {"L": 1, "T": 2}


def test_composition_refuses_scalings_of_different_systems():
    other = pt.System({"l": "L", "t": "T"})
    with pytest.raises(
        pt.InvalidRequestError,
        match=r"different systems, System\(\{'l': 'L', 't': 'T', 'v': 'L T\^-1'\}\)"
        r" and System\(\{'l': 'L', 't': 'T'\}\); build both scalings from the same System",
    ):
        pt.Scaling.from_unit_change(LT, {"L": 1}) * pt.Scaling.from_unit_change(other, {"L": 1})


def test_composition_with_a_scaling_without_units_has_none():
    units = pt.Scaling.from_unit_change(LT, {"L": 1})
    bare = pt.Scaling(LT, (Fraction(0), Fraction(0), Fraction(1)), None)  # v alone: not a change of units
    assert not (units * bare).is_unit_change
    assert (bare * units).unit_change_vector is None
    assert (units * bare).exponents == {"l": 1, "t": 0, "v": 2}


@pytest.mark.parametrize(
    ("k", "units"),
    [(2, {"L": 2, "T": -2}), (Fraction(1, 2), {"L": Fraction(1, 2), "T": Fraction(-1, 2)}), (-3, {"L": -3, "T": 3})],
)
def test_power_multiplies_exponents_and_unit_changes(k, units):
    base = pt.Scaling.from_unit_change(LT, {"L": 1, "T": -1})  # l -> s l, t -> t/s, v -> s^2 v
    powered = base**k
    assert powered.exponents == {"l": k, "t": -k, "v": 2 * k}
    assert powered.unit_change == units


def test_apply_scales_arrays_and_checks_numbers():
    sc = pt.Scaling.from_unit_change(LT, {"L": 1})  # l -> s l, v -> s v
    out = sc.apply({"l": np.array([1.0, 2.0]), "t": np.array([3.0]), "v": 4}, s=2)
    assert out["l"].tolist() == [2.0, 4.0]
    assert out["t"].tolist() == [3.0]
    assert out["v"] == 8
    for bad in ("four", float("nan"), None):
        with pytest.raises(pt.NumberError):
            sc.apply({"v": bad}, s=2)


def test_without_units_there_is_no_unit_change():
    bare = pt.Scaling(LT, (Fraction(0), Fraction(0), Fraction(1)), None)
    with pytest.raises(pt.InvalidRequestError, match="not a change of units"):
        bare.unit_change  # noqa: B018
    with pytest.raises(pt.InvalidRequestError, match="not a change of units"):
        bare.exponent_of("L")


def test_scalings_are_equal_only_with_the_same_system_and_exponents():
    length = pt.Scaling.from_unit_change(LT, {"L": 1})
    assert length == pt.Scaling.from_exponents(LT, {"l": 1, "v": 1})
    assert length != pt.Scaling.from_unit_change(LT, {"T": 1})
    assert length != pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T", "w": "L/T"}), {"L": 1})
    assert length != 5


def test_dimensionless_systems_allow_only_the_identity():
    # no base dimension: every variable is its own Pi group, so none may change
    plain = pt.System({"x": "1", "y": "1"})
    assert pt.Scaling.from_exponents(plain, {"x": 0}).exponents == {"x": 0, "y": 0}
    with pytest.raises(pt.InvalidRequestError, match="not a similarity scaling"):
        pt.Scaling.from_exponents(plain, {"x": 1})


def test_apply_float_in_float_out_exact_in_exact_out():
    sc = pt.Scaling.from_unit_change(LT, {"L": 1})  # l -> s l, v -> s v, t unchanged
    out = sc.apply({"l": 9.81, "t": 3, "v": Fraction(1, 3)}, s=10)
    # a float with an exact s: 981/100 times 10, rounded once (not 9.81 * 10.0 = 98.10000000000001)
    assert out["l"] == 98.1
    assert type(out["l"]) is float
    assert out["t"] == 3
    assert type(out["t"]) is Fraction
    assert out["v"] == Fraction(10, 3)
    assert type(out["v"]) is Fraction
    floats = sc.apply({"l": 9.81, "t": 3, "v": Fraction(1, 3)}, s=10.0)  # a float s: every result a float
    assert all(type(x) is float for x in floats.values())
    assert floats["t"] == 3.0
    assert floats["v"] == pytest.approx(10 / 3)


def test_irrational_results_are_exact_sympy_numbers():
    import sympy

    half = pt.Scaling.from_exponents(pt.System({"l": "L"}), {"l": Fraction(1, 2)})  # l -> s^(1/2) l
    assert half.apply({"l": 3}, s=4) == {"l": Fraction(6)}
    assert type(half.apply({"l": 3}, s=4)["l"]) is Fraction
    assert half.apply({"l": 8}, s="1/4") == {"l": Fraction(4)}
    root = half.apply({"l": 3}, s=2)["l"]
    assert not isinstance(root, Fraction)
    assert sympy.simplify(root - 3 * sympy.sqrt(2)) == 0
    assert half.apply({"l": 3.0}, s=2)["l"] == pytest.approx(3 * 2**0.5)
    assert half.factors(9) == {"l": Fraction(3)}
    assert type(half.factors(9)["l"]) is Fraction
    assert half.factors(2)["l"] == sympy.sqrt(2)
    assert half.factors(2.0) == {"l": pytest.approx(2**0.5)}
    assert type(half.factors(2.0)["l"]) is float


def test_every_float_factor_is_one_power_float_in_float_out():
    import sympy

    from pitheorem.exact import read_scale_factor
    from pitheorem.scaling import float_power
    from pitheorem.simulation import ModelScaling

    # an exact s is raised exactly and rounded once; a float s is raised in floating point
    assert float_power(Fraction(1, 10), Fraction(2), "x") == 0.01
    assert float_power(0.1, Fraction(2), "x") == 0.1**2 != 0.01
    assert float_power(sympy.sqrt(2), Fraction(2), "x") == 2.0 != float(sympy.sqrt(2)) ** 2
    assert float_power(Fraction(2), Fraction(1, 2), "x") == float(sympy.sqrt(2).evalf(30))
    assert float_power(7.5, 0, "x") == 1.0
    assert isinstance(float_power(Fraction(3), Fraction(2), "x"), float)
    with pytest.raises(pt.LimitError) as caught:
        float_power(Fraction(10) ** 200, Fraction(2), "the factor of 'g'")
    assert str(caught.value).startswith("the factor of 'g' is s^2 with s = about 10^200: it is beyond the range")
    with pytest.raises(pt.LimitError, match=r"x is s\^2 with s = about 10\^200"):
        float_power(1e200, Fraction(2), "x")
    # the factor overflows however exact the values are: the remedy is a smaller s
    assert str(caught.value).endswith("; choose an s nearer to 1")
    # the value types take their float factors from it
    sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 2})
    assert sc.factors(0.1) == {"l": 0.1**2, "t": 1.0}
    t, y = sc.map_back([2.0], [[1.0]], Fraction(1, 10), time="t", states=["l"])
    assert (t.tolist(), y.tolist()) == ([2.0], [[1 / 0.01]])
    gravity = ModelScaling.of(pt.models.projectile(), {"g": 1, "t": 1}, s=0.1)
    assert gravity.factor("vx") == float_power(read_scale_factor(0.1), gravity.exponents["vx"], "vx") == 0.1**2


def test_scaling_apply_and_map_back(rod):
    (sc,) = pt.search(rod, scale={"g": 1, "l": -1}, fixed=("m", "k_theta")).scalings
    params = {"m": Fraction(3, 2), "l": 2, "g": Fraction(981, 100), "c_theta": 10}
    scaled = sc.apply(params, s=2)
    assert scaled == {"m": Fraction(3, 2), "l": 1, "g": Fraction(981, 50), "c_theta": 5}
    for group in rod.pi_groups(repeating=("m", "l", "k_theta")):
        values = dict.fromkeys(rod.variables, 3) | params
        new = values | sc.apply(values, s=2)
        assert group.evaluate(values) == group.evaluate(new)
    t, y = sc.map_back([0.0, 1.0], [[0.5, 1.0], [0.6, 2.0]], 2, time="t", states=["1", "1/T"])
    assert t.tolist() == [0.0, 2.0]
    assert y.tolist() == [[0.5, 0.5], [0.6, 1.0]]
    assert (sc * sc.inverse()).changed == ()
    assert (sc**2).exponents["l"] == -2
    assert pt.Scaling.from_exponents(rod, {"l": -1, "g": 1, "c_theta": -1, "t": -1, "F": 1}) == sc
    assert sc.factors(2.0)["t"] == 0.5


def test_bad_scaling_use(rod):
    with pytest.raises(pt.InvalidRequestError, match="not a similarity scaling"):
        pt.Scaling.from_exponents(rod, {"g": 1})
    with pytest.raises(pt.InvalidRequestError, match="'Q'"):
        pt.Scaling.from_unit_change(rod, {"Q": 1})
    sc = pt.Scaling.from_unit_change(rod, {"L": 1})
    with pytest.raises(pt.InvalidRequestError, match="positive"):
        sc.apply({"l": 1}, s=-2)
    with pytest.raises(pt.UnknownVariableError, match="'length'"):
        sc.apply({"length": 1}, s=2)
    with pytest.raises(pt.InvalidRequestError, match="shape"):
        sc.map_back([0, 1], [[1, 2, 3]], 2, time="t", states=["1"])


def test_an_irrational_s_beyond_floats_is_refused_like_a_rational_one():
    import sympy

    # float() of a sympy number gives inf instead of raising: every float factor must still refuse it
    sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 3})
    huge = sympy.sqrt(2) * 10**150
    with pytest.raises(pt.LimitError, match=r"the scaled value of 'l' is .*beyond the range of floating point"):
        sc.apply({"l": 1.5}, huge)
    with pytest.raises(pt.LimitError, match=r"the factor of 'l' is s\^3 .*; choose an s nearer to 1"):
        sc.apply({"l": np.array([1.0])}, huge)
    # map_back names the state, by name or by dimension
    with pytest.raises(pt.LimitError, match=r"the factor of state 'l' is s\^3"):
        sc.map_back([0.0], [1.0], huge, time="t", states=["l"])
    with pytest.raises(pt.LimitError, match=r"the factor of a state of dimension L is s\^3"):
        sc.map_back([0.0], [1.0], huge, time="t", states=[pt.Dimension.parse("L")])


def test_apply_keeps_an_irrational_exact_value_exact():
    import sympy

    sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 2})
    scaled = sc.apply({"l": sympy.pi, "t": sympy.sqrt(2)}, 3)
    assert scaled["l"] == 9 * sympy.pi  # not 9 times pi's decimal rounding
    assert scaled["t"] == sympy.sqrt(2)


# -- arguments checked by name, and no silent infinity (issue 23's reproducers)


def test_apply_takes_a_mapping_of_values():
    sc = pt.Scaling.from_unit_change(LT, {"L": 1})
    with pytest.raises(pt.InvalidRequestError, match="mapping of variable names"):
        sc.apply([("l", 1)], 2)


@pytest.mark.parametrize(
    "build",
    [
        lambda: pt.Scaling.from_unit_change(LT, None),
        lambda: pt.Scaling.from_exponents(LT, None),
        lambda: pt.Scaling.from_unit_change(LT, ["L"]),
        lambda: pt.Scaling.from_exponents(LT, "l"),
        lambda: pt.Scaling.from_unit_change(None, {"L": 1}),
        lambda: pt.Scaling.from_exponents({"l": "L"}, {"l": 1}),
    ],
)
def test_constructors_name_a_wrong_argument(build):
    with pytest.raises(pt.InvalidRequestError, match=r"a Scaling needs a System|must be a mapping"):
        build()


@pytest.mark.parametrize(("value", "s"), [(3, 1e308), (3.0, 1e308), (1e300, 1e10), (3, np.float64(1e308))])
def test_apply_refuses_a_float_result_beyond_floating_point(value, s):
    sc = pt.Scaling.from_unit_change(LT, {"L": 1})
    with pytest.raises(pt.LimitError, match="beyond the range of floating point"):
        sc.apply({"l": value}, s=s)


def test_apply_refuses_a_sympy_float_s_beyond_doubles():
    import sympy

    sc = pt.Scaling.from_unit_change(LT, {"L": 1})
    with pytest.raises(pt.LimitError, match="scale factor s"):
        sc.apply({"l": 3}, s=sympy.Float("1e400"))
    assert sc.apply({"l": 3}, s=sympy.Float("1e300")) == {"l": 3e300}


def test_apply_refuses_samples_that_overflow_but_keeps_given_infinities():
    sc = pt.Scaling.from_unit_change(LT, {"L": 1})
    with pytest.raises(pt.LimitError, match="samples of 'l'"):
        sc.apply({"l": np.array([1.0, 1e300])}, s=1e10)
    out = sc.apply({"l": np.array([1.0, np.inf])}, s=2.0)["l"]
    assert out.tolist() == [2.0, np.inf]


def test_apply_at_the_edge_of_floating_point_is_exact_in_range():
    sc = pt.Scaling.from_unit_change(LT, {"L": 1})
    assert sc.apply({"l": 1.5}, s=1e308) == {"l": 1.5e308}


def test_exponent_of_a_base_the_system_lacks_is_named():
    sc = pt.Scaling.from_unit_change(LT, {"L": 1})
    with pytest.raises(pt.InvalidRequestError, match="uses base 'M'"):
        sc.exponent_of("M L")


def test_a_scaling_composes_only_with_scalings_and_its_repr_rebuilds_it():
    sc = pt.Scaling.from_unit_change(LT, {"L": 1, "T": Fraction(1, 2)})
    with pytest.raises(TypeError):
        sc * 2
    rebuilt = eval(repr(sc), {"Scaling": pt.Scaling, "System": pt.System})
    assert rebuilt == sc
    assert "'t': '1/2'" in repr(sc)


def test_an_exact_value_beyond_floats_scaled_by_a_float_s_is_rounded_once():
    sc = pt.Scaling.from_unit_change(LT, {"L": 1})
    assert sc.apply({"l": 10**400}, s=1e-300) == {"l": pytest.approx(1e100, rel=1e-15)}
    assert sc.apply({"l": "1e400"}, s=1e-300)["l"] == pytest.approx(1e100, rel=1e-15)
    with pytest.raises(pt.LimitError, match="scaled value of 'l'"):
        sc.apply({"l": 10**400}, s=2.0)


@pytest.mark.parametrize("value", ["1e400", "1e-400"])
def test_a_sympy_float_value_beyond_doubles_is_named_with_a_float_s(value):
    import sympy

    sc = pt.Scaling.from_unit_change(LT, {"L": 1, "T": 1})
    with pytest.raises(pt.LimitError, match="value of 'v'"):
        sc.apply({"l": 1.0, "v": sympy.Float(value)}, s=1e-200)


ROD = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})


def raised(call):
    """The PiTheoremError that `call` raises, for its message and culprit."""
    with pytest.raises(pt.PiTheoremError) as caught:
        call()
    return caught.value


def test_is_power_of_two_against_the_exact_fraction():
    def oracle(x):  # a positive dyadic number with numerator or denominator 1, both powers of two
        f = Fraction(x)
        return f > 0 and f.numerator & (f.numerator - 1) == 0 and f.denominator & (f.denominator - 1) == 0

    cases = [1.0, 2.0, 0.5, 1024.0, 2.0**-1074, 2.0**1023, 3.0, 0.75, 6.0, 0.0, -2.0, -0.5, 0.1, 1.5, 5e-324 * 3]
    for x in cases:
        assert pt.scaling.is_power_of_two(x) is oracle(x), x
    assert pt.scaling.is_power_of_two(Fraction(1, 4))
    assert pt.scaling.is_power_of_two(8)
    assert not pt.scaling.is_power_of_two(Fraction(1, 3))


def test_a_float_s_is_raised_in_floating_point():
    # float in, float out: Python's own power of the double, which can differ from the exact power
    # rounded once in the last place (73.66518562805436^-4 does)
    from pitheorem.scaling import float_power

    for x, p in ((73.66518562805436, -4), (99.50051472973581, -2), (88.63593255097763, -9), (0.1, 3)):
        assert float_power(x, p, "x") == x ** float(p)


def test_scaling_messages_in_full():
    sc = pt.Scaling.from_unit_change(ROD, {"L": 1})
    squared = pt.Scaling.from_unit_change(ROD, {"L": 2, "T": 2})
    beyond = "it is beyond the range of floating point"
    exact_hint = "use an exact s (an int, a Fraction or a string such as '1/2'), or an s nearer to 1"
    cases = [  # (call, message, culprit)
        (
            lambda: sc.apply({"l": 1e300}, s=10**10),
            f"the scaled value of 'l' is about 10^310: {beyond} (about 1e308); use an exact value (int or Fraction), "
            "or an s nearer to 1",
            "about 10^310",
        ),
        (
            lambda: sc.apply({"l": Fraction(10**300)}, s=1e10),
            f"the scaled value of 'l' is about 10^310: {beyond} (about 1e308); use an exact value (int or Fraction), "
            "or an s nearer to 1",
            "about 10^310",
        ),
        (
            lambda: sc.apply({"l": 1e300}, s=1e10),
            f"the scaled value of 'l' is 1e+300 times 10000000000.0: {beyond} (about 1.8e308); {exact_hint}",
            "1e+300 times 10000000000.0",
        ),
        (
            lambda: sc.apply({"l": np.array([1e300, 1.0])}, s=1e10),
            f"the scaled samples of 'l' is a sample times 10000000000.0: {beyond} (about 1.8e308); {exact_hint}",
            "a sample times 10000000000.0",
        ),
        (
            lambda: squared.apply({"l": 1.0}, s=1e300),
            f"the factor of 'l' is s^2 with s = about 10^300: {beyond}; choose an s nearer to 1",
            "s^2 with s = about 10^300",
        ),
        (
            lambda: squared.factors(1e300),
            f"the factor of 'l' is s^2 with s = about 10^300: {beyond}; choose an s nearer to 1",
            "s^2 with s = about 10^300",
        ),
        (
            lambda: squared.map_back([0.0, 1.0], [[1.0], [2.0]], 1e300, time="t", states=["m"]),
            f"the factor of 't' is s^2 with s = about 10^300: {beyond}; choose an s nearer to 1",
            "s^2 with s = about 10^300",
        ),
        (
            lambda: pt.scaling.float_power(sympy.sqrt(2), 5000, "the factor of 'x'"),
            f"the factor of 'x' is s^5000 with s = sqrt(2): {beyond}; choose an s nearer to 1",
            "s^5000 with s = sqrt(2)",
        ),
        (lambda: pt.Scaling.from_unit_change(3, {"L": 1}), "a Scaling needs a System, got int", 3),
        (lambda: pt.Scaling.from_exponents(3, {"l": 1}), "a Scaling needs a System, got int", 3),
        (lambda: pt.Scaling.from_unit_change(ROD, 5), "unit_change must be a mapping such as {'L': 1}, got 5", 5),
        (lambda: pt.Scaling.from_exponents(ROD, 5), "exponents must be a mapping such as {'l': 1}, got 5", 5),
        (
            lambda: pt.Scaling.from_unit_change(ROD, {"Q": 1}),
            "unknown base dimension 'Q' in unit_change; the system's base dimensions are M, L, T",
            None,
        ),
        (
            lambda: pt.Scaling.from_exponents(ROD, {"q": 1}),
            "unknown variable 'q' in exponents; the system has m, l, g, t",
            "q",
        ),
        (
            lambda: pt.Scaling.from_exponents(ROD, {"l": 1}),
            "exponents {'l': 1} are not a similarity scaling: they change a Pi group (only changes of base units keep "
            "every group invariant)",
            None,
        ),
        (
            lambda: sc.apply(3, s=2),
            "values must be a mapping of variable names to numbers, such as {'l': 2}, got int",
            3,
        ),
        (lambda: sc.apply({"q": 1}, s=2), "unknown variable 'q' in values; the system has m, l, g, t", "q"),
        (
            lambda: sc.map_back([0, 1], [[1], [2]], 2.0, time="q", states=["l"]),
            "unknown variable 'q' in time; the system has m, l, g, t",
            "q",
        ),
    ]
    for call, message, culprit in cases:
        err = raised(call)
        assert str(err) == message
        assert err.culprit == culprit
    # an irrational exact result beyond floats is shown as sympy writes it
    huge = sympy.Integer(10) ** 310 * sympy.sqrt(10)  # 1e300 times s = sqrt(10)^21
    err = raised(lambda: sc.apply({"l": 1e300}, s=sympy.sqrt(10) ** 21))
    assert err.culprit == str(huge)
    assert str(err).startswith(f"the scaled value of 'l' is {huge}: {beyond} (about 1e308)")
    # the start of a number's refusal names what it was meant to be
    for call, what in (
        (lambda: pt.Scaling.from_unit_change(ROD, {"L": "x"}), "exponent of base unit 'L'"),
        (lambda: pt.Scaling.from_exponents(ROD, {"l": "x"}), "exponent of 'l'"),
        (lambda: sc.apply({"l": "abc"}, s=2), "the value of 'l'"),
        (lambda: sc ** "abc", "the power of a scaling"),
    ):
        assert str(raised(call)).startswith(f"{what} must be a finite real number")
    bare = pt.Scaling(ROD, (Fraction(0), Fraction(1), Fraction(0), Fraction(0)), None)
    assert str(raised(lambda: bare.unit_change)) == (
        f"{bare} is a symmetry of particular equations, not a change of units: it has no unit change, and "
        "quantities outside the system have no defined exponent"
    )


def test_exponents_are_fractions_even_without_base_dimensions():
    system = pt.System({"x": "1", "y": "1"})
    sc = pt.Scaling.from_unit_change(system, {})
    assert all(type(p) is Fraction for p in sc.exponents.values())
    assert type(sc.exponent_of("1")) is Fraction
    assert type(pt.Scaling.from_unit_change(LT, {"L": 1}).exponent_of("1")) is Fraction


def test_exponent_of_any_dimension_is_its_exponents_times_the_unit_change():
    sc = pt.Scaling.from_unit_change(ROD, {"M": 2, "L": Fraction(1, 3), "T": -1})
    # M^a L^b T^c moves by s^(2a + b/3 - c), by hand
    for text, want in (
        ("M", 2),
        ("L", Fraction(1, 3)),
        ("T", -1),
        ("1", 0),
        ("M L^2 T^-2", Fraction(14, 3)),
        ("L^3/M", -1),
    ):
        assert sc.exponent_of(text) == want
        assert sc.exponent_of(pt.Dimension.parse(text)) == want


def test_an_exact_value_given_as_a_string_is_read_as_a_number():
    sc = pt.Scaling.from_unit_change(ROD, {"L": 1})
    assert sc.apply({"l": "1/2", "m": "3"}, s=2) == {"l": Fraction(1), "m": Fraction(3)}


def test_map_back_reads_exact_times_and_states_as_floats():
    sc = pt.Scaling.from_unit_change(LT, {"T": 1})  # t -> s t, v -> v/s
    t, y = sc.map_back([Fraction(0), Fraction(1, 2)], [[Fraction(1)], [Fraction(3, 2)]], 2, time="t", states=["v"])
    assert t.dtype == y.dtype == np.float64
    assert t.tolist() == [0.0, 0.25]
    assert y.tolist() == [[2.0], [3.0]]


def test_samples_whose_factor_underflows_are_scaled_without_a_warning():
    sc = pt.Scaling.from_unit_change(LT, {"L": 2})  # l -> s^2 l; s = 1e-200 makes the factor 0.0
    out = sc.apply({"l": np.array([np.inf, 1.0])}, s=1e-200)
    assert out["l"][1] == 0.0


def test_a_power_of_a_scaling_without_units_has_none():
    bare = pt.Scaling(LT, (Fraction(0), Fraction(0), Fraction(1)), None)
    squared = bare**2
    assert squared.unit_change_vector is None
    assert squared.exponents == {"l": 0, "t": 0, "v": 2}


def test_scalings_hash_by_system_and_exponents():
    scalings = [pt.Scaling.from_unit_change(ROD, {"L": k, "T": j}) for k in range(-2, 3) for j in range(-2, 3)]
    assert len({hash(sc) for sc in scalings}) > len(scalings) // 2  # (Python's hash(-1) is hash(-2))
    assert hash(pt.Scaling.from_unit_change(ROD, {"L": 1})) == hash(pt.Scaling.from_exponents(ROD, {"l": 1, "g": 1}))


def test_repr_writes_integer_exponents_as_integers():
    rod = repr(ROD)
    assert repr(pt.Scaling.from_unit_change(ROD, {"L": 1})) == f"Scaling.from_exponents({rod}, {{'l': 1, 'g': 1}})"
    assert repr(
        pt.Scaling.from_unit_change(ROD, {"T": Fraction(1, 2)})
    ) == f"Scaling.from_exponents({rod}, {{'g': '-1', 't': '1/2'}})".replace("'-1'", "-1")
