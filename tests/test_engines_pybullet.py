"""pitheorem.engines.runners.pybullet: URDF models in PyBullet, its settings and scene, scaled files with their settings, runs."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt

pytest.importorskip("pybullet", reason="pybullet is not installed (pip install 'pitheorem[engines]')")

from pitheorem import engines
from pitheorem.engines import EngineModelError, UnscalableParameterError

DATA = Path(__file__).resolve().parent / "data" / "engines"
ARM = DATA / "slider_arm.urdf"


def test_engine_defaults_are_pybullets_own():
    import pybullet as pb

    model = engines.load(ARM)
    client = pb.connect(pb.DIRECT)
    try:
        body = pb.loadURDF(str(ARM), physicsClientId=client)
        # oracle: PyBullet's reports, read here directly; margins 0.001 for box and cylinder, the radius for spheres
        assert model.parameter("link_base_collision_margin").value == (pb.getDynamicsInfo(body, -1)[11],) == (0.001,)
        assert model.parameter("link_arm_collision_margin").value == (pb.getDynamicsInfo(body, 1)[11],)
        import pybullet_data

        sphere = engines.load(Path(pybullet_data.getDataPath()) / "sphere2.urdf")
        assert sphere.parameter("link_baseLink_collision_margin").value == (0.5,)  # a lone sphere: its radius
        assert model.parameter("link_cart_rollingFriction").value == (pytest.approx(0.01),)
        assert (
            pb.getPhysicsEngineParameters(physicsClientId=client)["fixedTimeStep"]
            == model.parameter("timestep").value[0]
        )
    finally:
        pb.disconnect(client)


def test_engine_settings_default_to_the_hidden_constant_catalogue():
    model = engines.load(ARM)  # PyBullet's own settings: split impulse on, multibody damping 0.04
    catalogue = {c.name: c for c in engines.hidden_constants("bullet")}
    pairs = {
        "timestep": "bullet_time_step",
        "contactSlop": "bullet_contact_slop",
        "restitutionVelocityThreshold": "bullet_restitution_velocity_threshold",
        "solverResidualThreshold": "bullet_solver_residual_threshold",
        "splitImpulsePenetrationThreshold": "bullet_split_impulse_penetration_threshold",
        "joint_slide_maxJointVelocity": "bullet_max_joint_velocity",
        "joint_swing_maxJointVelocity": "bullet_max_joint_velocity",
    }
    for name, constant in pairs.items():
        assert model.parameter(name).value == (catalogue[constant].default,)
    for name in ("timestep", "contactSlop", "restitutionVelocityThreshold", "solverResidualThreshold"):
        assert model.parameter(name).dimension == catalogue[pairs[name]].dimension
    # the values bullet3 and the PyBullet guide state, written out (an oracle apart from the catalogue)
    assert [model.parameter(name).value[0] for name in pairs] == [1 / 240, 1e-5, 0.2, 1e-7, -0.04, 100.0, 100.0]
    damping = model.parameter("link_cart_angularDamping")
    assert damping.value == (0.04,)
    assert damping.parts == (("rate", pt.Dimension.parse("T^-1")), ("per_radian", pt.Dimension.parse("1")))
    assert dict(damping.parts) == {
        "rate": catalogue["bullet_angular_damping_k1"].dimension,
        "per_radian": catalogue["bullet_angular_damping_k2"].dimension,
    }
    calls = engines.load(ARM, ground=True).settings()
    assert calls["ground"] == {"collisionMargin": 0.001}
    assert [call["maxJointVelocity"] for call in calls["changeDynamics"] if "maxJointVelocity" in call] == [100.0] * 2


def test_mixed_damping_is_refused_until_switched_off():
    model = engines.load(ARM)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    with pytest.raises(UnscalableParameterError, match="linearDamping"):
        model.scaled(sc, 2)
    with pytest.raises(UnscalableParameterError, match="split"):
        engines.load(ARM, damping=0.0).scaled(sc, 2)
    scaled = engines.load(ARM, damping=0.0, split_impulse=False).scaled(sc, 2)
    assert scaled.parameter("joint_slide_velocity").value == (4.0,)
    assert scaled.parameter("joint_swing_velocity").value == (10.0,)


def test_scaled_run_is_similar_and_a_broken_setting_is_not(tmp_path):
    model = engines.load(ARM, fixed_base=True, damping=0.0, split_impulse=False)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    rep = engines.verify(model, sc, 10, duration=1.0, controls=lambda t: [np.sin(t), 0.1 * np.cos(t)])
    assert rep.similar, str(rep)
    # the joint damping of the slide left unscaled in the saved file
    out = model.scaled(sc, 10).save(tmp_path / "scaled.urdf")
    text = out.read_text()
    scaled_damping = 0.3 * 10.0 ** float(sc.exponent_of("M T^-1"))
    assert f'damping="{scaled_damping!r}"' in text
    out.write_text(text.replace(f'damping="{scaled_damping!r}"', 'damping="0.3"'))
    broken = engines.load(out)  # with the scaled settings saved beside it
    rep = engines.verify(model, sc, 10, duration=1.0, controls=lambda t: [np.sin(t), 0.1 * np.cos(t)], scaled=broken)
    assert not rep.similar


def test_saved_settings_snippet_runs(tmp_path):
    model = engines.load(ARM, ground=True, damping=0.0, split_impulse=False)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    out = model.scaled(sc, 10).save(tmp_path / "arm10.urdf")
    snippet = Path(f"{out}.settings.py")
    import json

    settings = json.loads(Path(f"{out}.settings.json").read_text())
    assert settings["gravity"][2] == pytest.approx(-98.1, rel=1e-15)
    assert settings == model.scaled(sc, 10).settings()
    assert "p.setGravity(" in snippet.read_text()
    done = subprocess.run([sys.executable, str(snippet)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr


def _pd_controller(numbers_from):
    """A PD law on both joints whose gains and set points come from a model's own numbers."""

    def controller(run_model):
        source = run_model if numbers_from is None else numbers_from
        p = {
            n: source.parameter(n).value
            for n in ("joint_slide_effort", "joint_slide_upper", "link_arm_mass", "link_arm_com", "g")
        }
        k_slide = p["joint_slide_effort"][0] / p["joint_slide_upper"][0]  # M T^-2
        k_swing = 20 * p["link_arm_mass"][0] * p["g"][0] * p["link_arm_com"][2]  # M L^2 T^-2 per radian
        reach = p["joint_slide_upper"][0]

        def policy(client, body, t):
            import pybullet as pb

            (q_slide, _), (q_swing, _) = [s[:2] for s in pb.getJointStates(body, [0, 1], physicsClientId=client)]
            return [k_slide * (0.4 * reach * np.sin(3 * t) - q_slide), k_swing * (0.3 * np.sin(2 * t) - q_swing)]

        return policy

    return controller


def test_closed_loop_controller_in_pybullet_is_similar_only_with_its_numbers_scaled():
    model = engines.load(ARM, fixed_base=True, damping=0.0, split_impulse=False)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    rep = engines.verify(model, sc, 10, duration=1.0, controller=_pd_controller(None))
    assert rep.similar, str(rep)
    assert np.ptp(rep.original["q[swing]"]) > 0.3  # it moves the arm through the set point's swing
    # the same law with its numbers frozen at the original model's: Section 6 of the paper
    frozen = engines.verify(model, sc, 10, duration=1.0, controller=_pd_controller(model))
    assert not frozen.similar
    assert frozen.max_deviation > 1e-3


def test_saved_model_reloads_with_its_settings_and_only_so(tmp_path):
    model = engines.load(ARM, ground=True, damping=0.0, split_impulse=False, base_position=(0, 0, 0.3))
    # the solver's residual threshold has no pure dimension (no scaling carries it): exact only at 0
    model = model.with_values(solverResidualThreshold=0.0)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    scaled = model.scaled(sc, 10)
    out = scaled.save(tmp_path / "arm10.urdf")
    again = engines.load(out)
    assert again.settings() == scaled.settings()
    expected = {p.name: p.value for p in scaled.parameters}
    assert [p.name for p in again.parameters] == list(expected)
    for p in again.parameters:  # the file's numbers are written as repr, so they read back as they were
        assert p.value == pytest.approx(expected[p.name], rel=1e-15), p.name
    assert engines.verify(model, sc, 10, duration=0.5, scaled=again).similar
    # the settings fix the scene: options beside them are refused, settings=False reads the bare file
    with pytest.raises(pt.InvalidRequestError, match="fixes the scene"):
        engines.load(out, ground=True)
    bare = engines.load(out, settings=False)
    assert bare.parameter("g").value == (9.81,)
    Path(f"{out}.settings.json").write_text('{"gravity": [0, 0, -9.81]}')
    with pytest.raises(engines.EngineModelError, match=r"arm10\.urdf\.settings\.json.*'loadURDF'"):
        engines.load(out)
    with pytest.raises(engines.EngineModelError, match="no such settings file"):
        engines.load(out, settings=tmp_path / "absent.json")
    # with good settings, a broken URDF is blamed on the URDF, not on its settings file
    Path(f"{out}.settings.json").write_text(json.dumps(scaled.settings()))
    out.write_text("<robot")
    with pytest.raises(engines.EngineModelError, match="not well-formed XML") as caught:
        engines.load(out)
    assert "settings" not in str(caught.value)


@pytest.mark.parametrize(
    ("where", "bad", "says"),
    [
        (("gravity",), [0, 0, 9.81], "gravity along -z only"),
        (("loadURDF", "basePosition"), [0, 0, "x"], "base_position must be a finite real number"),
        (("loadURDF", "basePosition"), [0, 0], "base_position takes three numbers"),
        (("loadURDF", "useFixedBase"), "no", "fixed_base is true or false, got 'no'"),
        (
            ("jointSprings",),
            [{"jointIndex": 7, "stiffness": 1.0, "restPosition": 0.0}],
            "jointSprings: joint 7 is not a movable joint",
        ),
        (("jointSprings",), [{"jointIndex": 0, "stiffness": 1.0}], "key 'restPosition'"),
    ],
)
def test_a_saved_settings_file_with_a_bad_scene_is_named(tmp_path, where, bad, says):
    model = engines.load(ARM, damping=0.0, split_impulse=False)
    out = model.scaled(pt.search(model.system(), scale={"g": 1}).scalings[0], 2).save(tmp_path / "arm2.urdf")
    settings = Path(f"{out}.settings.json")
    doc = json.loads(settings.read_text())
    *parents, key = where
    place = doc
    for parent in parents:
        place = place[parent]
    place[key] = bad
    settings.write_text(json.dumps(doc))
    with pytest.raises(engines.EngineModelError, match=r"arm2\.urdf\.settings\.json") as caught:
        engines.load(out)
    assert says in str(caught.value)


@pytest.mark.parametrize(
    ("options", "error", "says"),
    [
        ({"g": -9.81}, pt.InvalidRequestError, "g cannot be negative, got -9.81"),
        ({"damping": -1e-9}, pt.InvalidRequestError, "damping cannot be negative"),
        ({"damping": "x"}, pt.NumberError, "damping must be a finite real number"),
        ({"ground": "yes"}, pt.InvalidRequestError, "ground is true or false, got 'yes'"),
        ({"fixed_base": 1}, pt.InvalidRequestError, "fixed_base is true or false, got 1"),
        ({"base_position": (0, 1)}, pt.InvalidRequestError, "base_position takes three numbers"),
        ({"base_position": "001"}, pt.InvalidRequestError, "base_position takes three numbers"),
        ({"base_position": (0, 0, float("inf"))}, pt.NumberError, "base_position must be a finite real number"),
    ],
)
def test_the_loader_reads_its_scene_as_the_command_line_does(options, error, says):
    # one reader for the keyword options, --scene and with_settings: the same refusals everywhere
    with pytest.raises(error) as caught:
        engines.load(ARM, **options)
    assert says in str(caught.value)
    name = next(iter(options))
    if name in ("ground", "fixed_base", "base_position"):
        with pytest.raises(error, match=says.split(",")[0]):
            engines.load(ARM).with_settings(**options)


def test_scene_values_are_read_exactly_once_into_floats_and_flags():
    from pitheorem.engines.runners.pybullet import scene_option

    model = engines.load(ARM, g="9.8", damping=0, base_position=("0", 0, "1/2"), ground=np.True_)
    settings = model.settings()
    assert settings["gravity"] == [0.0, 0.0, -9.8]
    assert settings["loadURDF"]["basePosition"] == [0.0, 0.0, 0.5]
    assert settings["ground"] is not None
    moved = model.with_settings(base_position=(1, 2, 3), split_impulse=False)
    assert moved.settings()["loadURDF"]["basePosition"] == [1.0, 2.0, 3.0]
    assert moved.settings()["setPhysicsEngineParameter"]["useSplitImpulse"] == 0
    with pytest.raises(pt.InvalidRequestError, match="split_impulse is true or false, got 'no'"):
        model.with_settings(split_impulse="no")
    assert scene_option("split_impulse", False) is False
    assert scene_option("g", 2) == 2.0
    assert type(scene_option("g", 2)) is float
    with pytest.raises(pt.InvalidRequestError, match="unknown scene option 'gravity'"):
        scene_option("gravity", 1)


# -- bad numbers in the file (issue 23): refused by name, never written into a scaled copy

_ARM_TEXT = ARM.read_text()


def test_params_on_a_urdf_with_a_word_for_a_mass_is_one_line(tmp_path, capsys):
    from pitheorem.cli import main

    path = tmp_path / "heavy.urdf"
    path.write_text(_ARM_TEXT.replace('<mass value="2.0"', '<mass value="heavy"', 1))
    assert main(["params", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("pitheorem: error: ")
    assert err.count("\n") == 1
    assert "'heavy'" in err


def test_the_default_scene_names_every_unscalable_number_at_once_with_one_remedy():
    """PyBullet's default scene fails in two ways (link damping, split impulses): both in one error."""
    robot = Path(__file__).resolve().parent / "robots" / "urdf" / "quadruped.urdf"
    model = engines.load(robot, ground=True, base_position=(0, 0, 0.5))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    with pytest.raises(engines.UnscalableParameterError) as caught:
        model.scaled(sc, 4)
    message = str(caught.value)
    assert "linearDamping" in message
    assert "split-impulse" in message
    assert "damping=0.0, split_impulse=False" in message
    fixed = engines.load(robot, ground=True, base_position=(0, 0, 0.5), damping=0.0, split_impulse=False)
    remedied = fixed.scaled(pt.search(fixed.system(), scale={"g": 1}).scalings[0], 4)  # the remedy suffices
    assert remedied.parameter("g").value == (4 * model.parameter("g").value[0],)


def test_runs_in_one_client_equal_the_runs_each_in_its_own():
    """run_many resets one client's world between runs: each run is what a fresh client gives, bit for bit."""
    pybullet_data = pytest.importorskip("pybullet_data")
    model = engines.load(
        Path(pybullet_data.getDataPath()) / "r2d2.urdf",
        base_position=(0, 0, 1),
        ground=True,
        damping=0.0,
        split_impulse=False,
    )  # wheels on the ground: contacts from the first steps
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    b, copy = model.runner, model.scaled(sc, 10).runner
    u = engines.smooth_controls(model)
    jobs = [(b, u, False, None), (copy, None, False, None), (b.twin(0), u, False, None), (b, u, True, None)]
    one_by_one = [backend.run(120, controls, nudge) for backend, controls, nudge, _ in jobs]
    together = b.run_many(120, jobs)
    assert all(np.array_equal(x, y) for x, y in zip(one_by_one, together, strict=True))
    assert not np.array_equal(one_by_one[0], one_by_one[3])  # the nudged run differs: not a vacuous equality


def test_a_scaled_copy_reads_as_its_saved_file_does(tmp_path):
    """The copy shares its original's reading of the links; the saved file is read by PyBullet afresh."""
    pybullet_data = pytest.importorskip("pybullet_data")
    model = engines.load(
        Path(pybullet_data.getDataPath()) / "r2d2.urdf",
        base_position=(0, 0, 1),
        ground=True,
        damping=0.0,
        split_impulse=False,
    )
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    copy = model.scaled(sc, 10)
    reread = engines.load(copy.save(tmp_path / "r2d2_10.urdf"))
    assert [(p.name, p.value) for p in copy.parameters] == [(p.name, p.value) for p in reread.parameters]
    assert copy.parameter("g").value[0] == 10 * model.parameter("g").value[0]  # scaled: not a vacuous equality


def test_no_file_is_written_into_the_users_folder_and_meshes_still_load(tmp_path, monkeypatch):
    """The robot's meshes are named by absolute paths in a copy in the system's temporary folder."""
    import shutil
    import tempfile

    robot = tmp_path / "robot"
    shutil.copytree(Path(__file__).resolve().parent / "robots" / "urdf", robot)
    written = []
    real = tempfile.mkstemp

    def recording(*args, **kwargs):
        fd, name = real(*args, **kwargs)
        written.append(Path(name).parent)
        return fd, name

    monkeypatch.setattr(tempfile, "mkstemp", recording)
    before = sorted(p.name for p in robot.rglob("*"))
    model = engines.load(robot / "arm.urdf", fixed_base=True, damping=0.0, split_impulse=False)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    assert engines.verify(model, sc, 4, duration=0.2, controls=engines.smooth_controls(model)).exact
    assert written  # PyBullet read copies ...
    assert all(folder != robot for folder in written)  # ... none of them in the user's folder
    assert sorted(p.name for p in robot.rglob("*")) == before
    assert any(
        shape[4].endswith(b".obj") or shape[4].endswith(b".stl")
        for shapes in model.runner._info["shapes"].values()
        for shape in shapes
    )  # meshes were loaded


def test_a_compound_collision_mesh_is_named_as_a_setting_cause_and_matters_only_in_contact():
    """pybullet_data's duck: five convex parts whose margins no changeDynamics reaches."""
    pybullet_data = pytest.importorskip("pybullet_data")
    duck = Path(pybullet_data.getDataPath()) / "duck_vhacd.urdf"

    def judged(ground, g=9.81):
        with pytest.warns(engines.UnscalableModelWarning, match="convex parts"):
            model = engines.load(duck, base_position=(0, 0, 0.2), ground=ground, damping=0.0, split_impulse=False)
        model = model.with_values(solverResidualThreshold=0.0, g=g)
        sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
        return engines.verify(model, sc, 4, duration=0.5)

    on_the_ground = judged(True)
    assert not on_the_ground.exact
    assert [c.element for c in on_the_ground.causes] == ["link 'baseLink' collision mesh 'duck_vhacd.obj'"]
    cause = on_the_ground.causes[0]
    assert cause.kind == "setting"
    # shown by a run: with every contact off in both runs (the duck's and the ground's) they are the same bits
    assert cause.restores is True
    assert "with contacts off in both runs they are equal bit for bit" in cause.detail
    assert judged(False).exact  # with nothing to touch, the margins play no part
    # falling fast enough for the copy (four times as fast) to meet Bullet's velocity clamp, with nothing to touch:
    # the clamp is named, and the margins, which a run with contacts off shows act on nothing here, are not
    fast = judged(False, g=60.0)
    assert not fast.exact
    assert [c.element for c in fast.causes] == ["velocity clamp"]


def test_a_file_pybullet_reads_despite_blank_lines_a_nul_or_a_material_inside_a_visual_geometry(tmp_path):
    """pybullet_data's biped, humanoid and racecar files have each of these; PyBullet's reader shrugs them off."""
    text = ARM.read_text()
    body = text[text.index("<robot") :]
    odd = tmp_path / "odd.urdf"
    odd.write_text(
        "\n\n"
        + '<?xml version="1.0"?>\n'
        + body.replace(
            "</robot>",
            '<link name="decor"><visual><geometry><box size="0.1 0.1 0.1"/><material name="grey"/>'
            '</geometry></visual></link><joint name="decor_fixed" type="fixed"><parent link="base"/>'
            '<child link="decor"/></joint></robot>',
        )
        + "\x00"
    )
    model = engines.load(odd)
    assert model.parameter("link_decor_visual0_size").value == (0.1, 0.1, 0.1)
    bad = tmp_path / "bad.urdf"  # the same in a collision: refused, for it would change the dynamics
    bad.write_text(
        body.replace(
            "</robot>",
            '<link name="decor"><collision><geometry><material name="grey"/></geometry></collision></link>'
            '<joint name="decor_fixed" type="fixed"><parent link="base"/><child link="decor"/></joint></robot>',
        )
    )
    with pytest.raises(EngineModelError, match="unknown geometry"):
        engines.load(bad)


# -- the reader: every dimensional number of a URDF, by element and attribute -------------------------


def test_joint_springs_have_the_dimension_of_their_joint_and_scale_save_and_reload(tmp_path):
    model = engines.load(ARM, fixed_base=True, damping=0.0, split_impulse=False).with_settings(
        joint_springs={"slide": (40, "0.1"), "swing": (2.5, -0.2)}
    )
    dims = {p.name: str(p.dimension) for p in model.parameters if "spring" in p.name}
    assert dims == {
        "joint_slide_spring_stiffness": "M T^-2",
        "joint_slide_spring_rest": "L",
        "joint_swing_spring_stiffness": "M L^2 T^-2",
        "joint_swing_spring_rest": "1",
    }
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    scaled = model.scaled(sc, 4)
    springs = {s["jointIndex"]: (s["stiffness"], s["restPosition"]) for s in scaled.settings()["jointSprings"]}
    assert springs == {0: (40.0, 0.1 * 4), 1: (2.5 * 16, -0.2)}  # M T^-2 keeps, M L^2 T^-2 by s^2
    again = engines.load(scaled.save(tmp_path / "arm4.urdf"))
    assert again.settings() == scaled.settings()
    snippet = Path(tmp_path / "arm4.urdf.settings.py").read_text()
    assert "def apply_springs():" in snippet
    rep = engines.verify(model, sc, 4, duration=0.5, ensemble=1)
    assert rep.exact, str(rep)
    assert rep.excited


def test_a_joint_spring_pulls_its_joint_as_the_torque_minus_k_q_minus_q0():
    """The spring's run against the same run with its torque given as a closed-loop policy, bit for bit."""
    plain = engines.load(ARM, fixed_base=True, damping=0.0, split_impulse=False)
    sprung = plain.with_settings(joint_springs={"swing": (2.5, 0.3)})
    names = plain.coordinates()[0]
    q = names.index("q[swing]")

    def by_hand(client, body, t):
        import pybullet

        angle = pybullet.getJointState(body, 1, physicsClientId=client)[0]
        return [0.0, -2.5 * (angle - 0.3)]

    ours = sprung.run(200)
    theirs = plain.run(200, policy=by_hand)
    assert np.array_equal(ours, theirs)
    assert np.ptp(ours[:, q]) > 0.1  # it swung


@pytest.mark.parametrize(
    ("springs", "says"),
    [
        ({"elbow": (1, 0)}, "no movable joint 'elbow' for a spring; the movable joints are slide, swing"),
        ({"swing": (-1, 0)}, "the spring stiffness of joint 'swing' cannot be negative"),
        ({"swing": 3}, "the spring of joint 'swing' is (stiffness, rest position)"),
        ([("swing", 1, 0)], "joint_springs maps a joint's name to (stiffness, rest position)"),
        ({"swing": ("stiff", 0)}, "stiff"),
    ],
)
def test_bad_joint_springs_are_named(springs, says):
    model = engines.load(ARM, fixed_base=True)
    with pytest.raises(pt.PiTheoremError) as err:
        model.with_settings(joint_springs=springs)
    assert says in str(err.value)


def test_with_settings_sets_the_multibody_damping_and_back_to_pybullets_own():
    model = engines.load(ARM, fixed_base=True)
    off = model.with_settings(damping=0)
    assert {p.value for p in off.parameters if p.name.endswith("Damping")} == {(0.0,)}
    back = off.with_settings(damping=None)
    assert back.settings() == model.settings()
    with pytest.raises(pt.InvalidRequestError, match="unknown setting 'gravity'"):
        model.with_settings(gravity=1)


def test_a_run_starts_from_a_given_first_row():
    model = engines.load(ARM, fixed_base=True, damping=0.0, split_impulse=False)
    names = model.coordinates()[0]
    first = model.run(0)[0]
    first[names.index("q[swing]")], first[names.index("qdot[slide]")] = 0.4, -0.3
    rows = model.run(3, initial=first)
    assert np.array_equal(rows[0], first)
    assert not np.array_equal(rows, model.run(3))


def test_a_compound_mesh_cause_names_the_file_never_a_machine_path(tmp_path):
    """A mesh written as an absolute path (a saved copy's) is named by its file name alone."""
    pybullet_data = pytest.importorskip("pybullet_data")
    data = Path(pybullet_data.getDataPath())
    text = (data / "duck_vhacd.urdf").read_text()
    assert 'filename="duck_vhacd.obj"' in text
    copy = tmp_path / "duck.urdf"
    copy.write_text(re.sub(r'filename="([^"/]+)"', lambda m: f'filename="{data / m.group(1)}"', text))
    with pytest.warns(engines.UnscalableModelWarning, match="convex parts"):
        model = engines.load(copy, base_position=(0, 0, 0.2), ground=True)
    causes = [c for c in model.runner.ignored_settings() if "collision mesh" in c.element]
    assert [c.element for c in causes] == ["link 'baseLink' collision mesh 'duck_vhacd.obj'"]
    assert str(data) not in causes[0].detail


def test_keep_inputs_is_refused_for_pybullet_whose_inputs_are_the_joint_forces_themselves():
    model = engines.load(ARM, damping=0.0, split_impulse=False)
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    with pytest.raises(pt.errors.InputsNotKeptError) as caught:
        model.scaled(sc, 4, keep_inputs=True)
    assert caught.value.culprit == "pybullet"
    assert str(caught.value) == (
        "a pybullet model cannot keep its inputs: its inputs are joint forces, with no gain to carry a factor"
    )
    assert isinstance(caught.value, pt.InvalidRequestError)
    model.scaled(sc, 4)  # the default stays as it is


# -- spherical joints (pybullet_data's humanoid): a quaternion and three torques each, PyBullet's motor off ----


def _humanoid():
    pybullet_data = pytest.importorskip("pybullet_data", reason="pybullet_data is not installed")
    return Path(pybullet_data.getDataPath()) / "humanoid" / "humanoid.urdf"


def test_a_spherical_joint_runs_with_its_quaternion_and_three_torques_and_no_motor():
    model = engines.load(_humanoid(), fixed_base=True)
    names, dims = model.coordinates()
    assert [n for n in names if n.startswith("q[chest")] == ["q[chest:x]", "q[chest:y]", "q[chest:z]", "q[chest:w]"]
    assert [str(dims[names.index(f"qdot[chest:{a}]")]) for a in "xyz"] == ["T^-1"] * 3
    assert str(dims[names.index("q[right_knee]")]) == "1"  # a revolute joint keeps its one coordinate
    inputs = model.inputs()[0]
    spherical, revolute = 8, 4  # the humanoid's joints as its file states them
    assert len(inputs) == 3 * spherical + revolute
    assert {str(d) for d in inputs} == {"M L^2 T^-2"}
    assert str(model.parameter("joint_neck_maxJointVelocity").dimension) == "T^-1"
    # zero input, the root held: with PyBullet's default motor on, the hip would stay within 1e-4 of rest;
    # without it the leg swings under gravity
    rows = model.run(240)
    hip = names.index("q[right_hip:x]")
    assert np.allclose(rows[0, hip : hip + 4], (0, 0, 0, 1))
    assert abs(rows[-1, hip : hip + 4] - (0, 0, 0, 1)).max() > 0.05
    assert np.allclose(np.linalg.norm(rows[:, hip : hip + 4], axis=1), 1.0)
    # each torque acts on its own joint and axis: a torque about the chest's x turns the chest about x
    push = np.zeros(len(inputs))
    push[0] = 50.0
    pushed = model.run(60, controls=lambda t: push)
    chest = names.index("q[chest:x]")
    still = model.run(60)
    assert abs(pushed[-1, chest] - still[-1, chest]) > 1e-3
    assert abs(pushed[-1, chest + 1] - still[-1, chest + 1]) < abs(pushed[-1, chest] - still[-1, chest]) / 10
    # a run started from a row restarts exactly there, the quaternions included
    again = model.run(10, initial=rows[-1])
    assert np.array_equal(again[0], rows[-1])


def test_a_spherical_joint_scales_bit_for_bit_and_refuses_a_spring_by_name():
    model = engines.load(_humanoid(), damping=0.0, split_impulse=False)
    scaling = pt.search(model.system(), scale={"g": 1}).scalings[0]
    rep = engines.verify(model, scaling, s=4, duration=0.1, controls=engines.smooth_controls(model))
    assert rep.exact
    assert rep.excited
    with pytest.raises(pt.InvalidRequestError, match="joint 'chest' is spherical; a spring takes a revolute"):
        model.with_settings(joint_springs={"chest": (1.0, 0.0)})


def test_a_link_without_a_mass_in_its_file_gets_pybullets_and_follows_the_scaling(tmp_path):
    # husky's sensor and bumper links state no <inertial>: PyBullet gives each 1 kg and a unit inertia
    path = tmp_path / "two.urdf"
    path.write_text(
        '<robot name="two"><link name="base"><inertial><mass value="2"/>'
        '<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
        '<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>'
        '<link name="tip"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>'
        '<joint name="hinge" type="revolute"><parent link="base"/><child link="tip"/>'
        '<origin xyz="0.3 0 0"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="10" velocity="10"/></joint>'
        "</robot>"
    )
    model = engines.load(path, damping=0.0, split_impulse=False)
    mass = model.parameter("link_tip_mass")
    assert (mass.value, str(mass.dimension), mass.source) == ((1.0,), "M", "engine")
    # the file's own mass keeps its one row
    assert [p.source for p in model.parameters if p.name.startswith("link_base_mass")] == ["file"]
    heavier = pt.Scaling.from_unit_change(model.system(), {"M": 1})
    copy = model.scaled(heavier, 4)
    assert copy.runner.stored_numbers()["link.mass"][:, 0].tolist() == [8.0, 4.0]
    rep = engines.verify(model, pt.search(model.system(), scale={"g": 1}).scalings[0], s=4, duration=0.2)
    assert rep.exact
    saved = copy.save(tmp_path / "two4.urdf")
    assert engines.load(saved).parameter("link_tip_mass").value == (4.0,)


def test_bullets_velocity_clamp_is_a_cause_shown_by_a_run():
    """Bullet clamps every coordinate velocity of a body at one number (100), the base's speed as well as the
    joints' angular speeds, whatever link changeDynamics(maxJointVelocity) names.  Example-robot-data's Allegro
    hand (its inertias unbalanced) flew off at the clamp in PyBullet, and the verdict named only a margin.  Here a
    box with a flap falls under a large gravity: the copy at s = 4 falls four times as fast and is cut at 100
    too.  The cause is named, and lifting the clamp in both runs restores the run bit for bit."""
    import pybullet as pb

    path = DATA / "falling_flap.urdf"
    dt, steps = 1 / 240, 36  # the original reaches 75 (below the clamp), the copy 300, cut at 100

    def speed(g: float, clamp: float | None) -> float:
        """By hand, in plain PyBullet: the box's downward speed after `steps` steps, under gravity `g`."""
        client = pb.connect(pb.DIRECT)
        try:
            pb.setGravity(0, 0, -g, physicsClientId=client)
            pb.setTimeStep(dt, physicsClientId=client)
            body = pb.loadURDF(str(path), physicsClientId=client)
            for link in (-1, 0):
                pb.changeDynamics(body, link, linearDamping=0, angularDamping=0, physicsClientId=client)
            if clamp is not None:
                pb.changeDynamics(body, -1, maxJointVelocity=clamp, physicsClientId=client)
            for _ in range(steps):
                pb.stepSimulation(physicsClientId=client)
            return -pb.getBaseVelocity(body, physicsClientId=client)[0][2]
        finally:
            pb.disconnect(physicsClientId=client)

    # the premise: the original stays below the clamp, the copy (gravity times 4) is cut at it; lifted, it is not
    assert speed(500.0, None) < 100.0
    assert speed(2000.0, None) == 100.0
    assert speed(2000.0, float("inf")) == 4 * speed(500.0, float("inf")) > 100.0

    model = engines.load(path, engine="pybullet", damping=0.0, split_impulse=False).with_values(g=500.0)
    assert model.runner.velocity_clamp()[0] == 100.0
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("timestep",)).scalings[0]
    rep = engines.verify(model, sc, 4, duration=steps * dt)
    assert not rep.exact
    clamp = next(c for c in rep.causes if c.element == "velocity clamp")
    assert clamp.kind == "threshold"
    assert clamp.restores is True
    assert "equal bit for bit" in clamp.detail
    # below the clamp nothing of it shows: a gravity the copy's speed stays under is exact
    calm = model.with_values(g=50.0)
    assert engines.verify(calm, sc, 4, duration=steps * dt).exact


def test_a_body_of_more_links_than_pybullet_reports_is_refused_at_load(tmp_path):
    """Example-robot-data's TIAGo with two arms (130 links) loaded in PyBullet and the run then stopped with
    pybullet.error "GetBasePositionAndOrientation failed".  PyBullet reports the state of a body of 128 links (its
    base and 127 joints) at most; one more is refused at load, by name, and 128 load."""
    import pybullet as pb

    from pitheorem.engines.runners.pybullet import MAX_LINKS

    def chain(n: int) -> Path:
        """A URDF of a base and `n` links, each fixed to the one before."""
        inertial = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
        links = "\n".join(f'<link name="l{i}">{inertial}</link>' for i in range(n + 1))
        joints = "\n".join(
            f'<joint name="j{i}" type="fixed"><parent link="l{i}"/><child link="l{i + 1}"/></joint>' for i in range(n)
        )
        path = tmp_path / f"chain{n}.urdf"
        path.write_text(f'<robot name="chain">\n{links}\n{joints}\n</robot>\n')
        return path

    # by hand, in plain PyBullet: the state of 129 links (128 joints) is not reported, that of 128 is
    client = pb.connect(pb.DIRECT)
    try:
        body = pb.loadURDF(str(chain(MAX_LINKS)), physicsClientId=client)
        with pytest.raises(pb.error, match="GetBasePositionAndOrientation failed"):
            pb.getBasePositionAndOrientation(body, physicsClientId=client)
        body = pb.loadURDF(str(chain(MAX_LINKS - 1)), physicsClientId=client)
        assert len(pb.getBasePositionAndOrientation(body, physicsClientId=client)) == 2
    finally:
        pb.disconnect(physicsClientId=client)

    with pytest.raises(EngineModelError, match="cannot report its state") as refused:
        engines.load(chain(MAX_LINKS), engine="pybullet")
    assert refused.value.element == "<robot>"
    assert f"body of {MAX_LINKS + 1} links" in refused.value.reason
    assert engines.load(chain(MAX_LINKS - 1), engine="pybullet").runner.run(2).shape == (3, 13)


def test_a_counter_run_whose_original_breaks_down_before_the_runs_part_is_said_to_show_nothing():
    """The flap's hinge has negative damping: its speed grows until the velocity clamp holds it.  The copy's fall,
    four times as fast, is cut by the clamp at another point; lifting the clamp (the counter-run) lets the flap's
    speed blow up before that point, so that counter-run can show nothing, and the unexplained parting says so.
    Example-robot-data's double pendulum (free base) does the same in PyBullet."""
    import pybullet as pb

    path = DATA / "unstable_flap.urdf"
    client = pb.connect(pb.DIRECT)  # by hand, in plain PyBullet: without the clamp the run breaks down
    try:
        pb.setGravity(0, 0, -25.0, physicsClientId=client)
        body = pb.loadURDF(str(path), physicsClientId=client)
        for link in (-1, 0):
            pb.changeDynamics(body, link, linearDamping=0, angularDamping=0, physicsClientId=client)
        pb.setJointMotorControl2(body, 0, pb.VELOCITY_CONTROL, force=0, physicsClientId=client)
        pb.changeDynamics(body, -1, maxJointVelocity=float("inf"), physicsClientId=client)
        speeds = []
        for _ in range(30):
            pb.stepSimulation(physicsClientId=client)
            speeds.append(pb.getJointState(body, 0, physicsClientId=client)[1])
        assert not np.isfinite(speeds).all()
    finally:
        pb.disconnect(physicsClientId=client)

    model = engines.load(path, engine="pybullet", damping=0.0, split_impulse=False).with_values(g=25.0)
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("timestep",)).scalings[0]
    rep = engines.verify(model, sc, 4, duration=1.2)
    assert not rep.exact
    unknown = next(c for c in rep.causes if c.kind == "unknown")
    broken = re.search(
        r"the velocity clamp lifted \(with it, the original's run breaks down at step (\d+), before the runs part\)",
        unknown.detail,
    )
    parts = re.search(r"differ in a bit at step (\d+)", unknown.detail)
    assert broken is not None
    assert parts is not None
    assert int(broken.group(1)) < int(parts.group(1))
    assert "velocity clamp" not in [c.element for c in rep.causes]


def test_pybullets_counter_runs_switch_contacts_off_and_name_what_they_cannot_switch():
    """The runner's counter-runs: every contact off (the robot's and the ground's), the velocity clamp lifted; a URDF
    has no equality constraint and no limit is switched off, so asking for one is refused by name.  A collision
    margin is removed by the contacts-off run; no other ignored setting is."""
    from pitheorem.engines.verdicts.causes import Cause

    model = engines.load(ARM, ground=True, base_position=(0, 0, 0.3), damping=0.0, split_impulse=False)
    runner = model.runner
    assert runner.equality_names() == runner.equality_kinds() == runner.limit_names() == []
    with pytest.raises(pt.InvalidRequestError, match="no equality constraint"):
        runner.variant(inactive_equalities=(0,))
    # on the ground, the arm's base rests on it; with every contact off it falls through
    resting, falling = runner.run(120), runner.variant(contacts=False).run(120)  # 0.5 s
    assert resting[-1, 2] > 0.0  # the base's height
    assert falling[-1, 2] < -0.5
    assert runner.variant(velocity_clamp=5.0).velocity_clamp()[0] == 5.0
    assert runner.removed_by(Cause("setting", "link 'base' collision mesh 'parts.obj'", "")) == {"contacts": False}
    assert runner.removed_by(Cause("setting", "changeDynamics(restitution)", "")) is None
    assert runner.removed_by(Cause("threshold", "changeDynamics(collisionMargin)", "")) is None


def test_joints_set_other_velocity_clamps_than_the_one_pybullet_holds_are_a_setting_cause_where_a_run_reaches_it():
    """A copy of the slider arm at s = 4 asks for a clamp of 400 m/s on its slide and 100 rad/s on its swing joint;
    PyBullet holds one, the last written, for both.  Where no run reaches it, it acts on nothing and is not named;
    where the slide is driven so hard that the copy's (four times as fast) reaches 100, it is named and shown by a
    run with the clamp lifted in both."""
    import pybullet as pb

    client = pb.connect(pb.DIRECT)  # by hand, in plain PyBullet: the swing's clamp, written last, holds the slide
    try:
        pb.setGravity(0, 0, 0, physicsClientId=client)
        body = pb.loadURDF(str(ARM), useFixedBase=True, physicsClientId=client)
        speeds = {}
        for clamps in ({0: 400.0}, {0: 400.0, 1: 100.0}):
            for joint, clamp in clamps.items():
                pb.changeDynamics(body, joint, maxJointVelocity=clamp, physicsClientId=client)
            pb.resetJointState(body, 0, 0.0, 150.0, physicsClientId=client)
            pb.stepSimulation(physicsClientId=client)
            speeds[len(clamps)] = pb.getJointState(body, 0, physicsClientId=client)[1]
        assert speeds[2] <= 100.0 < speeds[1]  # cut at the clamp (less the step's joint damping), or not
    finally:
        pb.disconnect(physicsClientId=client)

    model = engines.load(ARM, fixed_base=True, damping=0.0, split_impulse=False)
    model = model.with_values(solverResidualThreshold=0.0)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    audited = [c for c in engines.audit(model, sc, 4).causes if c.element == "changeDynamics(maxJointVelocity)"]
    assert len(audited) == 1
    assert "joint 'slide': set 400, PyBullet keeps 100" in audited[0].detail
    gentle = engines.verify(model, sc, 4, duration=0.2, controls=lambda t: [50.0, 0.0])
    assert gentle.exact
    assert gentle.causes == ()
    at_ten = engines.verify(model, sc, 10, duration=0.2, controls=lambda t: [50.0, 0.0])
    assert at_ten.similar
    assert "changeDynamics(maxJointVelocity)" not in [c.element for c in at_ten.causes]  # no run reaches it
    hard = engines.verify(model, sc, 4, duration=0.2, controls=lambda t: [1500.0, 0.0])
    assert not hard.exact
    assert [c.element for c in hard.causes] == ["changeDynamics(maxJointVelocity)"]
    assert hard.causes[0].restores is True
    assert "with the velocity clamp lifted in both runs they are equal bit for bit" in hard.causes[0].detail
