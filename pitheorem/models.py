"""Dynamical models and parameter lists of the white paper, in its notation.

This module owns the :class:`Model` value type -- a right-hand side
``dy/dt = f(t, y, params)`` together with a :class:`~pitheorem.System` that
gives a dimension to every parameter, to the time variable and to every
state -- and the shipped models:

* :func:`hinged_rod`: the rod on a hinge with a rotational spring and damper
  (Eq. 1 of the paper, with the restoring spring sign of its MATLAB code);
* :func:`hinged_rod_longitudinal`: the same rod held by a longitudinal spring
  (and optionally a longitudinal damper), in a dimensionally correct form;
* :func:`spring_mass_damper`: the vertical spring-mass-damper of Section 5;
* :func:`projectile`: a point mass under gravity.

It also holds the paper's parameter lists as systems: :func:`rod_system`
(Section 2.1) and :func:`superball_parameters` (Section 4, NTRT SUPERball).
Simulation and similarity checks live in :mod:`pitheorem.simulate`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from .errors import DuplicateVariableError, InvalidRequestError, UnknownVariableError
from .system import System

__all__ = [
    "Model",
    "hinged_rod",
    "hinged_rod_longitudinal",
    "model_equations",
    "projectile",
    "rod_system",
    "spring_mass_damper",
    "superball_parameters",
]


def _frozen_mapping(values, what: str) -> MappingProxyType:
    if values is None:
        return MappingProxyType({})
    try:
        items = dict(values)
    except (TypeError, ValueError):
        raise InvalidRequestError(f"{what} must be a mapping of names to numbers, got {values!r}") from None
    out = {}
    for name, value in items.items():
        try:
            out[name] = float(value)
        except (TypeError, ValueError):
            raise InvalidRequestError(f"{what}[{name!r}] must be a number, got {value!r}") from None
    return MappingProxyType(out)


@dataclass(frozen=True)
class Model:
    """An ODE model ``dy/dt = f(t, y, params)`` with dimensions.

    Parameters
    ----------
    system : System
        Dimensions of the parameters, of the time variable and of the
        states (it may hold further variables, e.g. force).
    parameters : tuple of str
        Names of the parameters ``f`` reads from its ``params`` dict.
    states : tuple of str
        Names of the states, in the order of ``y``.
    rhs : callable
        ``f(t, y, params) -> dy/dt`` with ``y`` a float array in the order of
        `states`, ``params`` a dict of floats; returns a float array.
    time : str
        Name of the time variable (default ``"t"``).
    defaults : mapping of str to float
        Default parameter values; stored read-only.
    initial : mapping of str to float
        Default initial state values; stored read-only.
    name : str
    description : str

    Examples
    --------
    >>> import numpy as np
    >>> import pitheorem as pt
    >>> decay = pt.Model(
    ...     system=pt.System({"tau": "T", "x": "L", "t": "T"}),
    ...     parameters=("tau",), states=("x",),
    ...     rhs=lambda t, y, p: -y / p["tau"],
    ...     defaults={"tau": 2.0}, initial={"x": 1.0}, name="decay")
    >>> decay.defaults["tau"]
    2.0
    >>> decay.state_dimension("x")
    Dimension.parse('L')
    """

    system: System
    parameters: tuple[str, ...]
    states: tuple[str, ...]
    rhs: Callable = field(repr=False)
    time: str = "t"
    defaults: Mapping[str, float] = field(default_factory=dict)
    initial: Mapping[str, float] = field(default_factory=dict)
    name: str = ""
    description: str = field(default="", repr=False)

    def __post_init__(self):
        if not all(hasattr(self.system, a) for a in ("variables", "dimension", "check_names", "index")):
            raise InvalidRequestError(f"system must be a pitheorem System, got {type(self.system).__name__}")
        params = self.system.check_names(self.parameters, "parameters")
        states = self.system.check_names(self.states, "states")
        if not states:
            raise InvalidRequestError("a model needs at least one state")
        if not isinstance(self.time, str):
            raise InvalidRequestError(f"time must be a variable name, got {self.time!r}")
        self.system.index(self.time, "time")
        roles = [*params, *states, self.time]
        for n in roles:
            if roles.count(n) > 1:
                raise DuplicateVariableError(n, "the model's parameters, states and time")
        if not callable(self.rhs):
            raise InvalidRequestError(f"rhs must be callable as f(t, y, params), got {self.rhs!r}")
        defaults = _frozen_mapping(self.defaults, "defaults")
        initial = _frozen_mapping(self.initial, "initial")
        for n in defaults:
            if n not in params:
                raise UnknownVariableError(n, params, "defaults (parameters)")
        for n in initial:
            if n not in states:
                raise UnknownVariableError(n, states, "initial (states)")
        object.__setattr__(self, "parameters", params)
        object.__setattr__(self, "states", states)
        object.__setattr__(self, "defaults", defaults)
        object.__setattr__(self, "initial", initial)

    def __reduce__(self):
        # read-only mappings do not pickle; rebuild from plain dicts
        return (type(self), (self.system, self.parameters, self.states, self.rhs, self.time,
                             dict(self.defaults), dict(self.initial), self.name, self.description))

    def __hash__(self) -> int:
        return hash((self.system, self.parameters, self.states, self.time, self.rhs,
                     tuple(self.defaults.items()), tuple(self.initial.items()), self.name))

    def state_dimension(self, name: str):
        """The dimension of one state variable.

        Parameters
        ----------
        name : str

        Returns
        -------
        Dimension

        Examples
        --------
        >>> import pitheorem as pt
        >>> str(pt.models.hinged_rod().state_dimension("omega"))
        'T^-1'
        """
        if name not in self.states:
            raise UnknownVariableError(name, self.states, "states")
        return self.system.dimension(name)

    def resolve_params(self, params: Mapping[str, object] | None = None) -> dict[str, float]:
        """Complete parameter values: the defaults overridden by `params`.

        Parameters
        ----------
        params : mapping of str to number, optional
            Values that replace the defaults.

        Returns
        -------
        dict of str to float
            One value per parameter, in parameter order.

        Raises
        ------
        UnknownVariableError
            For a name that is not a parameter of the model.
        InvalidRequestError
            For a missing parameter (no default, not given) or a value that
            is not a finite number.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.models.projectile().resolve_params({"g": 1.62})
        {'m': 2.0, 'g': 1.62}
        """
        given = {} if params is None else params
        if not isinstance(given, Mapping):
            raise InvalidRequestError(f"params must be a mapping of parameter names to numbers, got {given!r}")
        for n in given:
            if n not in self.parameters:
                raise UnknownVariableError(str(n), self.parameters, f"params of model {self.name or 'model'!r}")
        out = {}
        for n in self.parameters:
            if n in given:
                value = given[n]
            elif n in self.defaults:
                value = self.defaults[n]
            else:
                raise InvalidRequestError(
                    f"parameter {n!r} of model {self.name or 'model'!r} has no default: give it in params"
                )
            try:
                value = float(value)
            except (TypeError, ValueError):
                raise InvalidRequestError(f"parameter {n!r} must be a number, got {value!r}") from None
            if not math.isfinite(value):
                raise InvalidRequestError(f"parameter {n!r} must be finite, got {value!r}")
            out[n] = value
        return out

    def resolve_initial(self, y0=None) -> np.ndarray:
        """The initial state vector, in the order of :attr:`states`.

        Parameters
        ----------
        y0 : mapping or sequence of numbers, optional
            A mapping overrides the default initial values by name; a
            sequence gives every state, in order.

        Returns
        -------
        numpy.ndarray

        Raises
        ------
        InvalidRequestError
            For a sequence of the wrong length, a missing initial value or a
            non-finite number.
        UnknownVariableError
            For a name in a mapping that is not a state.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.models.spring_mass_damper().resolve_initial({"v": 0.5}).tolist()
        [1.0, 0.5]
        """
        if y0 is None or isinstance(y0, Mapping):
            given = {} if y0 is None else y0
            for n in given:
                if n not in self.states:
                    raise UnknownVariableError(str(n), self.states, f"y0 of model {self.name or 'model'!r}")
            values = []
            for n in self.states:
                if n in given:
                    values.append(given[n])
                elif n in self.initial:
                    values.append(self.initial[n])
                else:
                    raise InvalidRequestError(
                        f"state {n!r} of model {self.name or 'model'!r} has no initial value: give it in y0"
                    )
        else:
            try:
                values = list(y0)
            except TypeError:
                raise InvalidRequestError(f"y0 must be a mapping or a sequence of numbers, got {y0!r}") from None
            if len(values) != len(self.states):
                raise InvalidRequestError(
                    f"y0 has {len(values)} values but model {self.name or 'model'!r} has "
                    f"{len(self.states)} states {self.states}"
                )
        try:
            y = np.array(values, dtype=float)
        except (TypeError, ValueError):
            raise InvalidRequestError(f"y0 must contain numbers, got {values!r}") from None
        if y.ndim != 1 or not np.all(np.isfinite(y)):
            raise InvalidRequestError(f"y0 must be finite numbers, one per state {self.states}, got {values!r}")
        return y


# -- parameter lists of the paper ------------------------------------------------------------

_ROD = {
    "m": "M",
    "theta_r": "1",
    "l": "L",
    "g": "L T^-2",
    "k_theta": "M L^2 T^-2",
    "c_theta": "M L^2 T^-1",
    "t": "T",
    "F": "M L T^-2",
    "tau": "M L^2 T^-2",
}

_SUPERBALL = {
    "m": "M",
    "l": "L",
    "k": "M T^-2",
    "x_r": "L",
    "g": "L T^-2",
    "c": "M T^-1",
    "F": "M L T^-2",
    "t": "T",
    "G": "M L^-1 T^-2",
    "E": "M L^-1 T^-2",
    "v": "L T^-1",
    "rho": "M L^-3",
}


def rod_system() -> System:
    """The paper's nine rod variables (Section 2.1).

    Force and torque included: ``m, theta_r, l, g, k_theta, c_theta, t, F, tau``, in the paper's order.

    Returns
    -------
    System

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.models.rod_system()
    >>> len(rod), rod.rank, rod.n_groups
    (9, 3, 6)
    """
    return System(_ROD)


def superball_parameters() -> System:
    """The NTRT SUPERball parameters of Section 4, plus m and l.

    Longitudinal spring ``k ~ M T^-2`` and damper ``c ~ M T^-1``, rest length
    ``x_r``, gravity, pretension ``F``, time, the Corde moduli ``G`` and
    ``E``, actuator speed ``v`` and density ``rho``.

    Returns
    -------
    System

    Examples
    --------
    >>> import pitheorem as pt
    >>> sb = pt.models.superball_parameters()
    >>> sb.variables
    ('m', 'l', 'k', 'x_r', 'g', 'c', 'F', 't', 'G', 'E', 'v', 'rho')
    >>> sb.n_groups
    9
    """
    return System(_SUPERBALL)


# -- right-hand sides ------------------------------------------------------------------------
# Module-level functions (not closures), so models pickle and hash stably.


def _hinged_rod_rhs(t, y, p):
    theta, omega = map(float, y)
    acc = 3.0 / (p["m"] * p["l"] ** 2) * (
        (p["m"] * p["g"] * p["l"] / 2) * math.cos(theta)
        - p["c_theta"] * omega
        - p["k_theta"] * (theta - p["theta_r"])
    )
    return np.array([omega, acc])


def _longitudinal_rhs(t, y, p):
    theta, omega = map(float, y)
    m, l, g, k, x_r = p["m"], p["l"], p["g"], p["k"], p["x_r"]  # noqa: E741
    cos = math.cos(theta)
    x = l * math.sqrt(5.0 + 4.0 * math.sin(theta))  # spring length, tip to the anchor at (0, -2 l)
    arm = 2.0 * l * l * cos / x  # dx/dtheta; the torque of a tension T about the hinge is -T * arm
    tension = k * (x - x_r)
    if "c" in p:
        tension += p["c"] * arm * omega  # damper force c * x_dot along the spring
    acc = 3.0 / (m * l * l) * ((m * g * l / 2) * cos - tension * arm)
    return np.array([omega, acc])


def _spring_mass_damper_rhs(t, y, p):
    pos, vel = map(float, y)
    acc = (-p["k"] * (pos - p["y_rest"]) - p["c"] * vel) / p["m"] - p["g"]
    return np.array([vel, acc])


def _projectile_rhs(t, y, p):
    return np.array([y[2], y[3], 0.0, -p["g"]])


# -- model factories -------------------------------------------------------------------------


def hinged_rod() -> Model:
    r"""The paper's hinged rod, rotational spring and damper (Eq. 1).

    A uniform rod (mass ``m``, length ``l``, ``I = m l^2 / 3`` about the
    hinge) makes the angle ``theta`` with the horizontal, measured in the
    direction gravity turns it; a rotational spring ``k_theta`` (rest angle
    ``theta_r``) and damper ``c_theta`` act at the hinge::

        theta'' = 3/(m l^2) ((m g l / 2) cos(theta) - c_theta theta'
                             - k_theta (theta - theta_r))

    ERRATUM: the paper's Eq. (1) prints ``+ k_theta theta - k_theta theta_r``
    (an anti-restoring spring); its MATLAB code, which made the figures,
    and this model use the restoring sign above.

    States ``theta`` (dimensionless) and ``omega = theta'`` (``T^-1``).
    Defaults are those of the paper's MATLAB program: ``m=1.5, l=2,
    g=9.81, k_theta=100, c_theta=10, theta_r=pi/3``, from ``theta=pi/4``,
    ``omega=0``.

    Returns
    -------
    Model

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.models.hinged_rod()
    >>> rod.parameters, rod.states
    (('m', 'l', 'g', 'k_theta', 'c_theta', 'theta_r'), ('theta', 'omega'))
    >>> rod.rhs(0.0, [rod.defaults["theta_r"], 0.0], {**rod.defaults, "g": 0.0}).tolist()
    [0.0, 0.0]
    """
    system = System({
        "m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "c_theta": "M L^2 T^-1",
        "theta_r": "1", "t": "T", "theta": "1", "omega": "T^-1",
    })
    return Model(
        system=system,
        parameters=("m", "l", "g", "k_theta", "c_theta", "theta_r"),
        states=("theta", "omega"),
        rhs=_hinged_rod_rhs,
        time="t",
        defaults={"m": 1.5, "l": 2.0, "g": 9.81, "k_theta": 100.0, "c_theta": 10.0, "theta_r": math.pi / 3},
        initial={"theta": math.pi / 4, "omega": 0.0},
        name="hinged_rod",
        description="rod on a hinge with rotational spring and damper (white paper Eq. 1, restoring sign)",
    )


def hinged_rod_longitudinal(damper: bool = True) -> Model:
    r"""The hinged rod held by a longitudinal spring (and damper).

    Geometry (derived here; the paper's commented-out MATLAB variants are
    dimensionally inconsistent, see :mod:`matlab_ports.rod_hinge_dynamics`):
    the hinge is at the origin, ``theta`` is the rod's angle to the
    horizontal, positive in the direction gravity turns it, so the tip is
    at ``l (cos theta, sin theta)`` with the second axis pointing down.  A
    spring (constant ``k ~ M T^-2``, rest length ``x_r ~ L``) joins the tip
    to an anchor a distance ``2 l`` above the hinge, at ``(0, -2 l)``, out
    of the tip's reach.  The spring's length and its rate of change with
    the angle are::

        x = l sqrt(5 + 4 sin(theta)),     dx/dtheta = 2 l^2 cos(theta) / x

    The tension ``T = k (x - x_r) + c x'`` (``x' = dx/dtheta * omega``; the
    damper ``c ~ M T^-1`` only with ``damper=True``) acts along the spring.
    Its torque about the hinge, force times lever arm (the cross product of
    the tip position with the force), is ``-T dx/dtheta``, as virtual work
    requires.  With ``I = m l^2 / 3``::

        theta'' = 3/(m l^2) ((m g l / 2) cos(theta) - 2 T l^2 cos(theta) / x)

    Every term in the bracket is a torque ``M L^2 T^-2``, and ``x >= l``
    never vanishes, so the model has no singular angle.

    Parameters
    ----------
    damper : bool
        Include the longitudinal damper ``c``.

    Returns
    -------
    Model
        Parameters ``m, l, g, k, x_r`` (and ``c``); states ``theta``,
        ``omega``.  Defaults ``m=1.5, l=2, g=9.81`` as for
        :func:`hinged_rod`, ``k=20, x_r=4, c=2`` (equilibrium close to the
        horizontal, ``theta = -0.037``), from ``theta=pi/4``, ``omega=0``.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.models.hinged_rod_longitudinal(damper=False)
    >>> rod.parameters
    ('m', 'l', 'g', 'k', 'x_r')
    >>> str(rod.system.dimension("k")), str(rod.system.dimension("x_r"))
    ('M T^-2', 'L')
    """
    dims = {"m": "M", "l": "L", "g": "L T^-2", "k": "M T^-2", "x_r": "L"}
    defaults = {"m": 1.5, "l": 2.0, "g": 9.81, "k": 20.0, "x_r": 4.0}
    if damper:
        dims["c"] = "M T^-1"
        defaults["c"] = 2.0
    system = System({**dims, "t": "T", "theta": "1", "omega": "T^-1"})
    return Model(
        system=system,
        parameters=tuple(dims),
        states=("theta", "omega"),
        rhs=_longitudinal_rhs,
        time="t",
        defaults=defaults,
        initial={"theta": math.pi / 4, "omega": 0.0},
        name="hinged_rod_longitudinal",
        description="hinged rod held by a longitudinal spring"
        + (" and damper" if damper else "")
        + " from its tip to an anchor a distance l above the hinge",
    )


def spring_mass_damper() -> Model:
    """Vertical spring-mass-damper under gravity (Section 5).

    ``m y'' = -k (y - y_rest) - c y' - m g`` with states ``y`` (position,
    ``L``) and ``v = y'`` (``L T^-1``).  Defaults as in the paper's linear
    MATLAB program: ``m=2, k=150, c=10, g=9.81, y_rest=1``, from ``y=1``,
    ``v=0``.

    Returns
    -------
    Model

    Examples
    --------
    >>> import pitheorem as pt
    >>> smd = pt.models.spring_mass_damper()
    >>> y_static = 1.0 - 2.0 * 9.81 / 150.0   # y_rest - m g / k
    >>> abs(float(smd.rhs(0.0, [y_static, 0.0], dict(smd.defaults))[1])) < 1e-12  # at rest there
    True
    """
    system = System({"m": "M", "k": "M T^-2", "c": "M T^-1", "g": "L T^-2", "y_rest": "L",
                     "t": "T", "y": "L", "v": "L T^-1"})
    return Model(
        system=system,
        parameters=("m", "k", "c", "g", "y_rest"),
        states=("y", "v"),
        rhs=_spring_mass_damper_rhs,
        time="t",
        defaults={"m": 2.0, "k": 150.0, "c": 10.0, "g": 9.81, "y_rest": 1.0},
        initial={"y": 1.0, "v": 0.0},
        name="spring_mass_damper",
        description="vertical spring-mass-damper under gravity (white paper Section 5)",
    )


def projectile() -> Model:
    """A point mass under gravity, without drag.

    States ``x, y`` (``L``) and ``vx, vy`` (``L T^-1``); parameters ``m``
    (which the motion does not depend on) and ``g``.  Defaults ``m=2,
    g=9.81``; launch from the origin at ``v0 = 10`` and 45 degrees:
    ``vx = vy = 10 cos(pi/4)``.  (The paper's MATLAB program launches
    straight up; see :mod:`matlab_ports.scaling_counterexample_projectile`.)

    Returns
    -------
    Model

    Examples
    --------
    >>> import pitheorem as pt
    >>> proj = pt.models.projectile()
    >>> proj.states
    ('x', 'y', 'vx', 'vy')
    >>> round(proj.initial["vx"], 6), round(proj.initial["vy"], 6)
    (7.071068, 7.071068)
    """
    system = System({"m": "M", "g": "L T^-2", "t": "T", "x": "L", "y": "L", "vx": "L T^-1", "vy": "L T^-1"})
    v0, angle = 10.0, math.pi / 4
    return Model(
        system=system,
        parameters=("m", "g"),
        states=("x", "y", "vx", "vy"),
        rhs=_projectile_rhs,
        time="t",
        defaults={"m": 2.0, "g": 9.81},
        initial={"x": 0.0, "y": 0.0, "vx": v0 * math.cos(angle), "vy": v0 * math.sin(angle)},
        name="projectile",
        description="point mass under gravity, launched at 10 m/s and 45 degrees",
    )


# -- the same models as sympy equations ------------------------------------------------------


def model_equations(model: Model) -> list:
    """The shipped model's equations of motion as sympy equations.

    States are functions of the time symbol; the first-order form matches
    the model's ``rhs``, so :func:`pitheorem.check_dimensions` and
    :func:`pitheorem.scaling_symmetries` can analyse exactly what is
    simulated.

    Parameters
    ----------
    model : Model
        One of :func:`hinged_rod`, :func:`hinged_rod_longitudinal`,
        :func:`spring_mass_damper`, :func:`projectile`.

    Returns
    -------
    list of sympy.Eq

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.models.hinged_rod()
    >>> [str(pt.check_dimensions(eq, rod.system)) for eq in pt.models.model_equations(rod)]
    ['consistent: dimension T^-1', 'consistent: dimension T^-2']
    """
    import sympy

    builders = {
        "hinged_rod": _rod_equations,
        "hinged_rod_longitudinal": _longitudinal_equations,
        "spring_mass_damper": _smd_equations,
        "projectile": _projectile_equations,
    }
    name = getattr(model, "name", None)
    if name not in builders:
        raise InvalidRequestError(
            f"no equations are known for model {name!r}; shipped models are {', '.join(sorted(builders))}"
        )
    t = sympy.Symbol(model.time, positive=True)
    states = {n: sympy.Function(n)(t) for n in model.states}
    params = {n: sympy.Symbol(n, positive=True) for n in model.parameters}
    return builders[name](sympy, t, states, params)


def _rod_equations(sp, t, x, p):
    theta, omega = x["theta"], x["omega"]
    torque = p["m"] * p["g"] * p["l"] / 2 * sp.cos(theta) - p["c_theta"] * omega - p["k_theta"] * (theta - p["theta_r"])
    return [sp.Eq(theta.diff(t), omega), sp.Eq(omega.diff(t), 3 / (p["m"] * p["l"] ** 2) * torque)]


def _longitudinal_equations(sp, t, x, p):
    theta, omega = x["theta"], x["omega"]
    m, l, g, k, x_r = p["m"], p["l"], p["g"], p["k"], p["x_r"]  # noqa: E741
    length = l * sp.sqrt(5 + 4 * sp.sin(theta))
    arm = 2 * l**2 * sp.cos(theta) / length
    tension = k * (length - x_r) + (p["c"] * arm * omega if "c" in p else 0)
    return [sp.Eq(theta.diff(t), omega),
            sp.Eq(omega.diff(t), 3 / (m * l**2) * (m * g * l / 2 * sp.cos(theta) - tension * arm))]


def _smd_equations(sp, t, x, p):
    y, v = x["y"], x["v"]
    return [sp.Eq(y.diff(t), v),
            sp.Eq(p["m"] * v.diff(t), -p["k"] * (y - p["y_rest"]) - p["c"] * v - p["m"] * p["g"])]


def _projectile_equations(sp, t, x, p):
    return [sp.Eq(x["x"].diff(t), x["vx"]), sp.Eq(x["y"].diff(t), x["vy"]),
            sp.Eq(x["vx"].diff(t), 0), sp.Eq(x["vy"].diff(t), -p["g"])]
