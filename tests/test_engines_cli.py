"""The command line on MJCF and URDF files: params, search, apply; bad model files exit 2 naming file and element."""

from __future__ import annotations

import json
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

import pitheorem as pt
from pitheorem import engines
from pitheorem.cli import BASES_SHOWN, main
from pitheorem.modelfile import EXAMPLES, examples

DATA = Path(__file__).resolve().parent / "data" / "engines"
PENDULUM = str(engines.example_path("pendulum.xml"))


def test_params_lists_dimensions(capsys):
    assert main(["params", PENDULUM, "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    rows = {p["name"]: p for p in doc["parameters"]}
    assert doc["engine"] == "mujoco"
    assert rows["joint_hinge_damping"]["dimension"] == "M L^2 T^-1"
    assert rows["g"]["value"] == [9.81]


def test_params_on_a_toml_file_lists_its_variables(capsys):
    assert main(["params", "example:hinged_rod", "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    rows = {p["name"]: p for p in doc["parameters"]}
    assert doc["engine"] is None
    assert rows["k_theta"]["dimension"] == "M L^2 T^-2"
    assert rows["m"]["value"] == [1.5]
    assert rows["t"]["value"] == []
    assert main(["params", "example:hinged_rod"]) == 0
    assert capsys.readouterr().out.splitlines()[0] == "example:hinged_rod: model file, 9 variables"


def test_search_and_apply_write_a_file_the_engine_loads(tmp_path, capsys):
    assert main(["search", PENDULUM, "--scale", "g=1", "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["feasible"]
    assert doc["scalings"][0]["unit_change"]["L"] == "1"
    out = tmp_path / "pendulum_g10.xml"
    assert main(["apply", PENDULUM, "--scale", "g=1", "--s", "10", "--output", str(out)]) == 0
    assert f"wrote {out}" in capsys.readouterr().out
    again = engines.load(out)
    assert again.parameter("g").value[0] == pytest.approx(98.1, rel=1e-15)
    assert main(["apply", PENDULUM, "--scale", "g=1", "--s", "10", "--output", PENDULUM]) == 2


def test_apply_loads_the_engine_file_once(tmp_path, capsys, monkeypatch):
    import pitheorem.engines.cli as engine_cli

    loaded = []
    real_load = engine_cli.load
    monkeypatch.setattr(engine_cli, "load", lambda path, **options: loaded.append(path) or real_load(path, **options))
    out = tmp_path / "pendulum_g2.xml"
    assert main(["apply", PENDULUM, "--scale", "g=1", "--s", "2", "--output", str(out)]) == 0
    assert loaded == [PENDULUM]
    assert f"wrote {out}" in capsys.readouterr().out


def test_apply_and_verify_choose_the_scene_a_urdf_scaling_needs_and_say_so_in_one_line(tmp_path, capsys):
    urdf = str(DATA / "slider_arm.urdf")
    # PyBullet's multibody damping mixes a rate and an inverse length, and its split-impulse threshold (a
    # length) cannot be set: the command line runs both runs without them, and says so once
    out = tmp_path / "a.urdf"
    assert main(["apply", urdf, "--scale", "g=1", "--s", "2", "--output", str(out)]) == 0
    err = capsys.readouterr().err.splitlines()
    notes = [line for line in err if line.startswith("pitheorem: note: scene")]
    assert notes == [
        "pitheorem: note: scene damping=0 split_impulse=false in both runs (the default refuses this scaling; "
        "--scene sets it)"
    ]
    written = json.loads(Path(f"{out}.settings.json").read_text())
    assert written["setPhysicsEngineParameter"]["useSplitImpulse"] == 0
    assert {call["linearDamping"] for call in written["changeDynamics"] if "linearDamping" in call} == {0.0}
    assert main(["verify", urdf, "--scale", "g=1", "--s", "2", "--duration", "0.2"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert [line for line in err if line.startswith("pitheorem: note: scene")] == notes
    # and which of the minimal scalings it used, and how to pick another
    assert "pitheorem: note: minimal scaling #1 of 3; --solution K picks another (pitheorem search lists them)" in err
    # a scaling of masses alone needs no other scene: nothing is said
    assert main(["apply", urdf, "--scale", "link_base_mass=1", "--s", "4"]) == 0
    assert "note: scene" not in capsys.readouterr().err
    # the user's own scene stands; where it refuses the scaling, one short line gives the flags
    for scene in (["damping=0.1"], ["split_impulse=true"]):
        assert main(["verify", urdf, "--scale", "g=1", "--s", "2", "--scene", *scene]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1, err
        assert len(err) < 200, err
        assert err.rstrip().endswith("give --scene damping=0 split_impulse=false"), err
    # the search itself is fine: the damping's two parts are two variables of the system
    assert main(["search", urdf, "--scale", "g=1", "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    powers = doc["scalings"][0]["exponents"]
    assert powers["link_cart_linearDamping_rate"] != powers["link_cart_linearDamping_per_length"]


def test_scene_options_make_a_urdf_scalable_and_reach_its_settings(tmp_path, capsys):
    urdf = str(DATA / "slider_arm.urdf")
    out = tmp_path / "a.urdf"
    scene = ["--scene", "damping=0", "split_impulse=false", "ground=true", "base_position=0,0,0.5", "g=9.8"]
    assert main(["apply", urdf, "--scale", "g=1", "--s", "2", "--output", str(out), *scene]) == 0
    settings = json.loads(Path(f"{out}.settings.json").read_text())
    assert settings["gravity"][2] == pytest.approx(-2 * 9.8, rel=1e-15)
    assert settings["setPhysicsEngineParameter"]["useSplitImpulse"] == 0
    assert settings["loadURDF"]["basePosition"] == [0, 0, 1.0]
    # the saved file reloads with its settings (gravity, base position, contact constants times 2) and runs
    # like the original, landing on the ground included
    model = engines.load(urdf, damping=0.0, split_impulse=False, ground=True, base_position=(0, 0, 0.5), g=9.8)
    again = engines.load(out)
    assert again.parameter("g").value[0] == pytest.approx(19.6, rel=1e-15)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    rep = engines.verify(model, sc, 2, duration=0.3, scaled=again)
    assert rep.passed
    # at rest but for gravity, the arm cannot show a mass error (its damping barely acts): not similar, inconclusive
    assert rep.verdict == "inconclusive"
    assert [(c.group, c.caught) for c in rep.controls] == [("g", True), ("masses", False)]
    capsys.readouterr()


@pytest.mark.parametrize(
    ("scene", "says"),
    [
        (["dampin=0"], "NAME one of"),
        (["ground=maybe"], "true or false"),
        (["base_position=0,1"], "three numbers"),
        (["damping=-1"], "cannot be negative"),
        (["g=1", "g=2"], "twice"),
        (["damping=x"], "damping"),
    ],
)
def test_bad_scene_options_exit_2_naming_them(capsys, scene, says):
    assert main(["params", str(DATA / "slider_arm.urdf"), "--scene", *scene]) == 2
    err = capsys.readouterr().err
    assert says in err
    assert "Traceback" not in err


def test_scene_options_have_one_list_that_the_loader_parser_and_help_use(capsys):
    import inspect

    import pitheorem as pt
    from pitheorem.engines.cli import parse_scene
    from pitheorem.engines.runners.pybullet import SCENE_OPTIONS, load_urdf

    names = tuple(SCENE_OPTIONS)
    assert names == ("fixed_base", "ground", "split_impulse", "g", "damping", "base_position")
    # the defaults load_urdf documents
    assert {name: default for name, (_kind, default) in SCENE_OPTIONS.items()} == {
        "fixed_base": False,
        "ground": False,
        "split_impulse": True,
        "g": 9.81,
        "damping": None,
        "base_position": (0.0, 0.0, 0.0),
    }
    # load_urdf's keyword options are exactly the scene (and the settings file)
    keywords = [p.name for p in inspect.signature(load_urdf).parameters.values() if p.kind is p.KEYWORD_ONLY]
    assert sorted(keywords) == sorted(("settings", *names))
    # the parser takes every name of the list, each by its kind, and lists them in its message
    typed = {"flag": "true", "number": "2", "point": "1,2,3"}
    parsed = parse_scene([f"{name}={typed[kind]}" for name, (kind, _default) in SCENE_OPTIONS.items()])
    assert parsed == {
        "fixed_base": True,
        "ground": True,
        "split_impulse": True,
        "g": 2.0,
        "damping": 2.0,
        "base_position": (1.0, 2.0, 3.0),
    }
    with pytest.raises(pt.InvalidRequestError) as caught:
        parse_scene(["gravity=1"])
    assert str(caught.value).endswith("NAME one of " + ", ".join(names))
    # a URDF loaded with no scene option runs with every default of the list
    settings = engines.load(DATA / "slider_arm.urdf").settings()
    assert settings["loadURDF"] == {
        "basePosition": list(SCENE_OPTIONS["base_position"][1]),
        "useFixedBase": SCENE_OPTIONS["fixed_base"][1],
    }
    assert settings["ground"] is None
    assert settings["setPhysicsEngineParameter"]["useSplitImpulse"] == int(SCENE_OPTIONS["split_impulse"][1])
    assert settings["gravity"] == [0.0, 0.0, -SCENE_OPTIONS["g"][1]]
    # the command line's help for --scene names every option
    assert main(["params", "--help"]) == 0
    help_text = " ".join(capsys.readouterr().out.split())
    scene_help = help_text[help_text.index("--scene") :]
    assert all(f"{name}=" in scene_help for name in names)


def test_scene_options_are_refused_for_other_files(capsys):
    assert main(["groups", "example:hinged_rod", "--scene", "ground=true"]) == 2
    assert "URDF" in capsys.readouterr().err
    assert main(["params", PENDULUM, "--scene", "ground=true"]) == 2
    assert "URDF" in capsys.readouterr().err


BAD_FILES = [
    ("absent.xml", None, "no such file"),
    ("junk.xml", "this is not XML", "junk.xml"),
    ("unknown_element.xml", (DATA / "unknown_element.xml").read_text(), "gizmo"),
    ("missing_mesh.xml", (DATA / "missing_mesh.xml").read_text(), "mesh 'hull'"),
    (
        "bad.urdf",
        '<robot name="r"><link name="a"><collision><geometry><mesh filename="gone.stl"/></geometry>'
        "</collision></link></robot>",
        "mesh 'gone.stl'",
    ),
    ("junk.urdf", "<robot", "not well-formed XML"),
]


def write_bad(tmp_path, name, text):
    path = tmp_path / name
    if text is not None:
        path.write_text(text)
    return path


@pytest.mark.parametrize(("name", "text", "element"), BAD_FILES)
def test_bad_model_files_exit_2_with_one_line(tmp_path, capsys, name, text, element):
    path = write_bad(tmp_path, name, text)
    for command in (["params", str(path)], ["search", str(path), "--scale", "g=1"]):
        assert main(command) == 2
        lines = capsys.readouterr().err.strip().splitlines()
        assert len(lines) == 1
        assert lines[0].startswith("pitheorem: error: ")
        assert name in lines[0]
        assert element in lines[0]


@pytest.mark.parametrize(("name", "text", "element"), [BAD_FILES[3], BAD_FILES[4]])
@pytest.mark.parametrize("fmt", ["json", "latex"])
def test_bad_model_files_exit_2_in_every_format(tmp_path, capsys, name, text, element, fmt):
    # once a subprocess of the console script, which tests/test_cli.py::test_console_script proves
    path = write_bad(tmp_path, name, text)
    assert main(["params", str(path), "--format", fmt]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1, lines
    assert name in lines[0]
    assert element in lines[0]


def test_verify_exits_0_when_similar_1_when_not_and_2_on_bad_input(capsys, tmp_path):
    from pitheorem.cli import main

    pendulum = str(engines.example_path("pendulum.xml"))
    assert main(["verify", pendulum, "--scale", "g=1", "--s", "4", "--duration", "0.5"]) == 0
    assert capsys.readouterr().out.startswith("exact: the scaled copy, mapped back, equals the original bit for bit")
    assert main(["verify", pendulum, "--scale", "g=1", "--s", "10", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["similar"] is True
    assert data["exact"] is False
    assert data["causes"] == []
    # the contact test model with MuJoCo's default stopping rule and the PGS solver: not exact at s = 4
    pgs = tmp_path / "pgs.xml"
    pgs.write_text(
        (Path(__file__).parent / "data" / "engines" / "contact.xml")
        .read_text()
        .replace('<option timestep="0.002" tolerance="0"/>', '<option timestep="0.002" solver="PGS"/>')
    )
    code = main(["verify", str(pgs), "--scale", "g=1", "--s", "4"])
    out = capsys.readouterr().out
    assert code == 1, out
    assert out.startswith("NOT similar")
    # the stopping rule at 0 alone restores the run bit for bit (contacts off would too); the scale-free
    # solver alone only brings the runs closer: said beside it
    assert "causes:\n  solver: option tolerance = 1e-08" in out
    assert "with it at 0 in both runs they are equal bit for bit" in out
    assert re.search(r"removing .*option solver = PGS.* alone brings the runs closer", out)
    assert main(["verify", pendulum, "--scale", "g=1", "--s", "-1"]) == 2
    assert "--s" in capsys.readouterr().err
    assert main(["verify", str(pgs), "--scale", "g=1", "--s", "4", "--format", "latex"]) == 1
    latex = capsys.readouterr().out  # every format, as every other command prints
    assert latex.startswith("% ")
    assert "\\begin{itemize}" in latex
    assert "\\textbf{solver}" in latex
    assert main(["verify", "example:hinged_rod", "--scale", "g=1", "--s", "4"]) == 2


# -- every command on every shipped example and every gymnasium MuJoCo model ----------------------


def _gymnasium_models() -> list[Path]:
    try:
        import gymnasium
    except ImportError:  # an install without the test extra: the shipped examples still run
        return []
    return sorted((Path(gymnasium.__file__).parent / "envs" / "mujoco" / "assets").glob("*.xml"))


#: each command with the least a request needs
VERBS = (["params"], ["groups"], ["bases"], ["search", "--scale", "g=1"], ["apply", "--scale", "g=1", "--s", "2"])
MODELS = [f"example:{name}" for name in examples()] + [str(p) for p in _gymnasium_models()]


@pytest.mark.parametrize("model", MODELS, ids=[Path(m).name for m in MODELS])
def test_every_command_succeeds_on_every_shipped_and_gymnasium_model(capsys, model):
    for verb, *request in VERBS:
        with warnings.catch_warnings():
            warnings.simplefilter("always")  # e.g. ant.xml's custom numeric data: shown, not raised
            code = main([verb, model, *request])
        out, err = capsys.readouterr()
        assert code == 0, (verb, err)
        assert "Traceback" not in err
        assert all(line.startswith(("pitheorem: warning: ", "pitheorem: note: ")) for line in err.splitlines())
        assert len(set(err.splitlines())) == len(err.splitlines()), err  # every warning once
        assert str(EXAMPLES) not in out + err  # a shipped file by the name the user gave, example:NAME
        # a summary first: the first lines name the model and fit on a screen whatever its size
        assert all(len(line) < 400 for line in out.splitlines()[:3]), (verb, out[:800])
    assert len(MODELS) >= 4 + (14 if _gymnasium_models() else 0)


def test_groups_avoids_zero_repeaters_and_says_which(capsys):
    # pendulum.xml's default set would hold density = 0, so every group it divides would be undefined
    model = engines.load(PENDULUM)
    zero = [p.name for p in model.parameters if len(p.value) == 1 and p.value[0] == 0]
    assert "density" in zero
    assert main(["groups", PENDULUM, "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert not set(doc["repeating"]) & set(zero)
    assert "t" not in doc["repeating"]
    assert "timestep" not in doc["repeating"]
    # every group has a value now, each the product of the file's values to its exponents
    values = {p.name: p.value[0] for p in model.parameters if len(p.value) == 1}
    for group in doc["groups"]:
        if all(n in values for n in group["exponents"]):
            expected = 1.0
            for n, p in group["exponents"].items():
                expected *= values[n] ** p
            assert group["value"] == pytest.approx(expected, rel=1e-12)
    assert main(["groups", PENDULUM]) == 0
    text = capsys.readouterr().out.splitlines()
    assert text[2].startswith("(the first valid set without the engine's settings, time variables")
    assert "density" in text[2]


@pytest.mark.parametrize(
    "model",
    [f"example:{n}" for n in examples() if n.endswith((".xml", ".urdf"))]
    + sorted(str(p) for p in (Path(__file__).parent / "robots").glob("*/*.[xu][mr][ld]*")),
    ids=lambda m: Path(m).name,
)
def test_default_repeaters_are_never_a_solver_setting(capsys, model):
    engine_model = engines.load(engines.example_path(model[8:]) if model.startswith("example:") else model)
    settings = {p.name for p in engine_model.parameters if p.name not in ("g", "wind", "density", "viscosity")}
    settings = {n for n in settings if engine_model.parameter(n).path.startswith(("option ", "set"))}
    assert main(["groups", model, "--format", "json"]) == 0
    answer = json.loads(capsys.readouterr().out)
    repeating = answer["repeating"]
    assert repeating == list(engine_model.default_repeating())
    # Python agrees with the command line: the model's system carries these repeaters as its default
    groups = engine_model.system().pi_groups()
    assert list(groups.repeating) == repeating
    assert [dict(g.exponents) for g in groups] == [g["exponents"] for g in answer["groups"]]
    assert not set(repeating) & (settings | {"ccd_tolerance", "tolerance", "noslip_tolerance", "o_margin"})
    # each repeater is one nonzero number of the file or of gravity: every group gets a value
    assert all(len(engine_model.parameter(n).value) == 1 and engine_model.parameter(n).value[0] != 0 for n in repeating)


def test_groups_with_a_zero_repeater_given_shows_the_undefined_group_in_its_row(capsys):
    assert main(["groups", PENDULUM, "--repeating", "g", "density", "ccd_tolerance"]) == 0
    rows = {line.split()[0]: line for line in capsys.readouterr().out.splitlines()[3:]}
    assert rows["Pi_geom_rod_density"].endswith("undefined (density = 0)")


def test_shipped_engine_models_are_named_like_the_others(capsys):
    assert main(["params", "example:pendulum.xml"]) == 0
    assert capsys.readouterr().out.startswith("example:pendulum.xml: mujoco model, ")
    assert main(["groups", "example:pendulum"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert "hinged_rod, hinged_rod.urdf, hinged_rod.xml, pendulum.xml, superball, superball.xml" in err
    assert main(["--help"]) == 0
    help_text = capsys.readouterr().out
    assert "TOML model file." not in help_text
    assert (
        "example:NAME, NAME one of hinged_rod, hinged_rod.urdf, hinged_rod.xml, pendulum.xml, superball, superball.xml"
    ) in " ".join(help_text.split())


def test_shipped_files_are_shown_by_their_example_name_never_their_installed_path(capsys):
    # an error, a JSON document and a check's text: each names example:NAME, as the user wrote it
    assert main(["convert", "example:hinged_rod.urdf", "--units", "L=mm"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("pitheorem: error: example:hinged_rod.urdf: units:")
    assert main(["check", "example:pendulum.xml", "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["file"] == "example:pendulum.xml"
    assert main(["params", PENDULUM]) == 0  # the installed path typed out: the same file, the same name
    out = capsys.readouterr().out
    assert out.startswith("example:pendulum.xml: mujoco model, ")
    assert str(EXAMPLES) not in out


def test_bases_of_a_large_model_lists_the_first_sets_after_their_count(capsys):
    assert main(["bases", "example:superball.xml"]) == 0
    lines = capsys.readouterr().out.splitlines()
    count = int(lines[0].split(": ")[1].split()[0])
    assert count > 10**6
    assert lines[1].startswith(f"the first {BASES_SHOWN} (--all lists every one")
    assert len(lines) == 2 + BASES_SHOWN
    assert main(["bases", "example:superball.xml", "--count", "--all"]) == 2
    capsys.readouterr()


def test_search_on_a_large_model_opens_with_a_short_summary(capsys):
    assert main(["search", "example:superball.xml", "--scale", "g=1"]) == 0
    lines = capsys.readouterr().out.splitlines()
    model = engines.load(engines.example_path("superball.xml"))
    times = model.system().time_variables
    assert len(times) > 10
    # the long list of time variables held fixed is shortened with a count, in the first line and the note
    assert lines[0].startswith(
        f"Scaling g by s with {times[0]} and {len(times) - 1} more ({len(times)} in all) fixed: "
    )
    assert len(lines[0]) < 120
    n = int(lines[0].split(" fixed: ")[1].split()[0])
    start = lines.index(f"summary (the table below has a row for each of the {len(model.system())} variables):")
    assert [line.split(":")[0].strip() for line in lines[start + 1 : start + n + 1]] == [
        f"#{k}" for k in range(1, n + 1)
    ]


def test_apply_names_a_parameter_no_scene_option_can_fix(capsys):
    # a free joint's damping acts on lengths and on angles: no --scene option helps, so no hint is given
    code = main(["apply", str(DATA / "free_damped.xml"), "--scale", "g=1", "--s", "2"])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith("pitheorem: error: cannot scale ")
    assert err.count("\n") == 1
    assert "--scene" not in err


def test_search_says_which_scalings_a_mixed_number_refuses_and_apply_agrees(tmp_path, capsys):
    # the puck's free-joint damping and friction loss act on lengths and on angles: a scaling that moves L
    # cannot carry them (each solution counted once, the first number named)
    path = tmp_path / "puck.xml"
    path.write_text((DATA / "free_damped.xml").read_text().replace('damping="0.1"', 'damping="0.1" frictionloss="0.2"'))
    path = str(path)
    assert main(["search", path, "--scale", "g=1", "--fixed", "--format", "json"]) == 0
    out, err = capsys.readouterr()
    solutions = json.loads(out)["scalings"]
    moves_length = [k for k, sc in enumerate(solutions, 1) if sc["unit_change"].get("L", "0") != "0"]
    assert 0 < len(moves_length) < len(solutions)  # some solutions keep the length unit, some do not
    note = err.strip()
    assert note.startswith("pitheorem: note: apply refuses #")
    assert f"({len(moves_length)} of {len(solutions)})" in note
    assert "joint 'root' damping" in note
    assert err.count("\n") == 1
    # here the solutions that move L are the last ones, one run of numbers: written as a range
    assert moves_length == list(range(moves_length[0], len(solutions) + 1))
    assert f"apply refuses #{moves_length[0]} to #{len(solutions)} ({len(moves_length)} of " in note
    # and apply refuses exactly those: the first refused, the first kept
    for k, code in ((moves_length[0], 2), (next(k for k in range(1, 99) if k not in moves_length), 0)):
        args = ["apply", path, "--scale", "g=1", "--fixed", "--s", "2", "--solution", str(k)]
        assert main(args) == code
        capsys.readouterr()
    # with time fixed every solution moves L: one word for all
    assert main(["search", path, "--scale", "g=1"]) == 0
    assert "apply refuses every scaling listed: " in capsys.readouterr().err
    # a model with no mixed number gets no note
    assert main(["search", PENDULUM, "--scale", "g=1"]) == 0
    assert capsys.readouterr().err == ""


def test_apply_without_output_reports_the_changes_and_writes_nothing(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["apply", PENDULUM, "--scale", "g=1", "--s", "2"]) == 0
    out = capsys.readouterr().out
    assert "wrote" not in out
    assert list(tmp_path.iterdir()) == []


def test_verify_says_when_a_run_moved_nothing(capsys):
    from pitheorem.cli import main

    hanging = str(Path(__file__).parent / "data" / "engines" / "hanging.xml")
    assert main(["verify", hanging, "--scale", "g=1", "--s", "10", "--input", "zero"]) == 1  # inconclusive
    out = capsys.readouterr().out
    assert "this verdict proves nothing" in out
    assert out.startswith("inconclusive: the copy matches bit for bit (s = 10, ")
    assert len(out.splitlines()[0]) < 120
    assert "a gravity error cannot be seen" in out


def test_convert_writes_the_same_model_in_other_units_and_check_reads_it(tmp_path, capsys):
    out = tmp_path / "um.xml"
    assert main(["convert", PENDULUM, "--units", "L=um", "M=ug", "--output", str(out)]) == 0
    text = capsys.readouterr().out
    assert "M=kg L=m T=s -> M=ug L=um T=s" in text
    assert f"wrote {out}" in text
    model = engines.load(out)
    assert model.units == {"M": "ug", "L": "um", "T": "s"}
    assert model.parameter("g").value == (9810000.0,)
    assert main(["check", str(out)]) == 1
    text = capsys.readouterr().out
    assert "mujoco_maxval" in text
    assert "--fit mujoco" in text
    fitted = tmp_path / "fit.xml"
    assert main(["convert", str(out), "--fit", "mujoco", "--output", str(fitted), "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["feasible"] is True
    assert doc["thresholds"] == []
    assert doc["written"] == str(fitted)
    assert main(["check", str(fitted), "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["causes"] == []


def test_convert_fit_that_changes_nothing_says_so_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "same.xml"
    assert main(["convert", PENDULUM, "--fit", "mujoco", "--output", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines == ["pendulum.xml: its units (M=kg L=m T=s) are those --fit mujoco chooses; nothing to convert"]
    assert not out.exists()


def test_check_exits_0_on_a_clean_model_and_reads_the_units_given(capsys):
    assert main(["check", "example:pendulum.xml"]) == 0
    assert "clear of every catalogued threshold of mujoco" in capsys.readouterr().out
    # declared in micrometres and micrograms, the same numbers are fine: the units only label them
    assert main(["check", PENDULUM, "--from", "L=um", "M=ug"]) == 0
    capsys.readouterr()


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["convert", PENDULUM], "--units BASE=UNIT ... or --fit ENGINE"),
        (["convert", PENDULUM, "--units", "L=mm", "--fit", "mujoco"], "one of the two"),
        (["convert", PENDULUM, "--units", "L=furlongz"], "'furlongz' is no unit of length"),
        (["convert", PENDULUM, "--units", "X=mm"], "BASE one of M, L, T"),
        (["convert", PENDULUM, "--units", "L=mm", "L=cm"], "sets L twice"),
        (["convert", PENDULUM, "--units", "L=mm", "--output", PENDULUM], "is the input file"),
        (["convert", "example:hinged_rod", "--units", "L=mm"], "reads MJCF (.xml) or URDF"),
        (["check", PENDULUM, "--engine", "ode"], "ode"),
        (["check", PENDULUM, "--format", "latex"], "invalid choice"),
    ],
)
def test_bad_convert_and_check_requests_exit_2_with_one_line(argv, says, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert err[0].startswith("pitheorem: error:")
    assert says in err[0]


def test_verify_runs_a_file_in_the_engine_named(capsys):
    assert main(["verify", PENDULUM, "--scale", "g=1", "--s", "4", "--engine", "ode"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert "unknown engine 'ode'" in err[0]


# -- issue 32's rules on a sample of the corpus (tests/robots/cli_corpus.py runs them on the whole) -----


def _corpus_rules():
    import importlib.util

    spec = importlib.util.spec_from_file_location("cli_corpus", Path(__file__).parent / "robots" / "cli_corpus.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


#: the four pybullet_data robots a newcomer tried first (issue 32), and four that PyBullet loads and pitheorem
#: once refused: numbers that are not plain (bike, biped), spherical joints (humanoid), an unexpanded xacro (husky)
URDF_SAMPLE = (
    "r2d2.urdf",
    "cartpole.urdf",
    "kuka_iiwa/model.urdf",
    "teddy_vhacd.urdf",
    "bicycle/bike.urdf",
    "biped/biped2d_pybullet.urdf",
    "humanoid/humanoid.urdf",
    "husky/husky.urdf",
)


@pytest.mark.parametrize("name", URDF_SAMPLE)
def test_every_command_keeps_the_rules_on_pybullet_datas_robots_with_the_defaults(name):
    pybullet_data = pytest.importorskip("pybullet_data", reason="pybullet_data is not installed")
    rules = _corpus_rules()
    path = str(Path(pybullet_data.getDataPath()) / name)
    assert rules.pybullet_loads(Path(path))
    ran = {}  # each command's exit code and output, as the rules saw them (each command runs once)
    run = rules.run
    rules.run = lambda argv: ran.setdefault(tuple(argv), run(argv))
    for argv in rules.commands(path):
        assert rules.problems(argv) == [], argv
    # apply and verify at s = 4 with the defaults: exit 0, and verify finds the copy exact
    code, out, _err = ran["verify", path, "--scale", "g=1", "--s", "4", "--duration", "0.2"]
    assert code == 0
    assert out.startswith("exact: ")


def test_the_corpus_rules_catch_what_they_name(tmp_path, monkeypatch):
    # a long first line, a repeated line and an undocumented exit code are each found
    rules = _corpus_rules()
    monkeypatch.setattr(rules, "run", lambda argv: (2, "x" * 130 + "\nsame\nsame\n", ""))
    found = rules.problems(["params", "model.xml"])
    assert [text.split(" ")[0] for text in found] == ["exit", "first", "stdout"]


def test_check_on_dm_controls_dog_prints_at_most_ten_lines(capsys):
    dm_control = pytest.importorskip("dm_control", reason="dm-control is not installed (it ships the dog)")
    dog = Path(dm_control.__file__).parent / "suite" / "dog.xml"
    assert main(["check", str(dog)]) in (0, 1)
    lines = capsys.readouterr().out.splitlines()
    assert 1 <= len(lines) <= 10
    assert len(lines[0]) < 120


def test_apply_and_convert_keep_the_inputs_and_copy_the_assets_on_request(tmp_path, capsys):
    import shutil

    model = engines.load(DATA / "actuated.xml")
    low, high = model.inputs()[1:]
    for verb, request in (("apply", ["--scale", "g=1", "--s", "4"]), ("convert", ["--units", "L=mm", "M=g"])):
        out = tmp_path / f"{verb}.xml"
        assert main([verb, str(DATA / "actuated.xml"), *request, "--keep-inputs", "--output", str(out)]) == 0
        kept = engines.load(out)
        assert np.array_equal(kept.inputs()[1], low)
        assert np.array_equal(kept.inputs()[2], high)
        default = tmp_path / f"{verb}_default.xml"
        assert main([verb, str(DATA / "actuated.xml"), *request, "--output", str(default)]) == 0
        assert not np.array_equal(engines.load(default).inputs()[2], high)  # without the flag, as before
    capsys.readouterr()
    # assets: copied beside the output, which then travels alone
    shutil.copytree(Path(__file__).parent / "robots" / "mjcf", tmp_path / "robots")
    out = tmp_path / "out" / "arm4.xml"
    out.parent.mkdir()
    request = ["--scale", "g=1", "--s", "4", "--copy-assets", "--output", str(out)]
    assert main(["apply", str(tmp_path / "robots" / "arm.xml"), *request]) == 0
    shutil.rmtree(tmp_path / "robots")
    shutil.move(tmp_path / "out", tmp_path / "moved")
    assert engines.load(tmp_path / "moved" / "arm4.xml").runner.mjmodel.nmesh > 0


def test_keep_inputs_and_copy_assets_are_refused_by_name_where_they_mean_nothing(capsys):
    for flag in ("--keep-inputs", "--copy-assets"):
        assert main(["apply", "example:hinged_rod", "--scale", "g=1", "--s", "4", flag]) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"pitheorem: error: {flag} is for MJCF and URDF model files")
        assert err.count("\n") == 1
    pytest.importorskip("pybullet")
    assert main(["apply", "example:hinged_rod.urdf", "--scale", "g=1", "--s", "4", "--keep-inputs"]) == 2
    err = capsys.readouterr().err
    assert "cannot keep its inputs: its inputs are joint forces" in err
    assert err.count("\n") == 1
    assert len(err.splitlines()[0]) < 120


SHIPPED_ENGINE_FILES = [f"example:{n}" for n in examples() if n.endswith((".xml", ".urdf"))]


@pytest.mark.parametrize("model", SHIPPED_ENGINE_FILES, ids=lambda m: m[8:])
def test_every_commands_first_line_fits_120_characters_on_the_shipped_examples(capsys, model, tmp_path):
    commands = [
        ["params"],
        ["groups"],
        ["bases"],
        ["search", "--scale", "g=1"],
        ["apply", "--scale", "g=1", "--s", "4"],
        ["verify", "--scale", "g=1", "--s", "4", "--duration", "0.05"],
        ["check"],
        ["convert", "--units", "L=mm"],
    ]
    for verb, *request in commands:
        main([verb, model, *request])
        out, err = capsys.readouterr()
        first = (out or err).splitlines()[0]
        assert len(first) < 120, (verb, first)


def test_verify_shows_its_stages_on_stderr_when_asked(capsys, monkeypatch):
    from pitheorem import progress
    from pitheorem.engines.cli import verify_engine

    monkeypatch.setattr(progress, "DELAY", 0.0)  # the bar shows at once (else only after half a second)

    model = engines.load(engines.example_path("pendulum.xml"))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    verify_engine(model, sc, 4, 0.1, progress=True)
    assert "verify" in capsys.readouterr().err  # tqdm's bar, named
    verify_engine(model, sc, 4, 0.1)
    assert capsys.readouterr().err == ""


def test_sweep_on_a_urdf_chooses_the_scene_as_verify_does_and_says_each_cause_once(capsys):
    pybullet_data = pytest.importorskip("pybullet_data", reason="pybullet_data is not installed")
    # a compound mesh that lands on the ground: its margins are a cause at every s, shown by a run with contacts off
    base = str(Path(pybullet_data.getDataPath()) / "duck_vhacd.urdf")
    request = ["--scale", "g=1", "--s", "0.25", "4", "--duration", "0.5"]
    scene = ["ground=true", "base_position=0,0,0.2"]
    with warnings.catch_warnings():
        warnings.simplefilter("always")  # its compound mesh is warned about, once, on stderr
        code = main(["sweep", base, *request, "--scene", *scene])
        out, err = capsys.readouterr()
        assert main(["sweep", base, *request, "--scene", *scene, "damping=0.1"]) == 2
    # not similar, by its margins (exit 1); the default scene refused the scaling (exit 2) before the scene was chosen
    assert code == 1
    assert "pitheorem: note: scene damping=0 split_impulse=false in every run of duck_vhacd.urdf" in err
    lines = out.splitlines()
    assert len(lines) == len(set(lines))
    # a cause found at both factors: said once, with both
    assert next(line for line in lines if line.startswith("  setting: ")).endswith("(s = 1/4, 4)")
    # the user's own scene is kept, and a scene that still refuses gives the flags in one short line
    err = capsys.readouterr().err
    assert err.count("pitheorem: error: ") == 1
    assert "give --scene damping=0 split_impulse=false" in err
    assert len(err.splitlines()[-1]) - len("duck_vhacd.urdf") < 150


def test_convert_fit_on_a_urdf_says_in_a_short_first_line_that_no_units_fit(capsys):
    pybullet_data = pytest.importorskip("pybullet_data", reason="pybullet_data is not installed")
    finger = Path(pybullet_data.getDataPath()) / "gripper" / "wsg50_one_motor_gripper_right_finger.urdf"
    assert main(["convert", str(finger), "--fit", "pybullet"]) == 1
    first, second = capsys.readouterr().out.splitlines()
    assert first == f"{finger.name}: no units keep every number clear of pybullet's thresholds"
    assert second.startswith("its format holds only M=kg L=m T=s; ")


@pytest.mark.parametrize(
    ("command", "request_", "code"),
    # sweep takes a list of files, and exits 0 where every copy is inconclusive; verify exits 1 then
    [("verify", ["--s", "4"], 1), ("sweep", ["--s", "0.25", "4"], 0)],
)
def test_mujocos_warnings_are_one_line_each_after_the_command_and_leave_no_log_file(
    tmp_path, monkeypatch, capfd, command, request_, code
):
    import mujoco

    # a spring so stiff for its time step that MuJoCo gives up on the run (a NaN acceleration) a few steps in;
    # a verdict runs it many times (twins, controls, the copy), and MuJoCo warns in each
    path = tmp_path / "unstable.xml"
    path.write_text(
        '<mujoco><option timestep="0.01"/><worldbody><body name="arm" pos="0 0 1">'
        '<joint name="hinge" axis="0 1 0" stiffness="400" springref="0.5"/>'
        '<geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02" mass="0.1"/></body></worldbody>'
        '<actuator><motor joint="hinge"/></actuator></mujoco>'
    )
    monkeypatch.chdir(tmp_path)
    before = mujoco.get_mju_user_warning()
    assert main([command, str(path), "--scale", "g=1", *request_, "--duration", "0.4"]) == code
    out, err = capfd.readouterr()  # file descriptors 1 and 2: MuJoCo's own console lines would land here
    assert "inconclusive" in out
    told = [line for line in err.splitlines() if "mujoco" in line]
    assert len(told) == 1, err
    times = re.fullmatch(
        r"pitheorem: warning: mujoco: Nan, Inf or huge value in QACC .*\((\d+) times in the runs\)", told[0]
    )
    assert times is not None, told
    assert int(times.group(1)) > 1
    assert "WARNING" not in out + err  # MuJoCo's own console form
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()
    assert mujoco.get_mju_user_warning() is before  # the handler is the caller's again
