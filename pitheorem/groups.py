"""Dimensionless groups: :class:`PiGroup` and the immutable :class:`PiSet`.

A group is stored as its integer exponent vector, normalised to the
smallest integers with a positive exponent on its defining variable (or,
for a group not tied to one variable, on the first variable it uses).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import sympy

from .errors import InvalidRequestError, LimitError
from .exact import read_number, read_value
from .formatting import MathDisplay
from .immutable import immutable
from .linalg import primitive_integer_vector, rank

__all__ = ["PiGroup", "PiSet"]


def _symbol(name: str) -> sympy.Symbol:
    return sympy.Symbol(name, positive=True)


@immutable
@dataclass(frozen=True, slots=True)
class PiGroup(MathDisplay):
    """A dimensionless product of powers of variables.

    Parameters
    ----------
    exponents : mapping or iterable of (str, int) pairs
        Variables and their integer exponents, in system order (zeros are
        dropped).  Taken as given; :meth:`from_exponents` normalises
        rational exponents to the smallest integers instead.
    variable : str or None
        The non-repeating variable this group was built for, if any.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2"})
    >>> pi_g = rod.pi_groups(repeating=("m", "l", "k_theta"))[0]
    >>> pi_g
    PiGroup.from_exponents({'m': 1, 'l': 1, 'g': 1, 'k_theta': -1}, variable='g')
    >>> print(pi_g)
    Pi_g = g*l*m/k_theta
    >>> pi_g.evaluate({"m": 1, "l": 2, "g": 10, "k_theta": 4})
    Fraction(5, 1)
    >>> PiGroup({"t": 2, "l": -1}).exponents
    {'t': 2, 'l': -1}
    """

    # (variable, exponent) pairs with nonzero integer exponents, in order
    _exponents: tuple[tuple[str, int], ...]
    variable: str | None

    def __init__(self, exponents: Mapping[str, int] | Iterable[tuple[str, int]] = (), variable: str | None = None):
        items = exponents.items() if isinstance(exponents, Mapping) else exponents
        pairs = []
        for name, p in items:
            if not isinstance(name, str):
                raise InvalidRequestError(f"a Pi group's variables are names, got {name!r}", culprit=name)
            if type(p) is not int:  # the common case costs nothing more
                exact = read_number(p, f"the exponent of {name!r} in a Pi group")
                if exact.denominator != 1:
                    raise InvalidRequestError(
                        f"the exponent of {name!r} in a Pi group is {exact}: PiGroup takes integer exponents; "
                        "PiGroup.from_exponents normalises rational ones",
                        culprit=p,
                    )
                p = int(exact)
            if p:
                pairs.append((name, p))
        object.__setattr__(self, "_exponents", tuple(pairs))
        object.__setattr__(self, "variable", variable)

    @classmethod
    def from_exponents(
        cls, exponents: Mapping[str, object], *, variable: str | None = None, order: Sequence[str] | None = None
    ) -> PiGroup:
        """Normalise rational exponents to the canonical group.

        Parameters
        ----------
        exponents : mapping of str to number
            Exponent of each variable (rational allowed).
        variable : str, optional
            Variable whose exponent is made positive.
        order : sequence of str, optional
            Order of variables in the group (default: as given).

        Returns
        -------
        PiGroup

        Examples
        --------
        >>> from fractions import Fraction
        >>> from pitheorem import PiGroup
        >>> PiGroup.from_exponents({"a": Fraction(-1, 2), "b": 1}).exponents
        {'a': 1, 'b': -2}
        """
        names = list(order) if order is not None else list(exponents)
        vec = primitive_integer_vector([exponents.get(n, 0) for n in names])
        pivot = names.index(variable) if variable in names and vec[names.index(variable)] else None
        if pivot is None:
            pivot = next((i for i, v in enumerate(vec) if v), None)
        if pivot is not None and vec[pivot] < 0:
            vec = [-v for v in vec]
        return cls(tuple(zip(names, vec, strict=True)), variable)

    @property
    def exponents(self) -> dict[str, int]:
        """Exponent of each variable in the group (nonzero ones only).

        Examples
        --------
        >>> from pitheorem import PiGroup
        >>> PiGroup({"t": 2, "l": -1}).exponents
        {'t': 2, 'l': -1}
        """
        return dict(self._exponents)

    @property
    def name(self) -> str:
        """``Pi_<variable>`` when tied to a variable, else ``Pi``.

        Examples
        --------
        >>> from pitheorem import PiGroup
        >>> PiGroup({"g": 1}, "g").name
        'Pi_g'
        """
        return f"Pi_{self.variable}" if self.variable else "Pi"

    @property
    def expr(self) -> sympy.Expr:
        """The group as a sympy expression in positive symbols.

        The symbols are created with ``positive=True`` (physical magnitudes),
        so compare with ``sympy.Symbol(name, positive=True)``, or compare
        :attr:`exponents` instead.

        Examples
        --------
        >>> from pitheorem import PiGroup
        >>> PiGroup({"t": 2, "l": -1}).expr
        t**2/l
        """
        return sympy.Mul(*(_symbol(n) ** p for n, p in self._exponents))

    @property
    def latex(self) -> str:
        r"""LaTeX of the group's expression.

        Examples
        --------
        >>> from pitheorem import PiGroup
        >>> PiGroup({"c_theta": 2, "m": -1}).latex
        '\\frac{c_{\\theta}^{2}}{m}'
        """
        return sympy.latex(self.expr)

    @property
    def is_trivial(self) -> bool:
        """True for the empty product (the number 1).

        Examples
        --------
        >>> from pitheorem import PiGroup
        >>> PiGroup({}).is_trivial, PiGroup({"g": 1, "l": -1}).is_trivial
        (True, False)
        """
        return not self._exponents

    def reciprocal(self) -> PiGroup:
        """The group with every exponent negated.

        Examples
        --------
        >>> from pitheorem import PiGroup
        >>> PiGroup({"a": 1, "b": -2}).reciprocal().exponents
        {'a': -1, 'b': 2}
        """
        return PiGroup(tuple((n, -p) for n, p in self._exponents), self.variable)

    def is_power_of(self, other: PiGroup) -> bool:
        """True when one group is a rational power of the other (e.g. its reciprocal).

        Parameters
        ----------
        other : PiGroup

        Returns
        -------
        bool

        Examples
        --------
        >>> from pitheorem import PiGroup
        >>> a = PiGroup({"g": 1, "l": -1})
        >>> a.is_power_of(PiGroup({"l": 2, "g": -2}))
        True
        """
        names = sorted({n for n, _ in self._exponents} | {n for n, _ in other._exponents})
        a, b = self.exponents, other.exponents
        return rank([[a.get(n, 0) for n in names], [b.get(n, 0) for n in names]]) <= 1

    def evaluate(self, values: Mapping[str, object]):
        """Value of the group for given variable values.

        Float in, float out: a float when some value is a float (or an
        irrational sympy number), else an exact Fraction (values are read by
        :func:`pitheorem.exact.read_value`).

        Parameters
        ----------
        values : mapping of str to number
            Must contain every variable of the group.

        Returns
        -------
        Fraction or float

        Examples
        --------
        >>> from fractions import Fraction
        >>> from pitheorem import PiGroup
        >>> PiGroup({"t": 2, "l": -1}).evaluate({"t": Fraction(1, 2), "l": 3})
        Fraction(1, 12)
        >>> PiGroup({"t": 2, "l": -1}).evaluate({"t": 0.5, "l": 3.0})
        0.08333333333333333
        """
        missing = [n for n, _ in self._exponents if n not in values]
        if missing:
            raise InvalidRequestError(f"evaluate needs a value for {', '.join(map(repr, missing))} of {self}")
        read = [read_value(values[n], f"the value of {n!r}") for n, _ in self._exponents]
        for (n, p), v in zip(self._exponents, read, strict=True):
            if v == 0 and p < 0:
                raise InvalidRequestError(f"{n!r} = 0 appears with exponent {p} in {self}: the group is undefined")
        if all(isinstance(v, Fraction) for v in read):
            return self._product(read, Fraction(1))
        try:
            result = self._product([float(v) for v in read], 1.0)
        except (OverflowError, ZeroDivisionError):  # a power beyond floats (1e-200 ** -2, 1e-400 ** -1)
            result = math.inf
        if math.isfinite(result):
            return result
        # beyond floats on the way: the exact product of the floats' values and the exact values, rounded once
        try:
            return float(self._product([Fraction(v) for v in read], Fraction(1)))
        except OverflowError:
            raise LimitError(
                str(self), "the value of the group", "it is beyond the range of floating point (about 1.8e308)"
            ) from None

    def _product(self, values, one):
        result = one
        for (_, p), v in zip(self._exponents, values, strict=True):
            result = result * v**p
        return result

    def __repr__(self) -> str:
        var = f", variable={self.variable!r}" if self.variable else ""
        return f"PiGroup.from_exponents({dict(self._exponents)!r}{var})"


@immutable
class PiSet(MathDisplay, Sequence):
    """An immutable sequence of independent Pi groups.

    Parameters
    ----------
    groups : iterable of PiGroup
    variables : sequence of str
        All variables of the system, in order.
    repeating : sequence of str
        The repeating variables the groups were built from.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})
    >>> groups = rod.pi_groups(repeating=("m", "l", "g"))
    >>> print(groups)
    Pi_t = g*t**2/l
    >>> groups.equivalent(rod.pi_groups(repeating=("m", "l", "t")))
    True
    """

    __slots__ = ("_groups", "_repeating", "_variables")

    def __init__(self, groups: Iterable[PiGroup], variables: Sequence[str], repeating: Sequence[str] = ()):
        object.__setattr__(self, "_groups", tuple(groups))
        object.__setattr__(self, "_variables", tuple(variables))
        object.__setattr__(self, "_repeating", tuple(repeating))

    def __reduce__(self):
        return (PiSet, (self._groups, self._variables, self._repeating))

    @property
    def repeating(self) -> tuple[str, ...]:
        """The repeating variables.

        Examples
        --------
        >>> import pitheorem as pt
        >>> rod = pt.System({"m": "M", "l": "L", "g": "L/T^2", "t": "T"})
        >>> rod.pi_groups(repeating=("m", "l", "g")).repeating
        ('m', 'l', 'g')
        """
        return self._repeating

    @property
    def variables(self) -> tuple[str, ...]:
        """Every variable of the system, in order.

        Examples
        --------
        >>> import pitheorem as pt
        >>> rod = pt.System({"m": "M", "l": "L", "g": "L/T^2", "t": "T"})
        >>> rod.pi_groups(repeating=("m", "l", "g")).variables
        ('m', 'l', 'g', 't')
        """
        return self._variables

    def __getitem__(self, index):
        if isinstance(index, str):
            for g in self._groups:
                if g.variable == index:
                    return g
            raise InvalidRequestError(
                f"no group for {index!r}; groups exist for {', '.join(str(g.variable) for g in self._groups)}"
            )
        return self._groups[index]

    def __len__(self) -> int:
        return len(self._groups)

    def __eq__(self, other) -> bool:
        return isinstance(other, PiSet) and (self._groups, self._variables) == (other._groups, other._variables)

    def __hash__(self) -> int:
        return hash((self._groups, self._variables))

    def exponent_matrix(self) -> list[list[int]]:
        """Rows are groups, columns are the system's variables.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"l": "L", "x": "L"}).pi_groups(repeating=("l",)).exponent_matrix()
        [[-1, 1]]
        """
        return [[g.exponents.get(v, 0) for v in self._variables] for g in self._groups]

    def equivalent(self, other: PiSet) -> bool:
        """True when both sets generate the same dimensionless products.

        Two sets are equivalent when each group of one is a product of
        rational powers of the groups of the other: they describe the same
        physics, whatever repeaters produced them.

        Parameters
        ----------
        other : PiSet

        Returns
        -------
        bool

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"a": "L", "b": "L", "c": "L"})
        >>> s.pi_groups(repeating=("a",)).equivalent(s.pi_groups(repeating=("c",)))
        True
        """
        if set(self._variables) != set(other._variables):
            return False
        order = self._variables
        mine = self.exponent_matrix()
        theirs = [[g.exponents.get(v, 0) for v in order] for g in other]
        r = rank(mine) if mine else 0
        return r == (rank(theirs) if theirs else 0) == (rank(mine + theirs) if mine + theirs else 0)

    def __repr__(self) -> str:
        return f"PiSet({list(self._groups)!r}, variables={self._variables!r}, repeating={self._repeating!r})"
