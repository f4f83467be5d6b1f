"""Tests for pitheorem.modelfile: reading, checking and writing TOML model files."""

from __future__ import annotations

import json
import pickle
from fractions import Fraction

import pytest

import pitheorem as pt
from pitheorem import engines
from pitheorem.modelfile import (
    EXAMPLES,
    ModelFile,
    ModelFileError,
    dump_values,
    example_path,
    examples,
    load_model_file,
    write_model_file,
)
from tests.conftest import BROKEN_MODEL_FILES, broken_model_file


def write(tmp_path, text: str, name: str = "model.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_examples_are_listed():
    assert examples() == (
        "hinged_rod",
        "hinged_rod.urdf",
        "hinged_rod.xml",
        "pendulum.xml",
        "superball",
        "superball.xml",
    )
    assert example_path("hinged_rod.toml") == example_path("hinged_rod")
    assert example_path("hinged_rod").name == "hinged_rod.toml"
    assert example_path("pendulum.xml") == EXAMPLES / "pendulum.xml"
    # the engines' call is the same function: one home for the shipped files
    assert engines.example_path is example_path
    assert sorted(p.name for p in EXAMPLES.iterdir() if p.suffix in (".toml", ".xml", ".urdf")) == [
        "hinged_rod.toml",
        "hinged_rod.urdf",
        "hinged_rod.xml",
        "pendulum.xml",
        "superball.toml",
        "superball.xml",
    ]
    # a URDF's settings file ships beside it and is no example of its own
    assert (EXAMPLES / "hinged_rod.urdf.settings.json").is_file()


def test_hinged_rod_example_is_the_papers_rod():
    rod = load_model_file(example_path("hinged_rod"))
    assert rod.name == "hinged rod"
    assert rod.system == pt.models.rod_system()
    assert rod.values == {
        "m": 1.5,
        "theta_r": pytest.approx(1.0471975511965976),
        "l": 2,
        "g": 9.81,
        "k_theta": 100,
        "c_theta": 10,
    }
    assert rod.roles["t"] == "time"
    assert rod.time == "t"
    assert rod.roles["m"] == "parameter"
    assert rod.path.endswith("hinged_rod.toml")


def test_superball_example_has_the_section_4_list():
    sb = load_model_file("example:superball")
    assert sb.system.variables == ("g", "rho", "x_r", "k", "c", "F", "v", "t", "m", "l", "G", "E")
    assert sb.system.dimensions == pt.models.superball_parameters().dimensions
    assert sb.system.rank == 3


@pytest.mark.parametrize(
    "name", ["superbal", "pendulum", "hopper.xml", "../modelfile.py", "examples/pendulum.xml", "pendulum.xml.toml", ""]
)
def test_unknown_example(name):
    with pytest.raises(ModelFileError) as caught:
        example_path(name)
    assert str(caught.value) == (
        f"example:{name}: no such example; the shipped examples are "
        "hinged_rod, hinged_rod.urdf, hinged_rod.xml, pendulum.xml, superball, superball.xml; "
        "the how-to's models are causes/contact.xml, causes/hand.xml, causes/mesh_drop.xml, "
        "causes/quadruped.urdf, causes/walker_on_floor.xml"
    )
    assert caught.value.culprit == f"example:{name}"


def test_an_engine_example_is_no_toml_model_file():
    with pytest.raises(ModelFileError) as caught:
        load_model_file("example:pendulum.xml")
    assert str(caught.value) == (
        f"example:pendulum.xml: is an engine model, not a TOML model file; pass its path, {EXAMPLES / 'pendulum.xml'}"
    )


def test_minimal_file_defaults(tmp_path):
    model = load_model_file(write(tmp_path, '[variables]\nl = { dimension = "L" }\n', "pendulum.toml"))
    assert model.name == "pendulum"
    assert model.description == ""
    assert model.values == {}
    assert model.roles == {"l": "parameter"}
    assert model.time is None


def test_values_exact_and_float(tmp_path):
    model = load_model_file(
        write(
            tmp_path,
            """
[variables]
a = { dimension = "L", value = "1/3" }
b = { dimension = "L", value = 2 }
c = { dimension = "L", value = 2.5 }
d = { dimension = "L", value = " -4/2 " }
e = { dimension = "L", value = 1e-3 }
""",
        )
    )
    assert model.values == {"a": Fraction(1, 3), "b": 2, "c": 2.5, "d": -2, "e": 0.001}
    assert type(model.values["b"]) is Fraction  # every exact value is a Fraction
    assert type(model.values["d"]) is Fraction
    assert type(model.values["c"]) is float  # floats stay floats


def test_units_read_by_pint(tmp_path):
    model = load_model_file(
        write(
            tmp_path,
            """
[variables]
k_theta = { unit = "N*m/rad", value = 100 }
l = { unit = "cm" }
t = { unit = "s", role = "time" }
""",
        )
    )
    assert str(model.system.dimension("k_theta")) == "M L^2 T^-2"
    assert str(model.system.dimension("l")) == "L"
    assert model.units == {"k_theta": "N*m/rad", "l": "cm", "t": "s"}


def test_custom_base_dimensions(tmp_path):
    model = load_model_file(
        write(
            tmp_path,
            """
base_dimensions = ["M", "L", "T", "A"]
[variables]
k_theta = { dimension = "M L^2 T^-2 A^-1" }
theta = { dimension = "A", role = "state" }
""",
        )
    )
    assert model.system.base_dimensions == ("M", "L", "T", "A")


def test_order_of_variables_is_the_files(tmp_path):
    model = load_model_file(
        write(
            tmp_path,
            """
[variables]
z = { dimension = "T" }
a = { dimension = "L" }
[variables.m]
dimension = "M"
""",
        )
    )
    assert model.system.variables == ("z", "a", "m")


def test_round_trip_toml(tmp_path):
    rod = load_model_file("example:hinged_rod")
    new = {**rod.values, "m": Fraction(3, 7), "l": 5}
    out = write_model_file(rod, tmp_path / "copy.toml", new)
    text = out.read_text()
    assert 'value = "3/7"' in text
    assert "value = 5, " in text  # an integral Fraction is written as a TOML integer
    again = load_model_file(out)
    assert again.values == new
    assert again.system == rod.system
    assert again.roles == rod.roles
    assert again.descriptions == rod.descriptions


def test_round_trip_units_and_odd_names(tmp_path):
    model = load_model_file(
        write(
            tmp_path,
            """
name = "quote \\" and backslash \\\\"
[variables]
"θ" = { dimension = "1" }
l = { unit = "m", value = 1.5 }
""",
        )
    )
    again = load_model_file(write(tmp_path, dump_values(model), "again.toml"))
    assert again.name == 'quote " and backslash \\'
    assert again.system == model.system
    assert again.units == {"l": "m"}


def test_json_output(tmp_path):
    rod = load_model_file("example:hinged_rod")
    out = write_model_file(rod, tmp_path / "copy.json", {**rod.values, "m": Fraction(1, 2)})
    doc = json.loads(out.read_text())
    assert list(doc["variables"]) == list(rod.system.variables)
    assert doc["variables"]["m"] == {"dimension": "M", "value": "1/2", "description": "mass of the rod"}
    assert doc["variables"]["t"]["role"] == "time"


def test_with_values_converts_sympy_numbers():
    import sympy

    rod = load_model_file("example:hinged_rod")
    new = rod.with_values({"l": sympy.Rational(4, 2), "m": sympy.Rational(1, 3), "g": sympy.sqrt(2)})
    assert new.values == {"m": Fraction(1, 3), "l": 2, "g": pytest.approx(2**0.5)}
    assert isinstance(new.values["g"], float)
    with pytest.raises(ModelFileError, match="'nope'"):
        rod.with_values({"nope": 1})


def test_bad_output_suffix(tmp_path):
    with pytest.raises(ModelFileError, match=r"\.yaml"):
        write_model_file(load_model_file("example:superball"), tmp_path / "x.yaml")
    with pytest.raises(ModelFileError, match="format"):
        dump_values(load_model_file("example:superball"), format="yaml")


def test_model_file_is_a_record():
    model = ModelFile("x", "", pt.System({"l": "L"}))
    assert model == ModelFile("x", "", pt.System({"l": "L"}))
    with pytest.raises(TypeError):
        hash(model)


@pytest.mark.parametrize("case", sorted(BROKEN_MODEL_FILES))
def test_broken_file(tmp_path, case):
    path, fragments = broken_model_file(tmp_path, case)
    with pytest.raises(ModelFileError) as info:
        load_model_file(path)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(str(path))
    for fragment in fragments:
        assert fragment in message, (fragment, message)
    assert isinstance(info.value, ValueError)
    assert isinstance(info.value, pt.PiTheoremError)


def test_not_utf8(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes('[variables]\n"\u00e9" = { dimension = "M" }\n'.encode("latin-1"))
    with pytest.raises(ModelFileError, match="UTF-8"):
        load_model_file(path)


def test_missing_file_is_an_os_error(tmp_path):
    with pytest.raises(FileNotFoundError):
        load_model_file(tmp_path / "nope.toml")


def test_error_fields_and_pickling():
    err = ModelFileError("rod.toml", "unknown role 'clock'", variable="t", line=4)
    assert (err.path, err.variable, err.line) == ("rod.toml", "t", 4)
    assert str(err) == "rod.toml, line 4: variable 't': unknown role 'clock'"
    again = pickle.loads(pickle.dumps(err))
    assert str(again) == str(err)
    assert again.variable == "t"


def test_the_kind_of_a_model_file_is_told_in_one_place(tmp_path):
    from pitheorem.modelfile import model_kind

    urdf_in_xml = tmp_path / "robot.xml"
    urdf_in_xml.write_text('<?xml version="1.0"?>\n<robot name="r"><link name="a"/></robot>\n')
    mjcf = tmp_path / "world.xml"
    mjcf.write_text('<mujoco model="w"><worldbody/></mujoco>\n')
    # a shipped example is named by the command line's example list, whatever its name ends with
    kinds = {
        "robot.URDF": "urdf",
        "model.toml": "toml",
        "model.json": "toml",
        "example:superball": "toml",
        "example:robot.urdf": "toml",
        "example:pendulum.xml": "toml",
        str(urdf_in_xml): "urdf",
        str(mjcf): "mjcf",
        str(tmp_path / "absent.xml"): "mjcf",
        "hopper.mjcf": "mjcf",
    }
    assert {path: model_kind(path) for path in kinds} == kinds


@pytest.mark.parametrize("bad", [3, None, ["rod.toml"]])
def test_load_model_file_names_a_path_that_is_no_path(bad):
    with pytest.raises(pt.ModelFileError, match="named by a path"):
        pt.load_model_file(bad)


@pytest.mark.parametrize(
    ("unit", "exponent"),
    [("m**0.3333333", Fraction(3333333, 10**7)), ("m**1e-7", Fraction(1, 10**7)), ("m**(1/3)", Fraction(1, 3))],
)
def test_a_unit_in_a_file_keeps_its_exponent_exactly(tmp_path, unit, exponent):
    model = load_model_file(write(tmp_path, f'[variables]\nx = {{ unit = "{unit}" }}\n'))
    assert model.system.dimension("x") == pt.Dimension({"L": exponent})


@pytest.mark.parametrize(
    ("unit", "says"), [("m**inf", "finite"), ("m**(1/1000001)", "denominator"), ("m^-1/2", "ambiguous")]
)
def test_a_unit_exponent_no_fraction_can_hold_is_named_in_a_file(tmp_path, unit, says):
    with pytest.raises(pt.ModelFileError, match=says) as caught:
        load_model_file(write(tmp_path, f'[variables]\nx = {{ unit = "{unit}" }}\n'))
    assert caught.value.variable == "x"
