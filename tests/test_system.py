"""pitheorem.system: System, its input checks, and what it answers about its variables.

Pi groups (``pi_groups``, ``default_repeating``) against sympy's solutions,
dimension specs at and beyond the limits, the opt-in base letters, pint
units (``from_units``).  The enumeration behind ``bases`` is in test_bases.
"""

from __future__ import annotations

import re
from fractions import Fraction

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem.exact import (
    MAX_DENOMINATOR,
    MAX_EXPONENT,
)
from tests.conftest import BAD_FORMULAS, ROD, oracle_bases, oracle_groups, systems


def test_time_variables_are_those_of_dimension_time_alone_in_system_order():
    system = pt.System({"tau": "T", "l": "L", "f": "T^-1", "t": "T", "t2": "T^2", "c": "M T", "x": {"T": 1, "L": 0}})
    assert system.time_variables == ("tau", "t", "x")
    assert pt.System({"l": "L", "f": "T^-1"}).time_variables == ()


@pytest.mark.parametrize(
    ("variables", "expected"),
    [
        ({"t": "T", "l": "L", "g": "L T^-2"}, ("l", "g")),
        ({"tau": "T", "l": "L", "v": "L/T"}, ("l", "v")),
        ({"t": "T", "tau": "T", "l": "L", "v": "L/T"}, ("l", "v")),
        ({"t": "T", "l": "L"}, ("t", "l")),  # every basis needs time
    ],
)
def test_default_repeaters_avoid_the_time_variables(variables, expected):
    assert pt.System(variables).default_repeating() == expected


def test_a_column_is_the_exponents_of_the_variables_dimension_over_the_base_dimensions():
    from fractions import Fraction

    system = pt.System({"k": "M T^-2", "q": "Theta^(1/2) L", "one": "1"})
    assert system.base_dimensions == ("M", "L", "T", "Theta")
    assert system.column("k") == (1, 0, -2, 0)
    assert system.column("q") == (0, 1, 0, Fraction(1, 2))
    assert system.column("one") == (0, 0, 0, 0)
    assert all(type(x) is Fraction for x in system.column("q"))
    with pytest.raises(pt.UnknownVariableError, match="'x'"):
        system.column("x")


@pytest.mark.parametrize(
    "spec", ["L^99999999999999999999999", {"L": 1e300}, {"L": 10**400}, "L^1001", "L^(1/1000000000001)"]
)
def test_exponent_limits(spec):
    with pytest.raises(pt.LimitError) as info:
        pt.System({"x": spec})
    assert str(MAX_EXPONENT) in str(info.value) or str(MAX_DENOMINATOR) in str(info.value)


def test_exponents_at_the_limits_are_accepted():
    s = pt.System({"x": f"L^{MAX_EXPONENT}", "y": f"T^(-1/{MAX_DENOMINATOR})"})
    assert s.dimension("x").exponent_of("L") == MAX_EXPONENT
    assert s.dimension("y").exponent_of("T") == Fraction(-1, MAX_DENOMINATOR)


@pytest.mark.parametrize("bad", [float("inf"), float("-inf"), float("nan"), True, None, "x", np.bool_(True)])
def test_non_numbers_in_mappings(bad):
    with pytest.raises(pt.NumberError) as info:
        pt.System({"x": {"L": bad}})
    assert info.value.culprit is bad or repr(info.value.culprit) == repr(bad)
    assert "'x'" in str(info.value)


def test_decimal_in_mapping_is_the_decimal_written():
    assert pt.System({"x": {"L": 0.1}}).dimension("x") == pt.Dimension.parse("L^(1/10)")
    assert pt.System({"x": {"L": np.float64(0.5)}}).dimension("x") == pt.Dimension.parse("L^(1/2)")


def test_base_dimensions_string_is_refused():
    with pytest.raises(pt.InvalidRequestError, match="'LT'"):
        pt.System({"x": "L"}, base_dimensions="LT")


@pytest.mark.parametrize("irrational", [sympy.pi, sympy.sqrt(2), sympy.E])
def test_irrational_exponents_are_refused(irrational):
    with pytest.raises(pt.NumberError):
        pt.System({"x": {"L": irrational}})


@pytest.mark.parametrize(("letter", "unit"), [("N", "newton"), ("J", "joule"), ("A", "ampere")])
def test_unit_lookalike_letters_are_not_silent(letter, unit):
    with pytest.raises(pt.DimensionSyntaxError) as info:
        pt.System({"F": letter, "x": "L"})
    assert unit in str(info.value)
    assert "base_dimensions" in str(info.value)


def test_opt_in_letters_in_a_mapping_are_not_silent():
    # the mapping path (not the parser) names the letter and how to declare it
    with pytest.raises(pt.InvalidRequestError) as info:
        pt.System({"F": {"N": 1}})
    assert "base_dimensions=(..., 'N')" in str(info.value)
    with pytest.raises(pt.InvalidRequestError) as info:
        pt.System({"F": {"J": 1, "A": 2}})
    assert "base_dimensions=(..., 'J')" in str(info.value)
    assert info.value.culprit == "J"


def test_opt_in_letters_work_when_declared():
    s = pt.System({"n": "N", "a": "A", "x": "L"}, base_dimensions=("M", "L", "T", "N", "A"))
    assert s.base_dimensions == ("L", "N", "A")
    assert s.rank == 3


def test_from_units_declares_what_pint_names():
    s = pt.System.from_units({"c": "mol/m^3", "F": "N"})
    assert str(s.dimension("c")) == "L^-3 N"
    assert str(s.dimension("F")) == "M L T^-2"
    a = pt.System.from_units({"k": "N*m/rad"}, angle_as_base=True)
    assert str(a.dimension("k")) == "M L^2 T^-2 A^-1"


def test_exponents_near_two_to_the_59_are_refused_by_name():
    # the enumeration on this very matrix, whose determinant is 2^64: tests/test_bases.py
    a, b, c = (2**27 + 1) * 2**32, (2**27 + 2) * 2**32, 2**59
    with pytest.raises(pt.errors.LimitError, match="exceeds the limit"):
        pt.System({"a": {"L": a, "T": b}, "b": {"L": c, "T": a}})


def test_default_repeaters_need_time_when_the_rest_do_not_span():
    system = pt.System({"t": "T", "m": "M", "l": "L", "x": "L"})
    assert system.default_repeating() == ("t", "m", "l")  # the first basis: every basis holds t
    assert system.pi_groups().repeating == ("t", "m", "l")


@settings(max_examples=100, deadline=None)
@given(
    systems(exponent=st.sampled_from([-2, -1, 0, 0, 1, 2, Fraction(1, 2)]), max_vars=7),
    st.booleans(),
    st.integers(0, 7),
)
def test_pi_groups_equal_sympy_solutions(system, with_time, at):
    if with_time:  # a variable of dimension time, anywhere in the order
        items = [(n, system.dimension(n)) for n in system.variables]
        items.insert(min(at, len(items)), ("t", pt.Dimension({"T": 1})))
        system = pt.System(items)
    every = oracle_bases(system)
    timelike = {n for n in system.variables if system.dimension(n) == pt.Dimension({"T": 1})}
    avoiding = [b for b in every if not timelike & set(b)]
    default = (avoiding or every)[0]
    assert system.default_repeating() == default
    groups = system.pi_groups()
    assert groups.repeating == default
    assert [tuple(g.exponents.items()) for g in groups] == oracle_groups(system, default)
    for basis in every[:3]:
        assert [tuple(g.exponents.items()) for g in system.pi_groups(repeating=basis[::-1])] == oracle_groups(
            system, basis[::-1]
        )


@settings(max_examples=100, deadline=None)
@given(
    st.lists(
        st.tuples(st.sampled_from(["M", "L", "T", "Theta", "I", "N", "J", "A", "Q", "kg"]), st.integers(-120, 120)),
        min_size=1,
        max_size=4,
    ),
    st.booleans(),
)
def test_quick_formula_reader_agrees_with_the_parser(factors, spaced):
    text = (" " if spaced else "  ").join(f"{b}^{p}" if p != 1 else b for b, p in factors)
    try:
        expected = pt.Dimension.parse(text)
    except pt.PiTheoremError as err:
        with pytest.raises(type(err)):
            pt.System({"x": text})
        return
    assert pt.System({"x": text}).dimension("x") == expected


def test_rank_deficient_system_uses_rank_repeaters():
    # only force and length occur: rank 2 inside M, L, T
    s = pt.System({"F1": "M L T^-2", "F2": "M L T^-2", "a": "L", "b": "L"})
    assert s.rank == 2
    assert s.n_groups == 2
    assert s.bases() == [("F1", "a"), ("F1", "b"), ("F2", "a"), ("F2", "b")]
    groups = s.pi_groups(repeating=("F1", "a"))
    assert [g.exponents for g in groups] == [{"F1": -1, "F2": 1}, {"a": -1, "b": 1}]


def test_default_repeaters_avoid_time(rod):
    assert "t" not in rod.default_repeating()
    assert rod.pi_groups().repeating == rod.default_repeating()


def test_from_units_matches_formulas():
    s = pt.System.from_units(
        {"m": "kg", "l": "m", "g": "m/s^2", "k_theta": "N*m/rad", "c_theta": "N*m*s/rad", "t": "s"}
    )
    assert (
        s.dimensions
        == pt.System(
            {"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "c_theta": "M L^2 T^-1", "t": "T"}
        ).dimensions
    )


def test_from_units_angle_as_base():
    s = pt.System.from_units({"k_theta": "N*m/rad", "theta": "rad"}, angle_as_base=True)
    assert str(s.dimension("k_theta")) == "M L^2 T^-2 A^-1"
    assert str(s.dimension("theta")) == "A"


@pytest.mark.parametrize(("formula", "culprit"), BAD_FORMULAS[:6])
def test_bad_formula_in_system_names_variable(formula, culprit):
    with pytest.raises(pt.DimensionSyntaxError) as info:
        pt.System({"ok": "L", "bad_one": formula})
    assert "'bad_one'" in str(info.value)
    assert culprit in str(info.value)


BAD_SYSTEMS = [
    ({}, pt.EmptySystemError, "at least one variable"),
    ([], pt.EmptySystemError, "at least one variable"),
    ([("a", "L"), ("a", "T")], pt.DuplicateVariableError, "'a'"),
    ({"2x": "L"}, pt.InvalidRequestError, "'2x'"),
    ({"a b": "L"}, pt.InvalidRequestError, "'a b'"),
    ({"a": 3}, pt.InvalidRequestError, "'a'"),
    ({"a": None}, pt.InvalidRequestError, "'a'"),
    ({"a": {"L": "x"}}, pt.InvalidRequestError, "'a'"),
    ({"a": {"Q": 1}}, pt.InvalidRequestError, "'Q'"),
    (42, pt.InvalidRequestError, "int"),
    ([("a",)], pt.InvalidRequestError, "('a',)"),
]


@pytest.mark.parametrize(("variables", "kind", "culprit"), BAD_SYSTEMS)
def test_bad_system(variables, kind, culprit):
    with pytest.raises(kind) as info:
        pt.System(variables)
    assert culprit in str(info.value)


def test_bad_base_dimension_list():
    with pytest.raises(pt.DuplicateVariableError, match="'M'"):
        pt.System({"a": "M"}, base_dimensions=("M", "M"))
    with pytest.raises(pt.InvalidRequestError, match="'1x'"):
        pt.System({"a": "M"}, base_dimensions=("M", "1x"))


def test_custom_base_dimension_accepted_when_declared():
    s = pt.System({"q": "Q", "l": "L"}, base_dimensions=("L", "Q"))
    assert s.base_dimensions == ("L", "Q")


BAD_REPEATERS = [
    (("m", "l"), pt.RepeatingCountError, "rank 3"),
    (("m", "l", "k_theta", "t"), pt.RepeatingCountError, "exactly 3"),
    (("m", "l", "mass"), pt.UnknownVariableError, "'mass'"),
    (("m", "m", "t"), pt.DuplicateVariableError, "'m'"),
    (("k_theta", "tau", "m"), pt.DependentRepeatingSetError, "k_theta/tau"),
    (("l", "g", "t"), pt.DependentRepeatingSetError, "l/(g*t**2)"),
    (("m", "l", "theta_r"), pt.DependentRepeatingSetError, "theta_r"),
    ("m", pt.RepeatingCountError, "('m',)"),
    ((1, 2, 3), pt.InvalidRequestError, "1"),
    (5, pt.InvalidRequestError, "5"),
]


@pytest.mark.parametrize(("repeating", "kind", "culprit"), BAD_REPEATERS)
def test_bad_repeaters(repeating, kind, culprit):
    rod = pt.System(ROD)
    with pytest.raises(kind) as info:
        rod.pi_groups(repeating=repeating)
    assert culprit in str(info.value)


def test_bad_bases_arguments():
    rod = pt.System(ROD)
    with pytest.raises(pt.UnknownVariableError, match="'time'"):
        rod.bases(exclude=("time",))
    with pytest.raises(pt.InvalidRequestError, match="'t'"):
        rod.bases(exclude=("t",), require=("t",))
    with pytest.raises(pt.DependentRepeatingSetError, match="k_theta"):
        rod.bases(require=("k_theta", "tau"))
    with pytest.raises(pt.RepeatingCountError):
        rod.count_bases(require=("m", "l", "t", "g"))


def test_bad_units():
    with pytest.raises(pt.UnitError, match="'furlongs_per_blob'"):
        pt.System.from_units({"v": "furlongs_per_blob"})
    with pytest.raises(pt.UnitError, match="'x'"):
        pt.System.from_units({"x": 3})
    with pytest.raises(pt.UnitError, match=re.escape("'kg**'")):
        pt.System.from_units({"m": "kg**"})


def test_an_unknown_variables_dimension_is_named(rod):
    with pytest.raises(pt.UnknownVariableError, match="'q'"):
        rod.dimension("q")


@settings(max_examples=60, deadline=None)
@given(systems(), st.data())
def test_rows_are_the_dimension_matrix_over_the_names_asked(system, data):
    names = data.draw(st.lists(st.sampled_from(system.variables), unique=True))
    # the oracle: each variable's Dimension, read base by base
    expected = [[system.dimension(n).exponent_of(b) for n in names] for b in system.base_dimensions]
    assert system.rows(names) == expected
    assert system.rows() == [
        [Fraction(int(x.p), int(x.q)) for x in system.matrix.row(i)] for i in range(len(system.base_dimensions))
    ]


def test_rows_refuse_an_unknown_name():
    with pytest.raises(pt.UnknownVariableError, match="unknown variable 'mass'"):
        pt.System(ROD).rows(["m", "mass"])


# -- from_units: pint's float exponents under the float rule, never rounded to a nearby fraction


@pytest.mark.parametrize(
    ("unit", "exponent"),
    [
        ("m**1e-7", Fraction(1, 10**7)),  # was dimensionless
        ("m**0.3333333", Fraction(3333333, 10**7)),  # was 1/3
        ("m**(1/3)", Fraction(1, 3)),  # pint's 0.3333333333333333, a computed float
        ("m**(2/7)", Fraction(2, 7)),
        ("m**1.5", Fraction(3, 2)),
        ("m**(1/1000)", Fraction(1, 1000)),
    ],
)
def test_from_units_reads_exponents_by_the_float_rule(unit, exponent):
    assert pt.System.from_units({"x": unit}).dimension("x") == pt.Dimension({"L": exponent})


@pytest.mark.parametrize("unit", ["m**(2**0.5)", "m**(3**(1/3))", "s**(0.1+0.2)", "kg**(2**-0.5)"])
def test_from_units_refuses_an_irrational_power_by_name(unit):
    # issue 33: 2**0.5 was read as 131836323/93222358, the simplest fraction that rounds to its float
    with pytest.raises(pt.NumberError, match="must be a rational number") as info:
        pt.System.from_units({"x": unit})
    assert unit in str(info.value)
    assert "may not exceed 1000" in str(info.value)


@pytest.mark.parametrize(
    ("unit", "power"),
    [("m**(1/3)", Fraction(1, 3)), ("m**(2/7)", Fraction(2, 7)), ("m**(-997/991)", Fraction(-997, 991))],
)
def test_from_units_reads_a_computed_rational_power_as_that_fraction(unit, power):
    assert pt.System.from_units({"x": unit}).dimension("x").exponent_of("L") == power


def test_from_units_refuses_a_power_it_cannot_hold_exactly():
    # 1/1000001 prints as 9.99999000001e-07 (12 digits): that decimal's denominator 10^18 is beyond the limit,
    # refused by name rather than read as 1/1000000
    with pytest.raises(pt.LimitError, match="denominator"):
        pt.System.from_units({"x": "m**(1/1000001)"})


@pytest.mark.parametrize(
    ("unit", "error", "fragment"),
    [
        ("m**inf", pt.NumberError, "finite"),
        ("m**-1e400", pt.NumberError, "finite"),
        ("m**nan", pt.NumberError, "finite"),
        ("kg^nan/N", pt.NumberError, "finite"),  # pint loops forever on that one
        ("m**100000", pt.LimitError, "1000"),
        ("m**1e-13", pt.LimitError, "denominator"),
    ],
)
def test_from_units_refuses_exponents_beyond_the_limits_by_name(unit, error, fragment):
    with pytest.raises(error, match=fragment) as info:
        pt.System.from_units({"x": unit})
    assert unit in str(info.value)


@pytest.mark.parametrize("unit", ["m^-1/2", "m**-1/2", "kg*m^2/2", "m^0.5 / 3"])
def test_from_units_refuses_a_power_divided_by_a_number_as_dimension_parse_does(unit):
    with pytest.raises(pt.UnitError, match="ambiguous"):
        pt.System.from_units({"x": unit})
    with pytest.raises(pt.DimensionSyntaxError):
        pt.Dimension.parse(unit.replace("kg", "M").replace("m", "L"))


def test_from_units_still_reads_a_power_divided_by_a_unit():
    s = pt.System.from_units({"a": "m^2/s", "b": "m^(-1/2)", "c": "m**2/(s*kg)"})
    assert s.dimension("a") == pt.Dimension.parse("L^2/T")
    assert s.dimension("b") == pt.Dimension.parse("L^(-1/2)")
    assert s.dimension("c") == pt.Dimension.parse("L^2/(T M)")


@pytest.mark.parametrize("bad", [3, "m", ["m"], None])
def test_from_units_takes_a_mapping(bad):
    with pytest.raises(pt.UnitError, match="must map each variable"):
        pt.System.from_units(bad)


def test_from_units_messages_in_full():
    with pytest.raises(pt.UnitError) as caught:
        pt.System.from_units({"x": "m^-1/2"})
    assert str(caught.value) == (
        "the unit 'm^-1/2' of 'x' is ambiguous: '^-1/2' is a power divided by a number; "
        "write a fractional power in brackets, such as 'm^(-1/2)'"
    )
    # a unit text of up to 40 characters is quoted in the message, a longer one is not
    forty = "m**inf" + "*s" * 17
    longer = "m**inf" + "*s" * 16 + "*kg"
    assert (len(forty), len(longer)) == (40, 41)
    with pytest.raises(pt.NumberError) as caught:
        pt.System.from_units({"x": forty})
    assert str(caught.value).startswith(f"the exponent of meter in the unit {forty!r} of 'x' must be a finite")
    with pytest.raises(pt.NumberError) as caught:
        pt.System.from_units({"x": longer})
    assert str(caught.value).startswith("the exponent of meter in the unit of 'x' must be a finite")


def test_from_units_reads_a_bare_number_or_nothing_as_dimensionless():
    system = pt.System.from_units({"x": "3", "y": "", "z": "2 m", "w": "0.5"})
    assert system.dimension("x") == system.dimension("y") == system.dimension("w") == pt.Dimension.parse("1")
    assert system.dimension("z") == pt.Dimension.parse("L")


def test_systems_differ_by_dimensions_as_well_as_names():
    assert pt.System({"x": "L"}) != pt.System({"x": "T"})
    assert pt.System({"x": "L"}) != pt.System({"y": "L"})
    assert pt.System({"x": "L", "t": "T"}) == pt.System({"x": "L", "t": "T"})
    systems = [pt.System({"x": d}) for d in ("L", "T", "M", "L/T", "M L")] + [pt.System({n: "L"}) for n in "abc"]
    assert len({hash(s) for s in systems}) > 1
    assert hash(pt.System({"x": "L", "t": "T"})) == hash(pt.System({"x": "L", "t": "T"}))


def test_dimensionless_products_span_the_null_space():
    for dims in (
        {"l": "L", "t": "T", "v": "L/T"},
        {"m": "M", "l": "L", "g": "L T^-2", "t": "T", "k": "M L^2 T^-2"},
        {"x": "1", "y": "1"},
        {"a": "L", "b": "L^2"},
    ):
        system = pt.System(dims)
        # the dimension matrix by hand, from the formulas' exponents
        bases = ["M", "L", "T"]
        matrix = sympy.Matrix([[pt.Dimension.parse(d).exponent_of(b) for d in dims.values()] for b in bases])
        products = system.dimensionless_products()
        assert len(products) == len(dims) - matrix.rank()
        for vector in products:
            assert len(vector) == len(dims)
            assert all(isinstance(x, Fraction) for x in vector)
            assert matrix * sympy.Matrix([sympy.Rational(x.numerator, x.denominator) for x in vector]) == sympy.zeros(
                3, 1
            )
        if products:
            assert sympy.Matrix([[sympy.Rational(str(x)) for x in v] for v in products]).rank() == len(products)


def test_from_units_angles_malformed_and_unknown_dimensions():
    assert pt.System.from_units({"w": "rad/s"}, angle_as_base=True).dimension("w") == pt.Dimension({"A": 1, "T": -1})
    assert pt.System.from_units({"w": "rad/s"}).dimension("w") == pt.Dimension.parse("1/T")
    assert pt.System.from_units({"x": "m"}, angle_as_base=True).dimension("x") == pt.Dimension.parse("L")
    with pytest.raises(pt.LimitError) as caught:
        pt.System.from_units({"x": "rad**1001"}, angle_as_base=True)
    assert str(caught.value) == (
        "the exponent of radian in the unit 'rad**1001' of 'x' is 1001: its magnitude exceeds the limit 1000"
    )
    for text in ("m**", "m/", "*m"):
        with pytest.raises(pt.UnitError) as caught:
            pt.System.from_units({"x": text})
        assert str(caught.value) == f"cannot read the unit {text!r} of 'x': malformed unit expression"
    with pytest.raises(pt.UnitError) as caught:
        pt.System.from_units({"x": "pixel"})
    assert str(caught.value) == "unit 'pixel' of 'x' has dimension [printing_unit], which pitheorem does not know"


def test_a_base_outside_the_declared_ones_is_refused_even_in_a_simple_formula():
    for formula in ("M", "M L", "L T^-2 M^2"):
        with pytest.raises(pt.DimensionSyntaxError, match="unknown base dimension 'M'"):
            pt.System({"x": formula}, base_dimensions=("L", "T"))
    assert pt.System({"x": "L T^-2"}, base_dimensions=("L", "T")).dimension("x") == pt.Dimension({"L": 1, "T": -2})


def test_unknown_names_in_bases_and_pi_groups_are_named_with_the_argument():
    lt = pt.System({"l": "L", "t": "T", "v": "L/T"})
    for call, argument in (
        (lambda: lt.bases(require=("q",)), "require"),
        (lambda: lt.bases(exclude=("q",)), "exclude"),
        (lambda: lt.pi_groups(["q", "l"]), "repeating"),
    ):
        with pytest.raises(pt.UnknownVariableError) as caught:
            call()
        assert str(caught.value) == f"unknown variable 'q' in {argument}; the system has l, t, v"


def test_basis_and_dimension_refusals_in_full():
    lt = pt.System({"l": "L", "t": "T", "v": "L/T"})
    cases = [
        (
            lambda: lt.bases(require=("l", "t", "v")),
            "repeating set ('l', 't', 'v') has 3 variables, but the dimension matrix has rank 2: choose exactly 2 "
            "variables with independent dimensions (System.bases() lists every valid choice)",
            ("l", "t", "v"),
        ),
        (
            lambda: pt.System({"a": "L", "b": "T", "c": "L/T", "d": "M"}).bases(require=("a", "b", "c")),
            "repeating set ('a', 'b', 'c') is dependent: a/(b*c) is dimensionless, so these variables cannot serve as "
            "a basis; System.bases() lists every valid choice",
            ("a", "b", "c"),
        ),
        (
            lambda: lt.check_names(("l", "l"), "fixed"),
            "variable 'l' is named twice in fixed; name each variable once",
            "l",
        ),
        (lambda: lt.index("q"), "unknown variable 'q'; the system has l, t, v", "q"),
        (lambda: pt.System({"x": {3: 1}}), "dimension of 'x' must map base names to numbers, got the key 3", 3),
        (
            lambda: pt.System({"x": {"Q": 1}}),
            "dimension of 'x' uses base 'Q'; allowed bases are M, L, T, Theta, I",
            "Q",
        ),
        (
            lambda: pt.System({"x": {"N": 1}}),
            "dimension of 'x' uses base 'N'; allowed bases are M, L, T, Theta, I; 'N' is opt-in because it is also "
            "an SI unit symbol: declare it with base_dimensions=(..., 'N')",
            "N",
        ),
    ]
    for call, message, culprit in cases:
        with pytest.raises(pt.PiTheoremError) as caught:
            call()
        assert str(caught.value) == message
        assert caught.value.culprit == culprit


def test_a_name_given_twice_is_named_with_where():
    cases = [
        (
            lambda: pt.System({"x": "L"}, base_dimensions=("T", "L", "L")),
            "variable 'L' is named twice in base_dimensions; name each variable once",
            "L",
        ),
        (
            lambda: pt.System([("x", "L"), ("x", "T")]),
            "variable 'x' is named twice in the system; name each variable once",
            "x",
        ),
    ]
    for call, message, culprit in cases:
        with pytest.raises(pt.DuplicateVariableError) as caught:
            call()
        assert str(caught.value) == message
        assert caught.value.culprit == culprit


# -- a system's own default repeaters (an engine model's: the robot's numbers) -----------------


def test_a_system_made_with_repeaters_uses_them_when_given_none(rod):
    own = pt.System(rod.dimensions, repeating=("m", "l", "t"))
    assert own.default_repeating() == ("m", "l", "t")
    assert own.pi_groups().repeating == ("m", "l", "t")
    assert own.pi_groups().equivalent(own.pi_groups(repeating=("m", "l", "t")))
    # each group: its own variable over the oracle's product of the repeaters
    assert [tuple(sorted(g.exponents.items())) for g in own.pi_groups()] == [
        tuple(sorted(pairs)) for pairs in oracle_groups(rod, ("m", "l", "t"))
    ]
    assert rod.default_repeating() != own.default_repeating()  # the plain system avoids time
    assert own != rod  # the repeaters are part of the value
    assert own.with_repeating(None) == rod
    assert rod.with_repeating(("m", "l", "t")) == own
    assert "repeating=('m', 'l', 't')" in repr(own)


def test_a_systems_own_repeaters_survive_pickling_and_are_checked(rod):
    import pickle

    own = rod.with_repeating(("g", "l", "m"))
    back = pickle.loads(pickle.dumps(own))
    assert back == own
    assert back.default_repeating() == ("g", "l", "m")
    with pytest.raises(pt.RepeatingCountError):
        rod.with_repeating(("m", "l"))
    with pytest.raises(pt.DependentRepeatingSetError, match="t"):
        rod.with_repeating(("g", "l", "t"))  # g t^2 / l is dimensionless
    with pytest.raises(pt.UnknownVariableError, match="q"):
        pt.System({"l": "L"}, repeating=("q",))


@given(systems(), st.data())
@settings(max_examples=60, deadline=None)
def test_first_basis_is_the_first_of_the_bases_that_avoid_the_names(system, data):
    exclude = data.draw(st.lists(st.sampled_from(system.variables), unique=True))
    expected = next(iter(oracle_bases(system, exclude=exclude)), None)
    assert system.first_basis(exclude=exclude) == expected
