"""pitheorem.engines.units: the units a model is written in, and the same model in other units.

Every number of a converted model is held against an oracle that does not
use the package's scaling: pint's own conversion of one unit of each base,
raised to the number's exponents.  Round trips run over the corpus
(gymnasium's MuJoCo models and tests/robots), in memory and through the
written file.
"""

from __future__ import annotations

import warnings
from fractions import Fraction
from pathlib import Path

import numpy as np
import pint
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt

mujoco = pytest.importorskip("mujoco")
gymnasium = pytest.importorskip("gymnasium")

from pitheorem import engines  # noqa: E402
from pitheorem.engines.units import conversion, read_units, run_in_units, unit_size  # noqa: E402

ROBOTS = Path(__file__).resolve().parent / "robots"
ASSETS = Path(gymnasium.__file__).resolve().parent / "envs" / "mujoco" / "assets"
CORPUS = sorted(ASSETS.glob("*.xml")) + sorted((ROBOTS / "mjcf").glob("*.xml")) + [ROBOTS / "mjcf/attach/scene.xml"]
PENDULUM = engines.example_path("pendulum.xml")
UREG = pint.UnitRegistry()
SI_NAMES = {"M": "kg", "L": "m", "T": "s"}


def quiet(path, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        return engines.load(path, **options)


def ulps(a, b) -> float:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert np.array_equal(np.isnan(a), np.isnan(b))  # MuJoCo's "unset" (a NaN) stays unset
    a, b = np.nan_to_num(a), np.nan_to_num(b)
    return float(np.max(np.abs(a - b) / np.spacing(np.maximum(np.abs(a), np.abs(b))), initial=0.0))


def pint_factor(dimension, old: dict, new: dict) -> float:
    """The oracle: one old unit of each base in new units (pint), to the dimension's exponents."""
    out = 1.0
    for b in "MLT":
        e = dimension.exponent_of(b)
        if e:
            one = UREG.Quantity(1.0, old[b]).to(new[b]).magnitude
            out *= float(one) ** float(e)
    return out


def test_a_model_is_in_si_unless_told_and_units_name_each_base():
    model = engines.load(PENDULUM)
    assert model.units == {"M": "kg", "L": "m", "T": "s"}
    fly = engines.load(PENDULUM, units={"L": "cm", "M": "g"})
    assert fly.units == {"M": "g", "L": "cm", "T": "s"}
    assert fly.parameter("g").value == model.parameter("g").value  # declared, not converted
    assert read_units({"L": 0.001}) == {"M": "kg", "L": "1/1000 m", "T": "s"}
    assert unit_size("L", "inch") == Fraction(254, 10000)


@pytest.mark.parametrize(
    ("units", "error", "says"),
    [
        ({"L": "furlongz"}, pt.UnitError, "furlongz"),
        ({"L": "kg"}, pt.UnitError, "no unit of length"),
        ({"X": "m"}, pt.InvalidRequestError, "'X'"),
        ({"L": -1}, pt.InvalidRequestError, "positive"),
        ("cm", pt.InvalidRequestError, "map base dimensions"),
    ],
)
def test_bad_units_are_refused_by_name(units, error, says):
    with pytest.raises(error, match=says):
        engines.load(PENDULUM, units=units)


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ({"L": "cm", "M": "g"}, {"L": "mm", "M": "g"}),  # FlyGym's conversion
        ({}, {"L": "mm", "M": "g", "T": "ms"}),
        ({}, {"L": "inch", "M": "lb"}),  # no common base: one scaling per unit
    ],
)
def test_every_number_converts_by_its_dimension_as_pint_says(old, new):
    model = quiet(ROBOTS / "mjcf" / "drone.xml", units=old)  # air density and viscosity, site gears
    converted = model.converted(**new)
    full_old, full_new = read_units(old), read_units({**old, **new})
    assert converted.units == full_new
    for p, q in zip(model.parameters, converted.parameters, strict=True):
        assert p.name == q.name
        if p.mixed or p.source == "derived":
            continue
        expected = np.asarray(p.value) * pint_factor(p.dimension, full_old, full_new)
        assert ulps(q.value, expected) <= 2, (p.name, p.value, q.value, expected)


def test_gravity_density_viscosity_and_time_follow_their_dimensions():
    drone = quiet(ROBOTS / "mjcf" / "drone.xml", units={"L": "cm", "M": "g"})
    mm = drone.converted(L="mm")
    for name, factor in (("g", 10), ("density", 1e-3), ("viscosity", 1e-1), ("timestep", 1)):
        assert mm.parameter(name).value[0] == pytest.approx(drone.parameter(name).value[0] * factor, rel=1e-15)
    ms = drone.converted(T="ms")
    assert ms.parameter("timestep").value[0] == pytest.approx(drone.parameter("timestep").value[0] * 1000)
    assert ms.parameter("g").value[0] == pytest.approx(drone.parameter("g").value[0] * 1e-6)


def test_the_file_records_its_units_and_is_read_back_in_them(tmp_path):
    mm = engines.load(PENDULUM).converted(L="mm", M="g")
    out = mm.save(tmp_path / "mm.xml")
    assert 'name="pitheorem:units"' in out.read_text()
    again = engines.load(out)
    assert again.units == {"M": "g", "L": "mm", "T": "s"}
    assert again.parameter("g").value == (9810.0,)
    assert engines.load(out, units={"L": "mm", "M": "g"}).units == again.units
    with pytest.raises(pt.InvalidRequestError, match="records its units"):
        engines.load(out, units={"L": "cm"})


def test_a_urdf_is_si_by_its_specification_and_other_units_are_refused_by_name():
    arm = ROBOTS / "urdf" / "arm.urdf"
    with pytest.raises(engines.EngineModelError, match="URDF file is in SI units"):
        quiet(arm, units={"L": "cm"}, fixed_base=True)
    model = quiet(arm, fixed_base=True)
    assert model.units == {"M": "kg", "L": "m", "T": "s"}
    with pytest.raises(engines.EngineModelError, match=r"arm\.urdf: units"):
        model.converted(L="mm")


#: a fixed tendon's width, which MuJoCo neither uses nor writes to a file (so a saved copy has the default)
def _written(p) -> bool:
    return not (p.name.startswith("tendon_") and p.name.endswith("_width") and p.source == "default")


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: p.name)
def test_there_and_back_is_exact_at_powers_of_two_and_within_one_ulp_otherwise(path, tmp_path):
    model = quiet(path)
    for units, allowed in (({"L": 0.25, "M": 8, "T": 0.5}, 0), ({"L": "cm", "M": "g"}, 1)):
        there = model.converted(**units)
        file = there.save(tmp_path / "there.xml")
        for back in (there.converted(**model.units), quiet(file).converted(**model.units)):
            for p, q in zip(model.parameters, back.parameters, strict=True):
                if p.source == "derived" and allowed:  # MuJoCo computes it again from the converted geoms
                    continue
                if back is not there and not _written(p):
                    continue
                assert ulps(p.value, q.value) <= allowed, (units, p.name, p.value, q.value)


def test_a_conversion_is_one_similarity_scaling_when_the_factors_share_a_base():
    system = engines.load(PENDULUM).system()
    ((scaling, s),) = conversion(system, read_units({"L": "cm", "M": "g"}), read_units({"L": "mm", "M": "g"}))
    assert s == 10
    assert dict(scaling.unit_change) == {"M": 0, "L": 1, "T": 0}
    ((scaling, s),) = conversion(system, read_units({"L": "cm", "M": "g"}), read_units({"L": "mm"}))
    assert s == 10
    assert dict(scaling.unit_change) == {"M": -3, "L": 1, "T": 0}
    ((scaling, s),) = conversion(system, read_units({}), read_units({"L": 0.25, "M": 8, "T": 0.5}))
    assert s == 2
    assert dict(scaling.unit_change) == {"M": -3, "L": 2, "T": 1}
    assert len(conversion(system, read_units({}), read_units({"L": "inch", "M": "g"}))) == 2
    assert conversion(system, read_units({}), read_units({"L": "m"})) == ()


@settings(max_examples=15, deadline=None)
@given(st.integers(-6, 6), st.integers(-6, 6), st.integers(-3, 3))
def test_power_of_two_units_go_there_and_back_bit_for_bit(m, l, t):
    model = engines.load(PENDULUM)
    there = model.converted(M=2.0**m, L=2.0**l, T=2.0**t)
    back = there.converted(M="kg", L="m", T="s")
    assert [p.value for p in back.parameters] == [p.value for p in model.parameters]


def test_the_converted_copy_verifies_as_similar_under_the_conversions_scaling():
    model = quiet(ASSETS / "hopper.xml").with_values(tolerance=0)
    for units in ({"L": 0.25, "M": 1 / 16}, {"L": "cm", "M": "g"}):
        ((scaling, s),) = conversion(model.system(), model.units, read_units(units))
        report = engines.verify(model, scaling, s, duration=0.2, controls=engines.smooth_controls(model))
        assert report.similar, units
        assert report.excited, units
        assert report.max_deviation < 1e-12, units


def test_a_run_of_the_converted_copy_maps_back_onto_the_original(tmp_path):
    path = tmp_path / "spring.xml"
    path.write_text(SPRING)
    model = engines.load(path)
    ms = model.converted(T="ms", L="mm")
    assert ms.parameter("timestep").value == (1.0,)
    key = ms.runner.mjmodel
    assert key.key_time[0] == 500.0
    assert key.key_qvel[0][0] == pytest.approx(2e-3)
    rows = ms.runner.run(100)
    back = run_in_units(ms, rows, model.units)
    assert ulps(back, model.runner.run(100)) <= 64
    with pytest.raises(pt.InvalidRequestError, match="columns"):
        run_in_units(ms, rows[:, :1], model.units)


SPRING = """<mujoco>
  <option timestep="0.001"/>
  <worldbody>
    <body name="b">
      <joint name="j" type="hinge" springdamper="0.2 0.5"/>
      <joint name="s" type="slide" axis="1 0 0" stiffness="3" damping="0.1"/>
      <geom type="capsule" fromto="0 0 0 0.1 0 0" size="0.01"/>
    </body>
  </worldbody>
  <keyframe><key name="k" time="0.5" qpos="0.3 0.01" qvel="2 0"/></keyframe>
</mujoco>
"""


def test_a_springdamper_is_read_as_a_time_constant_and_scaled_with_time(tmp_path):
    path = tmp_path / "spring.xml"
    path.write_text(SPRING)
    model = engines.load(path)
    p = model.parameter("joint_j_springdamper_time")
    assert p.value == (0.2,)
    assert str(p.dimension) == "T"
    ms = model.converted(T="ms", M="g", L="mm")
    assert ms.parameter("joint_j_springdamper_time").value == (200.0,)
    # the compiler's stiffness and damping (M L^2 T^-2 and M L^2 T^-1) follow from it
    k0, k1 = model.runner.mjmodel.jnt_stiffness[0], ms.runner.mjmodel.jnt_stiffness[0]
    d0, d1 = model.runner.mjmodel.dof_damping[0], ms.runner.mjmodel.dof_damping[0]
    assert k1 == pytest.approx(k0 * 1e3 * 1e6 * 1e-6)
    assert d1 == pytest.approx(d0 * 1e3 * 1e6 * 1e-3)


#: FlyGym issue #289: the factors derived by hand for its fruit fly moved from cm to mm (grams kept)
FLYGYM = {"torque": 100, "rotational inertia": 100, "gravity": 10, "density": 1e-3, "viscosity": 1e-1}


def test_the_cgs_insect_in_millimetres_takes_the_factors_flygym_derived_by_hand():
    fly = engines.load(
        Path(__file__).resolve().parent / "data" / "engines" / "cgs_insect.xml", units={"L": "cm", "M": "g"}
    )
    mm = fly.converted(L="mm")
    assert mm.units == {"M": "g", "L": "mm", "T": "s"}

    def factor(name):
        before, after = fly.parameter(name).value, mm.parameter(name).value
        return next(b / a for a, b in zip(before, after, strict=True) if a)

    kinds = {
        "torque": "actuator_stroke_l_ctrlrange",
        "rotational inertia": "body_thorax_inertia",
        "gravity": "g",
        "density": "density",
        "viscosity": "viscosity",
    }
    for kind, name in kinds.items():
        # the dimension the package gives the number, and FlyGym's published factor, agree with the conversion
        dimension = fly.parameter(name).dimension
        assert factor(name) == pytest.approx(pint_factor(dimension, fly.units, mm.units), rel=1e-15), kind
        assert factor(name) == pytest.approx(FLYGYM[kind], rel=1e-15), kind
    # and what the hand-derived list leaves out: each by its own dimension
    for name, expected in (
        ("joint_hip_l_stiffness", 100),
        ("joint_hip_l_damping", 100),
        ("actuator_hip_l_gainprm_gain", 100),
        # adhesion: the gain is the force (MuJoCo's reference), the input a fraction of it
        ("actuator_stick_l_gainprm_gain", 10),
        ("geom_thorax_margin", 10),
        ("geom_thorax_friction_torsional_rolling", 10),
        ("geom_thorax_solref_timeconst", 1),
        ("timestep", 1),
    ):
        assert factor(name) == pytest.approx(expected, rel=1e-15), name
    assert mm.parameter("actuator_stick_l_ctrlrange").value == fly.parameter("actuator_stick_l_ctrlrange").value
