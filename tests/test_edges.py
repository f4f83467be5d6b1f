"""Issue 12's reproducers: each returns the right answer or a named PiTheoremError.

The oracles here are independent of the code under test: determinants and
ranks by Python-int arithmetic written out in the test, and answers
known by hand.
"""

from __future__ import annotations

import pickle
from fractions import Fraction

import numpy as np
import pytest
import sympy

import pitheorem as pt
from pitheorem.bases import count_independent_subsets, independent_subsets
from pitheorem.exact import (
    MAX_DENOMINATOR,
    MAX_EXPONENT,
    MAX_FORMULA_LENGTH,
    MAX_NESTING,
    is_float,
    read_exponent,
    read_number,
    read_positive,
    read_value,
    short_text,
)

ROD = {"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "c_theta": "M L^2 T^-1", "theta_r": "1", "t": "T"}
LT = pt.System({"l": "L", "t": "T"})


def det2(a, b, c, d):
    return a * d - b * c


# -- overflow in the fast basis paths --------------------------------------------------------


def test_determinant_two_to_the_64_is_not_zero():
    # was: rank 2 but no basis (float cancellation of 2^118-sized products)
    a, b, c = (2**27 + 1) * 2**32, (2**27 + 2) * 2**32, 2**59
    rows = [[a, c], [b, a]]
    assert det2(a, c, b, a) == 2**64
    assert count_independent_subsets(rows, [0, 1], [], 2) == 1
    assert list(independent_subsets(rows, [0, 1], [], 2)) == [(0, 1)]


@pytest.mark.parametrize("big", [3_100_000_000, 2**40, 2**62 + 1, 2**70, 10**30])
def test_entries_beyond_int64_safe_range(big):
    # was: (columns**2).sum() wrapped (math domain error) or OverflowError building int64 arrays
    rows = [[big, big + 1, 1], [1, 1, 0]]
    expected = [(i, j) for i, j in [(0, 1), (0, 2), (1, 2)]
                if det2(rows[0][i], rows[0][j], rows[1][i], rows[1][j]) != 0]
    assert list(independent_subsets(rows, [0, 1, 2], [], 2)) == expected
    assert count_independent_subsets(rows, [0, 1, 2], [], 2) == len(expected)


def test_dependent_columns_with_huge_entries_stay_dependent():
    big = 2**80 + 7
    rows = [[big, 2 * big, 1], [3, 6, 1]]  # columns 0 and 1 are parallel
    assert list(independent_subsets(rows, [0, 1, 2], [], 2)) == [(0, 2), (1, 2)]


def test_search_with_two_large_coprime_denominators():
    # was: OverflowError (the lcm of the denominators, ~1e24, entered an int64 array)
    s = pt.System({"l": "L", "t": "T", "m": "M", "v": "L/T"})
    q1, q2 = 999_999_999_989, 999_999_999_959
    res = pt.search(s, scale={"l": Fraction(1, q1), "t": Fraction(1, q2)}, fixed=())
    assert res.n_scalings == 1
    sc = res.scalings[0]
    assert sc.exponents["v"] == Fraction(1, q1) - Fraction(1, q2)
    assert sc.exponents["m"] == 0


@pytest.mark.parametrize("p", [2, 3, 5, 7, 11, 13, 17, 19, 23, 29])
def test_exponent_one_over_prime(p):
    rod = pt.System(ROD)
    res = pt.search(rod, scale={"g": Fraction(1, p)})
    assert res.feasible
    for sc in res.scalings:
        assert sc.exponents["g"] == Fraction(1, p)
        assert sc.exponents["t"] == 0


@pytest.mark.parametrize("value", [1 / 3, 0.123456789012345, 1e-13])
def test_float_exponent_beyond_denominator_limit_is_named(value):
    with pytest.raises(pt.LimitError) as info:
        pt.search(LT, scale={"l": value}, fixed=())
    assert str(MAX_DENOMINATOR) in str(info.value)
    assert "Fraction(1, 3)" in str(info.value)  # says how to write it exactly


@pytest.mark.parametrize(("value", "exponent"), [
    (Fraction(1, 10**9), Fraction(1, 10**9)),
    (1e-9, Fraction(1, 10**9)),
    (0.123456789, Fraction(123456789, 10**9)),
    (np.float64(0.5), Fraction(1, 2)),
    (np.float32(0.1), Fraction(1, 10)),
    (np.int64(2), Fraction(2)),
    ("1/3", Fraction(1, 3)),
])
def test_exponents_read_as_written(value, exponent):
    res = pt.search(LT, scale={"l": value}, fixed=())
    assert res.n_scalings == 1
    assert res.scalings[0].exponents["l"] == exponent


def test_fraction_one_over_ten_to_twenty_is_named():
    with pytest.raises(pt.LimitError, match=str(MAX_DENOMINATOR)):
        pt.search(LT, scale={"l": Fraction(1, 10**20)}, fixed=())


# -- sizes of formulas and mappings ------------------------------------------------------------


@pytest.mark.parametrize("spec", ["L^99999999999999999999999", {"L": 1e300}, {"L": 10**400}, "L^1001", "L^(1/1000000000001)"])
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


def test_nesting_limit():
    ok = "(" * MAX_NESTING + "L" + ")" * MAX_NESTING
    assert pt.Dimension.parse(ok) == pt.Dimension({"L": 1})
    with pytest.raises(pt.LimitError, match=str(MAX_NESTING)):
        pt.Dimension.parse("(" * (MAX_NESTING + 1) + "L" + ")" * (MAX_NESTING + 1))
    with pytest.raises(pt.LimitError):  # was RecursionError
        pt.Dimension.parse("(" * 5000 + "L" + ")" * 5000)


def test_decimal_in_mapping_is_the_decimal_written():
    assert pt.System({"x": {"L": 0.1}}).dimension("x") == pt.Dimension.parse("L^(1/10)")
    assert pt.System({"x": {"L": np.float64(0.5)}}).dimension("x") == pt.Dimension.parse("L^(1/2)")


def test_base_names_must_be_strings():
    with pytest.raises(pt.InvalidRequestError, match="must be strings") as info:
        pt.Dimension({1: 2})
    assert info.value.culprit == 1


def test_text_after_a_complete_formula_is_named():
    with pytest.raises(pt.DimensionSyntaxError, match="unexpected '\\)' after a complete formula"):
        pt.Dimension.parse("L T)")


def test_base_dimensions_string_is_refused():
    with pytest.raises(pt.InvalidRequestError, match="'LT'"):
        pt.System({"x": "L"}, base_dimensions="LT")
    with pytest.raises(pt.InvalidRequestError, match="'LT'"):
        pt.Dimension.parse("L", base_dimensions="LT")


def test_double_sign_is_a_syntax_error():
    # was read as L^2 (mutation survivor: the parser reading --2 as -2 went unnoticed)
    for text in ("L^--2", "L^+-2", "L^(--1/2)"):
        with pytest.raises(pt.DimensionSyntaxError):
            pt.Dimension.parse(text)
    assert pt.Dimension.parse("L^-2").exponent_of("L") == -2
    assert pt.Dimension.parse("L^+2").exponent_of("L") == 2
    assert pt.Dimension.parse("L^(-1/-2)").exponent_of("L") == Fraction(1, 2)


def test_fit_units_with_huge_value_is_named():
    s = pt.System({"r": "L", "t": "T"})
    with pytest.raises(pt.LimitError, match="1e300"):
        pt.fit_units(s, {"r": 10**400, "t": 1}, ranges={"r": (1, 10)})


# -- the number rule ---------------------------------------------------------------------------


@pytest.mark.parametrize(("value", "expected"), [
    (0.1, Fraction(1, 10)), (2.5e-3, Fraction(1, 400)), (1e22, Fraction(10**22)), (-0.0, Fraction(0)),
    (np.float64(0.5), Fraction(1, 2)), (np.float32(0.1), Fraction(1, 10)), (np.float16(0.25), Fraction(1, 4)),
    (np.int8(-3), Fraction(-3)), (np.array(0.2), Fraction(1, 5)), ("  -7/21 ", Fraction(-1, 3)),
    ("1e-3", Fraction(1, 1000)), (Fraction(2, 6), Fraction(1, 3)), (10**40, Fraction(10**40)),
])
def test_read_number_rule(value, expected):
    assert read_number(value) == expected


@pytest.mark.parametrize("bad", ["1/0", "1e", "0x10", "1.5/2", "", "--1", "nan", "inf", [1], {}, 1j, object()])
def test_read_number_refuses(bad):
    with pytest.raises(pt.NumberError):
        read_number(bad, "the test value")


@pytest.mark.parametrize(("value", "expected"), [(2, Fraction(2)), ("1/3", Fraction(1, 3)), (0.5, Fraction(1, 2)),
                                               (sympy.Rational(3, 4), Fraction(3, 4))])
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
    for value, exact in ((3, Fraction(3)), ("1/3", Fraction(1, 3)), (sympy.Rational(1, 7), Fraction(1, 7)),
                         (np.int64(-4), Fraction(-4))):
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


@pytest.mark.parametrize(("irrational", "printed"), [
    (sympy.pi, "3.141592653589793"), (sympy.sqrt(2), "1.4142135623730951"), (sympy.E, "2.718281828459045"),
])
def test_irrational_numbers_need_the_opt_in(irrational, printed):
    # an exponent must be rational: pi is refused unless the caller accepts irrationals (values, not exponents)
    with pytest.raises(pt.NumberError, match="rational number"):
        read_number(irrational)
    with pytest.raises(pt.NumberError):
        pt.System({"x": {"L": irrational}})
    assert read_number(irrational, irrational_ok=True) == Fraction(printed)


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
    for inexact in (1 / 3, np.float64(1 / 3)):
        with pytest.raises(pt.LimitError, match="a float is read as the decimal"):
            read_exponent(inexact, "x")


def test_short_text_is_exact_below_120_bits_and_a_magnitude_above():
    # numerator and denominator together: 2**117 has 118 bits (+1 for the denominator 1)
    assert short_text(Fraction(2**117)) == str(2**117)
    assert short_text(Fraction(2**118)) == "about 10^36"  # 2**118 = 3.3e35
    assert short_text(Fraction(1, 2**118)) == "about 10^-36"


def test_formula_over_the_length_limit_shows_its_first_twenty_characters():
    text = "L*" * (MAX_FORMULA_LENGTH // 2 + 1)
    with pytest.raises(pt.LimitError) as info:
        pt.Dimension.parse(text)
    assert info.value.value == "L*L*L*L*L*L*L*L*L*L*..."
    assert str(len(text)) in info.value.limit


def test_exponents_have_at_most_forty_digits():
    assert pt.Dimension.parse("L^" + "0" * 39 + "1") == pt.Dimension({"L": 1})  # 40 digits, value 1
    with pytest.raises(pt.LimitError, match="more than 40 digits") as info:
        pt.Dimension.parse("L^" + "0" * 40 + "1")
    assert info.value.value == "0" * 20 + "..."


def test_huge_power_of_ten_string_is_refused_before_it_is_built():
    with pytest.raises(pt.LimitError, match="power of ten"):
        read_exponent("1e99999999", "x")


# -- N, J and A are opt-in -----------------------------------------------------------------------


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


# -- errors: builtin bases, culprit, pickling ----------------------------------------------------


def provoked_errors():
    """One real instance of every error class, provoked through the public API where possible."""
    from pitheorem import engines, errors
    from pitheorem.cli import _parse_scale

    def catch(call):
        try:
            call()
        except pt.PiTheoremError as err:
            return err
        raise AssertionError(f"{call} raised nothing")

    rod = pt.System(ROD)
    return {
        errors.DimensionSyntaxError: (catch(lambda: pt.Dimension.parse("M L^^2")), "^2"),
        errors.UnknownVariableError: (catch(lambda: rod.pi_groups(repeating=("mass", "l", "t"))), "mass"),
        errors.DuplicateVariableError: (catch(lambda: rod.pi_groups(repeating=("m", "m", "t"))), "m"),
        errors.EmptySystemError: (catch(lambda: pt.System({})), None),
        errors.RepeatingCountError: (catch(lambda: rod.pi_groups(repeating=("m", "l"))), ("m", "l")),
        errors.DependentRepeatingSetError: (catch(lambda: rod.pi_groups(repeating=("l", "t", "g"))), ("l", "t", "g")),
        errors.InvalidRequestError: (catch(lambda: pt.System({"x": "L"}, base_dimensions="LT")), "LT"),
        errors.UnitError: (catch(lambda: pt.System.from_units({"x": "furlongs per flibber"})), None),
        errors.SystemMismatchError: (catch(lambda: pt.verify_similarity(
            pt.models.projectile(), pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1}),
            s=2, t_final=0.1)), "m"),
        errors.ModelEquationError: (catch(lambda: pt.Model(pt.System({"x": "L", "t": "T"}), [sympy.Eq(
            sympy.Function("x")(sympy.Symbol("t")).diff("t", 2), 0)])), "Eq(Derivative(x(t), (t, 2)), 0)"),
        errors.NumberError: (catch(lambda: pt.search(LT, scale={"l": float("nan")})), "nan"),
        errors.LimitError: (catch(lambda: pt.Dimension.parse("L^5000")), "5000"),
        errors.ModelFileError: (catch(lambda: pt.load_model_file("example:nope")), "example:nope"),
        errors.CommandLineError: (catch(lambda: _parse_scale(["g=1", "g=2"])), "g"),
        errors.EngineUnavailableError: (errors.EngineUnavailableError("bullet", "pybullet"), "bullet"),
        errors.EngineModelError: (catch(lambda: engines.load("no_such_robot.xml")), "no_such_robot.xml"),
        errors.UnscalableParameterError: (errors.UnscalableParameterError("joint_root_damping", "needs s^1 and s^3"),
                                          "joint_root_damping"),
    }


PROVOKED = provoked_errors()


def test_every_error_class_is_provoked_here():
    from pitheorem import errors

    names = {n for n in errors.__all__ if n != "PiTheoremError"}
    assert {c.__name__ for c in PROVOKED} == names


@pytest.mark.parametrize("cls", sorted(PROVOKED, key=lambda c: c.__name__), ids=lambda c: c.__name__)
def test_error_contract(cls):
    from pitheorem import errors

    err, culprit = PROVOKED[cls]
    assert type(err) is cls
    assert cls.__module__ == errors.__name__  # every error class lives in errors.py
    assert isinstance(err, pt.PiTheoremError)
    assert isinstance(err, ValueError | KeyError | TypeError | ImportError)
    if culprit is not None:
        shown = err.culprit if isinstance(err.culprit, str | tuple) else repr(err.culprit)
        assert shown == culprit or str(culprit) in str(shown)
    copy = pickle.loads(pickle.dumps(err))
    assert type(copy) is cls
    assert str(copy) == str(err)
    assert copy.culprit == err.culprit or repr(copy.culprit) == repr(err.culprit)
    assert str(err).strip(), "an error must say what is wrong"


def test_message_only_errors_pickle_their_culprit():
    err = pt.InvalidRequestError("bad thing", culprit="thing")
    copy = pickle.loads(pickle.dumps(err))
    assert (copy.culprit, str(copy)) == ("thing", "bad thing")
