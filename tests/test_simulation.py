"""Tests for pitheorem.simulation: integrators and numerical similarity checks."""

from __future__ import annotations

import dataclasses
import math
import pickle
from fractions import Fraction

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt
from matlab_ports import scaling_counterexample_nonlinear as nonlinear
from pitheorem import models
from pitheorem.simulation import ModelScaling, fixed_steps, nudged, positive_float, similarity_report

#: the paper's wrong scalings of the hinged rod (Figures 2-4), time unchanged
WRONG = {
    "figure2": {"g": 1},
    "figure3": {"g": 1, "l": -1},
    "figure4": {"g": 1, "l": -1, "c_theta": -1},
}


@pytest.fixture(scope="module")
def hinged():
    return models.hinged_rod()


@pytest.fixture(scope="module")
def figure5(hinged):
    """The search's answer for g by s, l by 1/s with m, k_theta fixed (the paper's Figure 5)."""
    res = pt.search(hinged.system, scale={"g": 1, "l": -1}, fixed=("m", "k_theta"))
    assert len(res.scalings) == 1
    return res.scalings[0]


@pytest.fixture(scope="module")
def figure1():
    return nonlinear.simulate_figures()["figure1"]


def test_search_scaling_is_figure5(figure5):
    assert figure5.exponents == {
        "m": 0,
        "l": -1,
        "g": 1,
        "k_theta": 0,
        "c_theta": -1,
        "theta_r": 0,
        "t": -1,
        "theta": 0,
        "omega": 1,
    }


@pytest.mark.parametrize("s", [2.0, 3.0, 0.37])
def test_search_scaling_reproduces_the_original(hinged, figure5, s):
    rep = pt.verify_similarity(hinged, figure5, s=s, t_final=10.0)
    assert rep.passed
    assert rep.max_deviation < 1e-7
    assert rep.is_similarity
    assert rep.scaling is figure5
    assert rep.exponents["t"] == -1
    # mapped back to original time
    np.testing.assert_allclose(rep.mapped.t, rep.original.t, rtol=1e-14, atol=1e-14)
    assert rep.original.t[-1] == 10.0


def test_time_free_scalings_of_the_papers_rod_all_agree(hinged, rod):
    # the paper's nine variables plus the states: three minimal ways to scale g with time fixed
    with_states = pt.System({**rod.dimensions, "theta": "1", "omega": "T^-1"})
    res = pt.search(with_states, scale={"g": 1})
    assert "t" in res.fixed
    assert len(res.scalings) == 3
    for sc in res.scalings:
        assert sc.exponents["t"] == 0
        rep = pt.verify_similarity(hinged, sc, s=2.5, t_final=10.0)
        assert rep.max_deviation < 1e-7, str(sc)


def test_dict_of_exponents_is_completed_from_the_units(hinged):
    rep = pt.verify_similarity(hinged, {"g": 1, "l": -1, "c_theta": -1, "t": -1}, s=3, t_final=2.0)
    assert rep.passed
    assert rep.is_similarity
    assert rep.exponents["omega"] == 1  # states follow from the change of units
    assert isinstance(rep.scaling, pt.Scaling)
    # the same with check=False: a similarity scaling stays one
    rep2 = pt.verify_similarity(hinged, {"g": 1, "l": -1, "c_theta": -1, "t": -1}, s=3, t_final=2.0, check=False)
    assert rep2.is_similarity
    assert rep2.passed
    # exponents given as strings or Fractions
    rep3 = pt.verify_similarity(hinged, {"g": "1", "l": -1, "c_theta": -1, "t": -1, "omega": 1}, s=3, t_final=1.0)
    assert rep3.passed


@pytest.mark.parametrize("figure", sorted(WRONG))
def test_papers_wrong_scalings_fail(hinged, figure):
    rep = pt.verify_similarity(hinged, WRONG[figure], s=2, t_final=10.0, check=False)
    assert not rep.passed
    assert np.abs(rep.difference).max() == rep.max_deviation  # mapped minus original
    assert not rep.is_similarity
    assert rep.deviation["theta"] > 0.05
    assert rep.max_deviation >= rep.deviation["theta"]
    assert rep.exponents["t"] == 0
    assert rep.exponents["omega"] == 0
    assert "FAILED" in str(rep)
    assert "NOT a similarity" in str(rep)


@pytest.mark.parametrize("figure", sorted(WRONG))
def test_wrong_scalings_are_refused_when_checked(hinged, figure):
    with pytest.raises(pt.InvalidRequestError, match="not a similarity scaling"):
        pt.verify_similarity(hinged, WRONG[figure], s=2, t_final=1.0)


def test_wrong_scaling_matches_the_matlab_figures(hinged):
    # Figure 3 of the port (g*s, l/s, Euler, time unchanged) is exactly the scaled run here
    data = nonlinear.simulate_figures(n_points=20001)
    rep = pt.verify_similarity(hinged, WRONG["figure3"], s=2, t_final=2.0, method="euler", dt=1e-4, check=False)
    np.testing.assert_allclose(rep.mapped["theta"], data["figure3"][1], rtol=0, atol=1e-9)
    np.testing.assert_allclose(rep.original["theta"], data["figure1"][1], rtol=0, atol=1e-9)


def test_euler_exact_only_with_scaled_dt(hinged, figure5, figure1):
    exact = pt.verify_similarity(hinged, figure5, s=2, t_final=10.0, method="euler", dt=1e-4)
    assert exact.max_deviation < 1e-12
    assert exact.scaled_dt
    assert len(exact.original) == 100001
    gap = pt.verify_similarity(hinged, figure5, s=2, t_final=10.0, method="euler", dt=1e-4, scale_dt=False)
    assert 5e-5 < gap.deviation["theta"] < 5e-4
    assert not gap.passed
    assert not gap.scaled_dt
    assert len(gap.mapped) == len(gap.original)
    # the port's Figure 5 is the same unscaled-dt run (plotted against t*s): the same gap
    p5 = dict(nonlinear.PARAMS, g=2 * nonlinear.PARAMS["g"], l=nonlinear.PARAMS["l"] / 2, c=nonlinear.PARAMS["c"] / 2)
    t5, theta5 = figure1[0] * 2, nonlinear.simulate(p5, figure1[0])[0]
    port_gap = np.abs(np.interp(figure1[0], t5, theta5) - figure1[1]).max()
    assert gap.deviation["theta"] == pytest.approx(port_gap, rel=0.05)


def test_euler_scaled_dt_is_exact_for_any_s(hinged, figure5):
    # s = 3 is not a power of two, so agreement is to rounding, not bit for bit
    rep = pt.verify_similarity(hinged, figure5, s=3.0, t_final=5.0, method="euler", dt=1e-3)
    assert rep.max_deviation < 1e-10


def test_euler_gap_is_first_order_in_dt(hinged, figure5):
    gaps = [
        pt.verify_similarity(hinged, figure5, s=2, t_final=5.0, method="euler", dt=dt, scale_dt=False).deviation[
            "theta"
        ]
        for dt in (2e-3, 1e-3)
    ]
    assert gaps[0] / gaps[1] == pytest.approx(2.0, rel=0.1)


def test_euler_with_time_fixed_scaling_needs_no_dt_change(hinged, rod):
    with_states = pt.System({**rod.dimensions, "theta": "1", "omega": "T^-1"})
    sc = pt.search(with_states, scale={"g": 1}).scalings[0]
    for scale_dt in (True, False):
        rep = pt.verify_similarity(hinged, sc, s=3, t_final=2.0, method="euler", dt=1e-3, scale_dt=scale_dt)
        assert rep.max_deviation < 1e-10


def test_euler_reproduces_figure1(hinged, figure1):
    t, theta = figure1
    tr = pt.simulate(hinged, t_final=10.0, method="euler", dt=1e-4)
    assert len(tr) == len(t) == 100001
    np.testing.assert_allclose(tr.t, t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(tr["theta"], theta, rtol=0, atol=1e-9)


def test_solve_ivp_is_close_to_euler(hinged, figure1):
    t, theta = figure1
    tr = pt.simulate(hinged, t_final=10.0, t_eval=t[::1000])
    # Euler at dt = 1e-4 is first order: the two agree to about 1e-4
    np.testing.assert_allclose(tr["theta"], theta[::1000], atol=5e-4)


def test_simulate_defaults_and_overrides(hinged):
    tr = pt.simulate(hinged, t_final=1.0)
    assert len(tr) == 1001
    assert tr.t[0] == 0.0
    assert tr.t[-1] == 1.0
    assert tr.states == ("theta", "omega")
    assert tr.time == "t"
    assert tr["theta"][0] == math.pi / 4
    lighter = pt.simulate(hinged, {"g": 1.62}, t_final=1.0)
    assert not np.allclose(lighter["theta"], tr["theta"])
    moved = pt.simulate(hinged, y0={"omega": 1.0}, t_final=1.0)
    assert moved["omega"][0] == 1.0
    seq = pt.simulate(hinged, y0=[0.0, 0.0], t_final=1.0)
    assert seq["theta"][0] == 0.0


def test_euler_grid_and_step_count(hinged):
    tr = pt.simulate(hinged, t_final=1.0, method="euler", dt=0.1)
    assert len(tr) == 11
    np.testing.assert_allclose(tr.t, np.arange(11) * 0.1)
    # not a multiple of dt: one more step, ending after t_final
    tr = pt.simulate(hinged, t_final=1.05, method="euler", dt=0.1)
    assert len(tr) == 12
    assert tr.t[-1] >= 1.05
    # one step by hand
    p = dict(hinged.defaults)
    y0 = hinged.resolve_initial()
    tr = pt.simulate(hinged, t_final=0.1, method="euler", dt=0.1)
    np.testing.assert_array_equal(tr.y[1], y0 + hinged.rhs(0.0, y0, p) * 0.1)


def _drift(dims: str, rate, **options) -> pt.Model:
    """A one-state model x' = rate(a, x, t), the parameter a of dimension `dims`."""
    t = sympy.Symbol("t")
    x = sympy.Function("x")(t)
    system = pt.System({"a": dims, "t": "T", "x": "L"})
    return pt.Model(system, [sympy.Eq(x.diff(t), rate(sympy.Symbol("a"), x, t))], **options)


def test_euler_passes_time_to_the_rhs():
    # x' = a t: Euler's step i adds a t_(i-1) dt, so the samples show which times the rhs saw
    model = _drift("L/T^2", lambda a, x, t: a * t, defaults={"a": 2.0}, initial={"x": 0.0})
    tr = pt.simulate(model, t_final=0.3, method="euler", dt=0.1)
    np.testing.assert_allclose(tr.t, [0.0, 0.1, 0.2, 0.3])
    np.testing.assert_allclose(tr["x"], [0.0, 0.0, 0.02, 0.06], rtol=1e-12)
    np.testing.assert_allclose(np.diff(tr["x"]), 2.0 * tr.t[:-1] * 0.1, rtol=1e-12)


def test_trajectory_is_read_only(hinged):
    tr = pt.simulate(hinged, t_final=0.1)
    with pytest.raises(ValueError, match="read-only"):
        tr.y[0, 0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        tr.t[0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        tr.t = np.zeros(3)
    with pytest.raises(pt.UnknownVariableError, match="'phi'"):
        tr["phi"]
    assert repr(tr) == "<Trajectory t=0..0.1, 1001 samples, states ('theta', 'omega')>"
    assert len({tr, tr}) == 1  # compared and hashed by identity: its arrays have no single truth value
    assert repr(pt.Trajectory([], np.zeros((0, 1)), ("x",))) == "<Trajectory t=empty, 0 samples, states ('x',)>"
    with pytest.raises(pt.InvalidRequestError, match="shape"):
        pt.Trajectory([0.0, 1.0], [[1.0, 2.0]], ("a", "b"))


def test_report_is_frozen(hinged, figure5):
    rep = pt.verify_similarity(hinged, figure5, s=2, t_final=0.5)
    # by default the verdict is absolute, without a one-ulp baseline run
    assert (rep.tol, rep.sensitivity, rep.nudged) == (1e-6, None, None)
    assert "tol 1e-06" in str(rep)
    with pytest.raises(dataclasses.FrozenInstanceError):
        rep.passed = False
    with pytest.raises(TypeError):
        rep.deviation["theta"] = 1.0
    assert rep.difference.shape == rep.original.y.shape
    assert rep.scaled_dt is True  # solve_ivp: nothing unscaled
    assert "PASSED" in str(rep)


def test_scaling_of_a_superset_system_is_accepted(hinged, rod, figure5):
    # the same change of units, built on a larger system (force, torque, an extra state)
    big = pt.System({**rod.dimensions, "theta": "1", "omega": "T^-1", "alpha": "T^-2"})
    sc = pt.Scaling.from_unit_change(big, figure5.unit_change)
    assert pt.verify_similarity(hinged, sc, s=2, t_final=1.0).passed


def test_bad_simulate_inputs(hinged):
    with pytest.raises(pt.UnknownVariableError, match="'mass'") as info:
        pt.simulate(hinged, {"mass": 1.0})
    assert "m, l, g" in str(info.value)
    with pytest.raises(pt.InvalidRequestError, match="'rk4'"):
        pt.simulate(hinged, method="rk4")
    with pytest.raises(pt.InvalidRequestError, match="dt"):
        pt.simulate(hinged, method="euler")
    with pytest.raises(pt.InvalidRequestError, match="dt"):
        pt.simulate(hinged, method="euler", dt=-1e-3)
    with pytest.raises(pt.InvalidRequestError, match="dt"):
        pt.simulate(hinged, dt=1e-3)
    with pytest.raises(pt.InvalidRequestError, match="t_eval"):
        pt.simulate(hinged, method="euler", dt=1e-3, t_eval=[0.0])
    with pytest.raises(pt.InvalidRequestError, match="t_final"):
        pt.simulate(hinged, t_final=0)
    with pytest.raises(pt.InvalidRequestError, match="t_final"):
        pt.simulate(hinged, t_final="long")
    with pytest.raises(pt.InvalidRequestError, match=r"3 values.*2 states"):
        pt.simulate(hinged, y0=[0.1, 0.2, 0.3])
    with pytest.raises(pt.UnknownVariableError, match="'phi'"):
        pt.simulate(hinged, y0={"phi": 0.1})
    with pytest.raises(pt.InvalidRequestError, match="t_eval"):
        pt.simulate(hinged, t_final=1.0, t_eval=[0.0, 2.0])
    with pytest.raises(pt.InvalidRequestError, match="t_eval"):
        pt.simulate(hinged, t_final=1.0, t_eval=[0.5, 0.1])
    with pytest.raises(pt.InvalidRequestError, match="t_eval must be strictly increasing"):
        pt.simulate(hinged, t_final=1.0, t_eval=[0.0, 0.5, 0.5, 1.0])  # scipy refuses a time twice
    with pytest.raises(pt.InvalidRequestError, match="non-empty"):
        pt.simulate(hinged, t_final=1.0, t_eval=[])
    one = pt.simulate(hinged, t_final=1.0, t_eval=[0.5])  # a single sample is a grid too
    assert one.t.tolist() == [0.5]
    with pytest.raises(pt.InvalidRequestError, match="Model"):
        pt.simulate("hinged_rod")
    with pytest.raises(TypeError):
        pt.simulate(hinged, 1.0, None, 1.0, "euler")  # options are keyword-only


def test_missing_parameter_is_named():
    model = _drift("L/T", lambda a, x, t: a, initial={"x": 0.0}, name="drift")
    with pytest.raises(pt.InvalidRequestError, match=r"'a'.*no default"):
        pt.simulate(model, t_final=1.0)
    with pytest.raises(pt.InvalidRequestError, match=r"'a'.*no default"):
        pt.verify_similarity(model, {"a": 1}, s=2, t_final=1.0)
    assert pt.simulate(model, {"a": 1.0}, t_final=1.0)["x"][-1] == pytest.approx(1.0)


@pytest.mark.parametrize("s", [0, -2, float("nan"), float("inf"), "two", None, True])
def test_bad_scale_factor(hinged, figure5, s):
    with pytest.raises(pt.InvalidRequestError, match="scale factor s"):
        pt.verify_similarity(hinged, figure5, s=s, t_final=0.1)
    with pytest.raises(pt.InvalidRequestError, match="scale factor s"):
        pt.verify_similarity(hinged, {"g": 1}, s=s, t_final=0.1, check=False)


def test_bad_verify_inputs(hinged, figure5):
    with pytest.raises(pt.InvalidRequestError, match="dt"):
        pt.verify_similarity(hinged, figure5, s=2, method="euler")
    with pytest.raises(pt.InvalidRequestError, match="'leapfrog'"):
        pt.verify_similarity(hinged, figure5, s=2, method="leapfrog")
    with pytest.raises(pt.UnknownVariableError, match="'gravity'"):
        pt.verify_similarity(hinged, {"gravity": 1}, s=2, check=False)
    with pytest.raises(pt.UnknownVariableError, match="'mass'"):
        pt.verify_similarity(hinged, figure5, s=2, params={"mass": 1.0})
    with pytest.raises(pt.InvalidRequestError, match="3 values"):
        pt.verify_similarity(hinged, figure5, s=2, y0=[1.0, 2.0, 3.0])
    with pytest.raises(pt.InvalidRequestError, match="tol"):
        pt.verify_similarity(hinged, figure5, s=2, tol=0)
    with pytest.raises(pt.InvalidRequestError, match="Scaling or a dict"):
        pt.verify_similarity(hinged, [1, 2], s=2)
    with pytest.raises(pt.InvalidRequestError, match="'g'"):
        pt.verify_similarity(hinged, {"g": "big"}, s=2, check=False)
    with pytest.raises(pt.InvalidRequestError, match=r"'omega'.*contradicts"):
        pt.verify_similarity(hinged, {"g": 1, "l": -1, "c_theta": -1, "t": -1, "omega": 2}, s=2)


def test_scaling_of_another_system_is_refused(hinged, figure5):
    # same variables, one dimension differs
    dims = {n: str(d) for n, d in hinged.system.dimensions.items()}
    dims["c_theta"] = "M L T^-1"
    other = pt.System(dims)
    sc = pt.Scaling.from_unit_change(other, {"L": 1})
    with pytest.raises(pt.SystemMismatchError, match=r"'c_theta'.*M L\^2 T\^-1.*M L T\^-1") as info:
        pt.verify_similarity(hinged, sc, s=2, t_final=0.1)
    assert info.value.name == "c_theta"
    assert isinstance(info.value, pt.PiTheoremError)
    assert isinstance(info.value, ValueError)
    # a system without the states
    sc = pt.Scaling.from_unit_change(models.rod_system(), {"L": 1})
    with pytest.raises(pt.SystemMismatchError, match=r"'theta'.*missing"):
        pt.verify_similarity(hinged, sc, s=2, t_final=0.1)
    # a scaling of another model
    sc = pt.Scaling.from_unit_change(models.spring_mass_damper().system, {"L": 1})
    with pytest.raises(pt.SystemMismatchError, match="'l'"):
        pt.verify_similarity(hinged, sc, s=2, t_final=0.1)


def test_system_mismatch_error_pickles():
    err = pt.SystemMismatchError("theta", "variable 'theta' is missing")
    again = pickle.loads(pickle.dumps(err))
    assert again.name == "theta"
    assert str(again) == str(err)


unit_exponent = st.integers(-2, 2)


@settings(max_examples=12, deadline=None)
@given(
    s=st.floats(0.5, 4.0),
    u_m=unit_exponent,
    u_l=unit_exponent,
    u_t=unit_exponent,
)
def test_any_change_of_units_is_similar(s, u_m, u_l, u_t):
    smd = models.spring_mass_damper()
    sc = pt.Scaling.from_unit_change(smd.system, {"M": u_m, "L": u_l, "T": u_t})
    rep = pt.verify_similarity(smd, sc, s=s, t_final=2.0)
    assert rep.passed, (s, u_m, u_l, u_t, rep.max_deviation)


def test_state_exponent_must_be_determined():
    # the parameters and time carry no length: the exponent of x is not fixed by them
    model = _drift("T^-1", lambda a, x, t: -a * x, defaults={"a": 1.0}, initial={"x": 1.0})
    with pytest.raises(pt.InvalidRequestError, match=r"state 'x'"):
        pt.verify_similarity(model, {"t": 1, "a": -1}, s=2, t_final=1.0)
    rep = pt.verify_similarity(model, {"t": 1, "a": -1, "x": 3}, s=2, t_final=1.0)
    assert rep.passed
    assert rep.exponents["x"] == 3
    unchecked = pt.verify_similarity(model, {"t": 1, "a": -1}, s=2, t_final=1.0, check=False)
    assert unchecked.exponents["x"] == 0  # applied as given
    assert not unchecked.is_similarity


def test_model_scaling_of_a_scaling_and_of_exponents(hinged, figure5):
    by_scaling = ModelScaling.of(hinged, figure5, s=2)
    by_dict = ModelScaling.of(hinged, {"g": 1, "l": -1, "c_theta": -1, "t": -1}, s=2)
    assert dict(by_scaling.exponents) == dict(by_dict.exponents)
    assert all(type(v) is Fraction for v in by_dict.exponents.values())
    assert set(by_dict.exponents) == {*hinged.parameters, "t", *hinged.states}
    assert by_dict.is_similarity
    assert by_dict.scaling == figure5
    assert by_scaling.scaling is figure5
    assert (by_scaling.factor("omega"), by_scaling.factor("t"), by_scaling.factor("m")) == (2.0, 0.5, 1.0)
    assert by_scaling.scale_params({"l": 2.0, "g": 9.81}) == {"l": 1.0, "g": 19.62}
    np.testing.assert_array_equal(by_scaling.scale_state([0.1, 3.0]), [0.1, 6.0])
    run = pt.Trajectory([0.0, 0.5], [[0.1, 2.0], [0.2, 4.0]], hinged.states)
    back = by_scaling.map_back(run)
    assert back.t.tolist() == [0.0, 1.0]
    assert back["omega"].tolist() == [1.0, 2.0]
    assert back["theta"].tolist() == [0.1, 0.2]
    onto = by_scaling.map_back(run, [0.0, 0.5, 1.0])  # another grid: interpolated onto it
    assert onto.t.tolist() == [0.0, 0.5, 1.0]
    assert onto["omega"].tolist() == [1.0, 1.5, 2.0]
    near = by_scaling.map_back(run, [0.0, 1.0 + 1e-15])  # the same grid up to rounding: not interpolated
    assert near.t.tolist() == [0.0, 1.0]


def test_a_failing_solver_is_reported():
    # x' = x^2 / (l tau) from x = l blows up at t = tau: solve_ivp cannot pass it
    t, ell, tau = sympy.Symbol("t"), sympy.Symbol("l"), sympy.Symbol("tau")
    x = sympy.Function("x")(t)
    blow_up = pt.Model(
        pt.System({"l": "L", "tau": "T", "t": "T", "x": "L"}),
        [sympy.Eq(x.diff(t), x**2 / (ell * tau))],
        defaults={"l": 1.0, "tau": 1.0},
        initial={"x": 1.0},
    )
    with pytest.raises(pt.PiTheoremError, match="solve_ivp failed"):
        pt.simulate(blow_up, t_final=2.0)


def test_baseline_report_names_the_largest_sensitivity(hinged, figure5):
    rep = pt.verify_similarity(hinged, figure5, s=2, t_final=0.5, baseline=True)
    assert math.isnan(rep.tol)
    largest = max(rep.sensitivity.values())
    assert largest > min(rep.sensitivity.values()) > 0
    assert f"(the largest {largest:.3g})" in str(rep)


def test_non_similarity_names_a_group_it_changes(hinged):
    with pytest.raises(pt.InvalidRequestError) as info:
        pt.verify_similarity(hinged, {"g": 1}, s=2)
    assert str(info.value) == (
        "exponents (g: 1) are not a similarity scaling; they multiply the Pi group k_theta/(g*l*m) by s^-1 "
        "(only changes of base units keep every group invariant)"
    )
    # the first group, k_theta/(g*l*m), keeps its value here: the message skips it
    with pytest.raises(pt.InvalidRequestError, match=r"the Pi group c_theta\*\*2/\(g\*l\*\*3\*m\*\*2\) by s\^2 "):
        pt.verify_similarity(hinged, {"c_theta": 1}, s=2)


def test_model_scaling_that_is_no_similarity(hinged, figure5):
    raw = ModelScaling.of(hinged, {"g": 1}, s=2, check=False)
    assert not raw.is_similarity
    assert len({raw, raw}) == 1  # identity: it holds a model and read-only mappings
    assert raw.scaling == {**dict.fromkeys(raw.exponents, 0), "g": 1}
    assert raw.exponents["omega"] == 0
    with pytest.raises(TypeError):
        raw.scaling["g"] = 2  # read-only
    assert raw.scale_params({"g": 9.81, "l": 2.0}) == {"g": 19.62, "l": 2.0}
    with pytest.raises(pt.InvalidRequestError, match="not a similarity scaling"):
        ModelScaling.of(hinged, {"g": 1}, s=2)
    with pytest.raises(pt.UnknownVariableError, match="'phi'"):
        raw.factor("phi")
    with pytest.raises(pt.UnknownVariableError, match="'phi'"):
        ModelScaling.of(hinged, {"phi": 1}, s=2, check=False)
    with pytest.raises(pt.InvalidRequestError, match="scale factor s"):
        ModelScaling.of(hinged, figure5, s=True)
    with pytest.raises(pt.InvalidRequestError, match="Model"):
        ModelScaling.of("hinged_rod", figure5, s=2)
    with pytest.raises(pt.InvalidRequestError, match="Scaling or a dict"):
        ModelScaling.of(hinged, (1, 2), s=2)


def test_fixed_steps_cover_the_span():
    assert fixed_steps(1.0, 0.1) == 10
    assert fixed_steps(0.07, 0.01) == 7  # 0.07 / 0.01 is 7.000000000000001: rounding, not one more step
    # the tolerance is relative: 149.38268 / 1e-5 is 14938268.000000002, 2e-9 above an integer
    assert fixed_steps(149.38268000000002, 1e-05) == 14938268
    assert fixed_steps(0.3, 0.1) == 3  # 0.3 / 0.1 is 2.9999999999999996
    assert fixed_steps(1.05, 0.1) == 11  # not a multiple: one more step, past t_final
    assert fixed_steps(1.0 + 1e-6, 1.0) == 2
    assert fixed_steps(1e-3, 1.0) == 1


@pytest.mark.parametrize("bad", [0, -1.0, float("inf"), float("nan"), "soon", None, True, False])
def test_positive_float_refuses_and_names(bad):
    with pytest.raises(
        pt.InvalidRequestError, match=r"^dt must be a positive finite number such as 2, 0.5 or .1/3., got "
    ):
        positive_float(bad, "dt")
    assert positive_float("2.5", "dt") == 2.5
    assert positive_float(np.float32(0.5), "dt") == 0.5


@pytest.mark.parametrize("s", [1e-6, 1e-9])
def test_tolerances_scale_with_each_state(s):
    # with one atol for every state, the shrunken positions are integrated to a tolerance
    # far coarser than theirs, and the mapped-back run drifts (about 2e-6 at s = 1e-6)
    model = pt.models.spring_mass_damper()
    sc = pt.Scaling.from_unit_change(model.system, {"L": 1})
    rep = pt.verify_similarity(model, sc, s=s, t_final=5)
    assert rep.max_deviation < 1e-9


def runs(dev, base, values=(1.0, 2.0)):
    t = [0.0, 1.0]
    original = pt.Trajectory(t, [[values[0]], [values[1]]], ("x",))
    mapped = pt.Trajectory(t, [[values[0]], [values[1] + dev]], ("x",))
    nudge = pt.Trajectory(t, [[values[0]], [values[1] + base]], ("x",))
    return original, mapped, nudge


def test_verdict_is_ten_times_the_baseline_per_state():
    # a constant signal: no range to fall back on, the baseline alone decides
    for dev, base, similar in ((9e-12, 1e-12, True), (1.1e-11, 1e-12, False), (0.0, 0.0, True), (1e-15, 0.0, False)):
        original, mapped, nudge = runs(dev, base, values=(2.0, 2.0))
        rep = similarity_report(original, mapped, s=2, scaling={}, exponents={}, nudged=nudge)
        assert rep.similar is similar
        assert math.isnan(rep.tol)  # judged against the baseline, not a tolerance
        assert rep.sensitivity["x"] == pytest.approx(base, rel=1e-3)


def test_zero_baseline_falls_back_to_a_billionth_of_the_range():
    # the signal spans 1 (from 1 to 2); the nudge changed nothing
    original, mapped, nudge = runs(0.9e-9, 0.0)
    assert similarity_report(original, mapped, s=2, scaling={}, exponents={}, nudged=nudge).similar
    original, mapped, nudge = runs(1.1e-9, 0.0)
    assert not similarity_report(original, mapped, s=2, scaling={}, exponents={}, nudged=nudge).similar


def test_absolute_tolerance_without_a_baseline():
    original, mapped, _ = runs(1e-7, 0.0)
    assert similarity_report(original, mapped, s=2, scaling={}, exponents={}, tol=1e-6).passed
    assert not similarity_report(original, mapped, s=2, scaling={}, exponents={}, tol=1e-8).passed
    exact = similarity_report(*runs(0.5, 0.0)[:2], s=2, scaling={}, exponents={}, tol=0.5)
    assert (exact.max_deviation, exact.passed) == (0.5, True)  # a deviation of exactly tol passes
    assert exact.scaled_dt is True  # the default: nothing says the step was not scaled
    with pytest.raises(pt.InvalidRequestError, match="tol"):
        similarity_report(original, mapped, s=2, scaling={}, exponents={})
    short = pt.Trajectory([0.0], [[1.0]], ("x",))
    with pytest.raises(pt.InvalidRequestError, match="cannot be compared"):
        similarity_report(original, short, s=2, scaling={}, exponents={}, tol=1.0)


@given(st.floats(min_value=-1e6, max_value=1e6, allow_nan=False))
def test_nudge_moves_by_one_ulp_of_the_value_or_of_one(x):
    moved = float(nudged([x])[0])
    assert moved > x
    if abs(x) >= 1:  # the next double up, exactly (math.nextafter is the independent oracle)
        assert moved == math.nextafter(x, math.inf)
    else:  # the ulp of 1, up to the rounding of the sum x + 2^-52 itself (half an ulp of the sum)
        assert abs((moved - x) - 2.0**-52) <= math.ulp(max(abs(moved), 2.0**-52)) / 2


def test_verify_similarity_with_a_baseline():
    rod = pt.models.hinged_rod()
    sc = pt.search(rod.system, scale={"g": 1, "l": -1}, fixed=("m", "k_theta")).scalings[0]
    rep = pt.verify_similarity(rod, sc, s=10, t_final=2, baseline=True)
    assert rep.similar
    assert rep.sensitivity is not None
    assert rep.nudged.y.shape == rep.original.y.shape
    assert rep.sensitivity["theta"] > 0
    bad = pt.verify_similarity(rod, {"g": 1}, s=10, t_final=2, check=False, baseline=True)
    assert not bad.similar


def test_check_names_the_pi_group_and_prints_plain_exponents():
    rod = pt.models.hinged_rod()
    with pytest.raises(pt.InvalidRequestError) as caught:
        pt.verify_similarity(rod, {"g": 1, "l": "1/2"}, s=2, t_final=0.1)
    message = str(caught.value)
    assert "Fraction" not in message
    assert "(l: 1/2, g: 1)" in message
    assert "Pi group k_theta/(g*l*m) by s^-3/2" in message


@pytest.mark.parametrize(
    ("option", "value"), [("dt", "1e-400"), ("tol", "1e-400"), ("s", "1e400"), ("s", 10**400), ("t_final", "1e400")]
)
def test_numbers_that_no_float_can_hold_are_refused_by_name(hinged, figure5, option, value):
    # exact and positive, but 1e-400 rounds to 0.0 and 1e400 overflows: neither can drive a simulation
    request = {"s": 2, "t_final": 0.5, "method": "euler", "dt": 0.01, option: value}
    with pytest.raises(
        pt.NumberError,
        match=f"{'the scale factor s' if option == 's' else option} must be a "
        r"positive number within the range of floating point",
    ) as info:
        pt.verify_similarity(hinged, figure5, **request)
    assert info.value.culprit is value


def test_verify_similarity_reads_t_final_and_dt_as_simulate_does(hinged, figure5):
    exact = pt.verify_similarity(hinged, figure5, s=2, t_final="1/2", method="euler", dt="1/100")
    floats = pt.verify_similarity(hinged, figure5, s=2, t_final=0.5, method="euler", dt=0.01)
    assert exact.passed
    assert floats.passed
    assert exact.scaled_dt == floats.scaled_dt
    assert np.array_equal(exact.original.y, floats.original.y)
    assert np.array_equal(exact.mapped.y, floats.mapped.y)
