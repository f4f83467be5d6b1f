"""pitheorem.engines.fileformats.numbers: the checks of a model file's numbers, on XML written here.

The loaders' use of them (the files of issue 23) is tested in test_engines_mjcf and test_engines_urdf.
"""

from __future__ import annotations

import pickle

import pytest

from pitheorem import engines
from pitheorem.engines import EngineModelError
from pitheorem.engines.fileformats.numbers import check_model_file, check_numbers


def write(tmp_path, text, name="m.xml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize(
    ("attribute", "value"),
    [
        ("damping", "nan"),
        ("damping", "NaN"),
        ("stiffness", "inf"),
        ("stiffness", "-Infinity"),
        ("pos", "0 0 nan"),
        ("range", "-1e999 1"),
        ("data", "1 nan"),
        ("damping", "1" + "0" * 309),  # infinite though it holds digits only (1e309): read like the others
        ("pos", "0 0 " + "9" * 310),
    ],
)
def test_nan_and_infinities_are_refused_naming_element_and_attribute(tmp_path, attribute, value):
    path = write(
        tmp_path,
        f'<mujoco><worldbody><body name="b"><joint name="h" {attribute}="{value}"/></body></worldbody></mujoco>',
    )
    with pytest.raises(EngineModelError) as caught:
        check_model_file(path)
    message = str(caught.value)
    assert message.startswith(f"{path}: line 1, <joint name='h'>: {attribute}={value!r} is not a finite number")
    assert str(pickle.loads(pickle.dumps(caught.value))) == message


def test_an_unnamed_element_is_named_by_its_nearest_named_ancestor(tmp_path):
    path = write(
        tmp_path, '<robot name="r"><link name="b"><inertial><mass value="nan"/></inertial></link></robot>', "r.urdf"
    )
    with pytest.raises(EngineModelError, match=r"<mass> in <link name='b'>: value='nan'"):
        check_model_file(path)


@pytest.mark.parametrize(
    "text",
    [
        '<mujoco model="nan"><worldbody><body name="inf"><joint name="nan"/></body></worldbody></mujoco>',
        '<mujoco><compiler meshdir="inf"/><asset><mesh file="nan"/></asset></mujoco>',
        '<mujoco><custom><text name="x" data="some nan text"/></custom></mujoco>',  # text data may say anything
        '<mujoco><option timestep="0.002" gravity="0 0 -9.81"/></mujoco>',
        "not xml at all",  # the engine's reader names that
    ],
)
def test_names_text_and_finite_numbers_pass(tmp_path, text):
    check_model_file(write(tmp_path, text))


def test_a_byte_that_is_not_utf8_is_named_with_its_line(tmp_path):
    path = tmp_path / "bad.xml"
    path.write_bytes(b'<mujoco>\n<worldbody>\n<body name="b\xff"/>\n</worldbody>\n</mujoco>')
    with pytest.raises(EngineModelError, match=r"line 3: byte 0xff at offset 34 is not UTF-8"):
        check_model_file(path)


def test_a_missing_file_is_left_to_the_engine(tmp_path):
    check_model_file(tmp_path / "absent.xml")


@pytest.mark.parametrize(
    ("text", "nonnegative"),
    [
        ("", False),
        ("   ", False),
        ("heavy", False),
        ("1 two", False),
        ("nan", False),
        ("inf", False),
        ("-inf", False),
        ("-1", True),
        ("1 -0.5", True),
    ],
)
def test_check_numbers_refuses_what_is_no_finite_number(text, nonnegative):
    with pytest.raises(EngineModelError, match=r"r\.urdf: link 'a' inertial mass: value="):
        check_numbers("r.urdf", "link 'a' inertial mass", "value", text, nonnegative=nonnegative)


@pytest.mark.parametrize(
    ("text", "nonnegative"), [(None, True), ("0", True), ("2.5", True), ("-1 2", False), ("1e-300 3", True)]
)
def test_check_numbers_passes_finite_numbers(text, nonnegative):
    check_numbers("r.urdf", "x", "value", text, nonnegative=nonnegative)


def test_the_whole_messages(tmp_path):
    path = write(tmp_path, '<mujoco><option timestep="nan"/></mujoco>')
    with pytest.raises(EngineModelError) as caught:
        check_model_file(path)
    assert (
        str(caught.value)
        == f"{path}: line 1, <option>: timestep='nan' is not a finite number; a model holds finite numbers only"
    )
    bad = tmp_path / "bad.xml"
    bad.write_bytes(b"<mujoco>\n<x a='\xc3'/></mujoco>")
    with pytest.raises(EngineModelError) as caught:
        check_model_file(bad)
    assert str(caught.value) == f"{bad}: line 2: byte 0xc3 at offset 15 is not UTF-8; save the file as UTF-8 text"
    cases = [  # (text, nonnegative, what the message says it must be)
        ("heavy", False, "a finite number, such as 1.5"),
        ("heavy", True, "a finite number, such as 1.5, and not negative"),
        ("", True, "a finite number, such as 1.5, and not negative"),
        ("-1", True, "a finite number, such as 1.5, and not negative"),
        ("1 nan", False, "finite numbers"),
        ("1 -2 3", True, "finite numbers"),
    ]
    for text, nonnegative, must in cases:
        with pytest.raises(EngineModelError) as caught:
            check_numbers("r.urdf", "link 'a' inertial mass", "value", text, nonnegative=nonnegative)
        assert str(caught.value) == f"r.urdf: link 'a' inertial mass: value={text!r} must be {must}"


def test_negative_numbers_pass_unless_asked_to_refuse_them():
    check_numbers("r.urdf", "joint 'j' dynamics", "damping", "-0.5")  # the default lets a sign through
    with pytest.raises(EngineModelError, match="not negative"):
        check_numbers("r.urdf", "joint 'j' dynamics", "damping", "-0.5", nonnegative=True)


def test_text_attributes_do_not_end_the_scan(tmp_path):
    # a text attribute (not numbers) is skipped; elements and attributes after it are still read
    path = write(
        tmp_path,
        '<mujoco><custom><text name="x" data="some text"/></custom>'
        '<option timestep="0.002"/><worldbody><geom size="1 inf"/></worldbody></mujoco>',
    )
    with pytest.raises(EngineModelError, match=r"<geom>: size='1 inf' is not a finite number"):
        check_model_file(path)
    fine = write(
        tmp_path,
        '<mujoco><custom><text name="x" data="some text"/></custom><option timestep="0.002"/></mujoco>',
        "fine.xml",
    )
    root = check_model_file(fine)
    assert root is not None
    assert [e.tag for e in root.iter()] == ["mujoco", "custom", "text", "option"]


def test_nan_in_a_default_class_names_the_class_and_the_line(tmp_path):
    path = write(
        tmp_path,
        "<mujoco>\n  <default>\n    <default class='stiff'>\n      <joint damping='1'/>\n    </default>\n"
        "    <default class='soft'>\n      <joint damping='nan'/>\n    </default>\n  </default>\n"
        "  <worldbody><body name='b'><joint class='soft'/><geom size='0.1'/></body></worldbody>\n</mujoco>",
    )
    with pytest.raises(EngineModelError) as caught:
        engines.load(path)
    # the seventh line, in the class 'soft' (not the first class, nor the body that uses it)
    assert str(caught.value) == (
        f"{path}: line 7, <joint> in <default class='soft'>: damping='nan' is not a finite number; "
        "a model holds finite numbers only"
    )


@pytest.mark.parametrize(
    ("inertial", "attribute"),
    [('mass="-1" diaginertia="1 1 1"', "mass"), ('mass="1" diaginertia="1 -1 1"', "diaginertia")],
)
def test_a_negative_inertial_mass_or_inertia_is_refused_with_its_body_and_line(tmp_path, inertial, attribute):
    # MuJoCo compiles a negative <inertial> mass or principal inertia of a welded body to 0 without a word
    body = f'<body name="tip">\n<inertial pos="0 0 0" {inertial}/>\n</body>'
    text = f'<mujoco>\n<worldbody>\n<body name="arm">\n<joint/>\n<geom size=".1"/>\n{body}\n</body>\n</worldbody>\n</mujoco>'
    mujoco_module = pytest.importorskip("mujoco")
    assert mujoco_module.MjModel.from_xml_string(text).body_mass[2] in (0.0, 1.0)  # MuJoCo itself says nothing
    path = write(tmp_path, text)
    with pytest.raises(EngineModelError) as caught:
        engines.load(path)
    assert str(caught.value).startswith(f"{path}: line 7, <inertial> in <body name='tip'>: {attribute}=")
    assert "is negative" in str(caught.value)
    # zero stays allowed (a massless frame), and a URDF's own check is untouched
    engines.load(write(tmp_path, text.replace("-1", "0")))


def test_a_value_of_digits_points_signs_and_blanks_up_to_300_characters_is_finite(tmp_path):
    # such values skip the reading of each number: none can be NaN or infinite (300 digits: below 1e300)
    largest = "-" + "9" * 299
    assert float(largest) == -(10.0**299)
    assert len(largest) == 300
    for value in (largest, "0 0 0.1", " +1.5 -2. .5 ", "1.2.3 4"):
        path = write(tmp_path, f'<mujoco><worldbody><body><joint damping="{value}"/></body></worldbody></mujoco>')
        assert check_model_file(path) is not None
