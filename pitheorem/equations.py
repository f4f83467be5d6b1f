"""Equations: dimensional consistency, and scaling symmetries beyond changes of units.

:func:`check_dimensions` walks a sympy expression or equation, giving each
symbol the dimension it has in a :class:`System` (derivatives divide by the
time variable's dimension), and reports every term whose dimension differs
from what its sum or equation needs, and every argument of a
transcendental function that is not dimensionless.

:func:`scaling_symmetries` finds every diagonal scaling ``x_i -> s^(a_i)
x_i`` of the symbols that maps each equation to a multiple of itself.
Expanding an equation into terms, that happens exactly when all its terms
pick up the same power of ``s`` and every function argument is invariant:
linear conditions on ``a``, so the answer is an exact subspace.  Changes
of units always lie in it when the equations are consistent; anything
else is a symmetry of the particular equations (an amplitude scaling of a
linear equation, independent horizontal and vertical lengths, ...).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction

import sympy
from sympy.core.function import AppliedUndef

from .bases import independent_subsets
from .dimensions import Dimension, product_of_powers
from .errors import InvalidRequestError, LimitError, UnknownVariableError
from .exact import read_exponent, read_rational
from .formatting import TableDisplay
from .immutable import immutable
from .linalg import nullspace, primitive_integer_vector, rank, row_space_basis, solve
from .system import System

__all__ = ["DimensionReport", "SymmetryReport", "check_dimensions", "scaling_symmetries"]

# How each function treats dimensions (anything else -- sin, exp, log, ... -- needs
# dimensionless arguments and gives a dimensionless value):
# the value has the dimension of the (single) argument, which may be any
_DIMENSION_PRESERVING = (sympy.Abs, sympy.re, sympy.im, sympy.conjugate)
# arguments of one common dimension, any; the value has that dimension
_SAME_DIMENSION = (sympy.Min, sympy.Max, sympy.Mod)
# arguments of one common dimension, any; the value is dimensionless (an angle)
_RATIO_OF_ARGUMENTS = (sympy.atan2,)
# the first argument may have any dimension (only its sign matters, which no change of
# units alters); further arguments (Heaviside's value at 0) are dimensionless
_SIGN_OF_ARGUMENT = (sympy.sign, sympy.Heaviside)
# floor and ceiling are NOT homogeneous (floor(2.5 m) = 2 m but floor(250 cm) = 250 cm),
# so their argument must be dimensionless, as for sin: write floor(x/dx)*dx
#: default name of the time variable; unlike another name, it may be absent from the system
_DEFAULT_TIME = "t"


def _exponent(exp) -> Fraction | None:
    """A numeric exponent as an exact Fraction (a float by the float rule of pitheorem.exact), else None."""
    if exp.is_Rational or exp.is_Float:
        return read_rational(exp, "an exponent in the equation")
    return None


def _term_product(node, factors) -> Dimension:
    """:func:`~pitheorem.dimensions.product_of_powers` of a term's factors; beyond the limits, the term is named."""
    try:
        return product_of_powers(factors)
    except LimitError as err:
        text = sympy.sstr(node)
        where = f" in the dimension of {text if len(text) <= 40 else text[:40] + '...'}"
        raise LimitError(err.value, err.what + where, err.limit, err.hint) from None


def _terms(side) -> list[sympy.Expr]:
    return list(side.args) if isinstance(side, sympy.Add) else [side]


def _time_in(system: System, time: str | None) -> str | None:
    """The time variable's name, or None when there is none to use."""
    if time is None or (time == _DEFAULT_TIME and time not in system.variables):
        return None
    return system.variables[system.index(time, "time")]


def _as_sides(equation) -> list[sympy.Expr]:
    if isinstance(equation, sympy.Equality):
        return [equation.lhs, equation.rhs]
    if isinstance(equation, sympy.Expr):
        return [equation]
    if isinstance(equation, str):
        raise InvalidRequestError(
            f"equations must be sympy expressions or sympy.Eq, not strings ({equation!r}); build them with sympy.symbols"
        )
    raise InvalidRequestError(f"expected a sympy expression or sympy.Eq, got {type(equation).__name__}")


def _name_of(node) -> str:
    return node.func.__name__ if isinstance(node, AppliedUndef) else node.name


def _vote(dims: list[Dimension]) -> list[Dimension]:
    """The dimensions shared by the most terms, in order of first appearance (several on a tie)."""
    counts: dict[Dimension, int] = {}
    for d in dims:
        counts[d] = counts.get(d, 0) + 1
    best = max(counts.values())
    return [d for d in counts if counts[d] == best]


@immutable
@dataclass(frozen=True, slots=True)
class DimensionReport(TableDisplay):
    """Result of :func:`check_dimensions`.

    Attributes
    ----------
    consistent : bool
    dimension : Dimension
        Dimension of the expression (of the left side, for an equation).
    offending : tuple of (sympy.Expr, Dimension, Dimension)
        Each inconsistent term with its dimension and the dimension expected:
        the dimension most terms of its sum (or equation) share.  On a tie
        every term of the tied dimensions is listed, each expected to have
        another tied dimension, and `ties` says so.
    ties : tuple of str
        One sentence per sum whose terms tie, naming the tied dimensions.

    Examples
    --------
    >>> import sympy, pitheorem as pt
    >>> s = pt.System({"x": "L", "y": "L", "t": "T"})
    >>> x, y, t = sympy.symbols("x y t")
    >>> print(pt.check_dimensions(x + y + t, s))
    inconsistent: 1 offending term(s)
      t has dimension T, expected L
    """

    consistent: bool
    dimension: Dimension
    offending: tuple[tuple[sympy.Expr, Dimension, Dimension], ...]
    ties: tuple[str, ...] = ()


class _DimensionWalker:
    def __init__(self, system: System):
        self.system = system
        self.offending: list[tuple[sympy.Expr, Dimension, Dimension]] = []
        self.ties: list[str] = []

    def lookup(self, name: str) -> Dimension:
        try:
            return self.system.dimension(name)
        except UnknownVariableError:
            raise UnknownVariableError(name, self.system.variables, "the equation") from None

    def flag(self, term, got: Dimension, want: Dimension) -> None:
        self.offending.append((term, got, want))

    def same(self, terms: Sequence[sympy.Expr]) -> Dimension:
        """Terms that must share one dimension: blame those outvoted, or every tied one."""
        return self.agree(terms, [self.dim(t) for t in terms])

    def agree(self, terms: Sequence[sympy.Expr], dims: list[Dimension]) -> Dimension:
        winners = _vote(dims)
        if len(winners) > 1:
            each = dims.count(winners[0])
            self.ties.append(
                f"in {' + '.join(sympy.sstr(t) for t in terms)}, {' and '.join(map(str, winners))} "
                f"have {each} term(s) each: no majority says which is wrong, so all are listed"
            )
        for term, d in zip(terms, dims, strict=True):
            if d not in winners:
                self.flag(term, d, winners[0])
            elif len(winners) > 1:
                self.flag(term, d, next(w for w in winners if w != d))
        return winners[0]

    def dimensionless_argument(self, node, args=None) -> None:
        for arg in node.args if args is None else args:
            d = self.dim(arg)
            if not d.is_dimensionless:
                self.flag(arg, d, Dimension.dimensionless())

    def dim(self, node) -> Dimension:
        if node.is_Number or node in (sympy.pi, sympy.E, sympy.I):
            return Dimension.dimensionless()
        if isinstance(node, sympy.Symbol):
            return self.lookup(node.name)
        if isinstance(node, AppliedUndef):
            for arg in node.args:  # theta(t + l) is as wrong as t + l
                self.dim(arg)
            return self.lookup(node.func.__name__)
        if isinstance(node, sympy.Derivative):
            factors = [(self.dim(node.expr), 1)] + [(self.dim(var), -int(c)) for var, c in node.variable_count]
            return _term_product(node, factors)
        if isinstance(node, sympy.Add):
            return self.same(node.args)
        if isinstance(node, sympy.Mul):
            return _term_product(node, [(self.dim(arg), 1) for arg in node.args])
        if isinstance(node, sympy.Pow):
            base, exp = node.args
            power = _exponent(exp)
            if power is not None:
                return _term_product(node, [(self.dim(base), power)])
            self.dimensionless_argument(node)  # x**y needs both dimensionless
            return Dimension.dimensionless()
        if isinstance(node, _DIMENSION_PRESERVING):
            return self.dim(node.args[0])
        if isinstance(node, _SAME_DIMENSION):
            return self.same(node.args)
        if isinstance(node, _RATIO_OF_ARGUMENTS):
            self.same(node.args)
            return Dimension.dimensionless()
        if isinstance(node, _SIGN_OF_ARGUMENT):
            self.dim(node.args[0])
            self.dimensionless_argument(node, node.args[1:])
            return Dimension.dimensionless()
        if isinstance(node, sympy.DiracDelta):  # integrates to 1 over its argument
            self.dimensionless_argument(node, node.args[1:])
            return Dimension.dimensionless() / self.dim(node.args[0])
        if isinstance(node, sympy.Function):
            self.dimensionless_argument(node)  # sin, cos, exp, log, ...
            return Dimension.dimensionless()
        raise InvalidRequestError(f"cannot find the dimension of {sympy.sstr(node)!r} ({type(node).__name__})")


def check_dimensions(equation, system: System, *, time: str | None = "t") -> DimensionReport:
    """Check that an expression or equation is dimensionally consistent.

    Parameters
    ----------
    equation : sympy.Expr or sympy.Eq
        Symbols and undefined functions such as ``theta(t)`` take their
        dimension from `system`; derivatives divide by the dimension of the
        variable differentiated by.
    system : System
        Dimensions of every symbol and function name in the equation.
    time : str or None
        Name of the time variable; it must be in `system`, except the
        default ``"t"``, which may be absent (then nothing is time).

    Returns
    -------
    DimensionReport

    Notes
    -----
    Functions: ``Abs`` keeps its argument's dimension; ``Min``, ``Max`` and
    ``Mod`` need arguments of one dimension and keep it; ``atan2(y, x)``
    needs ``y`` and ``x`` of one dimension and is dimensionless; ``sign``
    and ``Heaviside`` take an argument of any dimension and are
    dimensionless; ``DiracDelta(x)`` has the inverse dimension of ``x``;
    ``floor``, ``ceiling`` and every other function (``sin``, ``exp``,
    ``log`` ...) need dimensionless arguments.  Powers may be integers,
    rationals or floats (``x**0.5``, read as the decimal written); a
    symbolic exponent needs a dimensionless base and exponent.  Arguments
    of undefined functions (``theta(t)``) are checked too.

    Blame: the terms of a sum, and of the two sides of an equation taken
    together, vote; terms whose dimension differs from the majority are
    offending.  On a tie all tied terms are listed and the report says so.

    Examples
    --------
    The paper's Eq. 1, with the restoring spring sign:

    >>> import sympy, pitheorem as pt
    >>> rodx = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2",
    ...                   "c_theta": "M L^2 T^-1", "theta_r": "1", "t": "T", "theta": "1"})
    >>> t, m, l, g, k, c, th_r = sympy.symbols("t m l g k_theta c_theta theta_r")
    >>> th = sympy.Function("theta")(t)
    >>> eq = sympy.Eq(th.diff(t, 2), 3 / (m * l**2) * (m * g * l / 2 * sympy.cos(th)
    ...               - c * th.diff(t) - k * (th - th_r)))
    >>> print(pt.check_dimensions(eq, rodx))
    consistent: dimension T^-2
    """
    if not isinstance(system, System):
        raise InvalidRequestError(f"check_dimensions needs a System, got {type(system).__name__}")
    _time_in(system, time)  # validates the name
    walker = _DimensionWalker(system)
    sides = _as_sides(equation)
    # both sides' terms vote together; zero has every dimension (Eq(x'', 0) is consistent)
    terms = [term for side in sides for term in _terms(side) if term != 0]
    if not terms:
        return DimensionReport(True, Dimension.dimensionless(), ())
    dimension = walker.same(terms)
    return DimensionReport(not walker.offending, dimension, tuple(walker.offending), tuple(walker.ties))


# -- symmetries ---------------------------------------------------------------
Form = dict[str, Fraction]


def _add_forms(*forms: Form, scale: Fraction = Fraction(1)) -> Form:
    out: Form = {}
    for f in forms:
        for k, v in f.items():
            out[k] = out.get(k, Fraction(0)) + v * scale
    return {k: v for k, v in out.items() if v}


def _negate(form: Form) -> Form:
    return {k: -v for k, v in form.items()}


class _WeightWalker:
    """Collects linear conditions on exponents for an expression to be homogeneous."""

    def __init__(self, known: Iterable[str]):
        self.known = set(known)
        self.used: set[str] = set()
        self.conditions: list[Form] = []

    def leaf(self, name: str) -> Form:
        if name not in self.known:
            raise UnknownVariableError(name, tuple(sorted(self.known)), "the equations")
        self.used.add(name)
        return {name: Fraction(1)}

    def equal(self, forms: list[Form]) -> Form:
        for f in forms[1:]:
            diff = _add_forms(f, _negate(forms[0]))
            if diff:
                self.conditions.append(diff)
        return forms[0]

    def invariant(self, node) -> None:
        for arg in node.args:
            self.invariant_form(arg)

    def invariant_form(self, arg) -> None:
        form = self.weight(arg)
        if form:
            self.conditions.append(form)

    def weight(self, node) -> Form:
        if node.is_Number or node in (sympy.pi, sympy.E, sympy.I):
            return {}
        if isinstance(node, sympy.Symbol):
            return self.leaf(node.name)
        if isinstance(node, AppliedUndef):
            for arg in node.args:  # sums inside the arguments must be homogeneous too
                self.weight(arg)
            return self.leaf(node.func.__name__)
        if isinstance(node, sympy.Derivative):
            form = self.weight(node.expr)
            for var, count in node.variable_count:
                # d/dt divides by t: the derivative's weight loses count * weight(t)
                form = _add_forms(form, _add_forms(_negate(self.weight(var)), scale=Fraction(int(count))))
            return form
        if isinstance(node, sympy.Add):
            return self.equal([self.weight(a) for a in node.args])
        if isinstance(node, sympy.Mul):
            return _add_forms(*(self.weight(a) for a in node.args))
        if isinstance(node, sympy.Pow):
            base, exp = node.args
            power = _exponent(exp)
            if power is not None:
                return _add_forms(self.weight(base), scale=power)
            self.invariant(node)
            return {}
        if isinstance(node, _DIMENSION_PRESERVING):
            return self.weight(node.args[0])
        if isinstance(node, _SAME_DIMENSION):
            return self.equal([self.weight(a) for a in node.args])
        if isinstance(node, _RATIO_OF_ARGUMENTS):
            self.equal([self.weight(a) for a in node.args])
            return {}
        if isinstance(node, _SIGN_OF_ARGUMENT):
            self.weight(node.args[0])
            for arg in node.args[1:]:
                self.invariant_form(arg)
            return {}
        if isinstance(node, sympy.DiracDelta):
            for arg in node.args[1:]:
                self.invariant_form(arg)
            return _negate(self.weight(node.args[0]))
        if isinstance(node, sympy.Function):
            self.invariant(node)
            return {}
        raise InvalidRequestError(f"cannot analyse {sympy.sstr(node)!r} ({type(node).__name__}) for symmetries")


@immutable
@dataclass(frozen=True, slots=True)
class SymmetryReport(TableDisplay):
    """Result of :func:`scaling_symmetries`: an exact subspace of exponent vectors.

    Attributes
    ----------
    variables : tuple of str
        The symbols of the equations, in system order.
    basis : tuple of dict
        A basis of the symmetry subspace (exponent of ``s`` per variable).
    within_units : tuple of dict
        A basis of the symmetries that changes of units give: the exponent
        of ``s`` per variable of each, restricted to `variables`.
    beyond_units : tuple of dict
        Basis vectors of the symmetry subspace that no change of units gives
        (a complement of `within_units` in it).
    contains_units : bool
        True when every change of units is a symmetry (always, for
        dimensionally consistent equations).

    Examples
    --------
    >>> import sympy, pitheorem as pt
    >>> s = pt.System({"m": "M", "k": "M T^-2", "x": "L", "t": "T"})
    >>> t, m, k = sympy.symbols("t m k"); x = sympy.Function("x")(t)
    >>> sym = pt.scaling_symmetries([sympy.Eq(m * x.diff(t, 2), -k * x)], s)
    >>> sym.n_symmetries, len(sym.within_units), sym.beyond_units
    (3, 3, ())
    """

    variables: tuple[str, ...]
    basis: tuple[dict[str, Fraction], ...]
    within_units: tuple[dict[str, Fraction], ...]
    beyond_units: tuple[dict[str, Fraction], ...]
    contains_units: bool

    @property
    def n_symmetries(self) -> int:
        """Number of independent symmetries: the dimension of the subspace.

        Examples
        --------
        >>> import sympy, pitheorem as pt
        >>> s = pt.System({"x": "L", "t": "T"})
        >>> t = sympy.Symbol("t"); x = sympy.Function("x")(t)
        >>> pt.scaling_symmetries([sympy.Eq(x.diff(t, 2), 0)], s).n_symmetries
        2
        """
        return len(self.basis)

    def contains(self, exponents: dict[str, object]) -> bool:
        """True when the exponent vector is a symmetry of the equations.

        Parameters
        ----------
        exponents : mapping of str to number
            Exponent of ``s`` per variable; variables left out have 0.

        Returns
        -------
        bool

        Examples
        --------
        >>> import sympy, pitheorem as pt
        >>> s = pt.System({"x": "L", "t": "T"})
        >>> t = sympy.Symbol("t"); x = sympy.Function("x")(t)
        >>> pt.scaling_symmetries([sympy.Eq(x.diff(t, 2), 0)], s).contains({"x": 1})
        True
        """
        for n in exponents:
            if n not in self.variables:
                raise UnknownVariableError(n, self.variables, "the exponents (the equations' symbols)")
        vec = [read_exponent(exponents.get(v, 0), f"exponent of {v!r}") for v in self.variables]
        rows = [[b[v] for v in self.variables] for b in self.basis]
        return rank([*rows, vec]) == rank(rows) if rows else not any(vec)


def scaling_symmetries(equations, system: System, *, time: str | None = "t") -> SymmetryReport:
    """Every diagonal scaling of symbols that maps the equations to themselves.

    Parameters
    ----------
    equations : sympy.Eq or sympy.Expr, or a sequence of them
        Each equation may be multiplied by its own power of ``s``.
    system : System
        Must contain every symbol and function name used.
    time : str or None
        Name of the time variable, which is always included; the default
        ``"t"`` may be absent from `system`.

    Returns
    -------
    SymmetryReport

    Examples
    --------
    The projectile: horizontal and vertical lengths scale independently.

    >>> import sympy, pitheorem as pt
    >>> s = pt.System({"g": "L T^-2", "x": "L", "y": "L", "t": "T"})
    >>> t, g = sympy.symbols("t g")
    >>> x, y = sympy.Function("x")(t), sympy.Function("y")(t)
    >>> sym = pt.scaling_symmetries([sympy.Eq(x.diff(t, 2), 0), sympy.Eq(y.diff(t, 2), -g)], s)
    >>> sym.beyond_units
    ({'g': Fraction(0, 1), 'x': Fraction(1, 1), 'y': Fraction(0, 1), 't': Fraction(0, 1)},)
    """
    if not isinstance(system, System):
        raise InvalidRequestError(f"scaling_symmetries needs a System, got {type(system).__name__}")
    if isinstance(equations, sympy.Basic):
        equations = [equations]
    if isinstance(equations, str) or not isinstance(equations, Iterable):
        raise InvalidRequestError(
            f"scaling_symmetries needs sympy equations (a list of sympy.Eq or expressions), got {equations!r}",
            culprit=equations,
        )
    equations = list(equations)
    if not equations:
        raise InvalidRequestError("scaling_symmetries needs at least one equation")
    walker = _WeightWalker(system.variables)
    time = _time_in(system, time)
    if time is not None:
        walker.leaf(time)
    for eq in equations:
        sides = _as_sides(eq)
        expr = sympy.expand(sides[0] - sides[1] if len(sides) == 2 else sides[0])
        terms = list(expr.args) if isinstance(expr, sympy.Add) else [expr]
        walker.equal([walker.weight(term) for term in terms])
    names = tuple(v for v in system.variables if v in walker.used)
    rows = [[c.get(n, Fraction(0)) for n in names] for c in walker.conditions]
    basis = nullspace(rows, len(names)) if rows else nullspace([], len(names))
    units = system.rows(names)
    unit_rows = [u for u in units if any(u)]
    unit_basis = [row for row in _independent(unit_rows)]
    contains = all(
        all(sum(c.get(n, 0) * u[i] for i, n in enumerate(names)) == 0 for c in walker.conditions) for u in unit_basis
    )
    beyond = []
    current = list(unit_basis)
    for vec in basis:
        if rank([*current, vec]) > rank(current) if current else any(vec):
            beyond.append(vec)
            current.append(vec)
    if contains and beyond:
        beyond = _canonical_complement(beyond, unit_basis)

    def as_dict(vec):
        return {n: Fraction(x) for n, x in zip(names, vec, strict=True)}

    return SymmetryReport(
        names, tuple(map(as_dict, basis)), tuple(map(as_dict, unit_basis)), tuple(map(as_dict, beyond)), contains
    )


def _canonical_complement(vectors: list[list[Fraction]], units: list[list[Fraction]]) -> list[list[Fraction]]:
    """The same complement of the unit changes, each vector in its simplest form.

    Adding a change of units (itself a symmetry, when the equations are
    consistent) to a vector beyond units gives another one.  Each vector is
    replaced by the one with the fewest nonzero exponents that differs from
    it by a change of units, as coprime integers.  A fewest-support
    representative vanishes on some independent set of unit columns (else a
    unit change vanishing on its zeros could clear one more entry), so
    trying each such set, in lexicographic order, finds it.  For the
    gravity-free rod this turns an arbitrary complement into the plain
    amplitude scaling of theta, theta_r and omega.
    """
    out = []
    rows = row_space_basis(units) if units else []
    supports = list(independent_subsets(rows, range(len(vectors[0])), (), len(rows))) if rows else [()]
    for vec in vectors:
        best = list(vec)
        for cols in supports:
            # the unit change u^T rows that agrees with vec on cols
            u = solve([[row[c] for row in rows] for c in cols], [vec[c] for c in cols])
            cand = [
                x - sum((ui * row[j] for ui, row in zip(u, rows, strict=True)), Fraction(0)) for j, x in enumerate(vec)
            ]
            if sum(map(bool, cand)) < sum(map(bool, best)):
                best = cand
        out.append([Fraction(x) for x in primitive_integer_vector(best)])
    return out


def _independent(rows: list[list[Fraction]]) -> list[list[Fraction]]:
    kept: list[list[Fraction]] = []
    for row in rows:
        if rank([*kept, row]) > len(kept):
            kept.append(row)
    return kept
