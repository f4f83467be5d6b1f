"""pitheorem.exact: the one number reader and its limits, against Fractions worked out by hand."""

from __future__ import annotations

import math
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
import sympy
from hypothesis import assume, given
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem.exact import (
    MAX_DENOMINATOR,
    MAX_EXPONENT,
    is_float,
    read_exponent,
    read_number,
    read_positive,
    read_scale_factor,
    read_value,
    short_text,
    simplest_fraction_rounding_to,
)


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (0.1, Fraction(1, 10)),
        (2.5e-3, Fraction(1, 400)),
        (1e22, Fraction(10**22)),
        (-0.0, Fraction(0)),
        (np.float64(0.5), Fraction(1, 2)),
        (np.float32(0.1), Fraction(1, 10)),
        (np.float16(0.25), Fraction(1, 4)),
        (np.int8(-3), Fraction(-3)),
        (np.array(0.2), Fraction(1, 5)),
        ("  -7/21 ", Fraction(-1, 3)),
        ("1e-3", Fraction(1, 1000)),
        (Fraction(2, 6), Fraction(1, 3)),
        (10**40, Fraction(10**40)),
    ],
)
def test_read_number_rule(value, expected):
    assert read_number(value) == expected


@pytest.mark.parametrize("bad", ["1/0", "1e", "0x10", "1.5/2", "", "--1", "nan", "inf", [1], {}, 1j, object()])
def test_read_number_refuses(bad):
    with pytest.raises(pt.NumberError):
        read_number(bad, "the test value")


@pytest.mark.parametrize(
    "bad",
    [
        float("inf"),
        float("-inf"),
        float("nan"),
        np.float32("inf"),
        np.float64("nan"),
        Decimal("Infinity"),
        Decimal("-Infinity"),
        Decimal("NaN"),
        Decimal("sNaN"),
    ],
)
def test_read_number_refuses_non_finite_numbers_of_every_type_by_name(bad):
    with pytest.raises(pt.NumberError, match="the test value must be") as info:
        read_number(bad, "the test value")
    assert info.value.culprit is bad


@pytest.mark.parametrize(
    ("value", "expected"),
    [(2, Fraction(2)), ("1/3", Fraction(1, 3)), (0.5, Fraction(1, 2)), (sympy.Rational(3, 4), Fraction(3, 4))],
)
def test_read_positive_reads_like_read_number(value, expected):
    assert read_positive(value, "the scale factor s") == expected


@pytest.mark.parametrize("bad", [0, -2, "-1/3", 0.0, "big", True, float("inf"), -sympy.sqrt(2)])
def test_read_positive_refuses_everything_but_positive_numbers(bad):
    with pytest.raises(pt.NumberError, match="the scale factor s must be a positive finite number") as info:
        read_positive(bad, "the scale factor s", irrational_ok=True)
    assert info.value.culprit is bad


def test_read_value_keeps_floats_and_makes_the_rest_fractions():
    # float in, float out: the one rule for parameter values
    for value in (9.81, np.float32(0.5), sympy.Float(0.25), sympy.pi):
        assert type(read_value(value, "v")) is float
    assert read_value(sympy.pi, "v") == pytest.approx(3.141592653589793)
    for value, exact in (
        (3, Fraction(3)),
        ("1/3", Fraction(1, 3)),
        (sympy.Rational(1, 7), Fraction(1, 7)),
        (np.int64(-4), Fraction(-4)),
    ):
        got = read_value(value, "v")
        assert got == exact
        assert type(got) is Fraction
    with pytest.raises(pt.NumberError, match="'v'"):
        read_value(True, "'v'")
    assert is_float(np.array([1, 2]))
    assert not is_float("0.5")


def test_number_strings_up_to_a_thousand_characters_are_read():
    # mutation run: the limit 1000 -> 1001 went unnoticed
    assert read_number("1" * 1000) == Fraction(int("1" * 1000))
    with pytest.raises(pt.LimitError, match="at most 1000 characters") as info:
        read_number("1" * 1001)
    assert info.value.value == "1" * 20 + "..."


@pytest.mark.parametrize(
    ("irrational", "printed"),
    [
        (sympy.pi, "3.141592653589793"),
        (sympy.sqrt(2), "1.4142135623730951"),
        (sympy.E, "2.718281828459045"),
    ],
)
def test_irrational_numbers_need_the_opt_in(irrational, printed):
    # an exponent must be rational: pi is refused unless the caller accepts irrationals (values, not exponents);
    # accepted, it is read through its nearest float, whose 16 digits make it a computed float: the simplest
    # fraction rounding to it, far simpler than the printed decimal
    with pytest.raises(pt.NumberError, match="rational number"):
        read_number(irrational)
    read = read_number(irrational, irrational_ok=True)
    assert float(read) == float(printed)
    assert read.denominator < 10**9 < Fraction(printed).denominator


def test_long_exponent_strings_are_shortened_to_forty_characters_in_the_error():
    with pytest.raises(pt.LimitError) as info:
        read_exponent("9" * 45, "the exponent of 'x'")
    assert info.value.value == "9" * 40 + "..."
    with pytest.raises(pt.LimitError) as info:
        read_exponent("9" * 41, "the exponent of 'x'")
    assert info.value.value == "9" * 40 + "..."
    with pytest.raises(pt.LimitError) as info:
        read_exponent("9" * 40, "the exponent of 'x'")
    assert info.value.value == "9" * 40


def test_powers_of_ten_up_to_10000_are_read():
    assert read_number("1e10000") == Fraction(10**10000)
    assert read_number("1e-10000") == Fraction(1, 10**10000)
    for text in ("1e10001", "1e-10001"):
        with pytest.raises(pt.LimitError, match="10\\^10000"):
            read_number(text)


def test_the_float_hint_is_given_only_for_floats():
    # numpy is loaded here; the hint about floats must still follow the value's type
    too_fine = Fraction(1, MAX_DENOMINATOR + 1)
    for exact in (too_fine, f"1/{MAX_DENOMINATOR + 1}"):
        with pytest.raises(pt.LimitError) as info:
            read_exponent(exact, "x")
        assert "float" not in str(info.value)
    for inexact in (1e-13, np.float64(1e-13)):
        with pytest.raises(pt.LimitError, match="a float is read as the decimal"):
            read_exponent(inexact, "x")


def test_short_text_is_exact_below_120_bits_and_a_magnitude_above():
    # numerator and denominator together: 2**117 has 118 bits (+1 for the denominator 1)
    assert short_text(Fraction(2**117)) == str(2**117)
    assert short_text(Fraction(2**118)) == "about 10^36"  # 2**118 = 3.3e35
    assert short_text(Fraction(1, 2**118)) == "about 10^-36"


def test_huge_power_of_ten_string_is_refused_before_it_is_built():
    with pytest.raises(pt.LimitError, match="power of ten"):
        read_exponent("1e99999999", "x")


@pytest.mark.parametrize(
    ("s", "expected"),
    [
        (2, Fraction(2)),
        ("1/2", Fraction(1, 2)),
        (np.int64(3), Fraction(3)),
        (sympy.Rational(3, 4), Fraction(3, 4)),
        (Fraction(10, 4), Fraction(5, 2)),
        ("0.1", Fraction(1, 10)),
    ],
)
def test_read_scale_factor_makes_exact_numbers_fractions(s, expected):
    got = read_scale_factor(s)
    assert got == expected
    assert type(got) is Fraction


def test_read_scale_factor_keeps_floats_and_irrational_numbers():
    for s, expected in ((2.5, 2.5), (np.float32(0.5), 0.5), (sympy.Float(0.25), 0.25)):
        got = read_scale_factor(s)
        assert (got, type(got)) == (expected, float)
    assert read_scale_factor(sympy.sqrt(2)) is sympy.sqrt(2)  # exact as it is: powers of it stay exact
    for bad in (0, -1, "-1/2", 0.0, float("nan"), float("inf"), True, "ten", None):
        with pytest.raises(pt.NumberError, match="the scale factor s must be a positive finite number"):
            read_scale_factor(bad)


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        ("-1/2", Fraction(-1, 2)),
        (0.25, Fraction(1, 4)),
        (3, Fraction(3)),
        ("1e-3", Fraction(1, 1000)),
        (f"1/{MAX_DENOMINATOR}", Fraction(1, MAX_DENOMINATOR)),
        (MAX_EXPONENT, Fraction(MAX_EXPONENT)),
    ],
)
def test_read_exponent_reads_within_the_limits(value, expected):
    assert read_exponent(value, "the exponent of 'x'") == expected


@pytest.mark.parametrize("value", [MAX_EXPONENT + 1, -MAX_EXPONENT - 1, Fraction(1, MAX_DENOMINATOR + 1)])
def test_read_exponent_refuses_beyond_the_limits(value):
    with pytest.raises(pt.LimitError) as caught:
        read_exponent(value, "the exponent of 'x'")
    assert "the exponent of 'x'" in str(caught.value)


# -- the float rule: a float of at most 12 significant digits is the decimal typed; a longer one, the
# simplest fraction whose nearest double it is.  Oracles: decimal strings built here, float() of a
# Fraction (correctly rounded), and Fraction.limit_denominator for minimality.


@given(st.integers(-(10**12) + 1, 10**12 - 1), st.integers(-290, 290))
def test_a_float_of_at_most_twelve_digits_reads_as_the_decimal_typed(mantissa, exponent):
    typed = f"{mantissa}e{exponent}"
    assert read_number(float(typed)) == Fraction(mantissa) * Fraction(10) ** exponent


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_every_float_reads_as_a_fraction_that_rounds_back_to_it(x):
    assert float(read_number(x)) == x


@given(st.floats(allow_nan=False, allow_infinity=False, min_value=1e-300, max_value=1e300))
def test_a_long_float_reads_as_the_simplest_fraction_that_rounds_to_it(x):
    digits = repr(x).split("e")[0].replace(".", "").strip("0")
    assume(len(digits) > 12 and math.frexp(x)[0] != 0.5)  # a power of two has a lopsided rounding interval
    read = read_number(x)
    assert float(read) == x
    if read.denominator > 1:
        # the closest fraction with a smaller denominator does not round to x: none does
        assert float(Fraction(x).limit_denominator(read.denominator - 1)) != x
    assert read.denominator <= Fraction(repr(x)).denominator


@given(st.integers(-(10**4), 10**4), st.integers(1, 10**4))
def test_a_computed_quotient_of_small_integers_reads_as_that_fraction(p, q):
    assert read_number(p / q) == Fraction(p, q)


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (1 / 3, Fraction(1, 3)),
        (-22 / 7, Fraction(-22, 7)),
        (0.1, Fraction(1, 10)),
        (0.123456789, Fraction(123456789, 10**9)),
        (123456789012.0, Fraction(123456789012)),
        (0.000123456789012, Fraction(123456789012, 10**15)),
        (np.float64(2 / 3), Fraction(2, 3)),
        (sympy.Float(1 / 7), Fraction(1, 7)),
    ],
)
def test_float_rule_examples(value, expected):
    assert read_number(value) == expected


def test_thirteen_digits_are_a_computed_float():
    read = read_number(0.1234567890123)
    assert read != Fraction("0.1234567890123")
    assert float(read) == 0.1234567890123
    assert read.denominator < 10**13


def test_a_sum_that_misses_its_decimal_is_not_read_as_that_decimal():
    # 0.1 + 0.2 prints as 0.30000000000000004: 3/10 rounds to another double, so it cannot be the reading
    read = read_number(0.1 + 0.2)
    assert read != Fraction(3, 10)
    assert float(read) == 0.1 + 0.2


@pytest.mark.parametrize("x", [5e-324, 2.0**-1074 * 3, 2.0**-1022, 2.0**70, 1.7976931348623157e308, 2.0**53 + 2])
def test_the_simplest_fraction_at_the_ends_of_the_doubles_rounds_back(x):
    read = simplest_fraction_rounding_to(x)
    assert float(read) == x
    assert simplest_fraction_rounding_to(-x) == -read


@given(st.integers(1, 10**6), st.integers(1, 10**6))
def test_a_fraction_of_small_terms_is_the_simplest_that_rounds_to_its_double(p, q):
    # two fractions of denominators up to 10^6 differ by at least 10^-12, more than four ulps of a number below
    # 1024 (2.3e-13 at most): no simpler fraction rounds to the same double, so the reading is p/q itself
    assume(p < 1024 * q)
    assert simplest_fraction_rounding_to(p / q) == Fraction(p, q)


@given(st.floats(min_value=5e-324, max_value=1.7976931348623157e308, allow_nan=False, allow_infinity=False))
def test_no_fraction_of_a_smaller_denominator_rounds_to_the_double(x):
    # the closest fraction of a smaller denominator (Python's limit_denominator, not pitheorem's descent)
    # rounds to another double; away from a power of two, where the neighbours' spacings differ, the closest is
    # the first that would round to x
    assume(math.frexp(x)[0] != 0.5)
    read = simplest_fraction_rounding_to(x)
    assert float(read) == x
    if read.denominator > 1:
        assert float(Fraction(x).limit_denominator(read.denominator - 1)) != x


def test_rounding_ties_belong_to_the_double_with_an_even_significand():
    # 2**53 + 2 has an odd significand at spacing 2: the odd integers beside it are ties that round to its
    # even neighbours, so the only integer in its interval is itself; 2**53 + 4 (even) owns its ties
    assert simplest_fraction_rounding_to(2.0**53 + 2) == 2**53 + 2
    assert simplest_fraction_rounding_to(2.0**53 + 4) == 2**53 + 3
    assert float(2**53 + 3) == 2.0**53 + 4


def test_a_sympy_float_beyond_doubles_is_a_limit_error_where_a_float_is_kept():
    big = sympy.Float("1e400")
    assert read_number(big) == 10**400  # exact readings are fine
    for read in (lambda: read_value(big, "the value of 'x'"), lambda: read_scale_factor(big)):
        with pytest.raises(pt.LimitError, match="beyond the range of floating point"):
            read()


def test_the_simplest_fraction_of_zero_is_zero():
    assert simplest_fraction_rounding_to(0.0) == 0
    assert simplest_fraction_rounding_to(-0.0) == 0


# -- whole messages and culprits: every refusal names the value, what it was and what is valid
# (each assertion kills a mutmut survivor that changed one of them)

_FINITE = "a finite real number (int, float, Fraction, numpy or sympy number, or a string such as '0.1' or '1/3')"


@pytest.mark.parametrize(
    ("read", "error", "message", "culprit"),
    [
        (
            lambda: read_value(sympy.Float("1e400"), "the value of 'x'"),
            pt.LimitError,
            "the value of 'x' is about 10^400: it is beyond the range of floating point (about 1e-308 to 1.8e308); "
            "pass it exactly, as an int, a Fraction or a string",
            "about 10^400",
        ),
        (
            lambda: read_scale_factor(sympy.Float("1e400")),
            pt.LimitError,
            "the scale factor s is about 10^400: it is beyond the range of floating point (about 1e-308 to 1.8e308); "
            "pass it exactly, as an int, a Fraction or a string",
            "about 10^400",
        ),
        (lambda: read_number("abc", "w"), pt.NumberError, f"w must be {_FINITE}, got 'abc'", "abc"),
        (
            lambda: read_number("1e99999", "w"),
            pt.LimitError,
            "w is 1e99999: its power of ten exceeds the limit 10^10000",
            "1e99999",
        ),
        (
            lambda: read_positive("1e99999", "s"),
            pt.LimitError,
            "s is 1e99999: its power of ten exceeds the limit 10^10000",
            "1e99999",
        ),
        (
            lambda: read_number("1/0", "w"),
            pt.NumberError,
            f"w must be {_FINITE}, with a nonzero denominator, got '1/0'",
            "1/0",
        ),
        (
            lambda: read_number("1" * 1001, "w"),
            pt.LimitError,
            "w is 11111111111111111111...: a number string may have at most 1000 characters",
            "11111111111111111111...",
        ),
        (lambda: read_exponent(1001, "w"), pt.LimitError, "w is 1001: its magnitude exceeds the limit 1000", "1001"),
        (
            lambda: read_exponent(Fraction(1, 10**13), "w"),
            pt.LimitError,
            "w is 1/10000000000000: its denominator 10000000000000 exceeds the limit 1000000000000",
            "1/10000000000000",
        ),
        (
            lambda: read_exponent(np.float32(1e-13), "w"),
            pt.LimitError,
            f"w is {np.float32(1e-13)}: its denominator 10000000000000 exceeds the limit 1000000000000; a float is read as the decimal it "
            "prints as, or as the simplest fraction that rounds to it; pass an exact exponent such as Fraction(1, 3) or "
            "'1/3'",
            np.float32(1e-13),
        ),
        (lambda: read_number(None), pt.NumberError, f"the number must be {_FINITE}, got None", None),
        (lambda: read_number([1], "w"), pt.NumberError, f"w must be {_FINITE}, got [1]", [1]),
        (lambda: read_number(True, "w"), pt.NumberError, f"w must be {_FINITE}, not a bool, got True", True),
        (
            lambda: read_number(np.bool_(True), "w"),
            pt.NumberError,
            f"w must be {_FINITE}, not a bool, got np.True_",
            np.bool_(True),
        ),
        (
            lambda: read_number(sympy.pi, "w"),
            pt.NumberError,
            "w must be a rational number such as 1, -2 or '1/2', got pi",
            sympy.pi,
        ),
        (
            lambda: read_number(sympy.zoo, "w", irrational_ok=True),
            pt.NumberError,
            f"w must be {_FINITE}, got zoo",
            sympy.zoo,
        ),
        (
            lambda: read_positive(sympy.pi, "s"),
            pt.NumberError,
            "s must be a positive finite number such as 2, 0.5 or '1/3', got pi",
            sympy.pi,
        ),
    ],
)
def test_each_refusal_names_value_what_and_the_valid_kind(read, error, message, culprit):
    with pytest.raises(error) as caught:
        read()
    assert str(caught.value) == message
    assert caught.value.culprit == culprit


def test_a_limit_error_for_an_exact_value_carries_no_hint():
    with pytest.raises(pt.LimitError) as caught:
        read_exponent(Fraction(1, 10**13), "w")
    assert caught.value.hint == ""


@pytest.mark.parametrize("zero", [0.0, -0.0, np.float64(0), sympy.Float(0)])
def test_zero_as_a_float_is_zero(zero):
    assert read_value(zero, "x") == 0.0
    assert read_number(zero) == 0


def test_decimals_one_and_negative_magnitudes():
    assert read_number(Decimal("0.25")) == Fraction(1, 4)
    assert simplest_fraction_rounding_to(1.0) == 1
    assert short_text(Fraction(-(10**400))) == "about -10^400"
    assert short_text(Fraction(-1, 10**50)) == "about -10^-50"


@given(st.integers(min_value=-5, max_value=50), st.integers(min_value=0, max_value=3))
def test_read_count_takes_whole_numbers_from_its_least_up(value, least):
    from pitheorem.exact import read_count

    for given_as in (value, np.int64(value)):
        if value >= least:
            got = read_count(given_as, "n", least)
            assert (got, type(got)) == (value, int)
        else:
            with pytest.raises(pt.InvalidRequestError) as caught:
                read_count(given_as, "n", least)
            assert str(caught.value) == f"n must be a whole number of at least {least}, got {given_as!r}"
            assert caught.value.culprit == given_as


@given(st.integers(min_value=-5, max_value=50), st.integers(min_value=0, max_value=3), st.integers(0, 40))
def test_read_count_takes_whole_numbers_from_its_least_to_its_most(value, least, span):
    from pitheorem.exact import read_count

    most = least + span
    if least <= value <= most:
        assert read_count(value, "n", least, most) == value
    else:
        with pytest.raises(pt.InvalidRequestError) as caught:
            read_count(value, "n", least, most)
        assert str(caught.value) == f"n must be a whole number from {least} to {most}, got {value!r}"


@pytest.mark.parametrize("value", [True, 2.0, "2", None, Fraction(2)])
def test_read_count_refuses_what_is_no_integer(value):
    from pitheorem.exact import read_count

    with pytest.raises(pt.InvalidRequestError, match="n_steps must be a whole number of at least 0"):
        read_count(value, "n_steps")
