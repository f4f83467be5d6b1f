"""Tests for the pitheorem command line (pitheorem.cli, python -m pitheorem, the console script).

Every case calls :func:`pitheorem.cli.main` in-process (fast) and reads what it
printed with ``capsys``, except two that run the real programs in a subprocess:
``python -m pitheorem`` and the installed ``pitheorem`` console script.
"""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
import tomllib
from fractions import Fraction
from pathlib import Path

import pytest

import pitheorem as pt
from pitheorem.cli import EXIT_ERROR, EXIT_INFEASIBLE, EXIT_OK, main
from pitheorem.modelfile import (
    example_path,
    load_model_file,
)
from tests.conftest import BROKEN_MODEL_FILES, broken_model_file, loaded_after

ROD = str(example_path("hinged_rod"))


SUPERBALL = str(example_path("superball"))


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, *argv):
    code, out, err = run(capsys, *argv, "--format", "json")
    assert err == ""
    return code, json.loads(out)


def subprocess_run(*argv, program=None):
    cmd = [*(program or [sys.executable, "-m", "pitheorem"]), *map(str, argv)]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=60, check=False)


def _console_script() -> str | None:
    # pip puts the script beside the interpreter of the environment it installs into; the
    # environment's bin folder need not be on PATH (make test runs .venv/bin/python directly)
    beside = Path(sys.executable).with_name("pitheorem")
    return str(beside) if beside.exists() else shutil.which("pitheorem")


def test_groups_default_repeaters(capsys):
    code, out, _ = run(capsys, "groups", ROD)
    assert code == EXIT_OK
    assert "rank 3, 6 dimensionless groups" in out
    assert f"repeating variables: {', '.join(load_model_file(ROD).system.default_repeating())}" in out


def test_groups_json_matches_the_library(capsys):
    code, doc = run_json(capsys, "groups", ROD, "--repeating", "m", "l", "k_theta")
    assert code == EXIT_OK
    expected = pt.models.rod_system().pi_groups(repeating=("m", "l", "k_theta"))
    assert [g["exponents"] for g in doc["groups"]] == [g.exponents for g in expected]
    assert doc["repeating"] == ["m", "l", "k_theta"]
    by_name = {g["name"]: g for g in doc["groups"]}
    assert by_name["Pi_g"]["expression"] == "g*l*m/k_theta"
    assert by_name["Pi_g"]["value"] == pytest.approx(1.5 * 2 * 9.81 / 100)
    assert by_name["Pi_t"]["value"] is None  # t has no value in the file


def test_groups_latex(capsys):
    code, out, _ = run(capsys, "groups", ROD, "--repeating", "m", "l", "k_theta", "--format", "latex")
    assert code == EXIT_OK
    assert r"\frac" in out
    assert r"\Pi_{g} &= \frac{g l m}{k_{\theta}}" in out
    assert out.startswith(r"\begin{align*}")


def test_bases_count_and_list(capsys):
    system = pt.models.rod_system()
    code, out, _ = run(capsys, "bases", ROD, "--count")
    assert (code, out.strip()) == (EXIT_OK, str(system.count_bases()))
    code, doc = run_json(capsys, "bases", ROD, "--exclude", "t", "--require", "m")
    assert doc["count"] == len(doc["bases"]) == system.count_bases(exclude=("t",), require=("m",))
    assert [tuple(b) for b in doc["bases"]] == system.bases(exclude=("t",), require=("m",))
    code, out, _ = run(capsys, "bases", ROD, "--exclude", "t")
    assert out.splitlines()[0] == "hinged rod: 27 valid repeating sets of 3 variables (without t)"
    assert len(out.splitlines()) == 28
    code, out, _ = run(capsys, "bases", ROD, "--format", "latex")
    assert r"\begin{tabular}" in out
    assert r"k_{\theta}" in out


def test_search_gravity_has_three_minimal_solutions(capsys):
    code, out, _ = run(capsys, "search", ROD, "--scale", "g=1")
    assert code == EXIT_OK
    assert "3 minimal solutions" in out
    assert "give --fixed with no names to let time change" in out
    code, doc = run_json(capsys, "search", ROD, "--scale", "g=1")
    assert doc["feasible"] is True
    assert doc["count"] == 3
    assert doc["fixed"] == ["t"]
    assert doc["scalings"][0]["exponents"]["m"] == "-2"
    assert doc["scalings"][0]["unit_change"] == {"M": "-2", "L": "1", "T": "0"}
    assert all(sc["exponents"]["t"] == "0" for sc in doc["scalings"])


def test_search_certificate(capsys):
    argv = ("search", ROD, "--scale", "g=1", "--fixed", "t", "m", "k_theta")
    code, out, _ = run(capsys, *argv)
    assert code == EXIT_INFEASIBLE
    assert "certificate: Pi = g**2*m*t**2/k_theta" in out
    code, doc = run_json(capsys, *argv)
    assert code == EXIT_INFEASIBLE
    assert doc["feasible"] is False
    assert doc["scalings"] == []
    assert doc["certificate"]["expression"] == "g**2*m*t**2/k_theta"
    assert doc["certificate"]["power"] == "2"
    code, out, _ = run(capsys, *argv, "--format", "latex")
    assert r"\frac{g^{2} m t^{2}}{k_{\theta}}" in out


def test_search_superball_density(capsys):
    code, doc = run_json(capsys, "search", SUPERBALL, "--scale", "l=1", "--fixed", "t", "m")
    assert code == EXIT_OK
    assert doc["count"] == 1
    exps = doc["scalings"][0]["exponents"]
    assert exps["rho"] == "-3"
    assert exps["G"] == "-1"
    assert exps["k"] == "0"


def test_search_fixed_without_names_lets_time_change(capsys):
    _, held = run_json(capsys, "search", ROD, "--scale", "g=1")
    for extra in (["--fixed"], ["--no-default-fixed"]):
        code, doc = run_json(capsys, "search", ROD, "--scale", "g=1", *extra)
        assert code == EXIT_OK
        assert doc["fixed"] == []
        assert doc["notes"] == []
        assert doc["count"] > held["count"]
        assert any(sc["exponents"]["t"] != "0" for sc in doc["scalings"])


def test_search_notes_round_trip_through_text_and_json(capsys):
    result = pt.search(load_model_file(ROD).system, scale={"g": 1})
    assert [n.kind for n in result.notes] == ["time_fixed"]
    code, doc = run_json(capsys, "search", ROD, "--scale", "g=1")
    assert code == EXIT_OK
    # JSON: the data of each note rebuilds it, and its text is the command line's phrasing
    assert tuple(pt.SearchNote(n["kind"], n["variables"]) for n in doc["notes"]) == result.notes
    texts = [n["text"] for n in doc["notes"]]
    assert texts == ["Time variable t is held fixed by default; give --fixed with no names to let time change"]
    # text: the same sentences, in the note's place under the explanation
    for argv in (["search", ROD, "--scale", "g=1"], ["apply", ROD, "--scale", "g=1", "--s", "2"]):
        code, out, _ = run(capsys, *argv)
        assert code == EXIT_OK
        lines = out.splitlines()
        assert texts[0] in lines
        assert "fixed=()" not in out  # the Python phrasing never reaches the command line
    code, doc = run_json(capsys, "apply", ROD, "--scale", "g=1", "--s", "2")
    assert [n["text"] for n in doc["notes"]] == texts


def test_search_exact_exponents_and_allow(capsys):
    code, doc = run_json(capsys, "search", ROD, "--scale", "g=1/2", "l=-1", "--fixed")
    assert code == EXIT_OK
    assert doc["scale"] == {"g": "1/2", "l": "-1"}
    code, doc = run_json(capsys, "search", ROD, "--scale", "g=1", "--allow", "l", "m", "F")
    assert code == EXIT_OK
    assert doc["count"] == 1
    assert doc["scalings"][0]["changed"] == ["m", "l", "g", "F"]
    code, doc = run_json(capsys, "search", ROD, "--scale", "g=1", "--allow", "l")
    assert code == EXIT_INFEASIBLE
    assert doc["certificate"] is not None


def test_search_latex_table(capsys):
    code, out, _ = run(capsys, "search", ROD, "--scale", "g=1", "--format", "latex")
    assert code == EXIT_OK
    assert r"$m$ & free & $s^{-2}$ & $s^{-1}$ & - \\" in out
    # the change of base units behind each scaling, as in the text table
    assert r"$[\mathrm{M}]$ & base unit & $s^{-2}$ & $s^{-1}$ & - \\" in out
    assert r"$[\mathrm{L}]$ & base unit & $s$ & $s$ & $s$ \\" in out
    assert r"$[\mathrm{T}]$ & base unit & - & - & - \\" in out


def test_search_text_table_shows_the_base_unit_change(capsys):
    code, out, _ = run(capsys, "search", ROD, "--scale", "g=1")
    assert code == EXIT_OK
    rows = {line.split()[0]: line.split()[1:] for line in out.splitlines() if line.startswith("[")}
    assert rows == {
        "[M]": ["base", "1/s^2", "1/s", "-"],
        "[L]": ["base", "s", "s", "s"],
        "[T]": ["base", "-", "-", "-"],
    }


def test_json_is_deterministic(capsys):
    first = run(capsys, "search", SUPERBALL, "--scale", "g=1", "--format", "json")
    assert run(capsys, "search", SUPERBALL, "--scale", "g=1", "--format", "json") == first


def _groups_with_values(model):
    """Every Pi group, over all bases without time, whose variables all have values."""
    seen = {}
    for basis in model.system.bases():
        for g in model.system.pi_groups(repeating=basis):
            if all(n in model.values for n in g.exponents):
                seen[tuple(g.exponents.items())] = g
    return list(seen.values())


@pytest.mark.parametrize(("solution", "s"), [(1, "2"), (2, "1/3"), (3, "0.5")])
def test_apply_keeps_every_group(capsys, tmp_path, solution, s):
    out = tmp_path / "scaled.toml"
    code, text, _ = run(capsys, "apply", ROD, "--scale", "g=1", "--s", s, "--solution", solution, "--output", out)
    assert code == EXIT_OK
    assert f"minimal scaling #{solution} of 3" in text
    assert f"wrote {out}" in text
    before, after = load_model_file(ROD), load_model_file(out)
    assert after.values["g"] == pytest.approx(9.81 * float(Fraction(s)))
    groups = _groups_with_values(before)
    assert len(groups) >= 3
    for g in groups:
        assert g.evaluate(after.values) == pytest.approx(g.evaluate(before.values), rel=1e-12)
    assert after.system == before.system
    assert after.roles == before.roles


def test_apply_is_exact_for_exact_values(capsys, tmp_path):
    model = tmp_path / "exact.toml"
    model.write_text(
        '[variables]\nm = { dimension = "M", value = "3/2" }\nl = { dimension = "L", value = 2 }\n'
        'g = { dimension = "L T^-2", value = 10 }\nt = { dimension = "T", role = "time" }\n'
    )
    code, doc = run_json(capsys, "apply", model, "--scale", "g=1", "--s", "1/3")
    assert code == EXIT_OK
    assert doc["count"] == 1
    assert doc["solution"] == 1
    assert doc["s"] == "1/3"
    assert doc["scaled"] == {"m": "3/2", "l": "2/3", "g": "10/3"}
    out = tmp_path / "scaled.json"
    code, _, _ = run(capsys, "apply", model, "--scale", "g=1", "--s", "1/3", "--output", out)
    assert json.loads(out.read_text())["variables"]["l"]["value"] == "2/3"
    code, out, _ = run(capsys, "apply", model, "--scale", "g=1", "--s", "1/3", "--format", "latex")
    assert r"$\frac{2}{3}$" in out


def test_apply_rounds_an_irrational_scaled_value_once_to_the_nearest_float(capsys, tmp_path):
    model = tmp_path / "exact.toml"
    model.write_text(
        '[variables]\nl = { dimension = "L", value = 2 }\ng = { dimension = "L T^-2", value = 10 }\n'
        't = { dimension = "T", value = "1/2", role = "time" }\n'
    )
    # g times s with l fixed: t times s^(-1/2), and 1/2 / sqrt(2) is irrational
    code, doc = run_json(capsys, "apply", model, "--scale", "g=1", "--fixed", "l", "--s", "2")
    assert code == EXIT_OK
    assert doc["scaled"]["t"] == math.sqrt(2) / 4  # exact division of the correctly rounded sqrt(2) by 4
    assert doc["scaled"]["g"] == 20


def test_bases_all_lists_every_set(capsys):
    system = pt.models.rod_system()
    code, doc = run_json(capsys, "bases", ROD, "--all")
    assert code == EXIT_OK
    assert doc["count"] == len(doc["bases"]) == system.count_bases()
    assert [tuple(b) for b in doc["bases"]] == system.bases()


def test_verify_of_an_impossible_request_runs_nothing_and_says_why(capsys):
    pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")
    # g times s with the time step and a length fixed: g dt^2 / length cannot change
    code, out, err = run(
        capsys, "verify", "example:pendulum.xml", "--scale", "g=1", "--fixed", "timestep", "ccd_tolerance", "--s", "2"
    )
    assert code == EXIT_ERROR
    assert out == ""
    assert err.startswith("pitheorem: Impossible: g*timestep**2/ccd_tolerance is dimensionless")
    assert err.endswith(" Nothing verified.\n")
    assert err.count("\n") == 1


def test_apply_only_scaling_is_named(capsys):
    code, out, _ = run(capsys, "apply", ROD, "--scale", "g=1", "--allow", "l", "m", "F", "--s", "2")
    assert code == EXIT_OK
    assert "the only minimal scaling" in out


def test_apply_infeasible_writes_nothing(capsys, tmp_path):
    out = tmp_path / "never.toml"
    code, text, err = run(
        capsys, "apply", ROD, "--scale", "g=1", "--fixed", "t", "m", "k_theta", "--s", "2", "--output", out
    )
    assert code == EXIT_INFEASIBLE
    assert text == ""
    assert err.count("\n") == 1
    assert "g**2*m*t**2/k_theta" in err
    assert not out.exists()


BAD_REQUESTS = {
    "scale_and_fixed": (["search", ROD, "--scale", "g=1", "--fixed", "g"], "'g'"),
    "unknown_scale_variable": (["search", ROD, "--scale", "gravity=1"], "'gravity'"),
    "unknown_fixed_variable": (["search", ROD, "--scale", "g=1", "--fixed", "time"], "'time'"),
    "bad_exponent": (["search", ROD, "--scale", "g=two"], "'two'"),
    "zero_denominator": (["search", ROD, "--scale", "g=1/0"], "'1/0'"),
    "no_equals": (["search", ROD, "--scale", "g"], "'g'"),
    "empty_exponent": (["search", ROD, "--scale", "g="], "'g='"),
    "scale_twice": (["search", ROD, "--scale", "g=1", "g=2"], "'g'"),
    "zero_exponent": (["search", ROD, "--scale", "g=0"], "'g'"),
    "fixed_and_allowed": (["search", ROD, "--scale", "g=1", "--fixed", "l", "--allow", "l"], "'l'"),
    "wrong_repeating_count": (["groups", ROD, "--repeating", "m", "l"], "('m', 'l')"),
    "dependent_repeating": (["groups", ROD, "--repeating", "m", "k_theta", "tau"], "k_theta"),
    "unknown_repeating": (["groups", ROD, "--repeating", "m", "l", "mass"], "'mass'"),
    "exclude_unknown": (["bases", ROD, "--exclude", "T"], "'T'"),
    "exclude_and_require": (["bases", ROD, "--exclude", "m", "--require", "m"], "'m'"),
    "missing_file": (["groups", "no_such_model.toml"], "no_such_model.toml"),
    "directory": (["groups", "."], "'.'"),
    "unknown_example": (["groups", "example:rod"], "example:rod"),
    "unknown_example_named_like_urdf": (["groups", "example:robot.urdf"], "the shipped examples are hinged_rod"),
    "bad_s": (["apply", ROD, "--scale", "g=1", "--s", "big"], "'big'"),
    "negative_s": (["apply", ROD, "--scale", "g=1", "--s", "-2"], "'-2'"),
    "solution_out_of_range": (["apply", ROD, "--scale", "g=1", "--s", "2", "--solution", "4"], "--solution 4"),
    "bad_output_suffix": (["apply", ROD, "--scale", "g=1", "--s", "2", "--output", "out.yaml"], "out.yaml"),
    "overwrite_input": (["apply", ROD, "--scale", "g=1", "--s", "2", "--output", ROD], "input file"),
    "count_and_all": (["bases", ROD, "--count", "--all"], "--count prints only the number of sets and --all lists"),
    "verify_a_toml_file": (
        ["verify", ROD, "--scale", "g=1", "--s", "2"],
        "verify runs MJCF (.xml) or URDF (.urdf) model files",
    ),
    "check_a_toml_file": (["check", ROD], "check reads MJCF (.xml) or URDF (.urdf) model files"),
    "check_in_latex": (["check", "example:pendulum.xml", "--format", "latex"], "'latex'"),
    "convert_a_toml_file": (
        ["convert", ROD, "--units", "L=cm"],
        "convert reads MJCF (.xml) or URDF (.urdf) model files",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD_REQUESTS))
def test_bad_request(capsys, case, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    argv, culprit = BAD_REQUESTS[case]
    code, out, err = run(capsys, *argv)
    assert code == EXIT_ERROR, (out, err)
    assert out == ""
    assert err.startswith("pitheorem: error: "), err
    assert err.count("\n") == 1, err
    assert culprit in err, err
    assert "Traceback" not in err


def test_apply_without_values(capsys, tmp_path):
    path = tmp_path / "bare.toml"
    path.write_text('[variables]\nl = { dimension = "L" }\nt = { dimension = "T" }\n')
    code, out, err = run(capsys, "apply", path, "--scale", "l=1", "--s", "2")
    assert code == EXIT_ERROR
    assert out == ""
    assert err.startswith(f"pitheorem: error: {path}: no variable has a value")
    assert err.count("\n") == 1


@pytest.mark.parametrize("case", sorted(BROKEN_MODEL_FILES))
def test_broken_model_file(capsys, tmp_path, case):
    path, fragments = broken_model_file(tmp_path, case)
    code, out, err = run(capsys, "groups", path)
    assert code == EXIT_ERROR
    assert out == ""
    assert err.startswith(f"pitheorem: error: {path}"), err
    assert err.count("\n") == 1, err
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in err, err


def test_contradictory_search_exits_infeasible_with_the_proof(capsys, tmp_path):
    # a well-formed file and request whose constraints contradict each other: exit 1, not 2
    path = tmp_path / "superball.toml"
    path.write_text(
        '[variables]\nm = { dimension = "M" }\nl = { dimension = "L" }\nk = { dimension = "M T^-2" }\n'
        't = { dimension = "T", role = "time" }\n'
    )
    code, out, err = run(capsys, "search", path, "--scale", "k=1", "--fixed", "m", "t")
    assert code == EXIT_INFEASIBLE, err
    assert "Impossible" in out
    assert "k*t**2/m" in out
    assert err == ""


def test_usage_errors_and_help(capsys):
    assert run(capsys, "search", ROD)[0] == EXIT_ERROR  # --scale is required
    assert run(capsys, "frobnicate", ROD)[0] == EXIT_ERROR
    assert run(capsys, "groups", ROD, "--format", "yaml")[0] == EXIT_ERROR
    code, out, _ = run(capsys, "--help")
    assert code == EXIT_OK
    assert "Exit codes" in out
    code, out, _ = run(capsys, "--version")
    assert code == EXIT_OK
    assert pt.__version__ in out


def test_search_json_count(capsys):
    code, doc = run_json(capsys, "search", "example:hinged_rod", "--scale", "g=1")
    assert code == EXIT_OK
    assert doc["count"] == 3


@pytest.mark.parametrize(
    ("argv", "culprit"),
    [
        (["groups", "missing.toml"], "missing.toml"),
        (["search", ROD, "--scale", "gg=1"], "'gg'"),
        (["search", ROD, "--scale", "g=1", "--fixed", "g"], "'g'"),
    ],
)
def test_errors_are_one_line(capsys, argv, culprit, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # missing.toml is missing here
    code, out, err = run(capsys, *argv)
    assert code == EXIT_ERROR
    assert out == ""
    assert err.startswith("pitheorem: error: ")
    assert err.count("\n") == 1
    assert culprit in err
    assert "Traceback" not in err


def test_broken_file_message(capsys, tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text('[variables]\nm = { dimension = "M" }\nm = { dimension = "L" }\n')
    code, _, err = run(capsys, "groups", path)
    assert code == EXIT_ERROR
    assert (
        err == f"pitheorem: error: {path}, line 3: variable 'm': is defined twice in [variables]; "
        "each variable may appear once\n"
    )


def test_usage_error_names_the_missing_option(capsys):
    code, _, err = run(capsys, "search", ROD)
    assert code == EXIT_ERROR
    assert "--scale" in err
    assert "Traceback" not in err


def test_python_dash_m_infeasible_exit_code():
    # python -m pitheorem (pitheorem/__main__.py) in its own process: exit code, stdout, stderr
    proc = subprocess_run("search", ROD, "--scale", "g=1", "--fixed", "t", "m", "k_theta")
    assert proc.returncode == EXIT_INFEASIBLE
    assert "g**2*m*t**2/k_theta" in proc.stdout
    assert proc.stderr == ""


@pytest.mark.skipif(
    _console_script() is None, reason="pitheorem is not installed (pip install -e .), so no console script"
)
def test_console_script(tmp_path):
    out = tmp_path / "scaled.toml"
    proc = subprocess_run(
        "apply", "example:hinged_rod", "--scale", "g=1", "--s", "2", "--output", out, program=[_console_script()]
    )
    assert proc.returncode == EXIT_OK, proc.stderr
    assert load_model_file(out).values["g"] == pytest.approx(19.62)
    proc = subprocess_run("groups", tmp_path / "nope.toml", program=[_console_script()])
    assert proc.returncode == EXIT_ERROR
    assert proc.stderr.count("\n") == 1


def test_cli_groups_and_search_load_neither_scipy_nor_matplotlib(tmp_path):
    run = (
        "import sys\nfrom pitheorem.cli import main\nsys.argv = ['pitheorem', *{args!r}]\n"
        "try:\n    main()\nexcept SystemExit:\n    pass"
    )
    assert loaded_after(run.format(args=["groups", "example:hinged_rod"])) == set()
    assert "scipy" not in loaded_after(run.format(args=["search", "example:hinged_rod", "--scale", "g=1"]))
    assert "matplotlib" not in loaded_after(run.format(args=["bases", "example:hinged_rod"]))


MODEL = """
[variables]
g = { dimension = "L T^-2", value = 9.81 }
l = { dimension = "L", value = 0.3 }
m = { dimension = "M", value = "1/3" }
t = { dimension = "T" }
"""


@pytest.fixture
def model(tmp_path):
    path = tmp_path / "model.toml"
    path.write_text(MODEL, encoding="utf-8")
    return path


def assert_one_line_error(code, out, err, *fragments):
    assert code == EXIT_ERROR, (code, out, err)
    assert err.startswith("pitheorem: error: "), err
    assert err.count("\n") == 1, err
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in err, err


BAD_DIMENSIONS = [
    ('"L^20000"', "1000"),
    ('"L^99999999999999999999999"', "1000"),
    ('"N"', "newton"),
    ('"L^--2"', "'-'"),
    ('"' + "(" * 200 + "L" + ")" * 200 + '"', "nest"),
    ('"L^(1/0)"', "division by zero"),
]


@pytest.mark.parametrize(("dimension", "fragment"), BAD_DIMENSIONS)
@pytest.mark.parametrize("command", [["groups"], ["bases"], ["search", "--scale", "x=1"]])
def test_bad_dimension_in_file(tmp_path, capsys, dimension, fragment, command):
    path = tmp_path / "bad.toml"
    path.write_text(f'[variables]\nx = {{ dimension = {dimension}, value = 1 }}\nt = {{ dimension = "T" }}\n')
    code, out, err = run(capsys, command[0], path, *command[1:])
    assert_one_line_error(code, out, err, fragment, "'x'")


@pytest.mark.parametrize(
    ("entry", "fragments"),
    [
        ("g=1e400", ["1000", "exponent of the scale factor s"]),
        ("g=1/0", ["exponent of the scale factor s"]),
        ("g=s^2", ["exponent of the scale factor s", "not a factor"]),
        ("g=2s", ["exponent of the scale factor s"]),
        ("g=*6", ["exponent of the scale factor s"]),
        ("g=x6", ["exponent of the scale factor s"]),
        ("g=nan", ["exponent of the scale factor s"]),
        ("g=inf", ["exponent of the scale factor s"]),
        ("g", ["NAME=EXP", "exponent of the scale factor s"]),
        ("g=0.3333333333333333", ["1000000000000"]),
        ("nope=1", ["'nope'"]),
    ],
)
def test_bad_scale_entries(model, capsys, entry, fragments):
    code, out, err = run(capsys, "search", model, "--scale", entry)
    assert_one_line_error(code, out, err, *fragments)


@pytest.mark.parametrize("s", ["0", "-2", "abc", "1/0", "inf", "nan", "1e99999999"])
def test_bad_s(model, capsys, s):
    code, out, err = run(capsys, "apply", model, "--scale", "g=1", "--fixed", "--s", s)
    assert_one_line_error(code, out, err, "--s")


@pytest.mark.parametrize("s", ["1e300", "1e-300"])  # above and below the range of floats
def test_scaled_value_out_of_float_range(model, capsys, s):
    code, out, err = run(capsys, "apply", model, "--scale", "g=1000", "--fixed", "--s", s)
    # the command line's remedy, never the Python caller's ("use an exact value")
    assert_one_line_error(
        code,
        out,
        err,
        "the scaled value of 'g' is beyond the range of floating point "
        "(about 1e-308 to 1e308); choose an --s nearer to 1",
    )


def test_impossible_is_exit_1_and_only_that(model, capsys):
    code, out, _err = run(capsys, "search", model, "--scale", "g=1", "--fixed", "t", "l")
    assert code == EXIT_INFEASIBLE
    assert "certificate" in out


def test_scale_help_says_exponent_not_factor(capsys):
    assert main(["search", "--help"]) == EXIT_OK
    help_text = " ".join(capsys.readouterr().out.split())
    assert "exponent of the scale factor s, not a factor" in help_text
    assert "g=1/6: g -> s^(1/6) g" in help_text


def test_exponent_one_sixth_is_an_exponent(model, capsys):
    code, out, err = run(capsys, "search", model, "--scale", "g=1/6")
    assert code == EXIT_OK, err
    assert "s^(1/6)" in out


def test_apply_writes_no_float_noise(model, capsys, tmp_path):
    out_path = tmp_path / "scaled.toml"
    code, out, err = run(capsys, "apply", model, "--scale", "g=1", "--fixed", "--s", "10", "--output", out_path)
    assert code == EXIT_OK, err
    text = out_path.read_text()
    assert "98.1 " in text
    assert "98.10000000000001" not in text
    assert "3.0 " in text  # 0.3 * 10, not 3.0000000000000004
    values = tomllib.loads(text)["variables"]
    assert values["g"]["value"] == 98.1
    assert values["l"]["value"] == 3.0
    assert Fraction(values["m"]["value"]) == Fraction(1, 3)  # exact values stay exact
    # the printed table too
    assert "98.1" in out
    assert "98.10000000000001" not in out


def test_apply_rounds_once_from_the_exact_product(model, capsys, tmp_path):
    # s = 1/10 and exponent 1: 9.81 * 0.1 in floats is 0.9810000000000001
    out_path = tmp_path / "small.toml"
    code, _, err = run(capsys, "apply", model, "--scale", "g=1", "--fixed", "--s", "0.1", "--output", out_path)
    assert code == EXIT_OK, err
    assert 9.81 * 0.1 != 0.981
    assert tomllib.loads(out_path.read_text())["variables"]["g"]["value"] == 0.981


def test_the_command_line_reads_toml_files_without_the_engines(monkeypatch, capsys):
    import sys

    from pitheorem.cli import main

    for name in [m for m in sys.modules if m.startswith("pitheorem.engines")]:
        monkeypatch.setitem(sys.modules, name, None)  # importing any of them now fails
    monkeypatch.setitem(sys.modules, "pitheorem.engines", None)
    assert main(["groups", "example:hinged_rod"]) == 0
    assert capsys.readouterr().out.strip()


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        ([], "COMMAND"),
        (["frobnicate", ROD], "'frobnicate'"),
        (["groups", ROD, "--format", "yaml"], "'yaml'"),
        (["apply", ROD, "--scale", "g=1", "--s", "2", "--solution", "x"], "--solution"),
        (["search", ROD], "--scale"),
    ],
)
def test_usage_errors_are_one_line_not_the_usage_block(capsys, argv, fragment):
    code, out, err = run(capsys, *argv)
    assert_one_line_error(code, out, err, fragment)
    assert "usage:" not in err


@pytest.mark.parametrize(
    ("unit", "fragment"),
    [("m**inf", "finite"), ("m**-1e400", "finite"), ("m**100000", "1000"), ("m^-1/2", "ambiguous")],
)
def test_a_bad_unit_exponent_in_a_file_is_named_not_reported_as_a_bug(capsys, tmp_path, unit, fragment):
    path = tmp_path / "units.toml"
    path.write_text(f'[variables]\nx = {{ unit = "{unit}", value = 1.0 }}\ny = {{ dimension = "L", value = 2.0 }}\n')
    code, out, err = run(capsys, "groups", path)
    assert_one_line_error(code, out, err, "'x'", fragment)
    assert "please report" not in err


def test_groups_whose_value_overflows_floats_is_a_named_error(capsys, tmp_path):
    path = tmp_path / "tiny.toml"
    path.write_text('[variables]\nx = { dimension = "L^2", value = 1.0 }\ny = { dimension = "L", value = 1e-200 }\n')
    code, out, err = run(capsys, "groups", path, "--repeating", "y")
    assert_one_line_error(code, out, err, "beyond the range of floating point")
    assert "please report" not in err
