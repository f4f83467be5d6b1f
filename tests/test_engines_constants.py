"""pitheorem.engines.constants: the hidden-constant catalogue, engine_search and broken_constants.

The catalogue's values are checked exactly against its data file and
against the installed engines' own defaults (a fresh MjSpec, PyBullet's
getPhysicsEngineParameters), and its dimensions by scaled runs: which way
of treating a constant keeps a scaled run exact.
"""

from __future__ import annotations

import math
from fractions import Fraction
from types import SimpleNamespace

import numpy as np
import pytest

import pitheorem as pt
from pitheorem.engines import (
    CATALOGUE,
    ENGINES,
    broken_constants,
    engine_search,
    hidden_constants,
    with_hidden_constants,
)
from pitheorem.engines.registry import REGISTRY
from tests.conftest import FIG5, HINGED_ROD, TIME_FREE


def test_catalogue_entries_are_complete():
    names = [c.name for c in CATALOGUE]
    assert len(names) == len(set(names))
    for c in CATALOGUE:
        assert c.engine in ENGINES
        assert c.name.isidentifier()
        # PyBullet's constants are the Bullet library's, and keep its name: bullet_time_step
        assert c.name.startswith({"pybullet": "bullet_"}.get(c.engine, f"{c.engine}_"))
        assert isinstance(c.dimension, pt.Dimension)
        assert c.source
        assert c.where
        assert c.note


@pytest.mark.parametrize(
    ("name", "dimension", "default"),
    [
        ("bullet_time_step", "T", 1 / 240),
        ("bullet_collision_margin", "L", 0.001),
        ("bullet_contact_breaking_threshold", "1", 0.02),
        ("bullet_contact_slop", "L", 1e-5),
        ("bullet_solver_residual_threshold", "1", 1e-7),
        ("bullet_max_joint_velocity", "T^-1", 100.0),
        ("bullet_max_prismatic_joint_velocity", "L T^-1", 100.0),
        ("bullet_contact_erp", "1", 0.08),
        ("bullet_linear_sleep_threshold", "L T^-1", 0.8),
        ("bullet_angular_sleep_threshold", "T^-1", 1.0),
        ("bullet_linear_damping_k1", "T^-1", 0.04),
        ("mujoco_timestep", "T", 0.002),
        ("mujoco_solref_timeconst", "T", 0.02),
        ("mujoco_solimp_width", "L", 0.001),
        ("mujoco_geom_margin", "L", 0.0),
        ("mujoco_ccd_tolerance", "L", 1e-6),
        ("mujoco_tolerance", "1", 1e-8),
    ],
)
def test_catalogue_values(name, dimension, default):
    (c,) = hidden_constants(names=[name])
    assert c.dimension == pt.Dimension.parse(dimension)
    assert c.default == pytest.approx(default)


def test_catalogue_is_read_whole_and_exactly_from_its_data_file():
    # the values a float literal cannot show at a glance, compared exactly (not approx)
    assert ENGINES == tuple(e.name for e in REGISTRY)  # a table for each engine, in the registry's order
    # the file's order: engine by engine
    assert [c.engine for c in CATALOGUE] == [e for e in ENGINES for c in CATALOGUE if c.engine == e]
    assert len(hidden_constants("pybullet")) == 23
    assert len(hidden_constants("mujoco")) == 18
    assert len(hidden_constants("mjx")) == 5
    assert hidden_constants(names=["mjx_segment_regularizer"])[0].dimension == pt.Dimension.parse("L^2")
    assert hidden_constants(names=["bullet_time_step"])[0].default == 1 / 240
    assert hidden_constants(names=["mujoco_angle_unit"])[0].default == math.pi / 180
    assert math.isnan(hidden_constants(names=["bullet_default_motor_impulse"])[0].default)
    assert hidden_constants(names=["bullet_split_impulse_penetration_threshold"])[0].default == -0.04
    # the shared source texts are filled in: no placeholder is left, and each reaches the entries naming it
    assert not any("{" in c.source or "}" in c.source for c in CATALOGUE)
    multibody = [
        c.name for c in CATALOGUE if c.source.startswith("bullet3 src/BulletDynamics/Featherstone/btMultiBody")
    ]
    assert len(multibody) == 9
    assert hidden_constants(names=["mujoco_timestep"])[0].source == (
        "mujoco 4.0.0 model defaults (MjModel.opt, MjSpec.default); MuJoCo XML Reference (mujoco.readthedocs.io), "
        "option/timestep"
    )
    assert hidden_constants(names=["bullet_collision_margin"])[0].source.startswith(
        "measured with pybullet 3.2.7 (getPhysicsEngineParameters / getDynamicsInfo): getDynamicsInfo(...)[11]"
    )


def test_hidden_constants_filters():
    assert all(c.engine == "mujoco" for c in hidden_constants("mujoco"))
    assert all(not c.dimension.is_dimensionless for c in hidden_constants("pybullet", dimensional=True))
    assert all(c.dimension.is_dimensionless for c in hidden_constants("pybullet", dimensional=False))


def test_hidden_constants_bad_inputs():
    with pytest.raises(pt.InvalidRequestError, match="'ode'"):
        hidden_constants("ode")
    with pytest.raises(pt.UnknownVariableError, match="bullet_timestep"):
        hidden_constants("pybullet", names=["bullet_timestep"])


def test_with_hidden_constants_adds_dimensional_ones():
    ext = with_hidden_constants(HINGED_ROD.system, "pybullet")
    added = ext.variables[len(HINGED_ROD.system.variables) :]
    assert added == tuple(c.name for c in hidden_constants("pybullet", dimensional=True))
    assert ext.dimension("bullet_linear_damping_k2") == pt.Dimension.parse("L^-1")
    with pytest.raises(pt.DuplicateVariableError, match="mujoco_timestep"):
        with_hidden_constants(pt.System({"mujoco_timestep": "T"}), "mujoco")
    with pytest.raises(pt.InvalidRequestError, match="System"):
        with_hidden_constants({"l": "L"}, "mujoco")


def test_engine_search_shows_the_engine_breaks_every_gravity_scaling():
    # with Bullet's length and time constants fixed, no unit change may touch L or T: g cannot move
    res = engine_search(HINGED_ROD.system, "pybullet", {"g": 1})
    assert not res.feasible
    assert set(res.certificate.exponents) <= {"g", "t", *(c.name for c in CATALOGUE)}


def test_engine_search_with_only_the_time_step_keeps_the_time_free_answers():
    res = engine_search(HINGED_ROD.system, "mujoco", {"g": 1}, names=["mujoco_timestep"])
    assert res.feasible
    assert res.n_scalings == len(TIME_FREE)


def test_broken_constants_of_the_papers_scaling():
    broken = {c.name for c in broken_constants(FIG5, "pybullet")}
    assert "bullet_time_step" in broken
    assert "bullet_linear_damping_k1" in broken
    assert {"mujoco_timestep", "mujoco_solref_timeconst"} <= {c.name for c in broken_constants(FIG5, "mujoco")}
    # zero defaults and dimensionless constants are never broken
    assert "mujoco_geom_margin" not in {c.name for c in broken_constants(FIG5, "mujoco")}


def test_broken_constants_of_a_time_free_scaling():
    lengths = next(sc for sc in TIME_FREE if sc.unit_change == {"M": 0, "L": 1, "T": 0})
    names = {c.name for c in broken_constants(lengths, "pybullet")}
    assert "bullet_time_step" not in names
    assert {"bullet_collision_margin", "bullet_linear_damping_k2"} <= names
    assert lengths.exponent_of("L^-1") == Fraction(-1)


def test_broken_constants_needs_a_scaling():
    with pytest.raises(pt.InvalidRequestError, match="Scaling"):
        broken_constants({"g": 1}, "pybullet")
    sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1})
    look_alike = SimpleNamespace(
        system=sc.system, powers=sc.vector, exponent_of=sc.exponent_of, unit_change=sc.unit_change
    )  # what the old attribute check accepted
    with pytest.raises(pt.InvalidRequestError, match="needs a Scaling, got SimpleNamespace"):
        broken_constants(look_alike, "pybullet")


def default(name):
    return hidden_constants(names=[name])[0].default


def test_mujoco_defaults_match_the_engine():
    mujoco = pytest.importorskip("mujoco")
    spec = mujoco.MjSpec()
    body = spec.worldbody.add_body()
    geom, joint = body.add_geom(), body.add_joint()
    opt = spec.option
    assert opt.timestep == default("mujoco_timestep")
    assert opt.ccd_tolerance == default("mujoco_ccd_tolerance")
    assert opt.tolerance == default("mujoco_tolerance")
    assert opt.sleep_tolerance == default("mujoco_sleep_tolerance")
    assert opt.iterations == default("mujoco_iterations")
    assert geom.solref[0] == default("mujoco_solref_timeconst")
    assert geom.solref[1] == default("mujoco_solref_dampratio")
    assert geom.solimp[0] == default("mujoco_solimp_dmin")
    assert geom.solimp[2] == default("mujoco_solimp_width")
    assert geom.margin == default("mujoco_geom_margin")
    assert list(geom.friction) == [
        default("mujoco_sliding_friction"),
        default("mujoco_torsional_friction"),
        default("mujoco_rolling_friction"),
    ]
    assert geom.density == default("mujoco_geom_density")
    assert joint.margin == default("mujoco_joint_margin")
    assert list(joint.stiffness)[1:] == [default("mujoco_stiffness_poly")] * 2
    assert list(joint.damping)[1:] == [default("mujoco_damping_poly")] * 2


@pytest.fixture
def bullet():
    pb = pytest.importorskip("pybullet")
    from pitheorem.engines.packages import quiet_stdout

    with quiet_stdout():
        client = pb.connect(pb.DIRECT)
    yield pb, client
    # contactBreakingThreshold is a global of the process: put PyBullet's default back
    pb.setPhysicsEngineParameter(contactBreakingThreshold=0.02, physicsClientId=client)
    pb.disconnect(physicsClientId=client)


def test_bullet_defaults_match_the_engine(bullet):
    pb, client = bullet
    params = pb.getPhysicsEngineParameters(physicsClientId=client)
    assert params["fixedTimeStep"] == default("bullet_time_step")
    assert params["numSolverIterations"] == default("bullet_solver_iterations")
    box = pb.createMultiBody(
        1.0, pb.createCollisionShape(pb.GEOM_BOX, halfExtents=[0.1] * 3, physicsClientId=client), physicsClientId=client
    )
    assert pb.getDynamicsInfo(box, -1, physicsClientId=client)[11] == default("bullet_collision_margin")
    ball = pb.createMultiBody(
        1.0, pb.createCollisionShape(pb.GEOM_SPHERE, radius=0.25, physicsClientId=client), physicsClientId=client
    )
    assert pb.getDynamicsInfo(ball, -1, physicsClientId=client)[11] == 0.25  # a sphere's margin is its radius


def drop_ball(pb, client, *, scale, breaking):
    """A ball of radius 0.1 scale dropped from 1 scale onto a plane, gravity 9.81 scale; heights over 1 s."""
    pb.resetSimulation(physicsClientId=client)
    pb.setPhysicsEngineParameter(contactBreakingThreshold=breaking, physicsClientId=client)
    # the lengths among the solver's settings scaled too; split impulses (threshold not settable) off
    pb.setPhysicsEngineParameter(
        contactSlop=1e-5 * scale,
        restitutionVelocityThreshold=0.2 * scale,
        solverResidualThreshold=1e-7 * scale**2,
        useSplitImpulse=0,
        physicsClientId=client,
    )
    pb.setGravity(0, 0, -9.81 * scale, physicsClientId=client)
    plane = pb.createMultiBody(
        0, pb.createCollisionShape(pb.GEOM_PLANE, physicsClientId=client), physicsClientId=client
    )
    pb.changeDynamics(plane, -1, collisionMargin=0.001 * scale, restitution=0.9, physicsClientId=client)
    ball = pb.createMultiBody(
        1.0,
        pb.createCollisionShape(pb.GEOM_SPHERE, radius=0.1 * scale, physicsClientId=client),
        basePosition=[0, 0, 1.0 * scale],
        physicsClientId=client,
    )
    pb.changeDynamics(ball, -1, restitution=0.9, physicsClientId=client)
    # the multibody damping (0.04) mixes a rate and an inverse length: off in every run
    pb.changeDynamics(ball, -1, linearDamping=0.0, angularDamping=0.0, physicsClientId=client)
    heights = []
    for _ in range(240):
        pb.stepSimulation(physicsClientId=client)
        heights.append(pb.getBasePositionAndOrientation(ball, physicsClientId=client)[0][2])
    return np.array(heights) / scale


def test_contact_breaking_threshold_is_dimensionless(bullet):
    pb, client = bullet
    original = drop_ball(pb, client, scale=1.0, breaking=0.02)
    left_alone = drop_ball(pb, client, scale=10.0, breaking=0.02)
    as_length = drop_ball(pb, client, scale=10.0, breaking=0.2)
    assert original.min() < 0.2  # the ball reached the plane and bounced
    assert np.abs(left_alone - original).max() < 1e-9
    assert np.abs(as_length - original).max() > 1e-3


def test_an_engine_search_holds_the_systems_time_variables_by_default():
    system = pt.System({"l": "L", "g": "L T^-2", "t": "T", "tau": "T"})
    held = engine_search(system, "mujoco", {"g": 1}, names=[])
    free = engine_search(system, "mujoco", {"g": 1}, fixed=(), names=[])
    assert held.fixed == ("t", "tau")
    assert free.fixed == ()
    assert all(sc.exponents["tau"] == 0 for sc in held.scalings)
    assert any(sc.exponents["tau"] != 0 for sc in free.scalings)


def test_every_model_names_its_engine_as_the_catalogue_does(tmp_path):
    pytest.importorskip("pybullet")
    pytest.importorskip("mujoco")
    from pitheorem import engines

    urdf = tmp_path / "box.urdf"
    urdf.write_text(
        '<robot name="box"><link name="base"><inertial><mass value="1"/>'
        '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>'
    )
    for model in (engines.load(urdf), engines.load(engines.example_path("pendulum.xml"))):
        assert model.engine in ENGINES
        constants = hidden_constants(model.engine)
        assert constants
        assert {c.engine for c in constants} == {model.engine}
