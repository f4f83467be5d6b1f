"""The hidden-constant catalogue against the installed engines: defaults read from the engine, dimensions shown
by scaled runs (which way of treating a constant keeps a scaled run exact)."""

from __future__ import annotations

import numpy as np
import pytest

from pitheorem.engines import hidden_constants


def default(name):
    return hidden_constants(names=[name])[0].default


# -- MuJoCo: the defaults of a fresh MjSpec -----------------------------------------------------


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
    assert list(geom.friction) == [default("mujoco_sliding_friction"), default("mujoco_torsional_friction"),
                                   default("mujoco_rolling_friction")]
    assert geom.density == default("mujoco_geom_density")
    assert joint.margin == default("mujoco_joint_margin")
    assert list(joint.stiffness)[1:] == [default("mujoco_stiffness_poly")] * 2
    assert list(joint.damping)[1:] == [default("mujoco_damping_poly")] * 2


# -- PyBullet: what getPhysicsEngineParameters and getDynamicsInfo report -------------------------


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
    box = pb.createMultiBody(1.0, pb.createCollisionShape(pb.GEOM_BOX, halfExtents=[0.1] * 3,
                                                          physicsClientId=client), physicsClientId=client)
    assert pb.getDynamicsInfo(box, -1, physicsClientId=client)[11] == default("bullet_collision_margin")
    ball = pb.createMultiBody(1.0, pb.createCollisionShape(pb.GEOM_SPHERE, radius=0.25, physicsClientId=client),
                              physicsClientId=client)
    assert pb.getDynamicsInfo(ball, -1, physicsClientId=client)[11] == 0.25  # a sphere's margin is its radius


def drop_ball(pb, client, *, scale, breaking):
    """A ball of radius 0.1 scale dropped from 1 scale onto a plane, gravity 9.81 scale; heights over 1 s."""
    pb.resetSimulation(physicsClientId=client)
    pb.setPhysicsEngineParameter(contactBreakingThreshold=breaking, physicsClientId=client)
    # the lengths among the solver's settings scaled too; split impulses (threshold not settable) off
    pb.setPhysicsEngineParameter(contactSlop=1e-5 * scale, restitutionVelocityThreshold=0.2 * scale,
                                 solverResidualThreshold=1e-7 * scale**2, useSplitImpulse=0, physicsClientId=client)
    pb.setGravity(0, 0, -9.81 * scale, physicsClientId=client)
    plane = pb.createMultiBody(0, pb.createCollisionShape(pb.GEOM_PLANE, physicsClientId=client),
                               physicsClientId=client)
    pb.changeDynamics(plane, -1, collisionMargin=0.001 * scale, restitution=0.9, physicsClientId=client)
    ball = pb.createMultiBody(1.0, pb.createCollisionShape(pb.GEOM_SPHERE, radius=0.1 * scale,
                                                           physicsClientId=client),
                              basePosition=[0, 0, 1.0 * scale], physicsClientId=client)
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
