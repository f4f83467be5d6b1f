"""engines.audit: every number the engine holds against the original times its factor, without simulating."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt

mujoco = pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

from pitheorem import engines  # noqa: E402

DATA = Path(__file__).resolve().parent / "data" / "engines"


def searched(path, **values):
    model = engines.load(path)
    if values:
        model = model.with_values(**values)
    return model, pt.search(model.system(), scale={"g": 1}).scalings[0]


def kinds(audit):
    return sorted({c.kind for c in audit.causes})


@pytest.mark.parametrize("s", [4, 10, 0.25])
def test_a_faithful_copy_has_no_cause_once_the_solver_runs_exactly(s):
    model, sc = searched(DATA / "contact.xml")  # tolerance 0 in the file
    audit = engines.audit(model, sc, s)
    assert audit.causes == ()
    assert audit.compared > 100


def test_the_default_tolerance_is_named_a_solver_cause_and_tolerance_zero_removes_it():
    model, sc = searched(engines.example_path("pendulum.xml"))
    assert kinds(engines.audit(model, sc, 10)) == ["solver"]
    assert "tolerance" in engines.audit(model, sc, 10).causes[0].element
    exact_model, sc0 = searched(engines.example_path("pendulum.xml"), tolerance=0)
    assert engines.audit(exact_model, sc0, 10).causes == ()


def test_a_mass_left_unscaled_is_named_with_both_numbers():
    model, sc = searched(DATA / "contact.xml")
    name = "geom2_density"  # the box's geom: its body's mass comes from it
    factor = model.parameter(name).factor(sc, 10)
    assert factor != 1.0
    wrong = model.scaled(sc, 10).multiplied(**{name: 1 / factor})  # the box keeps its original density
    audit = engines.audit(model, sc, 10, scaled=wrong)
    unscaled = [c for c in audit.causes if c.kind == "unscaled"]
    assert unscaled
    assert any("body 'box'" in c.detail for c in unscaled if c.element == "body_mass")
    # what MuJoCo holds: the scaled volume times the original density; what it should: the scaled mass
    held = wrong.parameter("body_box_mass").value[0]
    should = model.parameter("body_box_mass").value[0] * model.parameter("body_box_mass").factor(sc, 10)
    detail = next(c.detail for c in unscaled if c.element == "body_mass")
    assert f"{held:.17g}" in detail
    assert f"{should:.17g}" in detail


def test_mesh_vertices_kept_in_float32_are_a_precision_cause_except_at_powers_of_four():
    model, sc = searched(DATA / "mesh_drop.xml")
    at_ten = engines.audit(model, sc, 10)
    assert "precision" in kinds(at_ten)
    assert any(c.element == "mesh_vert" and "float32" in c.detail for c in at_ten.causes)
    # the counter-run: at a power of four every vertex is scaled exactly
    assert engines.audit(model, sc, 4).causes == ()
    assert engines.audit(model, sc, 0.25).causes == ()


def test_float32_numbers_rounded_at_a_power_of_two_whose_exponent_is_half_are_precision_not_unscaled():
    """At s = 2 a scaling whose lengths take s**(1/2) multiplies the wedge's vertices by 2**(1/2), which float32
    rounds: their mismatch (and the normals MuJoCo computes from them) is rounding, not a number computed otherwise,
    though s is a power of two."""
    model, sc = searched(DATA / "mesh_drop.xml")
    half = sc ** Fraction(1, 2)
    assert half.exponent_of(pt.Dimension.parse("L")) == Fraction(1, 2)
    # the oracle, in numpy: some vertex times 2**(1/2) is no float32 number
    vertices = np.array(model.parameter("mesh_wedge_uservert").value, dtype=np.float64)
    assert (vertices * 2**0.5 != (vertices * 2**0.5).astype(np.float32)).any()
    audit = engines.audit(model, half, 2)
    by_field = {c.element: c.kind for c in audit.causes}
    assert by_field["mesh_vert"] == "precision"
    assert by_field["mesh_normal"] == "precision"  # computed from the rounded vertices
    assert "unscaled" not in by_field.values()
    assert engines.audit(model, half, 4).causes == ()  # 4**(1/2) = 2: exact
    # where every float32 factor is a power of two, vertices that differ were not rounded: held wrong
    wrong = model.scaled(sc, 4).multiplied(mesh_wedge_uservert=1 + 1e-6)
    held_wrong = {c.element: c.kind for c in engines.audit(model, sc, 4, scaled=wrong).causes}
    assert held_wrong["mesh_vert"] == "unscaled"
    assert "precision" not in held_wrong.values()


def test_a_tendon_rest_length_left_to_mujoco_stays_a_sentinel():
    model, sc = searched(DATA / "spring_tendon.xml")
    p = model.parameter("tendon_spring_springlength")
    assert p.source == "derived"
    assert p.value[0] > 0
    scaled = model.scaled(sc, 10)
    assert scaled.runner.spec.tendons[0].springlength[0] == -1  # the file still asks MuJoCo to compute it
    assert scaled.runner.mjmodel.tendon_lengthspring[0][0] == pytest.approx(10 * p.value[0], rel=1e-14)
    assert engines.audit(model, sc, 10).causes == ()


def test_a_mixed_derived_number_is_named_when_it_is_no_power_of_the_probe(tmp_path):
    """A number the engine computes that no change of units carries is named, with its two values.

    The probe is independent of the audit: the same scaled spec compiled by MuJoCo at 4 and 1/4.
    """
    model, sc = searched(DATA / "spring_tendon.xml")
    # scale the tendon's rest length by hand into a sentinel-free number that ignores the scaling
    wrong = model.scaled(sc, 10).multiplied(tendon_spring_stiffness=3.0)
    audit = engines.audit(model, sc, 10, scaled=wrong)
    assert [c.element for c in audit.causes if c.kind == "unscaled"] == ["tendon_stiffness"]


def test_bad_arguments_are_named():
    model, sc = searched(engines.example_path("pendulum.xml"))
    with pytest.raises(pt.InvalidRequestError, match="EngineModel"):
        engines.audit("pendulum.xml", sc, 2)
    with pytest.raises(pt.InvalidRequestError, match="same engine"):
        engines.audit(model, sc, 2, scaled="copy")
    with pytest.raises(pt.PiTheoremError):
        engines.audit(model, sc, -1)
    with pytest.raises(pt.InvalidRequestError, match="scaling"):
        engines.audit(model, {"g": 1}, 2)


def test_the_audit_reads_as_text():
    model, sc = searched(engines.example_path("pendulum.xml"))
    text = str(engines.audit(model, sc, 10))
    assert text.startswith("audit at s = 10:")
    assert "solver: option tolerance" in text


def test_a_probe_the_engine_refuses_is_named_on_the_copys_side_and_passed_over_on_the_other(tmp_path):
    """A speck whose inertia sits just above mjMINVAL: the probe at 1/4 of its mass unit does not compile.  A
    copy lighter than the original (s = 1/2) is on its way to that floor: the refusal is its threshold cause,
    and nothing is compared.  A heavier one (s = 2) is not: the probe by 4 alone gives the exponents."""
    speck = tmp_path / "speck.xml"
    speck.write_text(
        '<mujoco><option timestep="0.002"/><worldbody><geom type="plane" size="1 1 0.1"/>'
        '<body pos="0 0 0.1"><freejoint/><geom type="sphere" size="0.01" mass="6e-11"/></body>'
        "</worldbody></mujoco>"
    )
    model = engines.load(speck)
    unit = pt.Scaling.from_unit_change(model.system(), {"M": 1})
    with pytest.raises(engines.EngineModelError, match="mjMINVAL"):  # independent of audit: MuJoCo refuses it
        model.scaled(unit, 0.25)
    lighter = engines.audit(model, unit, Fraction(1, 2))
    assert lighter.compared == 0
    refused = [c for c in lighter.causes if c.kind == "threshold"]
    assert [c.element for c in refused] == ["the probe at s = 1/4"]
    assert "mjMINVAL" in refused[0].detail
    heavier = engines.audit(model, unit, 2)
    assert heavier.compared > 0
    assert not [c for c in heavier.causes if c.kind in ("threshold", "unscaled", "dimension")]
    # the probe by 4 alone still sees a number the copy holds wrong: the speck's mass left as it was
    wrong = model.scaled(unit, 2).with_values(geom1_mass=6e-11)
    assert [c.kind for c in engines.audit(model, unit, 2, scaled=wrong).causes if c.kind == "unscaled"]


def test_the_probe_by_a_quarter_alone_gives_the_exponents_when_the_probe_by_four_is_refused(monkeypatch):
    """The other way round: a copy lighter than the original, and an engine that refuses the probe by 4 (made
    to here); the probe by 1/4 alone holds the copy to its factors, and catches a number left as it was."""
    model, sc = searched(engines.example_path("pendulum.xml"))
    right, wrong = model.scaled(sc, Fraction(1, 2)), model.scaled(sc, Fraction(1, 2)).multiplied(g=2)
    scaled = type(model).scaled

    def refusing_four(self, scaling, s, **options):
        if s == 4:
            raise engines.EngineModelError("probe", "", "refused for this test")
        return scaled(self, scaling, s, **options)

    monkeypatch.setattr(type(model), "scaled", refusing_four)
    clean = engines.audit(model, sc, Fraction(1, 2), scaled=right)
    assert clean.compared > 0
    assert not [c for c in clean.causes if c.kind in ("threshold", "unscaled", "dimension")]
    caught = engines.audit(model, sc, Fraction(1, 2), scaled=wrong)
    assert [c.element for c in caught.causes if c.kind == "unscaled"] == ["opt.gravity"]


def test_the_solver_cause_names_the_engines_own_setting_and_its_remedy():
    pybullet_data = pytest.importorskip("pybullet_data")
    cube = engines.load(
        Path(pybullet_data.getDataPath()) / "cube.urdf",
        ground=True,
        base_position=(0, 0, 1),
        damping=0.0,
        split_impulse=False,
    )
    sc = pt.search(cube.system(), scale={"g": 1}).scalings[0]
    solver = [c for c in engines.audit(cube, sc, 10).causes if c.kind == "solver"]
    assert [c.element for c in solver] == ["option solverResidualThreshold"]
    assert "with_values(solverResidualThreshold=0)" in solver[0].detail
    cube.with_values(solverResidualThreshold=0)  # the remedy it names is a call that works
    model, sc = searched(engines.example_path("pendulum.xml"))
    assert "with_values(tolerance=0)" in engines.audit(model, sc, 10).causes[0].detail


def test_a_vertex_that_is_the_rounding_residue_of_zero_is_held_to_nothing():
    """The hand's meshes have vertices near 1e-9 beside vertices of 0.1: no exponent to hold them to."""
    hand = Path(__file__).resolve().parent / "robots" / "mjcf" / "hand.xml"
    model, sc = searched(hand, tolerance=0)
    vertices = model.runner.mjmodel.mesh_vert
    tiny = (vertices != 0) & (abs(vertices) < 1e-6)
    assert tiny.any()  # the case: nonzero residues of the compiler's centring, independent of the audit
    assert engines.audit(model, sc, 4).causes == ()


def test_a_threshold_that_moves_with_the_time_step_is_no_cause(tmp_path):
    """A solref time constant below two time steps is clamped in the model and its copy alike."""
    stiff = tmp_path / "stiff.xml"
    stiff.write_text(
        '<mujoco><option timestep="0.004"/><worldbody><geom type="plane" size="1 1 0.1"/>'
        '<body pos="0 0 0.1"><freejoint/><geom type="sphere" size="0.05" solref="0.005 1"/></body>'
        "</worldbody></mujoco>"
    )
    model = engines.load(stiff)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    assert any("refsafe" in c.detail for c in engines.check(model))  # the clamp is there, check names it
    assert not any("refsafe" in c.detail for c in engines.audit(model, sc, 10).causes)


def test_the_copys_thresholds_are_the_same_whether_it_is_made_here_or_read_from_its_file(tmp_path):
    """The audit knows a copy made by model.scaled without reading it; a saved file is read: same causes."""
    model = engines.load(engines.example_path("superball.xml"))
    unit = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    copy = model.scaled(unit, 1e-3)  # SUPERball at 1 mm: its rolling friction falls below mjMINMU
    reread = engines.load(copy.save(tmp_path / "small.xml"))
    made, read = engines.audit(model, unit, 1e-3, scaled=copy), engines.audit(model, unit, 1e-3, scaled=reread)
    threshold = [c for c in made.causes if c.kind == "threshold"]
    assert any("mujoco_minmu" in c.detail for c in threshold)
    assert threshold == [c for c in read.causes if c.kind == "threshold"]


def test_a_number_of_no_power_is_a_cause_only_where_the_copy_holds_it_otherwise():
    """Issue 31: polygon normals the probes could not give an exponent, held bit for bit alike in the copy, were
    named 'unscaled'; only entries the copy changes can change a run."""
    from pitheorem.engines.verdicts.audit import held_otherwise

    before = np.array([[1.0, 0.0, 0.0], [0.0, 0.6, 0.8]])
    unclean = np.zeros_like(before, dtype=bool)  # every entry without an exponent
    assert not held_otherwise(before, before.copy(), unclean).any()
    moved = before.copy()
    moved[1, 1] = 0.61
    assert held_otherwise(before, moved, unclean).tolist() == [[False] * 3, [False, True, False]]
    assert not held_otherwise(before, moved, ~unclean).any()  # entries with an exponent are judged elsewhere
    nan = np.array([np.nan])
    assert not held_otherwise(nan, nan.copy(), np.array([False])).any()


VISUAL_AND_COLLISION = """<mujoco>
  <asset>
    <mesh name="look" vertex="0 0 0  1 0 0  0 1 0  0 0 1" scale="0.1 0.1 0.1"/>
    <mesh name="touch" vertex="0 0 0  1 0 0  0 1 0  0 0 1" scale="0.1 0.1 0.1"/>
  </asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="arm" pos="0 0 0.5"><joint name="hinge" axis="0 1 0"/>
      <geom name="seen" type="mesh" mesh="look" contype="0" conaffinity="0" group="1"/>
      <geom name="hit" type="mesh" mesh="touch" pos="0.2 0 0"/>
    </body>
  </worldbody>
</mujoco>"""


def test_numbers_no_step_reads_are_held_to_nothing_but_a_collision_geoms_are(tmp_path, monkeypatch):
    """A geom that never collides only draws: its stored pose, and its mesh's vertices and offset, move nothing.

    MuJoCo recomputes a visual mesh's centre from its scaled vertices and may land a few ulps off four times
    the original's (robosuite's UR5e: 9.05e-07 became 2.26e-07); that is no cause.  The same number of a geom
    that collides is one.
    """
    path = tmp_path / "arm.xml"
    path.write_text(VISUAL_AND_COLLISION)
    model = engines.load(path)
    runner = model.runner
    m = runner.mjmodel
    seen, hit = (mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, n) for n in ("seen", "hit"))
    look = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_MESH, "look")
    unread = runner.unread_stored()
    assert unread["geom_pos"].tolist() == [g == seen for g in range(m.ngeom)]
    assert unread["mesh_pos"].tolist() == [k == look for k in range(m.nmesh)]
    vert = unread["mesh_vert"]  # the vertices of the visual mesh only, each by the mesh that owns it
    start, count = m.mesh_vertadr[look], m.mesh_vertnum[look]
    assert vert[start : start + count].all()
    assert vert.sum() == count
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    model = model.with_values(tolerance=0)  # the solver's stopping rule is a cause of its own
    assert engines.audit(model, sc, 4).causes == ()
    copy = model.scaled(sc, 4)
    stored = type(copy.runner).stored_numbers

    def nudged(geom):
        def numbers(self):
            out = stored(self)
            if self is copy.runner:
                out["geom_pos"][geom, 2] = out["geom_pos"][geom, 2] * (1 + 1e-6) + 1e-6
            return out

        return numbers

    monkeypatch.setattr(type(copy.runner), "stored_numbers", nudged(seen))
    assert [c.element for c in engines.audit(model, sc, 4, scaled=copy).causes] == []
    monkeypatch.setattr(type(copy.runner), "stored_numbers", nudged(hit))
    assert [c.element for c in engines.audit(model, sc, 4, scaled=copy).causes] == ["geom_pos"]
    # a geom in an explicit <pair> collides, and one in the fluid model is pushed by it, whatever its contype
    for change in (
        ("</worldbody>", '</worldbody><contact><pair geom1="seen" geom2="floor"/></contact>'),  # its geom2
        ("</worldbody>", '</worldbody><contact><pair geom1="seen" geom2="hit"/></contact>'),  # its geom1
        ('group="1"', 'group="1" fluidshape="ellipsoid"'),
    ):
        path.write_text(VISUAL_AND_COLLISION.replace(*change))
        again = engines.load(path).runner.unread_stored()
        assert "geom_pos" not in again
        assert "mesh_pos" not in again


def test_a_number_derived_from_larger_ones_is_held_to_the_rounding_of_its_field():
    """A mesh's centre at 1e-8, which MuJoCo finds from vertices of 0.05, rounds at their size, not at its own:
    a probe off by a few ulps of the field's largest number still shows its power of 4, and in float32 fields
    the ulps are float32's.  A number off by more (a factor of 3 where 4 is due) is still no power of 4."""
    from pitheorem.engines.verdicts.audit import RESIDUE, _probe_exponents

    for dtype, small in ((np.float64, 1e-8), (np.float32, 1e-5)):  # each above its field's residue of a zero
        ulp = float(np.spacing(dtype(0.2)))
        before = np.array([0.05, small], dtype=dtype)
        off = np.array([0.2, 4 * float(before[1]) + 8 * ulp], dtype=dtype)  # 8 ulps of the largest, in its precision
        k, clean, _ = _probe_exponents(before, off)
        assert clean.tolist() == [True, True]
        assert k.tolist() == [1.0, 1.0]
        far = np.array([0.2, 3 * float(before[1])], dtype=dtype)
        assert _probe_exponents(before, far)[1].tolist() == [True, False]
        beyond = np.array([0.2, 4 * float(before[1]) + 8 * RESIDUE * ulp], dtype=dtype)  # far past the rounding
        assert _probe_exponents(before, beyond)[1].tolist() == [True, False]


def test_a_small_number_below_its_fields_float32_floor_that_scales_exactly_is_no_residue():
    """In float32 the residue floor of a field that holds a table's inertia (241) beside a block's (2.7e-5: the two
    bodies of Meta-World's block scene in MuJoCo Warp) lies above the block's; a probe that carries the block's by
    an exact power of 4 shows it is a number, not a residue of zero.  One the probe does not carry so stays one."""
    from pitheorem.engines.verdicts.audit import RESIDUE, _probe_exponents

    before = np.array([[0.0, 0.0, 0.0], [127.6, 241.0, 223.3], [2.6666667e-05] * 3], dtype=np.float32)
    floor = RESIDUE * float(np.spacing(np.float32(241.0)))
    assert before[2, 0] < floor  # the case: the block's inertia is below the field's floor
    probe = before * np.float32(1024.0)  # 4**5: exact in float32
    k, clean, residue = _probe_exponents(before, probe)
    assert clean.all()
    assert k[1:].tolist() == [[5.0] * 3] * 2
    assert not residue.any()
    noisy = probe.copy()
    noisy[2] = np.float32(3e-5)  # no power of 4, and small: a residue, held to nothing
    k, clean, residue = _probe_exponents(before, noisy)
    assert residue[2].all()
    assert clean[2].all()


def test_a_field_is_named_once_and_set_right_whole_where_numbers_are_held_wrong_and_rounded_otherwise():
    """A copy whose ball weighs twice what it should and whose box's density is off by 1e-12 relative: the
    box's mass is the original's times its factor but for rounding, which at s = 4 no number needs, and the
    ball's is wrong.  Each field is named once (for its wrong number), and its repair sets both right."""
    from pitheorem.engines.verdicts.audit import audited

    model = engines.load(engines.example_path("causes/contact.xml"))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    wrong = model.scaled(sc, 4).multiplied(geom1_mass=2.0, geom2_density=1 + 1e-12)
    found, repairs = audited(model, sc, 4, wrong)
    elements = [c.element for c in found.causes]
    assert "body_mass" in elements
    assert len(elements) == len(set(elements))
    box = model.runner.mjmodel.body("box").id
    held, original = wrong.runner.mjmodel.body_mass[box], model.runner.mjmodel.body_mass[box]
    factor = float(4 ** sc.exponent_of(pt.Dimension.parse("M")))
    assert held != original * factor  # the box's mass rounded otherwise ...
    assert repairs["body_mass"][box] == original * factor  # ... and set right with the ball's
