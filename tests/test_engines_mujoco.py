"""pitheorem.engines.runners.mujoco: MuJoCo's runs of a document, as plain MuJoCo steps them."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pitheorem import engines

mujoco = pytest.importorskip("mujoco", reason="the models below are MuJoCo's (pip install 'pitheorem[engines]')")

DATA = Path(__file__).resolve().parent / "data" / "engines"


def test_a_run_starts_from_a_given_first_row_as_mujoco_steps_it():
    mujoco = pytest.importorskip("mujoco")
    path = engines.example_path("pendulum.xml")
    model = engines.load(path)
    rows = model.run(5, controls=lambda t: [0.2], initial=(0.5, -0.25))
    native = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(native)
    data.qpos[0], data.qvel[0] = 0.5, -0.25
    assert rows[0].tolist() == [0.5, -0.25]
    for step in range(5):
        data.ctrl[:] = 0.2
        mujoco.mj_step(native, data)
        assert rows[step + 1].tolist() == [*data.qpos, *data.qvel], step
    closed = model.run(5, policy=lambda m, d: [0.2], initial=(0.5, -0.25))
    assert np.array_equal(closed, rows)


def test_a_run_starts_from_a_given_activation_as_mujoco_steps_it(tmp_path):
    mujoco = pytest.importorskip("mujoco")
    path = tmp_path / "filtered.xml"
    path.write_text(
        '<mujoco><worldbody><body><joint name="j" type="hinge"/><geom size="0.1" mass="1"/></body>'
        '</worldbody><actuator><general joint="j" dyntype="filter" dynprm="0.1"/></actuator></mujoco>'
    )
    rows = engines.load(path).run(3, initial=(0.2, 0.0, 0.5))
    native = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(native)
    data.qpos[0], data.act[0] = 0.2, 0.5
    for step in range(3):
        mujoco.mj_step(native, data)
        assert rows[step + 1].tolist() == [*data.qpos, *data.qvel, *data.act], step
    assert rows[0].tolist() == [0.2, 0.0, 0.5]


@pytest.mark.parametrize("integrator", ["Euler", "RK4", "implicitfast"])
def test_a_policy_sees_everything_computed_for_the_state_it_acts_on(integrator, tmp_path):
    """Sensors, site poses and tendon lengths are the current state's when the policy is called, not the last step's."""
    pytest.importorskip("mujoco")
    (tmp_path / "arm.xml").write_text(
        f'<mujoco><option integrator="{integrator}"/><worldbody><body><joint name="j" type="hinge" axis="0 1 0"/>'
        '<geom type="capsule" fromto="0 0 0 1 0 0" size="0.05"/><site name="tip" pos="1 0 0"/></body></worldbody>'
        '<actuator><motor joint="j"/></actuator><sensor><jointpos joint="j"/></sensor></mujoco>'
    )
    model = engines.load(tmp_path / "arm.xml")
    seen = []

    def policy(m, d):
        # the tip of a unit arm turned by q about y sits at (cos q, 0, -sin q)
        seen.append((d.qpos[0], d.sensordata[0], d.site_xpos[0][0], -d.site_xpos[0][2]))
        return [0.0]

    model.run(30, policy=policy)
    q, sensed, x, z = np.array(seen).T
    assert np.ptp(q) > 0.01  # the arm fell: the state moved
    assert np.array_equal(sensed, q)
    assert np.allclose(x, np.cos(q), rtol=0, atol=1e-12)
    assert np.allclose(z, np.sin(q), rtol=0, atol=1e-12)


def test_a_batch_while_the_kept_thread_pool_is_busy_runs_on_a_pool_of_its_own():
    from pitheorem.engines.runners import mujoco as mjcf

    b = engines.load(DATA / "contact.xml").runner
    jobs = [(b, None, False, None), (b, None, True, None)]
    alone = b.run_many(50, jobs)
    with mjcf._thread_pool(2):  # the kept two-thread pool is taken, as by a batch on another Python thread
        busy = b.run_many(50, jobs)
    assert all(np.array_equal(x, y) for x, y in zip(alone, busy, strict=True))
    assert not np.array_equal(alone[0], alone[1])  # the nudged run differs: not a vacuous equality
