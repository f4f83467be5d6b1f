"""System: what it answers about its own variables (more in test_groups, test_fast_paths, test_edges)."""

from __future__ import annotations

import pytest

import pitheorem as pt
from pitheorem.engines import engine_search


def test_time_variables_are_those_of_dimension_time_alone_in_system_order():
    system = pt.System({"tau": "T", "l": "L", "f": "T^-1", "t": "T", "t2": "T^2", "c": "M T", "x": {"T": 1, "L": 0}})
    assert system.time_variables == ("tau", "t", "x")
    assert pt.System({"l": "L", "f": "T^-1"}).time_variables == ()


def test_a_search_holds_every_time_variable_by_default():
    system = pt.System({"l": "L", "g": "L T^-2", "t": "T", "tau": "T"})
    res = pt.search(system, scale={"g": 1})
    assert res.notes[0].variables == system.time_variables == ("t", "tau")
    assert all(sc.exponents["t"] == sc.exponents["tau"] == 0 for sc in res.scalings)
    # a scaled time variable is not held as well
    assert pt.search(system, scale={"tau": 1}).notes[0].variables == ("t",)


def test_an_engine_search_holds_the_systems_time_variables_by_default():
    system = pt.System({"l": "L", "g": "L T^-2", "t": "T", "tau": "T"})
    held = engine_search(system, "mujoco", {"g": 1}, names=[])
    free = engine_search(system, "mujoco", {"g": 1}, fixed=(), names=[])
    assert held.fixed == ("t", "tau")
    assert free.fixed == ()
    assert all(sc.exponents["tau"] == 0 for sc in held.scalings)
    assert any(sc.exponents["tau"] != 0 for sc in free.scalings)


@pytest.mark.parametrize(("variables", "expected"), [
    ({"t": "T", "l": "L", "g": "L T^-2"}, ("l", "g")),
    ({"tau": "T", "l": "L", "v": "L/T"}, ("l", "v")),
    ({"t": "T", "tau": "T", "l": "L", "v": "L/T"}, ("l", "v")),
    ({"t": "T", "l": "L"}, ("t", "l")),  # every basis needs time
])
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
