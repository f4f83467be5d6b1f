"""How strong a verdict is: the horizon of the twins, and negative controls that measure what a run can see.

A verdict of "similar" says that the scaled run stayed within the
yardstick of the original.  It says little in two cases, and a report
says which:

* **Past its horizon.** A chaotic run (a walker falling over, a hand
  closing on an object) parts from its own one-ulp twins: once they are
  far apart, any copy is "within the yardstick" of the original.
  :func:`horizon` is the time until the twins part by
  :data:`HORIZON_FRACTION` of the original's motion, coordinate by
  coordinate; past it the comparison says little.
* **An error the run cannot show.** A gravity-compensated arm moves the
  same whatever gravity is; a copy with gravity left unscaled is then
  "similar" and proves nothing about gravity.  A *negative control* is the
  scaled copy with one group deliberately wrong by a known relative error
  ``e`` (gravity times ``1 + e``; every mass, density and inertia times ``1 + e``),
  run in the same batch and judged by the same rule as the copy itself
  (bit for bit where every factor is a power of two, else against the
  yardstick), and against the right copy's own deviation: see
  :func:`caught`.  The smallest ``e`` a control is caught at is the run's
  :attr:`detection_limit`: a relative error in a dimensionless group
  smaller than it would pass unnoticed.  When a group's controls all pass
  unnoticed, not even gravity doubled (a gravity-compensated arm, a planar
  model, a run whose own copy parts from it as far: rounding the engine
  parts, chaos), the run cannot show an error in that group: the verdict
  is *inconclusive*, never *similar*, and the report names the group.

The margin of the yardstick (a copy may deviate 10 times as far as the
twins) is what the controls calibrate: the detection limit is what that
margin lets through on this run, stated in every report.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...immutable import immutable
from ...simulation import unseen_groups

__all__ = [
    "CONTROL_ERRORS",
    "COPY_MARGIN",
    "HORIZON_FRACTION",
    "STILL",
    "Control",
    "caught",
    "caught_or_hidden",
    "control_factors",
    "horizon",
    "unseen_groups",
]

#: the twins' spread, as a fraction of each coordinate's range over the run, that ends the horizon
HORIZON_FRACTION = 0.01

#: a coordinate's range counts as at least this fraction of the largest range of the run (still ones jitter)
STILL = 1e-3

#: the relative errors of the negative controls (gravity times 1 + e); the masses are doubled
CONTROL_ERRORS = (1e-4, 1e-2, 1.0)

#: "similar" with a detection limit above this is weak evidence, and the report says so
WEAK_LIMIT = 1e-2

#: a control is caught only where it leaves the original by more than this many times the right copy's own
#: deviation (coordinate by coordinate): the copy is the noise floor of the very run the control is judged in.
#: The copy's deviation is one sample of that noise (rounding the engine parts the runs by, chaos past the
#: horizon), and one sample bounds the next no better than one twin bounds the copy: the yardstick lets a copy
#: reach 10 times the twins' spread for that reason, and a control must stand as far clear of the copy.  A control
#: whose error shows grows in proportion to it, and CONTROL_ERRORS are a factor of 100 apart, so the margin costs
#: at most one rung of the detection limit; the controls that only differ by noise (R2-D2's wheels in MuJoCo: 1.00
#: to 1.01 times the copy's deviation) stay far below it.
COPY_MARGIN = 10.0


@immutable
@dataclass(frozen=True, slots=True)
class Control:
    """One negative control: the scaled copy with one group wrong by a known relative error.

    Parameters
    ----------
    group : str
        What is wrong: ``"g"`` (gravity) or ``"masses"`` (every mass and
        density).
    error : float
        The relative error ``e``: the group is times ``1 + e``.
    caught : bool
        Whether the run saw it (:func:`caught`): in some coordinate, not
        bit for bit where that was expected, else beyond the yardstick,
        and beyond :data:`COPY_MARGIN` times the right copy's own
        deviation there.
    hidden : bool
        Not caught only for the right copy's own deviation: the control
        left the rule's bound (a bit, the yardstick) but stayed within
        :data:`COPY_MARGIN` times what the copy itself deviates (rounding
        the engine parts the runs by, chaos), so this run's own noise
        hides it.

    Examples
    --------
    >>> from pitheorem.engines.verdicts.strength import Control
    >>> Control("g", 0.01, True).caught, Control("g", 0.01, False, hidden=True).hidden
    (True, True)
    """

    group: str
    error: float
    caught: bool
    hidden: bool = False


def horizon(t: np.ndarray, original: np.ndarray, twins) -> float:
    """How long the original's twins stay within :data:`HORIZON_FRACTION` of its motion, in its time unit.

    Each coordinate's spread (the largest distance of any twin from the
    original) is taken relative to the coordinate's range over the run,
    or to :data:`STILL` of the largest range of any coordinate where its
    own is smaller (a body at rest jitters by rounding: that is no motion
    to part from); a run in which nothing moves has no horizon short of
    its end.  The horizon is the last
    time before the largest relative spread first exceeds the fraction, or
    the run's end when it never does.

    Parameters
    ----------
    t : array of shape (n,)
    original : array of shape (n, k)
    twins : sequence of arrays of shape (n, k)

    Returns
    -------
    float

    Examples
    --------
    >>> import numpy as np
    >>> from pitheorem.engines.verdicts.strength import horizon
    >>> t = np.arange(4.0)
    >>> run = np.array([[0.0], [1.0], [2.0], [3.0]])
    >>> horizon(t, run, [run + [[0.0], [0.0], [0.01], [0.5]]])  # 0.5 of a range of 3 parts at t = 3
    2.0
    >>> horizon(t, run, [run])
    3.0
    """
    t = np.asarray(t, dtype=float)
    original = np.asarray(original, dtype=float)
    if not len(twins) or original.size == 0:
        return float(t[-1]) if len(t) else 0.0
    span = np.ptp(original, axis=0)
    # a coordinate that barely moves (a body at rest, jittering at 1e-15) has no motion to be a fraction of:
    # each range is taken as at least STILL of the largest range any coordinate covers
    span = np.maximum(span, STILL * float(np.max(span, initial=0.0)))
    with np.errstate(invalid="ignore", divide="ignore"):
        spread = np.max([np.abs(np.asarray(twin, dtype=float) - original) for twin in twins], axis=0)
        relative = np.where(span > 0, spread / np.where(span > 0, span, 1.0), 0.0)
    parted = ~(np.max(relative, axis=1) <= HORIZON_FRACTION)  # a NaN parts too
    rows = np.nonzero(parted)[0]
    if not rows.size:
        return float(t[-1])
    return float(t[max(int(rows[0]) - 1, 0)])


def control_factors(model, inputs=()) -> list[tuple[str, float, dict[str, float]]]:
    """The negative controls a model takes: ``(group, error, factors for EngineModel.multiplied)`` each.

    Gravity at each of :data:`CONTROL_ERRORS` where the model has a
    nonzero gravity; the masses (every nonzero mass, density and inertia:
    a dimension M L^k, without time) doubled, where something else
    carries mass (a nonzero parameter or input whose dimension has M: a
    damping, a stiffness, a motor's force).  Where nothing else does,
    every mass doubled is a change of the unit of mass, no error at all:
    a passive body falls alike whatever it weighs.

    Parameters
    ----------
    model : EngineModel
    inputs : sequence of Dimension
        The dimensions of the inputs the run gives (nonzero ones).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verdicts.strength import control_factors
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> [(group, error) for group, error, _ in control_factors(model)]
    [('g', 0.0001), ('g', 0.01), ('g', 1.0), ('masses', 1.0)]
    """
    out = []
    names = {p.name: p for p in model.parameters}
    gravity = names.get("g")
    if gravity is not None and any(v != 0 for v in gravity.value):
        out.extend(("g", e, {"g": 1.0 + e}) for e in CONTROL_ERRORS)
    nonzero = [p for p in model.parameters if p.source != "derived" and any(v != 0 for v in p.value)]
    masses = {p.name: 2.0 for p in nonzero if p.dimension is not None and _inertial(p.dimension)}
    carriers = [
        d
        for p in nonzero
        if p.name not in masses
        for d in ((p.dimension,) if p.dimension is not None else (d for _part, d in p.parts))
    ] + list(inputs)
    if masses and any(d.exponent_of("M") != 0 for d in carriers):
        out.append(("masses", 1.0, masses))
    return out


def _inertial(dimension) -> bool:
    """Whether a number is a mass, a density or an inertia: M times a power of L, without time."""
    return dimension.exponent_of("M") != 0 and dimension.exponent_of("T") == 0


def caught(original: np.ndarray, back: np.ndarray, limits: np.ndarray, bits: bool, *, copy: np.ndarray) -> bool:
    """Whether a run mapped back (`back`) is told apart from the original, beyond the right copy's own deviation.

    Coordinate by coordinate, each run's deviation is its largest
    distance from the original over the run (a NaN where the original
    has a number is infinitely far).  The control is caught when in some
    coordinate its deviation exceeds both the rule's own bound (any bit
    where `bits`, every factor a power of two; else `limits`, the
    yardstick) and :data:`COPY_MARGIN` times the deviation of the right
    `copy` (mapped back) in that coordinate.  Where the copy is bit for bit
    its deviation is 0 and the rule is the bound alone.  Where the engine
    parts the copy from the original on its own (a contact's softness at
    MuJoCo's floor, native CCD, chaos), a control that differs only by as
    much is no error seen: every wrong copy differs by that too.

    Parameters
    ----------
    original, back, copy : array of shape (n, k)
        The original's run, the control's and the right copy's, both
        mapped back to original units.
    limits : array of shape (k,)
        The yardstick, per coordinate (used where not `bits`).
    bits : bool
        Whether the rule is bit for bit.

    Returns
    -------
    bool

    Examples
    --------
    >>> import numpy as np
    >>> from pitheorem.engines.verdicts.strength import caught
    >>> a, lim = np.array([[1.0, 2.0]]), np.array([1e-9, 1e-9])
    >>> caught(a, a + 1e-17, lim, bits=True, copy=a), caught(a, a + 1e-12, lim, bits=False, copy=a)
    (False, False)
    >>> caught(a, np.nextafter(a, 3.0), lim, bits=True, copy=a)  # the copy bit for bit: any bit counts
    True
    >>> noisy = np.nextafter(a, 0.0)  # a copy the engine parted by one ulp: a control as far is no error seen
    >>> caught(a, np.nextafter(a, 3.0), lim, bits=True, copy=noisy), caught(a, a + 1e-6, lim, bits=True, copy=noisy)
    (False, True)
    """
    return caught_or_hidden(original, back, limits, bits, copy=copy)[0]


def caught_or_hidden(
    original: np.ndarray, back: np.ndarray, limits: np.ndarray, bits: bool, *, copy: np.ndarray
) -> tuple[bool, bool]:
    """Whether a control is :func:`caught`, and whether, uncaught, it is *hidden*: caught against a copy bit for bit.

    A hidden control passed only because the engine parts the right copy
    from the original as far as the control's error (the report says why).
    The control's deviation is computed once for both.

    Parameters
    ----------
    original, back, copy, limits, bits
        As for :func:`caught`.

    Returns
    -------
    tuple of bool
        (caught, hidden); hidden is never true of a control caught.

    Examples
    --------
    >>> import numpy as np
    >>> from pitheorem.engines.verdicts.strength import caught_or_hidden
    >>> a, lim = np.array([[1.0, 2.0]]), np.array([1e-9, 1e-9])
    >>> caught_or_hidden(a, np.nextafter(a, 3.0), lim, True, copy=a)
    (True, False)
    >>> caught_or_hidden(a, np.nextafter(a, 3.0), lim, True, copy=np.nextafter(a, 0.0))  # the copy parted as far
    (False, True)
    """
    far = _deviation(original, back)
    with np.errstate(invalid="ignore"):
        beyond = far > 0 if bits else ~(far <= limits)  # a NaN yardstick catches, as before
    seen = bool(np.any(beyond & (far > COPY_MARGIN * _deviation(original, copy))))
    return seen, not seen and bool(np.any(beyond & (far > 0)))  # far > 0: beyond a copy's zero deviation


def _deviation(original: np.ndarray, run: np.ndarray) -> np.ndarray:
    """Each coordinate's largest distance of `run` from `original`; a NaN on either side is infinitely far."""
    with np.errstate(invalid="ignore"):
        gap = np.abs(np.asarray(run, dtype=float) - np.asarray(original, dtype=float))
    gap = np.where(np.isnan(gap), np.inf, gap)
    return np.max(gap, axis=0, initial=0.0)
