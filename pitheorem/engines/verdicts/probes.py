"""The engine as a check of the reader: the power of s each stored number takes, against its dimension.

A probe copy of a model, scaled by a change of units at ``s = 4``, is
compiled by the engine; every number the engine stores from the file then
shows which power of 4 it took (:mod:`pitheorem.engines.verdicts.audit`).
Where the number is a copy of a file's number (or the reader took it from
the compiled model, a body's mass computed from its geoms), that power must
be the one the dimension the reader gave the number implies.  A number that
took another power was given the wrong dimension, by the reader or by the
numbers the engine computed it from: a cause of kind ``"dimension"``, naming
the element and the attribute.

:func:`dimension_causes` is the comparison, run by
:func:`~pitheorem.engines.verdicts.audit.audit` on its probe;
:func:`check_dimensions` runs it alone on three probes (lengths, masses,
times each scaled by 4), the cheap check of a freshly loaded model.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from ...errors import InvalidRequestError, PiTheoremError
from ...scaling import Scaling
from ..enginemodel import EngineModel
from ..protocols import KeepsInputs, StoresCopies
from .causes import Cause, sorted_causes

__all__ = ["check_dimensions", "dimension_causes", "kept_input_dimensions"]

#: the probe's scale factor: its powers with half-integer exponents are exact in binary
PROBE = 4
#: how far (relative) a probe's ratio may be from a power of the probe factor and still be that power
ROUNDING = 1e-9


def kept_input_dimensions(model: EngineModel) -> dict:
    """The part of each number's dimension that is an input's, where the copy keeps its inputs' values.

    With ``keep_inputs=True`` an input keeps its value, so each number that
    carries it (its range, a gain that multiplies it) takes the factor of its
    dimension divided by this part (:meth:`~pitheorem.engines.EngineModel.scaled`).

    Parameters
    ----------
    model : EngineModel

    Returns
    -------
    dict of str to Dimension
        Parameter name to the input's dimension to that number's power (empty
        for an engine whose inputs have no gain).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verdicts.probes import kept_input_dimensions
    >>> kept = kept_input_dimensions(engines.load(engines.example_path("pendulum.xml")))
    >>> {name: str(d) for name, d in kept.items() if name.endswith("gain")}
    {'actuator_torque_gainprm_gain': 'M^-1 L^-2 T^2'}
    """
    runner = model.runner
    if not isinstance(runner, KeepsInputs):
        return {}
    kept = {}
    for ctrl, powers in zip(runner.control_dimensions(), runner.input_parameters(), strict=True):
        kept.update({name: ctrl**power for name, power in powers.items()})
    return kept


def dimension_causes(
    model: EngineModel, scaling, original: dict, probe: dict, s=PROBE, *, keep_inputs: bool = False
) -> list[Cause]:
    """Causes of kind ``"dimension"``: stored copies of the file's numbers that took another power of `s`.

    Parameters
    ----------
    model : EngineModel
    scaling : Scaling
        The scaling the probe was made with.
    original, probe : dict of str to ndarray
        The stored numbers (``runner.stored_numbers()``) of the model and of its copy scaled at `s`.
    s : int, default 4
        The probe's scale factor.
    keep_inputs : bool
        The probe keeps its inputs' values (:func:`kept_input_dimensions`).

    Returns
    -------
    list of Cause
        One per parameter whose stored copy disagrees (an engine that names no copies gives none).

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verdicts.probes import dimension_causes
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    >>> probe = model.scaled(lengths, 4).runner.stored_numbers()
    >>> dimension_causes(model, lengths, model.runner.stored_numbers(), probe)
    []
    """
    backend = model.runner
    if not isinstance(backend, StoresCopies):
        return []
    seen, causes = set(), []
    kept = kept_input_dimensions(model) if keep_inputs else {}
    log_s = math.log(float(s))
    for copy in backend.stored_copies():
        dimension, key = copy.dimension, (copy.parameter or copy.element, copy.attribute)
        if dimension is None or key in seen or copy.field not in probe:
            continue
        before = float(np.ravel(original[copy.field])[copy.index])
        after = float(np.ravel(probe[copy.field])[copy.index])
        ratio = after / before if before != 0 else 0.0
        if not (math.isfinite(ratio) and ratio > 0):
            continue  # a zero takes every power; a sign change is the audit's "unscaled", as is an overflow
        took = math.log(ratio) / log_s
        nearest = round(2 * took) / 2
        if abs(ratio - float(s) ** nearest) > ROUNDING * float(s) ** nearest:
            continue  # no power of s at all: the audit names it "unscaled"
        # with kept inputs, an input's part of the dimension keeps its value
        scaled_as = dimension / kept[copy.parameter] if copy.parameter in kept else dimension
        want = Fraction(scaling.exponent_of(scaled_as))
        if Fraction(nearest) != want:
            seen.add(key)
            what = (
                f"the reader gives {copy.parameter} the dimension {dimension}"
                if copy.parameter
                else f"the engine computes {copy.field} (dimension {dimension}) from the file's numbers"
            )
            causes.append(
                Cause(
                    "dimension",
                    f"{copy.element} {copy.attribute}",
                    f"{what}, which this scaling multiplies by s^{want}; the engine stores it in "
                    f"{copy.field}[{copy.index}] and, in a copy scaled at s = {s}, {before:.17g} became "
                    f"{after:.17g}: s^{Fraction(nearest)}",
                )
            )
    return causes


def check_dimensions(model: EngineModel) -> tuple[Cause, ...]:
    """The reader's dimensions held against the engine: three probes, one per base (M, L, T) at s = 4.

    Parameters
    ----------
    model : EngineModel

    Returns
    -------
    tuple of Cause
        Of kind ``"dimension"``; ``()`` where every stored copy of a file's number took the power of
        s its dimension says.  A probe the engine refuses (a number pushed past a threshold) is
        skipped.

    Raises
    ------
    InvalidRequestError
        For something that is no EngineModel.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verdicts.probes import check_dimensions
    >>> check_dimensions(engines.load(engines.example_path("pendulum.xml")))
    ()
    """
    if not isinstance(model, EngineModel):
        raise InvalidRequestError(f"check_dimensions needs an EngineModel, got {type(model).__name__}")
    if not isinstance(model.runner, StoresCopies):
        return ()
    system = model.system()
    original = model.runner.stored_numbers()
    causes = []
    for base in ("M", "L", "T"):
        try:
            scaling = Scaling.from_unit_change(system, {base: 1})
            probe = model.scaled(scaling, PROBE).runner.stored_numbers()
        except PiTheoremError:
            continue  # a probe the engine refuses: nothing to compare
        causes.extend(dimension_causes(model, scaling, original, probe))
    return sorted_causes(causes)
