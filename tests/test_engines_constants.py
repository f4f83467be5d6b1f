"""pitheorem.engines.constants: the hidden-constant catalogue, engine_search and broken_constants.

The catalogue's values are checked exactly against its data file and
against the installed engines' own defaults (a fresh MjSpec, PyBullet's
getPhysicsEngineParameters), and its dimensions by scaled runs: which way
of treating a constant keeps a scaled run exact.
"""

from __future__ import annotations

import math
import re
from fractions import Fraction
from types import SimpleNamespace

import numpy as np
import pytest

import pitheorem as pt
from pitheorem.engines import (
    CATALOGUE,
    ENGINES,
    HiddenConstant,
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
    assert len(hidden_constants("mujoco")) == 28
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
    assert opt.ccd_iterations == default("mujoco_ccd_iterations")
    assert opt.ls_tolerance == default("mujoco_ls_tolerance")
    assert opt.noslip_tolerance == default("mujoco_noslip_tolerance")
    assert opt.impratio == default("mujoco_impratio")
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


# -- MuJoCo's own constants, measured ---------------------------------------------------------------
# Each catalogued constant read from MuJoCo's C source is shown here by a small model at two scales
# (every length by 4: a power of two, so that without the constant the copy is the original bit for
# bit) and by the smallest change of the model or its options that moves the quantity away from the
# constant.  The source locations are MuJoCo main of 2026-08-22 (a7255075b); the runs are the
# installed mujoco 4.0.0.


def compiled(xml: str):
    mujoco = pytest.importorskip("mujoco")
    return mujoco, mujoco.MjModel.from_xml_string(xml)


def contacts(xml: str) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """(depth, point, frame) of every contact of a model at its initial pose."""
    mujoco, m = compiled(xml)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    return [(float(c.dist), c.pos.copy(), c.frame.copy()) for c in d.contact[: d.ncon]]


def ellipsoids(s: float, ccd_tolerance: float = 1e-6, ccd_iterations: int = 35) -> str:
    """Two penetrating ellipsoids, every length times s: a pair that native CCD (GJK and EPA) handles."""
    return f"""<mujoco><option ccd_tolerance="{ccd_tolerance!r}" ccd_iterations="{ccd_iterations}"/><worldbody>
      <body><freejoint/><geom type="ellipsoid" size="{0.1 * s} {0.07 * s} {0.05 * s}" euler="10 20 30"/></body>
      <body><freejoint/><geom type="ellipsoid" size="{0.08 * s} {0.06 * s} {0.05 * s}"
        pos="{0.12 * s} {0.01 * s} {0.01 * s}" euler="-15 5 40"/></body></worldbody></mujoco>"""


def gaps(original, copy, s: float) -> tuple[float, float, float]:
    """Largest differences of the copy's contacts from the original's scaled: depth, point, frame."""
    assert len(original) == len(copy) > 0
    return (
        max(abs(s * a[0] - b[0]) for a, b in zip(original, copy, strict=True)),
        max(float(np.abs(s * a[1] - b[1]).max()) for a, b in zip(original, copy, strict=True)),
        max(float(np.abs(a[2] - b[2]).max()) for a, b in zip(original, copy, strict=True)),
    )


def test_ccd_tolerance():
    # engine_collision_convex.c mjc_penetration: config.tolerance = opt.ccd_tolerance;
    # engine_collision_gjk.c gjk (min_norm) and epa (upper - lower < tolerance)
    original = contacts(ellipsoids(1))
    depth, _, frame = gaps(original, contacts(ellipsoids(4)), 4)
    assert 1e-7 < depth < 1e-5  # measured: 1.1e-6
    assert frame > 1e-4  # measured: 1.3e-3
    # the tolerance scaled with the lengths: the copy is the original bit for bit
    assert gaps(original, contacts(ellipsoids(4, ccd_tolerance=4e-6)), 4) == (0, 0, 0)


def test_ccd_iterations_is_a_count():
    # engine_collision_convex.c mjc_penetration: config.max_iterations = opt.ccd_iterations; EPA stopped by
    # the count before it meets the tolerance runs the same in the copy, the tolerance left unscaled
    original = contacts(ellipsoids(1, ccd_iterations=10))
    assert gaps(original, contacts(ellipsoids(4, ccd_iterations=10)), 4) == (0, 0, 0)
    assert gaps(contacts(ellipsoids(1)), contacts(ellipsoids(4)), 4)[0] > 0


def box_vertices(a: float, b: float, c: float) -> str:
    """The eight corners of a box of half extents a, b, c, as an MJCF mesh's vertex list."""
    return " ".join(f"{x!r} {y!r} {z!r}" for x in (-a, a) for y in (-b, b) for z in (-c, c))


def box_meshes(s: float, ccd_tolerance: float = 1e-6) -> str:
    return f"""<mujoco><option ccd_tolerance="{ccd_tolerance!r}"/><asset>
      <mesh name="a" vertex="{box_vertices(0.1 * s, 0.07 * s, 0.05 * s)}"/>
      <mesh name="b" vertex="{box_vertices(0.08 * s, 0.06 * s, 0.05 * s)}"/></asset><worldbody>
      <body><freejoint/><geom type="mesh" mesh="a" euler="10 20 30"/></body>
      <body><freejoint/><geom type="mesh" mesh="b" pos="{0.15 * s} {0.01 * s} {0.01 * s}" euler="-15 5 40"/></body>
      </worldbody></mujoco>"""


def test_ccd_polytopes_scale():
    # engine_collision_gjk.c gjk: min_norm = mjMINVAL for two discrete geoms; epa: tolerance = mjMINEPATOL;
    # the option's ccd_tolerance is not used for two polytopes, and mjMINVAL is far below their lengths
    original = contacts(box_meshes(1))
    assert len(original) == 4
    assert gaps(original, contacts(box_meshes(4)), 4) == (0, 0, 0)
    assert gaps(original, contacts(box_meshes(4, ccd_tolerance=4e-6)), 4) == (0, 0, 0)


def touching_spheres(s: float, offset: float) -> str:
    """Two spheres of radius s whose centres are `offset` apart along y."""
    return f"""<mujoco><worldbody><body><freejoint/><geom type="sphere" size="{s}"/></body>
      <body pos="0 {offset!r} 0"><freejoint/><geom type="sphere" size="{s}"/></body></worldbody></mujoco>"""


def test_minval_normal():
    # engine_collision_primitive.c mjraw_SphereSphere: if (len < mjMINVAL) the normal is the cross product of
    # the z axes, (1, 0, 0) where they are parallel
    def normal(s, offset):
        ((_, _, frame),) = contacts(touching_spheres(s, offset))
        return tuple(frame[:3])

    # 4e-16 apart in the original, 1.6e-15 in the copy: the constant lies between them
    assert normal(1, 4e-16) == (1, 0, 0)
    assert normal(4, 1.6e-15) == (0, 1, 0)
    # moved away from it: 4e-15 and 1.6e-14 apart, the normal is the same
    assert normal(1, 4e-15) == normal(4, 1.6e-14) == (0, 1, 0)


def sphere_drop(dmin: float, dmax: float, steps: int = 200) -> np.ndarray:
    """A sphere resting on a plane, every geom with solimp (dmin, dmax, 0.001): its heights."""
    mujoco, m = compiled(f"""<mujoco><default><geom solimp="{dmin!r} {dmax!r} 0.001"/></default><worldbody>
      <geom type="plane" size="1 1 .1"/><body pos="0 0 0.1"><freejoint/><geom type="sphere" size="0.1"/></body>
      </worldbody></mujoco>""")
    d = mujoco.MjData(m)
    out = []
    for _ in range(steps):
        mujoco.mj_step(m, d)
        out.append(d.qpos[2])
    return np.array(out)


@pytest.mark.parametrize(("beyond", "at", "inside"), [(1e-6, 1e-4, 2e-4), (0.99999, 0.9999, 0.9998)])
def test_impedance_clamps(beyond, at, inside):
    # engine_core_constraint.c getsolparam: solimp[0], solimp[1] = min(mjMAXIMP, max(mjMINIMP, .))
    clamped = sphere_drop(at, at)
    assert np.array_equal(sphere_drop(beyond, beyond), clamped)
    assert np.abs(sphere_drop(inside, inside) - clamped).max() > 1e-8  # measured: 3.9e-7


def welded_box(s: float):
    """A box welded to the world at its own pose, every length times s (torquescale too; masses kept): the
    weld's rows at the first step, each row's MuJoCo softness R and its true inverse weight J M^-1 J'."""
    mujoco, m = compiled(f"""<mujoco><option gravity="0 0 {-9.81 * s}"/><worldbody>
      <body name="box" pos="0 0 {0.5 * s}"><freejoint/>
        <inertial pos="0 0 0" mass="2" diaginertia="{0.01 * s * s} {0.02 * s * s} {0.015 * s * s}"/>
        <geom type="box" size="{0.1 * s} {0.08 * s} {0.05 * s}" contype="0" conaffinity="0"/></body>
      </worldbody><equality><weld body1="box" torquescale="{1.0 * s}"/></equality></mujoco>""")
    d = mujoco.MjData(m)
    d.qvel[:] = [0.1 * s, 0, 0, 0.3, 0.2, 0.1]
    mujoco.mj_forward(m, d)
    jac = np.array(d.efc_J).reshape(d.nefc, m.nv)
    mass = np.zeros((m.nv, m.nv))
    mujoco.mj_fullM(m, d, mass)
    weight = np.einsum("ij,jk,ik->i", jac, np.linalg.inv(mass), jac)
    return np.array(d.efc_R), weight


def test_weld_rotational_weight():
    # engine_core_constraint.c mj_diagApprox: a weld's rotational rows take body_invweight0's rotation, not
    # times torquescale^2, while mj_instantiateEquality multiplies those rows' Jacobian by torquescale
    r1, w1 = welded_box(1.0)
    r4, w4 = welded_box(4.0)
    assert r1.shape == (6,)  # three translational rows, then three rotational
    # the true inverse weights are the original's times 1, rows of rotation as of translation (rounding only)
    assert np.allclose(w4 / w1, 1.0, rtol=1e-12, atol=0)
    assert np.array_equal(r4[:3], r1[:3])  # translation: R follows its weight
    assert np.array_equal(r4[3:], r1[3:] / 16)  # rotation: off by torquescale's 4 squared, exactly


def thrown(s: float, options: str = "", steps: int = 300) -> np.ndarray:
    """A box and a capsule thrown onto a plane, every length and gravity times s (masses kept, time kept).

    The positions of the copy come back divided by s (quaternions as they are): the original's, bit for
    bit, wherever the engine holds no constant against the scaled numbers.
    """
    mujoco, m = compiled(f"""<mujoco><option gravity="0 0 {-9.81 * s}" {options}/>
      <default><geom solimp="0.9 0.95 {0.001 * s} 0.5 2" friction="1 {0.005 * s} {0.0001 * s}"/></default>
      <worldbody><geom type="plane" size="{10 * s} {10 * s} {0.1 * s}"/>
      <body pos="0 0 {0.12 * s}" euler="5 3 0"><freejoint/>
        <inertial pos="0 0 0" mass="2" diaginertia="{0.01 * s * s} {0.02 * s * s} {0.015 * s * s}"/>
        <geom type="box" size="{0.1 * s} {0.08 * s} {0.05 * s}"/></body>
      <body pos="{0.5 * s} 0 {0.2 * s}"><freejoint/>
        <inertial pos="0 0 0" mass="0.5" diaginertia="{0.003 * s * s} {0.003 * s * s} {0.002 * s * s}"/>
        <geom type="capsule" size="{0.04 * s} {0.1 * s}" euler="80 0 10"/></body></worldbody></mujoco>""")
    d = mujoco.MjData(m)
    d.qvel[:] = [0.3 * s, 0.1 * s, 0, 0.5, 0.2, 1.0, -0.2 * s, 0, 0, 0, 1, 0]
    lengths = np.array([1 / s] * 3 + [1] * 4 + [1 / s] * 3 + [1] * 4)
    out = []
    for _ in range(steps):
        mujoco.mj_step(m, d)
        out.append(d.qpos * lengths)
    return np.array(out)


def parting(options: str, copy_options: str | None = None) -> float:
    """How far the copy by 4 parts from the original (in the original's units)."""
    return float(np.abs(thrown(1, options) - thrown(4, options if copy_options is None else copy_options)).max())


def test_solver_tolerance():
    # engine_solver.c solPGS: improvement * scale < opt.tolerance, scale = 1 / (meaninertia max(1, nv));
    # mj_solPrimal likewise for CG and Newton
    assert parting('solver="PGS"') > 1e-9  # measured: 1.1e-7
    assert parting('solver="PGS" tolerance="0"') == 0


def test_noslip_tolerance():
    # engine_solver.c solNoSlip: improvement * scale < opt.noslip_tolerance
    default = parting('tolerance="0" noslip_iterations="5"')
    zero = parting('tolerance="0" noslip_iterations="5" noslip_tolerance="0"')
    assert default > 1e-10  # measured: 8.1e-9
    # with it 0 in both runs the copy comes within 1e-16, but not bit for bit (measured: 6.9e-18)
    assert 0 < zero < 1e-16


def test_cg_eta():
    # engine_solver.c mj_solPrimal, Hager-Zhang update: eta = 0.01, eta_k = -1 / (|d| min(eta, |grad|))
    assert parting('solver="CG" tolerance="0" iterations="5"') > 1e-6  # measured: 3.2e-5
    assert parting('solver="CG" tolerance="0"') > 0  # measured: 2.3e-13
    # the other solvers, with the same tolerance and iterations: Newton within 1e-15 (measured: 4.3e-19, a
    # remainder the catalogue does not explain), PGS bit for bit
    assert parting('solver="Newton" tolerance="0" iterations="5"') < 1e-15
    assert parting('solver="PGS" tolerance="0" iterations="5"') == 0


@pytest.mark.parametrize("options", ['ls_tolerance="0.01"', 'ls_tolerance="0.1"', 'impratio="10"'])
def test_dimensionless_settings_scale(options):
    # engine_solver.c PrimalSearch: gtol = tolerance * ls_tolerance * |search| / scale (0 with tolerance 0);
    # engine_core_constraint.c mj_makeImpedance: R of friction rows = R / impratio
    assert parting(f'tolerance="0" {options}') == 0


def test_mujoco_measurements_name_their_tests():
    # every measured effect in the catalogue names a test of this module that asserts it, and each constant
    # read from the source names where; constants_for finds each by its paths
    from pitheorem.engines.constants import CAUSE_PATHS, constants_for

    measured = [c for c in hidden_constants("mujoco") if c.measured]
    assert len(measured) >= 10
    for c in measured:
        assert "a7255075b" in c.location
        (test,) = re.findall(r"test_engines_constants\.py, (test_\w+)\)", c.measured)
        assert callable(globals()[test]), test
        assert c.paths
        assert c.remedy
        assert all(c in constants_for("mujoco", p) for p in c.paths)
    assert {c.name for c in constants_for("mujoco", "native_ccd")} >= {"mujoco_ccd_tolerance", "mujoco_ccd_iterations"}
    assert constants_for("pybullet", "noslip") == ()
    assert set(CAUSE_PATHS) == {p for c in CATALOGUE for p in c.paths}
    with pytest.raises(pt.InvalidRequestError, match=r"'contact'.*native_ccd"):
        constants_for("mujoco", "contact")
    with pytest.raises(pt.InvalidRequestError, match="'ode'"):
        constants_for("ode", "native_ccd")
    with pytest.raises(pt.InvalidRequestError, match=r"'contacts'.*native_ccd"):
        HiddenConstant("mujoco", "mujoco_x", "L", 1.0, "w", "s", "n", paths=("contacts",))
