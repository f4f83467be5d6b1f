"""Units an engine likes: the ranges its thresholds leave a model's numbers, and the fit into them.

:func:`pitheorem.fit_units` with ``engine=`` (or given an
:class:`~pitheorem.engines.EngineModel`) asks this module for the ranges:
each number a threshold of that engine applies to (:data:`~pitheorem.engines.thresholds.KINDS`)
must stay a factor `clearance` clear of it, on the side the engine takes
as it is.  The fit is the smallest unit change
(:func:`pitheorem.fit_units` with ``centre=False``) that puts every
number in range, keeping the time unit where that suffices.  For an engine
that computes in float32 (:data:`FLOAT32_ENGINES`), every nonzero number
also gets float32's comfortable range, :data:`FLOAT32_RANGE`.

A vector's smallest and largest magnitude are both held to the range: the
fit runs on a system with one variable per parameter and end
(``name`` for the smallest, ``name__max`` for the largest where they differ).
Thresholds that are multiples of another of the model's numbers (two time
steps) move with them under every change of units and are left out.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from fractions import Fraction

from ..dimensions import Dimension
from ..errors import InvalidRequestError
from ..simulation import positive_float
from ..system import System
from ..unitfit import fit_units
from .packages import check_engine
from .parameters import Parameter, exact_product
from .registry import REGISTRY
from .thresholds import KINDS, held_against, thresholds
from .units import SI, unit_size

__all__ = ["FLOAT32_ENGINES", "FLOAT32_RANGE", "OPEN", "engine_fit", "engine_ranges", "fitted_units", "unit_name"]

#: engines that compute in single precision (by default): each registry line says its precision
FLOAT32_ENGINES = tuple(e.name for e in REGISTRY if e.precision == "float32")
#: where float32 computes comfortably: products and squares of such numbers keep seven digits clear of
#: float32's smallest normal number (1.2e-38) and its largest (3.4e38)
FLOAT32_RANGE = (1e-6, 1e6)
#: the bounds of a side no threshold bounds: far, but ordinary floats for the fit
OPEN = (1e-290, 1e290)


def _ends(p: Parameter) -> tuple[float, float] | None:
    """The smallest and largest nonzero finite magnitude of a parameter, or None."""
    values = [abs(v) for v in p.value if math.isfinite(v) and v != 0]
    return (min(values), max(values)) if values else None


def engine_ranges(engine: str, parameters, *, clearance: float = 10.0) -> dict[str, tuple[float, float]]:
    """The range each thresholded parameter's numbers must lie in for an engine to take them as they are.

    Parameters
    ----------
    engine : str
        An engine name (:func:`pitheorem.engines.packages.check_engine`,
        or one of :data:`FLOAT32_ENGINES`).
    parameters : iterable of Parameter
        A model's table.
    clearance : float
        How far clear of each threshold, as a factor (default 10).

    Returns
    -------
    dict of str to (float, float)
        Parameter name to ``(low, high)``; only parameters a threshold
        applies to (all nonzero ones for a float32 engine).  A side no
        threshold bounds is :data:`OPEN` (1e-290 or 1e290).

    Raises
    ------
    InvalidRequestError
        For an unknown engine or a clearance below 1.

    Examples
    --------
    >>> from pitheorem import Dimension
    >>> from pitheorem.engines import Parameter
    >>> from pitheorem.engines.fitting import engine_ranges
    >>> mass = Parameter("body_ant_mass", "body 'ant' mass", (1e-16,), Dimension.parse("M"), "file", "file")
    >>> engine_ranges("mujoco", [mass])
    {'body_ant_mass': (1e-14, 100000000000000.0)}
    """
    float32 = str(engine).lower() in FLOAT32_ENGINES
    engine = str(engine).lower() if float32 else check_engine(engine)
    clearance = positive_float(clearance, "clearance")
    if clearance < 1:
        raise InvalidRequestError(f"clearance must be a factor of at least 1, got {clearance!r}", culprit=clearance)
    pool = [t for t in thresholds(engine) if t.bound in ("below", "above") and not t.relative_to]
    out = {}
    for p in parameters:
        if p.mixed or p.path.startswith("option o_") or _ends(p) is None:
            continue
        low, high = OPEN
        for t in pool:
            if any(KINDS[k][1](p) for k in t.applies):
                if t.bound == "below":
                    low = max(low, exact_product(t.value, clearance))
                else:
                    high = min(high, exact_product(t.value, 1 / clearance))
        if float32:
            low, high = max(low, FLOAT32_RANGE[0]), min(high, FLOAT32_RANGE[1])
        if (low, high) != OPEN:
            out[p.name] = (low, high)
    return out


def _pseudo_parameters(system: System, values: Mapping[str, object]) -> list[Parameter]:
    """Parameters made of a system's variables and one value each, their paths read from their names."""
    out = []
    for name, value in values.items():
        dimension = system.dimension(name)
        out.append(Parameter(name, name.replace("_", " "), (float(value),), dimension, "file", "file"))
    return out


def engine_fit(
    source,
    values=None,
    *,
    engine: str | None = None,
    clearance: float = 10.0,
    nice: int | None = 10,
    ranges=None,
    fixed=(),
    fixed_units=(),
):
    """:func:`pitheorem.fit_units` for an engine: units that keep every number clear of its thresholds.

    Parameters
    ----------
    source : EngineModel or System
        A model (its parameters give each number's kind), or a system
        whose variable names are a model's parameter names
        (:meth:`~pitheorem.engines.EngineModel.system`).
    values : mapping of str to number, optional
        With a System: the values.  With a model: ignored (its own).
    engine : str, optional
        Default: the model's engine.
    clearance : float
        How far clear of each threshold (default 10).
    nice : int or None
        Factors are powers of `nice` (default 10, so the units have names
        such as ``mm`` and ``g``).
    ranges, fixed, fixed_units
        As for :func:`pitheorem.fit_units`, added to the engine's ranges.

    Returns
    -------
    UnitFit
        On the system of the model's numbers: ``fit.factors`` multiply
        readings of M, L and T; for a model, ``fit.units`` are its new
        units by name (:func:`fitted_units`).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.fitting import engine_fit
    >>> tiny = engines.load(engines.example_path("pendulum.xml")).converted(L=100, M=1e6)
    >>> [c.element for c in engines.check(tiny)]
    ['geom_rod_friction_torsional_rolling']
    >>> fit = engine_fit(tiny)
    >>> fit.feasible, fit.factors
    (True, {'M': Fraction(1, 1), 'L': Fraction(100, 1), 'T': Fraction(1, 1)})
    >>> fit.units
    {'M': '1000000 kg', 'L': 'm', 'T': 's'}
    """
    if isinstance(source, System):
        if engine is None:
            raise InvalidRequestError("fit_units on a System needs engine= (or give the EngineModel itself)")
        if values is None:
            raise InvalidRequestError("fit_units on a System needs its values")
        parameters = _pseudo_parameters(source, values)
    elif hasattr(source, "parameters") and hasattr(source, "engine"):
        engine = source.engine if engine is None else engine
        parameters = list(held_against(source, engine))  # for MJX, with the numbers its own constants read
    else:
        raise InvalidRequestError(
            f"fit_units with an engine needs an EngineModel or a System, got {type(source).__name__}"
        )
    wanted = engine_ranges(engine, parameters, clearance=clearance)
    dims, vals, rng = {}, {}, {}
    for p in parameters:
        if p.name not in wanted:
            continue
        low, high = _ends(p)
        for name, value in ((p.name, low), (f"{p.name}__max", high)):
            if name != p.name and value == low:
                continue
            dims[name], vals[name], rng[name] = p.dimension, value, wanted[p.name]
    for name, spec in (ranges or {}).items():
        p = next((q for q in parameters if q.name == name), None)
        if p is None or p.mixed or _ends(p) is None:
            raise InvalidRequestError(
                f"ranges names {name!r}, which is no parameter with a nonzero value", culprit=name
            )
        dims[name], vals[name], rng[name] = p.dimension, _ends(p)[0], spec
    for base in SI:  # every base present, so every factor is reported
        dims.setdefault(f"_{base}", Dimension.parse(base))
    system = System(dims)
    fixed = tuple(n for n in fixed if n in dims)
    # the smallest unit change that puts every number in range, keeping the time unit if that does
    fit = None
    for units in ((tuple(fixed_units) or ("T",)), tuple(fixed_units)):
        fit = fit_units(system, vals, ranges=rng, fixed=fixed, fixed_units=units, nice=nice, centre=False)
        if fit.feasible:
            break
    if not isinstance(source, System):  # a model's units, by name: what model.converted(fit) reads
        fit = dataclasses.replace(fit, unit_names=tuple(fitted_units(source, fit).items()))
    return fit


#: SI prefixes, by power of ten
_PREFIXES = {-12: "p", -9: "n", -6: "u", -3: "m", -2: "c", -1: "d", 0: "", 3: "k", 6: "M", 9: "G"}


def unit_name(base: str, size: Fraction) -> str | object:
    """A unit's name from its size in SI units: ``mm`` for 1/1000 m, ``10 km``; else the size.

    A power of ten gets the largest SI prefix not above it, times 1, 10
    or 100 (``100 g`` for 1/10 kg); pint reads every such name back.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.engines.fitting import unit_name
    >>> unit_name("L", Fraction(1, 1000)), unit_name("M", Fraction(1, 10)), unit_name("L", Fraction(10**4))
    ('mm', '100 g', '10 km')
    >>> unit_name("T", Fraction(60))
    Fraction(60, 1)
    """
    unit = {"M": "g", "L": "m", "T": "s"}[base]
    in_unit = size * (1000 if base == "M" else 1)
    k = round(math.log10(in_unit)) if in_unit > 0 else 0
    if Fraction(10) ** k != in_unit or k < min(_PREFIXES):
        return size
    prefix = max(p for p in _PREFIXES if p <= k)
    return (f"{10 ** (k - prefix)} " if k > prefix else "") + _PREFIXES[prefix] + unit


def fitted_units(model, fit) -> dict[str, object]:
    """The units a fit chose for a model: names where they have one (``mm``), else sizes in SI units.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.fitting import engine_fit, fitted_units
    >>> tiny = engines.load(engines.example_path("pendulum.xml")).converted(L=100, M=1e6)
    >>> fitted_units(tiny, engine_fit(tiny))
    {'M': '1000000 kg', 'L': 'm', 'T': 's'}
    """
    out = {}
    for base in SI:
        factor = Fraction(fit.factors[base])
        size = unit_size(base, model.units[base]) / factor
        name = unit_name(base, size)
        out[base] = name if factor != 1 else model.units[base]
    return out
