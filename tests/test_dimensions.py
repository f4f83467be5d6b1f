"""The dimension formula parser and the Dimension value type."""

from __future__ import annotations

from fractions import Fraction

import pytest

import pitheorem as pt

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
