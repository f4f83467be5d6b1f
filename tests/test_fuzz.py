"""Fuzz: malformed and extreme input either gives a verified answer or a PiTheoremError subclass.

One hypothesis test draws, in each of its 600 cases, one entry point (System,
Dimension.parse, pi_groups, bases, search, apply, fit_units,
check_dimensions, the model-file reader) and an input mixing valid
values with junk: huge, tiny and non-finite numbers, bools, numpy
scalars, unparsable formulas, deep nesting, unknown names.  Any exception
other than a PiTheoremError fails the test, and so does a case that runs
longer than the deadline.  Answers are checked against oracles that do
not use the code under test (sympy's own rank, exponent arithmetic
written out here).

Cross-cutting: its one test spans every public entry point at once, so that the
draw mixes them; each module's own bad-input cases are in that module's file.

The size limits of exponents (issue 33) are held the same way at every entry that
takes one (a formula, a mapping, a power, a product, a System, a unit string, a
model file): the tests below draw exponents within the limits, which every entry
accepts and gives back exactly, and beyond them, which every entry refuses by
name.  Whether an exponent is within is decided here, from the documented numbers
(|e| <= 1000, denominator <= 10^12), not by the code under test.
"""

from __future__ import annotations

import math
import pickle
import tempfile
from datetime import timedelta
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import sympy
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import pitheorem as pt
from tests.conftest import BASES, columns_of, sympy_rank

NAMES = ("a", "b", "c", "d", "e", "t")

# numbers users pass, good and bad
numbers = st.one_of(
    st.integers(-3, 3),
    st.integers(),
    st.sampled_from([10**400, -(10**30), 2**63, 2**64 + 1]),
    st.fractions(max_denominator=20),
    st.builds(Fraction, st.integers(-(10**20), 10**20), st.integers(1, 10**20)),
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-4, 4).map(np.float64),
    st.floats(-4, 4, width=32).map(np.float32),
    st.integers(-5, 5).map(np.int64),
    st.booleans(),
    st.none(),
    st.sampled_from(
        [
            "1/3",
            "-1/2",
            "0.1",
            "1e400",
            "1e99999",
            "x",
            "",
            "1/0",
            "--1",
            Decimal("0.25"),
            sympy.Rational(1, 7),
            sympy.pi,
            sympy.Float(0.5),
            [1],
            {},
        ]
    ),
)

formula_tokens = st.sampled_from(
    [
        "M",
        "L",
        "T",
        "Theta",
        "I",
        "N",
        "J",
        "A",
        "kg",
        "x",
        "1",
        "2",
        "^",
        "**",
        "*",
        "/",
        "(",
        ")",
        "-",
        "--",
        "+",
        "0.5",
        "(1/2)",
        "(1/0)",
        "99999999999999999999",
        " ",
        "$",
        "é",
        "1e5",
        "1001",
    ]
)
formulas = st.one_of(
    st.lists(formula_tokens, max_size=12).map("".join),
    st.lists(formula_tokens, max_size=12).map(" ".join),
    st.integers(0, 300).map(lambda k: "(" * k + "L" + ")" * k),
    st.text(max_size=20),
)
dimension_specs = st.one_of(
    formulas,
    st.dictionaries(st.sampled_from((*BASES, "N", "Q")), numbers, max_size=3),
    st.dictionaries(st.sampled_from(BASES[:3]), st.integers(-3, 3), min_size=1, max_size=3),
    st.sampled_from([None, 3, ["L"], pt.Dimension({"L": 1})]),
)
good_dims = st.dictionaries(st.sampled_from(BASES[:3]), st.integers(-2, 2), max_size=3).map(pt.Dimension)
names = st.one_of(st.sampled_from(NAMES), st.sampled_from(["2x", "", "a b", "t"]), st.text(max_size=4))


def good_system(draw) -> pt.System:
    n = draw(st.integers(1, 5))
    dims = draw(st.lists(good_dims, min_size=n, max_size=n))
    return pt.System({NAMES[i]: d for i, d in enumerate(dims)})


def name_lists(draw, system):
    known = st.sampled_from(system.variables)
    return draw(st.one_of(st.lists(known, max_size=3), st.lists(names, max_size=2), st.sampled_from(["a", 3, None])))


def is_dimensionless(system, exponents) -> bool:
    return all(
        sum(Fraction(p) * system.dimension(n).exponent_of(b) for n, p in exponents.items()) == 0
        for b in system.base_dimensions
    )


# -- the entry points, each with its own check of the answer ------------------------------


def fuzz_system(draw):
    spec = draw(st.dictionaries(names, dimension_specs, max_size=4))
    bases = draw(st.one_of(st.none(), st.just("LT"), st.lists(st.sampled_from((*BASES, "N", "1x")), max_size=4)))
    system = pt.System(spec, base_dimensions=bases)
    assert system.rank <= min(len(system.variables), len(system.base_dimensions))
    assert system.matrix.shape == (len(system.base_dimensions), len(system.variables))
    assert system.matrix.rank() == system.rank


def fuzz_parse(draw):
    text = draw(formulas)
    dim = pt.Dimension.parse(text)
    assert pt.Dimension.parse(str(dim)) == dim


def fuzz_pi_groups(draw):
    system = good_system(draw)
    repeating = name_lists(draw, system) if draw(st.booleans()) else None
    groups = system.pi_groups(repeating=repeating)
    assert len(groups) == system.n_groups
    for g in groups:
        assert is_dimensionless(system, g.exponents)


def fuzz_bases(draw):
    system = good_system(draw)
    exclude, require = name_lists(draw, system), name_lists(draw, system)
    found = system.bases(exclude=exclude, require=require)
    assert system.count_bases(exclude=exclude, require=require) == len(found)
    columns = dict(zip(system.variables, columns_of(system), strict=True))
    for basis in found[:5]:
        assert len(basis) == system.rank == sympy_rank([columns[n] for n in basis])


def fuzz_search(draw):
    system = good_system(draw)
    scale = draw(st.dictionaries(st.one_of(st.sampled_from(system.variables), names), numbers, max_size=2))
    fixed = name_lists(draw, system)
    res = pt.search(system, scale=scale, fixed=fixed)
    if res.feasible:
        groups = system.pi_groups()
        for sc in res.scalings[:3]:
            for n, value in scale.items():
                if isinstance(value, int | Fraction) and not isinstance(value, bool):
                    assert sc.exponents[n] == value
            for n in fixed if isinstance(fixed, list) else ():
                assert sc.exponents[n] == 0
            for g in groups:  # a similarity scaling leaves every Pi group unchanged
                assert sum(p * sc.exponents[n] for n, p in g.exponents.items()) == 0
    else:
        assert is_dimensionless(system, res.certificate.exponents)


def fuzz_apply(draw):
    system = good_system(draw)
    sc = pt.Scaling.from_unit_change(system, draw(st.dictionaries(st.sampled_from(BASES[:3]), st.integers(-2, 2))))
    values = draw(st.dictionaries(st.one_of(st.sampled_from(system.variables), names), numbers, max_size=3))
    s = draw(st.one_of(st.integers(1, 5), numbers))
    out = sc.apply(values, s)
    assert set(out) == set(values)
    for n, v in values.items():
        if isinstance(v, int) and not isinstance(v, bool) and isinstance(s, int) and not isinstance(s, bool):
            p = sc.exponents[n]
            assert sympy.Rational(v) * sympy.Rational(s) ** sympy.Rational(p.numerator, p.denominator) == out[n]
            # a rational result is a Fraction; only an irrational one is a sympy number
            assert isinstance(out[n], Fraction) or not out[n].is_Rational


def fuzz_fit_units(draw):
    system = good_system(draw)
    values = draw(
        st.dictionaries(
            st.one_of(st.sampled_from(system.variables), names), st.one_of(st.floats(1e-3, 1e3), numbers), max_size=3
        )
    )
    ranges = draw(
        st.dictionaries(
            st.one_of(st.sampled_from(system.variables), names),
            st.one_of(st.tuples(st.floats(1e-3, 1), st.floats(1, 1e3)), st.tuples(numbers, numbers), numbers),
            max_size=2,
        )
    )
    fit = pt.fit_units(system, values, ranges=ranges)
    assert isinstance(fit.feasible, bool)


def fuzz_check_dimensions(draw):
    system = good_system(draw)
    symbols = [sympy.Symbol(n) for n in system.variables] + [sympy.Symbol("zz")]
    atoms = st.one_of(st.sampled_from(symbols), st.sampled_from([sympy.Integer(2), sympy.Float(0.5), sympy.pi]))

    def grow(children):
        return st.one_of(
            st.tuples(children, children).map(lambda ab: ab[0] + ab[1]),
            st.tuples(children, children).map(lambda ab: ab[0] * ab[1]),
            st.tuples(children, st.sampled_from([2, -1, sympy.Rational(1, 2), 0.5, sympy.Symbol("a")])).map(
                lambda ab: ab[0] ** ab[1]
            ),
            children.map(sympy.sin),
            children.map(sympy.Abs),
            children.map(sympy.sign),
            children.map(sympy.floor),
            st.tuples(children, children).map(lambda ab: sympy.atan2(ab[0], ab[1])),
            st.tuples(children, children).map(lambda ab: sympy.Heaviside(ab[0] - ab[1])),
            children.map(lambda e: sympy.Function("f")(e)),
        )

    expr = draw(st.recursive(atoms, grow, max_leaves=6))
    time = draw(st.sampled_from(["t", None, "nope"]))
    report = pt.check_dimensions(expr, system, time=time)
    assert report.consistent == (not report.offending)
    pt.scaling_symmetries([expr], system, time=time)


def fuzz_model_file(draw):
    value = draw(
        st.one_of(
            st.sampled_from(
                ["1.5", '"1/3"', "true", "1e400", "nan", "inf", "-2", '"x"', "99999999999999999999999999", "[1]"]
            ),
            st.integers().map(str),
        )
    )
    dimension = draw(formulas).replace("\\", "").replace('"', "")
    extra = draw(st.sampled_from(["", 'role = "time"', 'unit = "m"', "rolee = 1", "value = 2"]))
    entry = ", ".join(p for p in (f'dimension = "{dimension}"', f"value = {value}", extra) if p)
    text = draw(
        st.sampled_from(
            [
                f'[variables]\nx = {{ {entry} }}\nt = {{ dimension = "T" }}\n',
                f'base_dimensions = ["M", "L", "T", "N"]\n[variables]\nx = {{ {entry} }}\n',
                f"[variables]\nx = {{ {entry} \n",
                "[variables]\n",
                f"name = 3\n[variables]\nx = {{ {entry} }}\n",
            ]
        )
    )
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "model.toml"
        path.write_text(text, encoding="utf-8")
        model = pt.load_model_file(path)
    assert set(model.values) <= set(model.system.variables)


ENTRY_POINTS = [
    fuzz_system,
    fuzz_parse,
    fuzz_pi_groups,
    fuzz_bases,
    fuzz_search,
    fuzz_apply,
    fuzz_fit_units,
    fuzz_check_dimensions,
    fuzz_model_file,
]


@settings(max_examples=600, deadline=timedelta(seconds=5), suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_fuzz_every_entry_point(data):
    entry = data.draw(st.sampled_from(ENTRY_POINTS), label="entry point")
    error = None
    try:
        entry(data.draw)
    except pt.PiTheoremError as err:
        error = err
    if error is not None:  # a named error, with a message that says something
        assert str(error).strip()
        assert isinstance(error, ValueError | KeyError | TypeError | ImportError)


# -- the exponent limits at every entry (issue 33) ----------------------------------------------

LIMIT, DENOMINATOR = 1000, 10**12  # as documented in docs/howto/numbers_and_base_letters.md


def within(e: Fraction) -> bool:
    return abs(e) <= LIMIT and e.denominator <= DENOMINATOR


@st.composite
def exponents_within(draw) -> Fraction:
    """An exponent within the limits: any denominator up to 10^12, so numerators up to 10^15."""
    q = draw(st.one_of(st.integers(1, 12), st.integers(1, DENOMINATOR), st.just(DENOMINATOR)))
    p = draw(st.one_of(st.integers(-LIMIT * q, LIMIT * q), st.sampled_from([LIMIT * q, -LIMIT * q, 1, -1, 0])))
    return Fraction(p, q)


@st.composite
def exponents_beyond(draw) -> Fraction:
    """An exponent beyond a limit: too large, or a denominator above 10^12 (a reduced one)."""
    if draw(st.booleans()):
        q = draw(st.integers(1, 10**6))
        return Fraction(draw(st.integers(LIMIT * q + 1, 10**20)), q) * draw(st.sampled_from([1, -1]))
    q = draw(st.integers(DENOMINATOR + 1, 10**18))
    e = Fraction(draw(st.integers(-LIMIT * q, LIMIT * q)), q)
    assume(not within(e))
    return e


any_exponent = st.one_of(exponents_within(), exponents_beyond())


def formula(e: Fraction, base: str = "L") -> str:
    return f"{base}^({e.numerator}/{e.denominator})"


def accepted_or_refused(build, expected: Fraction, culprit: str = "'L'"):
    """Build; within the limits it must give `expected`'s dimension, beyond them a LimitError naming the culprit."""
    if within(expected):
        dim = build()
        assert dim.exponents == ({"L": expected} if expected else {})
        return dim
    with pytest.raises(pt.LimitError) as info:
        build()
    message = str(info.value)
    assert culprit in message
    limit = "its magnitude exceeds the limit 1000" if abs(expected) > LIMIT else "exceeds the limit 1000000000000"
    assert limit in message
    return None


@settings(max_examples=150, deadline=None)
@given(any_exponent)
def test_an_exponent_is_accepted_within_the_limits_and_refused_beyond_them_at_every_entry(e):
    dim = accepted_or_refused(lambda: pt.Dimension({"L": e}), e)
    # the culprit: "exponent in 'L^(...)'", or, for a formula over 40 characters, "an exponent is ..." with its value
    accepted_or_refused(lambda: pt.Dimension.parse(formula(e)), e, culprit="exponent")
    accepted_or_refused(lambda: pt.Dimension.parse("L") ** e, e, culprit="the power of a dimension")
    for spec in (formula(e), {"L": e}, {"L": f"{e.numerator}/{e.denominator}"}):
        accepted_or_refused(lambda spec=spec: pt.System({"x": spec}).dimension("x"), e, culprit="of 'x'")
    model = accepted_or_refused_in_a_model_file(f'dimension = "{formula(e)}"', e)
    if dim is not None:  # within: every form it takes comes back as itself
        assert pt.Dimension.parse(str(dim)) == dim
        assert pt.Dimension.parse(str(dim)) ** 1 == dim
        assert pickle.loads(pickle.dumps(dim)) == dim
        assert pt.System({"x": dim}).dimension("x") == dim
        assert model.system.dimension("x") == dim
        assert pt.System({"x": str(pt.System({"x": dim}).dimension("x"))}).dimension("x") == dim


def accepted_or_refused_in_a_model_file(entry: str, e: Fraction):
    text = f'[variables]\nx = {{ {entry} }}\nt = {{ dimension = "T" }}\n'
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "model.toml"
        path.write_text(text, encoding="utf-8")
        if within(e):
            return pt.load_model_file(path)
        with pytest.raises(pt.ModelFileError, match=r"variable 'x'.*exceeds the limit"):
            pt.load_model_file(path)
    return None


@settings(max_examples=150, deadline=None)
@given(exponents_within(), exponents_within())
def test_products_and_powers_of_valid_dimensions_are_held_to_the_limits_as_totals(a, b):
    L = pt.Dimension.parse("L")
    accepted_or_refused(lambda: pt.Dimension({"L": a}) * pt.Dimension({"L": b}), a + b)
    accepted_or_refused(lambda: pt.Dimension({"L": a}) / pt.Dimension({"L": b}), a - b)
    accepted_or_refused(lambda: pt.Dimension.parse(f"{formula(a)} {formula(b)}"), a + b, culprit="exponent of 'L'")
    accepted_or_refused(lambda: pt.Dimension.parse(f"{formula(a)} / {formula(b)}"), a - b, culprit="exponent of 'L'")
    accepted_or_refused(lambda: pt.Dimension([("L", a), ("L", b)]), a + b)
    accepted_or_refused(lambda: pt.System({"x": f"{formula(a)} {formula(b)}"}).dimension("x"), a + b, "of 'x'")
    # a power of a power: the power is an exponent (within), and so must be the result
    accepted_or_refused(lambda: pt.Dimension.parse(f"({formula(a)})^({b.numerator}/{b.denominator})"), a * b)
    accepted_or_refused(lambda: (L**a) ** b, a * b)


@pytest.mark.parametrize(
    "text",
    [
        "(L^1000)^1000",
        "L^1000 L",
        "(L^(1/1000000))^(1/1000000000)",
        "L^(1000000000001/1000000000000) L^999",
        " ".join(f"L^(1/{p})" for p in (999999999989, 999999999961)),
    ],
)
def test_the_issue_33_formulas_beyond_the_limits_are_refused_by_name(text):
    with pytest.raises(pt.LimitError, match=r"the exponent of 'L' in .* exceeds the limit"):
        pt.Dimension.parse(text)
    accepted_or_refused_in_a_model_file(f'dimension = "{text}"', Fraction(10**20))  # beyond: refused


# a computed float (more than 12 significant digits) is an exponent only when its simplest fraction has a
# denominator of at most 1000; a float of at most 12 digits is the decimal it prints as


def is_short(x: float) -> bool:
    """Whether a float prints with at most 12 significant digits (written out here, not the package's)."""
    mantissa = repr(x).lstrip("-").split("e")[0]
    return len(mantissa.replace(".", "").strip("0")) <= 12


small_fractions = st.builds(Fraction, st.integers(-(10**6), 10**6), st.integers(1, 1000)).filter(
    lambda f: abs(f) <= 1000
)
irrational_powers = st.one_of(
    st.integers(2, 1000).filter(lambda k: math.isqrt(k) ** 2 != k).map(lambda k: (f"{k}**0.5", k**0.5)),
    st.integers(2, 1000).filter(lambda k: round(k ** (1 / 3)) ** 3 != k).map(lambda k: (f"{k}**(1/3)", k ** (1 / 3))),
    st.integers(1, 300).map(lambda k: (f"{k}*2**0.5", k * 2**0.5)),
    st.sampled_from([("3.141592653589793", math.pi), ("2.718281828459045", math.e)]),
)


@settings(max_examples=100, deadline=None)
@given(small_fractions)
def test_a_computed_float_of_a_fraction_within_the_limits_is_read_as_that_fraction(e):
    # pint computes m**(p/q) as the float p/q; so does a float passed in a mapping, a power or a search
    x = e.numerator / e.denominator
    unit = f"m**({e.numerator}/{e.denominator})"
    assert pt.System.from_units({"x": unit}).dimension("x").exponents == ({"L": e} if e else {})
    assert pt.Dimension({"L": x}).exponents == ({"L": e} if e else {})
    assert (pt.Dimension.parse("L") ** x).exponents == ({"L": e} if e else {})
    model = accepted_or_refused_in_a_model_file(f'unit = "{unit}"', e)
    assert model.system.dimension("x").exponents == ({"L": e} if e else {})


@settings(max_examples=100, deadline=None)
@given(irrational_powers)
def test_an_irrational_exponent_is_refused_by_name_at_every_entry(power):
    text, x = power
    assume(not is_short(x))  # a float of at most 12 digits is the decimal it prints as: a rational exponent
    unit = f"m**({text})"
    with pytest.raises(pt.NumberError, match="must be a rational number") as info:
        pt.System.from_units({"x": unit})
    assert unit in str(info.value)
    for build in (
        lambda: pt.Dimension({"L": x}),
        lambda: pt.Dimension.parse("L") ** x,
        lambda: pt.System({"x": {"L": x}}),
        lambda: pt.search(pt.System({"l": "L", "t": "T"}), scale={"l": x}),
        lambda: pt.check_dimensions(sympy.Symbol("l") ** sympy.Float(x), pt.System({"l": "L"})),
    ):
        with pytest.raises(pt.NumberError, match="may not exceed 1000") as info:
            build()
        assert info.value.culprit == x or float(info.value.culprit) == x
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "model.toml"
        path.write_text(f'[variables]\nx = {{ unit = "{unit}" }}\n', encoding="utf-8")
        with pytest.raises(pt.ModelFileError, match=r"variable 'x'.*must be a rational number"):
            pt.load_model_file(path)
