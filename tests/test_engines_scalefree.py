"""pitheorem.engines.verdicts.scalefree: the proof beside the verdict, with settings of no pure dimension made scale-free."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt

mujoco = pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

from pitheorem import engines  # noqa: E402
from pitheorem.engines.verdicts.scalefree import ScaleFree, scale_free_options  # noqa: E402
from tests.conftest import plain_mujoco_runs_equal, recorded_batches  # noqa: E402

DATA = Path(__file__).resolve().parent / "data" / "engines"


def searched(path):
    model = engines.load(path)
    return model, pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]


def scale_free_by_hand(solver):
    """A change for plain_mujoco_runs_equal: tolerance 0 by hand (and Newton where asked)."""

    def change(m):
        if solver == "Newton":
            m.opt.solver = int(mujoco.mjtSolver.mjSOL_NEWTON)
        m.opt.tolerance = 0.0
        m.opt.noslip_tolerance = 0.0

    return change


def test_a_solver_of_no_pure_dimension_is_proved_scale_free_beside_the_verdict(tmp_path):
    """A box on the floor under PGS with a tolerance: not bit for bit as written; with the tolerance at 0 it is
    (and Newton's steps at tolerance 0 are not: the way that is exact is the one reported)."""
    pgs = tmp_path / "pgs.xml"
    pgs.write_text((DATA / "contact.xml").read_text().replace('tolerance="0"', 'solver="PGS"'))
    model, sc = searched(pgs)
    rep = engines.verify(model, sc, 4, duration=0.4)
    assert not rep.exact
    free = rep.scale_free
    assert free.settings == (("option tolerance", "0"),)
    n_steps = len(rep.original) - 1
    copy = model.scaled(sc, 4)
    assert plain_mujoco_runs_equal(model, copy, sc, 4, n_steps, scale_free_by_hand(None))
    assert not plain_mujoco_runs_equal(model, copy, sc, 4, n_steps, scale_free_by_hand("Newton"))
    assert free.exact
    assert free.first_divergence is None
    assert free.text() in str(rep).splitlines()
    assert rep.verdict != "exact"  # the verdict stays what the model as written does


def test_a_run_that_parts_for_another_reason_says_where_even_when_scale_free():
    """The leg of the noslip test: its two stopping rules at 0 do not make it exact (a contact does)."""
    model, sc = searched(DATA / "noslip_leg.xml")
    rep = engines.verify(model, sc, 4, duration=1.0, controls=engines.smooth_controls(model))
    free = rep.scale_free
    quick = engines.verify(model, sc, 4, duration=1.0, controls=engines.smooth_controls(model), diagnose=False)
    assert quick.scale_free is None  # the verdict alone: no proof, no causes
    assert free.settings == (("option tolerance", "0"), ("option noslip_tolerance", "0"))
    assert not free.exact
    t, where = free.first_divergence
    assert 0 < t <= 1.0
    assert where in rep.original.states
    assert "still part" in free.text()
    data = json.loads(format(rep, "json"))
    assert data["scale_free"]["exact"] is False
    assert data["scale_free"]["settings"] == {"option tolerance": "0", "option noslip_tolerance": "0"}


def test_no_scale_free_run_where_the_runs_are_exact_or_cannot_be():
    model, sc = searched(engines.example_path("pendulum.xml"))
    u = engines.smooth_controls(model)
    assert engines.verify(model, sc, 4, duration=0.3, controls=u).scale_free is None  # exact as written
    assert engines.verify(model, sc, 10, duration=0.3, controls=u).scale_free is None  # no power of four
    assert scale_free_options(model.with_values(tolerance=0).runner) == []


def test_options_name_each_setting_of_no_pure_dimension():
    model = engines.load(engines.example_path("pendulum.xml"))
    assert scale_free_options(model.runner) == [{"tolerance": 0.0}]  # MuJoCo's default tolerance, 1e-8
    pgs = model.with_values(tolerance=0).runner.variant(solver="PGS")
    assert scale_free_options(pgs) == [{"solver": "Newton"}]
    assert ScaleFree((("option solver", "Newton"),), False, (0.5, "q")).text().endswith("first at t = 0.5 in q")


def test_the_diagnosis_reuses_the_scale_free_runs_as_its_counter_runs(tmp_path, monkeypatch):
    """Each way of the scale-free proof is also a counter-run of the diagnosis: it runs once, not twice."""
    from pitheorem.engines.runners.mujoco import MujocoRunner

    pgs = tmp_path / "pgs.xml"
    pgs.write_text((DATA / "contact.xml").read_text().replace('tolerance="0"', 'solver="PGS"'))
    model, sc = searched(pgs)
    batches = recorded_batches(monkeypatch, MujocoRunner)
    rep = engines.verify(model, sc, 4, duration=0.4)
    seen = [(float(r.mjmodel.opt.tolerance), int(r.mjmodel.opt.solver)) for jobs in batches for r, *_ in jobs]
    assert rep.scale_free is not None
    assert rep.causes
    pgs_id, newton = int(mujoco.mjtSolver.mjSOL_PGS), int(mujoco.mjtSolver.mjSOL_NEWTON)
    for way in ((0.0, pgs_id), (1e-8, newton), (0.0, newton)):  # the original and the copy, once each
        assert seen.count(way) == 2, way


def test_native_convex_collision_off_is_a_way_and_proves_two_meshes_exact():
    """A tetrahedron on a cube, both meshes, meet through MuJoCo's GJK/EPA: with the native path off in both
    runs (libccd's, whose tolerance scales with the copy) the copy is bit for bit the original."""
    model, sc = searched(DATA / "mesh_on_mesh.xml")
    runner = model.runner
    assert runner.uses_native_ccd()
    assert scale_free_options(runner) == [
        {"tolerance": 0.0},
        {"native_ccd": False},
        {"tolerance": 0.0, "native_ccd": False},
    ]
    assert not runner.variant(native_ccd=False).uses_native_ccd()  # the flag off: nothing goes through it
    rep = engines.verify(model, sc, 4, duration=1.0)
    assert not rep.exact
    assert rep.scale_free.exact
    assert rep.scale_free.settings == (("flag nativeccd", "disable"),)
    # by hand, in plain MuJoCo: both compiled models with the flag off, stepped side by side
    copy = model.scaled(sc, 4)

    def ccd_off(m):
        m.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_NATIVECCD)

    assert not plain_mujoco_runs_equal(model, copy, sc, 4, 500)
    assert plain_mujoco_runs_equal(model, copy, sc, 4, 500, ccd_off)


def test_native_convex_collision_off_is_tried_but_does_not_make_every_pair_exact():
    """The egg on its post (sphere against ellipsoid) parts under libccd too: the proof says where."""
    model, sc = searched(DATA / "egg_on_post.xml")
    rep = engines.verify(model, sc, 4, duration=1.0)
    assert {"native_ccd": False} in scale_free_options(model.runner)
    assert not rep.scale_free.exact
    assert ("flag nativeccd", "disable") in rep.scale_free.settings  # the last way: every setting changed
    # a pendulum's capsule on a plane meets it through a primitive function: no such way
    assert not engines.load(engines.example_path("pendulum.xml")).runner.uses_native_ccd()


@pytest.mark.parametrize(
    ("world", "geoms", "convex"),
    [
        ("", '<geom type="sphere" size="0.1"/>', False),  # sphere on the plane: mjc_PlaneSphere
        ("", '<geom type="ellipsoid" size="0.1 0.05 0.05"/>', False),  # on the plane: mjc_PlaneConvex
        # two geoms of one body never meet each other: each meets the plane through a primitive function
        (
            "",
            '<geom type="ellipsoid" size="0.1 0.05 0.05"/><geom type="box" size="0.1 0.1 0.1" pos="0 0 -0.3"/>',
            False,
        ),
        ('<geom type="box" size="0.1 0.1 0.1" pos="1 0 0"/>', '<geom type="ellipsoid" size="0.1 0.05 0.05"/>', True),
        ('<geom type="box" size="0.1 0.1 0.1" pos="1 0 0"/>', '<geom type="cylinder" size="0.1 0.05"/>', True),
        (  # the cylinder never collides
            '<geom type="box" size="0.1 0.1 0.1" pos="1 0 0"/>',
            '<geom type="cylinder" size="0.1 0.05" contype="0" conaffinity="0"/>',
            False,
        ),
    ],
)
def test_a_pair_goes_through_native_convex_collision_only_where_it_may_collide_through_no_primitive(
    tmp_path, world, geoms, convex
):
    path = tmp_path / "m.xml"
    path.write_text(
        f'<mujoco><worldbody><geom type="plane" size="1 1 0.1"/>{world}'
        f'<body pos="0 0 1"><freejoint/>{geoms}</body></worldbody></mujoco>'
    )
    assert engines.load(path).runner.uses_native_ccd() is convex


def test_the_collision_path_is_run_only_where_the_solvers_settings_do_not_prove_it(tmp_path):
    """The box under PGS, with a cylinder standing far off (so some pair may collide through MuJoCo's convex
    collision): the tolerance at 0 proves it exact, and native convex collision off is not run for the proof;
    the egg on its post is not proved by the solver's settings, so it is."""
    from pitheorem.engines.verdicts.scalefree import scale_free_run

    pgs = tmp_path / "pgs.xml"
    pgs.write_text(
        (DATA / "contact.xml")
        .read_text()
        .replace('tolerance="0"', 'solver="PGS"')
        .replace("</worldbody>", '<geom name="far" type="cylinder" size="0.1 0.2" pos="4 4 0.2"/></worldbody>')
    )
    for path, proved, n in ((pgs, True, 200), (DATA / "egg_on_post.xml", False, 500)):
        model, sc = searched(path)
        assert {"native_ccd": False} in scale_free_options(model.runner)
        copy = model.scaled(sc, 4)
        names, dims = model.runner.coordinate_dimensions()
        factors = 4 ** np.array([sc.exponent_of(d) for d in dims], dtype=float)
        ran: dict = {}
        free = scale_free_run(model.runner, copy.runner, n, None, None, factors, np.arange(n + 1) * 0.002, names, ran)
        assert free.exact is proved
        with_ccd_off = [key for key in ran if ("native_ccd", False) in key]
        assert bool(with_ccd_off) is not proved


def test_every_setting_changed_is_run_only_where_the_collision_path_alone_parts_the_runs_later(monkeypatch):
    """The egg on its post: native convex collision off alone parts its runs later than the tolerance at 0, so
    both changed are tried too; where it parts them no later, that last way is not run."""
    from pitheorem.engines.verdicts import scalefree
    from pitheorem.engines.verdicts.scalefree import _parts_later, scale_free_run

    a = np.zeros((4, 1))
    b = np.array([[0.0], [0.0], [1.0], [1.0]])
    c = np.array([[0.0], [1.0], [1.0], [1.0]])
    assert _parts_later((a, b), (a, c))
    assert not _parts_later((a, c), (a, b))
    assert _parts_later((a, a), (a, b))  # never parting is later than any step
    model, sc = searched(DATA / "egg_on_post.xml")
    copy = model.scaled(sc, 4)
    names, dims = model.runner.coordinate_dimensions()
    factors = 4 ** np.array([sc.exponent_of(d) for d in dims], dtype=float)
    both = (("native_ccd", False), ("tolerance", 0.0))
    for later in (True, False):
        monkeypatch.setattr(scalefree, "_parts_later", lambda pair, than, later=later: later)
        ran: dict = {}
        free = scale_free_run(model.runner, copy.runner, 500, None, None, factors, np.arange(501) * 0.002, names, ran)
        assert (both in ran) is later
        assert (("native_ccd", False),) in ran
        assert free.settings[-1] == ("flag nativeccd", "disable")  # the last way run, with where it parts
