"""pitheorem.engines.parameters: a parameter's variables, the factor of a dimension, a number written back exactly."""

from __future__ import annotations

import math
from decimal import Decimal, localcontext

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem.engines import Parameter
from pitheorem.engines.parameters import dim, dimension_factor, new_parameter


def test_a_parameter_stands_for_one_variable_or_one_per_part():
    mass = Parameter("body_torso_mass", "body 'torso' mass", (3.5,), dim("M"), "derived", "file")
    assert (mass.mixed, mass.variables()) == (False, {"body_torso_mass": dim("M")})
    parts = (("lin", dim("M T^-1")), ("rot", dim("M L^2 T^-1")))
    damping = Parameter("joint_root_damping", "joint 'root' damping", (0.5,), None, "file", "file", parts=parts)
    assert damping.mixed
    assert damping.variables() == {"joint_root_damping_lin": dim("M T^-1"), "joint_root_damping_rot": dim("M L^2 T^-1")}
    assert dim("M L T^-2") == pt.Dimension({"M": 1, "L": 1, "T": -2})


@pytest.mark.parametrize(
    ("unit_change", "dimension", "factor"),
    [
        ({"L": 1}, "L T^-2", 10.0),  # gravity with lengths
        ({"L": 1, "T": 1}, "L T^-2", 0.1),  # s / s^2
        ({"M": 1, "L": 2}, "M L^2", 10.0**5),  # an inertia
        ({"T": -1}, "1", 1.0),  # a number without dimension never moves
    ],
)
def test_dimension_factor_is_s_to_the_dimensions_exponent(unit_change, dimension, factor):
    sc = pt.Scaling.from_unit_change(pt.System({"m": "M", "l": "L", "t": "T"}), unit_change)
    assert dimension_factor(sc, 10, dim(dimension)) == factor


@settings(max_examples=200, deadline=None)
@given(digits=st.integers(-(10**6), 10**6), places=st.integers(0, 6), factor=st.sampled_from([10, 0.1, 2, 0.5, 1e3, 3]))
def test_attribute_text_writes_the_exact_decimal_product(digits, places, factor):
    from pitheorem.engines.parameters import attribute_text, exact_product

    value = float(f"{digits}e-{places}")  # a decimal as a file writes it, e.g. 9.81
    # oracle: the product of the two decimals in decimal arithmetic wide enough to be exact, rounded once
    with localcontext() as ctx:
        ctx.prec = 60
        expected = float(Decimal(repr(value)) * Decimal(repr(float(factor))))
    assert exact_product(value, factor) == expected
    assert attribute_text([value, value], factor) == f"{expected!r} {expected!r}"
    assert attribute_text([value]) == repr(value)


@settings(max_examples=300, deadline=None)
@given(value=st.floats(allow_nan=False, allow_infinity=False), k=st.integers(-40, 40))
def test_a_power_of_two_factor_gives_the_product_of_the_numbers_as_written(value, k):
    from pitheorem.engines.parameters import exact_product
    from pitheorem.exact import read_number

    factor = 2.0**k
    # oracle: each number read by the package's rule (the simplest fraction that rounds to it), multiplied
    # exactly and rounded once; the product of huge or tiny numbers beyond the doubles is the float's
    exact = read_number(value, "v") * read_number(factor, "f")
    try:
        expected = float(exact)
    except OverflowError:
        expected = value * factor
    assert exact_product(value, factor) == expected
    assert math.copysign(1.0, exact_product(value, factor)) == math.copysign(1.0, expected)


def test_attribute_text_writes_98_1_for_9_81_times_10():
    from pitheorem.engines.parameters import attribute_text

    assert 9.81 * 10 != 98.1  # the float product rounds twice
    assert attribute_text([0, 0, -9.81], 10) == "0.0 0.0 -98.1"
    assert attribute_text([math.inf], 2) == "inf"


def test_an_identifier_keeps_exactly_the_alphanumeric_characters_and_underscores():
    # the oracle: character by character, str.isalnum (the definition in identifier's docstring), over every
    # code point Python has, against the one substitution identifier makes
    import sys

    from pitheorem.engines.parameters import identifier

    text = "a" + "".join(map(chr, range(sys.maxunicode + 1)))
    assert identifier(text) == "".join(c if c.isalnum() or c == "_" else "_" for c in text)
    assert identifier("9 lives") == "_9_lives"
    assert identifier("") == "_"


@given(st.text(alphabet=st.characters(max_codepoint=0x7F) | st.sampled_from("é²\u0301\uff41\u0663"), max_size=12))
def test_an_identifier_of_a_short_name_keeps_the_same_characters_whether_or_not_it_is_one_already(text):
    # a name that is already an ASCII identifier is returned as it is, the others substituted: the oracle is
    # the character-by-character definition, a leading digit (or nothing) given a "_"
    from pitheorem.engines.parameters import identifier

    kept = "".join(c if c.isalnum() or c == "_" else "_" for c in text)
    assert identifier(text) == (kept if kept and not kept[0].isdigit() else f"_{kept}")
    assert identifier(f"geom_{text}") == f"geom_{kept}"  # as the walker names an element
    # a Python identifier that is not ASCII may hold what is no word character: a combining accent
    assert "joint_e\u0301".isidentifier()
    assert identifier("joint_e\u0301") == "joint_e_"


def test_a_joint_kinds_coefficient_dimension_is_remembered_for_equal_questions_only():
    from pitheorem.engines.parameters import JointKind

    for kind in (JointKind.HINGE, JointKind.SLIDE):
        for numerator in (kind.force, pt.Dimension.parse("M"), pt.Dimension.parse(str(kind.force))):
            for power in range(-2, 4):
                for rate in range(3):
                    # the oracle: numerator / (q T^-rate)^power, exponent by exponent
                    want = dict(numerator.exponents)
                    for base, p in {**kind.q.exponents, "T": kind.q.exponent_of("T") - rate}.items():
                        want[base] = want.get(base, 0) - power * p
                    want = {base: p for base, p in want.items() if p != 0}
                    for _ in range(2):  # computed, then remembered
                        assert kind.per(numerator, power, rate=rate).exponents == want


_TEXT = st.text(max_size=8)
_FIELDS = st.tuples(
    _TEXT,
    _TEXT,
    st.lists(st.floats(allow_nan=False), max_size=3).map(tuple),
    st.sampled_from([None, dim("M"), dim("L T^-2"), dim("1")]),
    st.sampled_from(["file", "default", "derived", "engine"]),
    _TEXT,
    st.lists(st.tuples(_TEXT, st.sampled_from([dim("M"), dim("M L^2")])), max_size=2).map(tuple),
    _TEXT,
)


@given(_FIELDS)
def test_a_parameter_made_quickly_is_the_one_its_constructor_makes(fields):
    import dataclasses

    quick, made = new_parameter(*fields), Parameter(*fields)
    assert type(quick) is Parameter
    assert quick == made
    assert hash(quick) == hash(made)
    assert repr(quick) == repr(made)
    # every field, the same object (not a copy), in the class's order: a field added later must be set too
    assert [getattr(quick, f.name) for f in dataclasses.fields(Parameter)] == list(fields)
    assert all(getattr(quick, f.name) is v for f, v in zip(dataclasses.fields(Parameter), fields, strict=True))
    with pytest.raises(dataclasses.FrozenInstanceError):
        quick.name = "other"


def test_a_parameter_made_quickly_takes_the_constructors_defaults():
    quick = new_parameter("l", "geom 'g' size", (1.0,), dim("L"), "file", "file")
    assert quick == Parameter("l", "geom 'g' size", (1.0,), dim("L"), "file", "file")
    assert (quick.parts, quick.note) == ((), "")
