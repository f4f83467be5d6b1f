"""Similarity scalings: the :class:`Scaling` value type.

A scaling multiplies each variable by a power of one scale factor ``s``:
``x_i -> s^(a_i) x_i``.  It keeps every Pi group of a system invariant
exactly when its exponent vector is ``a = D^T u`` for some change of base
units ``u`` (mass unit times ``s^(u_M)``, ...); so every scaling here is
stored as an exponent per variable together with one such unit change.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import sympy

from .dimensions import Dimension
from .errors import InvalidRequestError, LimitError
from .exact import is_float, numpy_if_loaded, read_exponent, read_number, read_scale_factor, read_value, short_text
from .formatting import MathDisplay
from .immutable import immutable
from .linalg import solve
from .system import System

__all__ = ["Scaling", "float_power", "is_power_of_two"]


def _rational_as_fraction(x):
    """A rational sympy number as the Fraction it equals; anything else as it is."""
    return read_number(x, "a rational number") if isinstance(x, sympy.Basic) and x.is_Rational else x


def _exact_power(s, exponent: Fraction):
    """``s**exponent`` for an exact `s`: a Fraction when rational, else an exact sympy number."""
    if isinstance(s, Fraction) and exponent.denominator == 1:
        return s ** int(exponent)
    return _rational_as_fraction(sympy.sympify(s) ** sympy.Rational(exponent.numerator, exponent.denominator))


def _rounded(x, name: str) -> float:
    """An exact number rounded once to the nearest float."""
    try:
        return _finite(float(x))
    except OverflowError:
        raise LimitError(
            short_text(x) if isinstance(x, Fraction) else str(x),
            f"the scaled value of {name!r}",
            "it is beyond the range of floating point (about 1e308)",
            "use an exact value (int or Fraction), or an s nearer to 1",
        ) from None


def _beyond_floats(what: str, shown: str) -> LimitError:
    return LimitError(
        shown,
        what,
        "it is beyond the range of floating point (about 1.8e308)",
        "use an exact s (an int, a Fraction or a string such as '1/2'), or an s nearer to 1",
    )


def _check_arguments(system, mapping, what: str, example: str) -> None:
    """A Scaling's constructors take a System and a mapping; anything else is named."""
    if not isinstance(system, System):
        raise InvalidRequestError(f"a Scaling needs a System, got {type(system).__name__}", culprit=system)
    if not isinstance(mapping, Mapping):
        raise InvalidRequestError(f"{what} must be a mapping such as {example}, got {mapping!r}", culprit=mapping)


def _finite(x: float) -> float:
    """`x`, or OverflowError for infinity: float() of a sympy number overflows to inf without raising."""
    if math.isinf(x):
        raise OverflowError
    return x


def is_power_of_two(factor) -> bool:
    """Whether a float factor is a power of two, so that multiplying by it is exact in binary.

    Examples
    --------
    >>> from pitheorem.scaling import is_power_of_two
    >>> [is_power_of_two(f) for f in (4.0, 0.25, 1.0, 10.0, 0.1, -2.0)]
    [True, True, True, False, False, False]
    """
    factor = float(factor)
    return factor > 0 and math.frexp(factor)[0] == 0.5


def float_power(s, exponent, what: str) -> float:
    """``s ** exponent`` as a float: the factor of one quantity under a scaling.

    Float in, float out: a float `s` is raised in floating point; an exact
    `s` (a Fraction or an irrational sympy number) is raised exactly and
    the power rounded once.  Every factor pitheorem computes in floating
    point (scaled values, samples mapped back, engine models) is this one.

    Parameters
    ----------
    s : float, Fraction or sympy number
        The scale factor, as :func:`pitheorem.exact.read_scale_factor` reads it.
    exponent : Fraction or int
        The power of ``s``.
    what : str
        Whose factor it is, for the error message (``"the factor of 'g'"``).

    Returns
    -------
    float

    Raises
    ------
    LimitError
        When the power is beyond the range of floating point.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.scaling import float_power
    >>> float_power(Fraction(10), Fraction(-2), "the factor of 'g'"), float_power(4.0, Fraction(1, 2), "a factor")
    (0.01, 2.0)
    """
    exponent = Fraction(exponent)
    if exponent == 0:
        return 1.0
    try:
        return float(s) ** float(exponent) if is_float(s) else _finite(float(_exact_power(s, exponent)))
    except OverflowError:  # s^p itself is beyond floating point, however exact the values it multiplies
        shown = short_text(read_number(s, "s")) if is_float(s) or isinstance(s, Fraction) else str(s)
        raise LimitError(
            f"s^{exponent} with s = {shown}",
            what,
            "it is beyond the range of floating point",
            "choose an s nearer to 1",
        ) from None


@immutable
@dataclass(frozen=True, slots=True)
class Scaling(MathDisplay):
    """A similarity scaling ``x -> s^a x`` of a system's variables.

    Build one with :func:`pitheorem.search`, :meth:`from_unit_change` or
    :meth:`from_exponents`.

    Parameters
    ----------
    system : System
    vector : tuple of Fraction
        Exponent of ``s`` for each variable, aligned with
        ``system.variables`` (:attr:`exponents` is the same as a dict).
    unit_change_vector : tuple of Fraction or None
        A change of base units producing it, aligned with
        ``system.base_dimensions`` (:attr:`unit_change` is the same as a
        dict); None for a symmetry of particular equations that no change
        of units gives (see :func:`pitheorem.scaling_symmetries`).

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})
    >>> sc = pt.Scaling.from_unit_change(rod, {"L": 1})
    >>> print(sc)
    l -> s l, g -> s g
    >>> sc.exponents
    {'m': Fraction(0, 1), 'l': Fraction(1, 1), 'g': Fraction(1, 1), 't': Fraction(0, 1)}
    >>> sc.apply({"m": 1.5, "l": 2.0, "g": 9.81}, s=2)
    {'m': 1.5, 'l': 4.0, 'g': 19.62}
    """

    system: System
    vector: tuple[Fraction, ...]
    unit_change_vector: tuple[Fraction, ...] | None

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
        >>> print(pt.Scaling.from_unit_change(s, {"T": -1}))
        v -> s v, t -> t/s
        """
        _check_arguments(system, unit_change, "unit_change", "{'L': 1}")
        bases = system.base_dimensions
        for b in unit_change:
            if b not in bases:
                raise InvalidRequestError(
                    f"unknown base dimension {b!r} in unit_change; the system's base dimensions are {', '.join(bases)}"
                )
        u = tuple(read_exponent(unit_change.get(b, 0), f"exponent of base unit {b!r}") for b in bases)
        of_column: dict = {}  # a model's hundreds of variables share a handful of dimensions

        def exponent(column) -> Fraction:
            key = tuple((c.numerator, c.denominator) for c in column)  # integers hash fast, Fractions do not
            if key not in of_column:
                of_column[key] = sum((c * x for c, x in zip(column, u, strict=True)), Fraction(0))
            return of_column[key]

        vector = tuple(exponent(system.column(v)) for v in system.variables)
        return cls(system, vector, u)

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
        {'M': Fraction(0, 1), 'L': Fraction(1, 1), 'T': Fraction(0, 1)}
        """
        _check_arguments(system, exponents, "exponents", "{'l': 1}")
        names = system.check_names(tuple(exponents), "exponents")
        a = [Fraction(0)] * len(system.variables)
        for n in names:
            a[system.index(n)] = read_exponent(exponents[n], f"exponent of {n!r}")
        rows = [list(system.column(v)) for v in system.variables]
        u = solve(rows, a) if system.base_dimensions else ([] if not any(a) else None)
        if u is None:
            raise InvalidRequestError(
                f"exponents {dict(exponents)!r} are not a similarity scaling: they change a Pi group "
                "(only changes of base units keep every group invariant)"
            )
        return cls(system, tuple(a), tuple(u))

    # -- views ------------------------------------------------------------
    @property
    def exponents(self) -> dict[str, Fraction]:
        """Power of ``s`` for each variable, in system order.

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"l": "L", "a": "L^2"})
        >>> pt.Scaling.from_unit_change(s, {"L": 1}).exponents
        {'l': Fraction(1, 1), 'a': Fraction(2, 1)}
        """
        return dict(zip(self.system.variables, self.vector, strict=True))

    @property
    def unit_change(self) -> dict[str, Fraction]:
        """Power of ``s`` by which each base unit's reading changes.

        Raises
        ------
        InvalidRequestError
            For a symmetry of particular equations, which is no change of
            units (see :attr:`is_unit_change`).

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.Scaling.from_unit_change(pt.System({"l": "L"}), {"L": 2}).unit_change
        {'L': Fraction(2, 1)}
        """
        return dict(zip(self.system.base_dimensions, self._need_units(), strict=True))

    @property
    def is_unit_change(self) -> bool:
        """Whether a change of base units gives this scaling.

        Always true for scalings from :func:`pitheorem.search` without
        ``within=``; a symmetry of particular equations may be none.

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.Scaling.from_unit_change(pt.System({"l": "L"}), {"L": 1}).is_unit_change
        True
        """
        return self.unit_change_vector is not None

    def _need_units(self) -> tuple[Fraction, ...]:
        if self.unit_change_vector is None:
            raise InvalidRequestError(
                f"{self} is a symmetry of particular equations, not a change of units: "
                "it has no unit change, and quantities outside the system have no defined exponent"
            )
        return self.unit_change_vector

    @property
    def changed(self) -> tuple[str, ...]:
        """Variables whose exponent is nonzero (the support).

        Examples
        --------
        >>> import pitheorem as pt
        >>> pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1}).changed
        ('l',)
        """
        return tuple(n for n, p in zip(self.system.variables, self.vector, strict=True) if p)

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
        extra = [b for b in dim.base_dimensions if b not in bases]
        if extra:
            raise InvalidRequestError(f"dimension {dim} uses base {extra[0]!r}, which no variable of the system has")
        return sum((dim.exponent_of(b) * u for b, u in zip(bases, self._need_units(), strict=True)), Fraction(0))

    def factors(self, s) -> dict[str, object]:
        """The factor ``s^a`` for each variable.

        Float in, float out: a float ``s`` gives floats.  An exact ``s``
        (int, Fraction, sympy Rational, a string such as ``"1/2"``) gives
        exact factors: a Fraction when the factor is rational, and an exact
        sympy number when it is not (``s = 2`` with exponent 1/2 gives
        ``sqrt(2)``).

        Parameters
        ----------
        s : number
            The scale factor, positive.

        Returns
        -------
        dict of str to Fraction, sympy number or float

        Examples
        --------
        >>> import pitheorem as pt
        >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "a": "L^2", "t": "T"}), {"L": -1})
        >>> sc.factors(2)
        {'l': Fraction(1, 2), 'a': Fraction(1, 4), 't': Fraction(1, 1)}
        >>> sc.factors(2.0)
        {'l': 0.5, 'a': 0.25, 't': 1.0}
        >>> pt.Scaling.from_exponents(pt.System({"l": "L"}), {"l": "1/2"}).factors(2)
        {'l': sqrt(2)}
        """
        s = read_scale_factor(s)
        if is_float(s):
            return {
                n: float_power(s, p, f"the factor of {n!r}")
                for n, p in zip(self.system.variables, self.vector, strict=True)
            }
        return {n: _exact_power(s, p) for n, p in zip(self.system.variables, self.vector, strict=True)}

    def apply(self, values: Mapping[str, object], s) -> dict[str, object]:
        """Scale a dict of parameter values: ``x -> s^a x``.

        Keys must be variables of the system; values are numbers or numpy
        arrays.  Float in, float out: a float ``s`` makes every result a
        float, and a float value (or an array) gives a float (array) for
        any ``s``; with an exact ``s``, a float value is read by the float
        rule of :mod:`pitheorem.exact` (9.81 is 981/100), scaled exactly and
        rounded once (9.81 times 10 is 98.1).  A float result beyond the
        range of floating point raises :class:`~pitheorem.LimitError`.  An exact value with an exact ``s`` (int, Fraction, sympy
        Rational, a string such as ``"1/2"``) gives an exact result: a
        Fraction when it is rational, and an exact sympy number when it is
        not (``s = 2`` with exponent 1/2 gives a multiple of ``sqrt(2)``).

        Parameters
        ----------
        values : mapping of str to number or array
        s : number
            The scale factor, positive.

        Returns
        -------
        dict

        Examples
        --------
        >>> import pitheorem as pt
        >>> sc = pt.Scaling.from_unit_change(pt.System({"g": "L T^-2", "t": "T"}), {"L": 1})
        >>> sc.apply({"g": 10, "t": 3}, s=2)
        {'g': Fraction(20, 1), 't': Fraction(3, 1)}
        >>> sc.apply({"g": 9.81, "t": 3}, s=2.0)
        {'g': 19.62, 't': 3.0}
        >>> pt.Scaling.from_exponents(pt.System({"l": "L"}), {"l": "1/2"}).apply({"l": 3}, s=2)
        {'l': 3*sqrt(2)}
        """
        if not isinstance(values, Mapping):
            raise InvalidRequestError(
                f"values must be a mapping of variable names to numbers, such as {{'l': 2}}, "
                f"got {type(values).__name__}",
                culprit=values,
            )
        s = read_scale_factor(s)
        np = numpy_if_loaded()  # a value cannot be an array unless numpy is loaded
        out = {}
        for name, value in values.items():
            p = self.vector[self.system.index(name, "values")]
            if np is not None and isinstance(value, np.ndarray):  # samples: scaled in floating point
                factor = float_power(s, p, f"the factor of {name!r}")
                with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused below, by name
                    out[name] = value * factor
                if not np.all(np.isfinite(out[name][np.isfinite(value)])):
                    raise _beyond_floats(f"the scaled samples of {name!r}", f"a sample times {factor!r}")
                continue
            number = read_number(value, f"the value of {name!r}", irrational_ok=True)
            if is_float(s):
                factor = float_power(s, p, f"the factor of {name!r}")
                if is_float(value):
                    out[name] = read_value(value, f"the value of {name!r}") * factor
                    if math.isinf(out[name]):
                        raise _beyond_floats(f"the scaled value of {name!r}", f"{float(value)!r} times {factor!r}")
                else:  # an exact value times the float factor, rounded once: 10^400 times 1e-300 is 1e100
                    out[name] = _rounded(number * Fraction(factor), name)
            elif is_float(value):  # read by the float rule, scaled exactly, rounded once
                out[name] = _rounded(number * _exact_power(s, p), name)
            else:
                # an irrational sympy value stays itself (number is its rounding, for the float branches)
                exact = value if isinstance(value, sympy.Basic) and not value.is_Rational else number
                out[name] = _rational_as_fraction(exact * _exact_power(s, p))
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

        s = read_scale_factor(s)
        t = np.asarray(t, dtype=float)
        y = np.asarray(y, dtype=float)
        if y.ndim == 1:
            y = y[:, None]
        if y.shape != (t.shape[0], len(states)):
            raise InvalidRequestError(
                f"y has shape {y.shape}; expected ({t.shape[0]}, {len(states)}): one row per time, one column per state"
            )
        a_t = self.vector[self.system.index(time, "time")]
        a_y = [
            self.vector[self.system.index(st, "states")]
            if isinstance(st, str) and st in self.system.variables
            else self.exponent_of(st)
            for st in states
        ]
        scale = np.array(
            [
                float_power(
                    s,
                    p,
                    f"the factor of state {st!r}"
                    if isinstance(st, str)
                    else f"the factor of a state of dimension {st}",
                )
                for st, p in zip(states, a_y, strict=True)
            ]
        )
        return t / float_power(s, a_t, f"the factor of {time!r}"), y / scale

    # -- algebra ----------------------------------------------------------
    def inverse(self) -> Scaling:
        """The scaling that undoes this one (all exponents negated).

        Examples
        --------
        >>> import pitheorem as pt
        >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L"}), {"L": 1})
        >>> print(sc.inverse())
        l -> l/s
        """
        return self**-1

    def __mul__(self, other: Scaling) -> Scaling:
        """Compose: apply both (exponents add).

        Examples
        --------
        >>> import pitheorem as pt
        >>> sys = pt.System({"l": "L", "t": "T"})
        >>> a, b = pt.Scaling.from_unit_change(sys, {"L": 1}), pt.Scaling.from_unit_change(sys, {"T": 1})
        >>> print(a * b)
        l -> s l, t -> s t
        """
        if not isinstance(other, Scaling):
            return NotImplemented
        if other.system != self.system:
            raise InvalidRequestError(
                f"cannot compose scalings of different systems, {self.system!r} and {other.system!r}; "
                "build both scalings from the same System"
            )
        return Scaling(
            self.system,
            tuple(a + b for a, b in zip(self.vector, other.vector, strict=True)),
            None
            if self.unit_change_vector is None or other.unit_change_vector is None
            else tuple(a + b for a, b in zip(self.unit_change_vector, other.unit_change_vector, strict=True)),
        )

    def __pow__(self, k) -> Scaling:
        k = read_exponent(k, "the power of a scaling")
        units = None if self.unit_change_vector is None else tuple(u * k for u in self.unit_change_vector)
        return Scaling(self.system, tuple(p * k for p in self.vector), units)

    def __eq__(self, other) -> bool:
        return isinstance(other, Scaling) and self.system == other.system and self.vector == other.vector

    def __hash__(self) -> int:
        return hash((self.system, self.vector))

    def __repr__(self) -> str:
        exps = {
            n: str(p) if p.denominator != 1 else int(p)
            for n, p in zip(self.system.variables, self.vector, strict=True)
            if p
        }
        return f"Scaling.from_exponents({self.system!r}, {exps!r})"
