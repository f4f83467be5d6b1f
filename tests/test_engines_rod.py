"""pitheorem.engines.paper.rod: the paper's hinged rod in PyBullet and MuJoCo, against the exact ODE.

A similarity scaling reproduces the engine's own run to rounding error when
the engine's time step is scaled with time; the paper's Figure 3 scaling
(length with gravity) does not, and neither does a fixed step.
"""

from __future__ import annotations

import numpy as np
import pytest

import pitheorem as pt
from pitheorem import engines
from pitheorem.engines import (
    simulate_rod,
    verify_engine_similarity,
)
from pitheorem.engines.packages import PACKAGES
from pitheorem.engines.paper.rod import DEFAULT_TIME_STEP, ROD_FILES, rod_file_numbers, rod_model
from tests.conftest import FIG5, HINGED_ROD, TIME_FREE

#: the forum rule "scale length with gravity": g and l both by s, nothing else (not a similarity
#: scaling). The paper's Section 3 text describes its Figure 3 this way, but the program behind
#: Figure 3 divides l by s (docs/explanation/errata.md, erratum 6).
LENGTH_WITH_GRAVITY = {"g": 1, "l": 1}

#: stated tolerances: a similarity scaling reproduces the engine's own run to rounding error
AGREE = 1e-10

#: ... while a broken one differs by far more than that
DIFFER = 1e-3


@pytest.fixture(params=tuple(DEFAULT_TIME_STEP))  # the engines the rod is built in (MJX runs files only)
def engine(request):
    pytest.importorskip(
        PACKAGES[request.param], reason=f"{PACKAGES[request.param]} is not installed (pip install 'pitheorem[engines]')"
    )
    return request.param


def test_the_rods_default_time_steps_are_the_catalogues_and_the_files():
    assert dict(DEFAULT_TIME_STEP) == {"pybullet": 1 / 240, "mujoco": 0.002}
    for engine in PACKAGES.keys() & DEFAULT_TIME_STEP.keys():
        pytest.importorskip(PACKAGES[engine], reason=f"{PACKAGES[engine]} is not installed")
        assert engines.load(engines.example_path(ROD_FILES[engine])).timestep() == DEFAULT_TIME_STEP[engine]


def _mujoco_numbers(model):
    """What MuJoCo compiled from the rod's file: the oracle is the engine, not the file's table."""
    m = model.runner.mjmodel
    return {
        "m": m.body_mass[1],
        "com": tuple(m.body_ipos[1]),
        "inertia": tuple(m.body_inertia[1]),
        "g": -m.opt.gravity[2],
        "k_theta": m.jnt_stiffness[0],
        "theta_r": m.qpos_spring[0],
        "c_theta": m.dof_damping[0],
    }


def _bullet_numbers(model):
    """What PyBullet holds once the rod is loaded and set, and the spring the settings file gives."""
    dyn, joints = model.runner._held()
    spring = model.settings()["jointSprings"][0]
    return {
        "m": dyn[1][0],
        "com": tuple(dyn[1][3]),
        "inertia": tuple(dyn[1][2]),
        "g": -model.settings()["gravity"][2],
        "k_theta": spring["stiffness"],
        "theta_r": spring["restPosition"],
        "c_theta": joints[0][6],
    }


def _expected(p):
    i_com = p["m"] * p["l"] ** 2 / 12
    return {
        "m": p["m"],
        "com": (p["l"] / 2, 0.0, 0.0),
        "inertia": (i_com,) * 3,
        "g": p["g"],
        "k_theta": p["k_theta"],
        "theta_r": p["theta_r"],
        "c_theta": p["c_theta"],
    }


@pytest.mark.parametrize(
    "params", [None, {"m": 0.25, "l": 0.3, "g": 3.7, "k_theta": 7.0, "c_theta": 0.5, "theta_r": -0.2}]
)
def test_the_shipped_files_hold_the_papers_rod(engine, params):
    p = HINGED_ROD.resolve_params(params)
    numbers = (_mujoco_numbers if engine == "mujoco" else _bullet_numbers)(rod_model(engine, params))
    want = _expected(p)
    for name, value in want.items():
        assert numbers[name] == pytest.approx(value, rel=1e-15, abs=1e-15), name
    if params is None:  # the files themselves: the paper's values as written
        assert numbers == {n: pytest.approx(v, rel=0, abs=1e-15) for n, v in want.items()}


def test_rod_model_bad_inputs():
    with pytest.raises(pt.InvalidRequestError, match="'Verlet'"):
        rod_model("mujoco", integrator="Verlet")
    with pytest.raises(pt.InvalidRequestError, match="'theta_r'"):
        rod_file_numbers("mujoco", {"m": 1, "l": 1, "g": 1, "k_theta": 1, "c_theta": 1})
    with pytest.raises(pt.InvalidRequestError, match="'mjx'"):
        rod_file_numbers("mjx", HINGED_ROD.defaults)


def _stepped_in_python(p, y0, dt, n_steps):
    """The oracle: the rod written out here as MJCF text and stepped with mj_step, one step at a time."""
    mujoco = pytest.importorskip("mujoco", reason="mujoco is not installed")
    i = p["m"] * p["l"] ** 2 / 12
    text = (
        f'<mujoco><compiler angle="radian"/><option timestep="{dt!r}" gravity="0 0 {-p["g"]!r}">'
        '<flag contact="disable"/></option><worldbody><body>'
        f'<joint type="hinge" axis="0 1 0" stiffness="{p["k_theta"]!r}" springref="{p["theta_r"]!r}" '
        f'damping="{p["c_theta"]!r}"/><inertial pos="{p["l"] / 2!r} 0 0" mass="{p["m"]!r}" '
        f'diaginertia="{i!r} {i!r} {i!r}"/></body></worldbody></mujoco>'
    )
    m = mujoco.MjModel.from_xml_string(text)
    d = mujoco.MjData(m)
    d.qpos[0], d.qvel[0] = y0
    rows = [(d.qpos[0], d.qvel[0])]
    for _ in range(n_steps):
        mujoco.mj_step(m, d)
        rows.append((d.qpos[0], d.qvel[0]))
    return np.array(rows)


def test_simulate_rod_is_mujoco_stepping_the_rod_bit_for_bit():
    p = HINGED_ROD.resolve_params({"l": 0.5, "k_theta": 20.0})
    run = simulate_rod("mujoco", p, (0.3, -1.0), t_final=0.2)
    assert np.array_equal(run.y, _stepped_in_python(p, (0.3, -1.0), 0.002, 100))


def test_unknown_engine_and_options():
    with pytest.raises(pt.InvalidRequestError, match="'ode'"):
        simulate_rod("ode")
    with pytest.raises(pt.InvalidRequestError, match="integrator"):
        simulate_rod("pybullet", integrator="RK4")
    with pytest.raises(pt.InvalidRequestError, match="engine_defaults"):
        simulate_rod("mujoco", engine_defaults=True)


def test_original_run_is_close_to_the_ode(engine):
    rep = verify_engine_similarity(engine, TIME_FREE[0], s=2)
    # a first-order engine at its default step: within 0.05 rad and rad/s of the exact solution
    assert rep.engine_vs_ode < 0.05
    assert rep.original.t[1] == pytest.approx({"pybullet": 1 / 240, "mujoco": 0.002}[engine])


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
    clean = verify_engine_similarity("pybullet", lengths, s=2, tol=AGREE, compare_ode=False)
    default = verify_engine_similarity("pybullet", lengths, s=2, tol=AGREE, compare_ode=False, engine_defaults=True)
    assert clean.passed
    assert default.max_deviation > DIFFER


def test_mujoco_rk4_is_close_to_the_ode():
    pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")
    rep = verify_engine_similarity("mujoco", FIG5, s=2, integrator="RK4", tol=AGREE)
    assert rep.passed
    assert rep.engine_vs_ode < 1e-6


def test_the_shipped_files_verify_like_a_users(engine):
    """The rod's files go through engines.load and engines.verify: at s = 4 bit for bit, and a broken copy fails."""
    model = engines.load(engines.example_path(ROD_FILES[engine]))
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    rep = engines.verify(model, lengths, s=4, duration=2.0, ensemble=1)
    assert rep.exact
    assert rep.excited
    spring = "joint_hinge_stiffness" if engine == "mujoco" else "joint_hinge_spring_stiffness"
    broken = model.scaled(lengths, 4).multiplied(**{spring: 1 / 16})  # the spring left as it was
    rep = engines.verify(model, lengths, s=4, duration=2.0, ensemble=1, scaled=broken)
    assert not rep.similar
    # named by the number the engine runs with: MuJoCo's compiled jnt_stiffness, the URDF run's spring
    assert [(c.kind, c.element) for c in rep.causes] == [
        ("unscaled", "jnt_stiffness" if engine == "mujoco" else "spring.stiffness")
    ]
