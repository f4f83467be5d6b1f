"""Simulation of models and numerical verification of similarity.

This module owns :func:`simulate` (scipy's ``solve_ivp`` or fixed-step
explicit Euler), the :class:`Trajectory` it returns, and
:func:`verify_similarity`: run a model, run it again with its parameters,
initial state, time span and step size scaled, map the scaled run back to
the original units and measure the difference, collected in a
:class:`SimilarityReport`.  A similarity scaling (a change of base units,
see :mod:`pitheorem.scaling`) must reproduce the original run up to the
solver's tolerance; any other scaling generally does not.

What every simulator of the package shares lives here too, public, for
:mod:`pitheorem.engines`: :class:`ModelScaling` (a scaling applied to one
model's inputs and mapped back from its run), :func:`similarity_report`
(the one comparison and verdict), :func:`nudged` (the one-ulp baseline),
:func:`fixed_steps` (the step count of Euler and of the paper's rod in an
engine; :func:`pitheorem.engines.verify` takes ``round(duration / dt)``
steps of the model's own time step) and
:func:`positive_float` (the check of a time, a step, a tolerance or ``s``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from types import MappingProxyType

import numpy as np

from .errors import InvalidRequestError, NumberError, PiTheoremError, SystemMismatchError, UnknownVariableError
from .exact import read_exponent, read_positive, short_text
from .formatting import TableDisplay
from .model import Model
from .scaling import Scaling, float_power
from .system import System

__all__ = [
    "ModelScaling",
    "SimilarityReport",
    "Trajectory",
    "first_broken_row",
    "fixed_steps",
    "nudged",
    "positive_float",
    "similarity_report",
    "simulate",
    "verify_similarity",
]


@dataclass(frozen=True, eq=False)
class Trajectory:
    """Sampled solution of a model: times and states, read-only.

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        Sample times.
    y : numpy.ndarray, shape (N, n_states)
        One row per time, one column per state.
    states : tuple of str
        Names of the columns.
    time : str
        Name of the time variable.

    Examples
    --------
    >>> import numpy as np
    >>> import pitheorem as pt
    >>> tr = pt.Trajectory(np.array([0.0, 1.0]), np.array([[1.0, 0.0], [0.5, -1.0]]), ("y", "v"))
    >>> tr["v"].tolist()
    [0.0, -1.0]
    >>> len(tr)
    2
    """

    t: np.ndarray
    y: np.ndarray
    states: tuple[str, ...]
    time: str = "t"

    def __post_init__(self):
        t = np.array(self.t, dtype=float)
        y = np.array(self.y, dtype=float)
        states = tuple(self.states)
        if y.ndim == 1:
            y = y[:, None]
        if t.ndim != 1 or y.shape != (t.shape[0], len(states)):
            raise InvalidRequestError(
                f"a trajectory needs t of shape (N,) and y of shape (N, {len(states)}); got {t.shape} and {y.shape}"
            )
        t.flags.writeable = False
        y.flags.writeable = False
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "y", y)
        object.__setattr__(self, "states", states)

    def __getitem__(self, name: str) -> np.ndarray:
        """The samples of one state.

        Examples
        --------
        >>> import pitheorem as pt
        >>> tr = pt.Trajectory([0.0], [[2.0]], ("x",))
        >>> tr["x"].tolist()
        [2.0]
        """
        if name not in self.states:
            raise UnknownVariableError(str(name), self.states, "trajectory states")
        return self.y[:, self.states.index(name)]

    def __len__(self) -> int:
        return self.t.shape[0]

    def __repr__(self) -> str:
        span = f"{self.t[0]:g}..{self.t[-1]:g}" if len(self) else "empty"
        return f"<Trajectory {self.time}={span}, {len(self)} samples, states {self.states}>"


# -- input checks ---------------------------------------------------------------------------


def positive_float(value, what: str) -> float:
    """A positive finite number as a float, or an error that names it.

    The check of every time span, step size, tolerance and scale factor a
    simulation takes.

    Parameters
    ----------
    value : number or str
        The value given; ``True`` and ``False`` are refused.
    what : str
        What it is, for the message (``"t_final"``, ``"the scale factor s"``).

    Returns
    -------
    float
        The value, read by :func:`pitheorem.exact.read_positive` (whose
        :class:`~pitheorem.NumberError` names `what`) and rounded once.

    Examples
    --------
    >>> from pitheorem.simulation import positive_float
    >>> positive_float("2.5", "dt")
    2.5
    >>> try:
    ...     positive_float(0, "dt")
    ... except ValueError as err:
    ...     print(err)
    dt must be a positive finite number such as 2, 0.5 or '1/3', got 0
    >>> try:
    ...     positive_float("1e-400", "dt")
    ... except ValueError as err:
    ...     print(err)
    dt must be a positive number within the range of floating point (about 1e-308 to 1e308), got '1e-400'
    """
    if isinstance(value, float) and 0.0 < value < math.inf:
        return float(value)  # what the exact reading below gives for it, without reading it
    number = read_positive(value, what, irrational_ok=True)
    try:
        x = float(number)
    except OverflowError:
        x = math.inf
    if not 0.0 < x < math.inf:  # exact and positive, but it rounds to 0 or overflows
        raise NumberError(value, what, "a positive number within the range of floating point (about 1e-308 to 1e308)")
    return x


_METHODS = ("solve_ivp", "euler")


def _check_method(method) -> str:
    if method not in _METHODS:
        raise InvalidRequestError(f"unknown method {method!r}; use one of {', '.join(map(repr, _METHODS))}")
    return method


def _check_model(model) -> Model:
    if not isinstance(model, Model):
        raise InvalidRequestError(
            f"model must be a pitheorem Model (e.g. pt.models.hinged_rod()), got {type(model).__name__}"
        )
    return model


def fixed_steps(t_final: float, dt: float) -> int:
    """The number of fixed steps ``dt`` that cover ``[0, t_final]``.

    ``t_final / dt``, rounded to the nearest whole number when within
    ``1e-9`` of it (so ``1.0 / 0.1`` takes 10 steps, not 11), else rounded
    up; at least one.

    Parameters
    ----------
    t_final : float
        The end time, positive.
    dt : float
        The step, positive.

    Returns
    -------
    int

    Examples
    --------
    >>> from pitheorem.simulation import fixed_steps
    >>> fixed_steps(1.0, 0.1), fixed_steps(1.05, 0.1)
    (10, 11)
    """
    ratio = t_final / dt
    n = round(ratio)
    if abs(ratio - n) > 1e-9 * max(1.0, ratio):
        n = math.ceil(ratio)
    return max(int(n), 1)


# -- integrators ----------------------------------------------------------------------------


def _euler(rhs, params, y0, dt, n_steps):
    t = np.arange(n_steps + 1, dtype=float) * dt
    y = np.empty((n_steps + 1, y0.shape[0]))
    y[0] = y0
    current = y0
    for i in range(1, n_steps + 1):
        current = current + np.asarray(rhs(t[i - 1], current, params), dtype=float) * dt
        y[i] = current
    return t, y


def _solve_ivp(rhs, params, y0, t_final, t_eval, rtol, atol, ivp_method):
    from scipy.integrate import solve_ivp

    sol = solve_ivp(
        lambda t, y: rhs(t, y, params),
        (0.0, t_final),
        y0,
        method=ivp_method,
        t_eval=t_eval,
        rtol=rtol,
        atol=atol,
    )
    if not sol.success:
        raise PiTheoremError(f"solve_ivp failed: {sol.message}")
    return sol.t, sol.y.T


def _run(model, params, y0, t_final, method, dt, n_steps, t_eval, rtol, atol, ivp_method):
    if method == "euler":
        t, y = _euler(model.rhs, params, y0, dt, n_steps)
    else:
        t, y = _solve_ivp(model.rhs, params, y0, t_final, t_eval, rtol, atol, ivp_method)
    return Trajectory(t, y, model.states, model.time)


def _default_grid(t_final: float) -> np.ndarray:
    return np.linspace(0.0, t_final, 1001)


def simulate(
    model,
    params=None,
    y0=None,
    t_final=10.0,
    *,
    method="solve_ivp",
    dt=None,
    t_eval=None,
    rtol=1e-10,
    atol=1e-12,
    ivp_method="DOP853",
) -> Trajectory:
    """Integrate a model from its initial state over ``[0, t_final]``.

    Two engines:

    * ``method="solve_ivp"``: scipy's adaptive ``solve_ivp`` (``ivp_method``,
      default ``"DOP853"``) with tolerances `rtol`, `atol`, sampled at
      `t_eval` (default 1001 evenly spaced times);
    * ``method="euler"``: fixed-step explicit Euler,
      ``y_i = y_{i-1} + f(t_{i-1}, y_{i-1}) dt`` at ``t_i = i dt``, with
      ``N = t_final/dt`` steps (rounded up when `t_final` is not a multiple
      of `dt`, so the run may end up to one step after `t_final`).

    The step size ``dt`` is a hidden parameter of every fixed-step engine
    (Euler here, the fixed time step of Bullet, MuJoCo or NTRT): it has
    dimension ``T`` and must be scaled like time for a scaled run to be
    exactly similar; see :func:`verify_similarity`.

    Parameters
    ----------
    model : Model
    params : mapping of str to float, optional
        Parameter values; unlisted parameters take the model's defaults.
    y0 : mapping or sequence of float, optional
        Initial state: a mapping overrides defaults by name, a sequence
        gives every state in order.  Default: the model's initial values.
    t_final : float
        End time (positive).
    method : {"solve_ivp", "euler"}
    dt : float, optional
        Euler step; required for ``method="euler"``.
    t_eval : array_like, optional
        Sample times for ``solve_ivp`` (within ``[0, t_final]``).
    rtol, atol : float
        Tolerances of ``solve_ivp``; `atol` may be one value per state.
    ivp_method : str
        Integrator of ``solve_ivp``.

    Returns
    -------
    Trajectory

    Raises
    ------
    InvalidRequestError
        For a bad method, a missing or non-positive `dt` or `t_final`, a
        wrong-length `y0`, a missing parameter value.
    UnknownVariableError
        For a name in `params` or `y0` that the model does not have.

    Examples
    --------
    >>> import pitheorem as pt
    >>> smd = pt.models.spring_mass_damper()
    >>> tr = pt.simulate(smd, t_final=0.5, method="euler", dt=0.01)
    >>> len(tr), round(float(tr["y"][-1]), 6)
    (51, 0.837309)
    >>> tr2 = pt.simulate(smd, {"g": 1.62}, t_final=0.5, t_eval=[0.0, 0.5])
    >>> tr2.t.tolist()
    [0.0, 0.5]
    """
    model = _check_model(model)
    method = _check_method(method)
    t_final = positive_float(t_final, "t_final")
    p = model.resolve_params(params)
    y_init = model.resolve_initial(y0)
    if method == "euler":
        if dt is None:
            raise InvalidRequestError("method='euler' needs a step size dt (a positive time)")
        dt = positive_float(dt, "dt")
        if t_eval is not None:
            raise InvalidRequestError("t_eval is only for method='solve_ivp'; Euler samples every step i*dt")
        return _run(model, p, y_init, t_final, method, dt, fixed_steps(t_final, dt), None, rtol, atol, ivp_method)
    if dt is not None:
        raise InvalidRequestError("dt is only for method='euler'; solve_ivp chooses its own steps")
    rtol = positive_float(rtol, "rtol")
    if t_eval is None:
        grid = _default_grid(t_final)
    else:
        grid = np.asarray(t_eval, dtype=float)
        if grid.ndim != 1 or grid.size == 0 or not np.all(np.isfinite(grid)):
            raise InvalidRequestError(f"t_eval must be a non-empty 1-d array of times, got {t_eval!r}")
        if grid.min() < 0 or grid.max() > t_final:
            raise InvalidRequestError(f"t_eval must lie within [0, t_final] = [0, {t_final}]")
        if np.any(np.diff(grid) <= 0):  # solve_ivp refuses a time given twice as well
            raise InvalidRequestError("t_eval must be strictly increasing: sorted, no time twice")
    return _run(model, p, y_init, t_final, method, None, None, grid, rtol, atol, ivp_method)


# -- similarity -----------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ModelScaling:
    """A scaling applied to one model: a factor for each parameter, the time and each state.

    What a verification does with a scaling, written once: scale the
    parameters and the initial state, scale the time span (and a fixed
    step) by the time's factor, and map the scaled run back to original
    units.  :func:`verify_similarity` and
    :func:`pitheorem.engines.verify_engine_similarity` both use it.  Build
    it with :meth:`of`.

    Parameters
    ----------
    model : Model
    s : float
        The scale factor.
    scaling : Scaling or mapping of str to Fraction
        The similarity scaling applied; the raw exponents, read-only, when
        they are not one (built with ``check=False``).
    exponents : mapping of str to Fraction
        The power of ``s`` of each parameter, the time and each state.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.simulation import ModelScaling
    >>> smd = pt.models.spring_mass_damper()
    >>> length = ModelScaling.of(smd, {"g": 1, "y_rest": 1}, s=2)   # the length unit
    >>> length.is_similarity, length.factor("v"), length.factor("t")
    (True, 2.0, 1.0)
    >>> length.scale_params({"g": 9.81, "m": 2.0})
    {'g': 19.62, 'm': 2.0}
    """

    model: Model
    s: float
    scaling: Scaling | Mapping[str, Fraction]
    exponents: Mapping[str, Fraction]

    @classmethod
    def of(cls, model: Model, scaling, s, *, check: bool = True) -> ModelScaling:
        """The scaling `scaling` applied to `model` with scale factor `s`.

        Parameters
        ----------
        model : Model
        scaling : Scaling or mapping of str to number
            As in :func:`verify_similarity`, which raises the same errors
            for it: a scaling of the model's variables, or exponents of
            ``s`` from which the states' exponents follow.
        s : float
            The scale factor, positive.
        check : bool
            With ``True`` a mapping of exponents must be a similarity
            scaling; with ``False`` one that is not is applied as given
            (unlisted exponents 0).

        Returns
        -------
        ModelScaling
            With every exponent an exact Fraction.

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem.simulation import ModelScaling
        >>> rod = pt.models.hinged_rod()
        >>> gravity = ModelScaling.of(rod, {"g": 1}, s=2, check=False)   # the paper's Figure 2
        >>> gravity.is_similarity, dict(gravity.scaling)["g"]
        (False, Fraction(1, 1))
        """
        s = positive_float(s, "the scale factor s")
        model = _check_model(model)
        variables = (*model.parameters, model.time, *model.states)
        if isinstance(scaling, Scaling):
            _check_scaling_system(model, scaling, variables)
            sc = scaling
        elif isinstance(scaling, Mapping):
            for n in scaling:
                if n not in variables:
                    raise UnknownVariableError(str(n), variables, "scaling exponents")
            given = {n: read_exponent(v, f"exponent of {n!r}") for n, v in scaling.items()}
            try:
                sc = _similarity_of_model(model, given)
            except InvalidRequestError:
                if check:
                    raise
                raw = MappingProxyType({n: given.get(n, Fraction(0)) for n in variables})
                return cls(model, s, raw, raw)
        else:
            raise InvalidRequestError(
                f"scaling must be a pitheorem Scaling or a dict of exponents, got {type(scaling).__name__}"
            )
        exps = sc.exponents
        return cls(model, s, sc, MappingProxyType({n: exps[n] for n in variables}))

    @property
    def is_similarity(self) -> bool:
        """Whether the exponents are a change of units (a :class:`Scaling`).

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem.simulation import ModelScaling
        >>> ModelScaling.of(pt.models.projectile(), {"g": 1}, s=2).is_similarity
        True
        """
        return isinstance(self.scaling, Scaling)

    def factor(self, name: str) -> float:
        """The factor ``s^a`` of one parameter, of the time or of one state.

        Parameters
        ----------
        name : str

        Returns
        -------
        float
            ``s`` to the power of the variable's exponent.

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem.simulation import ModelScaling
        >>> ModelScaling.of(pt.models.projectile(), {"g": 1, "t": 1}, s=2).factor("vx")
        4.0
        """
        if name not in self.exponents:
            raise UnknownVariableError(str(name), tuple(self.exponents), "the model's variables")
        return float_power(self.s, self.exponents[name], f"the factor of {name!r}")

    def scale_params(self, params: Mapping[str, float]) -> dict[str, float]:
        """Parameter values times their factors.

        Parameters
        ----------
        params : mapping of str to float
            Values of some or all of the parameters.

        Returns
        -------
        dict of str to float

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem.simulation import ModelScaling
        >>> ModelScaling.of(pt.models.projectile(), {"g": 1}, s=4).scale_params({"g": 9.81})
        {'g': 39.24}
        """
        return {n: float(v) * self.factor(n) for n, v in params.items()}

    def scale_state(self, y) -> np.ndarray:
        """A state vector (or rows of them) times the states' factors.

        Parameters
        ----------
        y : array_like, shape (n_states,) or (N, n_states)
            In the order of the model's states.

        Returns
        -------
        numpy.ndarray

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem.simulation import ModelScaling
        >>> figure5 = {"g": 1, "l": -1, "c_theta": -1, "t": -1}   # the paper's rod, twice as fast
        >>> ModelScaling.of(pt.models.hinged_rod(), figure5, s=2).scale_state([0.5, 1.0]).tolist()
        [0.5, 2.0]
        """
        return np.asarray(y, dtype=float) * self._state_factors()

    def _state_factors(self) -> np.ndarray:
        return np.array([self.factor(n) for n in self.model.states])

    def map_back(self, run: Trajectory, grid=None) -> Trajectory:
        """A run of the scaled model in original units.

        Times are divided by the time's factor and each state by its own.
        Given a `grid` of original times that the mapped times do not
        match (another length, or times apart by more than rounding), the
        mapped states are interpolated linearly onto it.

        Parameters
        ----------
        run : Trajectory
            The scaled model's run.
        grid : array_like, optional
            Original times to compare on.

        Returns
        -------
        Trajectory
            On the mapped times, or on `grid`.

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem.simulation import ModelScaling
        >>> smd = pt.models.spring_mass_damper()
        >>> slow = ModelScaling.of(smd, {"t": 1, "k": -2, "c": -1, "g": -2}, s=2)  # time unit
        >>> run = pt.Trajectory([0.0, 2.0], [[1.0, 0.0], [1.0, -4.0]], smd.states)
        >>> back = slow.map_back(run)
        >>> back.t.tolist(), back["v"].tolist()
        ([0.0, 1.0], [0.0, -8.0])
        """
        t = run.t / self.factor(self.model.time)
        y = run.y / self._state_factors()
        if grid is not None:
            grid = np.asarray(grid, dtype=float)
            if len(t) != len(grid) or not np.allclose(t, grid, rtol=1e-12, atol=0.0):
                y = np.column_stack([np.interp(grid, t, y[:, j]) for j in range(y.shape[1])])
                t = grid
        return Trajectory(t, y, self.model.states, self.model.time)


def _check_scaling_system(model: Model, scaling: Scaling, variables: tuple[str, ...]) -> None:
    other = scaling.system
    if other == model.system:
        return
    for name in variables:
        if name not in other.variables:
            raise SystemMismatchError(name, f"variable {name!r} of the model is missing from the scaling's system")
        mine, theirs = model.system.dimension(name), other.dimension(name)
        if mine != theirs:
            raise SystemMismatchError(
                name, f"variable {name!r} has dimension {mine} in the model but {theirs} in the scaling's system"
            )


def _similarity_of_model(model: Model, given: Mapping[str, Fraction]) -> Scaling:
    """The similarity scaling of the model's system with the given exponents (unlisted parameters and time: 0)."""
    # the parameters and time determine the change of units; states follow from it
    core = (*model.parameters, model.time)
    sub = System({n: model.system.dimension(n) for n in core})
    free = [n for n in model.states if System({**sub.dimensions, n: model.system.dimension(n)}).rank > sub.rank]
    if free:  # states whose dimension the parameters and time cannot build: their exponents must be given
        core = (*core, *free)
        sub = System({n: model.system.dimension(n) for n in core})
    for n in free:
        if n not in given:
            raise InvalidRequestError(
                f"the exponents of the parameters and time do not determine the scaling of state {n!r} "
                f"(dimension {model.system.dimension(n)}); give its exponent too"
            )
    partial = _similarity_or_raise(sub, {n: given.get(n, Fraction(0)) for n in core})
    scaling = Scaling.from_unit_change(model.system, partial.unit_change)
    exps = scaling.exponents
    for n in model.states:
        if n in given and given[n] != exps[n]:
            raise InvalidRequestError(
                f"exponent {short_text(given[n])} of state {n!r} contradicts the scaling of the parameters and "
                f"time, which gives it {short_text(exps[n])}"
            )
    return scaling


def _similarity_or_raise(system: System, exponents: Mapping[str, Fraction]) -> Scaling:
    """``Scaling.from_exponents``, whose error names a Pi group the exponents change."""
    try:
        return Scaling.from_exponents(system, exponents)
    except InvalidRequestError:
        pass
    given = ", ".join(f"{n}: {short_text(v)}" for n, v in exponents.items() if v != 0) or "none"
    broken = ""
    for group in system.pi_groups():
        change = sum((Fraction(e) * exponents.get(n, 0) for n, e in group.exponents.items()), Fraction(0))
        if change != 0:
            broken = f"; they multiply the Pi group {group.expr} by s^{short_text(change)}"
            break
    raise InvalidRequestError(
        f"exponents ({given}) are not a similarity scaling{broken} (only changes of base units keep every "
        "group invariant)"
    )


@dataclass(frozen=True, eq=False)
class SimilarityReport(TableDisplay):
    """Result of :func:`verify_similarity`: the two runs compared.

    Attributes
    ----------
    original : Trajectory
        The run with the given parameters.
    mapped : Trajectory
        The scaled run, mapped back to original units, on the original
        time grid.
    max_deviation : float
        Largest absolute difference over all states and times.
    deviation : mapping of str to float
        Largest absolute difference of each state.
    passed : bool
        ``max_deviation <= tol``.
    tol : float
    s : float
        The scale factor.
    scaling : Scaling or mapping of str to Fraction
        The scaling used; the raw exponents when they are not a similarity
        scaling (``check=False``).
    exponents : mapping of str to Fraction
        Power of ``s`` applied to each parameter, the time and each state.
    is_similarity : bool
        Whether the exponents are a change of units.
    method : str
    scaled_dt : bool
        Whether the Euler step was scaled with time.
    sensitivity : mapping of str to float or None
        The yardstick per state: how far the model's own twins (one ulp
        off) move from the original run; None when judged by `tol`.
    baseline_factor : float
        How many times its yardstick a state's deviation may reach.
    nudged : Trajectory or None
        One twin's run (the first), for plots.
    exact : bool
        Every state of the mapped run equals the original's bit for bit at
        every time.
    first_divergence : tuple of (float, str) or None
        The first time at which the runs differ and the state that differs
        most there; None when `exact`.
    excited : bool or None
        Whether the original run moved some state beyond its yardstick; a
        run that moved nothing proves nothing.  None without a yardstick.
    causes : tuple of Cause
        Why the runs are not exact or not similar, where an engine check
        found out (:func:`pitheorem.engines.verify`).
    ensemble : int
        How many twins made the yardstick.
    horizon : float or None
        How long the twins stay within 1% of the original's motion
        (``pitheorem.engines.verdicts.strength``); past it the run is
        chaotic and the comparison says little.  None without twins.
    detection_limit : float or None
        The smallest relative error in a dimensionless group (gravity
        times ``1 + e``) that the negative controls run beside the copy
        were caught at; None when none was run or none was caught.
    controls : tuple of Control
        The negative controls that ran and whether each was caught.
    inconclusive : bool
        A group's controls (gravity's, or the masses') all passed
        unnoticed: the run cannot show an error in that group, so the
        verdict is not "similar"; or the engine gave up on the original's
        run (`engine_reset`).
    scale_free : ScaleFree or None
        At a power of four, when the runs are not bit for bit: both runs
        again with the engine's settings of no pure dimension made
        scale-free (``pitheorem.engines.verdicts.scalefree``), and whether
        they are then exact.  None otherwise.
    engine_reset : tuple of (float, str) or None
        When the engine gave up on a run: the time, and ``"original"`` or
        ``"copy"``.  MuJoCo resets a run whose acceleration or velocity is
        NaN, infinite or huge (an unstable model, or a time step too long
        for it), and its batched runs stop at any warning (a control
        beyond 1e10 too).  An original's run is then compared only before
        that time and the verdict is inconclusive; a copy's alone makes it
        not similar.  None when every run went to the end.

    Examples
    --------
    >>> import pitheorem as pt
    >>> smd = pt.models.spring_mass_damper()
    >>> sc = pt.Scaling.from_unit_change(smd.system, {"L": 1, "T": 1})
    >>> rep = pt.verify_similarity(smd, sc, s=3, t_final=0.5)
    >>> rep.passed, rep.max_deviation < 1e-8
    (True, True)
    """

    original: Trajectory
    mapped: Trajectory
    max_deviation: float
    deviation: Mapping[str, float]
    passed: bool
    tol: float
    s: float
    scaling: object
    exponents: Mapping[str, Fraction] = field(repr=False)
    is_similarity: bool = True
    method: str = "solve_ivp"
    scaled_dt: bool = True
    sensitivity: Mapping[str, float] | None = None
    baseline_factor: float = 10.0
    nudged: Trajectory | None = field(default=None, repr=False)
    exact: bool = False
    first_divergence: tuple[float, str] | None = None
    excited: bool | None = None
    causes: tuple = ()
    ensemble: int = 0
    horizon: float | None = None
    detection_limit: float | None = None
    controls: tuple = ()
    inconclusive: bool = False
    scale_free: object | None = None
    engine_reset: tuple[float, str] | None = None

    @property
    def similar(self) -> bool:
        """The verdict: passed, unless the run could not tell (inconclusive).

        Examples
        --------
        >>> import pitheorem as pt
        >>> smd = pt.models.spring_mass_damper()
        >>> sc = pt.Scaling.from_unit_change(smd.system, {"L": 1})
        >>> pt.verify_similarity(smd, sc, s=2, t_final=0.2).similar
        True
        """
        return self.passed and not self.inconclusive

    @property
    def unseen(self) -> tuple[str, ...]:
        """The groups whose negative controls all passed unnoticed: errors unseen.

        Examples
        --------
        >>> import pitheorem as pt
        >>> smd = pt.models.spring_mass_damper()
        >>> sc = pt.Scaling.from_unit_change(smd.system, {"L": 1})
        >>> pt.verify_similarity(smd, sc, s=2, t_final=0.2).unseen  # no controls: nothing unseen
        ()
        """
        return unseen_groups(self.controls)

    @property
    def verdict(self) -> str:
        """The verdict in one word: exact, similar, inconclusive or not similar.

        Examples
        --------
        >>> import pitheorem as pt
        >>> smd = pt.models.spring_mass_damper()
        >>> sc = pt.Scaling.from_unit_change(smd.system, {"L": 1})
        >>> pt.verify_similarity(smd, sc, s=3, t_final=0.2).verdict, pt.verify_similarity(smd, sc, s=2, t_final=0.2).verdict
        ('similar', 'exact')
        """
        if not self.passed:
            return "not similar"
        if self.inconclusive:
            return "inconclusive"
        return "exact" if self.exact else "similar"

    @property
    def difference(self) -> np.ndarray:
        """``mapped.y - original.y``, shape ``(N, n_states)``.

        Examples
        --------
        >>> import pitheorem as pt
        >>> smd = pt.models.spring_mass_damper()
        >>> rep = pt.verify_similarity(smd, {"g": 2}, s=2, t_final=0.2, check=False)
        >>> rep.difference.shape
        (1001, 2)
        """
        return self.mapped.y - self.original.y

    def plot(self, states=None, units=None):
        """Figure comparing the original and the mapped-back scaled run.

        Top axes: each state of the original run (solid) and of the scaled
        run mapped back to original units (dashed), against original time.
        Bottom axes: the absolute difference of each state. See
        :func:`pitheorem.plotting.plot_similarity`.

        Parameters
        ----------
        states : sequence of str, optional
            The states drawn; all of them by default.
        units : mapping of str to str, optional
            Axis units by name, such as ``{"theta": "rad", "t": "s"}``; a
            name without one shows its dimension.

        Returns
        -------
        matplotlib.figure.Figure
            Made with pyplot: Jupyter shows it once, at the end of the cell.

        Examples
        --------
        >>> import pitheorem as pt
        >>> rep = pt.verify_similarity(pt.models.hinged_rod(), {"g": 1}, s=2, t_final=0.2,
        ...                            check=False)
        >>> fig = rep.plot(states=["theta"], units={"theta": "rad", "t": "s"})
        >>> len(fig.axes), fig.axes[1].get_ylabel()
        (2, '|difference|: theta [rad]')
        """
        from .plotting import plot_similarity

        return plot_similarity(self, states=states, units=units)


def verify_similarity(
    model,
    scaling,
    s,
    params=None,
    y0=None,
    t_final=10.0,
    *,
    method="solve_ivp",
    dt=None,
    scale_dt=True,
    check=True,
    rtol=1e-10,
    atol=1e-12,
    tol=1e-6,
    ivp_method="DOP853",
    baseline=False,
) -> SimilarityReport:
    """Check numerically that a scaled run reproduces the original.

    Simulates the model with `params`; then scales each parameter and
    each initial state by ``s`` to its exponent, the end time by
    ``s^(a_t)`` and (with `scale_dt`) the Euler step likewise, simulates
    again, maps the scaled trajectory back to original units and compares
    (``pitheorem.simulation.ModelScaling`` scales and maps back).  For
    ``solve_ivp`` the scaled run is sampled at the original times times
    ``s^(a_t)`` and its `atol` is scaled per state, so the adaptive step
    control sees the same problem; for Euler with scaled ``dt`` the two
    grids correspond step for step.  Otherwise (Euler with ``dt``
    unscaled) the mapped run is interpolated linearly onto the original
    grid.

    The step size ``dt`` of a fixed-step engine is a hidden parameter of
    dimension ``T``: leaving it unscaled while time is scaled breaks
    exact similarity by ``O(dt)``.

    Parameters
    ----------
    model : Model
    scaling : Scaling or mapping of str to number
        A scaling of ``model.system`` (or of a system holding all of the
        model's variables with the same dimensions), or exponents of ``s``
        per parameter and time (unlisted: 0).  The states' exponents follow
        from the change of units; list one only when the parameters and
        time cannot determine it (or to have it checked).
    s : float
        Scale factor, positive.
    params, y0, t_final, method, dt, rtol, atol, ivp_method
        As in :func:`simulate`, for the original run.
    scale_dt : bool
        Scale the Euler step with time (default); ``False`` keeps it.
    check : bool
        With ``True`` a dict of exponents must be a similarity scaling
        (else :class:`InvalidRequestError`).  With ``False`` a dict that is
        not is applied as given: each parameter, the time and each state
        by its listed exponent (default 0) -- to demonstrate wrong scalings.
    tol : float
        Largest deviation (in original units) that passes.
    baseline : bool
        Also run the original with every initial state nudged by one ulp
        (``pitheorem.simulation.nudged``) and judge each state's deviation against that
        run's, as :func:`pitheorem.engines.verify` does, instead of `tol`.

    Returns
    -------
    SimilarityReport

    Raises
    ------
    SystemMismatchError
        When the scaling's system lacks a model variable or gives it
        another dimension.
    InvalidRequestError, UnknownVariableError
        For bad inputs (see :func:`simulate`), a non-positive `s`, or
        exponents that are not a similarity scaling while `check` holds.

    Examples
    --------
    The paper's Figure 5 scaling of the hinged rod (g by s, l by 1/s, hence
    c_theta by 1/s and time by 1/s), found by :func:`pitheorem.search`:

    >>> import pitheorem as pt
    >>> rod = pt.models.hinged_rod()
    >>> sc = pt.search(rod.system, scale={"g": 1, "l": -1}, fixed=("m", "k_theta")).scalings[0]
    >>> rep = pt.verify_similarity(rod, sc, s=2, t_final=0.5)
    >>> rep.passed
    True

    The paper's Figure 2 (gravity alone scaled) is not a similarity:

    >>> bad = pt.verify_similarity(rod, {"g": 1}, s=2, t_final=0.5, check=False)
    >>> bad.passed, bad.is_similarity
    (False, False)
    """
    model = _check_model(model)
    method = _check_method(method)
    scaled = ModelScaling.of(model, scaling, s, check=check)
    tol = positive_float(tol, "tol")
    original = simulate(model, params, y0, t_final, method=method, dt=dt, rtol=rtol, atol=atol, ivp_method=ivp_method)
    # read as simulate read them ("1/2", Fractions): it has refused what is no positive number
    t_final = positive_float(t_final, "t_final")
    dt = None if dt is None else positive_float(dt, "dt")
    p = model.resolve_params(params)
    y_init = model.resolve_initial(y0)
    f_t = scaled.factor(model.time)
    t_final_scaled = t_final * f_t
    y_scaled = scaled.scale_state(y_init)
    if method == "euler":
        if scale_dt:
            dt_scaled, n_steps = dt * f_t, len(original) - 1  # same steps, one for one
        else:
            dt_scaled = dt
            n_steps = fixed_steps(t_final_scaled, dt_scaled)
        run = _run(
            model,
            scaled.scale_params(p),
            y_scaled,
            t_final_scaled,
            method,
            dt_scaled,
            n_steps,
            None,
            rtol,
            atol,
            ivp_method,
        )
    else:
        grid = np.minimum(original.t * f_t, t_final_scaled)
        atol_scaled = scaled.scale_state(np.broadcast_to(np.asarray(atol, dtype=float), y_init.shape))
        run = _run(
            model,
            scaled.scale_params(p),
            y_scaled,
            t_final_scaled,
            method,
            None,
            None,
            grid,
            rtol,
            atol_scaled,
            ivp_method,
        )
    mapped = scaled.map_back(run, original.t)

    reference = None
    if baseline:  # the same run from a one-ulp nudged start, on the same grid
        kwargs = {"dt": dt} if method == "euler" else {"t_eval": original.t, "rtol": rtol, "atol": atol}
        reference = simulate(model, params, nudged(y_init), t_final, method=method, ivp_method=ivp_method, **kwargs)
    return similarity_report(
        original,
        mapped,
        s=scaled.s,
        scaling=scaled.scaling,
        exponents=scaled.exponents,
        tol=None if baseline else tol,
        nudged=reference,
        is_similarity=scaled.is_similarity,
        method=method,
        scaled_dt=bool(scale_dt) if method == "euler" else True,
    )


def nudged(values) -> np.ndarray:
    """Each value moved up by one ulp: to the next double, by the ulp of 1 near 0.

    A value of magnitude 1 or more moves to the next double up (from
    ``-1.0`` that is ``1.1e-16`` away, half the ulp of ``1.0``); a smaller
    one by the ulp of 1.  A coordinate at exactly 0 has a denormal ulp
    (5e-324) that no computation feels; the ulp of 1 (2.2e-16) is the
    rounding every step makes on numbers of order one.

    Examples
    --------
    >>> from pitheorem.simulation import nudged
    >>> [float(v) for v in nudged([0.0, 4.0, -1.0])]
    [2.220446049250313e-16, 4.000000000000001, -0.9999999999999999]
    """
    x = np.asarray(values, dtype=float)
    return np.where(np.abs(x) >= 1.0, np.nextafter(x, np.inf), x + np.spacing(1.0))


def _max_abs(diff: np.ndarray) -> float:
    worst = float(diff.max()) if diff.size else 0.0
    return worst if math.isfinite(worst) and np.all(np.isfinite(diff)) else math.inf


def similarity_report(
    original: Trajectory,
    mapped: Trajectory,
    *,
    s: float,
    scaling,
    exponents,
    tol: float | None = None,
    nudged: Trajectory | None = None,
    baseline_factor: float = 10.0,
    is_similarity: bool = True,
    method: str = "solve_ivp",
    scaled_dt: bool = True,
    twins=None,
    causes=(),
) -> SimilarityReport:
    """Compare an original run with a scaled run mapped back: the one verdict of every simulator.

    :func:`verify_similarity` (scipy or Euler) and
    :func:`pitheorem.engines.verify` (MuJoCo, PyBullet) both end here.  The
    verdict is either absolute, ``max_deviation <= tol``, or, given a run
    `nudged` whose initial state moved by one ulp, relative to the model's
    own sensitivity: each state's deviation must stay within
    ``baseline_factor`` times the nudged run's deviation from the original,
    or below ``1e-9`` of the state's range where the nudge changed nothing.

    Parameters
    ----------
    original, mapped : Trajectory
        On the same time grid and states; `mapped` in original units.
    s : float
    scaling : Scaling or mapping
    exponents : mapping of str to Fraction
    tol : float, optional
        Absolute tolerance (used when `nudged` is None).
    nudged : Trajectory, optional
        The one-ulp sensitivity baseline.
    baseline_factor : float
    is_similarity, method, scaled_dt
        Recorded in the report.
    twins : sequence of Trajectory, optional
        Runs of twins of the original (every stored number one ulp off):
        the yardstick is their largest distance from the original, per
        state, instead of `nudged`'s alone.
    causes : sequence of Cause
        Recorded in the report.

    Returns
    -------
    SimilarityReport

    Examples
    --------
    >>> import numpy as np
    >>> import pitheorem as pt
    >>> from pitheorem.simulation import similarity_report
    >>> a = pt.Trajectory([0.0, 1.0], [[1.0], [2.0]], ("x",))
    >>> b = pt.Trajectory([0.0, 1.0], [[1.0], [2.0 + 1e-15]], ("x",))
    >>> n = pt.Trajectory([0.0, 1.0], [[1.0], [2.0 + 4e-16]], ("x",))
    >>> similarity_report(a, b, s=2, scaling={}, exponents={}, nudged=n).similar
    True
    """
    if original.y.shape != mapped.y.shape:
        raise InvalidRequestError(f"runs of shapes {original.y.shape} and {mapped.y.shape} cannot be compared")
    diff = np.abs(mapped.y - original.y)
    states = original.states
    divergence = first_divergence(original, mapped)
    per_state = {n: _max_abs(diff[:, j]) for j, n in enumerate(states)}
    worst = _max_abs(diff)
    sensitivity = excited = None
    twins = tuple(twins or ()) or ((nudged,) if nudged is not None else ())
    if twins:
        nudged = twins[0]
        base = np.max([np.abs(twin.y - original.y) for twin in twins], axis=0)
        sensitivity = {n: _max_abs(base[:, j]) for j, n in enumerate(states)}
        limits = allowed_deviation(original, sensitivity, baseline_factor)
        moved = np.max(np.abs(original.y - original.y[:1]), axis=0) if len(original) else np.zeros(len(states))
        passed = all(per_state[n] <= limits[j] for j, n in enumerate(states))
        excited = bool(np.any(moved > limits))
        tol = math.nan if tol is None else tol
    else:
        if tol is None:
            raise InvalidRequestError("similarity_report needs tol or a nudged baseline run")
        passed = worst <= tol
    return SimilarityReport(
        original=original,
        mapped=mapped,
        max_deviation=worst,
        deviation=MappingProxyType(per_state),
        passed=passed,
        tol=tol,
        s=s,
        scaling=scaling,
        exponents=MappingProxyType(dict(exponents)),
        is_similarity=is_similarity,
        method=method,
        scaled_dt=scaled_dt,
        sensitivity=None if sensitivity is None else MappingProxyType(sensitivity),
        baseline_factor=baseline_factor,
        nudged=nudged,
        exact=divergence is None,
        first_divergence=divergence,
        excited=excited,
        causes=tuple(causes),
        ensemble=len(twins),
    )


def allowed_deviation(original: Trajectory, sensitivity, baseline_factor: float) -> np.ndarray:
    """Each state's largest allowed deviation: `baseline_factor` times its sensitivity, or 1e-9 of its range.

    The floor is for a state the baseline runs do not move at all.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.simulation import allowed_deviation
    >>> run = pt.Trajectory([0.0, 1.0], [[0.0, 5.0], [2.0, 5.0]], ("x", "v"))
    >>> [float(v) for v in allowed_deviation(run, {"x": 1e-15, "v": 0.0}, 10.0)]
    [2e-09, 0.0]
    """
    span = np.ptp(original.y, axis=0) if len(original) else np.zeros(len(original.states))
    return np.array(
        [max(baseline_factor * sensitivity[n], 1e-9 * float(span[j])) for j, n in enumerate(original.states)]
    )


def unseen_groups(controls) -> tuple[str, ...]:
    """The groups whose every negative control passed unnoticed: errors a run cannot see, in the controls' order.

    Each control has a ``group`` (``"g"``, ``"masses"``) and whether it was
    ``caught`` (``pitheorem.engines.verdicts.strength.Control``).

    Examples
    --------
    >>> from pitheorem.engines.verdicts.strength import Control
    >>> from pitheorem.simulation import unseen_groups
    >>> unseen_groups([Control("g", 1e-4, False), Control("g", 1.0, False), Control("masses", 1.0, True)])
    ('g',)
    >>> unseen_groups([Control("g", 1e-4, False), Control("g", 1.0, True)])
    ()
    """
    groups = dict.fromkeys(c.group for c in controls)
    return tuple(g for g in groups if not any(c.caught for c in controls if c.group == g))


def first_broken_row(rows) -> int | None:
    """The first row of a run with a number that is not finite (the engine gave up on the run there), or None.

    Examples
    --------
    >>> import numpy as np
    >>> from pitheorem.simulation import first_broken_row
    >>> first_broken_row(np.array([[0.0, 1.0], [2.0, np.nan], [np.inf, 0.0]])), first_broken_row(np.zeros((2, 2)))
    (1, None)
    """
    bad = ~np.isfinite(rows).all(axis=1)
    return int(np.argmax(bad)) if bad.any() else None


def first_divergence(original: Trajectory, mapped: Trajectory) -> tuple[float, str] | None:
    """The first time two runs differ in any bit, and the state that differs most there; None if identical.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.simulation import first_divergence
    >>> a = pt.Trajectory([0.0, 1.0, 2.0], [[1.0, 5.0], [2.0, 5.0], [3.0, 5.0]], ("x", "v"))
    >>> b = pt.Trajectory([0.0, 1.0, 2.0], [[1.0, 5.0], [2.0, 5.5], [3.1, 5.0]], ("x", "v"))
    >>> first_divergence(a, b), first_divergence(a, a)
    ((1.0, 'v'), None)
    """
    same = original.y == mapped.y  # a NaN equals nothing: a run that blew up is never exact
    rows = np.nonzero(~same.all(axis=1))[0]
    if not rows.size:
        return None
    i = int(rows[0])
    with np.errstate(invalid="ignore"):
        gap = np.abs(mapped.y[i] - original.y[i])
    j = int(np.argmax(np.where(np.isnan(gap), np.inf, gap)))
    return float(original.t[i]), original.states[j]
