"""The static half of a verdict: every number the engine holds, against the original times its factor.

A scaled file can be right and the engine still run something else: it
computes numbers at load (masses from geoms, a tendon's rest length from
the pose), keeps some in float32 (mesh vertices), reads sentinels (``-1``:
"compute it"), clamps others at its thresholds, and ignores some settings.
:func:`audit` compiles the original and the scaled model and holds every
number the engine keeps for the one against the other, without simulating.

What factor should each compiled number get?  The engine says so itself:
the model scaled by the same change of units at ``s = 4`` (a *probe*) is
compiled too.  There every factor ``4**k`` with ``k`` a multiple of 1/2 is
exact in binary, so a number that scales at all shows its exponent ``k``
exactly; a number whose probe ratio is no power of 4 (a sentinel, a value
the engine derives in a way no change of units reaches) is itself a cause.
Then at the requested ``s`` each number must equal the original times
``s**k``: where it does not, a float32 number is named as ``precision``
(rounded, where its factor is no power of two) or ``unscaled`` (computed
otherwise, where it is), and a float64 number, off by more than rounding,
as ``unscaled``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from pitheorem.formatting.pieces import float_text

from ...errors import InvalidRequestError, PiTheoremError
from ...exact import read_scale_factor
from ...formatting import TextDisplay
from ...immutable import immutable
from ...scaling import float_power
from ..enginemodel import EngineModel, check_scaling
from ..protocols import CounterRuns, IgnoredSettings, NamesElements, StoresUnreadNumbers
from .binary import exact_in_binary
from .causes import Cause, sorted_causes
from .probes import dimension_causes

__all__ = ["Audit", "audit", "held_otherwise"]

#: the exact probe factor: every s**k with k a multiple of 1/2 is a power of two
PROBE = 4
#: a float64 number this far (relative) from its expected value is not rounding but another number
ROUNDING = 1e-9
#: an entry below this many ulps of its field's largest is a rounding residue of a zero (a centre at 1e-16)
RESIDUE = 64
#: at most this many element names quoted in a cause's detail
SHOWN = 3
#: compiled fields no step of the engine reads, held against nothing (why, for the reader of the code):
#: ``actuator_acc0`` converts a position servo's ``dampratio`` at compile time (a changed gain shows in
#: ``actuator_biasprm``); bounding volumes only choose which pairs are tested, and a plane's is a fixed 5e9;
#: ``stat.meaninertia`` (a mean of masses and moments of inertia) only normalises the solver's tolerance,
#: which is named as a solver cause of its own; the other statistics and a tendon's width only draw
NOT_STEPPED = (
    "actuator_acc0",
    "bvh_aabb",
    "stat.meaninertia",
    "stat.center",
    "stat.extent",
    "stat.meanmass",
    "stat.meansize",
    "tendon_width",
)
#: a float64 number this close (relative) to its expected value, in a model with float32 numbers rounded,
#: was computed from them (a mesh's mass and inertia from its vertices)
DERIVED = 1e-5


@immutable
@dataclass(frozen=True, slots=True)
class Audit(TextDisplay):
    """The answer of :func:`audit`.

    Attributes
    ----------
    causes : tuple of Cause
        Every stored copy of a file's number whose power of s in the probe
        is not the one its dimension says (kind ``"dimension"``), every
        number the engine holds that is not the original times its
        factor, every float32 number rounded, every solver setting of no
        pure dimension, every setting the engine does not apply and every
        engine threshold a number of either model is beyond.
    compared : int
        How many stored numbers were held against their expected value.
    s : float

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> a = engines.audit(model, sc, s=4)
    >>> a.compared > 0, [c.kind for c in a.causes]
    (True, ['solver'])
    """

    causes: tuple[Cause, ...]
    compared: int
    s: float


def audit(model: EngineModel, scaling, s, *, scaled: EngineModel | None = None, keep_inputs: bool = False) -> Audit:
    """Hold each number the engine stores for a scaled copy against its expected one.

    Parameters
    ----------
    model : EngineModel
    scaling : Scaling
        A scaling of ``model.system()``.
    s : float or Fraction
        The scale factor.
    scaled : EngineModel, optional
        The scaled model to audit (e.g. a saved and reloaded file);
        default ``model.scaled(scaling, s, keep_inputs=keep_inputs)``.
    keep_inputs : bool
        Hold the copy to one whose inputs keep their values
        (:meth:`~pitheorem.engines.EngineModel.scaled` with ``keep_inputs=True``):
        the actuators' factors expected on their gains, not on their ranges.

    Returns
    -------
    Audit

    Raises
    ------
    InvalidRequestError
        For something that is no EngineModel or no scaling of it.

    Examples
    --------
    A tendon whose rest length the file leaves to MuJoCo (``springlength``
    ``-1``) keeps that sentinel, and MuJoCo computes the length from the
    scaled pose:

    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("superball.xml"))
    >>> sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    >>> [c.kind for c in engines.audit(model, sc, s=10).causes]
    []
    """
    if not isinstance(model, EngineModel):
        raise InvalidRequestError(f"audit needs an EngineModel (engines.load(...)), got {type(model).__name__}")
    s = read_scale_factor(s)
    check_scaling(scaling)
    if scaled is None:
        scaled = model.scaled(scaling, s, keep_inputs=keep_inputs)
    elif not isinstance(scaled, EngineModel) or scaled.engine != model.engine:
        raise InvalidRequestError("scaled must be an EngineModel of the same engine as model")
    return audited(model, scaling, s, scaled, keep_inputs)[0]


def audited(model: EngineModel, scaling, s, scaled: EngineModel, keep_inputs: bool = False) -> tuple[Audit, dict]:
    """:func:`audit` of a scaled copy, and the copy's stored numbers repaired.

    For each field an ``"unscaled"`` cause names: the copy's values with
    those it holds wrong set to the original's times their factor (a
    number no power of s carries, by the field's one power where it has
    one; a field held in float32 and rounded by a factor that is no power
    of two cannot be repaired).
    :func:`~pitheorem.engines.verdicts.diagnose.find_causes` runs the copy
    repaired, field by field, to show whether each such number acts on the
    run.  The arguments are :func:`audit`'s, checked there.

    Returns
    -------
    tuple of (Audit, dict of str to ndarray)
        The audit, and field -> the copy's values, repaired.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verdicts.audit import audited
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> wrong = model.scaled(sc, 4).multiplied(g=0.25)  # gravity left as it was
    >>> found, repairs = audited(model, sc, 4, wrong)
    >>> [c.element for c in found.causes if c.kind == "unscaled"], list(repairs)
    (['opt.gravity'], ['opt.gravity'])
    >>> model.runner.stored_numbers()["opt.gravity"][2], repairs["opt.gravity"][2]  # the original's times 4
    (np.float64(-9.81), np.float64(-39.24))
    """
    backend = model.runner
    repairs: dict[str, np.ndarray] = {}
    causes, compared = [], 0
    original = backend.stored_numbers()

    # two probes, by 4 and by 1/4: a number that scales by 4**k one way and not by 4**-k the other is not
    # scale-free even where each probe alone looks clean (a rotation found by an iteration that stops at an
    # absolute tolerance, say); and at s = 4 itself the first probe is the copy
    probe, inverse, refused = {}, {}, []
    for factor, into in ((PROBE, probe), (Fraction(1, PROBE), inverse)):
        try:
            into.update(model.scaled(scaling, factor, keep_inputs=keep_inputs).runner.stored_numbers())
        except PiTheoremError as err:  # a probe the engine refuses (a mass below its floor): no exponents by it
            refused.append((factor, err))
    # a probe refused on the copy's side of 1 (or both) is a threshold this copy is on its way to: nothing is
    # compared.  One refused on the other side says nothing of this copy (robosuite's Sawyer at s = 10, whose
    # meshes at 1/4 fall below MuJoCo's volume floor): the other probe alone gives the exponents
    if refused and (len(refused) == 2 or (refused[0][0] > 1) == (s > 1) or s == 1):
        causes.append(
            Cause(
                "threshold",
                f"the probe{'s' if len(refused) == 2 else ''} at s = {' and '.join(str(f) for f, _e in refused)}",
                f"the engine refuses {'them' if len(refused) == 2 else 'it'}: {str(refused[0][1]).splitlines()[0]}; "
                "the stored numbers were not compared",
            )
        )
        original = {}
    if original:  # each stored copy of a file's number against the dimension the reader gave it
        one, by = (probe, PROBE) if probe else (inverse, Fraction(1, PROBE))
        causes.extend(dimension_causes(model, scaling, original, one, by, keep_inputs=keep_inputs))
    copy = scaled.runner.stored_numbers()

    def repair(field: str, expected: np.ndarray, off: np.ndarray) -> None:
        """The copy's field, as repaired so far, with the entries `off` set to `expected`, in its precision."""
        out = np.array(repairs.get(field, copy[field]), copy=True)
        out[off] = expected[off].astype(out.dtype)
        repairs[field] = out

    # rows no step reads (a visual geom's pose, its mesh): held to nothing, for nothing in a run moves by them
    unread = backend.unread_stored() if isinstance(backend, StoresUnreadNumbers) else {}
    probed = {}  # field -> (exponents, clean): pass one, for the largest number of each exponent
    scale: dict[float, float] = {}
    for field, before in original.items():
        if field in NOT_STEPPED:
            continue
        probes = [p[field] for p in (probe, inverse) if p]
        if field not in copy or copy[field].shape != before.shape or any(p.shape != before.shape for p in probes):
            causes.append(Cause("unscaled", field, "the scaled model holds another number of values here"))
            continue
        if probe:
            k, clean_up, residue = _probe_exponents(before, probe[field])
        else:  # the probe by 1/4 alone: its exponents are those by 4, negated
            k, clean_up, residue = _probe_exponents(before, inverse[field])
            k = -k
        clean_back = np.ones(before.shape, dtype=bool)
        if probe and inverse:
            back, clean_back, _ = _probe_exponents(before, inverse[field])
            clean_back &= back == -k
        clean = clean_up & clean_back
        idle = unread.get(field)
        if idle is not None:  # a mask of rows, across each row's entries
            idle = np.broadcast_to(idle.reshape((-1,) + (1,) * (before.ndim - 1)), before.shape)
            clean = clean & ~idle
        changed = held_otherwise(before, copy[field], clean)
        if idle is not None:
            changed &= ~idle
        probed[field] = k, clean, residue
        if changed.any():
            # the probe that shows it: the one by 4 where that is no power of 4, else the one by 1/4
            i = tuple(np.argwhere(changed)[0]) if changed.ndim else ()
            shown = (
                (PROBE, probe[field])
                if probe and (not clean_up[i] or not inverse)
                else (Fraction(1, PROBE), inverse[field])
            )
            causes.append(_not_a_power(backend, field, before, shown, changed))
            powers = np.unique(k[clean & ~residue & (before != 0)])  # a zero takes every power
            if powers.size == 1:  # the field's one power of s (a mesh's centre, a length): set right by it
                factor = _factors(s, np.full(before.shape, powers[0]), np.ones(before.shape, dtype=bool))
                repair(field, before.astype(float) * factor, changed)
        magnitude = np.abs(before.astype(float))
        for e in np.unique(k[clean]):
            scale[e] = max(scale.get(e, 0.0), float(np.max(magnitude[clean & (k == e)], initial=0.0)))
    # is any float32 number rounded by the scaling, its own factor no power of two (s = 10; or s = 2 where a
    # field takes s**(1/2))?  Then every float32 number that differs is put down to rounding, as MuJoCo computes
    # some from others (a mesh's normals from its vertices); else what differs was computed otherwise.  Each
    # number's own factor, not the model's: a time's factor of 2**(1/2) rounds no mesh vertex
    factors = {field: _factors(s, k, clean) for field, (k, clean, _residue) in probed.items()}
    rounded32 = any(
        (clean & ~residue & (before != 0) & (np.frexp(factors[field])[0] != 0.5)).any()
        for field, (_k, clean, residue) in probed.items()
        if (before := original[field]).dtype == np.float32
    )
    derived = []  # float64 mismatches small enough to come from float32 numbers rounded
    in_binary = exact_in_binary(model, scaling, s)  # every number of the file times a power of two: none rounded
    for field, (k, clean, residue) in probed.items():
        before = original[field]
        factor = factors[field]
        expected = before.astype(float) * factor
        got = copy[field].astype(float)
        # a residue has no exponent to hold it to (a mesh vertex at 1e-9 beside vertices of 0.1)
        ok = clean & ~residue & np.isfinite(expected)
        compared += int(ok.sum())
        if before.dtype == np.float32:
            off = ok & (got != expected)
            if off.any():
                if rounded32:
                    causes.append(_rounded(backend, field, before, got, expected, off))
                else:  # nothing in float32 rounded by the scaling: what differs was processed otherwise
                    causes.append(_reprocessed(backend, field, got, expected, off, float32=True))
                    repair(field, expected, off)
            continue
        # rounding: relative to the number, or to the largest number of its dimension (a residue of 1e-16
        # left by a difference of lengths of order one is rounding too)
        allowed = ROUNDING * np.abs(expected) + RESIDUE * np.spacing(np.vectorize(scale.get)(k, 0.0)) * factor
        off = ok & (np.abs(got - expected) > allowed)
        # where every factor is a power of two nothing need be rounded: a number off by less than rounding was
        # computed by the engine from the file, at each size otherwise (the quadrature of an ellipsoid's added
        # mass in MuJoCo's compiler), and a copy it parts from the original is no longer bit for bit
        otherwise = ok & ~off & (got != expected)
        if in_binary and otherwise.any():
            if not off.any() and all(c.element != field for c in causes):  # else set right under the field's cause
                causes.append(_reprocessed(backend, field, got, expected, otherwise, float32=False))
            repair(field, expected, otherwise)
        if off.any():
            rel = _relative(got[off], expected[off])
            if rel.max() <= DERIVED:
                derived.append((field, float(rel.max()), off, got, expected))
            else:
                causes.append(_mismatch(backend, field, got, expected, off))
                repair(field, expected, off)
    if derived and any(c.kind == "precision" for c in causes):
        fields = ", ".join(f for f, *_ in derived[:6]) + (f" and {len(derived) - 6} more" if len(derived) > 6 else "")
        worst = max(r for _, r, *_ in derived)
        causes.append(
            Cause(
                "precision",
                "numbers derived from float32 ones",
                f"{fields}: computed by the engine from the rounded float32 numbers, off by up to {worst:.2g} relative",
            )
        )
    else:
        for field, _, off, got, expected in derived:
            causes.append(_mismatch(backend, field, got, expected, off))
            repair(field, expected, off)
    for name, value in (backend.solver_settings() if isinstance(backend, CounterRuns) else {}).items():
        causes.append(
            Cause(
                "solver",
                f"option {name}",
                f"{float_text(value)}: a stopping rule of no pure dimension (it "
                "compares numbers of different dimensions: MuJoCo's cost is normalised by a mean of "
                "masses and moments of inertia, Bullet's residual adds rows in m/s and rad/s), so the "
                f"scaled run may stop after another number of iterations; with_values({name}=0) runs "
                "every iteration",
            )
        )
    if isinstance(scaled.runner, IgnoredSettings):
        causes.extend(scaled.runner.ignored_settings())
    # the engine's floors and clamps (mjMINVAL, mjMINMU, ...) that a number of either model is beyond:
    # the engine runs with the fixed threshold, not with the number, so the copy is not the original scaled
    # (a threshold that is a multiple of the time step moves with it, and clamps both alike)
    from ..thresholds import crossed

    origin = scaled.copied_from
    # float32's range binds only a model the engine computes in float32 (MJX's default)
    how = {"near": 1.0, "fixed_only": True, "grouped": True, "precision": model.runner.precision}
    if origin is not None and origin[0] is model and all(0 < f < math.inf for f in origin[1].values()):
        # a copy made by model.scaled: its table is the model's, each number times its factor
        causes.extend(crossed(model.engine, model.parameters, origin[1], **how))
    else:  # a file the user made: read it
        causes.extend(crossed(model.engine, scaled.parameters, **how))
    causes.extend(crossed(model.engine, model.parameters, **how))
    return Audit(sorted_causes(causes), compared, float(s)), repairs


def held_otherwise(before: np.ndarray, copy: np.ndarray, clean: np.ndarray) -> np.ndarray:
    """The entries of a field with no exponent (`clean` False) that the copy holds otherwise than the original.

    A number whose probes show no power of 4 is a cause only where the
    copy's number differs from the original's: where the engine holds the
    very same number in the copy (a mesh's polygon normals, recomputed
    alike at this scale), nothing in the run can differ by it.

    Examples
    --------
    >>> import numpy as np
    >>> from pitheorem.engines.verdicts.audit import held_otherwise
    >>> before = np.array([1.0, 0.5, 0.25])
    >>> held_otherwise(before, np.array([4.0, 0.5, 0.3]), np.array([True, False, False])).tolist()
    [False, False, True]
    """
    before, copy = np.asarray(before), np.asarray(copy)
    with np.errstate(invalid="ignore"):
        same = (before == copy) | (np.isnan(before) & np.isnan(copy))
    return ~np.asarray(clean, dtype=bool) & ~same


def _probe_exponents(before: np.ndarray, probe: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per entry: the power ``k`` of 4 that the probe multiplied it by, whether it was one at all, and
    whether the entry is the rounding residue of a zero (nonzero, but too small to carry an exponent).

    A zero must stay zero (exponent 0); a nonzero entry must have a positive ratio ``4**k`` with
    ``2k`` an integer, up to the rounding of a number derived from others.
    """
    b, p = before.astype(float), probe.astype(float)
    k = np.zeros(b.shape)
    clean = np.ones(b.shape, dtype=bool)
    finite = np.isfinite(b)
    # the field's rounding, in its own precision (float32 for mesh vertices): RESIDUE of its largest number's ulps
    largest = (
        np.max(np.abs(before[finite]), initial=0)
        if before.dtype.kind == "f"
        else np.max(np.abs(b[finite]), initial=0.0)
    )
    floor = RESIDUE * float(np.spacing(largest))
    nonzero = finite & (b != 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(nonzero, p / np.where(nonzero, b, 1.0), 1.0)
        half = np.where(ratio > 0, np.round(2 * np.log(np.abs(ratio)) / math.log(PROBE)) / 2, 0.0)
        power = float(PROBE) ** half
        # a power of 4 up to rounding: relative to the number, or, for a number the engine derives from larger
        # ones (a mesh's centre at 1e-8 found from vertices of 0.05), absolute at the rounding of the field's largest
        exact = nonzero & (ratio > 0) & (np.abs(ratio - power) <= ROUNDING * power)
        near = (ratio > 0) & (np.abs(p - b * power) <= floor * power)
    # a zero, or the rounding residue of one: held to nothing.  Not a number below the floor that the probe
    # carries by an exact power: in float32 the floor of a field that mixes a table's inertia (241) with a
    # block's (2.7e-5, Meta-World's in MuJoCo Warp) lies above the block's, which is no residue
    zero = (np.abs(b) <= floor) & ~exact
    clean[zero] = np.abs(p[zero]) <= PROBE**2 * floor
    live = ~zero & finite
    clean[live] = exact[live] | near[live]
    k[live] = half[live]
    return k, clean, zero & (b != 0)


def _factors(s, k: np.ndarray, clean: np.ndarray) -> np.ndarray:
    """``s**k`` per entry, each distinct exponent's factor computed once, exactly rounded."""
    out = np.ones(k.shape)
    for e in np.unique(k[clean]):
        out[clean & (k == e)] = float_power(s, Fraction(float(e)), "an audited factor")
    return out


def _where(backend, field: str, mask: np.ndarray) -> str:
    """Up to :data:`SHOWN` entries of a field, by element name where the engine names them."""
    rows = np.unique(np.nonzero(mask.reshape(mask.shape[0], -1))[0]) if mask.ndim else np.array([0])
    name_of = backend.element_name if isinstance(backend, NamesElements) else None
    names = list(dict.fromkeys(name_of(field, int(r)) if name_of else f"{field}[{int(r)}]" for r in rows))
    more = f" and {len(names) - SHOWN} more" if len(names) > SHOWN else ""
    names = names[:SHOWN]
    return ", ".join(names) + more


def _not_a_power(backend, field, before, shown, mask) -> Cause:
    """The cause of numbers that no power of 4 carries, with the probe (by 4 or by 1/4) that shows the first."""
    by, probe = shown
    i = tuple(np.argwhere(mask)[0]) if mask.ndim else ()
    return Cause(
        "unscaled",
        field,
        f"{_where(backend, field, mask)}: scaled by {by} as a change of units, "
        f"{float_text(before[i])} became {float_text(probe[i])}, no power of {by}: the engine reads a "
        "sentinel or derives this number in a way no change of units carries",
    )


def _relative(got: np.ndarray, expected: np.ndarray) -> np.ndarray:
    """How far each value is off, relative to what was expected; where zero was expected, the value itself."""
    gap = np.abs(got - expected)
    size = np.abs(expected)
    return np.where(size > 0, gap / np.where(size > 0, size, 1.0), gap)


def _rounded(backend, field, before, got, expected, mask) -> Cause:
    rel = _relative(got[mask], expected[mask])
    return Cause(
        "precision",
        field,
        f"{int(mask.sum())} of {before.size} values ({_where(backend, field, mask)}) "
        f"rounded to float32 (or computed from float32 numbers that were), by up to {float(rel.max()):.2g} "
        "relative: the engine keeps them in float32, "
        "where only a factor that is a power of two scales them exactly",
    )


def _reprocessed(backend, field, got, expected, mask, *, float32: bool) -> Cause:
    """A number the engine computes from the file, not the original's times its exact factor (a power of two)."""
    rel, where, n = float(_relative(got[mask], expected[mask]).max()), _where(backend, field, mask), int(mask.sum())
    values, them = ("values", "them") if n > 1 else ("value", "it")
    if float32:
        detail = (
            f"{n} float32 {values} ({where}) differ{'' if n > 1 else 's'} from the original times an exact factor, "
            f"by up to {rel:.2g} relative: the engine computes {them} from the file in a way that is not scale-free"
        )
    else:
        detail = (
            f"{n} {values} ({where}) {'are' if n > 1 else 'is'} the original times an exact factor but for rounding "
            f"(up to {rel:.2g} relative), which a power of two never needs: the engine computes {them} from the "
            f"file and at this size rounds {them} otherwise (or the file's own numbers are off by as little)"
        )
    return Cause("unscaled", field, detail)


def _mismatch(backend, field, got, expected, mask) -> Cause:
    i = tuple(np.argwhere(mask)[0])
    return Cause(
        "unscaled",
        field,
        f"{_where(backend, field, mask)}: the engine holds {float_text(got[i])}, the "
        f"original times its factor is {float_text(expected[i])}",
    )
