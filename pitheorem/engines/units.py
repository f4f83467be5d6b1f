"""The units an engine model is written in, and the same model in other units.

A file's numbers mean nothing without their units: MuJoCo and PyBullet
take every number as it is written, so a fruit fly written in centimetres
and grams falls under a gravity of 981, not 9.81.  :func:`pitheorem.engines.load`
takes the units a file is written in (``units={"L": "cm", "M": "g"}``; SI,
metres, kilograms and seconds, by default), and
:meth:`~pitheorem.engines.EngineModel.converted` gives the same robot in
other units.

A change of units is a similarity scaling (:meth:`pitheorem.Scaling.from_unit_change`),
so a conversion is :meth:`~pitheorem.engines.EngineModel.scaled` with
that scaling: every number by its dimension, gravity, densities,
viscosity, stiffness, damping, gains, margins, solref time constants, the
time step and the keyframes.  When every factor is an integer power of
one rational number ``s`` (every metric prefix, every power of two), the
conversion is one scaling by ``s`` and each number is rounded once (exact
at powers of two); otherwise one scaling per base unit, each rounded once.

An MJCF file written by pitheorem records its units in a custom text
element, ``<text name="pitheorem:units" data="M=g; L=mm; T=s"/>``, and is
read back in them.  A URDF file is in SI by its specification: a URDF
model is not converted (an :class:`~pitheorem.errors.EngineModelError`
says so).
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from fractions import Fraction

import numpy as np

from ..errors import InvalidRequestError, UnitError
from ..exact import read_number, short_text
from ..scaling import Scaling, float_power

__all__ = [
    "SI",
    "conversion",
    "convert",
    "declared_units",
    "factor_of",
    "read_units",
    "run_in_units",
    "unit_size",
]

#: the units of a file that declares none: SI (MuJoCo's and PyBullet's defaults are given in it)
SI = {"M": "kg", "L": "m", "T": "s"}
#: the name of the MJCF custom text element that records the units pitheorem wrote a file in
#: pint's name of each base dimension
_PINT_DIMENSION = {"M": "[mass]", "L": "[length]", "T": "[time]"}


def unit_size(base: str, unit) -> Fraction:
    """The size of a unit of one base dimension in SI units, exactly.

    Parameters
    ----------
    base : {"M", "L", "T"}
    unit : str or number
        A unit name pint reads (``"mm"``, ``"g"``, ``"ms"``, ``"inch"``),
        or the unit's size in SI units (``0.001`` for a millimetre).

    Returns
    -------
    Fraction
        The decimal pint's factor prints as, read exactly (a centimetre is
        1/100 m).

    Raises
    ------
    UnitError
        For a name pint does not know, or one of another dimension.
    InvalidRequestError
        For an unknown base, or a size that is not a positive number.

    Examples
    --------
    >>> from pitheorem.engines.units import unit_size
    >>> unit_size("L", "cm"), unit_size("M", "g"), unit_size("L", "inch")
    (Fraction(1, 100), Fraction(1, 1000), Fraction(127, 5000))
    """
    if base not in SI:
        raise InvalidRequestError(f"unknown base dimension {base!r}; units are given for M, L and T", culprit=base)
    if not isinstance(unit, str):
        size = read_number(unit, f"the size of the {base} unit")
        if size <= 0:
            raise InvalidRequestError(f"the size of the {base} unit must be positive, got {unit!r}", culprit=unit)
        return size
    return _named_size(base, unit)


@functools.lru_cache(maxsize=256)
def _named_size(base: str, unit: str) -> Fraction:
    """:func:`unit_size` of a unit name, asked of pint once per name (every load reads SI's three names)."""
    from ..system import unit_registry

    try:
        quantity = unit_registry()(unit)
        quantity = quantity.to_base_units() if hasattr(quantity, "to_base_units") else None
    except Exception:  # pint's parser fails with many kinds of error
        quantity = None
    expected = _PINT_DIMENSION[base]
    if quantity is None or dict(quantity.dimensionality) != {expected: 1}:
        raise UnitError(
            f"{unit!r} is no unit of {expected.strip('[]')} ({base}); give one such as "
            f"{ {'M': 'g', 'L': 'mm', 'T': 'ms'}[base]!r}",
            culprit=unit,
        )
    size = read_number(float(quantity.magnitude), f"the size of {unit!r}")
    if size <= 0:
        raise UnitError(f"{unit!r} has no positive size", culprit=unit)
    return size


def _unit_name(base: str, unit) -> str:
    """The name a unit is recorded under: its own name, or its size in SI units (``1/1000 m``)."""
    if isinstance(unit, str):
        return unit.strip()
    return f"{short_text(unit_size(base, unit))} {SI[base]}"


def read_units(units, what: str = "units") -> dict[str, str]:
    """Units for M, L and T: those given, SI for the others.

    Parameters
    ----------
    units : mapping of str to (str or number), or None
        Base dimension (``"M"``, ``"L"``, ``"T"``) to a unit name or the
        unit's size in SI units.
    what : str
        How the caller names the argument, for the error message.

    Returns
    -------
    dict of str to str
        In the order M, L, T.

    Raises
    ------
    InvalidRequestError
        For a key other than M, L and T, or no mapping.
    UnitError
        For a unit name pint does not read as that dimension.

    Examples
    --------
    >>> from pitheorem.engines.units import read_units
    >>> read_units({"L": "cm", "M": "g"})
    {'M': 'g', 'L': 'cm', 'T': 's'}
    >>> read_units({"L": 0.001})
    {'M': 'kg', 'L': '1/1000 m', 'T': 's'}
    """
    if units is None:
        return dict(SI)
    if not isinstance(units, Mapping):
        raise InvalidRequestError(
            f"{what} must map base dimensions (M, L, T) to units, such as "
            f"{{'L': 'cm', 'M': 'g'}}; got {type(units).__name__}",
            culprit=units,
        )
    for base in units:
        if base not in SI:
            raise InvalidRequestError(f"{what} names {base!r}; give units for M, L and T", culprit=base)
    out = {}
    for base, default in SI.items():
        unit = units.get(base, default)
        unit_size(base, unit)  # refuses a bad name here
        out[base] = _unit_name(base, unit)
    return out


def _factors(old: Mapping[str, str], new: Mapping[str, str]) -> dict[str, Fraction]:
    """Per base, the exact number a reading is multiplied by when its unit changes from old to new."""
    return {b: unit_size(b, old[b]) / unit_size(b, new[b]) for b in SI}


def _root(x: Fraction) -> tuple[Fraction, int]:
    """``(r, k)`` with ``x = r**k``, ``r > 1`` no perfect power of a rational (k may be negative)."""
    if x < 1:
        r, k = _root(1 / x)
        return r, -k
    n, d = x.numerator, x.denominator
    for k in range(max(n.bit_length(), 1), 1, -1):
        rn, rd = _integer_root(n, k), _integer_root(d, k)
        if rn is not None and rd is not None:
            return Fraction(rn, rd), k
    return x, 1


def _integer_root(n: int, k: int) -> int | None:
    try:
        r = round(n ** (1.0 / k))
    except OverflowError:  # beyond a float: no unit is that far from another
        return None
    for c in (r - 1, r, r + 1):
        if c >= 0 and c**k == n:
            return c
    return None


def conversion(system, old: Mapping[str, str], new: Mapping[str, str]) -> tuple[tuple[Scaling, Fraction], ...]:
    """The change of units from `old` to `new` as scalings of a system: ``(scaling, s)`` pairs.

    One pair when every factor is an integer power of one rational ``s``
    (metric prefixes: ``s = 10``); otherwise one pair per base unit that
    changes.  Applying the pairs in turn converts every number.

    Parameters
    ----------
    system : System
        Over M, L and T (an engine model's :meth:`~pitheorem.engines.EngineModel.system`).
    old, new : mapping of str to str
        Units of M, L and T (:func:`read_units`).

    Returns
    -------
    tuple of (Scaling, Fraction)
        Empty when the units are the same.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines.units import conversion, read_units
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})
    >>> [(str(sc), s) for sc, s in conversion(rod, read_units({"L": "cm", "M": "g"}), read_units({"L": "mm"}))]
    [('m -> m/s^3, l -> s l, g -> s g', Fraction(10, 1))]
    """
    factors = {b: f for b, f in _factors(old, new).items() if f != 1}
    if not factors:
        return ()
    roots = {b: _root(f) for b, f in factors.items()}
    if len({r for r, _k in roots.values()}) == 1:
        s = next(iter(roots.values()))[0]
        return ((Scaling.from_unit_change(system, {b: k for b, (_r, k) in roots.items()}), s),)
    return tuple((Scaling.from_unit_change(system, {b: 1}), f) for b, f in factors.items())


def convert(model, units: Mapping[str, object], *, keep_inputs: bool = False):
    """The same model in other units (:meth:`pitheorem.engines.EngineModel.converted`).

    Parameters
    ----------
    model : EngineModel
    units : mapping of str to (str or number)
        The new units of some of M, L and T; the others keep the model's.
    keep_inputs : bool
        Keep every control input's value (the factors on the gains; see
        :meth:`~pitheorem.engines.EngineModel.scaled`).

    Returns
    -------
    EngineModel
        Unsaved, with :attr:`~pitheorem.engines.EngineModel.units` the new
        units; saved, its file records them.

    Raises
    ------
    EngineModelError
        For a URDF model and units other than SI (URDF is SI by its
        specification).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.units import convert
    >>> mm = convert(engines.load(engines.example_path("pendulum.xml")), {"L": "mm"})
    >>> mm.units, mm.parameter("g").value
    ({'M': 'kg', 'L': 'mm', 'T': 's'}, (9810.0,))
    """
    old = model.units
    new = read_units({**old, **dict(units)}, "the new units")
    model.runner.check_units(new)  # a format fixed in its units (URDF: SI) refuses others, by name
    out = model
    for scaling, s in conversion(model.system(), old, new):
        out = out.scaled(scaling, s, keep_inputs=keep_inputs)
    return out.in_units(new)


def declared_units(model, units) -> dict[str, str]:
    """The units a freshly read model is in: those the caller gives, the file's record, or SI.

    Raises
    ------
    InvalidRequestError
        When the caller's units contradict those the file records.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.units import declared_units
    >>> declared_units(engines.load(engines.example_path("pendulum.xml")), {"L": "cm"})
    {'M': 'kg', 'L': 'cm', 'T': 's'}
    """
    found = model.runner.recorded_units()
    given = None if units is None else read_units(units)
    if found is not None and given is not None and found != given:
        raise InvalidRequestError(
            f"{model.path} records its units as {found}; units={given} contradicts them "
            "(leave units out to read the file in its own)",
            culprit=units,
        )
    return given or found or dict(SI)


def run_in_units(model, rows, units: Mapping[str, object]) -> np.ndarray:
    """A run of a model, mapped into other units: rows of (qpos, qvel, act).

    The map back of a converted model's trajectories: run ``mm``, a copy
    converted to millimetres, and ``run_in_units(mm, rows, fly.units)`` gives
    the rows in the original's units.

    Parameters
    ----------
    model : EngineModel
        The model that ran (an MJCF model).
    rows : array of shape (n, nq + nv + na)
        Its states, in ``model.units``.
    units : mapping of str to (str or number)
        The units to map into (:func:`read_units`).

    Returns
    -------
    numpy.ndarray
        The same shape, each coordinate times its dimension's factor.

    Examples
    --------
    >>> import numpy as np
    >>> from pitheorem import engines
    >>> from pitheorem.engines.units import run_in_units
    >>> mm = engines.load(engines.example_path("pendulum.xml")).converted(T="ms")
    >>> run_in_units(mm, np.array([[0.5, 0.002]]), {"T": "s"})
    array([[0.5, 2. ]])
    """
    names, dims = model.coordinates()
    rows = np.asarray(rows, dtype=float)
    if rows.ndim != 2 or rows.shape[1] != len(dims):
        raise InvalidRequestError(
            f"rows must have {len(dims)} columns ({', '.join(names[:4])}, ...), got shape {rows.shape}"
        )
    factors = _factors(model.units, read_units({**model.units, **dict(units)}))
    return rows * np.array([factor_of(d, factors) for d in dims])


def factor_of(dimension, factors: Mapping[str, Fraction]) -> float:
    """The factor a number of `dimension` is multiplied by under per-base `factors`, rounded once.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem import Dimension
    >>> from pitheorem.engines.units import factor_of
    >>> factor_of(Dimension.parse("M L^2"), {"M": Fraction(1), "L": Fraction(10), "T": Fraction(1)})
    100.0
    """
    exact, inexact = Fraction(1), 1.0
    for b in SI:
        e = dimension.exponent_of(b)
        if e.denominator == 1:
            exact *= factors[b] ** int(e)
        else:  # a root: no exact product
            inexact *= float_power(factors[b], e, f"the factor of {dimension}")
    return float(exact) * inexact
