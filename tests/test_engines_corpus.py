"""The corpus: every MJCF model among gymnasium's MuJoCo assets, loaded, searched, scaled, saved, reloaded, verified.

Cross-cutting: it runs the whole engine path (engines.load, System, search, scaled, save, reload and
engines.verify) on files nobody wrote for pitheorem, rather than one module of pitheorem.engines.

For each model: load, system, search with gravity by s and time fixed, ``scaled(...).save(...)``, reload,
and ``engines.verify`` against the one-ulp sensitivity baseline.  The default run verifies every model at
s = 10 with a smooth open-loop control; the ``slow`` variant adds s = 2 and zero controls.

Two settings of gymnasium's files are not scale-free, and the tests set them in both runs (the scaled copy
cannot carry them over faithfully): MuJoCo's solver ``tolerance`` stops the iterations relative to a
normalisation that mixes M and M L^2 (set to 0: run every iteration, capped at :data:`ITERATIONS`, a pure
number), and the PGS solver of the two humanoids, which differs in rounding-amplified ways even at s = 2 (the
humanoids are also checked with the Newton solver).

Each model is loaded and searched once, each scaled copy saved and reloaded once, and each run verified
once for the whole module (the caches below): a test that asks for a run another test asked for (the s = 10
run with controls is in the default and the slow sweep) checks the same report again instead of
simulating it twice.
"""

from __future__ import annotations

import re
import warnings
from functools import cache
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt

mujoco = pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")
gymnasium = pytest.importorskip("gymnasium", reason="gymnasium is not installed (its MuJoCo assets are the corpus)")

from pitheorem import engines  # noqa: E402

ASSETS = Path(gymnasium.__file__).resolve().parent / "envs" / "mujoco" / "assets"
CORPUS = sorted(p.name for p in ASSETS.glob("*.xml"))
PGS = ("humanoid.xml", "humanoidstandup.xml")
#: the models that move in a horizontal plane (or float): gravity cannot act on their motion
PLANAR = ("point.xml", "reacher.xml", "swimmer.xml")


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    """Where this module's models are written: one folder, as the caches hold their files for every test."""
    return tmp_path_factory.mktemp("corpus")


def test_the_corpus_is_gymnasiums_fourteen_files():
    assert len(CORPUS) == 14


def load_quiet(path, **options):
    """engines.load without its warnings about elements it copies unchanged.

    gymnasium's files carry <numeric name="frame_skip">, custom data of no known dimension; two of
    pybullet_data's URDFs have compound meshes (tested on their own below).
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        return engines.load(path, **options)


def exhaustive(test):
    """The slow sweep of a test over models: s = 2 and 10, each with and without controls."""
    for mark in (
        pytest.mark.parametrize("controls", [False, True]),
        pytest.mark.parametrize("s", [2, 10]),
        pytest.mark.slow,
    ):
        test = mark(test)
    return test


def smooth(nu):
    return lambda t: 0.5 * np.sin(3.0 * t + np.arange(nu))


#: the constraint solver's iterations in every step of the corpus' runs (MuJoCo's ``opt.iterations``, 100 by
#: default): with the tolerance at 0 the solver runs on past convergence, about 86 iterations a step in the
#: walkers (RK4: four solves a step), most of the module's time.  A count is a pure number, the same in both
#: runs, so the copy does the same iterations as the original whatever the count.
ITERATIONS = 10


@cache
def searched(name: str, solver: str | None, folder: Path):
    """The corpus model `name` (solver tolerance 0, :data:`ITERATIONS` iterations, its solver replaced by
    `solver`) and its search, once."""
    text = re.sub(r'\s+iterations="\d+"', "", (ASSETS / name).read_text())
    text = text.replace("<option ", f'<option iterations="{ITERATIONS}" ', 1)
    if solver is not None:
        text = text.replace('solver="PGS"', f'solver="{solver}"')
    path = folder / f"{solver}_{name}"
    path.write_text(text)
    model = load_quiet(path).with_values(tolerance=0)
    assert model.runner.mjmodel.opt.iterations == ITERATIONS
    return model, pt.search(model.system(), scale={"g": 1}, fixed=("t",))


@cache
def reloaded(name: str, solver: str | None, folder: Path, s):
    """The model scaled by its first scaling at `s`, saved and loaded again, once."""
    model, res = searched(name, solver, folder)
    place = folder / f"{Path(name).stem}_{solver}_{s}"
    place.mkdir()
    return load_quiet(model.scaled(res.scalings[0], s).save(place / f"scaled_{s}.xml"))


@cache
def verified(name: str, solver: str | None, folder: Path, s, controls: bool):
    model, res = searched(name, solver, folder)
    nu = model.runner.mjmodel.nu
    return engines.verify(
        model,
        res.scalings[0],
        s,
        duration=1.0,
        controls=smooth(nu) if controls else None,
        scaled=reloaded(name, solver, folder, s),
    )


def similar_or_unmoved(rep, name: str) -> None:
    """Within the yardstick, and "similar" unless the run moved nothing or gravity cannot act on it (then,
    rightly, inconclusive)."""
    assert rep.passed, str(rep)
    assert rep.similar or not rep.excited or name in PLANAR, str(rep)


def check(name, folder, s, controls, solver=None):
    model, res = searched(name, solver, folder)
    assert res.feasible
    sc = res.scalings[0]
    assert sc.exponent_of("L T^-2") == 1
    assert sc.exponent_of("T") == 0
    again = reloaded(name, solver, folder, s)
    assert again.parameter("g").value[0] == pytest.approx(model.parameter("g").value[0] * s, rel=1e-15)
    return verified(name, solver, folder, s, controls)


@pytest.mark.parametrize("name", [n for n in CORPUS if n not in PGS])
def test_corpus_model_is_similar_at_s10_with_controls(name, folder):
    rep = check(name, folder, 10, controls=True)
    if name in PLANAR:  # gravity cannot act on them: a gravity error cannot be seen, so never "similar"
        assert rep.passed, str(rep)
        assert rep.verdict == "inconclusive", str(rep)
        assert not any(c.caught for c in rep.controls if c.group == "g")
        return
    assert rep.similar, str(rep)


@pytest.mark.parametrize("name", PLANAR)
def test_planar_models_move_alike_under_any_gravity_in_plain_mujoco(name):
    """The oracle of their inconclusive verdicts, independent of pitheorem: gravity doubled in MuJoCo's own
    compiled model, under the same input, moves them by rounding only."""
    m = mujoco.MjModel.from_xml_path(str(ASSETS / name))
    runs = []
    for times in (1.0, 2.0):
        m.opt.gravity[:] = np.asarray(m.opt.gravity) * times
        d = mujoco.MjData(m)
        rows = []
        for i in range(round(1.0 / m.opt.timestep)):
            d.ctrl[:] = smooth(m.nu)(i * m.opt.timestep)
            mujoco.mj_step(m, d)
            rows.append(np.concatenate([d.qpos, d.qvel]))
        runs.append(np.array(rows))
    span = np.ptp(runs[0], axis=0).max()
    assert span > 1e-3  # they move
    assert np.abs(runs[1] - runs[0]).max() <= 1e-9 * span


@pytest.mark.parametrize("name", PGS)
def test_humanoids_are_similar_with_the_newton_solver(name, folder):
    rep = check(name, folder, 10, controls=True, solver="Newton")
    assert rep.similar, str(rep)


@pytest.mark.parametrize("name", PGS)
def test_humanoids_pgs_solver_is_not_scale_free(name, folder):
    # measured: at s = 2 (exact in binary) the PGS runs differ far beyond the one-ulp baseline
    rep = check(name, folder, 2, controls=True)
    assert not rep.similar


@pytest.mark.parametrize("name", CORPUS)
@exhaustive
def test_corpus_exhaustive(name, s, controls, folder):
    solver = "Newton" if name in PGS else None
    rep = check(name, folder, s, controls, solver=solver)
    similar_or_unmoved(rep, name)


# -- PyBullet: URDFs of pybullet_data, dropped from 1 m onto a ground plane ---------------------

URDFS = (
    "cartpole.urdf",
    "pendulum5.urdf",
    "sphere2.urdf",
    "sphere_small.urdf",
    "sphere_with_restitution.urdf",
    "soccerball.urdf",
    "cube.urdf",
    "cube_small.urdf",
    "lego/lego.urdf",
    "jenga/jenga.urdf",
    "table/table.urdf",
    "kuka_iiwa/model.urdf",
)

#: measured: not similar beyond the one-ulp baseline even at s = 2, and similar in the air (no contact): the
#: duck and the teddy are convex decompositions whose parts' collision margins changeDynamics cannot reach
#: (load warns); for r2d2 and TwoJointRobot, whose cylinders PyBullet turns into convex hulls, the cause is
#: not isolated
URDFS_NOT_SIMILAR = ("r2d2.urdf", "duck_vhacd.urdf", "teddy_vhacd.urdf", "TwoJointRobot_w_fixedJoints.urdf")
COMPOUND_MESHES = ("duck_vhacd.urdf", "teddy_vhacd.urdf")


def urdf_path(name) -> Path:
    pybullet_data = pytest.importorskip("pybullet_data")
    return Path(pybullet_data.getDataPath()) / name


@cache
def urdf_searched(name: str):
    """The URDF `name` dropped onto a ground plane, and its search, once."""
    # PyBullet's multibody damping (0.04) mixes dimensions and its split-impulse threshold (a length) cannot be
    # set from Python: both are switched off, in the original and in the scaled run alike; the solver's residual
    # threshold adds rows in rad/s to rows in m/s (no pure dimension): 0, so that every iteration runs
    model = load_quiet(urdf_path(name), base_position=(0, 0, 1), ground=True, damping=0.0, split_impulse=False)
    model = model.with_values(solverResidualThreshold=0.0)
    return model, pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]


@cache
def urdf_saved(name: str, folder: Path, s):
    """The scaled URDF's saved path, once."""
    model, sc = urdf_searched(name)
    place = folder / f"{name.replace('/', '_')}_{s}"
    place.mkdir()
    return model.scaled(sc, s).save(place / "scaled.urdf")


@cache
def urdf_verified(name: str, folder: Path, s, controls: bool):
    model, sc = urdf_searched(name)
    again = load_quiet(urdf_saved(name, folder, s))  # the saved settings beside the file set up the scaled scene
    nj = len(model.runner.control_dimensions())
    return again, engines.verify(
        model, sc, s, duration=1.0, controls=smooth(nj) if controls and nj else None, scaled=again
    )


def urdf_check(name, folder, s, controls):
    model, sc = urdf_searched(name)
    out = urdf_saved(name, folder, s)
    assert Path(f"{out}.settings.json").is_file()
    again, rep = urdf_verified(name, folder, s, controls)
    masses = [p for p in model.parameters if p.name.endswith("_mass")]
    for p in masses:  # the saved file holds the scaled masses
        assert again.parameter(p.name).value[0] == pytest.approx(p.value[0] * float(s) ** sc.exponent_of("M"))
    return rep


@pytest.mark.parametrize("name", URDFS)
def test_urdf_is_similar_at_s10_with_controls(name, folder):
    rep = urdf_check(name, folder, 10, controls=True)
    similar_or_unmoved(rep, name)  # a table has no joint to move


@pytest.mark.parametrize("name", URDFS_NOT_SIMILAR)
def test_urdf_known_not_similar(name, folder):
    """Not exact at s = 4 on the ground; where links carry shapes, the ignored link margins are named."""
    rep = urdf_check(name, folder, 4, controls=False)
    assert not rep.exact
    named = {c.kind for c in rep.causes}
    if name not in COMPOUND_MESHES:  # the duck and the teddy are one link: their margins are the compound's
        assert "setting" in named, rep.causes


@pytest.mark.parametrize("name", URDFS)
@exhaustive
def test_urdf_exhaustive(name, s, controls, folder):
    rep = urdf_check(name, folder, s, controls)
    similar_or_unmoved(rep, name)


@pytest.mark.parametrize("name", URDFS_NOT_SIMILAR)
def test_urdf_known_not_similar_is_similar_without_contact(name):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", engines.UnscalableModelWarning)
        model = engines.load(urdf_path(name), base_position=(0, 0, 1), damping=0.0, split_impulse=False)
    compound = [w for w in caught if "convex parts" in str(w.message)]
    assert bool(compound) == (name in COMPOUND_MESHES)
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    assert engines.verify(model, sc, 2, duration=1.0).similar  # in the air: the difference is in the contacts
