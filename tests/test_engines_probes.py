"""The engine as a check of the reader: each stored number's power of s against the dimension it was given."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

import pitheorem as pt

mujoco = pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

from pitheorem import engines  # noqa: E402
from pitheorem.engines.fileformats import mjcf  # noqa: E402
from pitheorem.engines.parameters import dim  # noqa: E402
from pitheorem.engines.verdicts.probes import check_dimensions, dimension_causes  # noqa: E402

gymnasium = pytest.importorskip("gymnasium", reason="gymnasium is not installed (its MuJoCo assets are the corpus)")
ASSETS = Path(gymnasium.__file__).resolve().parent / "envs" / "mujoco" / "assets"
CORPUS = sorted(p.name for p in ASSETS.glob("*.xml"))

BOX = (
    '<mujoco><compiler angle="radian"/><option timestep="0.002"/><worldbody><body name="box" pos="0 0 1"><freejoint/>'
    '<geom name="cube" type="box" size=".1 .2 .3" density="500" margin="0.01"/></body>'
    '<body name="arm" pos="1 0 1"><joint name="hinge" range="-1 1" damping="0.5"/>'
    '<geom type="capsule" fromto="0 0 0 0 0 .5" size=".05" mass="2"/></body></worldbody>'
    '<actuator><position name="servo" joint="hinge" kp="20" kv="1"/></actuator></mujoco>'
)


def load_quiet(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        return engines.load(path)


@pytest.fixture
def box(tmp_path):
    path = tmp_path / "box.xml"
    path.write_text(BOX)
    return path


def test_the_stored_copies_cover_the_files_numbers_and_the_computed_ones(box):
    copies = load_quiet(box).runner.stored_copies()
    by_field = {c.field for c in copies}
    assert {"geom_size", "geom_margin", "body_mass", "jnt_range", "actuator_gainprm", "opt.timestep"} <= by_field
    assert {"body_subtreemass", "geom_rbound"} <= by_field
    # a capsule's size is its radius in the file and radius, half-length in the engine: only the radius copies
    capsule = [c.index for c in copies if c.field == "geom_size" and c.parameter.startswith("geom1")]
    assert 3 in capsule
    assert 4 not in capsule


@pytest.mark.parametrize("name", CORPUS)
def test_every_corpus_file_agrees_with_the_engine(name):
    assert check_dimensions(load_quiet(ASSETS / name)) == ()


def misread(monkeypatch, kind: str, attr: str, dimension) -> None:
    """Make the MJCF walker give every `kind`'s `attr` the wrong `dimension`.

    Every attribute's slots are made by ``_Walker.add_forms``, whether asked for one attribute at a time
    (``add``) or by a plan (``add_each``): the forms it is given carry each attribute's dimension.
    """
    real = mjcf._Walker.add_forms

    def wrong(self, kind_, elem, ident, path, forms, *args, **kwargs):
        if kind_ == kind:
            forms = tuple((f[0], f[1], dimension, *f[3:]) if f[0] == attr else f for f in forms)
        return real(self, kind_, elem, ident, path, forms, *args, **kwargs)

    monkeypatch.setattr(mjcf._Walker, "add_forms", wrong)


def test_a_wrong_dimension_given_on_purpose_is_found(box, monkeypatch):
    misread(monkeypatch, "geom", "density", dim("M L^-2"))  # a density read as a mass per area
    causes = check_dimensions(load_quiet(box))
    assert causes
    assert {c.kind for c in causes} == {"dimension"}
    elements = {c.element for c in causes}
    assert "body 'box' mass" in elements  # computed from the density: M L^-2 * L^3 is no mass
    assert "body 'arm' mass" not in elements  # given as a mass
    assert all("s^" in c.detail for c in causes)


def test_a_wrong_dimension_of_a_copied_number_is_found(box, monkeypatch):
    # the reader's joint range as a length, while the probe is scaled by lengths: held against the
    # compiled subtree mass nothing changes, but the range's own stored copy takes the power the probe
    # gave it; the check compares it with the parameter's dimension as the table lists it
    model = load_quiet(box)
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    probe = model.scaled(lengths, 4).runner.stored_numbers()
    original = model.runner.stored_numbers()
    assert dimension_causes(model, lengths, original, probe) == []
    probe["jnt_range"] = probe["jnt_range"] * 4  # as if the engine had stored the range as a length
    (cause,) = dimension_causes(model, lengths, original, probe)
    assert cause.kind == "dimension"
    assert cause.element == "joint 'hinge' range"
    assert "s^0" in cause.detail
    assert "s^1" in cause.detail


def test_audit_reports_a_dimension_cause(box, monkeypatch):
    misread(monkeypatch, "geom", "size", dim("L^2"))
    model = load_quiet(box)
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    kinds = [c.kind for c in engines.audit(model, sc, s=2).causes]
    assert "dimension" in kinds


def test_audit_finds_no_dimension_cause_in_a_sound_file(box):
    model = load_quiet(box)
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1, "T": 1})
    assert "dimension" not in [c.kind for c in engines.audit(model, sc, s=2).causes]


def test_check_dimensions_refuses_what_is_no_model():
    with pytest.raises(pt.InvalidRequestError, match="EngineModel"):
        check_dimensions("robot.xml")
