"""pitheorem.engines.fileformats.urdf: every number a URDF file states, with its name, place and dimension; copies by address."""

from __future__ import annotations

import math
import pickle
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt

pytest.importorskip("pybullet", reason="pybullet is not installed (pip install 'pitheorem[engines]')")

from pitheorem import engines
from pitheorem.engines import EngineModelError

ARM = Path(__file__).resolve().parent / "data" / "engines" / "slider_arm.urdf"


_ARM_TEXT = ARM.read_text()

_EVERY_NUMBER = """<robot name="r">
  <link name="base">
    <inertial><origin xyz="0 0 0.1"/><mass value="2"/>
      <inertia ixx="1" ixy="0.5" ixz="0.25" iyy="2" iyz="0.125" izz="3"/></inertial>
    <collision><origin xyz="0.5 0 0"/><geometry><box size="1 2 3"/></geometry></collision>
    <collision><geometry><cylinder radius="0.1" length="0.4"/></geometry></collision>
    <collision><geometry><mesh filename="part.stl"/></geometry></collision>
    <collision><geometry><plane normal="0 0 1"/></geometry></collision>
    <collision><origin xyz="0 0 9"/></collision>
    <collision><origin xyz="0 0 8"/><geometry><sphere radius="0.3"/></geometry></collision>
    <visual><geometry><sphere radius="0.2"/></geometry></visual>
    <visual><geometry><material name="red"/></geometry></visual>
    <visual><geometry><mesh filename="part.stl" scale="2 2 2"/></geometry></visual>
    <contact><lateral_friction value="0.9"/><rolling_friction value="0.01"/><spinning_friction value="0.02"/>
      <stiffness value="3000"/><damping value="40"/><restitution value="0.5"/><contact_cfm value="0"/>
      <contact_erp value="0.2"/><inertia_scaling value="1"/><friction_anchor/></contact>
  </link>
  <link><collision><geometry><capsule radius="0.05" length="0.3"/></geometry></collision></link>
  <link name="tip"/>
  <joint name="weld" type="fixed"><origin xyz="1 0 0"/></joint>
  <joint name="slide" type="prismatic"><origin xyz="0 1 0"/>
    <limit lower="-0.5" upper="0.5" effort="10" velocity="2"/><dynamics damping="0.3" friction="0.4"/></joint>
  <joint name="swing" type="revolute"><limit lower="-1" upper="1" effort="5" velocity="3"/></joint>
  <joint name="spin" type="continuous"><dynamics damping="0.7"/></joint>
</robot>
"""

_INERTIA_NOTE = "PyBullet recomputes the inertia from the collision shapes unless URDF_USE_INERTIA_FROM_FILE is given"


def test_dimensions_follow_the_joint_type():
    model = engines.load(ARM)
    d = {p.name: p.dimension_text for p in model.parameters}
    assert d["joint_slide_velocity"] == "L T^-1"
    assert d["joint_swing_velocity"] == "T^-1"
    assert d["joint_slide_effort"] == "M L T^-2"
    assert d["joint_swing_effort"] == "M L^2 T^-2"
    assert d["joint_slide_damping"] == "M T^-1"
    assert d["joint_swing_damping"] == "M L^2 T^-1"
    assert d["joint_slide_upper"] == "L"
    assert d["joint_swing_upper"] == "1"
    assert d["joint_slide_maxJointVelocity"] == "L T^-1"  # the catalogue's T^-1 holds for revolute joints only
    assert d["joint_swing_maxJointVelocity"] == "T^-1"
    assert d["link_cart_rolling_friction"] == "L"
    assert d["contactSlop"] == "L"
    assert d["solverResidualThreshold"] == "1"  # no pure dimension: no change of units scales it
    assert d["link_cart_linearDamping"] == "T^-1 (rate) | L^-1 (per_length)"
    assert [str(x) for x in model.runner.control_dimensions()] == ["M L T^-2", "M L^2 T^-2"]


@pytest.mark.parametrize(
    ("text", "culprit"),
    [
        ("not xml at all", "not well-formed XML"),
        ("<mujoco/>", "root element must be <robot>"),
        ('<robot name="r"><!-- only a comment --></robot>', "a URDF file needs at least one <link>; this one has none"),
        # links and joints that make no tree, refused as ROS's URDF parser refuses them; PyBullet crashes the
        # process (a segmentation fault) on a joint given twice, found by a fuzz of the test models
        (
            '<robot name="r"><link name="a"/><link name="b"/>'
            + '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>' * 2
            + "</robot>",
            "joint 'j': two joints are named 'j'",
        ),
        ('<robot name="r"><link name="a"/><link name="a"/></robot>', "link 'a': two links are named 'a'"),
        (
            '<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/></joint></robot>',
            "joint 'j': a joint needs a <child link=...>",
        ),
        (
            '<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/><child link="z"/>'
            "</joint></robot>",
            "joint 'j': its child link 'z' is no link of the file",
        ),
        (
            '<robot name="r"><link name="a"/><link name="b"/><link name="c"/>'
            '<joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint>'
            '<joint name="k" type="fixed"><parent link="b"/><child link="c"/></joint></robot>',
            "joint 'k': link 'c' is the child of two joints",
        ),
        (
            '<robot name="r"><link name="a"/><link name="b"/></robot>',
            "<robot>: 2 links are no joint's child ('a', 'b')",
        ),
        (
            '<robot name="r"><link name="a"/><link name="b"/><link name="c"/>'
            '<joint name="j" type="fixed"><parent link="b"/><child link="c"/></joint>'
            '<joint name="k" type="fixed"><parent link="c"/><child link="b"/></joint></robot>',
            "its joints make a loop",
        ),
        (
            '<robot name="r"><link name="a"><collision><geometry><mesh filename="gone.stl"/></geometry></collision>'
            "</link></robot>",
            "link 'a' collision #0 mesh 'gone.stl'",
        ),
        (
            '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="planar"><parent link="a"/>'
            '<child link="b"/></joint></robot>',
            "joint 'j' (type 'planar')",
        ),
        (
            '<robot name="r"><link name="a"><collision><geometry><torus/></geometry></collision></link></robot>',
            "<torus>",
        ),
    ],
)
def test_bad_urdf_files_name_the_element(tmp_path, text, culprit):
    path = tmp_path / "bad.urdf"
    path.write_text(text)
    with pytest.raises(EngineModelError) as caught:
        engines.load(path)
    # the format's refusals, whatever the engine (MuJoCo compiled an empty <robot> as an empty world)
    with pytest.raises(EngineModelError) as in_mujoco:
        engines.load(path, engine="mujoco")
    assert culprit in str(in_mujoco.value)
    message = str(caught.value)
    assert culprit in message
    assert "bad.urdf" in message
    assert "\n" not in message
    assert str(pickle.loads(pickle.dumps(caught.value))) == message


@pytest.mark.parametrize(
    ("old", "new", "says"),
    [
        ('<mass value="2.0"', '<mass value="nan"', "value='nan' is not a finite number"),
        ('<mass value="2.0"', '<mass value="inf"', "value='inf' is not a finite number"),
        ('<mass value="2.0"', '<mass value=""', "inertial mass: value='' must be a finite number"),
        ('<mass value="2.0"', '<mass value="heavy"', "inertial mass: value='heavy' must be a finite number"),
        (
            '<mass value="2.0"',
            '<mass value="-1"',
            "inertial mass: value='-1' must be a finite number, such as 1.5, and not negative",
        ),
        ('izz="', 'izz="nan" old_izz="', "izz='nan' is not a finite number"),
        ('damping="', 'damping="nan" old_damping="', "damping='nan' is not a finite number"),
    ],
)
def test_bad_numbers_are_refused_by_element_and_attribute(tmp_path, old, new, says):
    assert old in _ARM_TEXT
    path = tmp_path / "bad.urdf"
    path.write_text(_ARM_TEXT.replace(old, new, 1))
    with pytest.raises(EngineModelError) as caught:
        engines.load(path)
    message = str(caught.value)
    assert message.startswith(f"{path}: ")
    assert says in message
    assert "\n" not in message


def test_reading_changes_nothing_and_a_copy_is_written_by_address(tmp_path, monkeypatch):
    """The parsed file stays as written (no mesh scale added); a scaled copy is not walked again."""
    import xml.etree.ElementTree as ET

    from pitheorem.engines.fileformats import urdf

    path = Path(__file__).resolve().parent / "robots" / "urdf" / "arm.urdf"
    model = engines.load(path, fixed_base=True, damping=0.0, split_impulse=False)
    tree = model.runner.tree
    assert ET.tostring(tree.getroot()) == ET.tostring(ET.parse(path).getroot())  # read, not changed
    scales = [p for p in model.parameters if p.name.endswith("_scale")]
    assert scales
    assert all(p.value == (1.0, 1.0, 1.0) for p in scales)  # PyBullet's default, read as such
    walks = []
    real = urdf._attributes
    monkeypatch.setattr(urdf, "_attributes", lambda *args: walks.append(args) or real(*args))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    copy = model.scaled(sc, 4)
    assert walks == []  # by address: the copy's numbers are the original's, moved to the copy's elements
    assert ET.tostring(tree.getroot()) == ET.tostring(ET.parse(path).getroot())  # the original untouched
    pure = [p for p in model.parameters if p.dimension is not None]  # (a mixed number has parts instead)
    assert len(pure) > 40
    for p in pure:  # the oracle: each number times s to its dimension's exponent (a power of two: exact)
        factor = 4.0 ** float(sc.exponent_of(p.dimension))
        assert copy.parameter(p.name).value == tuple(v * factor for v in p.value), p.name
    # the saved copy states the scale it was given, and reads back as the copy
    reread = engines.load(copy.save(tmp_path / "arm_4.urdf"))  # its scene from the settings saved beside it
    assert [(p.name, p.value) for p in reread.parameters] == [(p.name, p.value) for p in copy.parameters]
    assert {p.name: p.value for p in reread.parameters if p.name.endswith("_scale")} == {
        p.name: (4.0, 4.0, 4.0) for p in scales
    }


def test_the_reader_finds_every_number_with_its_name_place_dimension_and_note(tmp_path):
    import xml.etree.ElementTree as ET

    from pitheorem.engines.fileformats.urdf import _attributes

    (tmp_path / "part.stl").write_text("solid part\nendsolid part\n")
    tree = ET.ElementTree(ET.fromstring(_EVERY_NUMBER))
    read = [(a.name, a.path, a.attr, str(a.dimension), a.read(), a.note) for a in _attributes(tree, "r.urdf", tmp_path)]
    inertia = [
        (f"link_base_{i}", f"link 'base' inertia {i}", i, "M L^2", (v,), _INERTIA_NOTE)
        for i, v in (("ixx", 1.0), ("ixy", 0.5), ("ixz", 0.25), ("iyy", 2.0), ("iyz", 0.125), ("izz", 3.0))
    ]
    mesh_note = "a factor times the mesh file's units, a length"
    assert read == [
        ("link_base_com", "link 'base' inertial origin xyz", "xyz", "L", (0.0, 0.0, 0.1), ""),
        ("link_base_mass", "link 'base' inertial mass", "value", "M", (2.0,), ""),
        *inertia,
        ("link_base_collision0_xyz", "link 'base' collision #0 origin xyz", "xyz", "L", (0.5, 0.0, 0.0), ""),
        ("link_base_collision0_size", "link 'base' collision #0 box size", "size", "L", (1.0, 2.0, 3.0), ""),
        ("link_base_collision1_radius", "link 'base' collision #1 cylinder radius", "radius", "L", (0.1,), ""),
        ("link_base_collision1_length", "link 'base' collision #1 cylinder length", "length", "L", (0.4,), ""),
        # a mesh without a scale is read at scale 1, PyBullet's default (reading adds nothing to the file)
        ("link_base_collision2_scale", "link 'base' collision #2 mesh scale", "scale", "L", (1.0, 1.0, 1.0), mesh_note),
        # a shape without geometry keeps its origin, and the shapes after it are read
        ("link_base_collision4_xyz", "link 'base' collision #4 origin xyz", "xyz", "L", (0.0, 0.0, 9.0), ""),
        ("link_base_collision5_xyz", "link 'base' collision #5 origin xyz", "xyz", "L", (0.0, 0.0, 8.0), ""),
        ("link_base_collision5_radius", "link 'base' collision #5 sphere radius", "radius", "L", (0.3,), ""),
        ("link_base_visual0_radius", "link 'base' visual #0 sphere radius", "radius", "L", (0.2,), ""),
        ("link_base_visual2_scale", "link 'base' visual #2 mesh scale", "scale", "L", (2.0, 2.0, 2.0), mesh_note),
        ("link_base_rolling_friction", "link 'base' contact rolling_friction", "value", "L", (0.01,), ""),
        ("link_base_spinning_friction", "link 'base' contact spinning_friction", "value", "L", (0.02,), ""),
        ("link_base_stiffness", "link 'base' contact stiffness", "value", "M T^-2", (3000.0,), ""),
        ("link_base_damping", "link 'base' contact damping", "value", "M T^-1", (40.0,), ""),
        # a link without a name is read as the name ""
        ("link__collision0_radius", "link '' collision #0 capsule radius", "radius", "L", (0.05,), ""),
        ("link__collision0_length", "link '' collision #0 capsule length", "length", "L", (0.3,), ""),
        ("joint_weld_xyz", "joint 'weld' origin xyz", "xyz", "L", (1.0, 0.0, 0.0), ""),
        ("joint_slide_xyz", "joint 'slide' origin xyz", "xyz", "L", (0.0, 1.0, 0.0), ""),
        ("joint_slide_lower", "joint 'slide' limit lower", "lower", "L", (-0.5,), ""),
        ("joint_slide_upper", "joint 'slide' limit upper", "upper", "L", (0.5,), ""),
        ("joint_slide_effort", "joint 'slide' limit effort", "effort", "M L T^-2", (10.0,), ""),
        ("joint_slide_velocity", "joint 'slide' limit velocity", "velocity", "L T^-1", (2.0,), ""),
        ("joint_slide_damping", "joint 'slide' dynamics damping", "damping", "M T^-1", (0.3,), ""),
        ("joint_slide_friction", "joint 'slide' dynamics friction", "friction", "M L T^-2", (0.4,), ""),
        ("joint_swing_lower", "joint 'swing' limit lower", "lower", "1", (-1.0,), ""),
        ("joint_swing_upper", "joint 'swing' limit upper", "upper", "1", (1.0,), ""),
        ("joint_swing_effort", "joint 'swing' limit effort", "effort", "M L^2 T^-2", (5.0,), ""),
        ("joint_swing_velocity", "joint 'swing' limit velocity", "velocity", "T^-1", (3.0,), ""),
        ("joint_spin_damping", "joint 'spin' dynamics damping", "damping", "M L^2 T^-1", (0.7,), ""),
    ]
    # the absent mesh scale is read as PyBullet's default, and nothing is written into the parsed file
    assert tree.getroot().find("link/collision[3]/geometry/mesh").get("scale") is None


@pytest.mark.parametrize(
    ("text", "element", "reason"),
    [
        ("<mujoco/>", "<mujoco>", "a URDF file's root element must be <robot>"),
        (
            '<robot><link name="a"><visual><geometry><mesh filename="gone.stl"/></geometry></visual></link></robot>',
            "link 'a' visual #0 mesh 'gone.stl'",
            "mesh file not found (relative to the URDF's folder)",
        ),
        (
            '<robot><link name="a"><collision><geometry><mesh/></geometry></collision></link></robot>',
            "link 'a' collision #0 mesh ''",
            "mesh file not found (relative to the URDF's folder)",
        ),
        (
            '<robot><link name="a"><collision><geometry><torus/></geometry></collision></link></robot>',
            "link 'a' collision #0 <torus>",
            "unknown geometry; use box, cylinder, capsule, sphere, mesh or plane",
        ),
        (
            '<robot><link name="a"><contact><stickiness value="1"/></contact></link></robot>',
            "link 'a' contact <stickiness>",
            "unknown contact parameter",
        ),
        (
            '<robot><joint name="j" type="planar"/></robot>',
            "joint 'j' (type 'planar')",
            "joint type not supported by pitheorem's scaling; use revolute, continuous, prismatic, spherical, "
            "floating or fixed",
        ),
        (
            '<robot><joint name="j"/></robot>',
            "joint 'j' (type '')",
            "joint type not supported by pitheorem's scaling; use revolute, continuous, prismatic, spherical, "
            "floating or fixed",
        ),
    ],
)
def test_the_reader_refuses_what_it_cannot_read_in_full_words(tmp_path, text, element, reason):
    import xml.etree.ElementTree as ET

    from pitheorem.engines.fileformats.urdf import _attributes

    with pytest.raises(EngineModelError) as caught:
        _attributes(ET.ElementTree(ET.fromstring(text)), "bad.urdf", tmp_path)
    assert (caught.value.path, caught.value.element, caught.value.reason) == ("bad.urdf", element, reason)


def test_the_reader_reads_a_nameless_joint_and_every_joint_type(tmp_path):
    import xml.etree.ElementTree as ET

    from pitheorem.engines.fileformats.urdf import _attributes
    from pitheorem.engines.fileformats.urdf import joint_kind as _joint_kind
    from pitheorem.engines.parameters import JointKind

    assert [_joint_kind(t) for t in ("prismatic", "revolute", "continuous", "fixed", "planar", "Revolute", "")] == [
        JointKind.SLIDE,
        JointKind.HINGE,
        JointKind.HINGE,
        None,
        None,
        None,
        None,
    ]
    text = '<robot><joint type="revolute"><limit effort="2"/></joint></robot>'
    (read,) = _attributes(ET.ElementTree(ET.fromstring(text)), "j.urdf", tmp_path)
    assert (read.name, read.path, str(read.dimension), read.read()) == (
        "joint__effort",
        "joint '' limit effort",
        "M L^2 T^-2",
        (2.0,),
    )


def test_a_scaled_copy_keeps_each_file_numbers_name_place_dimension_and_note():
    model = engines.load(ARM, fixed_base=True, damping=0.0, split_impulse=False)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    copy = model.scaled(sc, 10)

    def described(m):
        return [(p.name, p.path, p.dimension_text, p.note) for p in m.parameters if p.source == "file"]

    assert described(copy) == described(model)
    assert any(note for *_, note in described(model))  # the inertia's note among them: not only empty notes


def test_a_saved_urdf_names_its_meshes_relative_to_itself_and_loads_after_its_folder_moves(tmp_path):
    import shutil

    import pybullet

    robots = Path(__file__).resolve().parent / "robots" / "urdf"
    shutil.copytree(robots, tmp_path / "lab" / "urdf")
    model = engines.load(tmp_path / "lab" / "urdf" / "arm.urdf", fixed_base=True, damping=0.0, split_impulse=False)
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    out = tmp_path / "lab" / "urdf" / "scaled" / "arm4.urdf"
    out.parent.mkdir()
    model.scaled(lengths, 4).save(out)
    text = out.read_text()
    assert 'filename="../meshes/base.obj"' in text
    assert str(tmp_path) not in text
    shutil.move(tmp_path / "lab", tmp_path / "moved")
    client = pybullet.connect(pybullet.DIRECT)
    try:
        body = pybullet.loadURDF(str(tmp_path / "moved" / "urdf" / "scaled" / "arm4.urdf"), physicsClientId=client)
        assert pybullet.getNumJoints(body, physicsClientId=client) == 4
    finally:
        pybullet.disconnect(client)


@pytest.mark.parametrize("engine", ["pybullet", "mujoco"])
def test_a_urdf_saved_with_its_meshes_copied_loads_alone_after_the_originals_are_gone(tmp_path, engine):
    import shutil

    pytest.importorskip(engine)
    robots = Path(__file__).resolve().parent / "robots" / "urdf"
    shutil.copytree(robots, tmp_path / "lab" / "urdf")
    options = {"fixed_base": True, "damping": 0.0, "split_impulse": False} if engine == "pybullet" else {}
    model = engines.load(tmp_path / "lab" / "urdf" / "arm.urdf", engine=engine, **options)
    out = tmp_path / "lab" / "out" / "arm_copy.urdf"
    out.parent.mkdir()
    model.save(out, copy_assets=True)
    assert 'filename="arm_copy_assets/base.obj"' in out.read_text()
    shutil.rmtree(tmp_path / "lab" / "urdf")
    shutil.move(tmp_path / "lab" / "out", tmp_path / "moved")
    again = engines.load(tmp_path / "moved" / "arm_copy.urdf", engine=engine)  # its saved settings hold the scene
    assert [p.value for p in again.parameters] == [p.value for p in model.parameters]


def _binary_stl(header: bytes) -> bytes:
    """A binary STL of one triangle whose 80-byte header (free text by the format) is `header`."""
    import struct

    return header.ljust(80, b" ") + struct.pack("<I12fH", 1, *[0.0] * 3, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)


def _mesh_robot(tmp_path) -> Path:
    """A URDF in ws/robot/urdf/ whose meshes sit beside it and, as ``package://tools/...``, two folders up."""
    folder = tmp_path / "ws" / "robot" / "urdf"
    (tmp_path / "ws" / "tools" / "meshes").mkdir(parents=True)
    folder.mkdir(parents=True)
    (folder / "parts.obj").write_text("o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nv 0 0 1\nf 1 2 4\n")
    (folder / "one.obj").write_text("o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (folder / "header.stl").write_bytes(_binary_stl(b"exported\no a\no b\no c\n"))  # lines that look like OBJ parts
    (folder / "skin.png").write_bytes(b"\x89PNG\r\n\x1a\n")
    (folder / "libplugin.so").write_bytes(b"")  # a plugin is found on Gazebo's plugin path, not beside the file
    (tmp_path / "ws" / "tools" / "meshes" / "hand.obj").write_text("o x\nv 0 0 0\no y\nv 1 0 0\no z\nv 0 1 0\n")
    path = folder / "robot.urdf"
    path.write_text(
        '<robot name="r"><link name="base">'
        '<collision><geometry><mesh filename="parts.obj"/></geometry></collision>'
        '<collision><geometry><mesh filename="one.obj"/></geometry></collision>'
        '<collision><geometry><mesh filename="header.stl"/></geometry></collision>'
        '<visual><geometry><mesh filename="parts.obj"/></geometry>'
        '<material name="skin"><texture filename="skin.png"/></material></visual></link>'
        '<link name="hand"><collision><geometry><mesh filename="package://tools/meshes/hand.obj"/></geometry>'
        "</collision></link>"
        '<joint name="wrist" type="fixed"><parent link="base"/><child link="hand"/></joint>'
        '<gazebo><plugin name="p" filename="libplugin.so"/></gazebo></robot>'
    )
    return path


def test_compound_meshes_are_the_collision_objs_of_several_parts_found_as_pybullet_finds_them(tmp_path):
    from pitheorem.engines.fileformats.urdf import read_urdf

    document = read_urdf(_mesh_robot(tmp_path))
    # two parts count (one does not); an STL whose header holds OBJ-like lines is not an OBJ; the visual
    # copy of parts.obj is not a collision shape; the package's mesh is found two folders up
    assert document.compound_meshes() == [("base", "parts.obj", 2), ("hand", "package://tools/meshes/hand.obj", 3)]
    scales = [p.path for p in document.parameters() if p.path.endswith("mesh scale")]
    assert scales == [f"link 'base' collision #{k} mesh scale" for k in range(3)] + [
        "link 'base' visual #0 mesh scale",
        "link 'hand' collision #0 mesh scale",
    ]


def test_a_package_path_is_found_under_ros_package_path_then_at_a_package_root_named_otherwise(tmp_path, monkeypatch):
    """``package://kr16_support/meshes/m.obj`` from ``kr16/urdf/robot.urdf``: PyBullet's search (a folder
    ``kr16_support`` beside the file or above it) finds nothing; ROS finds the package under
    ``ROS_PACKAGE_PATH``; without it, the package's root is the folder above ``urdf/``, named otherwise."""
    import os

    from pitheorem.engines.fileformats.urdf import read_urdf

    folder = tmp_path / "kr16" / "urdf"
    folder.mkdir(parents=True)
    path = folder / "robot.urdf"
    inertial = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
    path.write_text(
        f'<robot name="r"><link name="base">{inertial}<collision><geometry>'
        '<mesh filename="package://kr16_support/meshes/m.obj"/></geometry></collision></link></robot>'
    )
    obj = "o x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n"
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    with pytest.raises(EngineModelError, match="mesh file not found"):
        read_urdf(path)
    in_root = tmp_path / "kr16" / "meshes" / "m.obj"
    in_root.parent.mkdir()
    in_root.write_text(obj)
    assert str(in_root.resolve()) in read_urdf(path).portable_text()
    in_ws = tmp_path / "ws" / "kr16_support" / "meshes" / "m.obj"
    in_ws.parent.mkdir(parents=True)
    in_ws.write_text(obj)
    monkeypatch.setenv("ROS_PACKAGE_PATH", os.pathsep.join([str(tmp_path / "nowhere"), str(tmp_path / "ws")]))
    assert str(in_ws.resolve()) in read_urdf(path).portable_text()  # the package ROS names comes first
    beside = folder / "kr16_support" / "meshes" / "m.obj"  # and PyBullet's own search before it
    beside.parent.mkdir(parents=True)
    beside.write_text(obj)
    assert str(beside.resolve()) in read_urdf(path).portable_text()


def test_a_package_is_found_by_its_manifest_under_ros_package_path_or_in_an_ament_prefix(tmp_path, monkeypatch):
    """ROS 1 finds a package by the ``<name>`` of its ``package.xml`` anywhere below ``ROS_PACKAGE_PATH`` (its folder
    may be named otherwise); ROS 2 in ``share/NAME`` under each prefix of ``AMENT_PREFIX_PATH``."""
    from pitheorem.engines.fileformats.urdf import read_urdf

    path = tmp_path / "robot.urdf"
    inertial = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
    path.write_text(
        f'<robot name="r"><link name="base">{inertial}<collision><geometry>'
        '<mesh filename="package://arm_support/meshes/m.obj"/></geometry></collision></link></robot>'
    )
    obj = "o x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n"
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    ament = tmp_path / "install" / "share" / "arm_support" / "meshes" / "m.obj"
    ament.parent.mkdir(parents=True)
    ament.write_text(obj)
    with pytest.raises(EngineModelError, match="mesh file not found"):
        read_urdf(path)
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path / "install"))
    assert str(ament.resolve()) in read_urdf(path).portable_text()
    package = tmp_path / "catkin" / "src" / "vendor_arm"  # its folder named otherwise: found by its manifest
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text('<?xml version="1.0"?><package format="2"><name>arm_support</name></package>')
    (package / "meshes" / "m.obj").write_text(obj)
    decoy = package / "nested" / "package.xml"  # a manifest inside a package is not looked at (ROS's crawl)
    decoy.parent.mkdir()
    decoy.write_text("<package><name>elsewhere</name></package>")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "catkin"))
    assert str((package / "meshes" / "m.obj").resolve()) in read_urdf(path).portable_text()  # before AMENT's
    from pitheorem.engines.fileformats.urdf import _manifests

    assert set(_manifests(str(tmp_path / "catkin"))) == {"arm_support"}


def test_a_mesh_is_looked_for_in_every_folder_above_the_file_as_pybullet_does(tmp_path):
    from pitheorem.engines.fileformats.urdf import read_urdf

    folder = tmp_path / "top" / "a" / "b" / "c" / "d" / "urdf"
    folder.mkdir(parents=True)
    path = folder / "robot.urdf"
    inertial = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
    for name in ("package://far/m.obj", "far/m.obj"):  # PyBullet drops package:// and searches the same folders
        path.write_text(
            f'<robot name="r"><link name="base">{inertial}<collision><geometry><mesh filename="{name}"/>'
            "</geometry></collision></link></robot>"
        )
        with pytest.raises(EngineModelError, match="mesh file not found"):
            read_urdf(path)
        for up in (folder.parents[3], folder.parents[4]):  # folders a (4th above) and top (5th)
            (up / "far").mkdir()
            (up / "far" / "m.obj").write_text("o x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n")
            assert read_urdf(path).parameters()[-1].path == "link 'base' collision #0 mesh scale"
            import pybullet  # the oracle: PyBullet finds the same file

            client = pybullet.connect(pybullet.DIRECT)
            try:
                body = pybullet.loadURDF(str(path), physicsClientId=client)
                shape = pybullet.getCollisionShapeData(body, -1, physicsClientId=client)[0]
            finally:
                pybullet.disconnect(client)
            assert Path(shape[4].decode()) == up / "far" / "m.obj"
            (up / "far" / "m.obj").unlink()
            (up / "far").rmdir()


def test_the_portable_text_names_meshes_and_textures_by_absolute_path_and_nothing_else(tmp_path):
    from pitheorem.engines.fileformats.urdf import read_urdf

    path = _mesh_robot(tmp_path)
    document = read_urdf(path)
    text = document.portable_text()
    assert text is not None
    for name in ("parts.obj", "one.obj", "header.stl", "skin.png"):
        assert f'filename="{(path.parent / name).resolve()}"' in text
    assert f'filename="{(tmp_path / "ws" / "tools" / "meshes" / "hand.obj").resolve()}"' in text
    assert 'filename="libplugin.so"' in text  # not a mesh or a texture: left as written
    assert document.text().count('filename="parts.obj"') == 2  # the document itself is unchanged
    (path.parent / "skin.png").unlink()
    assert read_urdf(path).portable_text() is None  # a texture that cannot be found: no portable text


def test_a_saved_copy_renames_meshes_and_textures_only(tmp_path):
    from pitheorem.engines.fileformats.urdf import read_urdf

    out = tmp_path / "elsewhere" / "copy.urdf"
    out.parent.mkdir()
    read_urdf(_mesh_robot(tmp_path)).save(out)
    text = out.read_text()
    assert 'filename="../ws/robot/urdf/parts.obj"' in text
    assert 'filename="../ws/robot/urdf/skin.png"' in text
    assert 'filename="../ws/tools/meshes/hand.obj"' in text
    assert 'filename="libplugin.so"' in text  # the plugin keeps its name, though a file of that name is beside


def test_a_file_that_is_not_well_formed_is_refused_at_its_line(tmp_path):
    from pitheorem.engines.fileformats.urdf import read_urdf

    path = tmp_path / "broken.urdf"
    path.write_text('<robot name="r">\n  <link name="a"/>\n  <link name="b"></robot>\n')
    with pytest.raises(EngineModelError) as caught:
        read_urdf(path)
    assert caught.value.element == "line 3"  # its column (19) is not its line
    assert "not well-formed XML" in str(caught.value)


# -- numbers as PyBullet reads them: text that is not plain numbers (pybullet_data's bike, biped, husky) --------


def _libc_atof():
    import ctypes
    import ctypes.util

    name = ctypes.util.find_library("c")
    if name is None:  # a platform without a C library to load by name (Windows): no oracle to ask
        pytest.skip("no C library found to compare with its atof")
    libc = ctypes.CDLL(name)
    libc.atof.restype, libc.atof.argtypes = ctypes.c_double, (ctypes.c_char_p,)
    return libc.atof


@given(st.text(alphabet="0123456789.eE+- ,\tinfaINF$(x)", max_size=14))
@settings(max_examples=300, deadline=None)
def test_a_number_is_read_as_c_atof_reads_it(text):
    from pitheorem.engines.fileformats.urdf import bullet_numbers

    atof = _libc_atof()  # the oracle: C's own atof, which PyBullet's URDF reader calls
    if "x" in text.lower():  # C reads hexadecimal ("0x1p3"), which no URDF writes; the reader does not
        text = text.replace("x", "").replace("X", "")
    expected = atof(text.encode())
    (value,) = bullet_numbers("value", text)
    assert value == expected or (math.isnan(value) and math.isnan(expected))
    pieces = [p for p in text.split(" ") if p]
    three = bullet_numbers("xyz", text)
    if len(pieces) < 3:
        assert three is None
    else:
        want = [atof(p.encode()) for p in pieces[:3]]
        assert all(a == b or (math.isnan(a) and math.isnan(b)) for a, b in zip(three, want, strict=True))


LOOSE_URDFS = {  # a file of pybullet_data with numbers that are not plain, the first such attribute, PyBullet's reading
    "bicycle/bike.urdf": ("joint 'handlebar_to_frontwheel' origin xyz", (0.07, 0.0, -0.69)),
    "biped/biped2d_pybullet.urdf": ("joint 'torso_to_rightleg' limit lower", (-1.57,)),
    "husky/husky.urdf": ("joint 'imu_joint' origin xyz", (0.0, 0.0, 0.19)),  # an unexpanded xacro $(optenv ...)
}


@pytest.mark.parametrize("name", sorted(LOOSE_URDFS))
def test_numbers_that_are_not_plain_are_read_as_pybullet_holds_them_and_said_once(name):
    import warnings

    import pybullet

    from pitheorem.engines.fileformats.urdf import read_urdf

    pybullet_data = pytest.importorskip("pybullet_data", reason="pybullet_data is not installed")
    path = Path(pybullet_data.getDataPath()) / name
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        document = read_urdf(path)
    said = [str(w.message) for w in caught if "read as PyBullet reads it" in str(w.message)]
    where, numbers = LOOSE_URDFS[name]
    assert len(said) == 1
    assert said[0].startswith(f"{path.name}: {where}: ")
    assert ("run xacro first" in said[0]) == (name == "husky/husky.urdf")
    values = {p.path: p.value for p in document.parameters()}
    assert values[where] == numbers
    # the oracle: what PyBullet holds once it loaded the file, joint by joint
    client = pybullet.connect(pybullet.DIRECT)
    try:
        body = pybullet.loadURDF(str(path), physicsClientId=client)
        checked = 0
        for j in range(pybullet.getNumJoints(body, physicsClientId=client)):
            info = pybullet.getJointInfo(body, j, physicsClientId=client)
            joint = info[1].decode()
            xyz = values.get(f"joint {joint!r} origin xyz")
            if xyz is not None:  # PyBullet keeps the origin in the parent's inertial frame: back to the link's
                com, turn = pybullet.getDynamicsInfo(body, info[16], physicsClientId=client)[3:5]
                held = pybullet.multiplyTransforms(com, turn, info[14], (0.0, 0.0, 0.0, 1.0))[0]
                assert np.allclose(held, xyz, rtol=0, atol=1e-6), joint
                checked += 1
            for k, limit in ((8, "lower"), (9, "upper")):
                if f"joint {joint!r} limit {limit}" in values and info[2] != pybullet.JOINT_FIXED:
                    assert values[f"joint {joint!r} limit {limit}"] == (info[k],), joint
                    checked += 1
    finally:
        pybullet.disconnect(client)
    assert checked >= 2


def test_text_with_no_number_pybullet_reads_is_still_refused(tmp_path):
    from pitheorem.engines.fileformats.urdf import read_urdf

    path = tmp_path / "r.urdf"
    for bad, message in (
        ('<mass value="heavy"/>', "value='heavy' must be a finite number"),
        ('<mass value="-2,5"/>', "value='-2,5' must be a finite number, such as 1.5, and not negative"),
        ('<origin xyz="a b c"/><mass value="1"/>', "xyz='a b c' must be finite numbers"),
    ):
        path.write_text(f'<robot name="r"><link name="a"><inertial>{bad}</inertial></link></robot>')
        with pytest.raises(EngineModelError, match=re.escape(message)):
            read_urdf(path)


def test_a_floating_joint_states_no_number_and_runs_as_pybullet_runs_it(tmp_path):
    # PyBullet loads a floating joint as a fixed one ("joint unsupported, creating a fixed joint instead")
    inertial = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
    path = tmp_path / "floating.urdf"
    path.write_text(
        f'<robot name="r"><link name="a">{inertial}</link><link name="b">{inertial}</link>'
        '<joint name="j" type="floating"><parent link="a"/><child link="b"/><origin xyz="0 0 1"/>'
        '<limit lower="-1" upper="1"/></joint></robot>'
    )
    model = engines.load(path, damping=0.0, split_impulse=False)
    assert [p.path for p in model.parameters if p.path.startswith("joint 'j'")] == ["joint 'j' origin xyz"]
    assert not any(name.startswith("q[") for name in model.coordinates()[0])
    rep = engines.verify(model, pt.search(model.system(), scale={"g": 1}).scalings[0], s=4, duration=0.1)
    assert rep.exact


def test_a_spherical_joints_limits_are_angles_and_its_effort_a_torque():
    pybullet_data = pytest.importorskip("pybullet_data", reason="pybullet_data is not installed")
    model = engines.load(Path(pybullet_data.getDataPath()) / "spherical_joint_limit.urdf")
    table = {p.name: p for p in model.parameters}
    assert [(table[f"joint_neck_{a}"].value, str(table[f"joint_neck_{a}"].dimension)) for a in ("lower", "twist")] == [
        ((0.2,), "1"),
        ((0.3,), "1"),
    ]
    assert str(table["joint_neck_effort"].dimension) == "M L^2 T^-2"
    assert [n for n in model.coordinates()[0] if "neck" in n] == [
        *(f"q[neck:{a}]" for a in "xyzw"),
        *(f"qdot[neck:{a}]" for a in "xyz"),
    ]
