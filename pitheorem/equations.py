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
from .dimensions import Dimension
from .errors import InvalidRequestError, UnknownVariableError
from .linalg import nullspace, primitive_integer_vector, rank, row_space_basis, solve
from .system import System

__all__ = ["DimensionReport", "SymmetryReport", "check_dimensions", "scaling_symmetries"]

# functions whose value has the dimension of their (single) argument
_DIMENSION_PRESERVING = (sympy.Abs, sympy.re, sympy.im, sympy.conjugate, sympy.floor, sympy.ceiling)


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


def _most_common(dims: list[Dimension]) -> Dimension:
    counts: dict[Dimension, int] = {}
    for d in dims:
        counts[d] = counts.get(d, 0) + 1
    best = max(counts.values())
    return next(d for d in dims if counts[d] == best)


@dataclass(frozen=True, slots=True)
class DimensionReport:
    """Result of :func:`check_dimensions`.

    Attributes
    ----------
    consistent : bool
    dimension : Dimension
        Dimension of the expression (of the left side, for an equation).
    offending : tuple of (sympy.Expr, Dimension, Dimension)
        Each inconsistent term with its dimension and the dimension expected.

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

    def __str__(self) -> str:
        if self.consistent:
            return f"consistent: dimension {self.dimension}"
        lines = [f"inconsistent: {len(self.offending)} offending term(s)"]
        lines += [f"  {sympy.sstr(term)} has dimension {got}, expected {want}" for term, got, want in self.offending]
        return "\n".join(lines)


class _DimensionWalker:
    def __init__(self, system: System, time: str | None):
        self.system = system
        self.time = time
        self.offending: list[tuple[sympy.Expr, Dimension, Dimension]] = []

    def lookup(self, name: str) -> Dimension:
        try:
            return self.system.dimension(name)
        except UnknownVariableError:
            raise UnknownVariableError(name, self.system.variables, "the equation") from None

    def flag(self, term, got: Dimension, want: Dimension) -> None:
        self.offending.append((term, got, want))

    def same(self, terms: Sequence[sympy.Expr]) -> Dimension:
        dims = [self.dim(t) for t in terms]
        want = _most_common(dims)
        for term, d in zip(terms, dims, strict=True):
            if d != want:
                self.flag(term, d, want)
        return want

    def dimensionless_argument(self, node) -> None:
        for arg in node.args:
            d = self.dim(arg)
            if not d.is_dimensionless:
                self.flag(arg, d, Dimension.dimensionless())

    def dim(self, node) -> Dimension:
        if node.is_Number or node in (sympy.pi, sympy.E, sympy.I):
            return Dimension.dimensionless()
        if isinstance(node, sympy.Symbol):
            return self.lookup(node.name)
        if isinstance(node, AppliedUndef):
            return self.lookup(node.func.__name__)
        if isinstance(node, sympy.Derivative):
            d = self.dim(node.expr)
            for var, count in node.variable_count:
                d = d / self.dim(var) ** int(count)
            return d
        if isinstance(node, sympy.Add):
            return self.same(node.args)
        if isinstance(node, sympy.Mul):
            d = Dimension.dimensionless()
            for arg in node.args:
                d = d * self.dim(arg)
            return d
        if isinstance(node, sympy.Pow):
            base, exp = node.args
            if exp.is_Rational:
                return self.dim(base) ** Fraction(int(exp.p), int(exp.q))
            self.dimensionless_argument(node)  # x**y needs both dimensionless
            return Dimension.dimensionless()
        if isinstance(node, _DIMENSION_PRESERVING):
            return self.dim(node.args[0])
        if isinstance(node, sympy.Min | sympy.Max):
            return self.same(node.args)
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
        Name of the time variable (must be in `system` if used).

    Returns
    -------
    DimensionReport

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
    if time is not None:
        system.index(time, "time")
    walker = _DimensionWalker(system, time)
    sides = _as_sides(equation)
    dims = [walker.dim(side) for side in sides]
    if len(sides) == 2 and sides[0] == 0:
        sides, dims = sides[::-1], dims[::-1]
    for side, d in zip(sides[1:], dims[1:], strict=True):
        if side == 0:  # zero has every dimension: Eq(x'', 0) is consistent
            continue
        if d != dims[0]:
            walker.flag(side, d, dims[0])
    return DimensionReport(not walker.offending, dims[0], tuple(walker.offending))


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
            form = self.weight(arg)
            if form:
                self.conditions.append(form)

    def weight(self, node) -> Form:
        if node.is_Number or node in (sympy.pi, sympy.E, sympy.I):
            return {}
        if isinstance(node, sympy.Symbol):
            return self.leaf(node.name)
        if isinstance(node, AppliedUndef):
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
            if exp.is_Rational:
                return _add_forms(self.weight(base), scale=Fraction(int(exp.p), int(exp.q)))
            self.invariant(node)
            return {}
        if isinstance(node, _DIMENSION_PRESERVING):
            return self.weight(node.args[0])
        if isinstance(node, sympy.Min | sympy.Max):
            return self.equal([self.weight(a) for a in node.args])
        if isinstance(node, sympy.Function):
            self.invariant(node)
            return {}
        raise InvalidRequestError(f"cannot analyse {sympy.sstr(node)!r} ({type(node).__name__}) for symmetries")


@dataclass(frozen=True, slots=True)
class SymmetryReport:
    """Result of :func:`scaling_symmetries`: an exact subspace of exponent vectors.

    Attributes
    ----------
    variables : tuple of str
        The symbols of the equations, in system order.
    basis : tuple of dict
        A basis of the symmetry subspace (exponent of ``s`` per variable).
    unit_changes : tuple of dict
        A basis of the changes of units, restricted to `variables`.
    beyond_units : tuple of dict
        Basis vectors of the symmetry subspace that no change of units gives
        (a complement of `unit_changes` in it).
    contains_units : bool
        True when every change of units is a symmetry (always, for
        dimensionally consistent equations).

    Examples
    --------
    >>> import sympy, pitheorem as pt
    >>> s = pt.System({"m": "M", "k": "M T^-2", "x": "L", "t": "T"})
    >>> t, m, k = sympy.symbols("t m k"); x = sympy.Function("x")(t)
    >>> sym = pt.scaling_symmetries([sympy.Eq(m * x.diff(t, 2), -k * x)], s)
    >>> sym.dimension, len(sym.unit_changes), sym.beyond_units
    (3, 3, ())
    """

    variables: tuple[str, ...]
    basis: tuple[dict[str, Fraction], ...]
    unit_changes: tuple[dict[str, Fraction], ...]
    beyond_units: tuple[dict[str, Fraction], ...]
    contains_units: bool

    @property
    def dimension(self) -> int:
        """Dimension of the symmetry subspace."""
        return len(self.basis)

    def contains(self, exponents: dict[str, object]) -> bool:
        """True when the exponent vector is a symmetry of the equations.

        Examples
        --------
        >>> import sympy, pitheorem as pt
        >>> s = pt.System({"x": "L", "t": "T"})
        >>> t = sympy.Symbol("t"); x = sympy.Function("x")(t)
        >>> pt.scaling_symmetries([sympy.Eq(x.diff(t, 2), 0)], s).contains({"x": 1})
        True
        """
        vec = [Fraction(exponents.get(v, 0)) for v in self.variables]
        rows = [[b[v] for v in self.variables] for b in self.basis]
        return rank([*rows, vec]) == rank(rows) if rows else not any(vec)

    def __str__(self) -> str:
        def fmt(vec):
            return ", ".join(f"{n}: {p}" for n, p in vec.items() if p) or "0"

        lines = [f"symmetry subspace of dimension {self.dimension} over {', '.join(self.variables)}",
                 f"changes of units: dimension {len(self.unit_changes)}"
                 + ("" if self.contains_units else " (NOT all symmetries: the equations are inconsistent)")]
        if self.beyond_units:
            lines.append("symmetries beyond changes of units:")
            lines += [f"  {fmt(v)}" for v in self.beyond_units]
        else:
            lines.append("no symmetries beyond changes of units")
        return "\n".join(lines)


def scaling_symmetries(equations, system: System, *, time: str | None = "t") -> SymmetryReport:
    """Every diagonal scaling of symbols that maps the equations to themselves.

    Parameters
    ----------
    equations : sympy.Eq or sympy.Expr, or a sequence of them
        Each equation may be multiplied by its own power of ``s``.
    system : System
        Must contain every symbol and function name used.
    time : str or None
        Name of the time variable, which is always included.

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
    equations = list(equations)
    if not equations:
        raise InvalidRequestError("scaling_symmetries needs at least one equation")
    walker = _WeightWalker(system.variables)
    if time is not None:
        walker.leaf(system.variables[system.index(time, "time")])
    for eq in equations:
        sides = _as_sides(eq)
        expr = sympy.expand(sides[0] - sides[1] if len(sides) == 2 else sides[0])
        terms = list(expr.args) if isinstance(expr, sympy.Add) else [expr]
        walker.equal([walker.weight(term) for term in terms])
    names = tuple(v for v in system.variables if v in walker.used)
    rows = [[c.get(n, Fraction(0)) for n in names] for c in walker.conditions]
    basis = nullspace(rows, len(names)) if rows else nullspace([], len(names))
    bases = system.base_dimensions
    units = [[system.dimension(n).exponent(b) for n in names] for b in bases]
    unit_rows = [u for u in units if any(u)]
    unit_basis = [row for row in _independent(unit_rows)]
    contains = all(all(sum(c.get(n, 0) * u[i] for i, n in enumerate(names)) == 0 for c in walker.conditions)
                   for u in unit_basis)
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
            cand = [x - sum((ui * row[j] for ui, row in zip(u, rows, strict=True)), Fraction(0))
                    for j, x in enumerate(vec)]
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
