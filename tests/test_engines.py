"""Engines: hidden-constant catalogue and searches (always), PyBullet and MuJoCo runs (with the extra)."""

from __future__ import annotations

import math
import pickle
import subprocess
import sys
from fractions import Fraction
from pathlib import Path
from types import SimpleNamespace

import pytest

import pitheorem as pt
from pitheorem.engines import (
    CATALOGUE,
    ENGINES,
    broken_constants,
    engine_search,
    hidden_constants,
    simulate_rod,
    verify_engine_similarity,
    with_hidden_constants,
)
from pitheorem.engines.packages import PACKAGES, check_engine, engine_module
from pitheorem.engines.rod import EngineUnavailableError, rod_mjcf

ROD = pt.models.hinged_rod()
#: the paper's Figure 5 scaling: g by s, l by 1/s with m and k_theta held, hence c_theta by 1/s and t by 1/s
FIG5 = pt.search(ROD.system, scale={"g": 1, "l": -1}, fixed=("m", "k_theta")).scalings[0]
#: every minimal scaling of g by s that leaves time alone
TIME_FREE = pt.search(ROD.system, scale={"g": 1}).scalings
#: the forum rule "scale length with gravity": g and l both by s, nothing else (not a similarity
#: scaling). The paper's Section 3 text describes its Figure 3 this way, but the program behind
#: Figure 3 divides l by s (docs/explanation/errata.md, erratum 6).
LENGTH_WITH_GRAVITY = {"g": 1, "l": 1}

#: stated tolerances: a similarity scaling reproduces the engine's own run to rounding error
AGREE = 1e-10
#: ... while a broken one differs by far more than that
DIFFER = 1e-3

REPO = Path(__file__).resolve().parents[1]

@pytest.fixture(params=ENGINES)
def engine(request):
    pytest.importorskip(PACKAGES[request.param],
                        reason=f"{PACKAGES[request.param]} is not installed (pip install 'pitheorem[engines]')")
    return request.param


# -- catalogue (no engine needed) ------------------------------------------------------------


def test_catalogue_entries_are_complete():
    names = [c.name for c in CATALOGUE]
    assert len(names) == len(set(names))
    for c in CATALOGUE:
        assert c.engine in ENGINES
        assert c.name.isidentifier()
        assert c.name.startswith(c.engine + "_")
        assert isinstance(c.dimension, pt.Dimension)
        assert c.source
        assert c.where
        assert c.note


@pytest.mark.parametrize(
    ("name", "dimension", "default"),
    [
        ("bullet_time_step", "T", 1 / 240),
        ("bullet_collision_margin", "L", 0.001),
        ("bullet_contact_breaking_threshold", "1", 0.02),
        ("bullet_contact_slop", "L", 1e-5),
        ("bullet_solver_residual_threshold", "L^2 T^-2", 1e-7),
        ("bullet_max_joint_velocity", "T^-1", 100.0),
        ("bullet_max_prismatic_joint_velocity", "L T^-1", 100.0),
        ("bullet_contact_erp", "1", 0.08),
        ("bullet_linear_sleep_threshold", "L T^-1", 0.8),
        ("bullet_angular_sleep_threshold", "T^-1", 1.0),
        ("bullet_linear_damping_k1", "T^-1", 0.04),
        ("mujoco_timestep", "T", 0.002),
        ("mujoco_solref_timeconst", "T", 0.02),
        ("mujoco_solimp_width", "L", 0.001),
        ("mujoco_geom_margin", "L", 0.0),
        ("mujoco_ccd_tolerance", "L", 1e-6),
        ("mujoco_tolerance", "1", 1e-8),
    ],
)
def test_catalogue_values(name, dimension, default):
    (c,) = hidden_constants(names=[name])
    assert c.dimension == pt.Dimension.parse(dimension)
    assert c.default == pytest.approx(default)


def test_catalogue_is_read_whole_and_exactly_from_its_data_file():
    # the values a float literal cannot show at a glance, compared exactly (not approx)
    assert ENGINES == ("bullet", "mujoco")
    assert [c.engine for c in CATALOGUE] == sorted(c.engine for c in CATALOGUE)  # the file's order, by engine
    assert len(hidden_constants("bullet")) == 23
    assert len(hidden_constants("mujoco")) == 18
    assert hidden_constants(names=["bullet_time_step"])[0].default == 1 / 240
    assert hidden_constants(names=["mujoco_angle_unit"])[0].default == math.pi / 180
    assert math.isnan(hidden_constants(names=["bullet_default_motor_impulse"])[0].default)
    assert hidden_constants(names=["bullet_split_impulse_penetration_threshold"])[0].default == -0.04
    # the shared source texts are filled in: no placeholder is left, and each reaches the entries naming it
    assert not any("{" in c.source or "}" in c.source for c in CATALOGUE)
    multibody = [c.name for c in CATALOGUE if c.source.startswith("bullet3 src/BulletDynamics/Featherstone/btMultiBody")]
    assert len(multibody) == 9
    assert hidden_constants(names=["mujoco_timestep"])[0].source == (
        "mujoco 4.0.0 model defaults (MjModel.opt, MjSpec.default); MuJoCo XML Reference (mujoco.readthedocs.io), "
        "option/timestep")
    assert hidden_constants(names=["bullet_collision_margin"])[0].source.startswith(
        "measured with pybullet 3.2.7 (getPhysicsEngineParameters / getDynamicsInfo): getDynamicsInfo(...)[11]")


def test_hidden_constants_filters():
    assert all(c.engine == "mujoco" for c in hidden_constants("mujoco"))
    assert all(not c.dimension.is_dimensionless for c in hidden_constants("bullet", dimensional=True))
    assert all(c.dimension.is_dimensionless for c in hidden_constants("bullet", dimensional=False))


def test_hidden_constants_bad_inputs():
    with pytest.raises(pt.InvalidRequestError, match="'ode'"):
        hidden_constants("ode")
    with pytest.raises(pt.UnknownVariableError, match="bullet_timestep"):
        hidden_constants("bullet", names=["bullet_timestep"])


def test_with_hidden_constants_adds_dimensional_ones():
    ext = with_hidden_constants(ROD.system, "bullet")
    added = ext.variables[len(ROD.system.variables):]
    assert added == tuple(c.name for c in hidden_constants("bullet", dimensional=True))
    assert ext.dimension("bullet_linear_damping_k2") == pt.Dimension.parse("L^-1")
    with pytest.raises(pt.DuplicateVariableError, match="mujoco_timestep"):
        with_hidden_constants(pt.System({"mujoco_timestep": "T"}), "mujoco")
    with pytest.raises(pt.InvalidRequestError, match="System"):
        with_hidden_constants({"l": "L"}, "mujoco")


def test_engine_search_shows_the_engine_breaks_every_gravity_scaling():
    # with Bullet's length and time constants fixed, no unit change may touch L or T: g cannot move
    res = engine_search(ROD.system, "bullet", {"g": 1})
    assert not res.feasible
    assert set(res.certificate.exponents) <= {"g", "t", *(c.name for c in CATALOGUE)}


def test_engine_search_with_only_the_time_step_keeps_the_time_free_answers():
    res = engine_search(ROD.system, "mujoco", {"g": 1}, names=["mujoco_timestep"])
    assert res.feasible
    assert res.n_scalings == len(TIME_FREE)


def test_broken_constants_of_the_papers_scaling():
    broken = {c.name for c in broken_constants(FIG5, "bullet")}
    assert "bullet_time_step" in broken
    assert "bullet_linear_damping_k1" in broken
    assert {"mujoco_timestep", "mujoco_solref_timeconst"} <= {c.name for c in broken_constants(FIG5, "mujoco")}
    # zero defaults and dimensionless constants are never broken
    assert "mujoco_geom_margin" not in {c.name for c in broken_constants(FIG5, "mujoco")}


def test_broken_constants_of_a_time_free_scaling():
    lengths = next(sc for sc in TIME_FREE if sc.unit_change == {"M": 0, "L": 1, "T": 0})
    names = {c.name for c in broken_constants(lengths, "bullet")}
    assert "bullet_time_step" not in names
    assert {"bullet_collision_margin", "bullet_linear_damping_k2"} <= names
    assert lengths.exponent_of("L^-1") == Fraction(-1)


def test_broken_constants_needs_a_scaling():
    with pytest.raises(pt.InvalidRequestError, match="Scaling"):
        broken_constants({"g": 1}, "bullet")
    sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1})
    look_alike = SimpleNamespace(system=sc.system, powers=sc.vector, exponent_of=sc.exponent_of,
                                 unit_change=sc.unit_change)  # what the old attribute check accepted
    with pytest.raises(pt.InvalidRequestError, match="needs a Scaling, got SimpleNamespace"):
        broken_constants(look_alike, "bullet")


def test_engine_unavailable_error_message_and_pickle():
    err = EngineUnavailableError("mujoco", "mujoco")
    assert isinstance(err, pt.PiTheoremError)
    assert isinstance(err, ImportError)
    assert "pitheorem[engines]" in str(err)
    assert str(pickle.loads(pickle.dumps(err))) == str(err)


def test_the_rods_default_time_steps_are_the_catalogues():
    from pitheorem.engines.rod import DEFAULT_TIME_STEP

    assert dict(DEFAULT_TIME_STEP) == {"bullet": 1 / 240, "mujoco": 0.002}
    assert rod_mjcf(ROD.defaults).count('timestep="0.002"') == 1


def test_each_engine_names_its_package_in_one_place(monkeypatch):
    # the catalogue's engines are the engines with a package, and every reader of an engine name agrees
    assert tuple(PACKAGES) == ENGINES == ("bullet", "mujoco")
    assert PACKAGES["bullet"] == "pybullet"
    for call in (lambda: check_engine("ode"), lambda: engine_module("ode"), lambda: hidden_constants("ode"),
                 lambda: simulate_rod("ode")):
        with pytest.raises(pt.InvalidRequestError) as caught:
            call()
        assert str(caught.value) == "unknown engine 'ode'; use 'bullet' or 'mujoco'"
        assert caught.value.culprit == "ode"
    with pytest.raises(pt.InvalidRequestError, match="unknown engine 3"):
        check_engine(3)
    # a missing package is named in the error, as the one list has it
    monkeypatch.setitem(sys.modules, "pybullet", None)  # import pybullet now raises ImportError
    with pytest.raises(EngineUnavailableError) as caught:
        engine_module("bullet")
    assert (caught.value.engine, caught.value.package, caught.value.culprit) == ("bullet", "pybullet", "bullet")
    assert str(caught.value) == 'engine \'bullet\' needs the Python package \'pybullet\': pip install "pitheorem[engines]"'


def test_rod_mjcf_bad_inputs():
    with pytest.raises(pt.InvalidRequestError, match="'Verlet'"):
        rod_mjcf(ROD.defaults, integrator="Verlet")
    with pytest.raises(pt.InvalidRequestError, match="'theta_r'"):
        rod_mjcf({"m": 1, "l": 1, "g": 1, "k_theta": 1, "c_theta": 1})


def test_core_does_not_import_engines():
    code = "import sys, pitheorem; print(any(m.startswith(('pitheorem.engines', 'pybullet', 'mujoco')) for m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=REPO)
    assert out.stdout.strip() == "False"


# -- runs in the engines ---------------------------------------------------------------------


def test_unknown_engine_and_options():
    with pytest.raises(pt.InvalidRequestError, match="'ode'"):
        simulate_rod("ode")
    with pytest.raises(pt.InvalidRequestError, match="integrator"):
        simulate_rod("bullet", integrator="RK4")
    with pytest.raises(pt.InvalidRequestError, match="engine_defaults"):
        simulate_rod("mujoco", engine_defaults=True)


def test_original_run_is_close_to_the_ode(engine):
    rep = verify_engine_similarity(engine, TIME_FREE[0], s=2)
    # a first-order engine at its default step: within 0.05 rad and rad/s of the exact solution
    assert rep.engine_vs_ode < 0.05
    assert rep.original.t[1] == pytest.approx({"bullet": 1 / 240, "mujoco": 0.002}[engine])


@pytest.mark.parametrize("s", [2, 10])
@pytest.mark.parametrize("k", range(len(TIME_FREE)))
def test_time_free_scalings_agree(engine, s, k):
    rep = verify_engine_similarity(engine, TIME_FREE[k], s=s, tol=AGREE, compare_ode=False)
    assert not rep.scaled_dt
    assert rep.passed, str(rep)


@pytest.mark.parametrize("s", [2, 10])
def test_papers_figure5_scaling_agrees_with_the_step_scaled(engine, s):
    rep = verify_engine_similarity(engine, FIG5, s=s, tol=AGREE)
    assert rep.passed, str(rep)
    assert rep.dt_scaled == pytest.approx(rep.dt / s)
    assert rep.ode_report.passed


def test_papers_figure5_scaling_fails_with_the_engines_step(engine):
    rep = verify_engine_similarity(engine, FIG5, s=10, scale_dt=False)
    assert rep.max_deviation > DIFFER
    assert rep.ode_report.passed  # the ODE itself is similar: the fixed step is what breaks it


@pytest.mark.parametrize("s", [2, 10])
def test_papers_figure3_scaling_does_not_agree(engine, s):
    rep = verify_engine_similarity(engine, LENGTH_WITH_GRAVITY, s=s, check=False)
    assert not rep.is_similarity
    assert rep.max_deviation > 0.1
    assert not rep.ode_report.passed


def test_bullet_default_damping_breaks_a_length_scaling():
    pytest.importorskip("pybullet", reason="pybullet is not installed (pip install 'pitheorem[engines]')")
    lengths = next(sc for sc in TIME_FREE if sc.unit_change == {"M": 0, "L": 1, "T": 0})
    clean = verify_engine_similarity("bullet", lengths, s=2, tol=AGREE, compare_ode=False)
    default = verify_engine_similarity("bullet", lengths, s=2, tol=AGREE, compare_ode=False, engine_defaults=True)
    assert clean.passed
    assert default.max_deviation > DIFFER


def test_mujoco_rk4_is_close_to_the_ode():
    pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")
    rep = verify_engine_similarity("mujoco", FIG5, s=2, integrator="RK4", tol=AGREE)
    assert rep.passed
    assert rep.engine_vs_ode < 1e-6


def test_bullet_prints_no_banner():
    pytest.importorskip("pybullet", reason="pybullet is not installed (pip install 'pitheorem[engines]')")
    code = "from pitheorem.engines import simulate_rod; simulate_rod('bullet', t_final=0.01)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=REPO)
    assert out.stdout == ""
    assert out.stderr == ""
