"""pitheorem.engines.verdicts.binary: whether a scaling multiplies every number of a model by a power of two."""

from __future__ import annotations

from fractions import Fraction

import pytest

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

import pitheorem as pt
from pitheorem import engines
from pitheorem.engines.verdicts.binary import every_factor_a_power_of_two, exact_in_binary

PENDULUM = engines.example_path("pendulum.xml")


def test_bits_are_expected_where_every_factor_is_a_power_of_two():
    model = engines.load(PENDULUM)
    half = pt.Scaling.from_unit_change(model.system(), {"L": Fraction(1, 2)})  # lengths times s^(1/2)
    powers = [
        s for s in ("4", "16", "1/4", "1/64", "2", "8", "10", "3/4", "1") if exact_in_binary(model, half, Fraction(s))
    ]
    assert powers == ["4", "16", "1/4", "1/64", "1"]
    whole = pt.Scaling.from_unit_change(model.system(), {"L": 1})  # whole exponents: every power of two
    assert [s for s in ("2", "8", "1/2", "3") if exact_in_binary(model, whole, Fraction(s))] == ["2", "8", "1/2"]
    angles = pt.Scaling.from_unit_change(model.system(), {"M": 1})  # masses only: the coordinates keep factor 1
    assert not exact_in_binary(model, angles, 10)


def test_every_number_counts_the_coordinates_and_time_too():
    """A factor that is a power of two for every parameter's dimension but not for a coordinate's, or time's,
    still rounds: each is held on its own (an oracle of factors by dimension, not a scaling)."""
    model = engines.load(PENDULUM)
    (dims, _mixed), (_names, coords) = model.by_dimension(), model.coordinates()
    parameters = {d for d, _names in dims}
    assert every_factor_a_power_of_two(model, lambda d: 4.0)
    assert not every_factor_a_power_of_two(model, lambda d: 3.0)
    odd_ones = {*coords, pt.Dimension.parse("T")} - parameters
    assert odd_ones == {pt.Dimension.parse("T^-1")}  # the hinge's angular velocity: no parameter has it
    for odd in odd_ones:
        assert not every_factor_a_power_of_two(model, lambda d, odd=odd: 3.0 if d == odd else 4.0), odd
