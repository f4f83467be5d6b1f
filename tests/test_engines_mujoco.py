"""pitheorem.engines.runners.mujoco: MuJoCo's runs of a document, as plain MuJoCo steps them."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt
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
    # MuJoCo's URDF reader makes no actuators: the runner gives each joint a motor (the rail a force)
    assert native.nu == 0
    assert [str(d) for d in model.runner.control_dimensions()] == ["M L T^-2", "M L^2 T^-2"]


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
    with pytest.raises(engines.EngineModelError, match="inertia must have positive eigenvalues") as refused:
        engines.load(PYBULLET_DATA / "cube_no_rotation.urdf", engine="mujoco")  # MuJoCo's own refusal
    assert refused.value.element == "link 'x_prismatic'"  # the link MuJoCo's message names


def test_a_moving_link_without_inertia_is_named_with_what_mujoco_needs(tmp_path):
    """PyBullet runs a URDF whose moving links are point masses (robotics-toolbox's AL5D and PUMA 560); MuJoCo's
    compiler refuses them, naming the first such body only in a line of its own.  The refusal names the link and
    what to give it."""
    inertial = (
        '<inertial><mass value="{m}"/><inertia ixx="{i}" iyy="{i}" izz="{i}" ixy="0" ixz="0" iyz="0"/></inertial>'
    )
    path = tmp_path / "arm.urdf"
    path.write_text(
        f'<robot name="arm"><link name="base">{inertial.format(m=1, i=0.1)}</link>'
        f'<link name="upper">{inertial.format(m=0.2, i=0)}</link>'
        '<joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 1 0"/>'
        '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint></robot>'
    )
    assert engines.load(path, engine="pybullet").engine == "pybullet"
    with pytest.raises(engines.EngineModelError, match="mass and inertia of moving bodies") as refused:
        engines.load(path, engine="mujoco")
    assert refused.value.element == "link 'upper'"
    assert "give the link an <inertial> with a mass and moments of inertia above 1e-15" in refused.value.reason


def _two_link_urdf(tmp_path, *, upper_inertia="0.01 0.01 0.01 0 0 0", mesh=None, block=""):
    """A URDF of a base and an upper arm on a hinge: the arm's <inertia> (ixx iyy izz ixy ixz iyz) and its mesh."""
    ixx, iyy, izz, ixy, ixz, iyz = upper_inertia.split()
    collision = f'<collision><geometry><mesh filename="{mesh}"/></geometry></collision>' if mesh else ""
    path = tmp_path / "arm.urdf"
    path.write_text(
        f'<robot name="arm">{block}<link name="base"><inertial><mass value="1"/>'
        '<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>'
        f'<link name="upper"><inertial><mass value="0.2"/><inertia ixx="{ixx}" iyy="{iyy}" izz="{izz}" '
        f'ixy="{ixy}" ixz="{ixz}" iyz="{iyz}"/></inertial>{collision}</link>'
        '<joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 1 0"/>'
        '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint></robot>'
    )
    return path


def test_a_mesh_mujoco_cannot_read_is_named_with_the_links_that_use_it(tmp_path):
    """MuJoCo's refusal names a mesh by the stem of its file and does not say it is a mesh: the refusal says so,
    with the link that uses it (example-robot-data's Kinova arm: mesh 'base.dae' of link 'j2s6s200_link_base',
    which was called link 'base'), and what to do.  An ASCII STL file, which MuJoCo cannot read and PyBullet
    can, is told apart by its first bytes."""
    (tmp_path / "shell.dae").write_text("<COLLADA/>")
    with pytest.raises(engines.EngineModelError, match="no decoder found") as refused:
        engines.load(_two_link_urdf(tmp_path, mesh="shell.dae"), engine="mujoco")
    assert refused.value.element == "mesh 'shell' (of link 'upper')"
    assert "MuJoCo reads mesh files in STL, OBJ and MSH only" in refused.value.reason

    facet = "facet normal 0 0 1\nouter loop\nvertex {}\nvertex {}\nvertex {}\nendloop\nendfacet\n"
    corners = ("0 0 0", "0.1 0 0", "0 0.1 0", "0 0 0.1")
    faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    (tmp_path / "wedge.stl").write_text(
        "solid wedge\n" + "".join(facet.format(*(corners[i] for i in f)) for f in faces) + "endsolid wedge\n"
    )
    path = _two_link_urdf(tmp_path, mesh="wedge.stl")
    assert engines.load(path, engine="pybullet").engine == "pybullet"
    with pytest.raises(engines.EngineModelError, match="stl_decoder") as refused:
        engines.load(path, engine="mujoco")
    assert refused.value.element == "mesh 'wedge' (of link 'upper')"
    assert "MuJoCo reads binary STL only" in refused.value.reason
    # a binary STL whose 80-byte header happens to begin with 'solid' is no ASCII file
    (tmp_path / "wedge.stl").write_bytes(b"solid but binary".ljust(80, b" ") + (0).to_bytes(4, "little"))
    with pytest.raises(engines.EngineModelError, match="stl_decoder") as refused:
        engines.load(path, engine="mujoco")
    assert "binary STL only" not in refused.value.reason


def test_moments_of_inertia_mujoco_refuses_are_named_with_the_remedy_that_works(tmp_path):
    """Allegro's hand and Go1 (example-robot-data) in MuJoCo: moments that break A + B >= C, and an <inertia> of
    all 1e-6 (no positive definite matrix).  PyBullet takes both.  The remedy given for the first, MuJoCo's
    balanceinertia in the URDF's <mujoco> block, loads the file, with the three moments set to their mean."""
    unbalanced = _two_link_urdf(tmp_path, upper_inertia="0.01 0.01 0.03 0 0 0")
    with pytest.raises(engines.EngineModelError, match="A \\+ B >= C") as refused:
        engines.load(unbalanced, engine="mujoco")
    assert refused.value.element == "link 'upper'"
    assert '<mujoco><compiler balanceinertia="true"/></mujoco> inside <robot>' in refused.value.reason
    balanced = _two_link_urdf(
        tmp_path, upper_inertia="0.01 0.01 0.03 0 0 0", block='<mujoco><compiler balanceinertia="true"/></mujoco>'
    )
    model = engines.load(balanced, engine="mujoco")
    upper = model.runner.mjmodel.body("upper").id
    assert model.runner.mjmodel.body_inertia[upper].tolist() == pytest.approx([0.05 / 3] * 3)

    singular = _two_link_urdf(tmp_path, upper_inertia="1e-6 1e-6 1e-6 1e-6 1e-6 1e-6")
    assert engines.load(singular, engine="pybullet").engine == "pybullet"
    with pytest.raises(engines.EngineModelError, match="positive eigenvalues") as refused:
        engines.load(singular, engine="mujoco")
    assert refused.value.element == "link 'upper'"
    assert "no positive definite matrix" in refused.value.reason


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


# -- URDF files in MuJoCo: a motor per movable joint, meshes under <mujoco><compiler meshdir>, and the
# verdicts on pybullet_data's robots whose runs MuJoCo's own arithmetic parts (issue 35 item 2)

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
    with pytest.raises(engines.EngineModelError, match="mesh file not found"):
        engines.load(path)  # PyBullet reads no <mujoco> block: it looks beside the file only


def test_a_mesh_missing_from_meshdir_is_refused_naming_the_folder(tmp_path):
    path = _with_mesh_folder(tmp_path, "../elsewhere", "")
    with pytest.raises(engines.EngineModelError, match=r"mesh folder '.*elsewhere', its <mujoco><compiler meshdir>"):
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
    # the mechanism the cause names: the softness floor for r2d2, the collision function for the minitaur
    named = "R at MuJoCo's floor mjMINVAL" if name == "r2d2.urdf" else "mjc_Convex (GJK/EPA)"
    assert all(named in c.element for c in rep.causes), rep.causes
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


_PINNED_WHEEL = """<robot name="pinned_wheel">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <link name="wheel">
    <inertial><mass value="0.5"/><inertia ixx="5e-4" iyy="5e-4" izz="5e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="axle" type="continuous">
    <parent link="base"/><child link="wheel"/><origin xyz="0 0 0.149"/><axis xyz="0 1 0"/>
  </joint>
  <link name="roller">
    <inertial><mass value="0.5"/><inertia ixx="5e-4" iyy="5e-4" izz="5e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin rpy="1.5707963267948966 0 0"/><geometry><capsule radius="0.02" length="0.1"/></geometry></collision>
  </link>
  <joint name="spindle" type="continuous">
    <parent link="base"/><child link="roller"/><origin xyz="0.05 0 -0.119"/><axis xyz="0 1 0"/>
  </joint>
</robot>"""


@pytest.mark.parametrize(
    "change",
    [{"L": 1, "M": -2}, {"L": 1, "M": 1}, {"M": 2}, {"L": 1}, {"L": -1}],
    ids=str,
)
def test_a_contact_whose_softness_is_mujocos_floor_is_exact_exactly_under_scalings_that_keep_the_mass_unit(
    tmp_path, change
):
    """R2-D2's, the PR2 gripper's and minitaur_single_motor's mechanism on a tiny robot: a ball and a capsule
    each hinged at its centre, 1 mm into a box of the root (welded to the world).  Neither body of a contact
    moves along it, so MuJoCo's approximate inverse weight is 0 and R = mjMINVAL in the original and the copy
    alike; a spin moves the contact point sideways, so the friction rows act.  R is an inverse mass: the
    floor is the copy's true R when the mass unit is kept, and not otherwise.  The cause is one for both
    pairs (a sphere-box and a capsule-box pair): either alone off leaves the other's rows at the floor."""
    path = tmp_path / "pinned_wheel.urdf"
    path.write_text(_PINNED_WHEEL)
    model = engines.load(path, engine="mujoco")
    scaling = pt.Scaling.from_unit_change(model.system(), change)
    copy = model.scaled(scaling, 4)
    keeps_mass = change.get("M", 0) == 0
    # by hand in plain MuJoCo: the contacts found alike, their rows' R at the floor in both, and the friction
    # rows' Jacobian not zero (the spins move along them)
    m, c = model.runner.mjmodel, copy.runner.mjmodel
    assert m.body_invweight0[:, 0].tolist() == c.body_invweight0[:, 0].tolist() == [0.0, 0.0, 0.0]
    d, e = mujoco.MjData(m), mujoco.MjData(c)
    mujoco.mj_forward(m, d)
    mujoco.mj_forward(c, e)
    length = 4.0 ** change.get("L", 0)
    assert d.ncon == e.ncon == 3  # the ball's, and the capsule's two (its segment parallel to the face)
    assert all(x.dist * length == y.dist < 0 for x, y in zip(d.contact, e.contact, strict=True))
    assert d.efc_R[: d.nefc].tolist() == e.efc_R[: e.nefc].tolist() == [2 * mujoco.mjMINVAL] * 12
    assert np.abs(d.efc_J[: d.nefc * m.nv]).max() > 0
    u = engines.smooth_controls(model)
    torque = 4.0 ** (change.get("M", 0) + 2 * change.get("L", 0) - 2 * change.get("T", 0))
    angular_velocity = 4.0 ** -change.get("T", 0)
    equal = []
    for i in range(150):  # the joints' torques u(t), the copy's times their factor at the copy's time
        d.ctrl[:] = u(i * m.opt.timestep)
        e.ctrl[:] = d.ctrl * torque
        mujoco.mj_step(m, d)
        mujoco.mj_step(c, e)
        equal.append(d.qpos.tolist() == e.qpos.tolist() and (d.qvel * angular_velocity).tolist() == e.qvel.tolist())
    # the contacts, rigid at R = 1e-15, hold both against their motors with forces of 1e15 N whose net
    # torque is rounding: the runs part in the rounding of those forces
    assert np.abs(d.qfrc_actuator).min() > 0.1
    assert np.abs(d.qpos).max() < 1e-12
    assert d.efc_force[: d.nefc].min() > 1e14
    assert all(equal) is keeps_mass
    rep = engines.verify(model, scaling, 4, duration=0.3, controls=u)
    assert rep.excited
    assert rep.exact is keeps_mass
    if not keeps_mass:  # the cause named is the floor, and its counter-run (both pairs off) restores the run
        assert [c.kind for c in rep.causes] == ["contact"]
        assert rep.causes[0].restores
        assert "R at MuJoCo's floor mjMINVAL" in rep.causes[0].element
        assert "mujoco_minval_softness" in rep.causes[0].element
        assert rep.causes[0].element.endswith(": geom #0 / geom #1, geom #0 / geom #2")


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


def test_a_urdfs_spherical_joint_is_mujocos_ball_with_a_quaternion_and_verifies_exact():
    # pybullet_data's humanoid: MuJoCo reads its spherical joints as balls (4 positions, 3 velocities each)
    model = engines.load(PYBULLET_DATA / "humanoid" / "humanoid.urdf", engine="mujoco")
    m = model.runner.mjmodel
    names, dims = model.coordinates()
    assert len(names) == m.nq + m.nv
    balls = [j for j in range(m.njnt) if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_BALL]
    assert len(balls) == 8
    chest = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, balls[0])
    assert [n for n in names if n.startswith(f"qpos[{chest}]")] == [f"qpos[{chest}][{k}]" for k in range(4)]
    assert {str(dims[names.index(f"qvel[{chest}][{k}]")]) for k in range(3)} == {"T^-1"}
    rep = engines.verify(model, _unit_change(model), 4, duration=0.1)
    assert rep.exact, str(rep)
