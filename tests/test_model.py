"""Tests for pitheorem.model: a Model built from its equations, solved once, and its generated rhs."""

from __future__ import annotations

import dataclasses
import math
import pickle

import numpy as np
import pytest
import sympy
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem import models

T = sympy.Symbol("t")
X, V = sympy.Function("x")(T), sympy.Function("v")(T)
TAU, L = sympy.symbols("tau l")

#: x (a length), v (a speed), and the parameters tau (a time) and l (a length)
DIMS = {"tau": "T", "l": "L", "t": "T", "x": "L", "v": "L T^-1"}


def _decay(**kw) -> pt.Model:
    """x' = -x / tau, from x = 1."""
    args = {
        "system": pt.System({"tau": "T", "x": "L", "t": "T"}),
        "equations": [sympy.Eq(X.diff(T), -X / TAU)],
        "defaults": {"tau": 2.0},
        "initial": {"x": 1.0},
        "name": "decay",
    }
    args.update(kw)
    return pt.Model(**args)


# -- building from equations -------------------------------------------------------------------


def test_states_and_parameters_are_read_from_the_equations():
    model = _decay()
    assert model.states == ("x",)
    assert model.parameters == ("tau",)
    assert model.time == "t"
    assert model.equations == (sympy.Eq(X.diff(T), -X / TAU),)
    assert isinstance(model.equations, tuple)
    out = model.rhs(0.0, [3.0], {"tau": 2.0})
    assert isinstance(out, np.ndarray)
    assert out.dtype == float
    assert out.tolist() == [-1.5]


def test_states_follow_the_systems_order_not_the_equations():
    # the equations give v' first; y is in the order of the system: x, then v
    system = pt.System({"k": "T^-2", "t": "T", "x": "L", "v": "L T^-1"})
    k = sympy.Symbol("k")
    model = pt.Model(system, [sympy.Eq(V.diff(T), -k * X), sympy.Eq(X.diff(T), V)])
    assert model.states == ("x", "v")
    assert model.rhs(0.0, [2.0, 5.0], {"k": 3.0}).tolist() == [5.0, -6.0]


def test_parameters_follow_the_system_or_the_list_given():
    system = pt.System({"g": "L T^-2", "m": "M", "t": "T", "x": "L", "v": "L T^-1"})
    g = sympy.Symbol("g")
    eqs = [sympy.Eq(X.diff(T), V), sympy.Eq(V.diff(T), -g)]
    assert pt.Model(system, eqs).parameters == ("g",)  # m is in no equation
    listed = pt.Model(system, eqs, parameters=("m", "g"), defaults={"m": 1.0, "g": 9.81})
    assert listed.parameters == ("m", "g")
    assert listed.resolve_params() == {"m": 1.0, "g": 9.81}
    assert list(listed.resolve_params()) == ["m", "g"]


def test_a_mass_times_acceleration_left_side_is_solved():
    # m v' = -k (y - y_rest) - c v - m g, as the issue writes it
    smd = models.spring_mass_damper()
    p = dict(smd.defaults)
    for y, v in ((1.0, 0.0), (0.3, -2.0), (1.7, 4.5)):
        want = (-p["k"] * (y - p["y_rest"]) - p["c"] * v) / p["m"] - p["g"]
        got = smd.rhs(0.0, [y, v], p)
        assert got[0] == v
        assert got[1] == pytest.approx(want, rel=1e-14, abs=1e-13)


def test_derivatives_and_other_terms_on_either_side():
    # v = x' has the derivative on the right; v' + x/tau^2 = 2 v/tau has x/tau^2 on the left
    model = pt.Model(pt.System(DIMS), [sympy.Eq(V, X.diff(T)), sympy.Eq(V.diff(T) + X / TAU**2, 2 * V / TAU)])
    assert model.parameters == ("tau",)
    assert model.rhs(0.0, [3.0, 5.0], {"tau": 2.0}).tolist() == [5.0, 5.0 - 0.75]


def test_explicit_time_dependence_and_any_time_name():
    time = sympy.Symbol("time")
    x = sympy.Function("x")(time)
    a = sympy.Symbol("a")
    system = pt.System({"a": "L T^-2", "time": "T", "x": "L"})
    model = pt.Model(system, [sympy.Eq(x.diff(time), a * time)], time="time")
    assert model.time == "time"
    assert model.rhs(2.0, [0.0], {"a": 3.0}).tolist() == [6.0]
    assert model.rhs(-1.0, [0.0], {"a": 3.0}).tolist() == [-3.0]


def test_constant_rates_give_float_arrays():
    model = pt.Model(pt.System({"t": "T", "x": "L"}), [sympy.Eq(X.diff(T), 0)])
    out = model.rhs(0.0, [1.0], {})
    assert out.dtype == float
    assert out.tolist() == [0.0]
    assert model.parameters == ()


def test_any_parameter_name_compiles():
    # names that Python, the math module or the generated code's own temporaries also use
    system = pt.System({"lambda": "T^-1", "x0": "L", "cos": "L", "e": "1", "t": "T", "x": "L"})
    lam, x0, cos, e = sympy.symbols("lambda x0 cos e")
    eq = sympy.Eq(X.diff(T), -lam * (X - x0) * sympy.cos(e) + lam * cos * sympy.sin(e) ** 2)
    model = pt.Model(system, [eq])
    p = {"lambda": 2.0, "x0": 0.5, "cos": 3.0, "e": 0.25}
    want = -2.0 * (1.0 - 0.5) * math.cos(0.25) + 2.0 * 3.0 * math.sin(0.25) ** 2
    assert model.rhs(0.0, [1.0], p)[0] == pytest.approx(want, rel=1e-14)


def test_symbol_assumptions_do_not_matter():
    # the same names with and without assumptions are the same variables
    t = sympy.Symbol("t", positive=True)
    x = sympy.Function("x")(t)
    tau = sympy.Symbol("tau", positive=True)
    plain = _decay()
    positive = _decay(equations=[sympy.Eq(x.diff(t), -x / tau)])
    assert positive.states == plain.states
    assert positive.parameters == plain.parameters
    assert positive.rhs(0.0, [3.0], {"tau": 2.0}).tolist() == [-1.5]


# -- the solve, against an independent oracle ---------------------------------------------------

coefficient = st.integers(-3, 3)
value = st.floats(-5.0, 5.0, allow_nan=False)
positive = st.floats(0.1, 5.0)


@settings(max_examples=60, deadline=None)
@given(
    a=st.tuples(coefficient, coefficient, coefficient, coefficient),
    b=st.tuples(coefficient, coefficient, coefficient, coefficient),
    x=value,
    v=value,
    t=value,
    tau=positive,
    ell=positive,
)
def test_coupled_equations_solve_as_numpy_does(a, b, x, v, t, tau, ell):
    """A x' + ... = b: sympy's exact solution, generated, equals numpy's numeric solve."""
    a11, a12, a21, a22 = a
    assume(a11 * a22 - a12 * a21 != 0)
    b1, b2, b3, b4 = b
    # both sides of each equation are L T^-1 (first) and L T^-2 (second)
    eqs = [
        sympy.Eq(a11 * X.diff(T) + a12 * TAU * V.diff(T), b1 * V + b2 * L / TAU * sympy.sin(X / L)),
        # the same equation as a21 x'/tau + a22 v' = b3 x/tau^2 + ..., with terms on the other sides
        sympy.Eq(a22 * V.diff(T) - b3 * X / TAU**2, -a21 * X.diff(T) / TAU + b4 * V * sympy.cos(T / TAU) / TAU),
    ]
    model = pt.Model(pt.System(DIMS), eqs, parameters=("tau", "l"))  # some b may drop l from the equations
    assert model.states == ("x", "v")
    matrix = np.array([[a11, a12 * tau], [a21 / tau, a22]])
    right = np.array([b1 * v + b2 * ell / tau * math.sin(x / ell), b3 * x / tau**2 + b4 * v * math.cos(t / tau) / tau])
    want = np.linalg.solve(matrix, right)
    got = model.rhs(t, [x, v], {"tau": tau, "l": ell})
    np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-9 * (1 + np.abs(want).max()))


ROD, SPRING, PROJECTILE = models.hinged_rod(), models.hinged_rod_longitudinal(), models.projectile()


@settings(max_examples=40, deadline=None)
@given(
    theta=st.floats(-3.0, 3.0),
    omega=st.floats(-5.0, 5.0),
    m=positive,
    ell=positive,
    g=positive,
    k=positive,
    c=positive,
    x_r=positive,
)
def test_catalogue_rates_equal_hand_written_physics(theta, omega, m, ell, g, k, c, x_r):
    """The generated rhs of each paper model against its physics written out by hand."""
    p = {"m": m, "l": ell, "g": g, "k_theta": k, "c_theta": c, "theta_r": x_r}
    torque = m * g * ell / 2 * math.cos(theta) - c * omega - k * (theta - x_r)
    np.testing.assert_allclose(
        ROD.rhs(0.0, [theta, omega], p), [omega, 3 * torque / (m * ell**2)], rtol=1e-12, atol=1e-12
    )
    p = {"m": m, "l": ell, "g": g, "k": k, "x_r": x_r, "c": c}
    x = ell * math.sqrt(5 + 4 * math.sin(theta))
    arm = 2 * ell**2 * math.cos(theta) / x
    tension = k * (x - x_r) + c * arm * omega
    acc = 3 / (m * ell**2) * (m * g * ell / 2 * math.cos(theta) - tension * arm)
    np.testing.assert_allclose(SPRING.rhs(0.0, [theta, omega], p), [omega, acc], rtol=1e-10, atol=1e-10)
    np.testing.assert_array_equal(PROJECTILE.rhs(0.0, [theta, omega, c, k], {"m": m, "g": g}), [c, k, 0.0, -g])


# -- the bug: a model's name means nothing -------------------------------------------------


def test_a_user_model_named_projectile_with_other_states():
    # a ball thrown straight up, in h (height) and w (vertical speed): not the catalogue's x, y, vx, vy
    h, w = sympy.Function("h")(T), sympy.Function("w")(T)
    g = sympy.Symbol("g")
    system = pt.System({"g": "L T^-2", "t": "T", "h": "L", "w": "L T^-1"})
    user = pt.Model(
        system,
        [sympy.Eq(h.diff(T), w), sympy.Eq(w.diff(T), -g)],
        defaults={"g": 9.81},
        initial={"h": 0.0, "w": 10.0},
        name="projectile",
    )
    assert user.states == ("h", "w")
    assert user != models.projectile()
    for eq in user.equations:
        assert pt.check_dimensions(eq, user.system).consistent
    sym = pt.scaling_symmetries(user.equations, user.system)
    assert sym.contains({"h": 1, "w": 1, "g": 1})
    tr = pt.simulate(user, t_final=1.0, t_eval=[0.0, 0.5, 1.0])
    np.testing.assert_allclose(tr["h"], 10.0 * tr.t - 9.81 * tr.t**2 / 2, atol=1e-9)
    sc = pt.search(user.system, scale={"g": 1}).scalings[0]
    assert pt.verify_similarity(user, sc, s=3, t_final=1.0).passed


# -- bad input -----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kw", "error", "culprit"),
    [
        ({"parameters": ("tau", "nope")}, pt.UnknownVariableError, "nope"),
        ({"parameters": ("tau", "tau")}, pt.DuplicateVariableError, "tau"),
        ({"parameters": ("tau", "x")}, pt.DuplicateVariableError, "'x'"),
        ({"parameters": ()}, pt.ModelEquationError, "'tau'"),
        ({"time": "time"}, pt.UnknownVariableError, "time"),
        ({"time": 3}, pt.InvalidRequestError, "time"),
        ({"time": "tau"}, pt.ModelEquationError, "x(t)"),
        ({"defaults": {"tau": 2.0, "k": 1.0}}, pt.UnknownVariableError, "k"),
        ({"defaults": {"tau": "fast"}}, pt.InvalidRequestError, "tau"),
        ({"defaults": [1.0]}, pt.InvalidRequestError, "defaults"),
        ({"initial": {"v": 0.0}}, pt.UnknownVariableError, "v"),
        ({"system": {"tau": "T"}}, pt.InvalidRequestError, "System"),
        ({"equations": "x' = -x/tau"}, pt.InvalidRequestError, "sympy.Eq"),
        ({"equations": 3}, pt.InvalidRequestError, "sympy.Eq"),
        ({"equations": []}, pt.InvalidRequestError, "at least one equation"),
    ],
)
def test_model_validation(kw, error, culprit):
    with pytest.raises(error) as info:
        _decay(**kw)
    assert culprit in str(info.value)


def test_one_equation_alone_is_accepted():
    assert _decay(equations=sympy.Eq(X.diff(T), -X / TAU)) == _decay()


def _error(equations, dims=None, **kw) -> pt.ModelEquationError:
    with pytest.raises(pt.ModelEquationError) as info:
        pt.Model(pt.System(dims or DIMS), equations, **kw)
    err = info.value
    assert isinstance(err, pt.InvalidRequestError)
    assert isinstance(err, ValueError)
    again = pickle.loads(pickle.dumps(err))
    assert str(again) == str(err)
    assert (again.equation, again.reason, again.index) == (err.equation, err.reason, err.index)
    return err


GOOD_V = sympy.Eq(V.diff(T), -X / TAU**2)  # v' = -x / tau^2: a second, valid equation


@pytest.mark.parametrize(
    ("first", "index", "says"),
    [
        (sympy.Eq(X.diff(T, 2), -X / TAU**2), 1, "first order"),
        (sympy.Eq(sympy.Derivative(X**2, T), X * V), 1, "not the first time derivative of a state"),
        (sympy.Eq(sympy.Derivative(X, TAU), V / TAU), 1, "not the first time derivative of a state"),
        (sympy.Eq(sympy.Function("x")(2 * T) / TAU, V), 1, "x(2*t) is not a function of the time alone"),
        (sympy.Eq(X.diff(T) ** 2, V**2), 1, "not linear in the derivatives"),
        (sympy.Eq(X.diff(T) * V.diff(T), V * X / TAU**2), 1, "not linear in the derivatives"),
        (sympy.Eq(X.diff(T), V + V * TAU), 1, "dimensionally inconsistent: tau*v(t) has dimension L, expected L T^-1"),
        (sympy.Eq(X.diff(T), V + sympy.sin(X)), 1, "x(t) has dimension L, expected 1"),
        (sympy.Eq(X.diff(T), V + sympy.Symbol("x") / TAU), 1, "x is a state, but appears here as a plain symbol"),
        (X.diff(T) - V, 1, "it is a Add, not an equation"),
        ("Eq(x', v)", 1, "it is a string, not an equation"),
    ],
)
def test_bad_equations_are_named(first, index, says):
    err = _error([first, GOOD_V])
    assert says in str(err)
    assert err.index == index
    assert f"equation {index} of the model" in str(err)
    assert err.culprit == err.equation
    assert err.equation == (repr(first) if isinstance(first, str) else sympy.sstr(first))  # the one at fault


def test_an_equation_holding_no_derivative_is_named_by_position():
    err = _error([sympy.Eq(X.diff(T) + TAU * V.diff(T), V), sympy.Eq(X, V * TAU)])
    assert err.index == 2
    assert err.equation == "Eq(x(t), tau*v(t))"
    assert "holds no derivative" in str(err)


def test_equations_that_do_not_determine_the_rates():
    singular = [sympy.Eq(X.diff(T) + TAU * V.diff(T), V), sympy.Eq(2 * X.diff(T) + 2 * TAU * V.diff(T), 3 * V)]
    err = _error(singular)
    assert err.equation is None
    assert err.culprit is None
    assert "singular" in str(err)
    assert str(err).startswith("the model's equations:")
    err = _error([sympy.Eq(X.diff(T), -X / TAU), sympy.Eq(X.diff(T), -2 * X / TAU)])
    assert "2 equation(s) for 1 state(s) (x)" in str(err)
    err = _error([GOOD_V])  # v' without x': x(t) appears but is no state
    assert "x(t) is a function of time whose derivative appears in no equation" in str(err)
    assert err.index == 1


def test_symbols_without_a_dimension_are_named():
    with pytest.raises(pt.UnknownVariableError) as info:
        pt.Model(pt.System(DIMS), [sympy.Eq(X.diff(T), V), sympy.Eq(V.diff(T), -sympy.Symbol("k") * X)])
    assert info.value.name == "k"
    assert "equation 2 of the model" in str(info.value)
    assert "tau, l, t, x, v" in str(info.value)  # what would be valid
    with pytest.raises(pt.UnknownVariableError, match="'u'"):
        pt.Model(pt.System(DIMS), [sympy.Eq(X.diff(T), sympy.Function("u")(T)), GOOD_V])


def test_a_listed_parameter_must_cover_the_equations():
    err = _error([sympy.Eq(X.diff(T), V), sympy.Eq(V.diff(T), -L / TAU**2)], parameters=("tau",))
    assert err.index == 2
    assert "'l', which is not among the parameters ('tau',)" in str(err)


def test_a_model_with_no_state_is_refused():
    err = _error([sympy.Eq(sympy.Symbol("x"), L)])
    assert "no equation holds the time derivative of a state" in str(err)


# -- the value type --------------------------------------------------------------------------------


def test_model_is_immutable_and_hashable():
    rod = models.hinged_rod()
    with pytest.raises(dataclasses.FrozenInstanceError):
        rod.name = "other"
    with pytest.raises(dataclasses.FrozenInstanceError):
        rod.rhs = None
    with pytest.raises(TypeError):
        rod.defaults["m"] = 3.0
    with pytest.raises(TypeError):
        rod.initial["theta"] = 0.0
    assert hash(rod) == hash(models.hinged_rod())
    assert rod == models.hinged_rod()
    assert rod != models.spring_mass_damper()
    assert rod != dataclasses.replace(rod, defaults={**rod.defaults, "m": 2.0})
    assert isinstance(rod.parameters, tuple)
    assert "hinged_rod" in repr(rod)


@pytest.mark.parametrize("factory", [models.hinged_rod, models.projectile, _decay])
def test_models_pickle_and_their_rhs_is_regenerated(factory):
    model = factory()
    again = pickle.loads(pickle.dumps(model))
    assert again == model
    assert hash(again) == hash(model)
    assert again.parameters == model.parameters
    assert again.states == model.states
    assert dict(again.defaults) == dict(model.defaults)
    assert again.description == model.description
    y, p = model.resolve_initial(), model.resolve_params()
    np.testing.assert_array_equal(again.rhs(0.5, y, p), model.rhs(0.5, y, p))


def test_model_copies_mutable_inputs():
    defaults = {"tau": 2.0}
    equations = [sympy.Eq(X.diff(T), -X / TAU)]
    model = _decay(defaults=defaults, parameters=["tau"], equations=equations)
    defaults["tau"] = 5.0
    equations.append(GOOD_V)
    assert model.defaults["tau"] == 2.0
    assert model.parameters == ("tau",)
    assert len(model.equations) == 1


def test_resolve_params_and_initial():
    rod = models.hinged_rod()
    p = rod.resolve_params({"g": 1.62})
    assert p["g"] == 1.62
    assert p["m"] == 1.5
    assert list(p) == list(rod.parameters)
    with pytest.raises(pt.UnknownVariableError, match="'mass' in params of model 'hinged_rod'"):
        rod.resolve_params({"mass": 2.0})
    with pytest.raises(pt.InvalidRequestError, match="'g'"):
        rod.resolve_params({"g": "strong"})
    with pytest.raises(pt.InvalidRequestError, match="'g'"):
        rod.resolve_params({"g": float("nan")})
    with pytest.raises(pt.InvalidRequestError, match="mapping"):
        rod.resolve_params([1.0, 2.0])
    no_default = _decay(defaults={})
    with pytest.raises(pt.InvalidRequestError, match=r"'tau' of model 'decay' has no default"):
        no_default.resolve_params()
    with pytest.raises(pt.InvalidRequestError, match=r"'tau' of model 'model' has no default"):
        _decay(defaults={}, name="").resolve_params()  # a model without a name is called 'model'

    assert rod.resolve_initial().tolist() == [math.pi / 4, 0.0]
    assert rod.resolve_initial({"omega": 1.0}).tolist() == [math.pi / 4, 1.0]
    assert rod.resolve_initial([0.1, 0.2]).tolist() == [0.1, 0.2]
    with pytest.raises(pt.InvalidRequestError, match=r"3 values but model 'hinged_rod' has 2 states"):
        rod.resolve_initial([0.1, 0.2, 0.3])
    with pytest.raises(pt.UnknownVariableError, match="'phi' in y0 of model 'hinged_rod'"):
        rod.resolve_initial({"phi": 0.0})
    with pytest.raises(pt.InvalidRequestError, match=r"'x' of model 'decay' has no initial value"):
        _decay(initial={}).resolve_initial()
    with pytest.raises(pt.InvalidRequestError, match="finite numbers, one per state"):
        rod.resolve_initial([float("nan"), 0.0])
    with pytest.raises(pt.InvalidRequestError, match="finite numbers, one per state"):
        rod.resolve_initial({"omega": float("inf")})
    with pytest.raises(pt.InvalidRequestError, match="finite numbers, one per state"):
        rod.resolve_initial([[0.1, 0.2], [0.3, 0.4]])  # two rows for two states: not a state vector
    with pytest.raises(pt.InvalidRequestError):
        rod.resolve_initial(["a", "b"])
    with pytest.raises(pt.InvalidRequestError):
        rod.resolve_initial(5)
    with pytest.raises(pt.UnknownVariableError, match="'m'"):
        rod.state_dimension("m")
    assert str(rod.state_dimension("omega")) == "T^-1"
