"""URDF files in MuJoCo: a motor per movable joint, meshes under ``<mujoco><compiler meshdir>``, and the
verdicts on pybullet_data's robots whose runs MuJoCo's own arithmetic parts (issue 35 item 2)."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt
from pitheorem import engines

mujoco = pytest.importorskip("mujoco", reason="the models below are MuJoCo's (pip install 'pitheorem[engines]')")

ROBOTS = Path(__file__).resolve().parent / "robots" / "urdf"


def _pybullet_data() -> Path:
    pybullet_data = pytest.importorskip("pybullet_data", reason="pybullet_data's URDF files")
    return Path(pybullet_data.getDataPath())


def _gravity_scaled(model):
    """The issue's scaling: gravity by s, time fixed (so lengths by s, and masses as the search picks)."""
    return pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]


def test_every_movable_joint_of_a_urdf_gets_a_motor_whose_input_is_its_torque_or_force():
    path = ROBOTS / "gripper.urdf"  # a revolute wrist and two prismatic fingers
    model = engines.load(path, engine="mujoco")
    m = model.runner.mjmodel
    dims, low, high = model.inputs()
    by_joint = {mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_ACTUATOR, i): str(d) for i, d in enumerate(dims)}
    assert by_joint == {"wrist": "M L^2 T^-2", "left": "M L T^-2", "right": "M L T^-2"}
    assert np.all(np.isinf(low))  # no control range, as PyBullet's torques
    assert np.all(np.isinf(high))
    # the same inputs, by joint, as PyBullet's runner of the same file takes
    pybullet_model = engines.load(path)
    names = [name for _j, name, _t in pybullet_model.runner._info["joints"]]
    pybullet_dims = dict(zip(names, (str(d) for d in pybullet_model.inputs()[0]), strict=True))
    assert pybullet_dims == by_joint
    # each motor acts on its own joint: its input is that joint's generalised force, gear 1
    assert [int(m.actuator_trnid[i, 0]) for i in range(m.nu)] == list(range(m.njnt))
    assert np.array_equal(m.actuator_gear[:, 0], np.ones(m.nu))


def test_a_urdf_runs_its_joint_torques_as_plain_mujoco_applies_them_to_its_own_reading_of_the_file():
    path = ROBOTS / "gripper.urdf"
    model = engines.load(path, engine="mujoco")
    inputs = [0.02, -0.5, 0.75]  # within each joint's effort limit
    rows = model.run(20, controls=lambda t: inputs)
    native = mujoco.MjModel.from_xml_path(str(path))  # MuJoCo's own URDF reader: no actuators
    assert native.nu == 0
    data = mujoco.MjData(native)
    for step in range(20):
        data.qfrc_applied[:] = inputs  # one torque or force per joint, applied by hand
        mujoco.mj_step(native, data)
        assert rows[step + 1].tolist() == [*data.qpos, *data.qvel], step
    assert not np.array_equal(rows[-1], rows[0])  # the inputs moved it


def test_a_motor_is_capped_at_its_joints_effort_limit_as_mujoco_reads_the_urdf(tmp_path):
    text = (ROBOTS / "gripper.urdf").read_text()
    path = tmp_path / "gripper.urdf"
    shutil.copytree(ROBOTS / "meshes", tmp_path / "meshes")
    path.write_text(text)
    model = engines.load(path, engine="mujoco")
    m = model.runner.mjmodel
    effort = m.jnt_actfrcrange[:, 1]
    assert np.all(effort > 0)
    assert np.all(m.jnt_actfrclimited)
    at_limit = model.run(10, controls=lambda t: effort)
    beyond = model.run(10, controls=lambda t: 3 * effort)
    below = model.run(10, controls=lambda t: 0.5 * effort)
    assert np.array_equal(at_limit, beyond)  # the force MuJoCo applies stops at the effort
    assert not np.array_equal(at_limit, below)


@pytest.mark.parametrize("name", ["gripper.urdf", "arm.urdf"])
def test_smooth_controls_move_a_urdf_in_mujoco_and_its_copy_at_s_4_is_bit_for_bit(name):
    model = engines.load(ROBOTS / name, engine="mujoco")
    u = engines.smooth_controls(model)
    assert len(u(0.1)) == model.runner.mjmodel.njnt
    rep = engines.verify(model, _gravity_scaled(model), 4, duration=0.5, controls=u)
    assert rep.excited, str(rep)
    assert rep.exact, str(rep)


def _with_mesh_folder(tmp_path: Path, meshdir: str, filename: str) -> Path:
    """tests/robots' arm, its meshes moved to tmp_path/assets/obj and named relative to `meshdir`."""
    (tmp_path / "assets").mkdir()
    shutil.copytree(ROBOTS / "meshes", tmp_path / "assets" / "obj")
    text = (ROBOTS / "arm.urdf").read_text()
    text = text.replace('filename="meshes/', f'filename="{filename}')
    text = text.replace('<robot name="arm">', f'<robot name="arm">\n  <mujoco><compiler meshdir="{meshdir}"/></mujoco>')
    path = tmp_path / "robot" / "arm.urdf"
    path.parent.mkdir()
    path.write_text(text)
    return path


@pytest.mark.parametrize(("meshdir", "filename"), [("../assets/obj", ""), ("../assets", "obj/")])
def test_meshes_named_relative_to_the_mujoco_blocks_meshdir_load_scale_and_save(tmp_path, meshdir, filename):
    path = _with_mesh_folder(tmp_path, meshdir, filename)
    model = engines.load(path, engine="mujoco")
    native = mujoco.MjModel.from_xml_path(str(path))  # MuJoCo finds them there itself
    assert model.runner.mjmodel.nmesh == native.nmesh > 0
    assert np.array_equal(model.runner.mjmodel.mesh_vert, native.mesh_vert)
    reference = engines.load(ROBOTS / "arm.urdf", engine="mujoco")  # the same meshes beside the file
    assert np.array_equal(model.runner.mjmodel.mesh_vert, reference.runner.mjmodel.mesh_vert)
    scaling = pt.Scaling.from_unit_change(model.system(), {"L": 1, "M": 3, "T": -1})
    copy = model.scaled(scaling, 4)
    assert np.array_equal(copy.runner.mjmodel.mesh_vert, 4 * native.mesh_vert)
    (tmp_path / "out").mkdir()
    saved = copy.save(tmp_path / "out" / "arm_4.urdf")  # another folder: names relative to it, no meshdir
    assert "meshdir" not in saved.read_text()
    again = engines.load(saved, engine="mujoco")
    assert np.array_equal(again.runner.mjmodel.mesh_vert, copy.runner.mjmodel.mesh_vert)
    assert engines.load(path).engine == "pybullet"  # PyBullet gets every mesh by its absolute path


def test_a_mesh_missing_from_meshdir_is_refused_naming_the_folder(tmp_path):
    path = _with_mesh_folder(tmp_path, "../elsewhere", "")
    with pytest.raises(engines.EngineModelError, match=r"meshdir.*elsewhere"):
        engines.load(path, engine="mujoco")


@pytest.mark.parametrize("name", ["r2d2.urdf", "quadruped/minitaur.urdf"])
def test_pybullet_data_robots_whose_runs_mujoco_parts_get_a_cause_whose_counter_run_restores_them(name):
    """r2d2's wheels touch bodies that cannot move along the contact: MuJoCo floors the contacts'
    softness R at mjMINVAL, no scaled number.  The minitaur's cylinder-box contacts go through MuJoCo's
    native convex collision, whose stopping rules hold lengths against mjMINVAL."""
    model = engines.load(_pybullet_data() / name, engine="mujoco")
    scaling = _gravity_scaled(model)
    rep = engines.verify(model, scaling, 4, duration=0.3, controls=engines.smooth_controls(model))
    assert not rep.exact
    assert rep.causes
    assert all(c.kind == "contact" and c.restores for c in rep.causes), rep.causes
    # by hand, in plain MuJoCo: the copy is compiled from the original's numbers times their factors
    m, c = model.runner.mjmodel, model.scaled(scaling, 4).runner.mjmodel
    mass, length, time = (4.0 ** float(scaling.unit_change[b]) for b in "MLT")
    expected = {
        "geom_size": m.geom_size * length,
        "geom_margin": m.geom_margin * length,
        "geom_solimp": m.geom_solimp * [1, 1, length, 1, 1],  # the width is a length
        "geom_friction": m.geom_friction * [1, length, length],  # torsional and rolling: lengths
        "geom_solref": m.geom_solref * [time, 1],
        "body_mass": m.body_mass * mass,
        "body_inertia": m.body_inertia * mass * length**2,
        # a torque (revolute) or a force (prismatic)
        "jnt_actfrcrange": m.jnt_actfrcrange
        * (mass * length / time**2 * np.where(m.jnt_type == 2, 1, length))[:, None],
    }
    for field, value in expected.items():
        assert np.array_equal(getattr(c, field), value), field
    d, e = mujoco.MjData(m), mujoco.MjData(c)
    mujoco.mj_forward(m, d)
    mujoco.mj_forward(c, e)
    floor = d.efc_R[: d.nefc] <= 2 * mujoco.mjMINVAL
    if name == "r2d2.urdf":  # the same contacts, every one exactly 4 times as deep, yet R at the floor in both
        assert d.ncon == e.ncon > 0
        assert [x.dist * 4 for x in d.contact[: d.ncon]] == [x.dist for x in e.contact[: e.ncon]]
        assert floor.any()
        assert np.array_equal(d.efc_R[: d.nefc][floor], e.efc_R[: e.nefc][floor])
    else:
        assert not floor.any()


_COMPILER = """<robot name="bounded">
  <mujoco><compiler balanceinertia="true" boundmass="0.05" boundinertia="0.0002"/></mujoco>
  <link name="base"/>
  <link name="flat">
    <inertial><mass value="1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.005"/></inertial>
  </link>
  <joint name="hip" type="revolute">
    <parent link="base"/><child link="flat"/><axis xyz="0 1 0"/><origin xyz="0 0 0"/>
  </joint>
  <link name="light">
    <inertial><origin xyz="0.2 0 0"/><mass value="0.001"/>
      <inertia ixx="0.00001" ixy="0" ixz="0" iyy="0.00001" iyz="0" izz="0.00001"/></inertial>
  </link>
  <joint name="knee" type="revolute">
    <parent link="flat"/><child link="light"/><axis xyz="0 1 0"/><origin xyz="0.3 0 0"/>
  </joint>
  <link name="solid">
    <collision><origin xyz="0.1 0 0"/><geometry><box size="0.2 0.05 0.05"/></geometry></collision>
  </link>
  <joint name="ankle" type="prismatic">
    <parent link="light"/><child link="solid"/><axis xyz="1 0 0"/><origin xyz="0.2 0 0"/>
    <limit lower="-0.1" upper="0.1" effort="5" velocity="1"/>
  </joint>
</robot>
"""


def test_the_inertias_mujoco_derives_under_the_urdfs_compiler_block_scale_with_the_copy(tmp_path):
    """balanceinertia, boundmass and boundinertia, and a link's mass from its geometry (no <inertial>)."""
    path = tmp_path / "bounded.urdf"
    path.write_text(_COMPILER)
    model = engines.load(path, engine="mujoco")
    m = model.runner.mjmodel
    with pytest.raises(ValueError, match="balanceinertia"):  # MuJoCo refuses the flat link's inertia unbalanced
        mujoco.MjModel.from_xml_string(_COMPILER.replace(' balanceinertia="true"', ""))
    assert m.body_mass[2] == 0.05  # the light link raised to boundmass
    assert m.body_mass[3] == pytest.approx(1000 * 0.2 * 0.05 * 0.05)  # the solid link's box at density 1000
    scaling = pt.Scaling.from_unit_change(model.system(), {"L": 1, "M": 3, "T": -1})  # every bound moves
    mass, length = 4.0**3, 4.0
    copy = model.scaled(scaling, 4).runner.mjmodel
    assert np.array_equal(copy.body_mass, m.body_mass * mass)
    assert np.array_equal(copy.body_inertia, m.body_inertia * mass * length**2)
    rep = engines.verify(model, scaling, 4, duration=0.5, controls=engines.smooth_controls(model))
    assert rep.excited, str(rep)
    assert rep.exact, str(rep)
