"""MJCF models through MuJoCo: parameters and their dimensions, systems, scaled copies, saved files."""

from __future__ import annotations

import json
import math
import pickle
import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem import engines
from pitheorem.engines import EngineModelError, UnscalableParameterError

mujoco = pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")
DATA = Path(__file__).resolve().parent / "data" / "engines"


def load(name):
    return engines.load(DATA / name)


def dims(model):
    return {p.name: p.dimension_text for p in model.parameters}


def test_dimensions_follow_the_joint_type():
    d = dims(load("tendon_actuators.xml"))
    # hinge: torques and angles; slide: forces and lengths
    assert d["joint_hinge_damping"] == "M L^2 T^-1"
    assert d["joint_slide_damping"] == "M T^-1"
    assert d["joint_hinge_stiffness"] == "M L^2 T^-2"
    assert d["joint_slide_stiffness"] == "M T^-2"
    assert d["joint_slide_armature"] == "M"
    assert d["joint_hinge_frictionloss"] == "M L^2 T^-2"
    assert d["joint_slide_range"] == "L"
    assert d["joint_hinge_springref"] == "1"
    # the polynomial terms divide by one more power of the coordinate (rate)
    assert d["joint_slide_damping_poly1"] == "M L^-1"
    assert d["joint_slide_stiffness_poly2"] == "M L^-2 T^-2"
    # tendons: the spatial one measures a length, the fixed one over hinges an angle
    assert d["tendon_rope_stiffness"] == "M T^-2"
    assert d["tendon_couple_stiffness"] == "M L^2 T^-2"
    assert d["tendon_rope_springlength"] == "L"


def test_control_dimensions_follow_the_actuator_kind():
    model = load("tendon_actuators.xml")
    d = dims(model)
    assert d["actuator_push_ctrlrange"] == "M L T^-2"  # a motor on a slide: a force
    assert d["actuator_servo_biasprm_length"] == "M L^2 T^-2"  # kp of a hinge servo: torque per radian
    assert d["actuator_speed_gainprm_gain"] == "M T^-1"  # kv of a slide velocity servo: force per speed
    assert d["actuator_filtered_dynprm_timeconst"] == "T"
    controls = [str(x) for x in model.runner.control_dimensions()]
    assert controls == ["M L T^-2", "1", "L T^-1", "T^-1", "1", "M L T^-2"]


def test_a_ball_joint_a_derived_mass_and_a_partly_set_vector_keep_their_dimensions_and_sources(tmp_path):
    # a ball joint turns like a hinge; a body whose inertial the compiler replaces (inertiafromgeom="true")
    # has the mass MuJoCo computes from its geom (the oracle: a sphere's volume times its density); a surface
    # velocity whose first entry alone is set is listed; a free joint's damping polynomial mixes dimensions
    path = tmp_path / "kinds.xml"
    path.write_text("""<mujoco><compiler inertiafromgeom="true"/><worldbody>
      <body name="a"><joint name="ball" type="ball" damping="0.5" range="0 1"/>
        <inertial pos="0 0 0" mass="2" diaginertia="1 1 1"/>
        <geom name="belt" size=".1" density="1000" surfacevel="1 0 0 0 0 0"/></body>
    </worldbody></mujoco>""")
    model = load(path)
    d = dims(model)
    assert d["joint_ball_damping"] == "M L^2 T^-1"
    assert d["joint_ball_range"] == "1"
    assert d["geom_belt_surfacevel_linear"] == "L T^-1"
    mass = model.parameter("body_a_mass")
    assert mass.source == "derived"
    assert mass.value[0] == pytest.approx(4 / 3 * math.pi * 0.1**3 * 1000, rel=1e-12)
    free = tmp_path / "free.xml"
    free.write_text(
        '<mujoco><worldbody><body><joint type="free" damping="0 1"/><geom size=".1"/></body></worldbody></mujoco>'
    )
    with pytest.raises(EngineModelError, match="damping polynomial terms on a free joint"):
        load(free)


@given(st.lists(st.floats() | st.sampled_from([0.0, -0.0, math.nan]), max_size=6))
def test_an_attribute_is_set_where_any_entry_is_nonzero_or_nan(values):
    # the oracle: the definition entry by entry, on the forms MuJoCo's spec hands out (a float, a vector of
    # floats) and on integers
    from pitheorem.engines.fileformats.mjcf import _set

    want = any(v != 0 for v in values)
    assert _set(np.array(values, dtype=float)) is want
    assert _set(np.array(values, dtype=float).reshape(len(values), 1)) is want
    if values:
        assert _set(values[0]) is (values[0] != 0)
    whole = [int(v) for v in values if abs(v) < 2**62]  # NaN is no integer
    assert _set(np.array(whole, dtype=int)) is any(v != 0 for v in whole)


def test_an_adhesion_gain_is_a_force_and_its_input_a_fraction(tmp_path):
    # MuJoCo's reference: the adhesion force is the input times the gain, "in units of force"; the input is
    # a nonnegative fraction. The oracle is MuJoCo's own actuator force, which must be the gain times ctrl.
    path = tmp_path / "gecko.xml"
    path.write_text("""<mujoco><worldbody><geom type="plane" size="1 1 .1"/>
      <body name="pad" pos="0 0 .05"><freejoint/><geom type="box" size=".05 .05 .05"/></body></worldbody>
      <actuator><adhesion name="grip" body="pad" gain="3" ctrlrange="0 1"/></actuator></mujoco>""")
    model = load(path)
    d = dims(model)
    assert d["actuator_grip_gainprm_gain"] == "M L T^-2"
    assert d["actuator_grip_ctrlrange"] == "1"
    compiled = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(compiled)
    data.ctrl[:] = 0.5
    mujoco.mj_forward(compiled, data)
    assert data.actuator_force[0] == model.parameter("actuator_grip_gainprm_gain").value[0] * 0.5


def test_a_servos_damping_ratio_is_dimensionless_and_its_compiled_kv_follows_the_units(tmp_path):
    # <position dampratio>: MuJoCo keeps the ratio in biasprm[2] (positive) and its compiler replaces it by
    # -kv = -2 ratio sqrt(kp m); read as a kv, a change of mass units multiplied the ratio itself
    path = tmp_path / "servo.xml"
    path.write_text("""<mujoco><worldbody><body><joint name="j" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 -1" size=".1"/></body></worldbody>
      <actuator><position name="p" joint="j" kp="30" dampratio="0.7"/>
      <position name="q" joint="j" kp="30" kv="2"/></actuator></mujoco>""")
    model = load(path)
    d = dims(model)
    assert d["actuator_p_biasprm_dampratio"] == "1"
    assert d["actuator_q_biasprm_velocity"] == "M L^2 T^-1"  # an explicit kv is a torque per angular speed
    heavier = model.scaled(pt.Scaling.from_unit_change(model.system(), {"M": 1}), 4)
    assert heavier.parameter("actuator_p_biasprm_dampratio").value == (0.7,)
    original = mujoco.MjModel.from_xml_path(str(path)).actuator_biasprm[:, 2]
    assert original[0] < 0  # compiled into -kv
    copy = heavier.save(tmp_path / "heavier.xml")
    assert mujoco.MjModel.from_xml_path(str(copy)).actuator_biasprm[:, 2].tolist() == (4 * original).tolist()


def test_values_are_the_engines_own():
    model = load("tendon_actuators.xml")
    compiled = model.runner.mjmodel
    cart = mujoco.mj_name2id(compiled, mujoco.mjtObj.mjOBJ_BODY, "cart")
    assert model.parameter("body_cart_mass").value == (1.5,)
    mujoco.mj_name2id(compiled, mujoco.mjtObj.mjOBJ_BODY, "arm")
    # density 800 times the capsule's volume (cylinder plus sphere), computed by MuJoCo, read back
    r, h = 0.02, 0.4
    volume = math.pi * r * r * h + 4 / 3 * math.pi * r**3
    assert model.parameter("body_arm_mass").value[0] == pytest.approx(800 * volume, rel=1e-12)
    assert model.parameter("body_arm_mass").source == "derived"
    assert compiled.body_mass[cart] == 1.5
    assert model.parameter("g").value == (9.81,)
    assert model.parameter("timestep").value == (0.001,)
    assert model.parameter("joint_slide_damping").source == "file"
    assert model.parameter("joint_hinge_margin").source == "default"


def test_system_has_g_and_t_and_every_parameter():
    model = load("contact.xml")
    system = model.system()
    assert system.dimension("g") == pt.Dimension.parse("L T^-2")
    assert system.dimension("t") == pt.Dimension.parse("T")
    assert {p.name for p in model.parameters if not p.mixed} <= set(system.variables)
    res = pt.search(system, scale={"g": 1})
    assert res.feasible
    assert res.scalings[0].unit_change["L"] == 1  # gravity by s with time fixed: lengths by s


def test_mixed_free_joint_damping_is_reported_and_refused():
    model = load("free_damped.xml")
    damping = model.parameter("joint_root_damping")
    assert damping.mixed
    assert set(damping.variables()) == {"joint_root_damping_lin", "joint_root_damping_rot"}
    system = model.system()
    assert str(system.dimension("joint_root_damping_lin")) == "M T^-1"
    assert str(system.dimension("joint_root_damping_rot")) == "M L^2 T^-1"
    sc = pt.search(system, scale={"g": 1}).scalings[0]
    with pytest.raises(UnscalableParameterError, match="joint_root_damping"):
        model.scaled(sc, 2)
    # a change of units that moves only time keeps both parts equal: allowed
    time_only = pt.Scaling.from_unit_change(system, {"T": 1})
    assert model.scaled(time_only, 2).parameter("joint_root_damping").value == (0.05,)
    err = UnscalableParameterError("x", "y")
    assert str(pickle.loads(pickle.dumps(err))) == str(err)


def test_several_numbers_that_cannot_follow_are_named_once_each_kind_with_the_remedy(tmp_path):
    """Two free joints with damping (gymnasium-robotics' Shadow hand: its block and its target): one message
    names both, says once why, and keeps the remedy."""
    path = tmp_path / "two.xml"
    path.write_text(
        (DATA / "free_damped.xml")
        .read_text()
        .replace(
            "</worldbody>",
            '<body name="target" pos="1 0 1"><joint name="aim" type="free" damping="0.2"/>'
            '<geom type="sphere" size="0.1"/></body></worldbody>',
        )
    )
    model = engines.load(path)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    with pytest.raises(UnscalableParameterError) as caught:
        model.scaled(sc, 2)
    text = str(caught.value)
    assert "2 numbers cannot follow the scaling: 'joint_root_damping', 'joint_aim_damping'." in text
    assert text.count("acts with dimensions") == 1  # one reason per kind, not per joint
    assert text.endswith("Set it to 0 or hold the base units it mixes fixed.")


def test_scaled_model_compiles_to_the_scaled_numbers(tmp_path):
    model = load("tendon_actuators.xml")
    sc = pt.Scaling.from_unit_change(model.system(), {"M": 1, "L": 1, "T": 1})
    s = 2
    scaled = model.scaled(sc, s)
    a, b = model.runner.mjmodel, scaled.runner.mjmodel
    # oracle: MuJoCo's compiled arrays, each times s to the power of its dimension, worked out by hand
    assert np.array_equal(b.body_mass, a.body_mass * 2)  # M
    assert np.array_equal(b.body_inertia, a.body_inertia * 2 * 4)  # M L^2
    assert np.array_equal(b.geom_size, a.geom_size * 2)  # L
    slide = mujoco.mj_name2id(a, mujoco.mjtObj.mjOBJ_JOINT, "slide")
    hinge = mujoco.mj_name2id(a, mujoco.mjtObj.mjOBJ_JOINT, "hinge")
    assert b.dof_damping[a.jnt_dofadr[slide]] == a.dof_damping[a.jnt_dofadr[slide]] * 2 / 2  # M T^-1
    assert b.dof_damping[a.jnt_dofadr[hinge]] == a.dof_damping[a.jnt_dofadr[hinge]] * 2 * 4 / 2  # M L^2 T^-1
    assert b.jnt_stiffness[slide] == a.jnt_stiffness[slide] * 2 / 4  # M T^-2
    assert np.array_equal(b.jnt_range[slide], a.jnt_range[slide] * 2)
    assert b.opt.timestep == a.opt.timestep * 2
    assert np.array_equal(b.opt.gravity, a.opt.gravity * 2 / 4)
    assert np.array_equal(b.tendon_lengthspring, a.tendon_lengthspring * np.array([[1, 1], [2, 2]]))
    # saved, reloaded: the same numbers (full precision)
    out = scaled.save(tmp_path / "scaled.xml")
    again = engines.load(out).runner.mjmodel
    for field in (
        "body_mass",
        "body_inertia",
        "geom_size",
        "dof_damping",
        "jnt_stiffness",
        "actuator_gainprm",
        "actuator_biasprm",
        "tendon_stiffness",
        "geom_solref",
    ):
        assert np.array_equal(getattr(again, field), getattr(b, field)), field


def test_keyframes_scale_with_the_coordinates():
    model = load("contact.xml")
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    scaled = model.scaled(sc, 10)
    a, b = model.runner.mjmodel, scaled.runner.mjmodel
    # ball: free joint (x y z of length, quaternion), box likewise, then two hinges
    assert b.key_qpos[0][:3].tolist() == [0, 0, 5.0]
    assert b.key_qpos[0][3:7].tolist() == a.key_qpos[0][3:7].tolist()
    assert b.key_qvel[0][:3].tolist() == [5.0, 0, 10.0]
    assert b.key_qvel[0][6] == 10.0


def test_keyframes_of_a_model_with_activations_scale_velocity_and_activation_apart(tmp_path):
    # a filtered motor has an activation: the coordinates are qpos, qvel, then act; a keyframe's qvel is
    # the velocities alone (this raised a numpy broadcast error before)
    path = tmp_path / "filtered.xml"
    path.write_text("""<mujoco><worldbody><body><joint name="slide" type="slide" axis="1 0 0"/>
      <geom type="box" size="0.1 0.1 0.1" mass="1"/></body></worldbody>
      <actuator><general name="f" joint="slide" dyntype="filter" dynprm="0.1" gainprm="5"/></actuator>
      <keyframe><key time="0.5" qpos="0.25" qvel="0.5" ctrl="0.75" act="1"/></keyframe></mujoco>""")
    model = engines.load(path)
    sc = pt.Scaling.from_unit_change(model.system(), {"M": 1, "L": 1})
    b = model.scaled(sc, 2).runner.mjmodel
    # oracle by hand, mass and length units times 2: qpos a length (s), qvel L T^-1 (s), time T (1); ctrl
    # and act are the filtered force's input, a force M L T^-2 (s^2)
    assert b.key_qpos[0].tolist() == [0.5]
    assert b.key_qvel[0].tolist() == [1.0]
    assert b.key_time[0] == 0.5
    assert b.key_ctrl[0].tolist() == [3.0]
    assert b.key_act[0].tolist() == [4.0]


def test_with_values_and_bad_requests():
    model = load("contact.xml")
    assert model.with_values(timestep=0.001).parameter("timestep").value == (0.001,)
    with pytest.raises(pt.UnknownVariableError):
        model.with_values(no_such=1)
    with pytest.raises(pt.InvalidRequestError):
        model.scaled({"g": 1}, 2)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    for bad in (0, -1, math.inf, True, "x"):
        with pytest.raises(pt.InvalidRequestError):
            model.scaled(sc, bad)
    # the check is isinstance, not a list of attributes: a look-alike is refused
    look_alike = SimpleNamespace(
        system=sc.system,
        powers=sc.vector,
        vector=sc.vector,
        exponent_of=sc.exponent_of,
        units=sc.unit_change_vector,
        unit_change_vector=sc.unit_change_vector,
    )
    with pytest.raises(pt.InvalidRequestError, match="Scaling, got SimpleNamespace"):
        model.scaled(look_alike, 2)


@pytest.mark.parametrize(
    ("name", "element", "reason"),
    [
        ("missing_mesh.xml", "mesh 'hull'", "no_such_hull.stl"),
        ("unknown_element.xml", "gizmo", "unrecognized element"),
    ],
)
def test_bad_files_name_the_element(name, element, reason):
    with pytest.raises(EngineModelError) as caught:
        load(name)
    text = str(caught.value)
    assert element in text
    assert reason in text
    assert "\n" not in text
    assert str(pickle.loads(pickle.dumps(caught.value))) == text


def test_missing_and_non_xml_files(tmp_path):
    with pytest.raises(EngineModelError, match="no such file"):
        engines.load(tmp_path / "absent.xml")
    junk = tmp_path / "junk.xml"
    junk.write_text("this is not XML")
    with pytest.raises(EngineModelError, match=r"junk\.xml"):
        engines.load(junk)


def test_mixed_fixed_tendon_cannot_be_rewritten(tmp_path):
    text = (
        (DATA / "tendon_actuators.xml")
        .read_text()
        .replace('<joint joint="wrist" coef="-0.5"/>', '<joint joint="slide" coef="-0.5"/>')
    )
    path = tmp_path / "mixed.xml"
    path.write_text(text)
    model = engines.load(path)
    coefficient = model.parameter("tendon_couple_coef1")  # the path's second entry, as the file gives it
    assert (coefficient.dimension_text, coefficient.value) == ("L^-1", (-0.5,))
    with pytest.raises(UnscalableParameterError, match="tendon 'couple'"):
        model.scaled(pt.Scaling.from_unit_change(model.system(), {"L": 1}), 2)
    # lengths unchanged: the coefficient needs no change, so the copy is made
    assert model.scaled(pt.Scaling.from_unit_change(model.system(), {"M": 1}), 2).engine == "mujoco"


def test_unknown_sensor_and_numeric_warn(tmp_path):
    path = tmp_path / "numeric.xml"
    path.write_text(
        '<mujoco><custom><numeric name="frame_skip" data="5"/></custom>'
        '<worldbody><body><joint/><geom size="0.1"/></body></worldbody></mujoco>'
    )
    with pytest.warns(engines.UnscalableModelWarning, match="numeric 'frame_skip'"):
        engines.load(path)


def _custom_model(tmp_path, custom: str):
    path = tmp_path / "custom.xml"
    path.write_text(
        f"<mujoco><custom>{custom}</custom>"
        '<worldbody><body><joint type="slide"/><geom size="0.1"/></body></worldbody></mujoco>'
    )
    return path


def test_custom_numerics_with_a_declared_dimension_are_parameters(tmp_path):
    path = _custom_model(
        tmp_path,
        '<numeric name="gain" data="4 0.5"/><text name="dimension:gain" data="L T^-1"/>'
        '<numeric name="ratio" data="2"/><text name="dimension:ratio" data="1"/>',
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # declared numerics warn no more
        model = engines.load(path)
    gain = model.parameter("numeric_gain")
    assert (gain.value, gain.dimension_text, gain.source) == ((4.0, 0.5), "L T^-1", "file")
    assert model.system().dimension("numeric_gain") == pt.Dimension.parse("L T^-1")
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1, "T": -1})
    scaled = model.scaled(sc, 10)
    assert scaled.parameter("numeric_gain").value == (400.0, 50.0)  # L T^-1 at s^1 s^1
    assert scaled.parameter("numeric_ratio").value == (2.0,)
    saved = engines.load(scaled.save(tmp_path / "scaled.xml"))
    assert saved.parameter("numeric_gain").value == (400.0, 50.0)
    assert saved.parameter("numeric_gain").dimension_text == "L T^-1"  # the declaration travels with the file


@pytest.mark.parametrize(
    ("custom", "culprit", "hint"),
    [
        (
            '<numeric name="gain" data="4"/><text name="dimension:gain" data="L T^^-1"/>',
            "dimension:gain",
            "dimension formula",
        ),
        ('<numeric name="gain" data="4"/><text name="dimension:gian" data="L"/>', "dimension:gian", "'gain'"),
    ],
)
def test_bad_dimension_declarations_name_the_text(tmp_path, custom, culprit, hint):
    with pytest.raises(EngineModelError) as caught:
        engines.load(_custom_model(tmp_path, custom))
    assert culprit in str(caught.value)
    assert hint in str(caught.value)


# -- bad numbers in the file (issue 23): refused by name, not dropped (nan) or kept (inf)

_PENDULUM = """<mujoco model="p">
  <option timestep="{timestep}"/>
  <worldbody>
    <body name="b" pos="0 0 1">
      <joint name="h" type="hinge" damping="{damping}" stiffness="{stiffness}"/>
      <geom name="g" type="capsule" size="0.05" fromto="0 0 0 0 0 -1" mass="1"/>
    </body>
  </worldbody>
</mujoco>
"""


@pytest.mark.parametrize(
    ("numbers", "element", "attribute"),
    [
        ({"damping": "nan"}, "<joint name='h'>", "damping='nan'"),
        ({"stiffness": "inf"}, "<joint name='h'>", "stiffness='inf'"),
        ({"timestep": "nan"}, "<option>", "timestep='nan'"),
        ({"damping": "1e999"}, "<joint name='h'>", "damping='1e999'"),
    ],
)
def test_nan_and_infinite_numbers_are_refused_by_name(tmp_path, numbers, element, attribute):
    path = tmp_path / "bad.xml"
    text = _PENDULUM.format(**{"timestep": "0.002", "damping": "0.1", "stiffness": "0", **numbers})
    path.write_text(text)
    with pytest.raises(EngineModelError) as caught:
        engines.load(path)
    line = next(k for k, row in enumerate(text.strip().splitlines(), 1) if attribute.replace("'", '"') in row)
    assert str(caught.value) == (
        f"{path}: line {line}, {element}: {attribute} is not a finite number; a model holds finite numbers only"
    )


def test_the_same_file_with_finite_numbers_loads_them():
    # the oracle of the test above: the file itself is fine, and its damping is a parameter
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "good.xml"
        path.write_text(_PENDULUM.format(timestep="0.002", damping="0.1", stiffness="0"))
        values = {p.name: p.value for p in engines.load(path).parameters}
    assert values["joint_h_damping"] == (0.1,)
    assert values["timestep"] == (0.002,)


def test_a_byte_that_is_not_utf8_is_refused_by_line(tmp_path):
    path = tmp_path / "latin1.xml"
    path.write_bytes(
        _PENDULUM.format(timestep="0.002", damping="0.1", stiffness="0")
        .replace('name="b"', 'name="b\xe9"')
        .encode("latin-1")
    )
    with pytest.raises(EngineModelError, match=r"latin1\.xml: line 4: byte 0xe9 .* not UTF-8"):
        engines.load(path)


def test_a_composed_scene_saves_with_every_models_meshes_found(tmp_path):
    """<model> + <attach>: the attached model's meshes live in its own meshdir, not the scene's."""
    scene = Path(__file__).resolve().parent / "robots" / "mjcf" / "attach" / "scene.xml"
    model = engines.load(scene)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    for s in (1, 4):
        again = engines.load(model.scaled(sc, s).save(tmp_path / f"scene_{s}.xml"))
        assert [p.name for p in again.parameters] == [p.name for p in model.parameters]
    files = {m.name: Path(m.file) for m in again.runner.spec.meshes}
    assert files["g_palm"].parent.name == "gripper_parts"  # the gripper's folder, not the arm's
    assert files["base"].parent.name == "arm_parts"
    # each named relative to the saved file (which travels with them), and found from its folder
    assert not any(f.is_absolute() for f in files.values())
    assert all((tmp_path / f).is_file() for f in files.values())


def test_a_saved_copy_writes_each_scaled_number_as_its_exact_decimal_product(tmp_path):
    """9.81 x 10 is written 98.1 (the float product is 98.10000000000001); at s = 4 the same doubles as in memory."""
    from decimal import Decimal, getcontext

    getcontext().prec = 60
    model = engines.load(engines.example_path("pendulum.xml"))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    text = model.scaled(sc, 10).save(tmp_path / "p10.xml").read_text()
    assert 'gravity="0 0 -98.1"' in text
    again = engines.load(tmp_path / "p10.xml")
    for p in model.parameters:  # every single-number parameter: the double nearest the decimal product
        if len(p.value) != 1 or p.mixed or p.value[0] == 0 or p.source == "derived":
            continue
        factor = p.factor(sc, 10)
        exact = float(Decimal(repr(p.value[0])) * Decimal(repr(factor)))
        assert again.parameter(p.name).value[0] == exact, p.name
    at_four = model.scaled(sc, 4)
    reloaded = engines.load(at_four.save(tmp_path / "p4.xml"))
    assert [p.value for p in reloaded.parameters] == [p.value for p in at_four.parameters]


def test_assets_pairs_statistics_compiler_bounds_and_direct_solrefs_have_their_dimensions():
    # one file with the elements the other models lack; each dimension is the physics of the attribute
    with pytest.warns(engines.UnscalableModelWarning, match="magnetic field"):
        model = load("rich_elements.xml")
    got = {p.name: (p.dimension_text, p.value) for p in model.parameters}
    expected = {
        "stat_meanmass": ("M", (2.0,)),
        "stat_meansize": ("L", (0.5,)),
        "stat_extent": ("L", (3.0,)),
        "stat_center": ("L", (0.0, 0.0, 1.0)),
        "compiler_boundmass": ("M", (0.01,)),
        "compiler_boundinertia": ("M L^2", (0.001,)),
        "compiler_settotalmass": ("M", (3.0,)),
        "hfield_ground_size": ("L", (1.0, 1.0, 0.1, 0.05)),
        # a negative solref is a stiffness and a damping of the reference acceleration, not a time constant
        "joint_h_solref_limit_stiffness": ("T^-2", (-100.0,)),
        "joint_h_solref_limit_damping": ("T^-1", (-10.0,)),
        "pair0_margin": ("L", (0.01,)),
        "pair0_gap": ("L", (0.002,)),
        "pair0_solref_stiffness": ("T^-2", (-200.0,)),
        "pair0_solref_damping": ("T^-1", (-20.0,)),
    }
    assert {name: got[name] for name in expected} == expected
    # inline vertices are the length scaled; their scale (a factor on them) is not scaled too (s^2)
    assert "mesh_tet_scale" not in got
    assert got["mesh_tet_uservert"][0] == "L"
    assert len(got["mesh_tet_uservert"][1]) == 12


def test_a_flex_element_is_refused_by_name(tmp_path):
    path = tmp_path / "flex.xml"
    path.write_text(
        '<mujoco><worldbody><flexcomp name="cloth" type="grid" count="2 2 1" spacing="0.1 0.1 0.1" '
        'dim="2"/></worldbody></mujoco>'
    )
    with pytest.raises(EngineModelError, match="flex elements cannot be scaled"):
        engines.load(path)


WORM = """<mujoco model="worm">
  <option timestep="0.0005"/>
  <worldbody>
    <geom name="floor" type="plane" size="0.01 0.01 0.001" friction="1 5e-6 1e-7" condim="6"/>
    <body name="s0" pos="0 0 0.0001">
      <freejoint/>
      <geom type="capsule" fromto="0 0 0 0.0002 0 0" size="0.00005" density="1050"/>
      <body name="s1" pos="0.0002 0 0">
        <joint name="bend1" type="hinge" axis="0 0 1" stiffness="1e-9" damping="1e-11"/>
        <geom type="capsule" fromto="0 0 0 0.0002 0 0" size="0.00005" density="1050"/>
      </body>
    </body>
  </worldbody>
  <actuator><motor name="m1" joint="bend1" ctrlrange="-1e-9 1e-9"/></actuator>
</mujoco>
"""


def test_a_file_refused_for_a_threshold_loads_as_a_table_and_converts_into_units_that_run(tmp_path):
    path = tmp_path / "worm.xml"
    path.write_text(WORM)
    with pytest.raises(ValueError, match="mjMINVAL"):  # independent of pitheorem: MuJoCo refuses the file
        mujoco.MjModel.from_xml_path(str(path))
    worm = engines.load(path)
    assert type(worm.runner.document).__name__ == "RefusedMjcfDocument"
    # the table's masses are the file's own: density times volume, not the probe's
    radius, length = 5e-5, 2e-4
    volume = np.pi * radius**2 * length + 4 / 3 * np.pi * radius**3
    assert worm.parameter("body_s1_mass").value[0] == pytest.approx(1050 * volume, rel=1e-12)
    found = engines.check(worm)
    assert "mujoco refuses the file: Error: mass and inertia" in found[0].detail  # the refusal first
    causes = {c.element: c.detail for c in found}
    assert "mujoco_minval_mass" in causes["body_s1_inertia"]
    with pytest.raises(engines.EngineModelError, match="MuJoCo does not run it"):
        worm.runner.run(10)
    from pitheorem.engines.fitting import fitted_units

    units = fitted_units(worm, pt.fit_units(worm))
    fitted = worm.converted(**units)
    assert engines.check(fitted) == ()
    assert np.isfinite(fitted.runner.run(200)).all()
    mm = worm.converted(L="mm", M="mg")  # by hand: also clear
    assert mm.parameter("body_s1_mass").value[0] == pytest.approx(1050 * volume * 1e6, rel=1e-12)


MUSCLE = (
    '<mujoco><option timestep="0.002"/><worldbody><site name="a"/><body pos="0 0 -0.3">'
    '<joint name="j" type="slide" axis="0 0 1" limited="true" range="-0.1 0.1"/>'
    '<geom size="0.05" mass="1"/><site name="b"/></body></worldbody>'
    '<tendon><spatial name="t"><site site="a"/><site site="b"/></spatial></tendon>'
    '<actuator><muscle name="m" tendon="t" FORCE/></actuator></mujoco>'
)


def test_a_muscle_is_read_with_its_dimensions_and_its_found_length_range_is_stated_in_a_copy(tmp_path):
    path = tmp_path / "muscle.xml"
    path.write_text(MUSCLE.replace("FORCE", 'force="50"'))
    model = engines.load(path)
    dims = {p.name: p.dimension_text for p in model.parameters if p.name.startswith("actuator_m_")}
    assert dims["actuator_m_gainprm_peak_force"] == "M L T^-2"
    assert dims["actuator_m_gainprm_vmax"] == "T^-1"
    assert dims["actuator_m_dynprm_timeconst"] == "T"
    assert dims["actuator_m_ctrlrange"] == "1"
    found = model.parameter("actuator_m_lengthrange")
    assert found.source == "derived"  # the file leaves it out; MuJoCo's compiler simulated to find it
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    saved = engines.load(model.scaled(sc, 4).save(tmp_path / "muscle_4.xml"))
    import mujoco

    lengths = saved.runner.mjmodel.actuator_lengthrange[0]
    assert list(lengths) == [4 * v for v in found.value]  # stated, not found again by a simulation
    excite = engines.verify(model, sc, 4, duration=1.0, scaled=saved, controls=lambda t: [0.5 + 0.4 * np.sin(6 * t)])
    assert excite.exact
    assert excite.excited
    again = mujoco.MjModel.from_xml_string(
        MUSCLE.replace("FORCE", 'force="200"')
        .replace("0.3", "1.2")
        .replace("0.05", "0.2")
        .replace("-0.1 0.1", "-0.4 0.4")
    )  # the copy without the stated range: found again, not x4
    assert list(again.actuator_lengthrange[0]) != [4 * v for v in found.value]


def test_a_muscle_whose_peak_force_mujoco_derives_is_refused_by_name(tmp_path):
    path = tmp_path / "muscle.xml"
    path.write_text(MUSCLE.replace("FORCE", ""))
    with pytest.raises(engines.EngineModelError) as err:
        engines.load(path)
    assert str(err.value).endswith(
        "actuator 'm': a muscle whose peak force MuJoCo derives from scale and acc0 (gainprm[2] = -1) "
        'cannot be scaled: give its force explicitly (force="...")'
    )


def test_a_joint_equalitys_polynomial_coefficients_are_read_one_by_one(tmp_path):
    # q1 = c0 + c1 q2 + c2 q2^2 + ... between slide joints: c_i is a length to the power 1 - i
    path = tmp_path / "coupled.xml"
    path.write_text(
        '<mujoco><worldbody><body><joint name="a" type="slide"/><geom size=".1"/></body>'
        '<body><joint name="b" type="slide"/><geom size=".1"/></body></worldbody>'
        '<equality><joint name="couple" joint1="a" joint2="b" polycoef="0.1 0.2 0.3 0.4 0.5"/></equality></mujoco>'
    )
    params = {p.name: p for p in engines.load(path).parameters}
    for i in range(5):
        p = params[f"equality_couple_data_polycoef{i}"]
        assert p.value == (pytest.approx(0.1 * (i + 1)),)
        assert p.dimension == pt.Dimension.parse("L") ** (1 - i)


def test_an_actuators_default_ctrlrange_is_named_default_and_an_affine_gain_by_its_actuator(tmp_path):
    path = tmp_path / "affine.xml"
    path.write_text(
        '<mujoco><worldbody><body><joint name="j" type="slide"/><geom size=".1"/></body></worldbody>'
        '<actuator><general name="a" joint="j" gaintype="affine" gainprm="2 3 4" ctrlrange="0 1"/>'
        '<motor name="m" joint="j"/></actuator></mujoco>'
    )
    params = {p.name: p for p in engines.load(path).parameters}
    assert params["actuator_m_ctrlrange"].source == "default"  # MuJoCo's own 0 0, left unset
    assert params["actuator_a_ctrlrange"].source == "file"
    assert params["actuator_a_gainprm_gain"].dimension == pt.Dimension.parse("M L T^-2")
    assert params["actuator_a_gainprm_gain"].value == (2.0,)


def test_the_readers_names_paths_and_sources_of_plain_attributes(tmp_path):
    path = tmp_path / "plain.xml"
    path.write_text(
        '<mujoco><worldbody><body name="b" pos="0 0 1"><joint name="j" type="slide"/>'
        '<geom name="g" size=".1" mass="1"/></body></worldbody></mujoco>'
    )
    params = {p.name: p for p in engines.load(path).parameters}
    assert params["timestep"].path == "option timestep"
    assert params["o_friction_torsional_rolling"].path == "option o_friction torsional rolling"
    assert params["geom_g_solimp_width"].path == "geom 'g' solimp width"
    assert params["body_b_ipos"].path == "body 'b' ipos"
    # left at MuJoCo's own defaults: named so (the kind of element decides which default applies)
    assert params["joint_j_frictionloss"].source == "default"
    assert params["geom_g_pos"].source == "default"
    assert params["body_b_pos"].source == "file"


def _skin_file(path: Path, verts, faces, bones) -> None:
    """A binary ``.skn`` file as MuJoCo's documentation of ``<skin file>`` lays it out.

    Four int32 counts (vertices, texture coordinates, faces, bones), the vertex positions (float32), the
    faces (int32), then per bone: its body's name in 40 bytes, bind position (3 float32), bind quaternion
    (4 float32), vertex count (int32), vertex ids (int32) and weights (float32).
    """
    import struct

    out = struct.pack("4i", len(verts), 0, len(faces), len(bones))
    out += struct.pack(f"{3 * len(verts)}f", *(c for v in verts for c in v))
    out += struct.pack(f"{3 * len(faces)}i", *(i for f in faces for i in f))
    for name, pos, ids, weights in bones:
        out += name.encode().ljust(40, b"\0") + struct.pack("3f", *pos) + struct.pack("4f", 1, 0, 0, 0)
        out += struct.pack("i", len(ids)) + struct.pack(f"{len(ids)}i", *ids) + struct.pack(f"{len(ids)}f", *weights)
    path.write_bytes(out)


@pytest.mark.parametrize("inline", [True, False], ids=["inline", "file"])
def test_a_skin_is_scaled_as_lengths_and_written_back(tmp_path, inline):
    # a render-only mesh bound to a body: its vertices and bind positions are lengths, as in dm_control's dog
    verts = [(0.0, 0.0, 0.0), (0.5, 0.0, 0.0), (0.0, 0.25, 0.0), (0.0, 0.0, 0.125)]
    faces = [(0, 1, 2), (0, 2, 3), (0, 3, 1), (1, 3, 2)]
    bone = ("arm", (0.0, 0.0, 0.5), [0, 1, 2, 3], [1.0, 1.0, 1.0, 1.0])
    if inline:
        skin = (
            '<skin name="hide" inflate="0.01" vertex="{}" face="{}">'
            '<bone body="arm" bindpos="0 0 0.5" bindquat="1 0 0 0" vertid="0 1 2 3" vertweight="1 1 1 1"/></skin>'
        ).format(" ".join(f"{c:g}" for v in verts for c in v), " ".join(str(i) for f in faces for i in f))
    else:
        _skin_file(tmp_path / "hide.skn", verts, faces, [bone])
        skin = '<skin name="hide" file="hide.skn"/>'
    path = tmp_path / "skinned.xml"
    path.write_text(
        f"<mujoco><asset>{skin}</asset><worldbody><body name='arm' pos='0 0 0.5'><joint type='hinge'/>"
        "<geom size='0.1' mass='1'/></body></worldbody></mujoco>"
    )
    model = engines.load(path)
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    out = tmp_path / "moved" / "skinned4.xml"
    out.parent.mkdir()
    model.scaled(lengths, 4).save(out)
    original, scaled = mujoco.MjModel.from_xml_path(str(path)), mujoco.MjModel.from_xml_path(str(out))
    # every vertex, bind position and the inflation four times as long; the faces and bodies as they were
    np.testing.assert_array_equal(scaled.skin_vert, 4 * original.skin_vert)
    np.testing.assert_array_equal(scaled.skin_bonebindpos, 4 * original.skin_bonebindpos)
    np.testing.assert_array_equal(scaled.skin_inflate, 4 * original.skin_inflate)
    np.testing.assert_array_equal(scaled.skin_face, original.skin_face)
    np.testing.assert_array_equal(scaled.skin_bonebodyid, original.skin_bonebodyid)
    assert np.asarray(original.skin_vert).tolist() == [list(v) for v in verts]


ROBOT_MESHES = Path(__file__).resolve().parent / "robots" / "mjcf" / "meshes"
MESHED = """<mujoco>
  <compiler meshdir="parts"/>
  <asset><mesh name="crate" file="crate.stl"/></asset>
  <worldbody><body name="box" pos="0 0 1"><freejoint/><geom type="mesh" mesh="crate" mass="1"/></body></worldbody>
</mujoco>
"""


def _meshed_model(folder: Path) -> Path:
    (folder / "parts").mkdir(parents=True)
    (folder / "parts" / "crate.stl").write_bytes((ROBOT_MESHES / "crate.stl").read_bytes())
    (folder / "box.xml").write_text(MESHED)
    return folder / "box.xml"


def test_a_saved_copy_names_its_meshes_relative_to_itself_and_loads_after_its_folder_moves(tmp_path):
    import shutil

    path = _meshed_model(tmp_path / "lab" / "robot")
    model = engines.load(path)
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    out = tmp_path / "lab" / "robot" / "scaled" / "box4.xml"
    out.parent.mkdir()
    model.scaled(lengths, 4).save(out)
    text = out.read_text()
    assert 'file="../parts/crate.stl"' in text
    assert str(tmp_path) not in text  # no path of this machine
    shutil.move(tmp_path / "lab", tmp_path / "moved")  # the whole folder, elsewhere
    moved = mujoco.MjModel.from_xml_path(str(tmp_path / "moved" / "robot" / "scaled" / "box4.xml"))
    original = mujoco.MjModel.from_xml_path(str(tmp_path / "moved" / "robot" / "box.xml"))
    np.testing.assert_allclose(moved.mesh_vert, 4 * original.mesh_vert, rtol=1e-6)


def test_a_model_opened_through_a_symbolic_link_finds_its_meshes_where_mujoco_does(tmp_path):
    # the file's target lies in a folder without meshes; MuJoCo reads them beside the link
    target = tmp_path / "elsewhere" / "box.xml"
    target.parent.mkdir()
    target.write_text(MESHED)
    folder = tmp_path / "robot"
    _meshed_model(folder)
    (folder / "box.xml").unlink()
    (folder / "box.xml").symlink_to(target)
    assert mujoco.MjModel.from_xml_path(str(folder / "box.xml")).nmesh == 1
    model = engines.load(folder / "box.xml")
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    out = folder / "box4.xml"
    model.scaled(lengths, 4).save(out)
    assert 'file="parts/crate.stl"' in out.read_text()
    assert mujoco.MjModel.from_xml_path(str(out)).nmesh == 1


# -- large files (issue 33): the spec's elements listed in linear time, the collector paused while reading


def _corpus_files() -> list[Path]:
    robots = Path(__file__).resolve().parent / "robots" / "mjcf"
    files = sorted(robots.glob("**/*.xml")) + sorted(DATA.glob("*.xml"))
    try:
        import gymnasium
    except ImportError:
        return files
    return files + sorted((Path(gymnasium.__file__).resolve().parent / "envs" / "mujoco" / "assets").glob("*.xml"))


FRAMES = """<mujoco><worldbody>
<frame name="F0" pos="1 0 0"><geom size="0.1"/><frame><site/><body name="B0"><geom size="1"/></body></frame></frame>
<body name="A"><frame pos="0 1 0"><geom size=".1"/><body><joint/><geom size=".1"/>
<frame name="F3"><joint axis="1 0 0"/><camera/><light/></frame></body></frame><geom size=".1"/>
<body><freejoint/><geom size=".1"/></body></body><geom name="last" size=".1"/></worldbody></mujoco>"""


def test_the_walk_of_the_body_tree_lists_each_collection_as_mujoco_does():
    # the oracle is MuJoCo's own (quadratic) listing: each element it lists is marked through that
    # listing, and the marks must come back in the same order through the tree walk
    from pitheorem.engines.fileformats.mjcf import _COLLECTIONS, _listed

    specs = [(str(f), mujoco.MjSpec.from_file(str(f))) for f in _corpus_files() if _compiles(f)]
    specs.append(("frames", mujoco.MjSpec.from_string(FRAMES)))
    assert len(specs) > 10
    for label, spec in specs:
        for collection in _COLLECTIONS:
            theirs = list(getattr(spec, collection))
            for i, element in enumerate(theirs):
                if not (collection == "bodies" and i == 0):  # the world keeps its name
                    element.name = f"mark_{collection}_{i}"
            assert [e.name for e in _listed(spec, collection)] == [e.name for e in theirs], (label, collection)


def _compiles(path: Path) -> bool:
    try:
        mujoco.MjSpec.from_file(str(path))
    except ValueError:
        return False
    return True


def test_reading_a_file_pauses_the_collector_and_gives_it_back_as_it_was():
    import gc

    from pitheorem.engines.fileformats.mjcf import _collection_paused

    seen = []
    with _collection_paused():
        seen.append(gc.isenabled())
        with _collection_paused():
            seen.append(gc.isenabled())
        seen.append(gc.isenabled())
    assert seen == [False, False, False]
    assert gc.isenabled()
    engines.load(engines.example_path("pendulum.xml"))
    assert gc.isenabled()
    engines.load(engines.example_path("pendulum.xml")).parameters  # noqa: B018 (the table, made now, pauses it too)
    assert gc.isenabled()
    gc.disable()
    try:
        engines.load(engines.example_path("pendulum.xml")).parameters  # noqa: B018
        assert not gc.isenabled()  # a collector the caller disabled stays disabled
    finally:
        gc.enable()
    with pytest.raises(ZeroDivisionError), _collection_paused():
        1 / 0  # noqa: B018
    assert gc.isenabled()


def _same_numbers(a: tuple, b: tuple) -> bool:
    """Equal tuples of Python floats, a NaN equal to a NaN."""
    return (
        len(a) == len(b)
        and all(type(x) is float for x in a)
        and all(x == y or (x != x and y != y) for x, y in zip(a, b, strict=True))
    )


def test_the_table_holds_each_number_as_the_spec_holds_it():
    # the walk keeps the numbers it read, and the table is made from them later: the oracle reads each
    # one's attribute through MuJoCo's bindings again, with numpy, from the file's spec and from a copy
    # scaled by lengths (whose table is made from its own walk of the scaled spec)
    checked, scaled = 0, 0
    for path in _corpus_files():
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                model = engines.load(path)
                copy = model.scaled(pt.Scaling.from_unit_change(model.system(), {"L": 1}), 4)
        except (pt.PiTheoremError, ValueError):  # a file kept for its refusal, or one no length scaling fits
            continue
        for document in (model.runner.document, copy.runner.document):
            table = document.parameters()
            assert [p.name for p in table] == [slot.name for slot in document._slots]
            for p, slot in zip(table, document._slots, strict=True):
                if slot.read is None and slot.element is not None:
                    ((attr, index),) = slot.attrs
                    now = tuple(np.asarray(getattr(slot.element, attr), dtype=float).ravel()[index].tolist())
                    assert _same_numbers(p.value, now), (str(path), p.name, p.value, now)
                    checked += 1
                    scaled += document is copy.runner.document
    assert checked > 2000, checked
    assert scaled > 1000, scaled


def test_a_copy_saved_with_its_assets_copied_loads_alone_after_the_originals_are_gone(tmp_path):
    import shutil

    path = _meshed_model(tmp_path / "lab" / "robot")
    model = engines.load(path)
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    out = tmp_path / "lab" / "out" / "box4.xml"
    out.parent.mkdir()
    scaled = model.scaled(lengths, 4)
    scaled.save(out, copy_assets=True)
    text = out.read_text()
    assert 'file="box4_assets/crate.stl"' in text  # the copy, beside the file, named relative to it
    assert (out.parent / "box4_assets" / "crate.stl").read_bytes() == (ROBOT_MESHES / "crate.stl").read_bytes()
    shutil.rmtree(tmp_path / "lab" / "robot")  # the originals gone: the output folder holds everything
    shutil.move(tmp_path / "lab" / "out", tmp_path / "moved")
    moved = mujoco.MjModel.from_xml_path(str(tmp_path / "moved" / "box4.xml"))
    original = mujoco.MjModel.from_xml_path(str(_meshed_model(tmp_path / "again")))
    np.testing.assert_allclose(moved.mesh_vert, 4 * original.mesh_vert, rtol=1e-6)
    assert engines.load(tmp_path / "moved" / "box4.xml").parameter("g").value == scaled.parameter("g").value


def _table_row(p) -> str:
    parts = " ".join(f"{name}={dimension}" for name, dimension in p.parts)
    dimension = f"parts: {parts}" if p.parts else p.dimension_text
    return " | ".join([p.name, p.path, dimension, p.source, " ".join(repr(v) for v in p.value), p.note])


@pytest.mark.parametrize("tour", ["walker_tour", "walker_tour_defaults"])
def test_the_reader_lists_every_number_of_a_tour_of_elements_with_its_name_place_dimension_and_source(tour):
    # walker_tour.xml sets, on one model, an attribute of nearly every kind of element the reader walks
    # (option, statistic, compiler, an inline mesh, a height field, bodies with and without an inertial,
    # geoms, a frame, sites, a camera, a light, hinge, slide and free joints, a fixed tendon over a slide
    # and a hinge, a spatial tendon, ten actuators of every kind, four equalities, a pair and sensors);
    # walker_tour_defaults.xml leaves at MuJoCo's built-in defaults (or sets to them) the numbers of
    # elements whose defaults the first never holds, and has the kinds of actuator and equality it leaves
    # out. Each .txt is its model's table, in the reader's order, each row checked by hand against MuJoCo's
    # table of units and, for its source, against MuJoCo's documented defaults
    expected = [
        line for line in (DATA / f"{tour}.txt").read_text().splitlines() if line.strip() and not line.startswith("#")
    ]
    got = [_table_row(p) for p in load(f"{tour}.xml").parameters]
    missing = [row for row in expected if row not in got]
    extra = [row for row in got if row not in expected]
    assert (missing, extra) == ([], [])
    assert got == expected  # and in the reader's order


def test_a_scaled_copy_of_the_tour_holds_every_number_times_its_own_factor(tmp_path):
    # each number is found again in the saved copy at its own address, times s to the power its dimension
    # gives: a number written to the wrong element, attribute or entry, or with the wrong dimension, is not
    # (left out: the coefficient between a slide and a hinge, which MjSpec cannot rewrite, and the free
    # joint's mixed numbers, which no change of the length unit keeps; tests above)
    text = (DATA / "walker_tour.xml").read_text().replace('<joint joint="hinge" coef="0.3"/>', "")
    text = text.replace(' damping="0.2" armature="0.01" frictionloss="0.03"', "")
    (tmp_path / "tour.xml").write_text(text)
    model = engines.load(tmp_path / "tour.xml")
    request = {"stat_meanmass": 1, "stat_meansize": 1, "timestep": 1}
    sc = pt.search(model.system(), scale=request, fixed=()).scalings[0]
    assert (sc.unit_change["M"], sc.unit_change["L"], sc.unit_change["T"]) == (1, 1, 1)
    again = engines.load(model.scaled(sc, 4).save(tmp_path / "tour4.xml"))
    checked = 0
    for p in model.parameters:
        if p.mixed or p.source == "derived":  # derived: computed again by MuJoCo from the scaled geometry
            continue
        if p.name == "tendon_mix_width":  # MJCF has no width for a fixed tendon: MuJoCo writes none, reads 0.003
            continue
        factor = p.factor(sc, 4)  # a power of 4: every product is exact, in float32 and float64 alike
        want = " ".join(repr(v * factor) for v in p.value)
        assert " ".join(repr(v) for v in again.parameter(p.name).value) == want, p.name
        checked += factor != 1
    assert checked > 150


_REFUSED = (
    '<mujoco><worldbody><body name="b"><joint name="free" type="free"/><geom size=".1"/></body>'
    '<body name="c" pos="1 0 0"><joint name="ball" type="ball"/><geom size=".1"/>'
    '<body pos="0 0 1"><joint name="h" type="hinge"/><geom size=".1"/></body></body></worldbody>'
    "<actuator>{}</actuator></mujoco>"
)


@pytest.mark.parametrize(
    ("actuator", "reason"),
    [
        ('<motor name="a" joint="free"/>', "an actuator on a free joint mixes forces and torques; not supported"),
        (
            '<motor name="a" joint="ball" gear="1 0 0 1 0 0"/>',
            "ball-joint gear beyond three components is not supported",
        ),
        (
            '<general name="a" joint="h" gaintype="user"/>',
            "gain type mjGAIN_USER is not supported by pitheorem's scaling",
        ),
        (
            '<general name="a" joint="h" biastype="user"/>',
            "bias type mjBIAS_USER is not supported by pitheorem's scaling",
        ),
        (
            '<general name="a" joint="h" dyntype="user"/>',
            "dynamics type mjDYN_USER is not supported by pitheorem's scaling",
        ),
        (  # a muscle's passive force is read with a muscle's gain only
            '<general name="a" joint="h" biastype="muscle" biasprm="0.75 1.05 100 200 0.5 1.6 1.5 1.3 1.2" '
            'lengthrange="0.5 1.5"/>',
            "bias type mjBIAS_MUSCLE is not supported by pitheorem's scaling",
        ),
    ],
)
def test_an_actuator_the_reader_cannot_scale_is_refused_by_name_and_reason(tmp_path, actuator, reason):
    # MuJoCo compiles each of these; the reader refuses it, naming the actuator and why, in one line
    path = tmp_path / "refused.xml"
    path.write_text(_REFUSED.format(actuator))
    with pytest.raises(EngineModelError) as caught:
        engines.load(path)
    assert str(caught.value) == f"{path}: actuator 'a': {reason}"


def test_each_actuators_input_is_carried_by_its_ranges_and_its_gain():
    # what a copy that keeps every input divides by the input's factor: the control's and the activation's
    # ranges (in the input's own units: power 1) and the gain's parameters (force per input: power -1); a
    # muscle's input has no unit, and its gainprm holds its peak force and speed, no gain of the input
    affine = ("gain", "length", "velocity")
    gains = {"dmp": affine, "filt": affine, "mus": ()}
    expected = []
    for name in ("mot", "pos", "ratio", "vel", "iv", "dmp", "site", "crank", "glue", "mus", "filt"):
        powers = {f"actuator_{name}_ctrlrange": 1, f"actuator_{name}_actrange": 1}
        powers.update({f"actuator_{name}_gainprm_{term}": -1 for term in gains.get(name, ("gain",))})
        expected.append(powers)
    assert load("walker_tour.xml").runner.input_parameters() == expected


def test_a_damping_ratio_servo_keeps_its_compiled_damping_in_a_copy_that_keeps_inputs(tmp_path):
    # a slide servo with kp 50 and dampratio 0.7 on a 2 kg cart: MuJoCo compiles kv = 2 * 0.7 * sqrt(50 * 2) = 14.
    # Lengths times 4 with the input kept: the same control (now a quarter of the target length it was)
    # needs four times the gain; the length term (M T^-2) and the damping (M T^-1) keep their values. In the
    # copy the gain is no longer -biasprm[1], so MuJoCo would read a ratio left in biasprm[2] as a damping:
    # the copy states the compiled damping instead
    path = tmp_path / "servo.xml"
    path.write_text(
        '<mujoco><worldbody><body name="cart"><joint name="s" type="slide" axis="1 0 0"/>'
        '<geom type="box" size=".1 .1 .1" mass="2"/></body></worldbody>'
        '<actuator><position name="p" joint="s" kp="50" dampratio="0.7" ctrlrange="-1 1"/></actuator></mujoco>'
    )
    model = engines.load(path)
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    copy = mujoco.MjModel.from_xml_path(str(model.scaled(lengths, 4, keep_inputs=True).save(tmp_path / "servo4.xml")))
    assert list(copy.actuator_gainprm[0][:3]) == [200.0, 0.0, 0.0]
    assert list(copy.actuator_biasprm[0][:3]) == [0.0, -50.0, -14.0]


# -- the table pinned: every field of every row, as the reader gave it before the walker was made faster

#: files that hold between them every kind of element the walker reads (frames, cameras, lights, pairs,
#: equalities, sensors, tendons of both kinds, custom numerics, a height field, the statistic)
TABLED = ("walker_tour.xml", "rich_elements.xml", "tendon_actuators.xml")
TABLES = DATA / "mjcf_tables.json"


def _table(path: Path) -> dict:
    """Every field of every row of a file's table, and its warnings, as text (a float as its repr)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = engines.load(path)
    rows = [
        [
            p.name,
            p.path,
            " ".join(map(repr, p.value)),
            p.dimension_text,
            p.source,
            p.settable,
            " ".join(f"{part}={d}" for part, d in p.parts),
            p.note,
        ]
        for p in model.parameters
    ]
    said = [f"{w.category.__name__}: {w.message}".replace(str(path.parent), "<DATA>") for w in caught]
    return {"parameters": rows, "warnings": said}


def _record_tables() -> None:
    """Write TABLES (run this file as a script): the reader's tables of the TABLED files, one row a line."""
    lines = ["{"]
    for k, name in enumerate(TABLED):
        table = _table(DATA / name)
        lines.append(f"  {json.dumps(name)}: {{")
        lines.append(f'    "warnings": {json.dumps(table["warnings"])},')
        lines.append('    "parameters": [')
        lines.extend(f"      {json.dumps(row)}," for row in table["parameters"])
        lines[-1] = lines[-1].rstrip(",")
        lines.append("    ]")
        lines.append("  }" + ("," if k < len(TABLED) - 1 else ""))
    lines.append("}")
    TABLES.write_text("\n".join(lines) + "\n", encoding="utf-8")


@pytest.mark.parametrize("name", TABLED)
def test_the_table_of_a_file_is_the_one_recorded_before_the_walker_was_made_faster(name):
    # recorded by the walker of commit ed45294 (issue 33, before its speed-up), under MuJoCo 4.0.0: the
    # same names, paths, values, dimensions, sources, parts and notes in the same order, and the same warnings
    expected = json.loads(TABLES.read_text(encoding="utf-8"))[name]
    got = _table(DATA / name)
    assert got["warnings"] == expected["warnings"]
    missing = [row for row in expected["parameters"] if row not in got["parameters"]]
    extra = [row for row in got["parameters"] if row not in expected["parameters"]]
    assert (missing, extra) == ([], [])
    assert got["parameters"] == expected["parameters"]  # and in the same order


if __name__ == "__main__":
    _record_tables()


def test_an_mjcf_file_of_any_suffix_the_format_reads_loads_with_its_includes_and_assets(tmp_path):
    """MuJoCo 4.0's MjSpec.from_file has a decoder for ``.xml`` alone: a ``.mjcf`` or ``.XML`` file, which the format
    reads and MjModel.from_xml_path loads, was refused ("could not find decoder").  Such a file now loads, nested
    includes and a mesh found as from the file, and compiles to MuJoCo's own model of it."""
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "wedge.obj").write_text(
        "v 0 0 0\nv 0.13 0 0\nv 0 0.11 0\nv 0 0 0.07\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
    )
    (tmp_path / "wedge.xml").write_text(
        '<mujocoinclude><body name="wedge" pos="0 0 1"><freejoint/>'
        '<geom type="mesh" mesh="wedge" density="700"/></body></mujocoinclude>'
    )
    (tmp_path / "bodies.xml").write_text('<mujocoinclude><include file="wedge.xml"/></mujocoinclude>')
    text = (
        '<mujoco><compiler meshdir="meshes"/><asset><mesh name="wedge" file="wedge.obj"/></asset>'
        '<worldbody><geom type="plane" size="1 1 1"/><include file="bodies.xml"/></worldbody></mujoco>'
    )
    for name in ("model.mjcf", "model.XML", "model.xml"):
        path = tmp_path / name
        path.write_text(text)
        own = mujoco.MjModel.from_xml_path(str(path))  # the oracle: MuJoCo's reader of any suffix
        model = engines.load(path)
        assert model.runner.mjmodel.nbody == own.nbody == 2
        assert model.runner.mjmodel.body_mass.tolist() == own.body_mass.tolist()
        assert model.runner.mjmodel.mesh_vert.tolist() == own.mesh_vert.tolist()
