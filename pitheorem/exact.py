"""Reading numbers exactly, and the size limits of exact arithmetic.

Every number a user passes (an exponent in a formula or a mapping, a scale
exponent, a value, a bound, the scale factor on the command line) is read
here, by :func:`read_number`, under one rule:

* ``int``, :class:`~fractions.Fraction`, ``Decimal``, sympy
  Rationals and numpy integers are exact already and kept as they are.
* A float -- Python's or numpy's -- is read by the *float rule*.  When
  its shortest decimal form (its ``repr``) has at most
  :data:`FLOAT_DIGITS` (12) significant digits, the float is read as that
  decimal: the number the user typed.  So ``0.1`` is 1/10,
  ``np.float64(0.5)`` is 1/2, ``2.5e-3`` is 1/400 and ``0.123456789`` is
  123456789/10^9.  A float with more digits is the result of a computation
  (``1/3`` prints as ``0.3333333333333333``): it is read as the simplest
  fraction -- smallest denominator, then smallest numerator -- whose
  nearest double is that float, so ``1/3`` is 1/3 and ``0.1 + 0.2`` is the
  simplest fraction that rounds to ``0.30000000000000004``.  Either way the
  reading rounds back to the same float.  The exponent limits below apply
  to the fraction read.
* A string is an integer, a decimal (``"0.1"``, ``"1e-3"``) or a fraction
  ``"p/q"``, read exactly.
* ``True``/``False``, infinities, NaN and anything else are refused with a
  :class:`~pitheorem.errors.NumberError` that names the value.

Every exact number pitheorem gives back is a :class:`~fractions.Fraction`.
Further rules build on :func:`read_number`: :func:`read_positive` for a
positive number, :func:`read_scale_factor` for the scale factor ``s``, and
:func:`read_value` for a parameter value; the last two keep a float a float
(float in, float out) and make any other number exact.

The size limits, stated here and nowhere else (:data:`LIMITS` lists
them for the documentation):

* an exponent -- of a base dimension, of the scale factor ``s``, or a
  power a dimension is raised to -- lies within :data:`MAX_EXPONENT`
  (1000) in magnitude, with a denominator of at most
  :data:`MAX_DENOMINATOR` (10^12); its numerator is whatever these two
  allow (up to 10^15);
* a dimension formula nests brackets at most :data:`MAX_NESTING` (100)
  deep and is at most :data:`MAX_FORMULA_LENGTH` (10,000) characters long.

They are enforced wherever an exponent enters: a formula
(``Dimension.parse``, a model file's ``dimension``), a mapping
(``Dimension({...})``, ``System({...})``), a power or product of
dimensions (``Dimension ** p``, ``*``, ``/``: every
:class:`~pitheorem.Dimension` lies within them), a unit string
(``System.from_units``, a model file's ``unit``), and the exponents of a
scaling or a search.  The limits hold for totals (``"L^1000 L^1000"``,
``(L^1000)^1000``), not only for each number written.  Beyond them a
:class:`~pitheorem.errors.LimitError` states the limit; within them
nothing is refused.  No physical model comes near these limits; they keep
exact arithmetic fast and every result printable.
"""

from __future__ import annotations

import math
import numbers
import re
import sys
from decimal import Decimal
from fractions import Fraction

import sympy

from .errors import InvalidRequestError, LimitError, NumberError

__all__ = [
    "FLOAT_DIGITS",
    "LIMITS",
    "MAX_DENOMINATOR",
    "MAX_EXPONENT",
    "MAX_FLOAT_DENOMINATOR",
    "MAX_FORMULA_LENGTH",
    "MAX_NESTING",
    "is_float",
    "read_count",
    "read_exponent",
    "read_number",
    "read_positive",
    "read_rational",
    "read_scale_factor",
    "read_value",
    "short_text",
    "simplest_fraction_rounding_to",
]

#: largest magnitude of an exponent (of a base dimension or of ``s``)
MAX_EXPONENT = 1000
#: largest denominator of an exponent
MAX_DENOMINATOR = 10**12
#: deepest bracket nesting in a dimension formula
MAX_NESTING = 100
#: longest dimension formula, in characters
MAX_FORMULA_LENGTH = 10_000
#: most significant digits of a float's shortest decimal form that is read as that decimal
FLOAT_DIGITS = 12
#: largest denominator of an exponent read from a computed float (one of more than FLOAT_DIGITS digits): the
#: float of every such fraction within the exponent limits reads back as that fraction, and the float of an
#: irrational number almost never does (the chance is about 1e-7 at worst, for exponents near 1000)
MAX_FLOAT_DENOMINATOR = 1000
#: the size limits, as the documentation tables them: (what, limit); beyond one, a LimitError
LIMITS: tuple[tuple[str, str], ...] = (
    ("magnitude of an exponent (of a base dimension, of s, or a power)", f"{MAX_EXPONENT}"),
    ("denominator of an exponent", f"10^{len(str(MAX_DENOMINATOR)) - 1}"),
    ("bracket nesting in a dimension formula", f"{MAX_NESTING}"),
    ("length of a dimension formula", f"{MAX_FORMULA_LENGTH:,} characters"),
)
#: largest power of ten written in a number string (``"1e400"`` is fine, ``"1e99999999"`` is not)
_MAX_DECIMAL_EXPONENT = 10_000
_MAX_STRING_LENGTH = 1_000

_NUMBER_TEXT = re.compile(r"[+-]?\d+/\d+|[+-]?(\d+(\.\d*)?|\.\d+)([eE](?P<exp>[+-]?\d+))?")

_EXPECTED = "a finite real number (int, float, Fraction, numpy or sympy number, or a string such as '0.1' or '1/3')"


def read_number(value, what: str = "the number", *, irrational_ok: bool = False) -> Fraction:
    """A finite real number as an exact Fraction, under the module's rule.

    Parameters
    ----------
    value : int, float, Fraction, Decimal, str, numpy or sympy number
        The number.  Floats are read by the float rule (module notes).
    what : str
        What the number is, for the error message (``"exponent of 'g'"``).
    irrational_ok : bool
        Also accept irrational sympy numbers (``pi``, ``sqrt(2)``), through
        the float nearest to them.

    Returns
    -------
    Fraction

    Raises
    ------
    NumberError
        For anything that is not a finite real number.
    LimitError
        For a number string with a power of ten beyond 10^10000.

    Examples
    --------
    >>> import numpy as np
    >>> from pitheorem.exact import read_number
    >>> read_number(0.1), read_number(np.float64(0.5)), read_number("1/3"), read_number("2.5e-3")
    (Fraction(1, 10), Fraction(1, 2), Fraction(1, 3), Fraction(1, 400))
    >>> read_number(1 / 3), read_number(2 / 7), read_number(0.123456789)
    (Fraction(1, 3), Fraction(2, 7), Fraction(123456789, 1000000000))
    """
    np = numpy_if_loaded()
    if isinstance(value, bool) or (np is not None and isinstance(value, np.bool_)):
        raise NumberError(value, what, _EXPECTED + ", not a bool")
    if np is not None and isinstance(value, np.ndarray) and value.shape == ():
        value = value[()]
    if isinstance(value, int) or (np is not None and isinstance(value, np.integer)):
        return Fraction(int(value))
    if isinstance(value, Fraction):
        return value
    # floats and Decimals go through their text: "inf", "nan", "Infinity" and "NaN" match no number
    # text, so _from_text refuses them with the same message as any other non-number
    if isinstance(value, float) or (np is not None and isinstance(value, np.floating)):
        return _from_float(value, what)
    if isinstance(value, Decimal):
        return _from_text(str(value), value, what)
    if isinstance(value, sympy.Basic):
        if value.is_Rational:
            return Fraction(int(value.p), int(value.q))
        if isinstance(value, sympy.Float) and value.is_finite:
            # sympy.Float(0.1) carries a double's 53 bits: read it as that double; a Float made with
            # more digits, or beyond the doubles' range (1e-400), is read as the decimal it holds
            if value._prec <= 53 and (value == 0 or float(value) not in (0.0, math.inf, -math.inf)):
                return read_number(float(value), what)
            return _from_text(str(value), value, what)
        if irrational_ok and value.is_number and value.is_extended_real and value.is_finite:
            return read_number(float(value), what)
        raise NumberError(value, what, _EXPECTED if irrational_ok else "a rational number such as 1, -2 or '1/2'")
    if isinstance(value, str):
        return _from_text(value, value, what)
    raise NumberError(value, what, _EXPECTED)


def read_positive(value, what: str, *, irrational_ok: bool = False) -> Fraction:
    """Read a positive finite number, such as the scale factor ``s``.

    Parameters
    ----------
    value : number or str
        As for :func:`read_number`.
    what : str
        What the number is, for the error message (``"the scale factor s"``).
    irrational_ok : bool
        Also accept positive irrational sympy numbers (``sqrt(2)``), read
        as the float nearest to them.

    Returns
    -------
    Fraction

    Raises
    ------
    NumberError
        For anything that is not a positive finite number.

    Examples
    --------
    >>> from pitheorem.exact import read_positive
    >>> read_positive("1/3", "the scale factor s"), read_positive(0.5, "the scale factor s")
    (Fraction(1, 3), Fraction(1, 2))
    >>> from pitheorem import NumberError
    >>> try:
    ...     read_positive(-2, "the scale factor s")
    ... except NumberError as err:
    ...     print(err)
    the scale factor s must be a positive finite number such as 2, 0.5 or '1/3', got -2
    """
    expected = "a positive finite number such as 2, 0.5 or '1/3'"
    try:
        number = read_number(value, what, irrational_ok=irrational_ok)
    except NumberError:
        raise NumberError(value, what, expected) from None
    if number <= 0:
        raise NumberError(value, what, expected)
    return number


def read_count(value, what: str, least: int = 0, most: int | None = None) -> int:
    """Read a count, such as a number of steps: a whole number of at least `least` (and at most `most`).

    Parameters
    ----------
    value : int
        A Python or numpy integer; ``True``, ``2.0`` and ``"2"`` are not
        counts.
    what : str
        What the count is, for the error message (``"n_steps"``).
    least : int
        The smallest count allowed (default 0).
    most : int, optional
        The largest count allowed: a count that would make that many runs,
        copies or rows of memory is refused before any is made.

    Returns
    -------
    int

    Raises
    ------
    InvalidRequestError
        For anything else, naming `what`, `least` and the value.

    Examples
    --------
    >>> from pitheorem.exact import read_count
    >>> read_count(3, "n_steps")
    3
    >>> from pitheorem import InvalidRequestError
    >>> try:
    ...     read_count(0, "ensemble", least=1)
    ... except InvalidRequestError as err:
    ...     print(err)
    ensemble must be a whole number of at least 1, got 0
    >>> try:
    ...     read_count(2**70, "ensemble", least=1, most=100)
    ... except InvalidRequestError as err:
    ...     print(err)
    ensemble must be a whole number from 1 to 100, got 1180591620717411303424
    """
    if (
        isinstance(value, bool)
        or not isinstance(value, numbers.Integral)
        or value < least
        or (most is not None and value > most)
    ):
        wanted = f"of at least {least}" if most is None else f"from {least} to {most}"
        raise InvalidRequestError(f"{what} must be a whole number {wanted}, got {value!r}", culprit=value)
    return int(value)


def read_scale_factor(s) -> float | Fraction | sympy.Expr:
    """Read the scale factor ``s``: positive, and float in, float out.

    A float (Python's, numpy's or sympy's) stays a float, so arithmetic
    with it stays in floating point; an irrational sympy number
    (``sqrt(2)``) stays exact as it is; any other number becomes a Fraction.

    Parameters
    ----------
    s : number or str
        As for :func:`read_positive`.

    Returns
    -------
    float, Fraction or sympy number

    Raises
    ------
    NumberError
        For anything that is not a positive finite number; the message
        names "the scale factor s".

    Examples
    --------
    >>> import sympy
    >>> from pitheorem.exact import read_scale_factor
    >>> read_scale_factor(2), read_scale_factor("1/2"), read_scale_factor(2.5), read_scale_factor(sympy.sqrt(2))
    (Fraction(2, 1), Fraction(1, 2), 2.5, sqrt(2))
    """
    exact = read_positive(s, "the scale factor s", irrational_ok=True)
    if is_float(s):
        return _finite_float(s, exact, "the scale factor s")
    return s if isinstance(s, sympy.Basic) and not s.is_Rational else exact


def is_float(value) -> bool:
    """Whether a number is floating point: arithmetic on it stays in floats.

    Python and numpy floats, sympy Floats and numpy arrays are; ints,
    Fractions, sympy Rationals and strings are not.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.exact import is_float
    >>> is_float(0.5), is_float(Fraction(1, 2)), is_float(2)
    (True, False, False)
    """
    np = numpy_if_loaded()
    return isinstance(value, float | sympy.Float) or (np is not None and isinstance(value, np.floating | np.ndarray))


def read_value(value, what: str) -> float | Fraction:
    """Read a parameter value the way pitheorem keeps it: float in, float out.

    A float (Python's, numpy's or sympy's) stays a float, and so does an
    irrational sympy number (its nearest float); any other number is read
    exactly by :func:`read_number` and becomes a Fraction.

    Parameters
    ----------
    value : number or str
        The value.
    what : str
        What it is, for the error message (``"the value of 'm'"``).

    Returns
    -------
    float or Fraction

    Raises
    ------
    NumberError
        For anything that is not a finite real number.

    Examples
    --------
    >>> from pitheorem.exact import read_value
    >>> read_value(9.81, "g"), read_value(3, "m"), read_value("1/3", "l")
    (9.81, Fraction(3, 1), Fraction(1, 3))
    """
    exact = read_number(value, what, irrational_ok=True)
    if is_float(value) or (isinstance(value, sympy.Basic) and not value.is_Rational):
        return _finite_float(value, exact, what)
    return exact


def _finite_float(value, exact: Fraction, what: str) -> float:
    """``float(value)``, or LimitError where it is infinite or a nonzero number became 0.0.

    A sympy Float such as 1e400 or 1e-400 is beyond doubles, and float() of it gives inf or 0.0
    without a word.
    """
    number = float(value)
    if math.isinf(number) or (number == 0 and exact != 0):
        raise LimitError(
            short_text(exact),
            what,
            "it is beyond the range of floating point (about 1e-308 to 1.8e308)",
            "pass it exactly, as an int, a Fraction or a string",
        )
    return number


def numpy_if_loaded():
    """numpy, if some code has imported it; a value cannot be a numpy scalar otherwise.

    Looking it up instead of importing it keeps ``import pitheorem`` free of numpy.
    """
    return sys.modules.get("numpy")


def _from_float(value, what: str) -> Fraction:
    """A Python or numpy float under the float rule (module notes)."""
    if not isinstance(value, float):  # numpy's float32 and friends: their own shortest decimal, as typed
        return _from_text(str(value), value, what)
    if not math.isfinite(value):
        raise NumberError(value, what, _EXPECTED)
    if not _is_computed_float(value):
        return _from_text(repr(float(value)), value, what)  # np.float64 is a float too; its repr is numpy's
    return simplest_fraction_rounding_to(float(value))


def simplest_fraction_rounding_to(x: float) -> Fraction:
    """The simplest fraction whose nearest double is `x`.

    Simplest: the smallest denominator, and among those the smallest
    numerator in magnitude.  The fractions that round to `x` fill the
    interval between the midpoints to its neighbouring doubles; the
    midpoints themselves round to `x` when its last bit is even (ties to
    even).

    Examples
    --------
    >>> from pitheorem.exact import simplest_fraction_rounding_to
    >>> simplest_fraction_rounding_to(1 / 3), simplest_fraction_rounding_to(-22 / 7)
    (Fraction(1, 3), Fraction(-22, 7))
    >>> simplest_fraction_rounding_to(0.1 + 0.2)  # not 3/10, which rounds to 0.29999999999999999
    Fraction(415716888680356, 1385722962267853)
    """
    if x < 0:
        return -simplest_fraction_rounding_to(-x)
    if x == 0:
        return Fraction(0)
    # the ends, in integers (a third of the time of Fraction's arithmetic): the midpoints between x = n / d and
    # its neighbours below and above
    n, d = x.as_integer_ratio()
    below_n, below_d = math.nextafter(x, 0).as_integer_ratio()
    low_n, low_d = n * below_d + below_n * d, 2 * d * below_d
    if x < sys.float_info.max:
        above_n, above_d = math.nextafter(x, math.inf).as_integer_ratio()
        high = (n * above_d + above_n * d, 2 * d * above_d)
    else:
        high = None
    ties_to_x = int(x / math.ulp(x)) % 2 == 0  # round half to even: an even significand keeps the ties
    return _simplest_between(low_n, low_d, high, ties_to_x)


def _simplest_between(low_n: int, low_d: int, high: tuple[int, int] | None, closed: bool) -> Fraction:
    """The simplest fraction from ``low_n / low_d`` > 0 to ``high`` (a ratio ``(n, d)``; None: no upper end),
    ends included if `closed`.

    Stern-Brocot descent through continued fractions, in integers: take the
    smallest integer in the interval if there is one; else both ends share an
    integer part a, and the answer is a + 1/y for the simplest y between the
    reciprocals of the ends' fractional parts.  The partial quotients a are
    folded into the convergents p/q as they come, so that the last one, w,
    gives the answer (w p + p') / (w q + q').
    """
    p_before, q_before, p, q = 0, 1, 1, 0  # the convergents before the first quotient
    while True:
        a, rest = divmod(low_n, low_d)
        whole = a if closed and rest == 0 else a + 1
        if high is None or whole * high[1] < high[0] or (closed and whole * high[1] == high[0]):
            return Fraction(whole * p + p_before, whole * q + q_before)
        p_before, q_before, p, q = p, q, a * p + p_before, a * q + q_before
        # y runs from 1 / (high - a) to 1 / (low - a); low == a: an open end at a, no upper end for y
        high_n, high_d = high
        low_n, low_d, high = high_d, high_n - a * high_d, (None if rest == 0 else (low_d, rest))


def _from_text(text: str, value, what: str) -> Fraction:
    text = text.strip()
    if len(text) > _MAX_STRING_LENGTH:
        raise LimitError(f"{text[:20]}...", what, f"a number string may have at most {_MAX_STRING_LENGTH} characters")
    match = _NUMBER_TEXT.fullmatch(text)
    if match is None:
        raise NumberError(value, what, _EXPECTED)
    # check the power of ten before Fraction builds 10**exp
    if match.group("exp") is not None and abs(int(match.group("exp"))) > _MAX_DECIMAL_EXPONENT:
        raise LimitError(text, what, f"its power of ten exceeds the limit 10^{_MAX_DECIMAL_EXPONENT}")
    try:
        return Fraction(text)
    except ZeroDivisionError:
        raise NumberError(value, what, _EXPECTED + ", with a nonzero denominator") from None


def check_exponent(exponent: Fraction, what: str, *, shown: object = None) -> Fraction:
    """Return `exponent` if it lies within the exponent limits, else raise LimitError.

    `shown` is the value as the user gave it, for the message.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.exact import check_exponent
    >>> check_exponent(Fraction(1, 3), "exponent of 'g'")
    Fraction(1, 3)
    """
    np = numpy_if_loaded()
    from_decimal = isinstance(shown, float | Decimal | sympy.Float) or (
        np is not None and isinstance(shown, np.floating)
    )
    if shown is None or isinstance(shown, int | Fraction):
        shown = short_text(Fraction(exponent))
    elif isinstance(shown, str) and len(shown) > 40:
        shown = shown[:40] + "..."
    if abs(exponent) > MAX_EXPONENT:
        raise LimitError(shown, what, f"its magnitude exceeds the limit {MAX_EXPONENT}")
    if exponent.denominator > MAX_DENOMINATOR:
        hint = ""
        if from_decimal:
            hint = (
                "a float is read as the decimal it prints as, or as the simplest fraction that rounds to it; "
                "pass an exact exponent such as Fraction(1, 3) or '1/3'"
            )
        raise LimitError(
            shown,
            what,
            f"its denominator {short_text(Fraction(exponent.denominator))} exceeds the limit {MAX_DENOMINATOR}",
            hint,
        )
    return exponent


def read_rational(value, what: str) -> Fraction:
    """Read a number that must be rational, such as an exponent.

    :func:`read_number`, and one rule more for a computed float (one of
    more than :data:`FLOAT_DIGITS` significant digits): the simplest
    fraction that rounds to it must have a denominator of at most
    :data:`MAX_FLOAT_DENOMINATOR`.  ``1/3`` passes as 1/3; ``2**0.5``,
    whose simplest fraction is 131836323/93222358, is the float of an
    irrational number and is refused.  No limit on the size is applied
    (:func:`read_exponent` applies them).

    Parameters
    ----------
    value : number or str
        As for :func:`read_number`.
    what : str
        What the number is, for the error message.

    Returns
    -------
    Fraction
        The exact number read.

    Raises
    ------
    NumberError
        For anything that is not a rational number, naming the value.

    Examples
    --------
    >>> from pitheorem.exact import read_rational
    >>> read_rational(1 / 3, "the power"), read_rational(0.1 + 0.6, "the power")
    (Fraction(1, 3), Fraction(7, 10))
    >>> from pitheorem import NumberError
    >>> try:
    ...     read_rational(2**0.5, "the power")
    ... except NumberError as err:
    ...     print(err.culprit)
    1.4142135623730951
    """
    number = read_number(value, what)
    if number.denominator > MAX_FLOAT_DENOMINATOR and _is_computed_float(value):
        raise NumberError(
            value,
            what,
            f"a rational number: a float of more than {FLOAT_DIGITS} digits is read as the simplest fraction that "
            f"rounds to it, here {short_text(number)}, and the denominator of an exponent read so may not exceed "
            f"{MAX_FLOAT_DENOMINATOR} (the float of an irrational number, such as a square root, has no simpler "
            "one); give the exponent exactly, as a Fraction, a string such as '1/3', or a formula such as 'L^(1/3)'",
        )
    return number


def _is_computed_float(value) -> bool:
    """Whether `value` is a double that the float rule reads as a computed float (more than FLOAT_DIGITS digits)."""
    if isinstance(value, sympy.Float) and value._prec <= 53:
        value = float(value)
    if not isinstance(value, float):  # np.float64 is a float; float32 and Decimal are read as the decimal they print
        return False
    digits = repr(float(value)).lstrip("-").split("e")[0].replace(".", "").strip("0")
    return len(digits) > FLOAT_DIGITS


def read_exponent(value, what: str) -> Fraction:
    """Read an exponent: :func:`read_rational`, then the exponent limits.

    Examples
    --------
    >>> from pitheorem.exact import read_exponent
    >>> read_exponent("-1/2", "exponent of 'l'"), read_exponent(0.25, "exponent of 'g'")
    (Fraction(-1, 2), Fraction(1, 4))
    >>> from pitheorem import LimitError
    >>> try:
    ...     read_exponent(1e-13, "exponent of 'g'")
    ... except LimitError as err:
    ...     print(err.limit)
    its denominator 10000000000000 exceeds the limit 1000000000000
    """
    return check_exponent(read_rational(value, what), what, shown=value)


def short_text(value: Fraction) -> str:
    """The number itself when short, else its order of magnitude.

    Python refuses to print integers of more than 4300 digits, and error
    messages should stay one line.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.exact import short_text
    >>> short_text(Fraction(1, 3)), short_text(Fraction(10**400)), short_text(Fraction(-1, 10**50))
    ('1/3', 'about 10^400', 'about -10^-50')
    """
    value = Fraction(value)
    if value.numerator.bit_length() + value.denominator.bit_length() < 120:
        return str(value)
    decades = round(math.log10(abs(value.numerator)) - math.log10(value.denominator))
    return f"about {'-' if value < 0 else ''}10^{decades}"
