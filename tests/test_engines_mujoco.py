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


# -- URDF files compiled by MuJoCo's URDF reader -----------------------------------------------------

pybullet_data = pytest.importorskip("pybullet_data", reason="pybullet_data's robots (pip install 'pitheorem[engines]')")
PYBULLET_DATA = Path(pybullet_data.getDataPath())


def _unit_change(model):
    """Lengths by s, masses by s^3 and times by s^-1: every setting of a dimension moves."""
    import pitheorem as pt

    return pt.Scaling.from_unit_change(model.system(), {"L": 1, "M": 3, "T": -1})


def test_a_urdf_in_mujoco_is_mujocos_own_reading_of_the_file_with_its_settings_listed():
    path = PYBULLET_DATA / "cartpole.urdf"
    model = engines.load(path, engine="mujoco")
    native = mujoco.MjModel.from_xml_path(str(path))  # MuJoCo's own URDF reader, from the file
    assert model.engine == "mujoco"
    for field in ("body_mass", "body_inertia", "geom_size", "geom_friction", "geom_solref", "jnt_range", "dof_damping"):
        assert np.array_equal(getattr(model.runner.mjmodel, field), getattr(native, field)), field
    assert model.timestep() == native.opt.timestep
    from pitheorem.engines.fileformats.urdf import read_urdf

    names = [p.name for p in model.parameters]
    urdf_names = [p.name for p in read_urdf(path).parameters()]
    assert names[: len(urdf_names)] == urdf_names  # the URDF's numbers first, as the format reads them
    table = {p.name: p for p in model.parameters}
    assert table["g"].value == (pytest.approx(float(np.linalg.norm(native.opt.gravity))),)
    assert table["geom_solref_time"].value == (native.geom_solref[0, 0],)
    assert str(table["slide_solimp_limit_width"].dimension) == "L"  # the cart's rail: a slide
    assert str(table["hinge_solimp_limit_width"].dimension) == "1"  # the pole's hinge
    assert model.runner.control_dimensions() == []  # MuJoCo's URDF reader makes no actuators


@pytest.mark.parametrize("name", ["cartpole.urdf", "kuka_iiwa/model.urdf", "pendulum5.urdf"])
def test_verify_is_exact_at_s_4_for_a_urdf_in_mujoco_under_a_change_of_every_unit(name):
    model = engines.load(PYBULLET_DATA / name, engine="mujoco")
    rep = engines.verify(model, _unit_change(model), 4, duration=0.5)
    assert rep.exact, str(rep)


def test_every_setting_of_a_scaled_urdf_copy_is_its_factor_times_the_original():
    model = engines.load(PYBULLET_DATA / "cartpole.urdf", engine="mujoco")
    scaling = _unit_change(model)
    copy = model.scaled(scaling, 4)
    before, after = {p.name: p for p in model.parameters}, {p.name: p for p in copy.parameters}
    # the factor from the dimension alone: L by 4, M by 4^3, T by 1/4
    factor = {
        n: 4.0 ** float(p.dimension.exponent_of("L") + 3 * p.dimension.exponent_of("M") - p.dimension.exponent_of("T"))
        for n, p in before.items()
    }
    assert after["timestep"].value == (before["timestep"].value[0] / 4,)
    assert after["geom_solref_time"].value == (before["geom_solref_time"].value[0] / 4,)
    for name, p in before.items():
        assert after[name].value == tuple(v * factor[name] for v in p.value), name
    # and the compiled copy holds them: MuJoCo's time constants of contacts and limits, a quarter
    assert np.array_equal(copy.runner.mjmodel.geom_solref[:, 0], model.runner.mjmodel.geom_solref[:, 0] / 4)
    assert np.array_equal(copy.runner.mjmodel.jnt_solref[:, 0], model.runner.mjmodel.jnt_solref[:, 0] / 4)


def test_a_saved_urdf_copy_reloads_in_mujoco_with_its_settings_bit_for_bit(tmp_path):
    model = engines.load(PYBULLET_DATA / "kuka_iiwa" / "model.urdf", engine="mujoco")
    copy = model.scaled(_unit_change(model), 4)
    target = tmp_path / "kuka.urdf"
    copy.save(target)
    assert (tmp_path / "kuka.urdf.mujoco.json").is_file()
    again = engines.load(target, engine="mujoco")
    mine, theirs = copy.runner.stored_numbers(), again.runner.stored_numbers()
    assert mine.keys() == theirs.keys()
    for field in mine:
        assert np.array_equal(mine[field], theirs[field]), field
    ignored = engines.load(target, engine="mujoco", settings=False)  # MuJoCo's defaults: not the copy's
    assert ignored.timestep() != again.timestep()


def test_a_urdf_with_mimic_joints_and_package_paths_compiles_and_its_mimic_softness_scales():
    # the Panda's fingers: a <mimic> (a joint equality in MuJoCo) and meshes named package://...
    model = engines.load(PYBULLET_DATA / "franka_panda" / "panda.urdf", engine="mujoco")
    assert model.runner.mjmodel.neq == 1
    assert model.runner.mjmodel.nmesh > 0
    copy = model.scaled(_unit_change(model), 4)
    m, c = model.runner.mjmodel, copy.runner.mjmodel
    assert c.eq_solref[0, 0] == m.eq_solref[0, 0] / 4  # a time constant
    assert c.eq_solimp[0, 2] == m.eq_solimp[0, 2] * 4  # a width along the fingers' slides: a length


_BLOCK = """<robot name="slider">
  <mujoco><option timestep="0.001" gravity="0 0 -5" tolerance="0"/></mujoco>
  <link name="base"/>
  <link name="cart">
    <inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <joint name="rail" type="prismatic">
    <parent link="base"/><child link="cart"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>{mimic}
  </joint>
  <link name="cart2">
    <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
  <joint name="rail2" type="prismatic">
    <parent link="base"/><child link="cart2"/><axis xyz="0 0 1"/>{mimic2}
  </joint>
</robot>
"""


def test_the_mujoco_block_of_a_urdf_gives_the_settings_and_a_mimic_offset_is_refused_by_name(tmp_path):
    path = tmp_path / "slider.urdf"
    path.write_text(_BLOCK.format(mimic="", mimic2=""))
    model = engines.load(path, engine="mujoco")
    settings = model.settings()
    assert settings["option"]["timestep"] == 0.001
    assert settings["option"]["tolerance"] == 0.0
    assert {p.name: p.value for p in model.parameters}["g"] == (5.0,)
    assert sorted(settings) == ["compiler", "geom", "option", "slide"]  # no hinge: no hinge settings
    assert engines.verify(model, _unit_change(model), 4, duration=0.3).exact
    path.write_text(_BLOCK.format(mimic="", mimic2='<mimic joint="rail" multiplier="1" offset="0.1"/>'))
    with pytest.raises(engines.EngineModelError, match="joint 'rail2' mimic"):
        engines.load(path, engine="mujoco")


def test_bad_mujoco_settings_of_a_urdf_are_refused_by_name(tmp_path):
    import json

    source = PYBULLET_DATA / "cartpole.urdf"
    good = engines.load(source, engine="mujoco").settings()
    cases = [
        ({k: v for k, v in good.items() if k != "geom"}, "MuJoCo settings: groups"),
        ({**good, "geom": {**good["geom"], "margin": "wide"}}, r"MuJoCo setting geom\.margin"),
        ({**good, "option": {**good["option"], "gravity": [0, 0]}}, r"MuJoCo setting option\.gravity"),
        ({**good, "hinge": {**good["hinge"], "solref_limit": [-100, -10]}}, r"hinge\.solref_limit.*mix dimensions"),
        ({**good, "slide": {k: v for k, v in good["slide"].items() if k != "margin"}}, "settings 'slide'"),
    ]
    for table, message in cases:
        saved = tmp_path / "settings.json"
        saved.write_text(json.dumps(table))
        with pytest.raises(engines.EngineModelError, match=message):
            engines.load(source, engine="mujoco", settings=saved)
    (tmp_path / "broken.json").write_text("{not json")
    with pytest.raises(engines.EngineModelError, match="not a MuJoCo settings file"):
        engines.load(source, engine="mujoco", settings=tmp_path / "broken.json")
    with pytest.raises(engines.EngineModelError, match="no such settings file"):
        engines.load(source, engine="mujoco", settings=tmp_path / "missing.json")
    with pytest.raises(engines.EngineModelError, match="SI units"):
        engines.load(source, engine="mujoco", units={"M": "g", "L": "cm", "T": "s"})
    with pytest.raises(engines.EngineModelError, match="MuJoCo's compiler"):  # MuJoCo's own refusal
        engines.load(PYBULLET_DATA / "cube_no_rotation.urdf", engine="mujoco")


def test_mujoco_4_0_0s_sparse_cholesky_bug_is_noted_where_a_model_meets_it(tmp_path, capsys):
    """Issue 35 item 4: the Newton solver with sparse Jacobians, in MuJoCo 4.0.0 (fixed in 4.0.1, MuJoCo #3767)."""
    import mujoco

    from pitheorem.cli import main

    text = (DATA / "contact.xml").read_text()
    sparse, dense = tmp_path / "sparse.xml", tmp_path / "dense.xml"
    sparse.write_text(text.replace('<option timestep="0.002"', '<option jacobian="sparse" timestep="0.002"'))
    dense.write_text(text.replace('<option timestep="0.002"', '<option jacobian="dense" timestep="0.002"'))
    noted = engines.load(sparse).runner.engine_notes()
    assert engines.load(dense).runner.engine_notes() == ()
    if mujoco.__version__ != "4.0.0":
        assert noted == ()
        return
    assert len(noted) == 1
    assert "#3767" in noted[0]
    assert "4.0.1" in noted[0]
    main(["check", str(sparse)])
    assert "note: MuJoCo 4.0.0's Newton solver has a sparse Cholesky bug" in capsys.readouterr().out
    main(["verify", str(sparse), "--scale", "g=1", "--s", "4", "--duration", "0.1"])
    assert "note: MuJoCo 4.0.0's Newton solver" in capsys.readouterr().out


def test_dof_length_is_a_stored_number_only_where_sleep_makes_mujoco_read_it(tmp_path):
    """MuJoCo reads dof_length (a rotational dof's length scale) only to put bodies to sleep: without sleep a
    copy whose dof_length is off cannot run otherwise, so the audit does not hold it."""
    body = '<worldbody><body><joint type="hinge"/><geom size="0.1" mass="1"/></body></worldbody>'
    awake = tmp_path / "awake.xml"
    awake.write_text(f"<mujoco>{body}</mujoco>")
    asleep = tmp_path / "asleep.xml"
    asleep.write_text(f'<mujoco><option><flag sleep="enable"/></option>{body}</mujoco>')
    assert "dof_length" not in engines.load(awake).runner.stored_numbers()
    assert "dof_length" in engines.load(asleep).runner.stored_numbers()
