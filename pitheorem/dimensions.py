"""Dimensions: the :class:`Dimension` value type and its formula parser.

A dimension is a product of named base dimensions raised to exact rational
powers, e.g. ``M L^2 T^-2``.  Formulas are tokenized and parsed here, by
hand: user text is never passed to ``eval`` or ``sympify``.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from fractions import Fraction

from .errors import DimensionSyntaxError

__all__ = ["DEFAULT_BASE_DIMENSIONS", "Dimension"]

#: Base dimensions understood without being declared, in display order:
#: mass, length, time, temperature, current, amount, luminous intensity,
#: and ``A`` for angle when a model treats angle as a base dimension.
DEFAULT_BASE_DIMENSIONS: tuple[str, ...] = ("M", "L", "T", "Theta", "I", "N", "J", "A")

_TOKEN = re.compile(
    r"\s*(?:(?P<name>[A-Za-z_][A-Za-z_0-9]*)|(?P<number>\d+(?:\.\d*)?|\.\d+)|(?P<op>\*\*|[\^*/()+-]))"
)


def _order_key(base: str) -> tuple[int, str]:
    try:
        return (DEFAULT_BASE_DIMENSIONS.index(base), "")
    except ValueError:
        return (len(DEFAULT_BASE_DIMENSIONS), base)


def _format_power(p: Fraction) -> str:
    return str(p.numerator) if p.denominator == 1 else f"({p})"


@dataclass(frozen=True, slots=True)
class Dimension:
    """An exact product of base dimensions, such as ``M L^2 T^-2``.

    Immutable and hashable.  Zero powers are dropped, so two dimensions are
    equal exactly when they are the same physical dimension.

    Parameters
    ----------
    powers : mapping or iterable of (str, number) pairs
        Base dimension names and their (rational) exponents.

    Examples
    --------
    >>> from pitheorem import Dimension
    >>> torque = Dimension.parse("M L^2 T^-2")
    >>> torque
    Dimension.parse('M L^2 T^-2')
    >>> torque / Dimension.parse("L")
    Dimension.parse('M L T^-2')
    >>> (Dimension.parse("L") ** Fraction(1, 2)).powers
    (('L', Fraction(1, 2)),)
    >>> Dimension.parse("1").is_dimensionless
    True
    """

    powers: tuple[tuple[str, Fraction], ...]

    def __init__(self, powers: Mapping[str, object] | Iterable[tuple[str, object]] = ()):
        items = powers.items() if isinstance(powers, Mapping) else powers
        total: dict[str, Fraction] = {}
        for base, p in items:
            total[base] = total.get(base, Fraction(0)) + Fraction(p)
        clean = tuple(sorted(((b, p) for b, p in total.items() if p != 0), key=lambda bp: _order_key(bp[0])))
        object.__setattr__(self, "powers", clean)

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
            Names allowed as base dimensions.

        Returns
        -------
        Dimension

        Raises
        ------
        DimensionSyntaxError
            With the position of the offending token.

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
        return _Parser(text, tuple(base_dimensions)).parse()

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
        return not self.powers

    def exponent(self, base: str) -> Fraction:
        """The exponent of one base dimension (zero when absent).

        Examples
        --------
        >>> from pitheorem import Dimension
        >>> Dimension.parse("L T^-2").exponent("T")
        Fraction(-2, 1)
        """
        return dict(self.powers).get(base, Fraction(0))

    @property
    def bases(self) -> tuple[str, ...]:
        """The base dimensions with nonzero exponent, in display order.

        Examples
        --------
        >>> from pitheorem import Dimension
        >>> Dimension.parse("T^-2 L").bases
        ('L', 'T')
        """
        return tuple(b for b, _ in self.powers)

    # -- algebra ----------------------------------------------------------
    def __mul__(self, other: Dimension) -> Dimension:
        if not isinstance(other, Dimension):
            return NotImplemented
        return Dimension(self.powers + other.powers)

    def __truediv__(self, other: Dimension) -> Dimension:
        if not isinstance(other, Dimension):
            return NotImplemented
        return Dimension(self.powers + tuple((b, -p) for b, p in other.powers))

    def __pow__(self, exponent) -> Dimension:
        e = Fraction(exponent)
        return Dimension((b, p * e) for b, p in self.powers)

    # -- display ----------------------------------------------------------
    def __str__(self) -> str:
        if not self.powers:
            return "1"
        return " ".join(b if p == 1 else f"{b}^{_format_power(p)}" for b, p in self.powers)

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
        if not self.powers:
            return "1"
        parts = []
        for b, p in self.powers:
            name = r"\Theta" if b == "Theta" else rf"\mathsf{{{b}}}"
            parts.append(name if p == 1 else f"{name}^{{{p}}}")
        return r"\,".join(parts)

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {self.latex}$"


class _Parser:
    """Recursive-descent parser for dimension formulas (see Dimension.parse)."""

    def __init__(self, text: str, allowed: tuple[str, ...]):
        self.text, self.allowed = text, allowed
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
        dim = self.power()
        while True:
            kind, value, _ = self.peek()
            if value == "*":
                self.take()
                dim = dim * self.power()
            elif value == "/":
                self.take()
                dim = dim / self.power()
            elif kind in ("name", "number") or value == "(":
                dim = dim * self.power()  # juxtaposition: "M L^2"
            else:
                return dim

    def power(self) -> Dimension:
        dim = self.atom()
        if self.peek()[1] in ("^", "**"):
            self.take()
            dim = dim ** self.exponent()
        return dim

    def atom(self) -> Dimension:
        tok = self.take()
        kind, value, _ = tok
        if kind == "name":
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
            dim = self.product()
            if self.peek()[1] != ")":
                self.fail(self.peek(), "expected ')' to close the bracket")
            self.take()
            return dim
        self.fail(tok, "expected a base dimension, '1' or '('" if kind != "end" else "formula ends too early")
        raise AssertionError  # unreachable: fail() raises

    def exponent(self) -> Fraction:
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
        while self.peek()[1] in ("+", "-"):
            sign = -sign if self.take()[1] == "-" else sign
        tok = self.take()
        if tok[0] != "number":
            self.fail(tok, "expected a number as exponent, e.g. ^2, ^-1 or ^(1/2)")
        return sign * Fraction(tok[1])
