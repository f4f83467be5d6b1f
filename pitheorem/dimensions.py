"""Dimensions: the :class:`Dimension` value type and its formula parser.

A dimension is a product of named base dimensions raised to exact rational
powers, e.g. ``M L^2 T^-2``.  Formulas are tokenized and parsed here, by
hand: user text is never passed to ``eval`` or ``sympify``.

Base dimensions understood by default are ``M L T Theta I``.  The symbols
``N`` (amount of substance), ``J`` (luminous intensity) and ``A`` (angle)
are opt-in: each is also the symbol of an SI unit (newton, joule, ampere),
so a force written as ``"N"`` must not silently become an amount of
substance.  Declare them with ``base_dimensions=`` to use them; without
that, a formula using one is refused with a message that says so and
suggests the dimension or unit meant.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from fractions import Fraction

from .errors import DimensionSyntaxError, InvalidRequestError, LimitError
from .exact import (
    MAX_DENOMINATOR,
    MAX_EXPONENT,
    MAX_FORMULA_LENGTH,
    MAX_NESTING,
    check_exponent,
    read_exponent,
    read_rational,
)
from .formatting import MathDisplay, render
from .immutable import immutable

__all__ = ["DEFAULT_BASE_DIMENSIONS", "OPT_IN_BASE_DIMENSIONS", "Dimension", "base_dimension_names"]

#: Base dimensions understood without being declared, in display order:
#: mass, length, time, temperature, current.
DEFAULT_BASE_DIMENSIONS: tuple[str, ...] = ("M", "L", "T", "Theta", "I")

#: Base dimensions that must be declared (``base_dimensions=``) because
#: their letters are also SI unit symbols: amount of substance ``N``
#: (newton), luminous intensity ``J`` (joule), angle ``A`` (ampere).
OPT_IN_BASE_DIMENSIONS: tuple[str, ...] = ("N", "J", "A")

# display order of every known base dimension; others follow alphabetically
_DISPLAY_ORDER = DEFAULT_BASE_DIMENSIONS + OPT_IN_BASE_DIMENSIONS

# what a user who writes one of the opt-in letters most likely meant
_UNIT_LOOKALIKES = {
    "N": "the newton, a force: write 'M L T^-2' (or give units with System.from_units)",
    "J": "the joule, an energy: write 'M L^2 T^-2' (or give units with System.from_units)",
    "A": "the ampere, a current: write 'I' (or give units with System.from_units)",
}


def base_dimension_names(names, what: str = "base_dimensions") -> tuple[str, ...]:
    """Validate a collection of base-dimension names.

    A plain string is refused rather than read letter by letter
    (``"LT"`` would otherwise mean ``("L", "T")``).

    Examples
    --------
    >>> from pitheorem.dimensions import base_dimension_names
    >>> base_dimension_names(["M", "L", "T", "N"])
    ('M', 'L', 'T', 'N')
    """
    if isinstance(names, str):
        raise InvalidRequestError(
            f"{what} must be a list of names such as ('M', 'L', 'T'), not the string {names!r}", culprit=names
        )
    try:
        names = tuple(names)
    except TypeError:
        raise InvalidRequestError(
            f"{what} must be a list of names such as ('M', 'L', 'T'), got {names!r}", culprit=names
        ) from None
    for b in names:
        if not isinstance(b, str) or not b.isidentifier():
            raise InvalidRequestError(f"base dimension names must be identifiers, got {b!r}", culprit=b)
    return names


_TOKEN = re.compile(r"\s*(?:(?P<name>[A-Za-z_][A-Za-z_0-9]*)|(?P<number>\d+(?:\.\d*)?|\.\d+)|(?P<op>\*\*|[\^*/()+-]))")


def _order_key(base: str) -> tuple[int, str]:
    try:
        return (_DISPLAY_ORDER.index(base), "")
    except ValueError:
        return (len(_DISPLAY_ORDER), base)


@immutable
@dataclass(frozen=True, slots=True)
class Dimension(MathDisplay):
    """An exact product of base dimensions, such as ``M L^2 T^-2``.

    Immutable and hashable.  Zero exponents are dropped, so two dimensions
    are equal exactly when they are the same physical dimension.  Every
    Dimension lies within the exponent limits of :mod:`pitheorem.exact`
    (magnitude 1000, denominator 10^12): the constructor, the parser and
    ``*``, ``/`` and ``**`` refuse anything beyond them with a
    :class:`~pitheorem.LimitError`, and an irrational power with a
    :class:`~pitheorem.NumberError`.

    Parameters
    ----------
    exponents : mapping or iterable of (str, number) pairs
        Base dimension names and their (rational) exponents.

    Examples
    --------
    >>> from pitheorem import Dimension
    >>> torque = Dimension.parse("M L^2 T^-2")
    >>> torque
    Dimension.parse('M L^2 T^-2')
    >>> torque / Dimension.parse("L")
    Dimension.parse('M L T^-2')
    >>> (Dimension.parse("L") ** Fraction(1, 2)).exponents
    {'L': Fraction(1, 2)}
    >>> Dimension({"L": 1, "T": -2}) == Dimension.parse("L/T^2")
    True
    >>> Dimension.parse("1").is_dimensionless
    True
    >>> from pitheorem import LimitError
    >>> try:
    ...     Dimension.parse("L^999") * Dimension.parse("L^2")
    ... except LimitError as err:
    ...     print(err)
    the exponent of 'L' is 1001: its magnitude exceeds the limit 1000
    """

    # (base, exponent) pairs with nonzero exponents, in display order
    _exponents: tuple[tuple[str, Fraction], ...]

    def __init__(self, exponents: Mapping[str, object] | Iterable[tuple[str, object]] = ()):
        total: dict[str, Fraction] = {}
        for base, p in _pairs(exponents):
            if not isinstance(base, str) or not base.isidentifier():
                raise InvalidRequestError(
                    f"base dimension names must be identifiers such as 'L' or 'Theta', got {base!r}", culprit=base
                )
            total[base] = total.get(base, Fraction(0)) + read_rational(p, f"the exponent of {base!r}")
        object.__setattr__(self, "_exponents", _clean(total))
        # the limits hold for the total, however it was reached: many small terms, or a power of a power
        self._within_limits()

    @classmethod
    def _combined(cls, pairs: Iterable[tuple[str, Fraction]]) -> Dimension:
        """The product of exact (base, exponent) pairs, unchecked: callers check the total.

        The algebra's own constructor; every public way to a Dimension
        ends in :meth:`_within_limits`, so that each Dimension lies within
        the limits of :mod:`pitheorem.exact`.
        """
        total: dict[str, Fraction] = {}
        for base, p in pairs:
            total[base] = total.get(base, Fraction(0)) + p
        dim = object.__new__(cls)
        object.__setattr__(dim, "_exponents", _clean(total))
        return dim

    def _within_limits(self, where: str = "") -> Dimension:
        """This dimension, if every exponent lies within the limits; else LimitError (`where`: of what)."""
        for base, p in self._exponents:
            if abs(p) > MAX_EXPONENT or p.denominator > MAX_DENOMINATOR:
                check_exponent(p, f"the exponent of {base!r}{where}")
        return self

    # -- construction -----------------------------------------------------
    @classmethod
    def parse(cls, text: str, *, base_dimensions: Iterable[str] = DEFAULT_BASE_DIMENSIONS) -> Dimension:
        """Parse a formula as people write it.

        Accepted: juxtaposition or ``*`` for products, ``/`` for quotients,
        ``^`` or ``**`` for powers (integers, decimals, or ``(p/q)``), and
        ``1`` or the empty string for a dimensionless quantity.

        Parameters
        ----------
        text : str
            The formula, e.g. ``"M L^2 T^-2"``, ``"M*L**2/T**2"``, ``"L^(1/2)"``.
        base_dimensions : iterable of str
            Names allowed as base dimensions (default ``M L T Theta I``;
            ``N``, ``J`` and ``A`` only when listed, see the module notes).

        Returns
        -------
        Dimension

        Raises
        ------
        DimensionSyntaxError
            With the position of the offending token.
        LimitError
            For an exponent beyond the limits of :mod:`pitheorem.exact`,
            brackets nested too deep, or a formula too long.

        Examples
        --------
        >>> from pitheorem import Dimension
        >>> str(Dimension.parse("M*L**2/T**2"))
        'M L^2 T^-2'
        >>> str(Dimension.parse("L^(1/2) T^-0.5"))
        'L^(1/2) T^(-1/2)'
        """
        if not isinstance(text, str):
            raise DimensionSyntaxError(repr(text), 0, f"expected a string, got {type(text).__name__}")
        return _Parser(text, base_dimension_names(base_dimensions)).parse()

    @classmethod
    def dimensionless(cls) -> Dimension:
        """The dimension of a pure number.

        Examples
        --------
        >>> from pitheorem import Dimension
        >>> Dimension.dimensionless() == Dimension.parse("")
        True
        """
        return cls(())

    # -- queries ----------------------------------------------------------
    @property
    def is_dimensionless(self) -> bool:
        """True when every exponent is zero.

        Examples
        --------
        >>> from pitheorem import Dimension
        >>> Dimension.parse("L/L").is_dimensionless
        True
        """
        return not self._exponents

    @property
    def exponents(self) -> dict[str, Fraction]:
        """Exponent of each base dimension (nonzero ones only, in display order).

        Examples
        --------
        >>> from pitheorem import Dimension
        >>> Dimension.parse("T^-2 L").exponents
        {'L': Fraction(1, 1), 'T': Fraction(-2, 1)}
        """
        return dict(self._exponents)

    def exponent_of(self, base: str) -> Fraction:
        """The exponent of one base dimension (zero when absent).

        Parameters
        ----------
        base : str
            A base dimension, e.g. ``"T"``.

        Returns
        -------
        Fraction

        Examples
        --------
        >>> from pitheorem import Dimension
        >>> Dimension.parse("L T^-2").exponent_of("T")
        Fraction(-2, 1)
        """
        for b, p in self._exponents:
            if b == base:
                return p
        return Fraction(0)

    @property
    def base_dimensions(self) -> tuple[str, ...]:
        """The base dimensions with nonzero exponent, in display order.

        Examples
        --------
        >>> from pitheorem import Dimension
        >>> Dimension.parse("T^-2 L").base_dimensions
        ('L', 'T')
        """
        return tuple(b for b, _ in self._exponents)

    # -- algebra ----------------------------------------------------------
    def __mul__(self, other: Dimension) -> Dimension:
        if not isinstance(other, Dimension):
            return NotImplemented
        return _remembered(self, other, 1)

    def __truediv__(self, other: Dimension) -> Dimension:
        if not isinstance(other, Dimension):
            return NotImplemented
        return _remembered(self, other, -1)

    def __pow__(self, exponent) -> Dimension:
        # the power is an exponent as written in a formula, under the same rule and limits; so is the result
        if type(exponent) is int and abs(exponent) <= MAX_EXPONENT:  # the common case, exact and within them
            return _power(self._exponents, exponent)
        return _power(self._exponents, read_exponent(exponent, "the power of a dimension"))

    # -- display (text, LaTeX and the rest: pitheorem.formatting) -----------
    def __repr__(self) -> str:
        return f"Dimension.parse({str(self)!r})"

    @property
    def latex(self) -> str:
        r"""LaTeX for the dimension, e.g. ``\mathsf{M}\,\mathsf{L}^{2}``.

        Examples
        --------
        >>> from pitheorem import Dimension
        >>> Dimension.parse("L T^-2").latex
        '\\mathsf{L}\\,\\mathsf{T}^{-2}'
        """
        return render(self, "latex")


def product_of_powers(factors: Iterable[tuple[Dimension, Fraction]], where: str = "") -> Dimension:
    """The product of dimensions raised to exact powers, held to the limits once, at the end.

    For the dimension of a term of an equation: ``x**1000 * y**1000 / z**1000``
    lies within the limits though its first two factors together do not.
    `where` names the term in the LimitError (``" in the dimension of x**1001"``).

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.dimensions import Dimension, product_of_powers
    >>> L = Dimension.parse("L")
    >>> product_of_powers([(L, 1000), (L, 1000), (L, -1000)])
    Dimension.parse('L^1000')
    """
    return Dimension._combined((b, p * Fraction(e)) for d, e in factors for b, p in d._exponents)._within_limits(where)


# Products, quotients and powers are remembered: a Dimension never changes, each costs about 10 us of
# Fraction arithmetic, and a model file's reader asks the same few thousands of times (a joint's force
# over its coordinate, for every joint).  Keyed by the operands' exponents; a result beyond the limits
# raises, and is not remembered.  A product or quotient of the very same two objects is found first by
# their identities (:data:`_BY_IDENTITY`), without hashing their exponents' Fractions: 0.2 us, not 1.3.

#: (id(a), id(b), sign) -> (a, b, the result): the operands kept, so that no other object takes their ids
_BY_IDENTITY: dict[tuple[int, int, int], tuple] = {}


def _remembered(a: Dimension, b: Dimension, sign: int) -> Dimension:
    """`a` times (sign 1) or over (sign -1) `b`, remembered."""
    key = (id(a), id(b), sign)
    known = _BY_IDENTITY.get(key)
    if known is None:
        if len(_BY_IDENTITY) >= 4096:
            _BY_IDENTITY.clear()
        known = _BY_IDENTITY[key] = (a, b, _product(a._exponents, b._exponents, sign))
    return known[2]


@functools.lru_cache(maxsize=4096)
def _product(a: tuple, b: tuple, sign: int) -> Dimension:
    """The dimension of exponents `a` times (sign 1) or over (sign -1) those of `b`."""
    return Dimension._combined(a + (b if sign == 1 else tuple((base, -p) for base, p in b)))._within_limits()


@functools.lru_cache(maxsize=4096)
def _power(a: tuple, e: int | Fraction) -> Dimension:
    """The dimension of exponents `a` to the exact power `e`."""
    return Dimension._combined((base, p * e) for base, p in a)._within_limits()


def _clean(total: dict[str, Fraction]) -> tuple[tuple[str, Fraction], ...]:
    """Nonzero exponents in display order."""
    return tuple(sorted(((b, p) for b, p in total.items() if p != 0), key=lambda bp: _order_key(bp[0])))


def _pairs(exponents) -> list[tuple[object, object]]:
    """The (base, exponent) pairs of a mapping or an iterable of pairs; anything else is refused by name."""
    expected = "a mapping of base names to exponents, such as {'L': 1, 'T': -2} (use Dimension.parse for a formula)"
    if isinstance(exponents, Mapping):
        return list(exponents.items())
    if isinstance(exponents, str | bytes):
        raise InvalidRequestError(f"a Dimension takes {expected}, not the string {exponents!r}", culprit=exponents)
    try:
        pairs = [tuple(pair) for pair in exponents]
    except TypeError:
        raise InvalidRequestError(f"a Dimension takes {expected}, got {exponents!r}", culprit=exponents) from None
    for pair in pairs:
        if len(pair) != 2:
            raise InvalidRequestError(f"a Dimension takes {expected}, got the entry {pair!r}", culprit=pair)
    return pairs


class _Parser:
    """Recursive-descent parser for dimension formulas (see Dimension.parse)."""

    def __init__(self, text: str, allowed: tuple[str, ...]):
        self.text, self.allowed = text, allowed
        self.depth = 0
        self.where = f" in {text!r}" if len(text) <= 40 else ""  # for a total beyond the limits
        if len(text) > MAX_FORMULA_LENGTH:
            raise LimitError(
                f"{text[:20]}...",
                "the dimension formula",
                f"its length {len(text)} exceeds the limit of {MAX_FORMULA_LENGTH} characters",
            )
        self.tokens: list[tuple[str, str, int]] = []
        pos = 0
        while pos < len(text):
            if text[pos:].strip() == "":
                break
            m = _TOKEN.match(text, pos)
            if m is None or m.end() == pos:
                bad = len(text[pos:]) - len(text[pos:].lstrip()) + pos
                raise DimensionSyntaxError(
                    text, bad, f"unexpected character {text[bad]!r}; use base dimensions, * / ^ ** ( ) and numbers"
                )
            kind = m.lastgroup
            start = m.start(kind)
            self.tokens.append((kind, m.group(kind), start))
            pos = m.end()
        self.i = 0

    def peek(self):
        return self.tokens[self.i] if self.i < len(self.tokens) else ("end", "", len(self.text))

    def take(self):
        tok = self.peek()
        self.i += 1
        return tok

    def fail(self, tok, reason: str):
        found = "the end of the formula" if tok[0] == "end" else repr(tok[1])
        raise DimensionSyntaxError(self.text, tok[2], f"{reason}; found {found}")

    def parse(self) -> Dimension:
        if not self.tokens:
            return Dimension.dimensionless()
        dim = self.product()
        tok = self.peek()
        if tok[0] != "end":
            self.fail(tok, f"unexpected {tok[1]!r} after a complete formula")
        return dim

    def product(self) -> Dimension:
        # each product is held to the limits: the total of a formula, not only each exponent ("L^1000 L^1000")
        dim = self.power()
        while True:
            kind, value, _ = self.peek()
            if value == "*":
                self.take()
                dim = product_of_powers([(dim, 1), (self.power(), 1)], self.where)
            elif value == "/":
                self.take()
                dim = product_of_powers([(dim, 1), (self.power(), -1)], self.where)
            elif kind in ("name", "number") or value == "(":
                dim = product_of_powers([(dim, 1), (self.power(), 1)], self.where)  # juxtaposition: "M L^2"
            else:
                return dim

    def power(self) -> Dimension:
        dim = self.atom()
        if self.peek()[1] in ("^", "**"):
            self.take()
            dim = product_of_powers([(dim, self.exponent())], self.where)  # "(L^1000)^1000" is beyond
        return dim

    def atom(self) -> Dimension:
        tok = self.take()
        kind, value, _ = tok
        if kind == "name":
            if value not in self.allowed and value in _UNIT_LOOKALIKES:
                self.fail(
                    tok,
                    f"{value!r} is not a base dimension by default: it is the SI symbol of {_UNIT_LOOKALIKES[value]}; "
                    f"to mean the base dimension {value!r}, declare it with base_dimensions=(..., {value!r})",
                )
            if value not in self.allowed:
                self.fail(
                    tok,
                    f"unknown base dimension {value!r}; valid base dimensions are {', '.join(self.allowed)} "
                    "(declare others with base_dimensions=..., or give units with System.from_units)",
                )
            return Dimension({value: 1})
        if kind == "number":
            if Fraction(value) != 1:
                self.fail(tok, f"a bare number {value!r} has no dimension; only '1' may stand alone")
            return Dimension.dimensionless()
        if value == "(":
            self.depth += 1
            if self.depth > MAX_NESTING:
                raise LimitError(
                    f"{self.text[:20]}...",
                    "the dimension formula",
                    f"its brackets nest deeper than the limit of {MAX_NESTING}",
                )
            dim = self.product()
            if self.peek()[1] != ")":
                self.fail(self.peek(), "expected ')' to close the bracket")
            self.take()
            self.depth -= 1
            return dim
        self.fail(tok, "expected a base dimension, '1' or '('" if kind != "end" else "formula ends too early")
        raise AssertionError  # unreachable: fail() raises

    def exponent(self) -> Fraction:
        value = self.exponent_value()
        return check_exponent(value, f"exponent in {self.text!r}" if len(self.text) <= 40 else "an exponent")

    def exponent_value(self) -> Fraction:
        tok = self.peek()
        if tok[1] == "(":
            self.take()
            value = self.signed_number()
            if self.peek()[1] == "/":
                self.take()
                den_tok = self.peek()
                den = self.signed_number()
                if den == 0:
                    self.fail(den_tok, "division by zero in exponent")
                value = value / den
            if self.peek()[1] != ")":
                self.fail(self.peek(), "expected ')' to close the exponent")
            self.take()
            return value
        return self.signed_number()

    def signed_number(self) -> Fraction:
        sign = 1
        if self.peek()[1] in ("+", "-"):  # one sign at most: "--2" is a typo, not 2
            sign = -1 if self.take()[1] == "-" else 1
        tok = self.take()
        if tok[0] != "number":
            self.fail(tok, "expected a number as exponent, e.g. ^2, ^-1 or ^(1/2)")
        if len(tok[1]) > 40:
            raise LimitError(f"{tok[1][:20]}...", "an exponent", "it has more than 40 digits")
        return sign * Fraction(tok[1])
