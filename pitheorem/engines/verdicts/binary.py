"""Whether a scaling multiplies every number of a model by a power of two, so that nothing is rounded.

Where it does, a faithful engine runs the scaled copy as the original's
bits mapped back, and the verdict holds the runs to bit-for-bit equality
(:func:`pitheorem.engines.verify`); the audit holds the engine's own
numbers to it too (:func:`pitheorem.engines.audit`).
"""

from __future__ import annotations

from ...exact import read_scale_factor
from ...scaling import is_power_of_two
from ..enginemodel import EngineModel
from ..parameters import dim, dimension_factors

__all__ = ["every_factor_a_power_of_two", "exact_in_binary"]


def exact_in_binary(model: EngineModel, scaling, s) -> bool:
    """Whether a scaling multiplies every number of a model by a power of two (and the runs must agree bit for bit).

    Every number, not only every recorded coordinate: a humanoid's coordinates are angles, of
    factor 1 under any scaling that keeps time, while its lengths and masses are not exact at
    ``s = 10``.  At ``s`` a power of four every factor ``s**e`` (``e`` a multiple of 1/2) is one.

    Parameters
    ----------
    model : EngineModel
    scaling : Scaling
    s : float or Fraction

    Returns
    -------
    bool

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verdicts.binary import exact_in_binary
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> exact_in_binary(model, sc, 4), exact_in_binary(model, sc, 10), exact_in_binary(model, sc, 3)
    (True, False, False)
    """
    return every_factor_a_power_of_two(model, dimension_factors(scaling, read_scale_factor(s))[0])


def every_factor_a_power_of_two(model: EngineModel, factor) -> bool:
    """:func:`exact_in_binary` with the factors of a scaling already at hand (``factor(dimension)``)."""
    by_dimension, mixed = model.by_dimension()
    dimensions = [d for d, _names in by_dimension] + [d for p in mixed for _part, d in p.parts]
    _names, coordinates = model.coordinates()
    return all(is_power_of_two(factor(d)) for d in (*dimensions, *coordinates, dim("T")))
