"""Why a scaled engine model is not exact or not similar: the :class:`Cause` record.

A verdict of "not similar" helps nobody unless it says why.  Every check of
the engines layer that finds something a scaling cannot carry
(:func:`pitheorem.engines.verify`, :func:`pitheorem.engines.audit`,
:func:`pitheorem.engines.check`) answers with ``Cause`` records of seven kinds:

``precision``
    a number the engine stores in lower precision than the scaling needs
    (MuJoCo keeps mesh vertices in float32): rounded differently at another
    scale.
``solver``
    a solver setting of no pure dimension (a stopping tolerance that
    compares numbers of different dimensions).
``contact``
    a contact that starts or ends at another step in the scaled run.
``threshold``
    an engine constant that a scaled number crosses (a floor, a clamp).
``setting``
    a setting written to the model that the engine does not apply.
``unscaled``
    a number the engine holds that is not the original times its factor
    (a sentinel such as ``-1`` for "compute it", a value derived at load).
``unknown``
    the runs part and no counter-run removes the difference: the step and
    the coordinate where they part, and what was tried.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...errors import InvalidRequestError
from ...formatting import TextDisplay
from ...immutable import immutable

__all__ = ["CAUSE_KINDS", "Cause"]

#: the kinds of cause, in the order reports list them
CAUSE_KINDS = ("unscaled", "setting", "threshold", "solver", "precision", "contact", "unknown")


@immutable
@dataclass(frozen=True, slots=True)
class Cause(TextDisplay):
    """One reason a scaled engine model is not exact or not similar.

    Parameters
    ----------
    kind : {"precision", "solver", "contact", "threshold", "setting", "unscaled", "unknown"}
        What sort of reason (see the module's documentation).
    element : str
        What it concerns: a parameter, a geom pair, an engine constant.
    detail : str
        The numbers behind it, and what would remove it.
    restores : bool or None
        For a cause found by a counter-run: whether that counter-run, with
        the other causes named removed too, reproduces the original (bit
        for bit where every factor is a power of two, else within the
        yardstick).  None for a cause no run tests (a number the audit
        finds unscaled, a threshold crossed).

    Examples
    --------
    >>> from pitheorem.engines import Cause
    >>> c = Cause("solver", "option tolerance", "a stopping rule of no pure dimension; set it to 0")
    >>> print(c)
    solver: option tolerance: a stopping rule of no pure dimension; set it to 0
    >>> import pitheorem as pt
    >>> try:
    ...     Cause("luck", "x", "")
    ... except pt.InvalidRequestError as err:
    ...     print(err)
    unknown cause kind 'luck'; valid: unscaled, setting, threshold, solver, precision, contact, unknown
    """

    kind: str
    element: str
    detail: str
    restores: bool | None = None

    def __post_init__(self) -> None:
        if self.kind not in CAUSE_KINDS:
            raise InvalidRequestError(f"unknown cause kind {self.kind!r}; valid: {', '.join(CAUSE_KINDS)}")
        for field in ("element", "detail"):
            if not isinstance(getattr(self, field), str):
                raise InvalidRequestError(f"a Cause's {field} must be text, got {type(getattr(self, field)).__name__}")

    def to_dict(self) -> dict[str, str]:
        """The record as a JSON-ready dictionary.

        Examples
        --------
        >>> from pitheorem.engines import Cause
        >>> Cause("contact", "geom 'foot' / geom 'floor'", "starts at step 3").to_dict()["kind"]
        'contact'
        """
        return {"kind": self.kind, "element": self.element, "detail": self.detail, "restores": self.restores}


def sorted_causes(causes) -> tuple[Cause, ...]:
    """Causes without repeats, in a deterministic order: by kind as :data:`CAUSE_KINDS` lists them.

    Examples
    --------
    >>> from pitheorem.engines.verdicts.causes import Cause, sorted_causes
    >>> [c.kind for c in sorted_causes([Cause("contact", "a", ""), Cause("unscaled", "b", ""),
    ...                                 Cause("contact", "a", "")])]
    ['unscaled', 'contact']
    """
    unique = dict.fromkeys(causes)
    return tuple(sorted(unique, key=lambda c: (CAUSE_KINDS.index(c.kind), c.element, c.detail)))
