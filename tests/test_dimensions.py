"""The dimension formula parser and the Dimension value type."""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem.exact import (
    MAX_FORMULA_LENGTH,
    MAX_NESTING,
)
from tests.conftest import BAD_FORMULAS, BASES, rational_exponent

TORQUE = pt.Dimension({"M": 1, "L": 2, "T": -2})


@pytest.mark.parametrize(
    "formula",
    ["M L^2 T^-2", "M*L**2/T**2", "M L**2 T**-2", "M*L^2*T^(-2)", "L^2 M / T / T", "(M L^2)/(T^2)", " M  L^2 T^-2 "],
)
def test_torque_spellings(formula):
    assert pt.Dimension.parse(formula) == TORQUE


@pytest.mark.parametrize("formula", ["1", "", "  ", "L/L", "M^0", "1/1"])
def test_dimensionless_spellings(formula):
    assert pt.Dimension.parse(formula).is_dimensionless


def test_rational_and_decimal_exponents():
    assert pt.Dimension.parse("L^(1/2)").exponent_of("L") == Fraction(1, 2)
    assert pt.Dimension.parse("L^0.25").exponent_of("L") == Fraction(1, 4)
    assert pt.Dimension.parse("T^(-3/2)").exponent_of("T") == Fraction(-3, 2)


def test_value_semantics():
    assert hash(pt.Dimension.parse("L T^-1")) == hash(pt.Dimension({"T": -1, "L": 1}))
    assert pt.Dimension.parse("L") * pt.Dimension.parse("T^-1") == pt.Dimension.parse("L/T")
    assert (TORQUE**2).exponent_of("M") == 2
    assert str(TORQUE) == "M L^2 T^-2"
    assert eval(repr(TORQUE), {"Dimension": pt.Dimension}) == TORQUE
    with pytest.raises(AttributeError):
        TORQUE.exponents = {}  # type: ignore[misc]


def test_display_order_follows_base_list():
    assert pt.Dimension.parse("T L M").base_dimensions == ("M", "L", "T")
    assert pt.Dimension.parse("A Theta M", base_dimensions=("M", "Theta", "A")).base_dimensions == ("M", "Theta", "A")
    assert pt.Dimension.parse("A Theta M", base_dimensions=("A", "Theta", "M")).base_dimensions == ("M", "Theta", "A")


def test_nesting_limit():
    ok = "(" * MAX_NESTING + "L" + ")" * MAX_NESTING
    assert pt.Dimension.parse(ok) == pt.Dimension({"L": 1})
    with pytest.raises(pt.LimitError, match=str(MAX_NESTING)):
        pt.Dimension.parse("(" * (MAX_NESTING + 1) + "L" + ")" * (MAX_NESTING + 1))
    with pytest.raises(pt.LimitError):  # was RecursionError
        pt.Dimension.parse("(" * 5000 + "L" + ")" * 5000)


def test_base_names_must_be_strings():
    with pytest.raises(pt.InvalidRequestError, match="must be identifiers") as info:
        pt.Dimension({1: 2})
    assert info.value.culprit == 1


def test_text_after_a_complete_formula_is_named():
    with pytest.raises(pt.DimensionSyntaxError, match="unexpected '\\)' after a complete formula"):
        pt.Dimension.parse("L T)")


def test_double_sign_is_a_syntax_error():
    # was read as L^2 (mutation survivor: the parser reading --2 as -2 went unnoticed)
    for text in ("L^--2", "L^+-2", "L^(--1/2)"):
        with pytest.raises(pt.DimensionSyntaxError):
            pt.Dimension.parse(text)
    assert pt.Dimension.parse("L^-2").exponent_of("L") == -2
    assert pt.Dimension.parse("L^+2").exponent_of("L") == 2
    assert pt.Dimension.parse("L^(-1/-2)").exponent_of("L") == Fraction(1, 2)


def test_formula_over_the_length_limit_shows_its_first_twenty_characters():
    text = "L*" * (MAX_FORMULA_LENGTH // 2 + 1)
    with pytest.raises(pt.LimitError) as info:
        pt.Dimension.parse(text)
    assert info.value.value == "L*L*L*L*L*L*L*L*L*L*..."
    assert str(len(text)) in info.value.limit


def test_formula_length_limit_is_ten_thousand_characters_inclusive():
    # the documented limit, written out: the test must not read it from the code it checks
    assert MAX_FORMULA_LENGTH == 10_000
    at_limit = "L" + " " * 9_999
    assert pt.Dimension.parse(at_limit) == pt.Dimension({"L": 1})
    with pytest.raises(pt.LimitError, match="its length 10001 exceeds the limit of 10000 characters"):
        pt.Dimension.parse(at_limit + " ")


def test_exponents_have_at_most_forty_digits():
    assert pt.Dimension.parse("L^" + "0" * 39 + "1") == pt.Dimension({"L": 1})  # 40 digits, value 1
    with pytest.raises(pt.LimitError, match="more than 40 digits") as info:
        pt.Dimension.parse("L^" + "0" * 40 + "1")
    assert info.value.value == "0" * 20 + "..."


@settings(max_examples=60, deadline=None)
@given(st.dictionaries(st.sampled_from(BASES), rational_exponent, max_size=4))
def test_dimension_string_round_trip(powers):
    dim = pt.Dimension(powers)
    assert pt.Dimension.parse(str(dim)) == dim
    assert all(isinstance(p, Fraction) and p != 0 for p in dim.exponents.values())


def test_base_dimensions_string_is_refused():
    with pytest.raises(pt.InvalidRequestError, match="'LT'"):
        pt.Dimension.parse("L", base_dimensions="LT")


@pytest.mark.parametrize(("formula", "culprit"), BAD_FORMULAS)
def test_bad_formula(formula, culprit):
    with pytest.raises(pt.DimensionSyntaxError) as info:
        pt.Dimension.parse(formula)
    assert culprit in str(info.value)
    assert 0 <= info.value.position <= len(formula)


# -- the limits hold for totals, and the arguments are checked by name (issue 23's reproducers)


@pytest.mark.parametrize(
    "build",
    [
        lambda: pt.Dimension({"L": Fraction(1, 10**5000)}),  # str() would hit Python's digit limit
        lambda: pt.Dimension.parse("L^1000 L^1000"),
        lambda: pt.Dimension.parse("L^1000 * L"),
        lambda: pt.Dimension.parse("L") ** Fraction(1, 10**13),
        lambda: pt.Dimension.parse("L") ** 10**5000,
        lambda: pt.Dimension([("L", 600), ("L", 600)]),
        lambda: pt.Dimension(pt.Dimension.parse("L^999").exponents | {"L": 1001}),
    ],
)
def test_exponent_limits_hold_for_the_total(build):
    with pytest.raises(pt.LimitError, match=r"exponent of 'L'|the power of a dimension"):
        build()


def test_many_factors_each_within_the_limits_cannot_pass_together():
    primes = [p for p in range(2, 2500) if all(p % d for d in range(2, int(p**0.5) + 1))][:360]
    formula = " ".join(f"L^(1/{p})" for p in primes)
    assert len(formula) < 10_000  # within the length limit: it is the denominator that is refused
    with pytest.raises(pt.LimitError, match="denominator"):
        pt.Dimension.parse(formula)


def test_the_algebra_of_dimensions_is_held_to_the_limits():
    # issue 33: every Dimension lies within the limits, however it is reached; products and powers up to them stay
    assert (pt.Dimension.parse("L^999") * pt.Dimension.parse("L")).exponents == {"L": 1000}
    assert (pt.Dimension.parse("L^-999") / pt.Dimension.parse("L")).exponents == {"L": -1000}
    assert (pt.Dimension.parse("L^(4/3)") ** 750).exponents == {"L": 1000}
    assert (pt.Dimension.parse("L^(1/1000)") ** Fraction(1, 10**9)).exponents == {"L": Fraction(1, 10**12)}
    beyond = [
        lambda: pt.Dimension.parse("L^999") * pt.Dimension.parse("L^2"),
        lambda: pt.Dimension.parse("L^999") / pt.Dimension.parse("L^-2"),
        lambda: pt.Dimension.parse("L^(4/3)") ** 751,
        lambda: pt.Dimension.parse("L^(1/1000)") ** Fraction(1, 10**10),
        lambda: pt.Dimension.parse("(L^1000)^1000"),
        lambda: pt.Dimension.parse("(L^(1/1000000))^(1/1000000000)"),
    ]
    for build in beyond:
        with pytest.raises(pt.LimitError, match="the exponent of 'L'"):
            build()
    with pytest.raises(pt.LimitError, match="the power of a dimension is 1001: its magnitude exceeds the limit 1000"):
        pt.Dimension.parse("L") ** 1001


def test_a_power_is_an_exponent_however_large_its_numerator():
    # issue 33: 6851352532656/12727076077 (about 538) was refused because its numerator passed 10^12
    p = Fraction(6851352532656, 12727076077)
    dim = pt.Dimension({"T": p})
    assert pt.Dimension.parse(str(dim)) == dim
    assert pt.Dimension.parse("T") ** p == dim
    assert pt.System({"x": str(dim)}).dimension("x") == dim


def test_exponents_at_the_limits_are_kept():
    assert pt.Dimension.parse("L^500 L^500").exponents == {"L": 1000}
    assert pt.Dimension({"L": Fraction(1, 10**12)}).exponents == {"L": Fraction(1, 10**12)}
    assert str(pt.Dimension.parse("L^1000 / L^1000")) == "1"


@pytest.mark.parametrize("bad", [3, "L", b"L", 1.5, None, [("L",)], [3], [("L", 1, 2)]])
def test_a_dimension_takes_a_mapping_or_pairs_and_names_anything_else(bad):
    with pytest.raises(pt.InvalidRequestError, match="a Dimension takes a mapping"):
        pt.Dimension(bad)


@pytest.mark.parametrize("name", ["1L", "", "L T", "L-1", "L^2"])
def test_base_names_must_be_identifiers(name):
    with pytest.raises(pt.InvalidRequestError, match="identifiers") as info:
        pt.Dimension({name: 1})
    assert info.value.culprit == name


def test_a_dimension_from_pairs_equals_the_one_from_a_mapping():
    assert pt.Dimension([("L", 1), ("T", -2)]) == pt.Dimension({"L": 1, "T": -2}) == pt.Dimension.parse("L/T^2")


@pytest.mark.parametrize("bad", [3, None, 1.5, ["L"]])
def test_parse_takes_a_string_only(bad):
    with pytest.raises(pt.DimensionSyntaxError, match="expected a string"):
        pt.Dimension.parse(bad)


def test_base_dimensions_that_are_no_list_are_named():
    with pytest.raises(pt.InvalidRequestError, match="must be a list of names"):
        pt.Dimension.parse("L", base_dimensions=3)


def test_a_dimension_multiplies_and_divides_only_by_dimensions():
    length = pt.Dimension.parse("L")
    for operation in (lambda: length * 2, lambda: length / 2, lambda: 2 * length):
        with pytest.raises(TypeError):
            operation()


# -- whole messages and culprits (each assertion kills a mutmut survivor that changed one of them)

_NUMBER = "a finite real number (int, float, Fraction, numpy or sympy number, or a string such as '0.1' or '1/3')"


@pytest.mark.parametrize(
    ("build", "error", "first_line", "culprit"),
    [
        (
            lambda: pt.Dimension.parse("L Q"),
            pt.DimensionSyntaxError,
            "cannot parse dimension 'L Q' at position 2: unknown base dimension 'Q'; valid base dimensions are M, L, T, "
            "Theta, I (declare others with base_dimensions=..., or give units with System.from_units); found 'Q'",
            "Q",
        ),
        (
            lambda: pt.Dimension.parse("L 2"),
            pt.DimensionSyntaxError,
            "cannot parse dimension 'L 2' at position 2: a bare "
            "number '2' has no dimension; only '1' may stand alone; found '2'",
            "2",
        ),
        (
            lambda: pt.Dimension.parse("(L"),
            pt.DimensionSyntaxError,
            "cannot parse dimension '(L' at position 2: expected "
            "')' to close the bracket; found the end of the formula",
            "",
        ),
        (
            lambda: pt.Dimension.parse("L^(1"),
            pt.DimensionSyntaxError,
            "cannot parse dimension 'L^(1' at position 4: "
            "expected ')' to close the exponent; found the end of the formula",
            "",
        ),
        (
            lambda: pt.Dimension.parse("L^(1/0)"),
            pt.DimensionSyntaxError,
            "cannot parse dimension 'L^(1/0)' at position 5: division by zero in exponent; found '0'",
            "0)",
        ),
        (
            lambda: pt.Dimension.parse("L^x"),
            pt.DimensionSyntaxError,
            "cannot parse dimension 'L^x' at position 2: "
            "expected a number as exponent, e.g. ^2, ^-1 or ^(1/2); found 'x'",
            "x",
        ),
        (
            lambda: pt.Dimension.parse("L*"),
            pt.DimensionSyntaxError,
            "cannot parse dimension 'L*' at position 2: formula ends too early; found the end of the formula",
            "",
        ),
        (
            lambda: pt.Dimension.parse("L*)"),
            pt.DimensionSyntaxError,
            "cannot parse dimension 'L*)' at position 2: expected a base dimension, '1' or '('; found ')'",
            ")",
        ),
        (
            lambda: pt.Dimension.parse(3),
            pt.DimensionSyntaxError,
            "cannot parse dimension '3' at position 0: expected a string, got int",
            "3",
        ),
        (
            lambda: pt.Dimension.parse("L^" + "1" * 41),
            pt.LimitError,
            "an exponent is 11111111111111111111...: it has more than 40 digits",
            "11111111111111111111...",
        ),
        (
            lambda: pt.Dimension.parse("M" * 10_001),
            pt.LimitError,
            "the dimension formula is MMMMMMMMMMMMMMMMMMMM...: its length 10001 exceeds the limit of 10000 characters",
            "MMMMMMMMMMMMMMMMMMMM...",
        ),
        (
            lambda: pt.Dimension.parse("(" * 101 + "L" + ")" * 101),
            pt.LimitError,
            "the dimension formula is ((((((((((((((((((((...: its brackets nest deeper than the limit of 100",
            "((((((((((((((((((((...",
        ),
        (
            lambda: pt.Dimension.parse("L^1001"),
            pt.LimitError,
            "exponent in 'L^1001' is 1001: its magnitude exceeds the limit 1000",
            "1001",
        ),
        (
            lambda: pt.Dimension.parse("L^1001" + " T" * 17),
            pt.LimitError,  # 40 characters: the formula is quoted
            f"exponent in {'L^1001' + ' T' * 17!r} is 1001: its magnitude exceeds the limit 1000",
            "1001",
        ),
        (
            lambda: pt.Dimension.parse("L^1001" + " T" * 17 + " "),
            pt.LimitError,  # 41 characters: it is not
            "an exponent is 1001: its magnitude exceeds the limit 1000",
            "1001",
        ),
        (
            lambda: pt.Dimension.parse("L") ** 10**13,
            pt.LimitError,
            "the power of a dimension is 10000000000000: its magnitude exceeds the limit 1000",
            "10000000000000",
        ),
        (
            lambda: pt.Dimension.parse("L") ** "x",
            pt.NumberError,
            f"the power of a dimension must be {_NUMBER}, got 'x'",
            "x",
        ),
        (lambda: pt.Dimension({"L": "x"}), pt.NumberError, f"the exponent of 'L' must be {_NUMBER}, got 'x'", "x"),
        (
            lambda: pt.Dimension(3),
            pt.InvalidRequestError,
            "a Dimension takes a mapping of base names to exponents, such "
            "as {'L': 1, 'T': -2} (use Dimension.parse for a formula), got 3",
            3,
        ),
        (
            lambda: pt.Dimension("L"),
            pt.InvalidRequestError,
            "a Dimension takes a mapping of base names to exponents, such "
            "as {'L': 1, 'T': -2} (use Dimension.parse for a formula), not the string 'L'",
            "L",
        ),
        (
            lambda: pt.Dimension([("L",)]),
            pt.InvalidRequestError,
            "a Dimension takes a mapping of base names to exponents, "
            "such as {'L': 1, 'T': -2} (use Dimension.parse for a formula), got the entry ('L',)",
            ("L",),
        ),
        (
            lambda: pt.Dimension.parse("L", base_dimensions="LT"),
            pt.InvalidRequestError,
            "base_dimensions must be a list of names such as ('M', 'L', 'T'), not the string 'LT'",
            "LT",
        ),
        (
            lambda: pt.Dimension.parse("L", base_dimensions=3),
            pt.InvalidRequestError,
            "base_dimensions must be a list of names such as ('M', 'L', 'T'), got 3",
            3,
        ),
        (
            lambda: pt.Dimension.parse("L", base_dimensions=["1L"]),
            pt.InvalidRequestError,
            "base dimension names must be identifiers, got '1L'",
            "1L",
        ),
    ],
)
def test_each_refusal_names_the_culprit_and_what_is_valid(build, error, first_line, culprit):
    with pytest.raises(error) as caught:
        build()
    assert str(caught.value).splitlines()[0] == first_line
    assert caught.value.culprit == culprit


def test_brackets_one_after_another_do_not_count_as_nesting():
    # the depth falls back when a bracket closes: 150 groups side by side are fine, 101 nested ones are not,
    # even after groups side by side
    assert pt.Dimension.parse("(L)" * 150) == pt.Dimension({"L": 150})
    with pytest.raises(pt.LimitError, match="nest deeper"):
        pt.Dimension.parse("(L)" * 5 + "(" * 101 + "L" + ")" * 101)
    assert pt.Dimension.parse("(L)" * 5 + "(" * 100 + "L" + ")" * 100) == pt.Dimension({"L": 6})


def test_a_one_beside_a_dimension_is_dimensionless():
    assert pt.Dimension.parse("L 1") == pt.Dimension.parse("1 L") == pt.Dimension.parse("L")


# -- products, quotients and powers are remembered (a model file's reader asks the same few thousands of times)

exponent_maps = st.dictionaries(st.sampled_from(BASES), rational_exponent, max_size=4)


def _by_hand(a: dict, b: dict, sign) -> dict:
    """The exponents of a * b**sign, added base by base: the oracle, apart from Dimension's algebra."""
    out = {base: Fraction(p) for base, p in a.items()}
    for base, p in b.items():
        out[base] = out.get(base, Fraction(0)) + Fraction(p) * sign
    return {base: p for base, p in out.items() if p != 0}


@given(exponent_maps, exponent_maps, st.integers(-3, 3))
@settings(max_examples=200)
def test_a_remembered_product_quotient_or_power_is_the_one_computed_by_hand(a, b, k):
    x, y = pt.Dimension(a), pt.Dimension(b)
    for _ in range(2):  # the second time from the memory: the same answers, for equal operands that are new objects
        assert (x * y).exponents == _by_hand(a, b, 1)
        assert (x / y).exponents == _by_hand(a, b, -1)
        assert (x**k).exponents == _by_hand({}, a, k)
        assert (x ** Fraction(k, 2)).exponents == _by_hand({}, a, Fraction(k, 2))
        x, y = pt.Dimension(dict(a)), pt.Dimension(dict(b))


def test_a_result_beyond_the_limits_is_refused_every_time_not_remembered():
    big = pt.Dimension.parse("L^999")
    for _ in range(2):
        with pytest.raises(pt.LimitError, match="the exponent of 'L' is 1001"):
            big * pt.Dimension.parse("L^2")
        with pytest.raises(pt.LimitError, match="the exponent of 'L' is -1001"):
            pt.Dimension.parse("L^-999") / pt.Dimension.parse("L^2")
        with pytest.raises(pt.LimitError, match="the power of a dimension is 1001"):
            pt.Dimension.parse("L") ** 1001
        with pytest.raises(pt.LimitError, match="the exponent of 'L' is 1998"):
            big**2
    assert (pt.Dimension.parse("L") ** 1000).exponents == {"L": 1000}
    assert (pt.Dimension.parse("L") ** -1000).exponents == {"L": -1000}
    with pytest.raises(pt.NumberError, match="not a bool"):  # an int by class, not by type: read and refused
        pt.Dimension.parse("L") ** True
