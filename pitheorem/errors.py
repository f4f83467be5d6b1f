"""Exceptions raised by pitheorem.

Every error a user can provoke derives from :class:`PiTheoremError` and from
the matching builtin (``ValueError``, ``KeyError`` ...), so existing
``except ValueError`` code keeps working.  Each error stores its culprit in
fields and builds its message in ``__str__``; ``__reduce__`` keeps errors
picklable (for multiprocessing and pytest-xdist).
"""

from __future__ import annotations

__all__ = [
    "DependentRepeatingSetError",
    "DimensionSyntaxError",
    "DuplicateVariableError",
    "EmptySystemError",
    "InvalidRequestError",
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

    def __init__(self, message: str = ""):
        super().__init__(message)
        self.message = message

    def __str__(self) -> str:
        return self.message

    def __reduce__(self):
        return (type(self), (self.message,))


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

    def __init__(self, message: str = "a system needs at least one variable, e.g. System({'l': 'L', 't': 'T'})"):
        super().__init__(message)


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

    def __str__(self) -> str:
        return (
            f"the scaling does not belong to the model's system: {self.reason}; build the scaling "
            "from model.system (e.g. pt.search(model.system, ...))"
        )

    def __reduce__(self):
        return (type(self), (self.name, self.reason))
