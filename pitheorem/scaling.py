"""Similarity scalings: the :class:`Scaling` value type.

A scaling multiplies each variable by a power of one scale factor ``s``:
``x_i -> s^(a_i) x_i``.  It keeps every Pi group of a system invariant
exactly when its exponent vector is ``a = D^T u`` for some change of base
units ``u`` (mass unit times ``s^(u_M)``, ...); so every scaling here is
stored as an exponent per variable together with one such unit change.
"""

from __future__ import annotations

import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import sympy

from .dimensions import Dimension
from .display import power_text
from .errors import InvalidRequestError, LimitError, PiTheoremError
from .exact import read_exponent, read_number, short_text
from .linalg import solve
from .system import System

__all__ = ["Scaling", "as_exponent", "exact_fraction"]


def exact_fraction(value, *, irrational_ok: bool = False) -> Fraction:
    """A real number as an exact Fraction; floats as written (0.1 -> 1/10).

    The one number reader of the package, :func:`pitheorem.exact.read_number`
    (see there for the rule); raises :class:`~pitheorem.errors.NumberError`.

    Examples
    --------
    >>> from pitheorem.scaling import exact_fraction
    >>> exact_fraction("1/3"), exact_fraction(0.1)
    (Fraction(1, 3), Fraction(1, 10))
    """
    return read_number(value, irrational_ok=irrational_ok)


def as_exponent(value, what: str) -> Fraction:
    """Read an exact exponent (:func:`pitheorem.exact.read_exponent`).

    Examples
    --------
    >>> from pitheorem.scaling import as_exponent
    >>> as_exponent("1/2", "g"), as_exponent(0.25, "g")
    (Fraction(1, 2), Fraction(1, 4))
    """
    return read_exponent(value, f"exponent of {what}")


def _is_exact(x) -> bool:
    return isinstance(x, int | Fraction | sympy.Rational) and not isinstance(x, bool)


def _power(s, exponent: Fraction):
    """s**exponent, exact for exact s, float otherwise."""
    if _is_exact(s):
        return sympy.Rational(s) ** sympy.Rational(exponent.numerator, exponent.denominator)
    if isinstance(s, sympy.Basic):
        return s ** sympy.Rational(exponent.numerator, exponent.denominator)
    return float(s) ** float(exponent)


@dataclass(frozen=True, slots=True)
class Scaling:
    """A similarity scaling ``x -> s^a x`` of a system's variables.

    Build one with :func:`pitheorem.search` or :meth:`from_unit_change`.

    Parameters
    ----------
    system : System
    powers : tuple of Fraction
        Exponent of ``s`` for each variable, in system order.
    units : tuple of Fraction or None
        A change of base units producing it, one per base dimension; None
        for a symmetry of particular equations that no change of units
        gives (see :func:`pitheorem.scaling_symmetries`).

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})
    >>> sc = pt.Scaling.from_unit_change(rod, {"L": 1})
    >>> print(sc)
    l -> s l, g -> s g
    >>> sc.apply({"m": 1.5, "l": 2, "g": 9.81}, s=2)
    {'m': 1.5, 'l': 4, 'g': 19.62}
    """

    system: System
    powers: tuple[Fraction, ...]
    units: tuple[Fraction, ...] | None

    @classmethod
    def from_unit_change(cls, system: System, unit_change: Mapping[str, object]) -> Scaling:
        """The scaling produced by changing base units.

        Parameters
        ----------
        system : System
        unit_change : mapping of str to number
            Exponent of ``s`` for each base unit, e.g. ``{"L": 1}``: the
            length unit shrinks by ``s`` so every length reads ``s`` times
            larger.

        Returns
        -------
        Scaling

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"v": "L/T", "t": "T"})
        >>> pt.Scaling.from_unit_change(s, {"T": -1}).exponents
        {'v': 1, 't': -1}
        """
        bases = system.base_dimensions
        for b in unit_change:
            if b not in bases:
                raise InvalidRequestError(
                    f"unknown base dimension {b!r} in unit_change; the system's base dimensions are {', '.join(bases)}"
                )
        u = tuple(as_exponent(unit_change.get(b, 0), f"base unit {b!r}") for b in bases)
        powers = tuple(sum((system.dimension(v).exponent(b) * x for b, x in zip(bases, u, strict=True)), Fraction(0))
                       for v in system.variables)
        return cls(system, powers, u)

    @classmethod
    def from_exponents(cls, system: System, exponents: Mapping[str, object]) -> Scaling:
        """A scaling given by exponents; raises unless it is a similarity scaling.

        Parameters
        ----------
        system : System
        exponents : mapping of str to number
            Exponent of ``s`` per variable (unlisted: 0).

        Returns
        -------
        Scaling

        Raises
        ------
        InvalidRequestError
            When the exponents are not a change of units, i.e. some Pi group
            would change.

        Examples
        --------
        >>> import pitheorem as pt
        >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})
        >>> pt.Scaling.from_exponents(rod, {"l": 1, "g": 1}).unit_change
        {'M': 0, 'L': 1, 'T': 0}
        """
        names = system.check_names(tuple(exponents), "exponents")
        a = [Fraction(0)] * len(system.variables)
        for n in names:
            a[system.index(n)] = as_exponent(exponents[n], repr(n))
        bases = system.base_dimensions
        rows = [[system.dimension(v).exponent(b) for b in bases] for v in system.variables]
        u = solve(rows, a) if bases else ([] if not any(a) else None)
        if u is None:
            raise InvalidRequestError(
                f"exponents {dict(exponents)!r} are not a similarity scaling: they change a Pi group "
                "(only changes of base units keep every group invariant)"
            )
        return cls(system, tuple(a), tuple(u))

    # -- views ------------------------------------------------------------
    @property
    def exponents(self) -> dict[str, sympy.Rational]:
        """Power of ``s`` for each variable (exact).

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"l": "L", "a": "L^2"})
        >>> pt.Scaling.from_unit_change(s, {"L": 1}).exponents
        {'l': 1, 'a': 2}
        """
        return {n: sympy.Rational(p.numerator, p.denominator) for n, p in zip(self.system.variables, self.powers, strict=True)}

    @property
    def unit_change(self) -> dict[str, sympy.Rational]:
        """Power of ``s`` by which each base unit's reading changes.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.Scaling.from_unit_change(pt.System({"l": "L"}), {"L": 2}).unit_change
        {'L': 2}
        """
        return {b: sympy.Rational(x.numerator, x.denominator) for b, x in zip(self.system.base_dimensions, self._need_units(), strict=True)}

    def _need_units(self) -> tuple[Fraction, ...]:
        if self.units is None:
            raise InvalidRequestError(
                f"{self} is a symmetry of particular equations, not a change of units: "
                "it has no unit change, and quantities outside the system have no defined exponent"
            )
        return self.units

    @property
    def changed(self) -> tuple[str, ...]:
        """Variables whose exponent is nonzero (the support).

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1}).changed
        ('l',)
        """
        return tuple(n for n, p in zip(self.system.variables, self.powers, strict=True) if p)

    def exponent_of(self, dimension) -> Fraction:
        """Power of ``s`` for any quantity of the given dimension.

        Parameters
        ----------
        dimension : str or Dimension

        Returns
        -------
        Fraction

        Examples
        --------
        >>> import pitheorem as pt
        >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1, "T": 1})
        >>> sc.exponent_of("L/T^2")
        Fraction(-1, 1)
        """
        dim = dimension if isinstance(dimension, Dimension) else Dimension.parse(str(dimension))
        bases = self.system.base_dimensions
        extra = [b for b in dim.bases if b not in bases]
        if extra:
            raise InvalidRequestError(
                f"dimension {dim} uses base {extra[0]!r}, which no variable of the system has"
            )
        return sum((dim.exponent(b) * u for b, u in zip(bases, self._need_units(), strict=True)), Fraction(0))

    def factors(self, s) -> dict[str, object]:
        """The factor ``s^a`` for each variable.

        Exact (sympy) for an exact ``s``; floats for a float ``s``.

        Parameters
        ----------
        s : number
            The scale factor.

        Returns
        -------
        dict of str to number

        Examples
        --------
        >>> import pitheorem as pt
        >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "a": "L^2", "t": "T"}), {"L": -1})
        >>> sc.factors(2)
        {'l': 1/2, 'a': 1/4, 't': 1}
        """
        return {n: _power(s, p) for n, p in zip(self.system.variables, self.powers, strict=True)}

    def apply(self, values: Mapping[str, object], s) -> dict[str, object]:
        """Scale a dict of parameter values: ``x -> s^a x``.

        Keys must be variables of the system; values are numbers or
        numpy arrays.  Exact inputs give exact results.

        Parameters
        ----------
        values : mapping of str to number or array
        s : number
            The scale factor.

        Returns
        -------
        dict

        Examples
        --------
        >>> import pitheorem as pt
        >>> sc = pt.Scaling.from_unit_change(pt.System({"g": "L T^-2", "t": "T"}), {"L": 1})
        >>> sc.apply({"g": 10, "t": 3}, s=2)
        {'g': 20, 't': 3}
        """
        self._check_s(s)
        out = {}
        for name, value in values.items():
            p = self.powers[self.system.index(name, "values")]
            np = sys.modules.get("numpy")  # a value cannot be an array unless numpy is loaded
            if np is None or not isinstance(value, np.ndarray):  # arrays (of samples) pass as they are
                read_number(value, f"the value of {name!r}", irrational_ok=True)
            if p == 0:
                out[name] = value
            elif _is_exact(value) and _is_exact(s):
                out[name] = sympy.Rational(value) * _power(s, p)
            else:
                try:
                    out[name] = value * float(_power(s, p))
                except OverflowError:  # s^p itself is beyond floating point
                    raise LimitError(f"s^{p} with s = {short_text(read_number(s, 's', irrational_ok=True))}",
                                     f"the factor of {name!r}", "it is beyond the range of floating point",
                                     "use an exact value (int or Fraction), or an s nearer to 1") from None
        return out

    def map_back(self, t, y, s, *, time: str, states: Sequence[object]):
        """Map a trajectory of the scaled run back to original units.

        Parameters
        ----------
        t : array_like, shape (N,)
            Times of the scaled run.
        y : array_like, shape (N, len(states))
            States of the scaled run, one column per state.
        s : float
            The scale factor.
        time : str
            The system's time variable.
        states : sequence of str or Dimension
            For each column, a variable name or the state's dimension.

        Returns
        -------
        t_original, y_original : numpy.ndarray

        Examples
        --------
        >>> import pitheorem as pt
        >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"T": 1, "L": 1})
        >>> t, y = sc.map_back([0.0, 2.0], [[0.0], [4.0]], 2, time="t", states=["L/T"])
        >>> t.tolist(), y.tolist()
        ([0.0, 1.0], [[0.0], [4.0]])
        """
        import numpy as np  # only here: the rest of the module (and the CLI) runs without numpy

        self._check_s(s)
        t = np.asarray(t, dtype=float)
        y = np.asarray(y, dtype=float)
        if y.ndim == 1:
            y = y[:, None]
        if y.shape != (t.shape[0], len(states)):
            raise InvalidRequestError(
                f"y has shape {y.shape}; expected ({t.shape[0]}, {len(states)}): one row per time, one column per state"
            )
        a_t = self.powers[self.system.index(time, "time")]
        a_y = [
            self.powers[self.system.index(st, "states")] if isinstance(st, str) and st in self.system.variables
            else self.exponent_of(st)
            for st in states
        ]
        scale = np.array([float(s) ** float(p) for p in a_y])
        return t / float(s) ** float(a_t), y / scale

    @staticmethod
    def _check_s(s):
        try:
            ok = read_number(s, "the scale factor s", irrational_ok=True) > 0
        except PiTheoremError:
            ok = False
        if not ok:
            raise InvalidRequestError(f"the scale factor s must be a positive finite number, got {s!r}", culprit=s)

    # -- algebra ----------------------------------------------------------
    def inverse(self) -> Scaling:
        """The scaling that undoes this one (all exponents negated).

        Examples
        --------
        >>> import pitheorem as pt
        >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L"}), {"L": 1})
        >>> sc.inverse().exponents
        {'l': -1}
        """
        return self**-1

    def __mul__(self, other: Scaling) -> Scaling:
        """Compose: apply both (exponents add).

        Examples
        --------
        >>> import pitheorem as pt
        >>> sys = pt.System({"l": "L", "t": "T"})
        >>> a, b = pt.Scaling.from_unit_change(sys, {"L": 1}), pt.Scaling.from_unit_change(sys, {"T": 1})
        >>> (a * b).exponents
        {'l': 1, 't': 1}
        """
        if not isinstance(other, Scaling):
            return NotImplemented
        if other.system != self.system:
            raise PiTheoremError("cannot compose scalings of different systems")
        return Scaling(
            self.system,
            tuple(a + b for a, b in zip(self.powers, other.powers, strict=True)),
            None if self.units is None or other.units is None
            else tuple(a + b for a, b in zip(self.units, other.units, strict=True)),
        )

    def __pow__(self, k) -> Scaling:
        k = as_exponent(k, "the power of a scaling")
        units = None if self.units is None else tuple(u * k for u in self.units)
        return Scaling(self.system, tuple(p * k for p in self.powers), units)

    def __eq__(self, other) -> bool:
        return isinstance(other, Scaling) and self.system == other.system and self.powers == other.powers

    def __hash__(self) -> int:
        return hash((self.system, self.powers))

    def __str__(self) -> str:
        parts = []
        for n, p in zip(self.system.variables, self.powers, strict=True):
            if p:
                f = power_text(p)
                parts.append(f"{n} -> {n}/{f[2:]}" if f.startswith("1/") else f"{n} -> {f} {n}")
        return ", ".join(parts) or "identity (nothing changes)"

    def __repr__(self) -> str:
        exps = {n: str(p) if p.denominator != 1 else int(p) for n, p in zip(self.system.variables, self.powers, strict=True) if p}
        return f"Scaling.from_exponents({self.system!r}, {exps!r})"

    def _repr_latex_(self) -> str:
        parts = []
        for n, p in zip(self.system.variables, self.powers, strict=True):
            if p:
                sym = sympy.latex(sympy.Symbol(n))
                parts.append(rf"{sym} \to {sympy.latex(sympy.Symbol('s') ** sympy.Rational(p.numerator, p.denominator))}\,{sym}")
        return "$" + (r",\quad ".join(parts) or r"\text{identity}") + "$"
