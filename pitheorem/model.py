"""The :class:`Model` type: a dynamical model defined by its sympy equations.

A model is a :class:`~pitheorem.System`, which gives a dimension to every
parameter, to the time and to every state, together with equations of
motion in first-order form: each side of each equation is linear in the
first time derivatives of the states, such as
``m v' = -k (y - y_rest) - c v - m g``.  The model checks the equations
(one per state, first order, dimensionally consistent by
:func:`pitheorem.check_dimensions`), solves them exactly for the
derivatives with sympy, once, and generates from that solution the numeric
right-hand side ``f(t, y, params) -> dy/dt`` that
:func:`pitheorem.simulate` integrates.  So the physics is written once, and
what :func:`pitheorem.scaling_symmetries` analyses is what is simulated.

The paper's models are in :mod:`pitheorem.models`; simulation and
similarity checks in :mod:`pitheorem.simulation`.
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable, Iterable, Mapping
from dataclasses import KW_ONLY, dataclass, field
from functools import partial
from types import MappingProxyType

import numpy as np
import sympy
from sympy.core.function import AppliedUndef

from .equations import check_dimensions
from .errors import DuplicateVariableError, InvalidRequestError, ModelEquationError, UnknownVariableError
from .system import System

__all__ = ["Model"]


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
    """A dynamical model with dimensions, defined by its equations of motion.

    The equations are solved exactly for the states' derivatives when the
    model is built; :attr:`rhs` is generated from that solution.

    Parameters
    ----------
    system : System
        A dimension for every symbol of the equations: parameters, time and
        states (it may hold further variables).
    equations : sequence of sympy.Eq
        One equation per state, in first-order form: each side linear in
        the first time derivatives of the states.  A state is an undefined
        function of the time, such as ``sympy.Function("v")(t)``, whose
        derivative appears in the equations; every other symbol is a
        parameter (or the time itself, for an explicit time dependence).
    time : str
        Name of the time variable (default ``"t"``).
    parameters : sequence of str, optional
        The parameters, in the order :meth:`resolve_params` returns them.
        By default the equations' symbols other than the time and the
        states, in the system's order; list them to fix the order or to
        keep a parameter the equations do not use.
    defaults : mapping of str to float, optional
        Default parameter values; stored read-only.
    initial : mapping of str to float, optional
        Default initial state values; stored read-only.
    name : str
    description : str

    Attributes
    ----------
    states : tuple of str
        The states, in the system's order: the order of ``y``.
    rhs : callable
        ``rhs(t, y, params) -> dy/dt``, generated from the solved
        equations: ``y`` a sequence of floats in the order of `states`,
        ``params`` a mapping of every parameter to a float; returns a float
        numpy array.

    Raises
    ------
    ModelEquationError
        For an equation that is not first order, not linear in the
        derivatives, or dimensionally inconsistent, and for equations that
        do not give each state's rate once.
    UnknownVariableError
        For a symbol without a dimension in `system`.

    Examples
    --------
    A vertical spring, mass and damper, ``m v' = -k (y - y_rest) - c v - m g``:

    >>> import sympy
    >>> import pitheorem as pt
    >>> t = sympy.Symbol("t")
    >>> y, v = sympy.Function("y")(t), sympy.Function("v")(t)
    >>> m, k, c, g, y_rest = sympy.symbols("m k c g y_rest")
    >>> smd = pt.Model(
    ...     pt.System({"m": "M", "k": "M T^-2", "c": "M T^-1", "g": "L T^-2",
    ...                "y_rest": "L", "t": "T", "y": "L", "v": "L T^-1"}),
    ...     [sympy.Eq(y.diff(t), v),
    ...      sympy.Eq(m * v.diff(t), -k * (y - y_rest) - c * v - m * g)],
    ...     defaults={"m": 2, "k": 150, "c": 10, "g": 9.81, "y_rest": 1},
    ...     initial={"y": 1, "v": 0}, name="smd")
    >>> smd.states, smd.parameters
    (('y', 'v'), ('m', 'k', 'c', 'g', 'y_rest'))
    >>> smd.rhs(0.0, [1.0, 0.0], smd.defaults).tolist()
    [0.0, -9.81]
    """

    system: System
    equations: tuple
    _: KW_ONLY
    time: str = "t"
    parameters: tuple[str, ...] | None = None
    defaults: Mapping[str, float] | None = None
    initial: Mapping[str, float] | None = None
    name: str = ""
    description: str = field(default="", repr=False)
    states: tuple[str, ...] = field(init=False)
    rhs: Callable = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        if not isinstance(self.system, System):
            raise InvalidRequestError(f"system must be a pitheorem System, got {type(self.system).__name__}")
        if not isinstance(self.time, str):
            raise InvalidRequestError(f"time must be a variable name, got {self.time!r}")
        self.system.index(self.time, "time")
        equations = _read_equations(self.equations)
        found = _Equations(equations, self.system, self.time)
        params = found.parameters if self.parameters is None else self._listed_parameters(found)
        defaults = _frozen_mapping(self.defaults, "defaults")
        initial = _frozen_mapping(self.initial, "initial")
        for n in defaults:
            if n not in params:
                raise UnknownVariableError(n, params, "defaults (parameters)")
        for n in initial:
            if n not in found.states:
                raise UnknownVariableError(n, found.states, "initial (states)")
        for name, value in (
            ("equations", equations),
            ("parameters", params),
            ("states", found.states),
            ("defaults", defaults),
            ("initial", initial),
            ("rhs", found.compile(params)),
        ):
            object.__setattr__(self, name, value)

    def _listed_parameters(self, found: _Equations) -> tuple[str, ...]:
        params = self.system.check_names(self.parameters, "parameters")
        for n in params:
            if n in found.states or n == self.time:
                raise DuplicateVariableError(n, "the model's parameters, states and time")
        for n in found.parameters:
            if n not in params:
                i, text = found.user(n)
                raise ModelEquationError(
                    text,
                    f"it uses {n!r}, which is not among the parameters {params}; list it there, "
                    "or leave parameters out to take every symbol of the equations",
                    i,
                )
        return params

    def __reduce__(self):
        # the generated rhs does not pickle: rebuild the model (and its rhs) from its equations
        options = {
            "time": self.time,
            "parameters": self.parameters,
            "defaults": dict(self.defaults),
            "initial": dict(self.initial),
            "name": self.name,
            "description": self.description,
        }
        return (partial(type(self), **options), (self.system, self.equations))

    def __hash__(self) -> int:
        return hash(
            (
                self.system,
                self.equations,
                self.time,
                self.parameters,
                self.states,
                tuple(self.defaults.items()),
                tuple(self.initial.items()),
                self.name,
            )
        )

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


# -- reading and solving the equations -------------------------------------------------------


def _read_equations(equations) -> tuple:
    if isinstance(equations, sympy.Basic):  # one equation alone
        equations = (equations,)
    if isinstance(equations, str) or not isinstance(equations, Iterable):
        raise InvalidRequestError(f"equations must be a sequence of sympy.Eq, got {equations!r}")
    equations = tuple(equations)
    if not equations:
        raise InvalidRequestError("a model needs at least one equation, one per state")
    for i, eq in enumerate(equations, start=1):
        if not isinstance(eq, sympy.Equality):
            what = "a string" if isinstance(eq, str) else f"a {type(eq).__name__}"
            raise ModelEquationError(
                repr(eq) if isinstance(eq, str) else sympy.sstr(eq),
                f"it is {what}, not an equation; write sympy.Eq(left side, right side) with sympy "
                "symbols and functions of time",
                i,
            )
    return equations


class _Equations:
    """The first-order equations of a model, read, checked and solved for the states' rates."""

    def __init__(self, equations: tuple, system: System, time: str):
        self.equations, self.system, self.time = equations, system, time
        self.texts = [sympy.sstr(eq) for eq in equations]
        self.derivatives: dict[sympy.Basic, str] = {}  # each x'(t) node -> state name
        self.leaves: dict[sympy.Basic, str] = {}  # each symbol and x(t) node -> its name
        uses: list[set[str]] = []
        for i, eq in enumerate(equations, start=1):
            uses.append(self._scan(eq, i))
        self.uses = uses
        rated = set(self.derivatives.values())
        self.states = tuple(n for n in system.variables if n in rated)
        calls = {name for node, name in self.leaves.items() if isinstance(node, AppliedUndef)}
        for n in sorted(calls - rated):
            i, text = self.user(n)
            raise ModelEquationError(
                text,
                f"{n}({time}) is a function of time whose derivative appears in no equation; every "
                f"function of {time} must be a state with an equation for its rate, such as "
                f"Eq({n}({time}).diff({time}), ...); write a parameter as a plain symbol",
                i,
            )
        plain = {name for node, name in self.leaves.items() if isinstance(node, sympy.Symbol)}
        for n in sorted(plain & rated):
            i, text = self.user(n)
            raise ModelEquationError(text, f"{n} is a state, but appears here as a plain symbol; write {n}({time})", i)
        self.parameters = tuple(n for n in system.variables if n in plain - rated - {time})
        for i, (eq, text) in enumerate(zip(equations, self.texts, strict=True), start=1):
            report = check_dimensions(eq, system, time=time)
            if not report.consistent:
                terms = "; ".join(
                    f"{sympy.sstr(term)} has dimension {got}, expected {want}" for term, got, want in report.offending
                )
                raise ModelEquationError(
                    text,
                    f"it is dimensionally inconsistent: {terms}; every term of an equation needs "
                    "one dimension (check the term, or the dimensions in the system)",
                    i,
                )
        self.rates = self._solve()

    def user(self, name: str) -> tuple[int, str]:
        """The first equation that uses `name`: its number and its text."""
        i = next(i for i, names in enumerate(self.uses) if name in names)
        return i + 1, self.texts[i]

    def _scan(self, eq, i: int) -> set[str]:
        text, time = self.texts[i - 1], self.time
        names = set()
        for node in sympy.preorder_traversal(eq):
            if isinstance(node, sympy.Derivative):
                (var, count), *more = node.variable_count
                first = isinstance(var, sympy.Symbol) and var.name == time and count == 1 and not more
                if not (first and self._of_time(node.expr)):
                    raise ModelEquationError(
                        text,
                        f"{sympy.sstr(node)} is not the first time derivative of a state; a model's "
                        f"equations are first order: write a higher derivative with a new state (omega({time}) "
                        f"for theta({time}).diff({time})), and differentiate only functions x({time})",
                        i,
                    )
                self.derivatives[node] = node.expr.func.__name__
            elif isinstance(node, AppliedUndef):
                if not self._of_time(node):
                    raise ModelEquationError(
                        text,
                        f"{sympy.sstr(node)} is not a function of the time alone; write {node.func.__name__}({time})",
                        i,
                    )
                self.leaves[node] = node.func.__name__
            elif isinstance(node, sympy.Symbol):
                self.leaves[node] = node.name
            else:
                continue
            name = self.derivatives.get(node) or self.leaves[node]
            if name not in self.system.variables:
                raise UnknownVariableError(name, self.system.variables, f"equation {i} of the model, {text}")
            names.add(name)
        return names

    def _of_time(self, node) -> bool:
        return (
            isinstance(node, AppliedUndef)
            and len(node.args) == 1
            and isinstance(node.args[0], sympy.Symbol)
            and node.args[0].name == self.time
        )

    def _solve(self) -> list[sympy.Expr]:
        """Each state's rate, in state order: A d = c solved exactly, A and c free of the derivatives d."""
        if not self.states:
            raise ModelEquationError(
                None,
                f"no equation holds the time derivative of a state, such as x({self.time}).diff({self.time}); "
                "a model needs at least one state, a function of time with an equation for its rate",
            )
        if len(self.equations) != len(self.states):
            raise ModelEquationError(
                None,
                f"{len(self.equations)} equation(s) for {len(self.states)} state(s) "
                f"({', '.join(self.states)}); give one first-order equation per state",
            )
        d = {n: sympy.Dummy(f"d{n}") for n in self.states}
        to_d = {node: d[name] for node, name in self.derivatives.items()}
        to_zero = dict.fromkeys(d.values(), 0)
        rows, right = [], []
        for i, (eq, text) in enumerate(zip(self.equations, self.texts, strict=True), start=1):
            lhs, rhs = eq.lhs.xreplace(to_d), eq.rhs.xreplace(to_d)
            row = [sympy.diff(lhs - rhs, d[n]) for n in self.states]
            if any(a.has(*d.values()) for a in row):
                raise ModelEquationError(
                    text,
                    "it is not linear in the derivatives; write it as (coefficient) * x'(t) + ... = "
                    "(right side), with coefficients and right side free of derivatives",
                    i,
                )
            if all(a == 0 for a in row):
                raise ModelEquationError(
                    text,
                    "it holds no derivative of a state; a model's equations are differential "
                    "equations, one per state, such as Eq(x(t).diff(t), v(t))",
                    i,
                )
            rows.append(row)
            right.append(rhs.xreplace(to_zero) - lhs.xreplace(to_zero))
        return _solve_linear(sympy.Matrix(rows), right, self.states)

    def compile(self, parameters: tuple[str, ...]) -> Callable:
        """The numeric right-hand side ``f(t, y, params)`` of the solved equations."""
        t = sympy.Symbol("t0")
        y = [sympy.Symbol(f"y{j}") for j in range(len(self.states))]
        p = [sympy.Symbol(f"p{j}") for j in range(len(parameters))]
        # fresh names for every symbol: a parameter may be called `cos`, `lambda` or `x0` (cse's names)
        named = {self.time: t, **dict(zip(self.states, y, strict=True)), **dict(zip(parameters, p, strict=True))}
        fresh = {node: named[name] for node, name in self.leaves.items()}
        rates = [rate.xreplace(fresh) for rate in self.rates]
        f = sympy.lambdify([t, y, p], rates, modules="math", cse=True)
        # itemgetter is the fastest way to read the values, but gives a bare value for one name
        values = operator.itemgetter(*parameters) if len(parameters) > 1 else lambda d: [d[n] for n in parameters]

        def rhs(t, y, params):
            # Python floats: the generated arithmetic is faster on them than on numpy scalars
            ys = y.tolist() if isinstance(y, np.ndarray) else [float(v) for v in y]
            return np.array(f(t, ys, values(params)), dtype=float)

        return rhs


def _solve_linear(a: sympy.Matrix, c: list, states: tuple[str, ...]) -> list[sympy.Expr]:
    n = len(states)
    one = [[j for j in range(n) if a[i, j] != 0] for i in range(n)]
    if all(len(js) == 1 for js in one) and len({js[0] for js in one}) == n:
        # each equation gives one rate (the usual case): divide, keeping the equation's own form
        rates = [None] * n
        for i, (j,) in enumerate(one):
            rates[j] = c[i] / a[i, j]
        return rates
    if sympy.simplify(a.det()) == 0:
        raise ModelEquationError(
            None,
            "they do not determine each state's rate: the coefficients of the derivatives of "
            f"{', '.join(states)} form a singular matrix; give each state an equation of its own",
        )
    return list(a.LUsolve(sympy.Matrix(c)))
