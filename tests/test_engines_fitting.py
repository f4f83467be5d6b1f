"""pitheorem.engines.fitting: units clear of an engine's thresholds (fit_units with engine=, or on a model).

The fitted units are checked by engines.check (the thresholds module, not the fit) on the converted copy,
the copy is run in MuJoCo (no NaN), and engines.verify compares it with the model it was fitted for.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import pitheorem as pt

pytest.importorskip("mujoco")

from pitheorem import Dimension, engines
from pitheorem.engines import Parameter
from pitheorem.engines.fitting import OPEN, engine_fit, engine_ranges, fitted_units, unit_name
from pitheorem.engines.units import conversion, read_units

PENDULUM = engines.example_path("pendulum.xml")


def superball_scaled(s):
    model = engines.load(engines.example_path("superball.xml"))
    return model.scaled(pt.search(model.system(), scale={"g": 1}).scalings[0], s)


def test_ranges_keep_a_factor_clear_of_each_threshold_on_the_side_the_engine_takes():
    mass = Parameter("body_b_mass", "body 'b' mass", (1.0,), Dimension.parse("M"), "file", "file")
    rolling = Parameter(
        "geom_g_friction_torsional_rolling",
        "geom 'g' friction torsional rolling",
        (1e-3, 1e-4),
        Dimension.parse("L"),
        "file",
        "file",
    )
    ctrl = Parameter(
        "actuator_a_ctrlrange", "actuator 'a' ctrlrange", (-1.0, 1.0), Dimension.parse("M L T^-2"), "file", "file"
    )
    size = Parameter("geom_g_size", "geom 'g' size", (1.0,), Dimension.parse("L"), "file", "file")
    ranges = engine_ranges("mujoco", [mass, rolling, ctrl, size])
    assert ranges == {
        "body_b_mass": (1e-14, 1e14),
        "geom_g_friction_torsional_rolling": (1e-4, OPEN[1]),
        "actuator_a_ctrlrange": (OPEN[0], 1e9),
    }
    assert engine_ranges("mujoco", [mass], clearance=100)["body_b_mass"] == (1e-13, 1e13)
    with pytest.raises(pt.InvalidRequestError, match="clearance"):
        engine_ranges("mujoco", [mass], clearance=0.5)
    with pytest.raises(pt.InvalidRequestError, match="ode"):
        engine_ranges("ode", [mass])


def test_a_model_clear_of_every_threshold_keeps_its_units():
    model = engines.load(PENDULUM)
    fit = pt.fit_units(model)
    assert fit.feasible
    assert set(fit.factors.values()) == {1}
    assert fitted_units(model, fit) == model.units


@pytest.mark.parametrize("s", [1e-3, 1e-4])
def test_superball_at_a_millimetre_is_clamped_and_fitted_units_clear_it(s):
    tiny = superball_scaled(s)
    assert any("mujoco_minmu" in c.detail for c in engines.check(tiny))
    fit = pt.fit_units(tiny, engine="mujoco")
    units = fitted_units(tiny, fit)
    assert fit.feasible
    assert units["T"] == "s"
    assert units["M"] == "kg"
    fitted = tiny.converted(**units)
    assert engines.check(fitted) == ()
    assert np.isfinite(fitted.runner.run(200)).all()
    ((scaling, factor),) = conversion(tiny.system(), tiny.units, read_units(units))
    assert engines.verify(tiny, scaling, factor, duration=0.2).similar


def test_a_model_whose_numbers_are_too_large_is_fitted_into_smaller_units():
    big = engines.load(PENDULUM).converted(L="um", M="ug")  # ctrlrange 1e21, inertia 3e19
    assert {c.element for c in engines.check(big)} == {"actuator_torque_ctrlrange", "body_arm_inertia"}
    fit = pt.fit_units(big)
    fitted = big.converted(**fitted_units(big, fit))
    assert fit.feasible
    assert engines.check(fitted) == ()
    assert np.isfinite(fitted.runner.run(100)).all()


def test_fit_units_on_a_system_reads_each_numbers_kind_from_its_name():
    tiny = superball_scaled(1e-3)
    values = {
        p.name: min(abs(v) for v in p.value if v)
        for p in tiny.parameters
        if not p.mixed and any(v != 0 for v in p.value)
    }
    fit = pt.fit_units(tiny.system(), values, engine="mujoco")
    assert fit.feasible
    assert fit.factors["L"] >= 10
    with pytest.raises(pt.InvalidRequestError, match="needs its values"):
        engine_fit(tiny.system(), engine="mujoco")
    with pytest.raises(pt.InvalidRequestError, match="needs engine="):
        engine_fit(tiny.system(), values)


def test_a_float32_engine_also_keeps_every_number_in_float32s_comfortable_range():
    model = engines.load(PENDULUM)
    ranges = engine_ranges("mjx", model.parameters)
    assert all(lo >= 1e-6 and hi <= 1e6 for lo, hi in ranges.values())
    assert "geom_rod_size" in ranges  # every nonzero number, not only the thresholded ones


def test_user_ranges_join_the_engines():
    model = engines.load(PENDULUM)
    fit = pt.fit_units(model, ranges={"geom_rod_size": (1, 100)})
    assert fit.feasible
    assert fit.factors["L"] == 100
    with pytest.raises(pt.InvalidRequestError, match="no_such"):
        pt.fit_units(model, ranges={"no_such": (1, 2)})


def test_unit_names_follow_si_prefixes():
    assert unit_name("L", Fraction(1, 1000)) == "mm"
    assert unit_name("M", Fraction(1)) == "kg"
    assert unit_name("M", Fraction(1, 10**6)) == "mg"
    assert unit_name("T", Fraction(1, 1000)) == "ms"
    assert unit_name("L", Fraction(10)) == "10 m"  # no prefix for ten
    assert unit_name("M", Fraction(10**4)) == "10 Mg"
    assert unit_name("T", Fraction(60)) == Fraction(60)  # a minute is no power of ten: its size
    assert unit_name("L", Fraction(1, 10**15)) == Fraction(1, 10**15)  # below the smallest prefix
    for base, size in (("L", Fraction(10**4)), ("M", Fraction(1, 10)), ("T", Fraction(1, 100))):
        assert engines.units.unit_size(base, unit_name(base, size)) == size


def test_superball_a_thousand_times_larger_at_the_same_density_is_fitted_and_verifies():
    model = engines.load(engines.example_path("superball.xml"))
    big = model.scaled(pt.Scaling.from_unit_change(model.system(), {"L": 1, "M": 3}), 1e3)
    crossed = {c.detail.split(": ")[0].split(" is ")[1].split(" (")[0] for c in engines.check(big)}
    assert crossed == {"above mujoco_maxval", "within a factor 2 of mujoco_minval_softness"}
    units = fitted_units(big, pt.fit_units(big))
    fitted = big.converted(**units)
    assert engines.check(fitted) == ()
    assert np.isfinite(fitted.runner.run(200)).all()
    ((scaling, factor),) = conversion(big.system(), big.units, read_units(units))
    assert engines.verify(big, scaling, factor, duration=0.2).similar


def test_a_fit_of_a_model_names_its_units_and_converted_takes_the_fit_itself():
    tiny = engines.load(PENDULUM).converted(L=100, M=1e6)
    fit = pt.fit_units(tiny)
    assert fit.units == fitted_units(tiny, fit) == {"M": "1000000 kg", "L": "m", "T": "s"}
    # the units read back to the fit's factors: each new unit is the old one over its factor, exactly
    sizes_old = {b: engines.units.unit_size(b, tiny.units[b]) for b in "MLT"}
    sizes_new = {b: engines.units.unit_size(b, fit.units[b]) for b in "MLT"}
    assert {b: sizes_old[b] / sizes_new[b] for b in "MLT"} == fit.factors
    one_step, two_steps = tiny.converted(fit), tiny.converted(**fit.units)
    assert one_step.units == two_steps.units == fit.units
    assert one_step.parameters == two_steps.parameters
    assert not engines.check(one_step)  # the fitted copy is clear of every threshold
    assert pt.fit_units(pt.System({"l": "L"}), {"l": 500}, ranges={"l": (1, 2)}).units is None


@pytest.mark.parametrize(
    ("fit", "units", "says"),
    [
        ("mm", {}, "converted takes the fit of an engine model"),
        (pt.fit_units(pt.System({"l": "L"}), {"l": 500}, ranges={"l": (1, 2)}), {}, "the fit of an engine model"),
        (None, None, "a fit or units, not both"),
    ],
)
def test_converted_refuses_a_fit_it_cannot_read(fit, units, says):
    model = engines.load(PENDULUM)
    if units is None:
        fit, units = pt.fit_units(model.converted(L=100)), {"L": "mm"}
    with pytest.raises(pt.InvalidRequestError, match=says):
        model.converted(fit, **units)
