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
"""

from __future__ import annotations

import tempfile
from datetime import timedelta
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import numpy as np
import sympy
from hypothesis import HealthCheck, given, settings
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
