"""pitheorem.engines.thresholds: the engines' thresholds, each clamp shown in the installed engine, and check.

Every catalogued threshold that a model's number can cross is measured here
against the engine itself: a run on the far side of it is bit for bit the
run at the threshold (the engine clamps), or the engine refuses, and a run
on the near side differs.  The API tests hold check and crossed against
models whose numbers are put beyond, near and clear of the thresholds.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import re
import textwrap
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt
from pitheorem import engines
from pitheorem.engines.packages import quiet_stdout
from pitheorem.engines.thresholds import (
    BOUNDS,
    KINDS,
    THRESHOLDS,
    Threshold,
    crossed,
    held_against,
    thresholds,
)
from tests.conftest import REPO

mjx_parameters = pytest.importorskip("pitheorem.engines.runners.mjx").mjx_parameters

mujoco = pytest.importorskip("mujoco")
pb = pytest.importorskip("pybullet")


def value(name: str) -> float:
    (t,) = thresholds(names=[name])
    return t.value


def hopper():
    import gymnasium

    return engines.load(Path(gymnasium.__file__).parent / "envs" / "mujoco" / "assets" / "hopper.xml")


def compile_xml(xml: str):
    return mujoco.MjModel.from_xml_string(textwrap.dedent(xml))


# -- the catalogue --------------------------------------------------------------------------------


def test_every_threshold_is_complete_and_of_a_catalogued_engine():
    names = [t.name for t in THRESHOLDS]
    assert len(names) == len(set(names))
    assert {t.engine for t in THRESHOLDS} == set(engines.ENGINES)
    # MJX has MuJoCo's (it compiles with MuJoCo's compiler), then its own
    own = [t for t in THRESHOLDS if t.engine == "mjx"]
    assert thresholds("mjx") == (*thresholds("mujoco"), *own)
    assert own
    assert not set(own) & set(thresholds("mujoco"))
    assert not set(own) & set(thresholds("pybullet"))
    for t in THRESHOLDS:
        assert t.name.startswith({"pybullet": "bullet_"}.get(t.engine, f"{t.engine}_"))
        assert t.precision in ("", "float32")
        assert t.bound in BOUNDS
        assert set(t.applies) <= set(KINDS)
        assert t.dimension is None or isinstance(t.dimension, pt.Dimension)
        assert t.crossed_by
        assert t.effect
        assert "{" not in t.source
        assert "measured with" in t.source  # every threshold is shown against the installed engine
        # only a floor or a ceiling is compared with the model's numbers; an internal threshold or an
        # ignored setting is crossed by nothing the model's table holds
        if t.applies:
            assert t.bound in ("below", "above")


def test_mujoco_thresholds_are_the_engines_own_constants():
    assert value("mujoco_minval_mass") == mujoco.mjMINVAL
    assert value("mujoco_minval_softness") == pytest.approx(1 / mujoco.mjMINVAL, rel=1e-15)
    assert value("mujoco_minmu") == mujoco.mjMINMU
    assert value("mujoco_maxval") == mujoco.mjMAXVAL
    assert value("mujoco_solver_tolerance") == compile_xml("<mujoco/>").opt.tolerance


def test_solver_settings_of_no_pure_dimension_are_catalogued_without_one():
    for name in (
        "mujoco_solver_tolerance",
        "bullet_solver_residual",
        "bullet_multibody_sleep",
        "mujoco_minval_mass",
        "mujoco_minmu",
        "mujoco_maxval",
    ):
        assert thresholds(names=[name])[0].dimension is None
    (residual,) = engines.hidden_constants("pybullet", names=["bullet_solver_residual_threshold"])
    assert residual.dimension.is_dimensionless  # no change of units scales it: copied unchanged
    assert thresholds(names=["mujoco_refsafe"])[0].dimension == pt.Dimension.parse("T")


def test_threshold_records_are_immutable_and_checked():
    t = THRESHOLDS[0]
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.value = 0.0
    fields = {f.name: getattr(t, f.name) for f in dataclasses.fields(t)}
    with pytest.raises(pt.InvalidRequestError, match="unknown bound 'under'"):
        Threshold(**{**fields, "bound": "under"})
    with pytest.raises(pt.InvalidRequestError, match="unknown kind 'torque'"):
        Threshold(**{**fields, "applies": ("torque",)})
    assert Threshold(**{**fields, "dimension": "L T^-1"}).dimension == pt.Dimension.parse("L T^-1")


def test_thresholds_are_picked_by_engine_and_name():
    assert [t.name for t in thresholds("mujoco", names=["mujoco_maxval", "mujoco_minmu"])] == [
        "mujoco_maxval",
        "mujoco_minmu",
    ]
    assert thresholds("bullet") == thresholds("pybullet")  # the old spelling reads as the one name
    assert {t.engine for t in thresholds("pybullet")} == {"pybullet"}
    with pytest.raises(pt.InvalidRequestError, match="no threshold 'mujoco_minmu' of pybullet"):
        thresholds("pybullet", names=["mujoco_minmu"])
    with pytest.raises(pt.InvalidRequestError, match="unknown engine 'ode'"):
        thresholds("ode")


# -- MuJoCo: each clamp, measured -----------------------------------------------------------------


def sliding_body(mass: float, inertia: float) -> str:
    return (
        f'<mujoco><worldbody><body><joint type="slide"/><inertial pos="0 0 0" mass="{mass!r}" '
        f'diaginertia="{inertia!r} {inertia!r} {inertia!r}"/></body></worldbody></mujoco>'
    )


def test_mujoco_refuses_moving_masses_and_inertias_below_minval():
    floor = value("mujoco_minval_mass")
    compile_xml(sliding_body(floor, floor))  # at the threshold: compiles
    for mass, inertia in ((floor / 10, 1.0), (1.0, floor / 10)):
        with pytest.raises(ValueError, match="mass and inertia of moving bodies must be larger than mjMINVAL"):
            compile_xml(sliding_body(mass, inertia))


def softness(mass: float) -> np.ndarray:
    """The regulariser R of the one contact row of a sphere of this mass resting on a plane."""
    m = compile_xml(f"""
        <mujoco><worldbody><geom type="plane" size="1 1 .1" condim="1"/>
          <body pos="0 0 .0999"><freejoint/><geom type="sphere" size=".1" mass="{mass!r}" condim="1"/></body>
        </worldbody></mujoco>""")
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    return d.efc_R[: d.nefc].copy()


def test_mujoco_floors_the_softness_of_heavy_bodies_at_minval():
    light, heavier = softness(1e12), softness(1e13)
    assert light[0] == pytest.approx(10 * heavier[0], rel=1e-12)  # R goes as 1/m while clear of the floor
    past = value("mujoco_minval_softness")
    for mass in (10 * past, 1e5 * past):
        assert list(softness(mass)) == [value("mujoco_minval_mass")]  # the floor, the same at every mass


def spinning_sphere(torsional: float, rolling: float = 1e-4) -> tuple[np.ndarray, np.ndarray]:
    """Velocities of a sphere spinning on a plane with condim 6 over 1 s, and its contact's friction."""
    friction = f'friction="1 {torsional!r} {rolling!r}" condim="6"'
    m = compile_xml(f"""
        <mujoco><worldbody><geom type="plane" size="1 1 .1" {friction}/>
          <body pos="0 0 .1"><freejoint/><geom type="sphere" size=".1" mass="1" {friction}/></body>
        </worldbody></mujoco>""")
    d = mujoco.MjData(m)
    d.qvel[5] = 10.0
    out = []
    for _ in range(500):
        mujoco.mj_step(m, d)
        out.append(d.qvel.copy())
    return np.array(out), d.contact.friction[0].copy()


def test_mujoco_raises_torsional_and_rolling_friction_to_minmu():
    mu = value("mujoco_minmu")
    at, contact = spinning_sphere(mu)
    below, contact_below = spinning_sphere(mu / 100)
    assert np.array_equal(below, at)  # bit for bit: 1e-7 acts as 1e-5
    assert list(contact_below) == list(contact) == [1.0, 1.0, mu, 1e-4, 1e-4]
    assert not np.array_equal(spinning_sphere(2 * mu)[0], at)  # above it, the number counts
    assert not np.array_equal(at[:, 5], np.full(500, 10.0))  # and the spin is braked by it
    rolling_at, _ = spinning_sphere(1e-3, mu)
    rolling_below, contact_rolling = spinning_sphere(1e-3, mu / 100)
    assert np.array_equal(rolling_below, rolling_at)
    assert list(contact_rolling[3:]) == [mu, mu]


def motor_force(ctrl: float) -> tuple[float, int]:
    m = compile_xml("""
        <mujoco><worldbody><body><joint name="j" type="slide"/><geom size=".1" mass="2"/></body></worldbody>
          <actuator><motor joint="j"/></actuator></mujoco>""")  # mass 2: the acceleration stays below mjMAXVAL
    d = mujoco.MjData(m)
    d.ctrl[0] = ctrl
    with quiet_stdout():  # MuJoCo prints its warning from C
        mujoco.mj_step(m, d)
    return float(d.qfrc_actuator[0]), int(d.warning[mujoco.mjtWarning.mjWARN_BADCTRL].number)


def test_mujoco_zeroes_controls_beyond_maxval():
    top = value("mujoco_maxval")
    assert motor_force(top) == (top, 0)
    assert motor_force(-top) == (-top, 0)
    for ctrl in (math.nextafter(top, math.inf), 2 * top, -2 * top):
        assert motor_force(ctrl) == (0.0, 1)


def dropped_sphere(timeconst: float, timestep: float = 0.002) -> np.ndarray:
    solref = f'solref="{timeconst!r} 1"'
    m = compile_xml(f"""
        <mujoco><option timestep="{timestep!r}"/><worldbody><geom type="plane" size="1 1 .1" {solref}/>
          <body pos="0 0 .2"><freejoint/><geom type="sphere" size=".1" mass="1" {solref}/></body>
        </worldbody></mujoco>""")
    d = mujoco.MjData(m)
    out = []
    for _ in range(300):
        mujoco.mj_step(m, d)
        out.append(d.qpos.copy())
    return np.array(out)


def test_mujoco_stiffens_no_solref_below_two_time_steps():
    (refsafe,) = thresholds(names=["mujoco_refsafe"])
    assert refsafe.relative_to == "timestep"
    floor = refsafe.limit({"timestep": 0.002})
    at = dropped_sphere(floor)
    assert np.array_equal(dropped_sphere(floor / 4), at)
    assert np.array_equal(dropped_sphere(0.75 * floor), at)
    assert not np.array_equal(dropped_sphere(1.25 * floor), at)
    assert not np.array_equal(dropped_sphere(floor, timestep=0.001), dropped_sphere(floor / 2, timestep=0.001))


def solver_iterations(path) -> tuple[list[int], float]:
    """The solver's iterations in the first 100 steps of a model driven by a smooth input, and its meaninertia."""
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    out = []
    for i in range(100):
        d.ctrl[:] = 0.5 * np.sin(np.arange(m.nu) + 0.01 * i)
        mujoco.mj_step(m, d)
        out.append(int(d.solver_niter[0]))
    return out, float(m.stat.meaninertia)


def test_mujoco_solver_tolerance_is_held_against_a_normalisation_of_no_pure_dimension(tmp_path):
    (t,) = thresholds(names=["mujoco_solver_tolerance"])
    assert (t.bound, t.dimension, t.applies) == ("internal", None, ())
    model = hopper()
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]  # lengths and gravity by s, masses by 1/s^2
    original, inertia = solver_iterations(model.save(tmp_path / "hopper.xml"))
    _, inertia_scaled = solver_iterations(model.scaled(sc, 4).save(tmp_path / "hopper4.xml"))
    # the solver's stopping rule divides by meaninertia, which averages masses (x 1/16 at s = 4) with
    # inertias (x 1): it moves by neither factor, so no change of units carries the tolerance
    assert 1 / 16 < inertia_scaled / inertia < 1
    assert max(original) < compile_xml("<mujoco/>").opt.iterations  # the tolerance stops the solver early


def line_search_stops(model, scaling, n_steps: int) -> list[tuple[int, int]]:
    """Each step's count of solver iterations in a model and its copy at s = 4, both at tolerance 0, by hand."""
    runs = []
    for compiled in (model.runner.mjmodel, model.scaled(scaling, 4).runner.mjmodel):
        m = copy.copy(compiled)
        m.opt.tolerance = 0.0
        d = mujoco.MjData(m)
        counts = []
        for _ in range(n_steps):
            mujoco.mj_step(m, d)
            counts.append(int(d.solver_niter[0]))
        runs.append(counts)
    return list(zip(*runs, strict=True))


def test_mujoco_line_search_stops_where_its_direction_is_under_mjminval_whatever_the_tolerance():
    """With the tolerance at 0 nothing but the count of iterations and the line search's floor on the norm of its
    direction (generalized accelerations: hinges' and slides' together) stops MuJoCo's Newton solver; the leg
    with a sliding shin stops short of opt.iterations, and a copy whose accelerations are not the original's
    stops elsewhere: with the time unit by 4 (every acceleration by 1/16) never later and somewhere earlier,
    with the slide's accelerations by 4 (the issue's change: masses by 1/16, lengths by 4) somewhere later;
    with the mass unit alone changed (no acceleration moves) at the same iteration every step."""
    (t,) = thresholds(names=["mujoco_minval_search"])
    assert (t.value, t.bound, t.dimension, t.applies) == (mujoco.mjMINVAL, "internal", None, ())
    model = engines.load(Path(__file__).parent / "data" / "engines" / "slide_leg.xml")
    cap = model.runner.mjmodel.opt.iterations

    def change(**units):
        return pt.Scaling.from_unit_change(model.system(), {"M": 0, "L": 0, "T": 0, **units})

    mass = line_search_stops(model, change(M=1), 300)
    assert all(a == b for a, b in mass)
    assert max(a for a, _ in mass) < cap  # the tolerance at 0 stopped nothing: the floor did
    slower = line_search_stops(model, change(T=1), 300)
    assert all(b <= a for a, b in slower)
    assert any(b < a for a, b in slower)
    issue = line_search_stops(model, change(M=-2, L=1), 300)
    assert any(b > a for a, b in issue)


# -- PyBullet: each clamp, measured ---------------------------------------------------------------


@pytest.fixture
def client():
    with quiet_stdout():
        cid = pb.connect(pb.DIRECT)
    yield cid
    pb.disconnect(physicsClientId=cid)


def resting_height(cid, shape: str, size: float) -> float:
    """Height of a 1 kg box (half extent `size`) or sphere (radius `size`) set on the ground, after 2 s."""
    pb.resetSimulation(physicsClientId=cid)
    pb.setGravity(0, 0, -9.81, physicsClientId=cid)
    pb.createMultiBody(0, pb.createCollisionShape(pb.GEOM_PLANE, physicsClientId=cid), physicsClientId=cid)
    geometry = (
        {"shapeType": pb.GEOM_BOX, "halfExtents": [size] * 3}
        if shape == "box"
        else {"shapeType": pb.GEOM_SPHERE, "radius": size}
    )
    body = pb.createMultiBody(
        1.0, pb.createCollisionShape(**geometry, physicsClientId=cid), basePosition=[0, 0, size], physicsClientId=cid
    )
    for _ in range(480):
        pb.stepSimulation(physicsClientId=cid)
    return pb.getBasePositionAndOrientation(body, physicsClientId=cid)[0][2]


def test_bullet_boxes_below_the_minimum_size_fall_through_the_ground(client):
    smallest = value("bullet_box_minimum_size")
    assert resting_height(client, "box", smallest) > 0.99 * smallest
    assert resting_height(client, "box", 0.99 * smallest) < 0  # through the plane
    assert resting_height(client, "box", smallest / 4) < 0


def test_bullet_contact_slop_sinks_resting_objects_by_its_length(client):
    slop = value("bullet_contact_slop_against_size")
    (catalogued,) = engines.hidden_constants("pybullet", names=["bullet_contact_slop"])
    assert slop == catalogued.default
    for radius in (1e-3, 1e-4):
        assert resting_height(client, "sphere", radius) == pytest.approx(radius - slop, abs=1e-9)
    assert 0.9 * slop < 0.01 - resting_height(client, "box", 0.01) < 1.2 * slop


def slide(cid, speed: float, turn: float = 0.0, *, maximal: bool, sleeping: bool = True) -> tuple[float, float]:
    """Speed and turning rate of a frictionless 1 kg box (half extent 0.1) after 4 s on the ground."""
    pb.resetSimulation(physicsClientId=cid)
    pb.setGravity(0, 0, -9.81, physicsClientId=cid)
    plane = pb.createMultiBody(0, pb.createCollisionShape(pb.GEOM_PLANE, physicsClientId=cid), physicsClientId=cid)
    pb.changeDynamics(plane, -1, lateralFriction=0, physicsClientId=cid)
    box = pb.createMultiBody(
        1.0,
        pb.createCollisionShape(pb.GEOM_BOX, halfExtents=[0.1] * 3, physicsClientId=cid),
        basePosition=[0, 0, 0.1],
        useMaximalCoordinates=maximal,
        physicsClientId=cid,
    )
    flag = {"activationState": pb.ACTIVATION_STATE_ENABLE_SLEEPING} if sleeping else {}
    pb.changeDynamics(box, -1, lateralFriction=0, linearDamping=0, angularDamping=0, physicsClientId=cid, **flag)
    pb.resetBaseVelocity(box, [speed, 0, 0], [0, 0, turn], physicsClientId=cid)
    for _ in range(960):
        pb.stepSimulation(physicsClientId=cid)
    linear, angular = pb.getBaseVelocity(box, physicsClientId=cid)
    return linear[0], angular[2]


@pytest.mark.parametrize(("name", "maximal"), [("bullet_rigid_body_sleep", True), ("bullet_multibody_sleep", False)])
def test_bullet_sleeps_slow_bodies_only_when_asked_and_mixes_speed_with_turning(client, name, maximal):
    threshold = value(name)
    assert slide(client, 0.999 * threshold, maximal=maximal) == (0.0, 0.0)  # asleep: stopped
    assert slide(client, 1.001 * threshold, maximal=maximal)[0] == 1.001 * threshold
    assert slide(client, 0.01, maximal=maximal, sleeping=False)[0] == 0.01  # PyBullet's default: never asleep
    # speed and turning, each below the speed or turning rate that alone puts it to sleep, keep it awake
    assert slide(client, 0.999 * threshold, 0.127, maximal=maximal, sleeping=True)[0] != 0.0
    assert slide(client, 0.0, 0.127, maximal=maximal) == (0.0, 0.0)


def fall(cid, path: str, height: float, link_margin: float | None) -> tuple[np.ndarray, list[float], int]:
    """Base pose and joint angles of a URDF robot falling onto the plane for 1 s, link margins, contacts."""
    import pybullet_data

    pb.resetSimulation(physicsClientId=cid)
    pb.setGravity(0, 0, -9.81, physicsClientId=cid)
    pb.loadURDF(f"{pybullet_data.getDataPath()}/plane.urdf", physicsClientId=cid)
    with quiet_stdout():
        robot = pb.loadURDF(f"{pybullet_data.getDataPath()}/{path}", [0, 0, height], physicsClientId=cid)
    joints = range(pb.getNumJoints(robot, physicsClientId=cid))
    for j in joints:
        pb.setJointMotorControl2(robot, j, pb.VELOCITY_CONTROL, force=0, physicsClientId=cid)
        if link_margin is not None:
            pb.changeDynamics(robot, j, collisionMargin=link_margin, physicsClientId=cid)
    out = []
    for _ in range(240):
        pb.stepSimulation(physicsClientId=cid)
        pose = pb.getBasePositionAndOrientation(robot, physicsClientId=cid)
        angles = [s[0] for s in pb.getJointStates(robot, joints, physicsClientId=cid)]
        out.append([*pose[0], *pose[1], *angles])
    margins = [pb.getDynamicsInfo(robot, j, physicsClientId=cid)[11] for j in joints]
    return np.array(out), margins, len(pb.getContactPoints(robot, physicsClientId=cid))


@pytest.mark.parametrize(("path", "height"), [("r2d2.urdf", 0.5), ("quadruped/minitaur.urdf", 0.3)])
def test_bullet_ignores_collision_margins_set_on_links(client, path, height):
    (t,) = thresholds(names=["bullet_link_collision_margin"])
    assert t.bound == "unapplied"
    default, margins, contacts = fall(client, path, height, None)
    changed, margins_after, _ = fall(client, path, height, 50 * t.value)
    assert contacts > 0  # the links touch the ground
    assert margins_after == margins  # the links keep their margins (a box's 0.001, a sphere's radius)
    assert t.value in margins
    assert np.array_equal(changed, default)  # bit for bit


def test_bullet_solver_residual_is_exact_only_at_zero():
    # a prismatic and a revolute joint with a base on the ground: rows in m/s and rad/s in one residual;
    # the scaled copy keeps the residual threshold (it has no dimension a scaling could carry)
    model = engines.load(
        REPO / "tests" / "data" / "engines" / "slider_arm.urdf",
        ground=True,
        damping=0.0,
        split_impulse=False,
        base_position=(0, 0, 0.3),
    )
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    assert model.parameter("solverResidualThreshold").value == (value("bullet_solver_residual"),)
    assert model.scaled(sc, 10).parameter("solverResidualThreshold").value == (value("bullet_solver_residual"),)
    # at s = 4 every factor is exact: the threshold alone keeps the copy from the original bit for bit, and
    # verify names it with its counter-run (0 in both runs)
    rep = engines.verify(model, sc, 4, duration=0.5)
    assert not rep.exact
    assert [c.element for c in rep.causes if c.kind == "solver"] == ["option solverResidualThreshold = 1e-07"]
    assert engines.verify(model.with_values(solverResidualThreshold=0.0), sc, 4, duration=0.5).exact


# -- crossed and check ---------------------------------------------------------------------------


def parameter(name, path, values, dimension):
    return engines.Parameter(name, path, tuple(values), pt.Dimension.parse(dimension), "file", "file")


def test_crossed_tells_beyond_from_near_from_clear():
    timestep = parameter("timestep", "option timestep", [0.002], "T")
    table = [
        timestep,
        parameter("body_a_mass", "body 'a' mass", [1e-16], "M"),  # beyond the compiler's floor
        parameter("body_b_mass", "body 'b' mass", [1.5e-15], "M"),  # near it
        parameter("body_c_mass", "body 'c' mass", [3e-15], "M"),  # clear at near=2, near at near=10
        parameter("body_d_inertia", "body 'd' inertia", [1e16, 1, 1], "M L^2"),  # beyond the softness floor
        parameter("geom_e_solref_timeconst", "geom 'e' solref timeconst", [0.003], "T"),  # under 2 steps
        parameter("geom_f_solref_timeconst", "geom 'f' solref timeconst", [0.005], "T"),  # near
        parameter("actuator0_ctrlrange", "actuator #0 ctrlrange", [-2e10, 1], "M L^2 T^-2"),
        parameter("geom_g_friction_torsional_rolling", "geom 'g' friction torsional rolling", [0.005, 1e-7], "L"),
    ]
    causes = crossed("mujoco", table)
    assert all(c.kind == "threshold" for c in causes)
    said = {c.element: c.detail.split(" is ")[1].split(" (")[0] for c in causes}
    assert said == {
        "body_a_mass": "below mujoco_minval_mass",
        "body_b_mass": "within a factor 2 of mujoco_minval_mass",
        "body_d_inertia": "above mujoco_minval_softness",
        "geom_e_solref_timeconst": "below mujoco_refsafe",
        "geom_f_solref_timeconst": "within a factor 2 of mujoco_refsafe",
        "actuator0_ctrlrange": "above mujoco_maxval",
        "geom_g_friction_torsional_rolling": "below mujoco_minmu",
    }
    assert "= 1e-07 is below" in next(c.detail for c in causes if c.element == "geom_g_friction_torsional_rolling")
    assert "body_c_mass" in {c.element for c in crossed("mujoco", table, near=10)}
    assert {c.element for c in crossed("mujoco", table, near=1)} == {
        "body_a_mass",
        "body_d_inertia",
        "geom_e_solref_timeconst",
        "actuator0_ctrlrange",
        "geom_g_friction_torsional_rolling",
    }
    # the time step scales the refsafe floor with it
    assert "geom_e_solref_timeconst" not in {c.element for c in crossed("mujoco", table, {"timestep": 0.25})}
    # PyBullet has none of MuJoCo's thresholds
    assert crossed("pybullet", table) == ()


def test_crossed_leaves_out_zeros_overrides_and_other_kinds():
    table = [
        parameter("body_a_mass", "body 'a' mass", [0.0], "M"),  # zero: scale-free
        parameter("o_friction_torsional_rolling", "option o_friction torsional rolling", [1e-9, 1e-9, 1e-9], "L"),
        parameter("geom_a_size", "geom 'a' size", [1e-20], "L"),  # no threshold of MuJoCo's applies to sizes
        parameter("geom_a_fromto", "geom 'a' fromto", [float("nan")], "L"),
    ]
    assert crossed("mujoco", table) == ()


def test_crossed_with_factors_judges_the_scaled_copy():
    model = hopper()
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    for s in (1e-5, 1e-3, 10.0, 1e3):
        factors = {p.name: p.factor(lengths, s) for p in model.parameters}
        assert crossed(model.engine, model.parameters, factors) == engines.check(model.scaled(lengths, s))


def test_check_flags_a_shrunk_hopper_and_not_the_original():
    model = hopper()
    assert engines.check(model) == ()
    shrunk = model.scaled(pt.Scaling.from_unit_change(model.system(), {"L": 1}), 1e-5)
    causes = engines.check(shrunk)
    # every geom of the file touches something, and each one's torsional and rolling friction is now
    # below mjMINMU (0.005 and 1e-4 m shrunk to 5e-8 and 1e-9 m)
    assert {c.element for c in causes} == {
        f"geom_{g}_friction_torsional_rolling" for g in ("floor", "torso_geom", "thigh_geom", "leg_geom", "foot_geom")
    }
    assert all(c.kind == "threshold" and "below mujoco_minmu" in c.detail for c in causes)
    # each cause names the change of units that clears it: lengths by the largest factor named clear them all
    needs = [float(re.search(r"dimension L by (\S+) clears it", c.detail).group(1)) for c in causes]
    lengths = pt.Scaling.from_unit_change(shrunk.system(), {"L": 1})
    assert engines.check(shrunk.scaled(lengths, max(needs))) == ()
    assert engines.check(shrunk.scaled(lengths, max(needs) / 4)) != ()


def test_check_flags_a_urdf_box_below_the_minimum_size(tmp_path):
    def box(size: float):
        urdf = tmp_path / f"box{size}.urdf"
        urdf.write_text(f"""<robot name="box"><link name="base">
            <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
            <collision><geometry><box size="{size} {size} {size}"/></geometry></collision></link></robot>""")
        return engines.load(urdf)

    model = box(0.5)
    assert model.engine == "pybullet"
    assert engines.hidden_constants(model.engine)  # the engine's name is the catalogue's
    assert engines.check(model) == ()
    (cause,) = engines.check(box(0.002))
    assert cause.element == "link_base_collision0_size"
    assert "below bullet_box_minimum_size (0.0021)" in cause.detail
    (near,) = engines.check(box(0.004))
    assert "within a factor 2 of bullet_box_minimum_size" in near.detail


def test_bad_requests_name_their_culprit():
    table = hopper().parameters
    for call, culprit in (
        (lambda: crossed("ode", table), "ode"),
        (lambda: crossed("mujoco", table, {"no_such": 2.0}), "no_such"),
        (lambda: crossed("mujoco", table, near=0.5), 0.5),
        (lambda: crossed("mujoco", [*table, "body_mass"]), "body_mass"),
    ):
        with pytest.raises(pt.InvalidRequestError) as caught:
            call()
        assert caught.value.culprit == culprit
    # numbers that are no positive factor: the message names which
    for call, named in (
        (lambda: crossed("mujoco", table, {"timestep": -1.0}), "the factor of 'timestep'"),
        (lambda: crossed("mujoco", table, {"timestep": True}), "the factor of 'timestep'"),
        (lambda: crossed("mujoco", table, near=float("nan")), "near"),
    ):
        with pytest.raises(pt.NumberError, match=named):
            call()
    with pytest.raises(pt.InvalidRequestError, match="factors must map"):
        crossed("mujoco", table, [2.0])
    with pytest.raises(pt.InvalidRequestError, match="check needs an EngineModel"):
        engines.check("hopper.xml")


def test_grouped_causes_name_every_number_once_and_detail_the_worst():
    from pitheorem.engines import Parameter

    def mass(name, value):
        return Parameter(f"body_{name}_mass", f"body {name!r} mass", (value,), pt.Dimension.parse("M"), "file", "file")

    table = [mass(n, v) for n, v in (("e", 5e-16), ("a", 4e-16), ("d", 2e-16), ("c", 3e-16), ("b", 8e-16))]
    inertia = Parameter(
        "body_a_inertia", "body 'a' inertia", (1e-17, 2e-17, 3e-17), pt.Dimension.parse("M L^2"), "file", "file"
    )
    one_each = crossed("mujoco", [*table, inertia], near=1.0)
    assert len(one_each) == 6
    grouped = crossed("mujoco", [*table, inertia], near=1.0, grouped=True)
    assert len(grouped) == 2  # masses and inertias: one threshold, two dimensions, two remedies
    masses = next(c for c in grouped if "mass" in c.element)
    assert masses.element == "body_a_mass, body_b_mass, body_c_mass and 2 more"
    assert masses.detail.startswith("5 numbers; the worst: body 'd' mass = 2e-16 is below")
    alone = next(c for c in grouped if "inertia" in c.element)
    assert alone == next(c for c in one_each if c.element == "body_a_inertia")  # a group of one reads as before


def test_mjx_parameters_are_the_half_lengths_mjxs_collisions_hold_against_its_constants(tmp_path):
    path = tmp_path / "segments.xml"
    path.write_text(
        textwrap.dedent("""\
        <mujoco><worldbody>
          <geom name="ground" type="plane" size="1 1 0.1"/>
          <body name="a" pos="0 0 1"><freejoint/>
            <geom name="arm" type="capsule" fromto="0 0 0 0.3 0.4 0" size="0.01"/></body>
          <body name="b" pos="0 0 2"><freejoint/><geom name="ball" type="sphere" size="0.05"/></body>
          <body name="c" pos="0 0 3"><freejoint/><geom type="cylinder" size="0.02 0.0004"/></body>
        </worldbody></mujoco>""")
    )
    model = engines.load(path)
    found = {p.name: p for p in mjx_parameters(model)}
    assert sorted(found) == ["geom3_half_length", "geom_arm_half_length"]
    arm, disk = found["geom_arm_half_length"], found["geom3_half_length"]
    assert arm.value == pytest.approx((0.5 / 2,), rel=1e-12)  # half of the fromto's length, 0.5
    assert arm.path == "geom 'arm' capsule half-length"
    assert disk.path == "geom #3 cylinder half-length"
    assert {p.dimension for p in found.values()} == {pt.Dimension.parse("L")}
    assert {p.source for p in found.values()} == {"derived"}
    assert {k for k, (_, is_kind) in KINDS.items() if is_kind(arm)} == {"capsule_segment", "number"}
    assert {k for k, (_, is_kind) in KINDS.items() if is_kind(disk)} == {"cylinder_on_plane", "number"}
    # MuJoCo holds nothing against them; MJX holds both, with the unit change that clears each
    assert engines.check(model) == ()
    said = {c.element: c.detail for c in engines.check(model, "mjx")}
    assert set(said) == {"geom_arm_half_length", "geom3_half_length"}
    assert "below mjx_segment_regularizer_float32 (2)" in said["geom_arm_half_length"]  # 2.0 in its shortest text
    assert "by 16 clears it" in said["geom_arm_half_length"]  # to twice 2: 4 / 0.25
    assert "below mjx_cylinder_plane_parallel (0.001)" in said["geom3_half_length"]
    assert "by 5 clears it" in said["geom3_half_length"]  # to twice 1e-3: 2e-3 / 4e-4
    assert engines.check(model.converted(L="mm"), "mjx") == ()  # 250 and 0.4 mm
    # what check and the fit hold against each engine: the table, and for MJX the half-lengths after it
    assert held_against(model, "mujoco") == held_against(model, "pybullet") == model.parameters
    assert held_against(model, "mjx") == (*model.parameters, *mjx_parameters(model))
    with pytest.raises(pt.InvalidRequestError, match="unknown engine 'MJX'"):
        held_against(model, "MJX")


def test_float32s_range_is_held_only_against_float32():
    table = [
        parameter("joint_a_damping", "joint 'a' damping", [1e-40], "M L^2 T^-1"),
        parameter("joint_b_damping", "joint 'b' damping", [-1e39], "M L^2 T^-1"),
        parameter("joint_c_damping", "joint 'c' damping", [2e-38], "M L^2 T^-1"),
    ]
    said = {c.element: c.detail.split(" is ")[1].split(" (")[0] for c in crossed("mjx", table)}
    assert said == {
        "joint_a_damping": "below mjx_float32_min_normal",
        "joint_b_damping": "above mjx_float32_max",
        "joint_c_damping": "within a factor 2 of mjx_float32_min_normal",
    }
    assert crossed("mjx", table, precision="float64") == crossed("mujoco", table) == ()
    with pytest.raises(pt.InvalidRequestError) as caught:
        crossed("mjx", table, precision="float16")
    assert caught.value.culprit == "float16"


def test_the_fluid_models_numbers_join_only_with_a_fluid_and_a_compiled_mass(tmp_path):
    def speck(radius, fluid):
        path = tmp_path / f"speck{radius}{fluid}.xml"
        path.write_text(
            f'<mujoco><option {fluid}/><worldbody><body name="s"><freejoint/>'
            f'<geom size="{radius}" density="1000"/></body></worldbody></mujoco>'
        )
        return engines.load(path)

    model = speck(0.01, 'viscosity="1e-3"')
    found = {p.name: p for p in mjx_parameters(model)}
    assert sorted(found) == ["body_s_fluid_box_moments", "body_s_mass_in_fluid"]
    assert found["body_s_mass_in_fluid"].value == model.parameter("body_s_mass").value
    moment = model.parameter("body_s_inertia").value[0]  # a sphere: I1 + I2 - I0 = I
    assert found["body_s_fluid_box_moments"].value == pytest.approx((moment,) * 3, rel=1e-12)
    assert mjx_parameters(speck(0.01, 'density="0"')) == ()  # no fluid
    refused = speck(1e-6, 'density="1.2"')  # MuJoCo refuses it; its compiled masses are a probe's
    assert type(refused.runner.document).__name__ == "RefusedMjcfDocument"
    assert mjx_parameters(refused) == ()


# -- the command line's summary: one cause per threshold and value ---------------------------------

SUMMARY_MODEL = """<mujoco>
  <option timestep="0.01"/>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="a" pos="0 0 1"><freejoint/><geom name="ball_a" size="0.1" mass="1"/></body>
    <body name="b" pos="1 0 1"><freejoint/><geom name="ball_b" size="0.1" mass="1" solref="0.015 1"/></body>
    <body name="c" pos="2 0 1"><freejoint/>
      <geom name="ghost" size="0.1" mass="1" contype="0" conaffinity="0" solref="0.011 1"/></body>
  </worldbody>
</mujoco>
"""


def test_check_summary_groups_by_threshold_and_value_says_at_truly_and_skips_numbers_never_read(tmp_path):
    from pitheorem.engines.thresholds import check_summary

    path = tmp_path / "balls.xml"
    path.write_text(SUMMARY_MODEL)
    model = engines.load(path)
    causes, units_help = check_summary(model)
    # two geoms at MuJoCo's floor of two time steps (0.02 = 2 x 0.01: left as they are), one below it (0.015:
    # raised); the ghost's 0.011 is never read (it collides with nothing) and is not named
    assert [c.element for c in causes] == [
        "2 numbers (solref timeconst of 2 geoms)",
        "1 number (solref timeconst of 1 geom)",
    ]
    assert causes[0].detail.startswith("0.02 is at mujoco_refsafe (0.02 = 2.0 timestep): left as it is")
    assert causes[1].detail.startswith("0.015 is below mujoco_refsafe (0.02 = 2.0 timestep): raised")
    # a floor that moves with the time step: no change of units helps, the remedy says what does
    assert "change it or timestep by a factor 2.67" in causes[1].detail
    assert "units that multiply" not in causes[0].detail + causes[1].detail
    assert not units_help
    assert "geom_ghost_solref_timeconst" in model.runner.unread()
    assert "geom_ball_a_solref_timeconst" not in model.runner.unread()
    # engines.check leaves the unread number out too, and keeps one cause per number
    assert sorted(c.element for c in engines.check(model)) == [
        "geom_ball_a_solref_timeconst",
        "geom_ball_b_solref_timeconst",
        "geom_floor_solref_timeconst",
    ]


def test_a_urdfs_tiny_products_of_inertia_cross_no_floor_in_mujoco(tmp_path):
    # example-robot-data's TIAGo Pro writes products of inertia of 1e-22 (CAD noise): MuJoCo holds
    # mjMINVAL against principal moments only, compiles the file and runs it; no threshold may be named
    urdf = tmp_path / "arm.urdf"
    urdf.write_text("""<robot name="arm">
      <link name="base"/>
      <link name="arm"><inertial><mass value="0.5"/>
        <inertia ixx="1e-3" iyy="2e-3" izz="3e-3" ixy="1e-22" ixz="-2e-22" iyz="0"/></inertial>
        <collision><geometry><box size="0.1 0.1 0.4"/></geometry></collision></link>
      <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/>
        <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="5"/></joint>
    </robot>""")
    model = engines.load(urdf, engine="mujoco")  # MuJoCo's compiler takes it
    assert model.runner.mjmodel.body_inertia[1:].min() > value("mujoco_minval_mass")  # the world is body 0
    products = {"link_arm_ixy", "link_arm_ixz"}
    assert products <= {p.name for p in model.parameters}
    assert engines.check(model) == ()
    # scaled so far that a product would sit a factor 1e10 below the floor: still no cause
    assert crossed("mujoco", model.parameters, dict.fromkeys(products, 1e-3)) == ()
    # a principal moment shrunk below the floor is still named
    (cause,) = crossed("mujoco", model.parameters, {"link_arm_izz": 1e-13})
    assert cause.element == "link_arm_izz"
    assert "below mujoco_minval_mass" in cause.detail
