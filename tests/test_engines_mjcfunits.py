"""The MJCF reader held against MuJoCo's own table of units (``doc/XMLunits.rst`` in its wheel).

Every attribute the table lists is set, nonzero, on a model generated from the table itself, and the
dimension the reader gives each component is compared with the table's (angles dimensionless);
an attribute is either read so, refused by the reader by name, or listed in ``EXCEPTIONS`` with a reason.
"""

from __future__ import annotations

import pathlib
import warnings

import pytest

mujoco = pytest.importorskip("mujoco", reason="the MJCF reader needs MuJoCo")

from pitheorem import Dimension  # noqa: E402
from pitheorem.engines import EngineModelError  # noqa: E402
from pitheorem.engines.fileformats.mjcf import read_mjcf  # noqa: E402
from pitheorem.engines.fileformats.mjcfunits import (  # noqa: E402
    EXCEPTIONS,
    UnitsRow,
    _by_the_reader,
    check_attribute,
    component_dimension,
    read_units_table,
)

TABLE = pathlib.Path(mujoco.__file__).parent / "doc" / "XMLunits.rst"


@pytest.fixture(scope="module")
def rows():
    if not TABLE.exists():
        pytest.skip(f"MuJoCo {mujoco.__version__} ships no {TABLE.name} (MuJoCo 3.16 and later do)")
    return read_units_table(TABLE.read_text())


@pytest.fixture(scope="module")
def checks(rows, tmp_path_factory):
    folder = tmp_path_factory.mktemp("units")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the reader's warnings about sensors copied unchanged
        return [check_attribute(row, folder) for row in rows]


def test_every_attribute_of_the_table_is_read_refused_or_an_exception(rows, checks):
    # not true of an empty table: the table is read in full, and most of its attributes are read
    assert len(rows) >= 700  # MuJoCo 4.0.0 lists 742
    assert [c.attribute for c in checks] == [row.attribute for row in rows]
    disagreements = {c.attribute: c.problems for c in checks if c.status == "disagrees"}
    assert disagreements == {}
    assert sum(c.status == "read" for c in checks) >= 300


def test_every_dimensional_attribute_is_accounted_for(rows, checks):
    by_name = {c.attribute: c for c in checks}
    for row in rows:
        if row.dimensional:
            assert by_name[row.attribute].status in ("read", "refused", "exception"), row.attribute
    read = sum(c.status == "read" for c in checks)
    assert read >= 300  # MuJoCo 4.0.0: 312 of the 417 attributes with a dimension


def test_the_exceptions_name_attributes_of_the_table(rows):
    listed = {row.attribute for row in rows}
    assert sorted(set(EXCEPTIONS) - listed) == []
    assert all(reason.strip() for reason in EXCEPTIONS.values())


def test_the_table_is_parsed_as_written(rows):
    by_name = {row.attribute: row for row in rows}
    assert by_name["body/geom/surfacevel"].forms == ((("L T^{-1}",) * 3 + ("A T^{-1}",) * 3),)
    assert by_name["body/joint/solreflimit"].forms == (("T", "1"), ("T^{-2}", "T^{-1}"))
    assert by_name["option/magnetic"].forms == ()
    assert not by_name["body/euler"].dimensional
    assert by_name["actuator/position/kp"].uses_joint


def test_a_wrong_dimension_in_the_table_is_a_disagreement(tmp_path):
    assert check_attribute(UnitsRow("body/geom/margin", (("T",),)), tmp_path).status == "disagrees"
    assert check_attribute(UnitsRow("body/geom/margin", (("L",),)), tmp_path).status == "read"
    wrong = check_attribute(UnitsRow("body/geom/surfacevel", (("L T^{-1}",) * 6,)), tmp_path)
    assert wrong.status == "disagrees"
    assert "component 3" in wrong.problems[0]


def test_a_component_left_unread_is_a_disagreement(tmp_path):
    # the table's adhesion is a force: a model that sets it and a reader that did not list it would disagree
    check = check_attribute(UnitsRow("body/geom/adhesion", (("M L T^{-2}",),)), tmp_path)
    assert check.status == "read"
    check = check_attribute(UnitsRow("body/geom/solmix", (("L",),)), tmp_path)
    assert check.status == "disagrees"
    assert "not read" in check.problems[0]


def test_component_dimensions_follow_the_joint():
    L, one = Dimension.parse("L"), Dimension.parse("1")
    force = Dimension.parse("M L T^-2")
    assert component_dimension("F T Q^{-1}", L, force) == Dimension.parse("M T^-1")
    assert component_dimension("F T Q^{-1}", one, force * L) == Dimension.parse("M L^2 T^-1")
    assert component_dimension("A", L, force) == one
    assert component_dimension("1", L, force) == one


def _dimensions(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return {p.name: p.dimension for p in read_mjcf(path).parameters()}


def test_surfacevel_is_three_velocities_then_three_angular_velocities(tmp_path):
    path = tmp_path / "belt.xml"
    path.write_text(
        '<mujoco><worldbody><geom name="belt" type="box" size="1 1 .1" surfacevel="1 2 3 0.1 0.2 0.3"/>'
        "</worldbody></mujoco>"
    )
    dims = _dimensions(path)
    assert str(dims["geom_belt_surfacevel_linear"]) == "L T^-1"
    assert str(dims["geom_belt_surfacevel_angular"]) == "T^-1"


def test_a_file_mesh_refpos_is_in_the_file_units(tmp_path):
    (tmp_path / "tet.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    path = tmp_path / "mesh.xml"
    mesh = '<mesh name="m" {} refpos="0.5 0 0" scale="2 2 2"/>'
    path.write_text(
        f"<mujoco><asset>{mesh.format('file=' + chr(34) + 'tet.obj' + chr(34))}</asset><worldbody>"
        '<geom type="mesh" mesh="m"/></worldbody></mujoco>'
    )
    # MuJoCo subtracts refpos before it multiplies by scale: scale carries the length, refpos none
    dims = _dimensions(path)
    assert str(dims["mesh_m_scale"]) == "L"
    assert "mesh_m_refpos" not in dims
    inline = tmp_path / "inline.xml"
    inline.write_text(
        f"<mujoco><asset>{mesh.format('vertex=' + chr(34) + '0 0 0 1 0 0 0 1 0 0 0 1' + chr(34))}</asset>"
        '<worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>'
    )
    dims = _dimensions(inline)  # inline vertices carry the length, and refpos with them
    assert str(dims["mesh_m_uservert"]) == "L"
    assert str(dims["mesh_m_refpos"]) == "L"


def test_the_readers_refusals_are_told_apart_from_mujocos_own_rejections(tmp_path):
    # a refusal by the reader (a number it cannot scale) makes an attribute "refused"; MuJoCo's own rejection
    # of a generated value is a problem with the generated model instead
    muscle = (
        '<mujoco><worldbody><site name="a"/><body pos="0 0 -0.3"><joint name="j" type="slide" axis="0 0 1" '
        'limited="true" range="-0.1 0.1"/><geom size="0.05" mass="1"/><site name="b"/></body></worldbody>'
        '<tendon><spatial name="t"><site site="a"/><site site="b"/></spatial></tendon>'
        '<actuator><muscle name="m" tendon="t"/></actuator></mujoco>'
    )
    files = {
        "ball gear": '<mujoco><worldbody><body><joint name="j" type="ball"/><geom size=".1"/></body></worldbody>'
        '<actuator><general joint="j" gear="1 0 0 1 0 0"/></actuator></mujoco>',
        "muscle without a force": muscle,
        "an attribute MuJoCo does not know": '<mujoco><worldbody><geom size=".1" foo="1"/></worldbody></mujoco>',
    }
    told = {}
    for what, text in files.items():
        path = tmp_path / "refused.xml"
        path.write_text(text)
        with pytest.raises(EngineModelError) as err:
            read_mjcf(path)
        told[what] = _by_the_reader(err.value)
    assert told == {"ball gear": True, "muscle without a force": True, "an attribute MuJoCo does not know": False}


def test_only_rows_that_name_an_attribute_are_read():
    # the table's header row and any cell after a row's own two are not attributes
    text = (
        "   * - Attribute\n     - Units\n"
        "   * - :ref:`option/timestep<option-timestep>`\n     - :math:`T`\n     - a third cell\n"
        "   * - :ref:`body/geom/size<body-geom-size>`\n     - :math:`L`\n"
    )
    rows = read_units_table(text)
    assert [(r.attribute, r.forms) for r in rows] == [("option/timestep", (("T",),)), ("body/geom/size", (("L",),))]
