"""The command line on bad and extreme input: one line on stderr and exit 2; exit 1 only for "impossible"."""

from __future__ import annotations

import tomllib
from fractions import Fraction

import pytest

from pitheorem.cli import EXIT_ERROR, EXIT_INFEASIBLE, EXIT_OK, main

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


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


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


@pytest.mark.parametrize(("entry", "fragments"), [
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
])
def test_bad_scale_entries(model, capsys, entry, fragments):
    code, out, err = run(capsys, "search", model, "--scale", entry)
    assert_one_line_error(code, out, err, *fragments)


@pytest.mark.parametrize("s", ["0", "-2", "abc", "1/0", "inf", "nan", "1e99999999"])
def test_bad_s(model, capsys, s):
    code, out, err = run(capsys, "apply", model, "--scale", "g=1", "--fixed", "--s", s)
    assert_one_line_error(code, out, err, "--s")


def test_scaled_value_out_of_float_range(model, capsys):
    code, out, err = run(capsys, "apply", model, "--scale", "g=1000", "--fixed", "--s", "1e300")
    assert_one_line_error(code, out, err, "floating point")


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
