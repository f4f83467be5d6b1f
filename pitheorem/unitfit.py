"""Choosing units for an engine: :func:`fit_units` and :class:`UnitFit`.

Engines work best when the numbers they see lie in some range (Bullet's
documentation suggests moving objects between 0.05 and 10 units).  A change
of base units moves every parameter at once, so the question "which units
put every parameter in its range?" is a linear program in the logarithms
of the unit factors.

Convention (the one of :meth:`pitheorem.Scaling.from_unit_change`): the
*factor* ``f_b`` of base dimension ``b`` multiplies every reading of that
dimension, so a variable of dimension ``prod_b b^(d_b)`` reads
``x * prod_b f_b^(d_b)`` in the new units.  ``f_L = 100`` means lengths read
100 times larger: the new length unit is 1/100 of the old (metres to
centimetres).  Written as a scaling ``x -> s^a x``, the factors are
``f_b = s^(u_b)`` with the unit change ``u`` of
:meth:`~pitheorem.Scaling.from_unit_change`.

The fit, in decades (base-10 logarithms), with ``y_b = log10 f_b``:

1. minimise the worst violation ``t``: the largest distance, in decades, of a
   value outside its range (0 when every value is in range);
2. among those, minimise the sum over ranged variables of the distance of
   the value from the centre of its range (geometric mean of the bounds),
   each divided by the half-width of its range: values move to the middle;
3. among those, minimise ``sum_b |y_b|``: the smallest unit change, so a
   base dimension no range depends on keeps its unit.

Each stage is one :func:`scipy.optimize.linprog` (HiGHS) call, with the
variables held fixed as equality constraints; with ``nice=B`` the factors
are restricted to integer powers of ``B`` and each stage is a
:func:`scipy.optimize.milp`, after which the ranges are checked again in
exact arithmetic.  When no unit change puts every value in range, a
deletion filter over the feasibility of the bounds returns a minimal set
of bounds that conflict: dropping any one of them makes the rest feasible.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from fractions import Fraction
from types import MappingProxyType

import numpy as np
from scipy.optimize import Bounds, LinearConstraint, linprog, milp

from .dimensions import Dimension
from .errors import DimensionSyntaxError, DuplicateVariableError, InvalidRequestError, LimitError
from .exact import MAX_DENOMINATOR, MAX_EXPONENT, read_number, read_value, short_text
from .formatting import MathDisplay, TableDisplay
from .immutable import immutable
from .linalg import nullspace
from .scaling import Scaling, float_power
from .system import System

__all__ = ["RangeBound", "UnitFit", "fit_units"]

#: a value counts as in range when it is within this many decades of it (continuous fit)
TOL = 1e-9
#: factors, and scaled values, stay within 10^(+-LIMIT): ordinary floats
LIMIT = 300.0
_HIGHS = {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}


@immutable
@dataclass(frozen=True, slots=True)
class RangeBound(MathDisplay):
    """One side of a variable's range: ``low <= x`` or ``x <= high``.

    Parameters
    ----------
    name : str
        The variable.
    side : {"low", "high"}
    bound : Fraction
        The bound itself.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem import RangeBound
    >>> print(RangeBound("l", "low", Fraction(1, 20)))
    l >= 1/20
    """

    name: str
    side: str
    bound: Fraction


# -- reading the request ------------------------------------------------------------------


_HUGE = Fraction(10**300)


def _in_float_range(value: Fraction, what: str) -> Fraction:
    """`value` itself; the fit runs in floating point (logarithms, a linear program), so it must stay well inside."""
    if value and not 1 / _HUGE <= abs(value) <= _HUGE:
        raise LimitError(short_text(value), what, "fit_units needs magnitudes between 1e-300 and 1e300")
    return value


def _read_range(spec, what: str) -> tuple[Fraction, Fraction]:
    try:
        lo, hi = spec
    except (TypeError, ValueError):
        raise InvalidRequestError(f"{what} must be a pair (low, high), got {spec!r}") from None
    lo, hi = (
        _in_float_range(
            read_number(x, f"the {side} bound of {what}", irrational_ok=True), f"the {side} bound of {what}"
        )
        for x, side in ((lo, "low"), (hi, "high"))
    )
    if lo <= 0 or hi <= 0:
        raise InvalidRequestError(f"{what} is ({lo}, {hi}): both bounds must be positive (a range of magnitudes)")
    if lo >= hi:
        raise InvalidRequestError(f"{what} is ({lo}, {hi}): the low bound must be below the high bound")
    return lo, hi


def _resolve_ranges(system: System, values, ranges, dimension_ranges):
    """Per-variable ranges, in system order: per-variable entries override per-dimension ones."""
    chosen: dict[str, tuple[Fraction, Fraction] | None] = {}
    for key, spec in (dimension_ranges or {}).items():
        try:
            dim = key if isinstance(key, Dimension) else Dimension.parse(str(key))
        except DimensionSyntaxError as err:
            raise InvalidRequestError(
                f"dimension_ranges key {key!r} is not a dimension formula: {err.reason}"
            ) from None
        rng = _read_range(spec, f"the range of dimension {dim}")
        matched = [n for n in system.variables if system.dimension(n) == dim]
        if not matched:
            raise InvalidRequestError(
                f"dimension_ranges names {dim}, but no variable has that dimension; the system's dimensions are "
                + ", ".join(sorted({str(d) for d in system.dimensions.values()}))
            )
        for n in matched:
            chosen[n] = rng
    for name, spec in (ranges or {}).items():
        system.index(name, "ranges")
        chosen[name] = None if spec is None else _read_range(spec, f"the range of {name!r}")
    out = []
    for n in system.variables:
        rng = chosen.get(n)
        if rng is None:
            continue
        if n not in values:
            raise InvalidRequestError(f"variable {n!r} has a range but no value: give its value in values")
        if values[n] <= 0:
            raise InvalidRequestError(
                f"variable {n!r} has the value {values[n]}, but a range needs a positive value (use its magnitude)"
            )
        out.append((n, *rng))
    return tuple(out)


# -- the linear programs ------------------------------------------------------------------


class _Problem:
    """Rows ``w . v <= r`` (one per bound) over decision variables ``v``.

    ``v`` are free coordinates of the unit change (decades, or integer powers
    of `nice`); ``y = P v`` gives the decades of every base dimension.
    """

    def __init__(self, system, values, ranges, fixed, fixed_units, nice, centre=True):
        self.system, self.centre_values = system, centre
        self.values = values
        bases = system.base_dimensions
        self.bases = bases
        eq_rows = [list(system.column(n)) for n in fixed]
        eq_rows += [[Fraction(int(b == c)) for b in bases] for c in fixed_units]
        self.nice = nice
        if nice is None:
            # parametrise the unit changes that keep the fixed variables: y = N z, N exact
            basis = nullspace(eq_rows, len(bases)) if eq_rows else nullspace([], len(bases))
            self.P = np.array([[float(v[i]) for v in basis] for i in range(len(bases))]).reshape(len(bases), len(basis))
            self.basis = basis
            self.A_eq = None
        else:
            # integer powers of nice; fixed variables as equalities on them
            self.P = np.eye(len(bases)) * math.log10(nice)
            self.basis = None
            self.A_eq = np.array([[float(x) for x in row] for row in eq_rows]) if eq_rows else np.zeros((0, len(bases)))
        self.n_v = self.P.shape[1]
        # integer variables get explicit bounds too, so that the branch and bound of HiGHS
        # never chases an unbounded direction
        self.vmax = np.inf if nice is None else math.floor(LIMIT / math.log10(nice))
        self.ranges = ranges
        self.bounds: list[RangeBound] = []
        w_rows, rhs, centre, half = [], [], [], []
        for name, lo, hi in ranges:
            d = np.array([float(x) for x in system.column(name)])
            w = d @ self.P if len(bases) else np.zeros(self.n_v)
            z0 = _log10(values[name])
            a, b = _log10(lo), _log10(hi)
            self.bounds.append(RangeBound(name, "low", lo))
            w_rows.append(-w)
            rhs.append(z0 - a)
            self.bounds.append(RangeBound(name, "high", hi))
            w_rows.append(w)
            rhs.append(b - z0)
            centre.append((a + b) / 2 - z0)
            half.append((b - a) / 2)
        self.W = np.array(w_rows).reshape(len(w_rows), self.n_v)
        self.r = np.array(rhs)
        # hard limits, so that every number stays a float: each base factor, each variable's
        # factor and each scaled value within 10^(+-LIMIT)
        h_rows, h_rhs = [], []
        for i in range(len(bases)):
            h_rows += [self.P[i], -self.P[i]]
            h_rhs += [LIMIT, LIMIT]
        for name in system.variables:
            d = np.array([float(x) for x in system.column(name)])
            w = d @ self.P if len(bases) else np.zeros(self.n_v)
            h_rows += [w, -w]
            h_rhs += [LIMIT, LIMIT]
            if values.get(name):
                z0 = _log10(abs(values[name]))
                h_rows += [w, -w]
                h_rhs += [LIMIT - z0, LIMIT + z0]
        self.H = np.array(h_rows).reshape(len(h_rows), self.n_v)
        self.h = np.array(h_rhs)
        self.centre = np.array(centre)
        self.half = np.array(half)

    # one solver entry point for both kinds
    def _solve(self, c, A_ub, b_ub, lb, ub, n_int):
        if self.nice is None:
            res = linprog(
                c,
                A_ub=A_ub if len(b_ub) else None,
                b_ub=b_ub if len(b_ub) else None,
                bounds=list(zip(lb, ub, strict=True)),
                method="highs",
                options=_HIGHS,
            )
            return res.x if res.status == 0 else None
        n = len(c)
        cons = []
        if len(b_ub):
            cons.append(LinearConstraint(A_ub, -np.inf, b_ub))
        if self.A_eq.shape[0]:
            cons.append(LinearConstraint(np.hstack([self.A_eq, np.zeros((self.A_eq.shape[0], n - self.n_v))]), 0, 0))
        integrality = np.zeros(n)
        integrality[:n_int] = 1
        res = milp(
            c,
            constraints=cons,
            integrality=integrality,
            bounds=Bounds(lb, ub),
            options={"presolve": True, "mip_rel_gap": 0.0},
        )
        return res.x if res.status == 0 else None

    def worst(self, keep=None, *, slack: bool = False) -> tuple[float, np.ndarray | None]:
        """Stage 1 over a subset of the bounds: (minimal worst violation, v).

        With `slack`, a negative violation is allowed: the largest margin by
        which every bound is met.
        """
        idx = range(len(self.bounds)) if keep is None else keep
        idx = list(idx)
        n = self.n_v + 1
        c = np.zeros(n)
        c[-1] = 1.0
        A = np.hstack([self.W[idx], -np.ones((len(idx), 1))]) if idx else np.zeros((0, n))
        A = np.vstack([A, np.hstack([self.H, np.zeros((len(self.h), 1))])])
        lb = [-self.vmax] * self.n_v + [-2 * LIMIT if slack else 0.0]
        ub = [self.vmax] * self.n_v + [np.inf]
        x = self._solve(c, A, np.concatenate([self.r[idx], self.h]), lb, ub, self.n_v)
        if x is None:  # only when the integer equalities leave nothing (cannot happen: v = 0 works)
            return math.inf, None
        return float(x[-1]), x[: self.n_v]

    def fit(self) -> tuple[float, np.ndarray]:
        """All three stages; returns (worst violation, v)."""
        m, nv, k = len(self.bounds), self.n_v, len(self.bases)
        t_star, v1 = self.worst()
        if m == 0 and nv == 0:
            return 0.0, np.zeros(0)
        n_e = len(self.ranges)
        # variables: v (nv), t, e (n_e), p (k)
        n = nv + 1 + n_e + k
        lb = [-self.vmax] * nv + [0.0] + [0.0] * n_e + [0.0] * k
        ub = [self.vmax] * nv + [t_star + 1e-10] + [np.inf] * (n_e + k)
        rows, rhs = [], []
        for i in range(m):
            row = np.zeros(n)
            row[:nv] = self.W[i]
            row[nv] = -1.0
            rows.append(row)
            rhs.append(self.r[i])
        w_centre = self.W[1::2]  # the "high" rows carry +w
        for j in range(n_e):
            for sign in (1.0, -1.0):
                row = np.zeros(n)
                row[:nv] = sign * w_centre[j]
                row[nv + 1 + j] = -self.half[j]
                rows.append(row)
                rhs.append(sign * self.centre[j])
        for b in range(k):
            for sign in (1.0, -1.0):
                row = np.zeros(n)
                row[:nv] = sign * self.P[b]
                row[nv + 1 + n_e + b] = -1.0
                rows.append(row)
                rhs.append(0.0)
        for hrow, hb in zip(self.H, self.h, strict=True):
            row = np.zeros(n)
            row[:nv] = hrow
            rows.append(row)
            rhs.append(hb)
        A = np.array(rows).reshape(len(rows), n)
        b_ub = np.array(rhs)
        c2 = np.zeros(n)
        if self.centre_values:  # else stage 3 alone: the smallest unit change within the worst violation
            c2[nv + 1 : nv + 1 + n_e] = 1.0
        x2 = self._solve(c2, A, b_ub, lb, ub, nv)
        if x2 is None:
            return t_star, v1
        opt2 = float(c2 @ x2)
        c3 = np.zeros(n)
        c3[nv + 1 + n_e :] = 1.0
        A3 = np.vstack([A, c2])
        b3 = np.append(b_ub, opt2 + 1e-9 * max(1.0, abs(opt2)))
        x3 = self._solve(c3, A3, b3, lb, ub, nv)
        x = x3 if x3 is not None else x2
        return t_star, x[:nv]

    def conflict(self) -> tuple[RangeBound, ...]:
        """A minimal infeasible set of bounds, by a deletion filter (in bound order)."""
        keep = list(range(len(self.bounds)))
        if self._feasible(keep):
            return ()
        for i in list(keep):
            trial = [j for j in keep if j != i]
            if not self._feasible(trial):
                keep = trial
        return tuple(self.bounds[j] for j in keep)

    def _feasible(self, keep) -> bool:
        """Whether some unit change meets the bounds `keep`.

        Factors rounded to powers of `nice` are judged in exact arithmetic,
        as :func:`fit_units` judges them: when the best integer choice meets
        the bounds only to within the floats' tolerance, its exact values
        decide (1e-6 times 10^7 read from a float may be 10.000000000000002,
        above a bound of 10).
        """
        t, v = self.worst(keep, slack=self.nice is not None)
        if t > TOL:
            return False
        if self.nice is None or t < -TOL or v is None:
            return True
        powers = [round(float(x)) for x in v]
        for j in keep:
            bound = self.bounds[j]
            power = sum((c * p for c, p in zip(self.system.column(bound.name), powers, strict=True)), Fraction(0))
            if power.denominator != 1:
                continue  # an irrational factor: the floats' judgement stands
            new = self.values[bound.name] * Fraction(self.nice) ** int(power)
            if new < bound.bound if bound.side == "low" else new > bound.bound:
                return False
        return True


def _log10(x) -> float:
    x = Fraction(x)
    # exact enough for huge or tiny Fractions: split off the powers of ten
    return math.log10(x.numerator) - math.log10(x.denominator)


# -- the result ---------------------------------------------------------------------------


@immutable
@dataclass(frozen=True, eq=False)
class UnitFit(TableDisplay):
    """The change of base units chosen by :func:`fit_units`.

    Attributes
    ----------
    system : System
    s : int or float
        Scale factor of `scaling`: 10 (a float) for a continuous fit, the
        integer `nice` for a rounded one.
    unit_change : mapping of str to Fraction
        Exponent of `s` for each base dimension: the factor of base ``b``
        is ``s**unit_change[b]``.
    scaling : Scaling
        The similarity scaling this unit change is, for `s`:
        ``scaling.apply(values, s)`` gives `scaled`.
    values, scaled : mapping of str to Fraction or float
        The values given and the same values in the new units: float in,
        float out (see :meth:`pitheorem.Scaling.apply`); exact values are
        Fractions.
    ranges : tuple of (str, Fraction, Fraction)
        The range of each constrained variable, in system order.
    satisfied, violated : tuple of str
        Constrained variables in and out of range.
    worst_violation : float
        Largest distance of a scaled value outside its range, in decades
        (0 when everything fits).
    conflict : tuple of RangeBound
        When not every value fits: a minimal set of bounds that no unit
        change meets together (dropping any one makes the rest feasible).
    fixed : tuple of str
        Variables held unchanged.
    fixed_units : tuple of str
        Base dimensions whose unit is kept.
    nice : int or None
        The base the factors were rounded to, or None.
    exact : bool
        Whether `satisfied` was decided in exact arithmetic.
    unit_names : tuple of (str, str)
        For a fit of an engine model: its new units, as ``units``
        gives them; empty for a fit of a System.

    Examples
    --------
    >>> import pitheorem as pt
    >>> ball = pt.System({"r": "L", "m": "M", "t": "T"})
    >>> fit = pt.fit_units(ball, {"r": 0.02, "m": 0.17, "t": 1},
    ...                    dimension_ranges={"L": (0.05, 10)}, nice=10)
    >>> fit.feasible, fit.factors["L"], fit.scaled["r"]
    (True, Fraction(100, 1), 2.0)
    """

    system: System
    s: object
    unit_change: Mapping[str, Fraction]
    scaling: Scaling
    values: Mapping[str, object]
    scaled: Mapping[str, object]
    ranges: tuple[tuple[str, Fraction, Fraction], ...]
    satisfied: tuple[str, ...]
    violated: tuple[str, ...]
    worst_violation: float
    conflict: tuple[RangeBound, ...]
    fixed: tuple[str, ...]
    fixed_units: tuple[str, ...]
    nice: int | None
    exact: bool
    unit_names: tuple[tuple[str, object], ...] = ()

    @property
    def feasible(self) -> bool:
        """Whether every constrained value lies in its range.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.fit_units(pt.System({"l": "L"}), {"l": 500}, ranges={"l": (0.05, 10)}).feasible
        True
        """
        return not self.violated

    @property
    def factors(self) -> dict[str, object]:
        """Factor by which readings of each base dimension are multiplied.

        Exact (Fraction) for a rounded fit, floats otherwise.

        Examples
        --------
        >>> import pitheorem as pt
        >>> fit = pt.fit_units(pt.System({"l": "L"}), {"l": 500}, ranges={"l": (1, 2)}, nice=2)
        >>> fit.factors
        {'L': Fraction(1, 256)}
        """
        out = {}
        for b, u in self.unit_change.items():
            if self.nice is not None and u.denominator == 1:
                out[b] = Fraction(self.nice) ** int(u)
            else:
                out[b] = float_power(float(self.s), u, f"the factor of {b}")
        return out

    @property
    def units(self) -> dict[str, object] | None:
        """An engine model's new units: a name for each of M, L and T.

        Ready for ``model.converted(**fit.units)``, or ``model.converted(fit)``
        in one step; a unit with no name is its size in SI units.  None for a
        fit of a System, whose values carry no units.

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml")).converted(L=100, M=1e6)
        >>> fit = pt.fit_units(model)
        >>> fit.units
        {'M': '1000000 kg', 'L': 'm', 'T': 's'}
        >>> model.converted(fit).units == fit.units
        True
        >>> print(pt.fit_units(pt.System({"l": "L"}), {"l": 500}, ranges={"l": (1, 2)}).units)
        None
        """
        return dict(self.unit_names) if self.unit_names else None

    @property
    def new_units(self) -> dict[str, object]:
        """Size of each new base unit in old units (``1 / factor``).

        Examples
        --------
        >>> import pitheorem as pt
        >>> fit = pt.fit_units(pt.System({"l": "L"}), {"l": 0.004}, ranges={"l": (0.05, 10)}, nice=10)
        >>> fit.new_units
        {'L': Fraction(1, 100)}
        """
        return {b: 1 / f for b, f in self.factors.items()}

    def rounded(self, nice: int = 10) -> UnitFit:
        """The same request with factors restricted to powers of `nice`.

        Parameters
        ----------
        nice : int
            Base of the allowed factors (10, 2, ...).

        Returns
        -------
        UnitFit

        Examples
        --------
        >>> import pitheorem as pt
        >>> fit = pt.fit_units(pt.System({"l": "L"}), {"l": 0.004}, ranges={"l": (0.05, 10)})
        >>> fit.rounded(10).factors
        {'L': Fraction(100, 1)}
        """
        return fit_units(
            self.system,
            dict(self.values),
            ranges={n: (lo, hi) for n, lo, hi in self.ranges},
            fixed=self.fixed,
            fixed_units=self.fixed_units,
            nice=nice,
        )

    def __repr__(self) -> str:
        return (
            f"UnitFit(feasible={self.feasible}, s={self.s!r}, unit_change={dict(self.unit_change)!r}, "
            f"violated={self.violated!r})"
        )


def _snap(problem: _Problem, v: np.ndarray, t_star: float) -> list[Fraction]:
    """Exact decades of a continuous fit: the coarsest decimal grid that loses nothing."""
    k = len(problem.bases)
    if problem.n_v == 0:
        return [Fraction(0)] * k

    def decades(zq):
        return [sum((problem.basis[j][i] * zq[j] for j in range(problem.n_v)), Fraction(0)) for i in range(k)]

    def worst(zq):
        if not len(problem.bounds):
            return 0.0
        viol = problem.W @ np.array([float(z) for z in zq]) - problem.r
        return max(0.0, float(viol.max()))

    def within_limits(exponents) -> bool:  # a unit's exponent is held to the package's size limits
        return all(e.denominator <= MAX_DENOMINATOR and abs(e) <= MAX_EXPONENT for e in exponents)

    finest = None
    for digits in (3, 6, 9, 12):
        zq = [Fraction(round(float(z) * 10**digits), 10**digits) for z in v]
        exact = decades(zq)
        if not within_limits(exact):  # a grid so fine that the decades leave the limits: the last one stands
            break
        finest = exact
        if worst(zq) <= max(t_star, 0.0) + TOL:
            return exact
    # no grid loses nothing: the finest one within the limits, off by less than its step (1e-9 decades or less)
    return finest if finest is not None else decades([Fraction(round(float(z) * 1000), 1000) for z in v])


def fit_units(
    system: System,
    values: Mapping[str, object],
    *,
    ranges: Mapping[str, object] | None = None,
    dimension_ranges: Mapping[str, object] | None = None,
    fixed: Iterable[str] = (),
    fixed_units: Iterable[str] = (),
    nice: int | None = None,
    centre: bool = True,
) -> UnitFit:
    """Find the change of base units that brings values into ranges.

    Parameters
    ----------
    system : System
    values : mapping of str to number
        Parameter values in the current units.  Variables with a range need
        a positive value; others may have any value (they are scaled too).
    ranges : mapping of str to (low, high) or None, optional
        Range per variable, ``0 < low < high``.  ``None`` removes a
        variable from a dimension range.
    dimension_ranges : mapping of str to (low, high), optional
        Range for every variable of a dimension, e.g. ``{"L": (0.05, 10)}``.
        A per-variable entry in `ranges` wins.
    fixed : iterable of str, optional
        Variables whose value must not change (e.g. the time step).
    fixed_units : iterable of str, optional
        Base dimensions whose unit must not change, e.g. ``("T",)``.
    nice : int, optional
        Restrict every factor to an integer power of `nice` (10, 2, ...) and
        check the ranges again in exact arithmetic.
    centre : bool
        Pull each value towards the middle of its range (default);
        False: the smallest unit change that puts every value in range
        (the choice of ``pt.fit_units(..., engine=...)``, which calls
        this function from :mod:`pitheorem.engines.fitting`).

    Returns
    -------
    UnitFit

    Raises
    ------
    UnknownVariableError
        For a name in `values`, `ranges` or `fixed` the system lacks.
    InvalidRequestError
        For a range with ``low >= high`` or a non-positive bound, a range
        without a value or on a non-positive value, an unknown base in
        `fixed_units`, a fixed variable whose value is outside its own
        range, or a bad `nice`.

    Notes
    -----
    Every number stays an ordinary float: the fit only considers unit
    changes whose base factors, per-variable factors and scaled values lie
    within ``10^(+-300)``.  A range that only a larger change could meet is
    reported as not met, with the conflict computed under the same limits.

    Examples
    --------
    A pool ball in metres is too small for Bullet; centimetres fit:

    >>> import pitheorem as pt
    >>> ball = pt.System({"r": "L", "m": "M", "g": "L T^-2", "dt": "T"})
    >>> fit = pt.fit_units(ball, {"r": 0.028, "m": 0.17, "g": 9.81, "dt": 1 / 240},
    ...                    ranges={"r": (0.05, 10)}, fixed=("dt",), nice=10)
    >>> fit.factors, fit.scaled["g"]
    ({'M': Fraction(1, 1), 'L': Fraction(10, 1), 'T': Fraction(1, 1)}, 98.1)

    When nothing fits, the conflict names the bounds that fight:

    >>> bad = pt.fit_units(ball, {"r": 0.028, "m": 0.17, "g": 9.81, "dt": 1 / 240},
    ...                    ranges={"r": (0.05, 10), "g": (1, 10)}, fixed=("dt",))
    >>> [str(b) for b in bad.conflict]
    ['r >= 1/20', 'g <= 10']
    """
    if not isinstance(system, System):
        raise InvalidRequestError(f"fit_units needs a System, got {type(system).__name__}")
    if not isinstance(values, Mapping):
        raise InvalidRequestError(f"values must be a mapping of variable names to numbers, got {type(values).__name__}")
    exact_values, given = {}, {}
    for name, x in values.items():
        system.index(name, "values")
        given[name] = read_value(x, f"the value of {name!r}")
        exact_values[name] = _in_float_range(
            read_number(x, f"the value of {name!r}", irrational_ok=True), f"the value of {name!r}"
        )
    if nice is not None and (isinstance(nice, bool) or not isinstance(nice, int | np.integer) or nice < 2):
        raise InvalidRequestError(f"nice must be an integer base of at least 2 (10, 2, ...), got {nice!r}")
    fixed = system.check_names(fixed, "fixed")
    if isinstance(fixed_units, str):
        fixed_units = (fixed_units,)
    fixed_units = tuple(fixed_units)
    for b in fixed_units:
        if b not in system.base_dimensions:
            raise InvalidRequestError(
                f"unknown base dimension {b!r} in fixed_units; the system's base dimensions are "
                f"{', '.join(system.base_dimensions)}"
            )
    if len(set(fixed_units)) != len(fixed_units):
        raise DuplicateVariableError(next(b for b in fixed_units if fixed_units.count(b) > 1), "fixed_units")
    rng = _resolve_ranges(system, exact_values, ranges, dimension_ranges)
    for name, lo, hi in rng:
        if name in fixed and not lo <= exact_values[name] <= hi:
            raise InvalidRequestError(
                f"variable {name!r} is held fixed at {exact_values[name]}, outside its own range [{lo}, {hi}]: "
                "fixing it contradicts its range; drop it from fixed or widen the range"
            )

    problem = _Problem(system, exact_values, rng, fixed, fixed_units, None if nice is None else int(nice), centre)
    t_star, v = problem.fit()
    if nice is None:
        s = 10.0
        units = _snap(problem, v, t_star)
    else:
        s = int(nice)
        units = [Fraction(round(float(x))) for x in v]
    scaling = Scaling.from_unit_change(system, dict(zip(system.base_dimensions, units, strict=True)))
    exact = nice is not None and all(p.denominator == 1 for p in scaling.vector)
    # the ranges are decided exactly when the factors are exact; the scaled values keep float in, float out
    exact_scaled = scaling.apply(exact_values, s) if exact else {}
    scaled = scaling.apply(given, s if exact else float(s))  # float in, float out; rounded once when exact

    satisfied, violated, worst = [], [], 0.0
    for name, lo, hi in rng:
        p = scaling.vector[system.index(name)]
        if exact:
            new = exact_scaled[name]
            ok = lo <= new <= hi
            z = _log10(new)
        else:
            z = _log10(exact_values[name]) + float(p) * math.log10(float(s))
            ok = _log10(lo) - TOL <= z <= _log10(hi) + TOL
        worst = max(worst, _log10(lo) - z, z - _log10(hi))
        (satisfied if ok else violated).append(name)
    conflict = problem.conflict() if violated else ()
    return UnitFit(
        system=system,
        s=s,
        unit_change=MappingProxyType(dict(zip(system.base_dimensions, units, strict=True))),
        scaling=scaling,
        values=MappingProxyType(given),
        scaled=MappingProxyType(scaled),
        ranges=rng,
        satisfied=tuple(satisfied),
        violated=tuple(violated),
        worst_violation=max(worst, 0.0) if violated else 0.0,
        conflict=conflict,
        fixed=fixed,
        fixed_units=fixed_units,
        nice=None if nice is None else int(nice),
        exact=exact,
    )
