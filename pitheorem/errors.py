"""Exceptions raised by pitheorem.

Every error a user can provoke is defined here (the engines' too), derives
from :class:`PiTheoremError` and from the matching builtin (``ValueError``,
``KeyError``, ``TypeError``, ``ImportError``), so existing ``except
ValueError`` code keeps working.  Each error carries its culprit (the
offending name, token or value) in the ``culprit`` attribute, builds its
message in ``__str__``, and pickles with everything it carries (for
multiprocessing and pytest-xdist).

The fields of an error are declared once, as the parameters of its
constructor: the constructor hands them to ``PiTheoremError._keep`` with
the culprit, which stores each under its parameter's name, and
``PiTheoremError.__reduce__`` gives them back to the constructor when the
error is unpickled.
"""

from __future__ import annotations

import inspect
from functools import cache

__all__ = [
    "CommandLineError",
    "DependentRepeatingSetError",
    "DimensionSyntaxError",
    "DuplicateVariableError",
    "EmptySystemError",
    "EngineModelError",
    "EngineUnavailableError",
    "InputsNotKeptError",
    "InvalidRequestError",
    "LimitError",
    "ModelEquationError",
    "ModelFileError",
    "NumberError",
    "PiTheoremError",
    "RepeatingCountError",
    "SystemMismatchError",
    "UnitError",
    "UnknownVariableError",
    "UnscalableParameterError",
]


class PiTheoremError(Exception):
    """Base class of every error raised by pitheorem.

    Examples
    --------
    >>> import pitheorem as pt
    >>> try:
    ...     pt.System({})
    ... except pt.PiTheoremError as err:
    ...     print(type(err).__name__)
    EmptySystemError
    """

    #: the offending name, token or value (None when the message is all there is)
    culprit: object = None

    def __init__(self, message: str = "", culprit: object = None):
        super().__init__(message)
        self.message, self.culprit = message, culprit

    def _keep(self, *fields: object, culprit: object) -> None:
        """Store a subclass's fields, then its culprit and the message its ``__str__`` builds.

        `fields` are the constructor's arguments in the order of its
        signature; each becomes the attribute of the parameter's name, and
        pickling passes them back to the constructor.
        """
        for name, value in zip(_field_names(type(self)), fields, strict=True):
            setattr(self, name, value)
        PiTheoremError.__init__(self, str(self), culprit)

    def __str__(self) -> str:
        return self.message

    def __reduce__(self):
        return (type(self), tuple(getattr(self, name) for name in _field_names(type(self))))


@cache
def _field_names(cls: type) -> tuple[str, ...]:
    """The parameters of an error class's constructor: the fields it keeps and pickles."""
    return tuple(inspect.signature(cls.__init__).parameters)[1:]


class DimensionSyntaxError(PiTheoremError, ValueError):
    """A dimension formula could not be parsed.

    Its culprit is the formula from the offending token on.

    Parameters
    ----------
    text : str
        The whole formula.
    position : int
        Index in `text` of the offending token.
    reason : str
        What is wrong and what would be valid.

    Examples
    --------
    >>> import pitheorem as pt
    >>> try:
    ...     pt.Dimension.parse("M L^^2")
    ... except pt.DimensionSyntaxError as err:
    ...     print(err.position, err.culprit)
    4 ^2
    """

    def __init__(self, text: str, position: int, reason: str):
        self._keep(text, position, reason, culprit=text[position:])

    def __str__(self) -> str:
        pointer = " " * self.position + "^"
        return f"cannot parse dimension {self.text!r} at position {self.position}: {self.reason}\n    {self.text}\n    {pointer}"


class UnitError(PiTheoremError, ValueError):
    """A unit string (read through pint) was not understood.

    Examples
    --------
    >>> import pitheorem as pt
    >>> try:
    ...     pt.System.from_units({"l": 3})
    ... except pt.UnitError as err:
    ...     print(err)
    unit of 'l' must be a string such as 'kg*m/s^2', got 3
    """


class UnknownVariableError(PiTheoremError, KeyError):
    """A variable name that the system does not contain.

    Parameters
    ----------
    name : str
        The unknown name (the culprit).
    known : tuple of str
        The names that would be valid.
    context : str
        Where the name was used.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L"})
    >>> try:
    ...     rod.pi_groups(repeating=("mass", "l"))
    ... except pt.UnknownVariableError as err:
    ...     print(err.name)
    mass
    """

    def __init__(self, name: str, known: tuple[str, ...] = (), context: str = ""):
        self._keep(name, tuple(known), context, culprit=name)

    def __str__(self) -> str:
        where = f" in {self.context}" if self.context else ""
        return f"unknown variable {self.name!r}{where}; the system has {', '.join(self.known) or 'no variables'}"


class DuplicateVariableError(PiTheoremError, ValueError):
    """The same variable named twice where names must be distinct.

    Parameters
    ----------
    name : str
        The name given twice (the culprit).
    context : str
        Where the names were given.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "t": "T"})
    >>> try:
    ...     rod.pi_groups(repeating=("m", "m", "t"))
    ... except pt.DuplicateVariableError as err:
    ...     print(err)
    variable 'm' is named twice in repeating; name each variable once
    """

    def __init__(self, name: str, context: str = ""):
        self._keep(name, context, culprit=name)

    def __str__(self) -> str:
        where = f" in {self.context}" if self.context else ""
        return f"variable {self.name!r} is named twice{where}; name each variable once"


class EmptySystemError(PiTheoremError, ValueError):
    """A system (or request) with nothing in it.

    Examples
    --------
    >>> import pitheorem as pt
    >>> try:
    ...     pt.System({})
    ... except pt.EmptySystemError as err:
    ...     print(err)
    a system needs at least one variable, e.g. System({'l': 'L', 't': 'T'})
    """

    def __init__(
        self,
        message: str = "a system needs at least one variable, e.g. System({'l': 'L', 't': 'T'})",
        culprit: object = None,
    ):
        super().__init__(message, culprit)


class RepeatingCountError(PiTheoremError, ValueError):
    """A repeating set with the wrong number of variables.

    Parameters
    ----------
    given : tuple of str
        The repeating set given (the culprit).
    expected : int
        How many repeaters there must be: the rank.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "t": "T", "g": "L/T^2"})
    >>> try:
    ...     rod.pi_groups(repeating=("m", "l"))
    ... except pt.RepeatingCountError as err:
    ...     print(err.expected)
    3
    """

    def __init__(self, given: tuple[str, ...], expected: int):
        self._keep(tuple(given), expected, culprit=tuple(given))

    def __str__(self) -> str:
        return (
            f"repeating set {self.given} has {len(self.given)} variables, but the dimension matrix has rank "
            f"{self.expected}: choose exactly {self.expected} variables with independent dimensions "
            "(System.bases() lists every valid choice)"
        )


class DependentRepeatingSetError(PiTheoremError, ValueError):
    """Repeating variables whose dimensions are not independent.

    Parameters
    ----------
    repeating : tuple of str
        The chosen repeaters (the culprit).
    product : str
        A dimensionless product the repeaters form on their own.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "t": "T", "g": "L/T^2"})
    >>> try:
    ...     rod.pi_groups(repeating=("l", "t", "g"))
    ... except pt.DependentRepeatingSetError as err:
    ...     print(err.product)
    l/(g*t**2)
    """

    def __init__(self, repeating: tuple[str, ...], product: str):
        self._keep(tuple(repeating), product, culprit=tuple(repeating))

    def __str__(self) -> str:
        return (
            f"repeating set {self.repeating} is dependent: {self.product} is dimensionless, "
            "so these variables cannot serve as a basis; System.bases() lists every valid choice"
        )


class InvalidRequestError(PiTheoremError, ValueError):
    """A malformed or contradictory request (search, scaling, evaluation).

    Examples
    --------
    >>> import pitheorem as pt
    >>> try:
    ...     pt.search(pt.System({"l": "L"}), scale={})
    ... except pt.InvalidRequestError as err:
    ...     print(err)
    empty request: scale must prescribe at least one variable, e.g. scale={'g': 1}
    """


class SystemMismatchError(InvalidRequestError):
    """A scaling built for a system that does not fit the model.

    The scaling's system must contain every parameter, state and the time
    variable of the model, each with the same dimension.

    Parameters
    ----------
    name : str
        The variable that is missing or has another dimension (the culprit).
    reason : str
        What differs.

    Examples
    --------
    >>> import pitheorem as pt
    >>> other = pt.System({"l": "L", "t": "T"})
    >>> sc = pt.Scaling.from_unit_change(other, {"L": 1})
    >>> try:
    ...     pt.verify_similarity(pt.models.projectile(), sc, s=2, t_final=0.1)
    ... except pt.SystemMismatchError as err:
    ...     print(err.name)
    m
    """

    def __init__(self, name: str, reason: str):
        self._keep(name, reason, culprit=name)

    def __str__(self) -> str:
        return (
            f"the scaling does not belong to the model's system: {self.reason}; build the scaling "
            "from model.system (e.g. pt.search(model.system, ...))"
        )


class ModelEquationError(InvalidRequestError):
    """An equation that cannot define a :class:`~pitheorem.Model`.

    A model's equations must be first order in time, linear in the
    states' derivatives, one per state, and dimensionally consistent.

    Parameters
    ----------
    equation : str or None
        The equation at fault, as text (``None`` when the fault lies in
        the set of equations rather than in one of them); the culprit.
    reason : str
        What is wrong and what would be valid.
    index : int or None
        The equation's position in the model's list, counted from 1.

    Examples
    --------
    >>> import sympy, pitheorem as pt
    >>> t = sympy.Symbol("t")
    >>> x = sympy.Function("x")(t)
    >>> try:
    ...     pt.Model(pt.System({"x": "L", "t": "T"}), [sympy.Eq(x.diff(t, 2), 0)])
    ... except pt.ModelEquationError as err:
    ...     print(err.index, err.culprit)
    1 Eq(Derivative(x(t), (t, 2)), 0)
    """

    def __init__(self, equation: str | None, reason: str, index: int | None = None):
        self._keep(equation, reason, index, culprit=equation)

    def __str__(self) -> str:
        if self.equation is None:
            return f"the model's equations: {self.reason}"
        where = f"equation {self.index}" if self.index is not None else "equation"
        return f"{where} of the model, {self.equation}: {self.reason}"


class NumberError(InvalidRequestError):
    """A value that cannot be read as an exact number.

    See :func:`pitheorem.exact.read_number` for what is accepted.

    Parameters
    ----------
    value : object
        The value given (the culprit).
    what : str
        What it was meant to be, e.g. ``"exponent of 'g'"``.
    expected : str
        What would be valid.

    Examples
    --------
    >>> import pitheorem as pt
    >>> try:
    ...     pt.search(pt.System({"l": "L"}), scale={"l": float("nan")})
    ... except pt.NumberError as err:
    ...     print(err.culprit)
    nan
    """

    def __init__(self, value: object, what: str, expected: str):
        self._keep(value, what, expected, culprit=value)

    def __str__(self) -> str:
        return f"{self.what} must be {self.expected}, got {self.value!r}"


class LimitError(InvalidRequestError):
    """A number or formula beyond one of pitheorem's size limits.

    The limits (in :mod:`pitheorem.exact`) keep exact arithmetic fast and
    the output printable; no physical model comes near them.

    Parameters
    ----------
    value : object
        The offending value or formula (the culprit).
    what : str
        What it was meant to be.
    limit : str
        The limit it breaks, stated with its bound.
    hint : str, optional
        What to do instead.

    Examples
    --------
    >>> import pitheorem as pt
    >>> try:
    ...     pt.Dimension.parse("L^100000")
    ... except pt.LimitError as err:
    ...     print(err)
    exponent in 'L^100000' is 100000: its magnitude exceeds the limit 1000
    """

    def __init__(self, value: object, what: str, limit: str, hint: str = ""):
        self._keep(value, what, limit, hint, culprit=value)

    def __str__(self) -> str:
        return f"{self.what} is {self.value}: {self.limit}" + (f"; {self.hint}" if self.hint else "")


class ModelFileError(PiTheoremError, ValueError):
    """A model file that cannot be read: bad TOML, unknown keys, bad values ...

    Its culprit is the variable at fault, or the file when no variable is.

    Parameters
    ----------
    path : str
        The file, as the user named it.
    reason : str
        What is wrong and what would be valid.
    variable : str, optional
        The variable at fault, if any.
    line : int, optional
        The line at fault, if known.

    Examples
    --------
    >>> from pitheorem.modelfile import ModelFileError
    >>> print(ModelFileError("rod.toml", "unknown role 'input'", variable="m"))
    rod.toml: variable 'm': unknown role 'input'
    >>> print(ModelFileError("rod.toml", "invalid TOML: unclosed inline table", line=3))
    rod.toml, line 3: invalid TOML: unclosed inline table
    >>> ModelFileError("rod.toml", "unknown role 'input'", variable="m").culprit
    'm'
    """

    def __init__(self, path, reason: str, variable: str | None = None, line: int | None = None):
        self._keep(str(path), reason, variable, line, culprit=str(path) if variable is None else variable)

    def __str__(self) -> str:
        where = self.path + (f", line {self.line}" if self.line is not None else "")
        what = f" variable {self.variable!r}:" if self.variable is not None else ""
        return f"{where}:{what} {self.reason}"


class EngineModelError(ModelFileError):
    """A model file the engine cannot load, or an element the package cannot scale.

    Its culprit is the file.

    Parameters
    ----------
    path : str
        The file.
    element : str
        The element at fault, e.g. ``"mesh 'torso'"``.
    reason : str
        What is wrong and what would be valid.

    Examples
    --------
    >>> from pitheorem.engines import EngineModelError
    >>> print(EngineModelError("robot.xml", "mesh 'torso'", "file torso.stl not found"))
    robot.xml: mesh 'torso': file torso.stl not found
    """

    variable = line = None  # a ModelFileError's, which an engine's message does not use

    def __init__(self, path, element: str, reason: str):
        self._keep(str(path), element, reason, culprit=str(path))

    def __str__(self) -> str:
        where = f" {self.element}:" if self.element else ""
        return f"{self.path}:{where} {self.reason}"


class UnscalableParameterError(PiTheoremError, ValueError):
    """A scaling that one number of a model cannot follow.

    Raised by :meth:`pitheorem.engines.EngineModel.scaled` for a number that
    mixes dimensions (a free joint's damping acts on lengths and on angles)
    when the scaling needs two different factors for it, and for an engine
    setting that no call can change.

    Parameters
    ----------
    name : str
        The parameter (the culprit).
    reason : str
        Why the scaling cannot reach it.

    Examples
    --------
    >>> from pitheorem.engines import UnscalableParameterError
    >>> print(UnscalableParameterError("joint_root_damping", "needs s^1 and s^3"))
    cannot scale 'joint_root_damping': needs s^1 and s^3
    """

    def __init__(self, name: str, reason: str):
        self._keep(name, reason, culprit=name)

    def __str__(self) -> str:
        return f"cannot scale {self.name!r}: {self.reason}"


class InputsNotKeptError(InvalidRequestError):
    """A model whose inputs cannot keep their values (``keep_inputs=True``).

    Raised by :meth:`pitheorem.engines.EngineModel.scaled` and
    :meth:`~pitheorem.engines.EngineModel.converted` with ``keep_inputs=True``
    for an engine whose inputs are applied as they are given, with no gain
    in the file to carry the actuators' factors.

    Parameters
    ----------
    engine : str
        The engine of the model (the culprit).
    reason : str
        Why its inputs cannot keep their values, and what to do instead.

    Examples
    --------
    >>> from pitheorem.errors import InputsNotKeptError
    >>> print(InputsNotKeptError("bullet", "its inputs are joint forces, with no gain to carry a factor"))
    a bullet model cannot keep its inputs: its inputs are joint forces, with no gain to carry a factor
    """

    def __init__(self, engine: str, reason: str):
        self._keep(engine, reason, culprit=engine)

    def __str__(self) -> str:
        return f"a {self.engine} model cannot keep its inputs: {self.reason}"


class CommandLineError(PiTheoremError, ValueError):
    """A bad command-line request that no library call caught (exit code 2).

    Examples
    --------
    >>> from pitheorem.errors import CommandLineError
    >>> CommandLineError("--s must be positive, got '-2'", culprit="-2").culprit
    '-2'
    """


class EngineUnavailableError(PiTheoremError, ImportError):
    """An engine's Python package is not installed.

    Parameters
    ----------
    engine : str
        The engine asked for (the culprit), e.g. ``"pybullet"``.
    package : str
        The Python package it needs, e.g. ``"pybullet"``.
    extra : str
        The extra of ``pip install "pitheorem[extra]"`` that installs it.
    installed : tuple of str
        The engines installed here, named in the message when given.

    Examples
    --------
    >>> from pitheorem.errors import EngineUnavailableError
    >>> print(EngineUnavailableError("pybullet", "pybullet"))
    engine 'pybullet' needs the Python package 'pybullet': pip install "pitheorem[engines]"
    >>> print(EngineUnavailableError("mjx", "jax", "mjx", ("mujoco",)))
    engine 'mjx' needs the Python package 'jax': pip install "pitheorem[mjx]"; installed here: 'mujoco'
    """

    def __init__(self, engine: str, package: str, extra: str = "engines", installed: tuple = ()):
        self._keep(engine, package, extra, tuple(installed), culprit=engine)

    def __str__(self) -> str:
        here = f"; installed here: {', '.join(map(repr, self.installed))}" if self.installed else ""
        return (
            f"engine {self.engine!r} needs the Python package {self.package!r}: "
            f'pip install "pitheorem[{self.extra}]"{here}'
        )
