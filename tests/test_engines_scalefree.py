"""pitheorem.engines.verdicts.scalefree: the proof beside the verdict, with settings of no pure dimension made scale-free."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt

mujoco = pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

from pitheorem import engines  # noqa: E402
from pitheorem.engines.protocols import CountsIterations  # noqa: E402
from pitheorem.engines.verdicts.scalefree import ScaleFree, capped_ways, scale_free_options  # noqa: E402
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
    # the last way: both stopping rules at 0, and then the solver's iterations capped too, at the most the
    # original takes with its own tolerance; that cap parts the runs no later, so no smaller one is tried
    cap = str(model.runner.solver_iterations(500, engines.smooth_controls(model)))  # 1 s of 0.002 s steps
    assert free.settings == (("option tolerance", "0"), ("option noslip_tolerance", "0"), ("option iterations", cap))
    assert not free.exact
    t, where = free.first_divergence
    assert 0 < t <= 1.0
    assert where in rep.original.states
    assert "still part" in free.text()
    data = json.loads(format(rep, "json"))
    assert data["scale_free"]["exact"] is False
    assert data["scale_free"]["settings"] == {
        "option tolerance": "0",
        "option noslip_tolerance": "0",
        "option iterations": cap,
    }


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
        # the last way run, with where it parts: every setting changed, the iterations capped too
        assert free.settings[-2:] == (("flag nativeccd", "disable"), ("option iterations", "1"))


def capped_by_hand(iterations):
    """A change for plain_mujoco_runs_equal: tolerance 0 and a fixed count of iterations, by hand."""

    def change(m):
        m.opt.tolerance = 0.0
        m.opt.iterations = iterations

    return change


def test_a_fixed_count_of_iterations_proves_exact_what_a_tolerance_of_0_does_not():
    """The leg with a sliding shin under the issue's scaling (masses by 1/16, lengths by 4): with the tolerance at
    0 the two runs' line searches still stop at other iterations (MuJoCo's floor on the norm of the search
    direction, mujoco_minval_search); capped at the one iteration a step the original takes with its own
    tolerance, both do the same, and the copy is bit for bit the original, until a step where the original's
    first search direction is under the floor already (about 0.74 s): the proof then says where."""
    model, sc = searched(DATA / "slide_leg.xml")
    assert {b: sc.unit_change[b] for b in "MLT"} == {"M": -2, "L": 1, "T": 0}
    assert scale_free_options(model.runner) == [{"tolerance": 0.0}]
    assert capped_ways(model.runner, [{"tolerance": 0.0}], 300) == [{"tolerance": 0.0, "iterations": 1}]
    rep = engines.verify(model, sc, 4, duration=0.6)
    assert not rep.exact
    free = rep.scale_free
    assert free.exact
    assert free.settings == (("option tolerance", "0"), ("option iterations", "1"))
    assert (
        free.text()
        == "scale-free: with option tolerance 0, option iterations 1 in both runs the copy is bit for bit the original"
    )
    copy = model.scaled(sc, 4)
    n = len(rep.original) - 1
    assert not plain_mujoco_runs_equal(model, copy, sc, 4, n, scale_free_by_hand(None))
    assert plain_mujoco_runs_equal(model, copy, sc, 4, n, capped_by_hand(1))
    later = engines.verify(model, sc, 4, duration=1.0).scale_free
    assert not later.exact
    assert later.settings[-1] == ("option iterations", "1")  # the last cap tried, with where the runs part
    assert 0.6 < later.first_divergence[0] < 1.0


def test_caps_go_on_halving_while_each_parts_the_runs_later_than_the_one_before():
    """pybullet_data's minitaur_rainbow_dash_v1 in MuJoCo, the issue's scaling, 1 s under the smooth input: its
    original takes at most 5 iterations a step, and capped at 5 the runs still part (at step 3, later than with
    every iteration run: step 1); capped at 2 they are bit for bit, which the proof reports."""
    pybullet_data = pytest.importorskip("pybullet_data", reason="pybullet_data comes with the engines extra")
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = engines.load(
            Path(pybullet_data.getDataPath()) / "quadruped/minitaur_rainbow_dash_v1.urdf", engine="mujoco"
        )
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    u = engines.smooth_controls(model)
    n = 500  # 1 s of 0.002 s steps
    assert model.runner.variant(native_ccd=False).solver_iterations(n, u) == 5
    free = engines.verify(model, sc, 4, duration=1.0, controls=u).scale_free
    assert free.exact
    assert free.settings == (("option tolerance", "0"), ("flag nativeccd", "disable"), ("option iterations", "2"))
    # by hand: capped at 5 the runs part, capped at 2 they do not
    copy = model.scaled(sc, 4)

    def capped_no_ccd(cap):
        def change(m):
            m.opt.tolerance = 0.0
            m.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_NATIVECCD)
            m.opt.iterations = cap

        return change

    assert not plain_mujoco_runs_equal(model, copy, sc, 4, n, capped_no_ccd(5), controls=u)
    assert plain_mujoco_runs_equal(model, copy, sc, 4, n, capped_no_ccd(2), controls=u)


@pytest.mark.parametrize("tolerance", [1e-8, 0.0])
def test_a_runner_counts_the_most_iterations_a_step_takes(tolerance):
    """Two legs apart (two islands of the solver; the second, heavier and driven, takes more iterations): capped
    at the count, a run is the run as written bit for bit; capped one lower, it is not."""
    model = engines.load(DATA / "two_legs.xml")
    runner = model.runner.variant(tolerance=tolerance)
    u = engines.smooth_controls(model)
    assert isinstance(runner, CountsIterations)
    most = runner.solver_iterations(300, u)
    assert 1 < most < runner.mjmodel.opt.iterations  # at 0, the line search's floor stops it short
    assert np.array_equal(runner.variant(iterations=most).run(300, u), runner.run(300, u))
    assert not np.array_equal(runner.variant(iterations=most - 1).run(300, u), runner.run(300, u))
    assert runner.variant(iterations=most - 1).solver_iterations(300, u) == most - 1
    assert runner.solver_iterations(0, u) == 0


def test_caps_halve_down_to_one_and_are_tried_only_where_a_tolerance_is_set_to_0():
    model = engines.load(DATA / "slide_leg.xml")
    runner = model.runner.variant(tolerance=0.0)  # every iteration it may: its own count is the floor's
    assert [w["iterations"] for w in capped_ways(runner, [{"tolerance": 0.0}], 300)] == [2, 1]
    assert [
        w["iterations"]
        for w in capped_ways(model.runner.variant(iterations=100, tolerance=0.0), [{"tolerance": 0.0}], 1000)
    ] == [2, 1]
    box = engines.load(DATA / "contact.xml").runner  # its file sets the tolerance to 0: 100 iterations a step
    assert [w["iterations"] for w in capped_ways(box, [{"tolerance": 0.0}], 200)] == [100, 50, 25, 12, 6, 3, 1]
    assert capped_ways(model.runner, [{"native_ccd": False}], 300) == []  # no tolerance set to 0: no cap
    assert capped_ways(model.runner, [], 300) == []


def test_a_runner_that_does_not_count_its_iterations_is_not_capped():
    pytest.importorskip("pybullet", reason="pybullet is not installed (pip install 'pitheorem[engines]')")
    runner = engines.load(engines.example_path("hinged_rod.urdf")).runner  # a URDF runs in PyBullet
    assert not isinstance(runner, CountsIterations)
    assert capped_ways(runner, [{"tolerance": 0.0}], 10) == []
