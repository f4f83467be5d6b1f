"""Tests for pitheorem.models: the paper's models and parameter lists (the Model type: test_model.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pitheorem as pt
from matlab_ports import scaling_counterexample
from matlab_ports.rod_hinge_dynamics import theta_ddot
from pitheorem import models

ALL_MODELS = {
    "hinged_rod": models.hinged_rod,
    "hinged_rod_longitudinal": models.hinged_rod_longitudinal,
    "hinged_rod_longitudinal_no_damper": lambda: models.hinged_rod_longitudinal(damper=False),
    "spring_mass_damper": models.spring_mass_damper,
    "projectile": models.projectile,
}


# -- parameter lists ----------------------------------------------------------------------------


def test_rod_system_is_the_papers_nine_variables(rod):
    assert models.rod_system() == rod
    rod = models.rod_system()
    assert rod.variables == ("m", "theta_r", "l", "g", "k_theta", "c_theta", "t", "F", "tau")
    assert rod.n_groups == 6


def test_superball_parameters_are_section_4(superball):
    sb = models.superball_parameters()
    assert sb == superball
    # Section 4: scaling g and l by s needs no change of time (a pure change of the length unit)
    res = pt.search(sb, scale={"g": 1, "l": 1}, fixed=("t", "m"))
    assert res.feasible
    assert res.scalings[0].unit_change == {"M": 0, "L": 1, "T": 0}


# -- the shipped models -------------------------------------------------------------------------


def test_hinged_rod_matches_the_paper_and_its_matlab_code():
    rod = models.hinged_rod()
    assert rod.parameters == ("m", "l", "g", "k_theta", "c_theta", "theta_r")
    assert rod.states == ("theta", "omega")
    assert rod.time == "t"
    assert dict(rod.defaults) == {
        "m": 1.5,
        "l": 2.0,
        "g": 9.81,
        "k_theta": 100.0,
        "c_theta": 10.0,
        "theta_r": math.pi / 3,
    }
    assert dict(rod.initial) == {"theta": math.pi / 4, "omega": 0.0}
    assert str(rod.state_dimension("theta")) == "1"
    assert str(rod.state_dimension("omega")) == "T^-1"
    rng = np.random.default_rng(1)
    p = dict(rod.defaults)
    for theta, omega in rng.uniform(-3, 3, size=(20, 2)):
        got = rod.rhs(0.0, np.array([theta, omega]), p)
        want = theta_ddot(theta, omega, p["m"], p["l"], p["g"], p["k_theta"], p["c_theta"], p["theta_r"])
        assert got[0] == omega
        assert got[1] == pytest.approx(want, rel=1e-13, abs=1e-12)


def test_hinged_rod_spring_is_restoring():
    rod = models.hinged_rod()
    p = {**rod.defaults, "g": 0.0, "c_theta": 0.0}
    above = rod.rhs(0.0, np.array([p["theta_r"] + 0.1, 0.0]), p)[1]
    below = rod.rhs(0.0, np.array([p["theta_r"] - 0.1, 0.0]), p)[1]
    assert above < 0 < below


def _longitudinal_energy(model, p, y):
    theta, omega = y[:, 0], y[:, 1]
    m, l, g, k, x_r = p["m"], p["l"], p["g"], p["k"], p["x_r"]
    x = l * np.sqrt(5 + 4 * np.sin(theta))
    # theta grows in the direction gravity turns the rod: the centre of mass sinks by (l/2) sin(theta)
    return m * l**2 / 6 * omega**2 + k / 2 * (x - x_r) ** 2 - m * g * l / 2 * np.sin(theta)


def test_longitudinal_rod_conserves_energy_without_damper():
    # an independent check of the derived torque: it is minus the derivative of the potential
    model = models.hinged_rod_longitudinal(damper=False)
    tr = pt.simulate(model, t_final=3.0, rtol=1e-12, atol=1e-12)
    energy = _longitudinal_energy(model, model.defaults, tr.y)
    assert np.ptp(energy) < 1e-7 * np.abs(energy).max()
    assert np.ptp(tr["theta"]) > 0.1  # it does move


def test_longitudinal_damper_dissipates():
    model = models.hinged_rod_longitudinal()
    assert model.parameters == ("m", "l", "g", "k", "x_r", "c")
    assert dict(model.defaults) == {"m": 1.5, "l": 2.0, "g": 9.81, "k": 20.0, "x_r": 4.0, "c": 2.0}
    assert dict(model.initial) == {"theta": math.pi / 4, "omega": 0.0}
    assert str(model.system.dimension("c")) == "M T^-1"
    tr = pt.simulate(model, t_final=3.0)
    energy = _longitudinal_energy(model, model.defaults, tr.y)
    assert np.all(np.diff(energy) <= 1e-9)
    assert energy[-1] < energy[0] - 1.0


def test_longitudinal_torque_is_force_times_lever_arm():
    # static check at one angle: torque of the spring = tension * perpendicular distance
    model = models.hinged_rod_longitudinal(damper=False)
    p = {**model.defaults, "g": 0.0}
    theta = 0.3
    tip = p["l"] * np.array([math.cos(theta), math.sin(theta)])
    anchor = np.array([0.0, -2 * p["l"]])
    d = anchor - tip
    x = np.linalg.norm(d)
    force = p["k"] * (x - p["x_r"]) * d / x
    torque = tip[0] * force[1] - tip[1] * force[0]
    inertia = p["m"] * p["l"] ** 2 / 3
    assert model.rhs(0.0, np.array([theta, 0.0]), p)[1] == pytest.approx(torque / inertia, rel=1e-12)


def test_spring_mass_damper_matches_the_linear_matlab_port():
    smd = models.spring_mass_damper()
    assert dict(smd.defaults) == {"m": 2.0, "k": 150.0, "c": 10.0, "g": 9.81, "y_rest": 1.0}
    assert dict(smd.initial) == {"y": 1.0, "v": 0.0}
    tr = pt.simulate(smd, t_final=4.0, method="euler", dt=0.01)
    port = scaling_counterexample.euler(scaling_counterexample.PARAMS, np.zeros(401))
    assert len(tr) == 401
    np.testing.assert_allclose(tr.y.T, port, rtol=0, atol=1e-12)


def test_projectile_follows_the_parabola():
    proj = models.projectile()
    assert dict(proj.defaults) == {"m": 2.0, "g": 9.81}
    v0 = math.hypot(proj.initial["vx"], proj.initial["vy"])
    assert v0 == pytest.approx(10.0)
    assert math.atan2(proj.initial["vy"], proj.initial["vx"]) == pytest.approx(math.pi / 4)
    tr = pt.simulate(proj, t_final=1.0, t_eval=np.linspace(0, 1, 11))
    t = tr.t
    np.testing.assert_allclose(tr["x"], proj.initial["vx"] * t, atol=1e-9)
    np.testing.assert_allclose(tr["y"], proj.initial["vy"] * t - 9.81 * t**2 / 2, atol=1e-9)


@pytest.mark.parametrize("name", sorted(ALL_MODELS))
def test_every_model_is_dimensionally_consistent(name):
    """Numerical consistency: a change of units of every variable maps the run onto itself."""
    model = ALL_MODELS[name]()
    for unit_change, s in (({"M": 1}, 3.0), ({"L": 1}, 0.7), ({"T": 1}, 2.5), ({"M": -1, "L": 2, "T": 1}, 1.3)):
        sc = pt.Scaling.from_unit_change(model.system, unit_change)
        rep = pt.verify_similarity(model, sc, s=s, t_final=1.0)
        assert rep.passed, (name, unit_change, rep.max_deviation)
        assert rep.max_deviation < 1e-8


@pytest.mark.parametrize("name", sorted(ALL_MODELS))
def test_every_model_declares_every_variable(name):
    model = ALL_MODELS[name]()
    for n in (*model.parameters, *model.states, model.time):
        assert n in model.system.variables
    assert set(model.defaults) == set(model.parameters)
    assert set(model.initial) == set(model.states)
    assert str(model.system.dimension(model.time)) == "T"
    assert model.name
    assert model.description
    out = model.rhs(0.0, model.resolve_initial(), dict(model.defaults))
    assert np.asarray(out).shape == (len(model.states),)
