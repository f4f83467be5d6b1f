"""Exceptions raised by pitheorem.

Every error a user can provoke is defined here, derives from
:class:`PiTheoremError` and from the matching builtin (``ValueError``,
``KeyError``, ``TypeError``, ``ImportError``), so existing ``except
ValueError`` code keeps working.  Each error carries its culprit (the
offending name, token or value) in the ``culprit`` attribute, builds its
message in ``__str__``, and pickles with everything it carries (for
multiprocessing and pytest-xdist).
"""

from __future__ import annotations

__all__ = [
    "CommandLineError",
    "DependentRepeatingSetError",
    "DimensionSyntaxError",
    "DuplicateVariableError",
    "EmptySystemError",
    "EngineUnavailableError",
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
        self.message = message
        if culprit is not None:
            self.culprit = culprit

    def __str__(self) -> str:
        return self.message

    def __reduce__(self):
        return (type(self), (self.message, self.culprit))


class DimensionSyntaxError(PiTheoremError, ValueError):
    """A dimension formula could not be parsed.

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
    ...     print(err.position)
    4
    """

    def __init__(self, text: str, position: int, reason: str):
        self.text, self.position, self.reason = text, position, reason
        super().__init__(str(self))

    @property
    def culprit(self) -> str:
        """The formula from the offending token on.

        Examples
        --------
        >>> from pitheorem.errors import DimensionSyntaxError
        >>> DimensionSyntaxError("M L^^2", 4, "expected a number after '^'").culprit
        '^2'
        """
        return self.text[self.position :]

    def __str__(self) -> str:
        pointer = " " * self.position + "^"
        return f"cannot parse dimension {self.text!r} at position {self.position}: {self.reason}\n    {self.text}\n    {pointer}"

    def __reduce__(self):
        return (type(self), (self.text, self.position, self.reason))


class UnitError(PiTheoremError, ValueError):
    """A unit string (read through pint) was not understood.

    Examples
    --------
    >>> import pitheorem as pt
    >>> issubclass(pt.UnitError, ValueError)
    True
    """


class UnknownVariableError(PiTheoremError, KeyError):
    """A variable name that the system does not contain.

    Parameters
    ----------
    name : str
        The unknown name.
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
        self.name, self.known, self.context = name, tuple(known), context
        super().__init__(str(self))

    @property
    def culprit(self) -> str:
        """The unknown name.

        Examples
        --------
        >>> from pitheorem.errors import UnknownVariableError
        >>> UnknownVariableError("mass", ("m", "l"), "repeating").culprit
        'mass'
        """
        return self.name

    def __str__(self) -> str:
        where = f" in {self.context}" if self.context else ""
        return f"unknown variable {self.name!r}{where}; the system has {', '.join(self.known) or 'no variables'}"

    def __reduce__(self):
        return (type(self), (self.name, self.known, self.context))


class DuplicateVariableError(PiTheoremError, ValueError):
    """The same variable named twice where names must be distinct.

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
        self.name, self.context = name, context
        super().__init__(str(self))

    @property
    def culprit(self) -> str:
        """The name given twice.

        Examples
        --------
        >>> from pitheorem.errors import DuplicateVariableError
        >>> DuplicateVariableError("m", "repeating").culprit
        'm'
        """
        return self.name

    def __str__(self) -> str:
        where = f" in {self.context}" if self.context else ""
        return f"variable {self.name!r} is named twice{where}; name each variable once"

    def __reduce__(self):
        return (type(self), (self.name, self.context))


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

    def __init__(self, message: str = "a system needs at least one variable, e.g. System({'l': 'L', 't': 'T'})",
                 culprit: object = None):
        super().__init__(message, culprit)


class RepeatingCountError(PiTheoremError, ValueError):
    """A repeating set with the wrong number of variables.

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
        self.given, self.expected = tuple(given), expected
        super().__init__(str(self))

    @property
    def culprit(self) -> tuple[str, ...]:
        """The repeating set given.

        Examples
        --------
        >>> from pitheorem.errors import RepeatingCountError
        >>> RepeatingCountError(("m", "l"), 3).culprit
        ('m', 'l')
        """
        return self.given

    def __str__(self) -> str:
        return (
            f"repeating set {self.given} has {len(self.given)} variables, but the dimension matrix has rank "
            f"{self.expected}: choose exactly {self.expected} variables with independent dimensions "
            "(System.bases() lists every valid choice)"
        )

    def __reduce__(self):
        return (type(self), (self.given, self.expected))


class DependentRepeatingSetError(PiTheoremError, ValueError):
    """Repeating variables whose dimensions are not independent.

    Parameters
    ----------
    repeating : tuple of str
        The chosen repeaters.
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
        self.repeating, self.product = tuple(repeating), product
        super().__init__(str(self))

    @property
    def culprit(self) -> tuple[str, ...]:
        """The dependent repeating set.

        Examples
        --------
        >>> from pitheorem.errors import DependentRepeatingSetError
        >>> DependentRepeatingSetError(("l", "t", "g"), "l/(g*t**2)").culprit
        ('l', 't', 'g')
        """
        return self.repeating

    def __str__(self) -> str:
        return (
            f"repeating set {self.repeating} is dependent: {self.product} is dimensionless, "
            "so these variables cannot serve as a basis; System.bases() lists every valid choice"
        )

    def __reduce__(self):
        return (type(self), (self.repeating, self.product))


class InvalidRequestError(PiTheoremError, ValueError):
    """A malformed or contradictory request (search, scaling, evaluation).

    Examples
    --------
    >>> import pitheorem as pt
    >>> issubclass(pt.InvalidRequestError, ValueError)
    True
    """


class SystemMismatchError(InvalidRequestError):
    """A scaling built for a system that does not fit the model.

    The scaling's system must contain every parameter, state and the time
    variable of the model, each with the same dimension.

    Parameters
    ----------
    name : str
        The variable that is missing or has another dimension.
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
        self.name, self.reason = name, reason
        PiTheoremError.__init__(self, str(self))

    @property
    def culprit(self) -> str:
        """The variable that is missing or differs.

        Examples
        --------
        >>> from pitheorem.errors import SystemMismatchError
        >>> SystemMismatchError("m", "the scaling's system has no variable 'm'").culprit
        'm'
        """
        return self.name

    def __str__(self) -> str:
        return (
            f"the scaling does not belong to the model's system: {self.reason}; build the scaling "
            "from model.system (e.g. pt.search(model.system, ...))"
        )

    def __reduce__(self):
        return (type(self), (self.name, self.reason))


class ModelEquationError(InvalidRequestError):
    """An equation that cannot define a :class:`~pitheorem.Model`.

    A model's equations must be first order in time, linear in the
    states' derivatives, one per state, and dimensionally consistent.

    Parameters
    ----------
    equation : str or None
        The equation at fault, as text (``None`` when the fault lies in
        the set of equations rather than in one of them).
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
        self.equation, self.reason, self.index = equation, reason, index
        PiTheoremError.__init__(self, str(self))

    @property
    def culprit(self) -> str | None:
        """The equation at fault, as text.

        Examples
        --------
        >>> from pitheorem.errors import ModelEquationError
        >>> ModelEquationError("Eq(x, 1)", "it holds no derivative", 2).culprit
        'Eq(x, 1)'
        """
        return self.equation

    def __str__(self) -> str:
        if self.equation is None:
            return f"the model's equations: {self.reason}"
        where = f"equation {self.index}" if self.index is not None else "equation"
        return f"{where} of the model, {self.equation}: {self.reason}"

    def __reduce__(self):
        return (type(self), (self.equation, self.reason, self.index))


class NumberError(InvalidRequestError):
    """A value that cannot be read as an exact number.

    See :func:`pitheorem.exact.read_number` for what is accepted.

    Parameters
    ----------
    value : object
        The value given.
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
        self.value, self.what, self.expected = value, what, expected
        PiTheoremError.__init__(self, str(self))

    @property
    def culprit(self) -> object:
        """The value given.

        Examples
        --------
        >>> from pitheorem.errors import NumberError
        >>> NumberError("1/0", "exponent of 'g'", "a finite number").culprit
        '1/0'
        """
        return self.value

    def __str__(self) -> str:
        return f"{self.what} must be {self.expected}, got {self.value!r}"

    def __reduce__(self):
        return (type(self), (self.value, self.what, self.expected))


class LimitError(InvalidRequestError):
    """A number or formula beyond one of pitheorem's size limits.

    The limits (in :mod:`pitheorem.exact`) keep exact arithmetic fast and
    the output printable; no physical model comes near them.

    Parameters
    ----------
    value : object
        The offending value (or formula).
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
        self.value, self.what, self.limit, self.hint = value, what, limit, hint
        PiTheoremError.__init__(self, str(self))

    @property
    def culprit(self) -> object:
        """The offending value.

        Examples
        --------
        >>> from pitheorem.errors import LimitError
        >>> LimitError("L^100000", "exponent in 'L^100000'", "its magnitude exceeds the limit 1000").culprit
        'L^100000'
        """
        return self.value

    def __str__(self) -> str:
        return f"{self.what} is {self.value}: {self.limit}" + (f"; {self.hint}" if self.hint else "")

    def __reduce__(self):
        return (type(self), (self.value, self.what, self.limit, self.hint))


class ModelFileError(PiTheoremError, ValueError):
    """A model file that cannot be read: bad TOML, unknown keys, bad values ...

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
    """

    def __init__(self, path, reason: str, variable: str | None = None, line: int | None = None):
        self.path, self.reason, self.variable, self.line = str(path), reason, variable, line
        super().__init__(str(self))

    @property
    def culprit(self) -> str:
        """The variable at fault, or the file when no variable is.

        Examples
        --------
        >>> from pitheorem.modelfile import ModelFileError
        >>> ModelFileError("rod.toml", "unknown role 'input'", variable="m").culprit
        'm'
        >>> ModelFileError("rod.toml", "invalid TOML", line=3).culprit
        'rod.toml'
        """
        return self.variable if self.variable is not None else self.path

    def __str__(self) -> str:
        where = self.path + (f", line {self.line}" if self.line is not None else "")
        what = f" variable {self.variable!r}:" if self.variable is not None else ""
        return f"{where}:{what} {self.reason}"

    def __reduce__(self):
        return (type(self), (self.path, self.reason, self.variable, self.line))


class CommandLineError(PiTheoremError, ValueError):
    """A bad command-line request that no library call caught (exit code 2).

    Examples
    --------
    >>> from pitheorem.errors import CommandLineError
    >>> CommandLineError("--s must be positive, got '-2'", culprit="-2").culprit
    '-2'
    """


#: the Python package each engine needs
_ENGINE_PACKAGES = {"bullet": "pybullet", "mujoco": "mujoco"}


class EngineUnavailableError(PiTheoremError, ImportError):
    """An engine's Python package is not installed.

    Examples
    --------
    >>> from pitheorem.errors import EngineUnavailableError
    >>> print(EngineUnavailableError("bullet"))
    engine 'bullet' needs the Python package 'pybullet': pip install "pitheorem[engines]"
    """

    def __init__(self, engine: str):
        self.engine = engine
        PiTheoremError.__init__(self, str(self))

    @property
    def culprit(self) -> str:
        """The engine asked for.

        Examples
        --------
        >>> from pitheorem.errors import EngineUnavailableError
        >>> EngineUnavailableError("mujoco").culprit
        'mujoco'
        """
        return self.engine

    def __str__(self) -> str:
        package = _ENGINE_PACKAGES.get(self.engine, self.engine)
        return f'engine {self.engine!r} needs the Python package {package!r}: pip install "pitheorem[engines]"'

    def __reduce__(self):
        return (type(self), (self.engine,))
