"""The :class:`System`: named variables with dimensions, and its dimension matrix.

This is the friendly layer: it validates names and formulas, reads pint
unit strings, and turns questions about Pi groups and bases into calls of
the exact kernels in :mod:`pitheorem.linalg` and :mod:`pitheorem.bases`.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from fractions import Fraction
from functools import lru_cache
from math import gcd, lcm
from typing import TYPE_CHECKING

import sympy

from .dimensions import DEFAULT_BASE_DIMENSIONS, OPT_IN_BASE_DIMENSIONS, Dimension, base_dimension_names
from .errors import (
    DependentRepeatingSetError,
    DimensionSyntaxError,
    DuplicateVariableError,
    EmptySystemError,
    InvalidRequestError,
    LimitError,
    PiTheoremError,
    RepeatingCountError,
    UnitError,
    UnknownVariableError,
)
from .exact import check_exponent, read_exponent
from .groups import PiGroup, PiSet
from .immutable import immutable
from .linalg import integer_rref, nullspace, rank

if TYPE_CHECKING:
    from .basis_sequence import BasisSequence

_TIME = Dimension({"T": 1})
_ZERO = Fraction(0)

#: the rows of a chunk of repeating sets :meth:`System.iter_bases` turns into names at a time
_ROWS_AT_A_TIME = 1024

__all__ = ["System"]

# pint's names for the SI base dimensions, mapped to ours
#: a power followed by a division by a number, 'm^-1/2': pint divides the unit by 2, a reader means m^(-1/2)
_AMBIGUOUS_POWER = re.compile(r"(\^|\*\*)\s*[+-]?\s*(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\s*/\s*[\d.]")

_PINT_BASES = {
    "[mass]": "M",
    "[length]": "L",
    "[time]": "T",
    "[temperature]": "Theta",
    "[current]": "I",
    "[substance]": "N",
    "[luminosity]": "J",
}


# "M L^2 T^-2": names with small integer powers, the formulas nearly every variable has.
# They are read in one regular-expression pass, each name's meaning taken from the parser
# itself (once per name), so that both ways agree; anything else goes to the parser.
_SIMPLE_FACTOR = re.compile(r"([A-Za-z_][A-Za-z_0-9]*)(?:\^(-?[1-9][0-9]?))?")


@lru_cache(maxsize=256)
def _parse_name(name: str, allowed: tuple[str, ...]) -> Dimension | None:
    try:
        return Dimension.parse(name, base_dimensions=allowed)
    except PiTheoremError:
        return None  # let the parser report it, on the whole formula


def _simple_dimension(text: str, allowed: tuple[str, ...]) -> Dimension | None:
    powers: dict[str, int | Fraction] = {}
    for word in text.split():
        factor = _SIMPLE_FACTOR.fullmatch(word)
        base = factor and _parse_name(factor[1], allowed)
        if base is None:
            return None
        p = int(factor[2] or 1)
        for b, q in base.exponents.items():
            # integer arithmetic where it can be: Fractions are slow to make
            q = int(q) if q.denominator == 1 else q
            powers[b] = powers.get(b, 0) + q * p
    return Dimension(powers) if powers else None


@lru_cache(maxsize=4096)
def _parse(text: str, allowed: tuple[str, ...]) -> Dimension:
    # the same few formulas ("L", "M L^2 T^-2") recur in every model: parse each once
    return _simple_dimension(text, allowed) or Dimension.parse(text, base_dimensions=allowed)


def _pairs(variables) -> list[tuple[str, object]]:
    if isinstance(variables, Mapping):
        return list(variables.items())
    try:
        return [tuple(item) for item in variables]  # type: ignore[misc]
    except TypeError:
        raise InvalidRequestError(
            f"variables must be a mapping of names to dimensions, got {type(variables).__name__}"
        ) from None


@lru_cache(maxsize=1024)
def _within_limits(dimension: Dimension) -> bool:
    """Whether every exponent of a dimension is within the package's limits (a model's hundreds of
    parameters share a handful of dimensions: each is checked once)."""
    try:
        for power in dimension.exponents.values():
            check_exponent(power, "an exponent")
    except PiTheoremError:
        return False
    return True


@immutable
class System:
    """Variables with dimensions: the input of every dimensional analysis.

    Parameters
    ----------
    variables : mapping of str to dimension, or iterable of (name, dimension)
        Each dimension is a formula string (``"M L^2 T^-2"``), a
        :class:`Dimension`, or a mapping of base names to exponents.
    base_dimensions : iterable of str, optional
        Names allowed as base dimensions, in display order.  Default:
        ``M L T Theta I``.  ``N`` (amount of substance), ``J`` (luminous
        intensity) and ``A`` (angle) must be listed here to be used,
        because each is also an SI unit symbol (newton, joule, ampere).
    repeating : iterable of str, optional
        The system's own default repeaters: ``rank`` variables with
        independent dimensions, which :meth:`pi_groups` uses when it is
        given none (:meth:`default_repeating`).  Default: the first valid set
        without time variables.  The system of an engine model carries the
        robot's numbers here (:meth:`pitheorem.engines.EngineModel.system`),
        never a solver's setting.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2",
    ...                  "c_theta": "M L^2 T^-1", "theta_r": "1", "t": "T"})
    >>> rod.base_dimensions, rod.rank, rod.n_groups
    (('M', 'L', 'T'), 3, 4)
    >>> rod.matrix
    Matrix([
    [1, 0,  0,  1,  1, 0, 0],
    [0, 1,  1,  2,  2, 0, 0],
    [0, 0, -2, -2, -1, 0, 1]])
    >>> print(rod.pi_groups(repeating=("m", "l", "k_theta")))
    Pi_g = g*l*m/k_theta
    Pi_c_theta = c_theta**2/(k_theta*l**2*m)
    Pi_theta_r = theta_r
    Pi_t = k_theta*t**2/(l**2*m)
    """

    __slots__ = ("_allowed", "_base_dimensions", "_columns", "_dimensions", "_reduced", "_repeating", "_variables")

    def __init__(self, variables, *, base_dimensions: Iterable[str] | None = None, repeating=None):
        allowed = DEFAULT_BASE_DIMENSIONS if base_dimensions is None else base_dimension_names(base_dimensions)
        if len(set(allowed)) != len(allowed):
            dup = next(b for b in allowed if allowed.count(b) > 1)
            raise DuplicateVariableError(dup, "base_dimensions")
        pairs = _pairs(variables)
        if not pairs:
            raise EmptySystemError()
        names: list[str] = []
        seen: set[str] = set()
        dims: list[Dimension] = []
        for item in pairs:
            if len(item) != 2:
                raise InvalidRequestError(f"expected (name, dimension) pairs, got {item!r}")
            name, spec = item
            if not isinstance(name, str) or not name.isidentifier():
                raise InvalidRequestError(
                    f"variable name {name!r} is not valid: use a Python identifier such as 'k_theta'"
                )
            if name in seen:
                raise DuplicateVariableError(name, "the system")
            names.append(name)
            seen.add(name)
            dims.append(self._read_dimension(name, spec, allowed))
        exponents = [d.exponents for d in dims]
        used = {b for e in exponents for b in e}
        order = [b for b in allowed if b in used]
        # attributes are written once, here (and the cache below): a System is immutable
        set_attribute = object.__setattr__
        set_attribute(self, "_allowed", allowed)
        set_attribute(self, "_variables", tuple(names))
        set_attribute(self, "_dimensions", tuple(dims))
        set_attribute(self, "_base_dimensions", tuple(order))
        set_attribute(self, "_columns", tuple(tuple(e.get(b, _ZERO) for b in order) for e in exponents))
        set_attribute(self, "_reduced", None)  # independent rows of D, found on first use
        set_attribute(self, "_repeating", None if repeating is None else self._checked_repeating(repeating))

    def __reduce__(self):
        pairs = tuple(zip(self._variables, self._dimensions, strict=True))
        return (_rebuild_system, (pairs, self._allowed, self._repeating))

    def _checked_repeating(self, repeating) -> tuple[str, ...]:
        """`repeating` as a valid repeating set of this system, or the error :meth:`pi_groups` raises."""
        rep = self.check_names(repeating, "repeating")
        if len(rep) != self.rank:
            raise RepeatingCountError(rep, self.rank)
        sub = self._submatrix([self.index(n) for n in rep])
        if rank(sub) < len(rep):
            dependency = nullspace(sub, len(rep))[0]
            product = PiGroup.from_exponents(dict(zip(rep, dependency, strict=True)))
            raise DependentRepeatingSetError(rep, str(sympy.sstr(product.expr)))
        return rep

    def with_repeating(self, repeating: Iterable[str] | None) -> System:
        """The same system with other default repeaters (None: the usual default).

        Parameters
        ----------
        repeating : iterable of str or None
            ``rank`` variables with independent dimensions.

        Returns
        -------
        System
            Equal variables and dimensions; :meth:`pi_groups` without
            repeaters uses `repeating`.

        Raises
        ------
        RepeatingCountError, DependentRepeatingSetError, UnknownVariableError

        Examples
        --------
        >>> import pitheorem as pt
        >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2"})
        >>> rod.default_repeating()
        ('m', 'l', 'g')
        >>> rod.with_repeating(("m", "l", "k_theta")).pi_groups().repeating
        ('m', 'l', 'k_theta')
        """
        copy = object.__new__(System)
        for name in System.__slots__:
            object.__setattr__(copy, name, getattr(self, name))
        object.__setattr__(copy, "_repeating", None if repeating is None else self._checked_repeating(repeating))
        return copy

    def _independent_rows(self) -> list[list[Fraction]]:
        # r independent rows of D itself (not its RREF): same column
        # dependencies, but small integer entries, which keeps the Hadamard
        # bound of the fast basis test low
        if self._reduced is None:
            rows = [[col[i] for col in self._columns] for i in range(len(self._base_dimensions))]
            keep = integer_rref(self._columns)[1] if rows else ()
            object.__setattr__(self, "_reduced", [rows[i] for i in keep])  # a cache, invisible but for speed
        return self._reduced

    @staticmethod
    def _read_dimension(name: str, spec, allowed) -> Dimension:
        if isinstance(spec, Dimension):
            dim = spec
            if not _within_limits(dim):  # a Dimension unpickled from elsewhere may pass the limits: name it
                for base, power in dim.exponents.items():
                    check_exponent(power, f"the exponent of {base!r} in the dimension of {name!r}")
        elif isinstance(spec, str):
            try:
                dim = _parse(spec, allowed)
            except DimensionSyntaxError as err:
                raise DimensionSyntaxError(err.text, err.position, f"{err.reason} (dimension of {name!r})") from None
            except LimitError as err:  # named as a syntax error is: the variable whose formula passes a limit
                raise LimitError(err.value, f"{err.what} (dimension of {name!r})", err.limit, err.hint) from None
        elif isinstance(spec, Mapping):
            for base, power in spec.items():
                if not isinstance(base, str):
                    raise InvalidRequestError(
                        f"dimension of {name!r} must map base names to numbers, got the key {base!r}", culprit=base
                    )
                read_exponent(power, f"the exponent of {base!r} in the dimension of {name!r}")
            dim = Dimension(spec)
        else:
            raise InvalidRequestError(f"dimension of {name!r} must be a formula string like 'M L^2 T^-2', got {spec!r}")
        unknown = [b for b in dim.base_dimensions if b not in allowed]
        if unknown:
            opt_in = (
                (
                    f"; {unknown[0]!r} is opt-in because it is also an SI unit symbol: declare it with "
                    f"base_dimensions=(..., {unknown[0]!r})"
                )
                if unknown[0] in OPT_IN_BASE_DIMENSIONS
                else ""
            )
            raise InvalidRequestError(
                f"dimension of {name!r} uses base {unknown[0]!r}; allowed bases are {', '.join(allowed)}{opt_in}",
                culprit=unknown[0],
            )
        return dim

    @classmethod
    def from_units(cls, units: Mapping[str, str], *, angle_as_base: bool = False) -> System:
        """Build a system from unit strings, read by pint.

        Parameters
        ----------
        units : mapping of str to str
            Unit of each variable, e.g. ``{"k_theta": "N*m/rad"}``.
        angle_as_base : bool
            Treat radians as a base dimension ``A`` instead of as 1.  Then a
            change of the angle unit counts as a similarity scaling; models
            with ``sin``/``cos`` of an angle are not invariant under it, so
            hold angles fixed when searching (see
            :func:`pitheorem.scaling_symmetries`).

        Returns
        -------
        System

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System.from_units({"k_theta": "N*m/rad", "rho": "kg/m^3", "t": "s"})
        >>> str(s.dimension("k_theta")), str(s.dimension("rho"))
        ('M L^2 T^-2', 'M L^-3')
        """
        import pint

        registry = unit_registry()
        if not isinstance(units, Mapping):
            raise UnitError(f"units must map each variable to a unit string, such as {{'l': 'm'}}, got {units!r}")
        dims = {}
        for name, text in units.items():
            if not isinstance(text, str):
                raise UnitError(f"unit of {name!r} must be a string such as 'kg*m/s^2', got {text!r}")
            ambiguous = _AMBIGUOUS_POWER.search(text)
            if ambiguous:
                # pint reads 'm^-1/2' as (m^-1)/2, a length to the -1; Dimension.parse refuses 'L^-1/2'
                raise UnitError(
                    f"the unit {text!r} of {name!r} is ambiguous: {ambiguous.group(0).strip()!r} is a power "
                    "divided by a number; write a fractional power in brackets, such as 'm^(-1/2)'"
                )
            what = f"the unit {text!r} of {name!r}" if len(text) <= 40 else f"the unit of {name!r}"
            try:
                quantity = registry.parse_expression(text) if text.strip() else registry.Quantity(1)
                if not isinstance(quantity, pint.Quantity):  # a bare number
                    quantity = registry.Quantity(quantity)
                for unit, p in quantity.unit_items():  # pint loops forever on the root units of 'kg^nan'
                    read_exponent(p, f"the exponent of {unit} in {what}")
                dimensionality = dict(quantity.dimensionality)
                root = dict(quantity.to_root_units().unit_items()) if angle_as_base else {}
            except PiTheoremError:
                raise
            except Exception as err:  # pint's parser can fail with almost anything, even AssertionError
                if isinstance(err, pint.errors.DefinitionSyntaxError | AssertionError | SyntaxError):
                    err = "malformed unit expression"  # its own message is empty or cryptic
                raise UnitError(f"cannot read the unit {text!r} of {name!r}: {err}") from None
            exponents = {}
            for key, p in dimensionality.items():
                if key not in _PINT_BASES:
                    raise UnitError(f"unit {text!r} of {name!r} has dimension {key}, which pitheorem does not know")
                # pint's exponents are floats (1/3 is 0.333...): read by the float rule, as every float is
                exponents[_PINT_BASES[key]] = read_exponent(p, f"the exponent of {key} in {what}")
            if angle_as_base and root.get("radian"):
                # pint treats angles as dimensionless; its root unit still records radians
                exponents["A"] = read_exponent(root["radian"], f"the exponent of radian in {what}")
            dims[name] = Dimension(exponents)
        # pint names the dimension, so an opt-in letter (N for [substance]) is meant here
        used = {b for d in dims.values() for b in d.base_dimensions}
        return cls(
            dims, base_dimensions=DEFAULT_BASE_DIMENSIONS + tuple(b for b in OPT_IN_BASE_DIMENSIONS if b in used)
        )

    # -- basic properties -------------------------------------------------
    @property
    def variables(self) -> tuple[str, ...]:
        """Variable names, in the order given.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"m": "M", "l": "L", "g": "L/T^2", "t": "T"}).variables
        ('m', 'l', 'g', 't')
        """
        return self._variables

    @property
    def base_dimensions(self) -> tuple[str, ...]:
        """Base dimensions that occur in some variable, in display order.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"g": "L/T^2", "m": "M"}).base_dimensions
        ('M', 'L', 'T')
        """
        return self._base_dimensions

    @property
    def dimensions(self) -> dict[str, Dimension]:
        """Each variable's :class:`Dimension` (a new dict on each call).

        Examples
        --------
        >>> import pitheorem as pt
        >>> {n: str(d) for n, d in pt.System({"l": "L", "g": "L/T^2"}).dimensions.items()}
        {'l': 'L', 'g': 'L T^-2'}
        """
        return dict(zip(self._variables, self._dimensions, strict=True))

    def column(self, name: str) -> tuple[Fraction, ...]:
        """A variable's column of the dimension matrix, as exact Fractions.

        The exponents of its dimension over :attr:`base_dimensions`, in
        that order (:attr:`matrix` holds the same numbers as sympy
        Rationals).

        Parameters
        ----------
        name : str
            A variable of the system.

        Returns
        -------
        tuple of Fraction

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"m": "M", "g": "L T^-2"}).column("g")
        (Fraction(0, 1), Fraction(1, 1), Fraction(-2, 1))
        """
        return self._columns[self.index(name)]

    def rows(self, names: Sequence[str] | None = None) -> list[list[Fraction]]:
        """The dimension matrix as exact rows: one per base dimension, a column per name.

        The rows of :attr:`matrix` as Fractions, over `names` only (the
        changes of units, as exponent vectors of those variables).

        Parameters
        ----------
        names : sequence of str, optional
            Variables of the system, in the order wanted (default: all).

        Returns
        -------
        list of list of Fraction

        Examples
        --------
        >>> import pitheorem as pt
        >>> [[str(x) for x in row] for row in pt.System({"m": "M", "g": "L T^-2"}).rows(["g"])]
        [['0'], ['1'], ['-2']]
        """
        cols = range(len(self._variables)) if names is None else [self.index(n) for n in names]
        return self._submatrix(cols)

    @property
    def time_variables(self) -> tuple[str, ...]:
        """The variables whose dimension is time alone (T), in system order.

        Time is hard to rescale in a running simulation (real-time
        controllers, an engine's fixed step), so these are held fixed by
        :func:`pitheorem.search` when no ``fixed`` is given, and avoided as
        repeaters by :meth:`default_repeating`.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"t": "T", "l": "L", "tau": "T", "f": "T^-1"}).time_variables
        ('t', 'tau')
        """
        return tuple(n for n, d in zip(self._variables, self._dimensions, strict=True) if d == _TIME)

    def dimension(self, name: str) -> Dimension:
        """The dimension of one variable.

        Parameters
        ----------
        name : str
            A variable of the system.

        Returns
        -------
        Dimension

        Raises
        ------
        UnknownVariableError
            For a name the system does not contain.

        Examples
        --------
        >>> import pitheorem as pt
        >>> str(pt.System({"g": "L/T^2"}).dimension("g"))
        'L T^-2'
        """
        return self._dimensions[self.index(name)]

    def index(self, name: str, context: str = "") -> int:
        """Position of a variable; raises UnknownVariableError for other names.

        Parameters
        ----------
        name : str
            A variable of the system.
        context : str, optional
            Where the name was used, for the error message (e.g. ``"fixed"``).

        Returns
        -------
        int

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"a": "L", "b": "T"}).index("b")
        1
        >>> try:
        ...     pt.System({"a": "L", "b": "T"}).index("c", "fixed")
        ... except pt.UnknownVariableError as err:
        ...     print(err)
        unknown variable 'c' in fixed; the system has a, b
        """
        try:
            return self._variables.index(name)
        except ValueError:
            raise UnknownVariableError(str(name), self._variables, context) from None

    def check_names(self, names, context: str) -> tuple[str, ...]:
        """Validate a collection of variable names: known, distinct, strings.

        Parameters
        ----------
        names : str or iterable of str
            The names; a single string is one name.
        context : str
            Where the names were used, for error messages (e.g. ``"exclude"``).

        Returns
        -------
        tuple of str

        Raises
        ------
        UnknownVariableError, DuplicateVariableError, InvalidRequestError
            For an unknown name, a name given twice, or something that is no name.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"a": "L", "b": "T"}).check_names(["b"], "exclude")
        ('b',)
        """
        if isinstance(names, str):
            names = (names,)
        try:
            names = tuple(names)
        except TypeError:
            raise InvalidRequestError(f"{context} must be a sequence of variable names, got {names!r}") from None
        seen = set()
        for n in names:
            if not isinstance(n, str):
                raise InvalidRequestError(f"{context} must contain variable names, got {n!r}")
            self.index(n, context)
            if n in seen:
                raise DuplicateVariableError(n, context)
            seen.add(n)
        return names

    @property
    def matrix(self) -> sympy.Matrix:
        """Dimension matrix: rows are base dimensions, columns variables.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"m": "M", "l": "L", "g": "L/T^2", "t": "T"}).matrix
        Matrix([
        [1, 0,  0, 0],
        [0, 1,  1, 0],
        [0, 0, -2, 1]])
        """
        return sympy.Matrix(
            len(self._base_dimensions),
            len(self._variables),
            lambda i, j: sympy.Rational(self._columns[j][i].numerator, self._columns[j][i].denominator),
        )

    @property
    def rank(self) -> int:
        """Rank of the dimension matrix: the number of repeating variables.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"m": "M", "l": "L", "g": "L/T^2", "t": "T"}).rank
        3
        """
        return len(self._independent_rows())

    @property
    def n_groups(self) -> int:
        """Number of independent dimensionless groups, ``n - rank``.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"m": "M", "l": "L", "g": "L/T^2", "t": "T"}).n_groups
        1
        """
        return len(self._variables) - self.rank

    def _submatrix(self, cols) -> list[list[Fraction]]:
        return [[self._columns[j][i] for j in cols] for i in range(len(self._base_dimensions))]

    def dimensionless_products(self) -> list[list[Fraction]]:
        """A basis of exponent vectors of dimensionless products (null space).

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"a": "L", "b": "L"}).dimensionless_products()
        [[Fraction(-1, 1), Fraction(1, 1)]]
        """
        rows = self.rows()
        return nullspace(rows, len(self._variables)) if rows else nullspace([], len(self._variables))

    # -- groups -----------------------------------------------------------
    def pi_groups(self, repeating: Iterable[str] | None = None) -> PiSet:
        """The Pi groups for a choice of repeating variables.

        Parameters
        ----------
        repeating : iterable of str, optional
            ``rank`` variables with independent dimensions.  Default:
            :meth:`default_repeating` (the system's own repeaters, given
            when it was made, else the first basis of :meth:`bases`
            without variables of dimension time alone).

        Returns
        -------
        PiSet
            One group per non-repeating variable, in system order.

        Raises
        ------
        RepeatingCountError, DependentRepeatingSetError, UnknownVariableError

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"F": "M L T^-2", "rho": "M L^-3", "v": "L/T", "d": "L"})
        >>> print(s.pi_groups(repeating=("rho", "v", "d")))
        Pi_F = F/(d**2*rho*v**2)
        """
        if repeating is None:
            rep_cols, (reduced, order) = self._default_basis()
            rep = tuple(self._variables[j] for j in rep_cols)
        else:
            rep = self.check_names(repeating, "repeating")
            if len(rep) != self.rank:
                raise RepeatingCountError(rep, self.rank)
            rep_cols = [self.index(n) for n in rep]
            reduced, order = self._eliminate(rep_cols)
            if reduced[1][: len(rep)] != tuple(range(len(rep))):
                sub = self._submatrix(rep_cols)
                dependency = nullspace(sub, len(rep))[0]
                product = PiGroup.from_exponents(dict(zip(rep, dependency, strict=True)))
                raise DependentRepeatingSetError(rep, str(sympy.sstr(product.expr)))
        return PiSet(self._groups_from(reduced, order, rep_cols), self._variables, rep)

    def _eliminate(self, first: Iterable[int]):
        """One fraction-free elimination of D with the columns `first` moved to the front.

        Returns ``((rows, pivots), order)``: the reduced rows and pivot
        positions of :func:`~pitheorem.linalg.integer_rref`, and the column
        order used (positions of variables).
        """
        first = list(first)
        chosen = set(first)
        order = first + [j for j in range(len(self._variables)) if j not in chosen]
        return integer_rref([[self._columns[j][i] for j in order] for i in range(len(self._base_dimensions))]), order

    def _groups_from(self, reduced, order, rep_cols) -> list[PiGroup]:
        """One group per non-repeating variable, read off a reduced matrix whose pivots are `rep_cols`.

        Reduced row ``i`` says ``pivot_i * D[rep_i] + sum_j a_ij D[j] = 0``
        over the non-pivot columns ``j``, so each column's group has the
        exponent ``a_ij / pivot_i`` on repeater ``i`` and -1 on itself
        (signs flipped below to make the variable's own exponent positive).
        """
        rows, pivots = reduced
        position = {col: k for k, col in enumerate(order)}
        rep_at = [(self._variables[rep_cols[i]], rows[i], rows[i][p]) for i, p in enumerate(pivots)]
        rep_set = set(rep_cols)
        groups = []
        for j, name in enumerate(self._variables):
            if j in rep_set:
                continue
            k = position[j]
            terms = [(n, row[k], piv) for n, row, piv in rep_at if row[k]]
            den = lcm(*(piv for _, _, piv in terms)) if terms else 1
            exps = {n: -a * (den // piv) for n, a, piv in terms}
            exps[name] = den
            g = gcd(*exps.values())
            groups.append(PiGroup(tuple((v, exps[v] // g) for v in self._variables if v in exps), name))
        return groups

    def _default_basis(self):
        """The default repeaters' columns and the elimination they come from.

        The system's own repeaters when it has them.  Else: bases are in
        lexicographic order of positions, so the first one is the greedy
        choice: the pivot columns of one elimination with the non-time
        variables first.  If they do not span, every basis needs time, and
        the first basis is the pivots in the plain order.
        """
        if self._repeating is not None:
            cols = [self.index(n) for n in self._repeating]
            return cols, self._eliminate(cols)
        time = self.time_variables
        avoid = [j for j, n in enumerate(self._variables) if n not in time]
        reduced, order = self._eliminate(avoid)
        pivots = reduced[1]
        if pivots and pivots[-1] >= len(avoid):
            reduced, order = self._eliminate(())
            pivots = reduced[1]
        cols = [order[p] for p in pivots]
        # _groups_from needs pivots in the same order as the repeaters they stand for
        return cols, (reduced, order)

    def default_repeating(self) -> tuple[str, ...]:
        """The repeaters :meth:`pi_groups` uses when none are given.

        The system's own, when it was made with ``repeating`` (an engine
        model's system: the robot's numbers, never a solver's setting).
        Else the first basis (in :meth:`bases` order) that avoids variables
        whose dimension is time alone, since time is hard to rescale in a
        running simulation; the first basis if every basis needs time.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"t": "T", "l": "L", "g": "L/T^2"}).default_repeating()
        ('l', 'g')
        >>> pt.System({"t": "T", "l": "L", "g": "L/T^2"}, repeating=("t", "g")).default_repeating()
        ('t', 'g')
        """
        if self._repeating is not None:
            return self._repeating
        return tuple(self._variables[j] for j in self._default_basis()[0])

    def first_basis(self, *, exclude: Iterable[str] = ()) -> tuple[str, ...] | None:
        """The first valid repeating set that avoids `exclude`, or None.

        The first in :meth:`bases` order: the same set as ``next(iter_bases(exclude=exclude), None)``, found
        by one elimination however many variables the system has.

        Parameters
        ----------
        exclude : iterable of str
            Variables never used as repeaters.

        Returns
        -------
        tuple of str or None
            None when every valid set uses one of `exclude`.

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"l": "L", "t": "T", "v": "L/T", "x": "L"})
        >>> s.first_basis(exclude=("l", "v")), s.first_basis(exclude=("t", "v"))
        (('t', 'x'), None)
        """
        if isinstance(exclude, str):
            exclude = (exclude,)
        avoid = set(exclude)
        unknown = avoid - set(self._variables)
        if unknown:
            self.index(sorted(unknown)[0], "exclude")  # raises, naming it
        cols = [j for j, n in enumerate(self._variables) if n not in avoid]
        (_rows, pivots), order = self._eliminate(cols)
        if len(pivots) < self.rank or (pivots and pivots[-1] >= len(cols)):
            return None
        return tuple(self._variables[order[p]] for p in pivots)

    # -- bases ------------------------------------------------------------
    def _basis_arguments(self, exclude, require):
        exclude = self.check_names(exclude, "exclude")
        require = self.check_names(require, "require")
        both = set(exclude) & set(require)
        if both:
            raise InvalidRequestError(f"variable {sorted(both)[0]!r} is both excluded and required")
        if len(require) > self.rank:
            raise RepeatingCountError(require, self.rank)
        req = [self.index(n) for n in require]
        if req and rank(self._submatrix(req)) < len(req):
            dependency = nullspace(self._submatrix(req), len(req))[0]
            product = PiGroup.from_exponents(dict(zip(require, dependency, strict=True)))
            raise DependentRepeatingSetError(require, str(sympy.sstr(product.expr)))
        cand = [j for j, n in enumerate(self._variables) if n not in exclude and n not in require]
        return self._independent_rows(), cand, req, self.rank

    def iter_bases(self, *, exclude: Iterable[str] = (), require: Iterable[str] = ()) -> Iterator[tuple[str, ...]]:
        """Lazily yield every valid repeating set (see :meth:`bases`).

        Parameters
        ----------
        exclude, require : iterable of str
            As for :meth:`bases`.

        Yields
        ------
        tuple of str

        Examples
        --------
        >>> import pitheorem as pt
        >>> next(pt.System({"l": "L", "t": "T", "v": "L/T"}).iter_bases())
        ('l', 't')
        """
        from .bases import independent_chunks  # numpy loads only when bases are listed

        names = self._variables
        for chunk in independent_chunks(*self._basis_arguments(exclude, require)):
            # a few rows at a time: a caller that wants the first sets (the command line shows a few
            # of a large model's millions) does not wait for a whole chunk turned into Python lists
            for start in range(0, len(chunk), _ROWS_AT_A_TIME):
                for subset in chunk[start : start + _ROWS_AT_A_TIME].tolist():
                    yield tuple(names[j] for j in subset)

    def bases(self, *, exclude: Iterable[str] = (), require: Iterable[str] = ()) -> BasisSequence:
        """Every valid repeating-variable set, in deterministic order.

        A valid set has ``rank`` variables with independent dimensions.
        Sets are ordered lexicographically by the variables' positions, and
        each set lists its variables in system order.

        Parameters
        ----------
        exclude : iterable of str
            Variables never to use as repeaters (e.g. time).
        require : iterable of str
            Variables every set must contain.

        Returns
        -------
        BasisSequence
            An immutable sequence of tuples of names that compares equal to
            the list of them, held as a compact array of variable positions
            (its ``indices``; the class is ``pitheorem.basis_sequence.BasisSequence``).

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"l": "L", "t": "T", "v": "L/T", "x": "L"})
        >>> s.bases()
        [('l', 't'), ('l', 'v'), ('t', 'v'), ('t', 'x'), ('v', 'x')]
        >>> s.bases(exclude=("t",))
        [('l', 'v'), ('v', 'x')]
        """
        from .bases import independent_chunks
        from .basis_sequence import BasisSequence

        return BasisSequence(self._variables, independent_chunks(*self._basis_arguments(exclude, require)), self.rank)

    def count_bases(self, *, exclude: Iterable[str] = (), require: Iterable[str] = ()) -> int:
        """Number of valid repeating sets, without building them.

        Parameters
        ----------
        exclude, require : iterable of str
            As for :meth:`bases`.

        Returns
        -------
        int

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.System({"l": "L", "t": "T", "v": "L/T", "x": "L"}).count_bases()
        5
        >>> pt.System({"l": "L", "t": "T", "v": "L/T", "x": "L"}).count_bases(exclude=("t",), require=("v",))
        2
        """
        from .bases import count_independent_subsets

        return count_independent_subsets(*self._basis_arguments(exclude, require))

    # -- display ----------------------------------------------------------
    def __repr__(self) -> str:
        body = ", ".join(f"{n!r}: {str(d)!r}" for n, d in zip(self._variables, self._dimensions, strict=True))
        own = "" if self._repeating is None else f", repeating={self._repeating!r}"
        return f"System({{{body}}}{own})"

    def __eq__(self, other) -> bool:
        return (
            isinstance(other, System)
            and self.dimensions == other.dimensions
            and self._variables == other._variables
            and self._repeating == other._repeating
        )

    def __hash__(self) -> int:
        return hash((self._variables, self._dimensions))

    def __len__(self) -> int:
        return len(self._variables)


def _rebuild_system(pairs, allowed, repeating=None) -> System:
    """Unpickle a System: build it again from its variables, dimensions and own repeaters."""
    return System(pairs, base_dimensions=allowed, repeating=repeating)


def unit_registry():
    """pint's unit registry, one per process (building it takes a noticeable moment).

    Examples
    --------
    >>> from pitheorem.system import unit_registry
    >>> str(unit_registry()("cm").to_base_units())
    '0.01 meter'
    """
    global _REGISTRY
    if _REGISTRY is None:
        import pint

        _REGISTRY = pint.UnitRegistry()
    return _REGISTRY


_REGISTRY = None
