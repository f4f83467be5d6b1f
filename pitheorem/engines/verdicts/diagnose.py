"""Why a scaled run is not exact or not similar: causes found by counter-runs, not guessed.

:func:`pitheorem.engines.verify` calls :func:`find_causes` when a run at a
power of four is not bit for bit the original, or a run is not similar.
Each cause is established, not presumed:

* the static ones by :func:`pitheorem.engines.audit` (numbers the engine
  holds that are not the original times their factor, float32 rounding,
  settings the engine ignores);
* ``solver``: the original and the scaled copy run again with the
  solver's tolerance at 0 (every iteration done), with the scale-free
  solver, with the equality constraints inactive (then each one alone),
  and with the joints' and tendons' limits off (then each one alone);
* ``contact``: with MuJoCo's native convex collision (native CCD) off,
  and with contacts off; the geom pairs in contact after each step are
  compared, and the first pair that touches in one run only is named;
* ``threshold``: with an engine's clamp on velocities lifted in both runs
  (PyBullet's, one number for a body's speeds and angular speeds), where a
  run may have met it.

A number the copy holds wrong that the engine can hold right (the audit's
``unscaled`` ones, mostly) is shown the same way: the copy is run again
with it set right.  Where that run is the very same bits, the number acts
on nothing in this run and is no cause of it.

A counter-run *shows* a cause when the runs, with it removed from both,
part later or never.  A cause that parts the runs first hides the others
(a weld acting from the first step hides a contact that would part them
later), so the counter-runs are made again with the causes found removed
in both runs, round after round, until nothing new shows.  Where no
counter-run shows a cause alone (two causes parting the runs from the same
step by like amounts, each leaving the other's share), the counter-runs
are made all together, and the fewest that still restore the run are
kept, each shown with the others removed.  A cause is
named only as part of the smallest set
whose counter-runs together *restore* the run: bit for bit where every
factor is a power of two ("nearly" is not agreement there), else within
the yardstick; each such cause says so (``cause.restores``).  Causes
that together do not restore it are named with ``restores=False``, and
the step and coordinate where the runs part become a cause of kind
``"unknown"`` (unless the audit found a number the copy holds wrong).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from pitheorem.formatting.pieces import float_text

from ...simulation import allowed_deviation, first_broken_row
from ..protocols import (
    ClampsVelocities,
    CounterRuns,
    IgnoredSettings,
    SolverDiagnosis,
    SwitchesConstraints,
    WritesStored,
)
from .audit import audited
from .causes import Cause, sorted_causes

__all__ = ["SHRINK", "find_causes"]

#: a counter-run that leaves the runs this many times closer than the verdict's shows a cause (or they part later)
SHRINK = 1000.0


def find_causes(
    model,
    scaled,
    scaling,
    s,
    n_steps,
    u_original,
    u_scaled,
    factors,
    report,
    exact_expected: bool,
    ran=None,
    keep_inputs: bool = False,
) -> tuple[Cause, ...]:
    """The causes of a verdict that is not exact (at a power of four) or not similar.

    Parameters
    ----------
    model, scaled : EngineModel
        The original and its scaled copy.
    scaling, s
        As given to :func:`pitheorem.engines.verify`.
    n_steps : int
    u_original, u_scaled : ndarray or None
        The open-loop inputs of each run, one row per step.
    factors : ndarray
        Each recorded coordinate's factor.
    report : SimilarityReport
        The verdict to explain.
    exact_expected : bool
        Whether every factor is a power of two (the runs should be bit for bit equal).
    ran : dict, optional
        Runs already made under some options (the scale-free proof's), by their sorted items: the
        original's and the copy's, reused as those counter-runs.
    keep_inputs : bool
        The copy keeps its inputs' values (the audit expects the actuators' factors on their gains).

    Returns
    -------
    tuple of Cause

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("pendulum.xml")).with_values(tolerance=1e-3)
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> rep = engines.verify(model, sc, s=4, duration=1.0, controls=lambda t: [0.1])
    >>> rep.exact, [c.kind for c in rep.causes]
    (True, [])
    """
    original, copy = model.runner, scaled.runner
    found_static, repairs = audited(model, scaling, s, scaled, keep_inputs)
    causes = [c for c in found_static.causes if c.kind != "solver"]
    # a number the copy holds wrong, where the engine can set it right in a copy: shown by a run, not presumed
    to_show = [c for c in causes if c.element in repairs] if isinstance(copy, WritesStored) else []
    causes = [c for c in causes if c not in to_show]
    # a setting the engine ignores whose effect a counter-run removes from both runs (PyBullet's collision margins,
    # which act through contacts only: contacts off): shown by that run, or found to act on nothing in it
    removable = []
    if isinstance(copy, IgnoredSettings) and isinstance(original, CounterRuns):
        removable = [(c, options) for c in causes if (options := copy.removed_by(c))]
        causes = [c for c in causes if all(c is not r for r, _o in removable)]
    # a clamp on the velocities (PyBullet's, one number for a body's speeds and angular speeds alike) acts on a run
    # that reaches it only: lifted in both runs where either may have met it, else acting on nothing here
    clamped = isinstance(original, ClampsVelocities) and (
        original.reaches_velocity_clamp(report.original.y) or copy.reaches_velocity_clamp(report.mapped.y * factors)
    )
    removable = [(c, options) for c, options in removable if clamped or "velocity_clamp" not in options]
    limits = allowed_deviation(report.original, report.sensitivity, report.baseline_factor)

    # Where the runs first part: where every factor is a power of two, the first step at which they differ in
    # a bit (a faithful engine reproduces the original exactly: "nearly" is a difference to explain); else the
    # first step at which a coordinate leaves the yardstick.  A counter-run *shows* a cause when, with the
    # candidate removed from both runs, they never part, or part later than the verdict's runs do (a model
    # with two causes is not repaired by removing one, but its first difference moves); it *restores* the run
    # when they never part.
    bits = exact_expected

    def parting(run: np.ndarray, back: np.ndarray) -> int | None:
        with np.errstate(invalid="ignore"):
            off = (run != back) if bits else ~(np.abs(back - run) <= limits)  # a NaN parts
        rows = np.nonzero(off.any(axis=1))[0]
        return int(rows[0]) if rows.size else None

    verdict_parts = parting(report.original.y, report.mapped.y)
    if verdict_parts is None:  # nothing to explain by a run: the static causes (the audit's) only
        # bit for bit, a number the copy holds wrong (that it could hold right) did not act on this run
        return sorted_causes([*causes, *([] if bits else [*to_show, *(c for c, _o in removable)])])

    done: dict[tuple, Counter] = {}  # a counter-run asked for twice (alone, then in the smallest set) runs once

    def runners(options: dict):
        """The original's and the copy's runners under a counter-run's options; ``repaired`` (fields the copy
        holds wrong, set right) changes the copy alone."""
        options = dict(options)
        fields = options.pop("repaired", ())
        there = copy.variant(**options)
        return original.variant(**options), there.with_stored({f: repairs[f] for f in fields}) if fields else there

    def counters(*variants) -> list[Counter]:
        """Both runs again under each variant's options, those not yet run in one batch: what each shows."""
        keys = [tuple(sorted(options.items())) for options in variants]
        for key in keys:
            if key not in done and ran and key in ran:
                judged(key, *ran[key])
        todo = list(dict.fromkeys(k for k in keys if k not in done))
        jobs = []
        for key in todo:
            here, there = runners(dict(key))
            jobs += [(here, u_original, False, None), (there, u_scaled, False, None)]
        runs = jobs[0][0].run_many(n_steps, jobs) if jobs else []
        for key, run, other in zip(todo, runs[::2], runs[1::2], strict=True):
            judged(key, run, other)
        return [done[k] for k in keys]

    def judged(key, run, other) -> None:
        back = other / factors
        parts = parting(run, back)
        worst = _largest(back - run)
        shows = _shows(parts, worst, verdict_parts, report.max_deviation)  # against the verdict's runs
        rows = len(report.mapped.y)  # the verdict's copy, cut where an engine reset it
        unchanged = back.shape[1:] == report.mapped.y.shape[1:] and np.array_equal(
            back[:rows], report.mapped.y, equal_nan=True
        )
        original_unchanged = run.shape[1:] == report.original.y.shape[1:] and np.array_equal(
            run[:rows], report.original.y, equal_nan=True
        )
        done[key] = Counter(
            shows,
            parts is None,
            worst,
            parts,
            bool(np.array_equal(run, back)),
            bool(unchanged),
            original_unchanged,
            first_broken_row(run),
        )

    t = report.original.t

    if not isinstance(original, CounterRuns):
        return sorted_causes([*causes, *to_show] or [_unknown(report, verdict_parts, bits, ())])
    solver = original.solver_settings()
    diagnosable = isinstance(original, SolverDiagnosis)  # a runner without: no solver to switch, no contact list
    # every counter-run a cause may need, in one batch (MuJoCo's rollout spreads them over the cores)
    variants = {}
    if solver:
        variants["tolerance"] = {"tolerance": 0.0}
    switches = isinstance(original, SwitchesConstraints)  # contacts off, equalities inactive, limits off
    equalities = original.equality_names() if switches else ()
    limited = original.limit_names() if switches else ()  # joints and tendons with a limit
    if diagnosable and original.solver_name() != original.scale_free_solver:
        variants["newton"] = {"solver": original.scale_free_solver}
    if equalities:
        variants["equalities"] = {"inactive_equalities": tuple(range(len(equalities)))}
    if limited:
        variants["limits"] = {"unlimited": tuple(range(len(limited)))}
    if diagnosable and original.uses_native_ccd():
        variants["native_ccd"] = {"native_ccd": False}
    if switches:
        variants["contacts"] = {"contacts": False}
    if clamped:
        variants["velocity_clamp"] = {"velocity_clamp": float("inf")}
    for cause in to_show:
        variants[f"repaired {cause.element}"] = {"repaired": (cause.element,)}
    for cause, options in removable:
        variants[f"removed {cause.element}"] = options

    def shown_causes(base: dict, ref_parts: int, ref_worst: float, besides: str) -> list[tuple[Cause, dict]]:
        """Each cause a counter-run shows with the options of `base` (causes already found) in both runs too:
        (cause, its own options).  It shows one when the runs part later than at step `ref_parts` (the runs
        with `base`), or never, or stay a thousand times closer than `ref_worst`."""

        def relative(counter: Counter) -> Counter:
            return Counter(_shows(counter.parts, counter.worst, ref_parts, ref_worst), *counter[1:])

        def with_base(*options) -> list[Counter]:
            return [relative(c) for c in counters(*(_merged([base, o]) for o in options))]

        also = f" and with {besides} too," if besides else ""

        def shown(counter: Counter) -> str:
            """What a counter-run that shows a cause showed, in words: never "agree" for "nearly"."""
            if counter.exact:
                return f"{also} they are equal bit for bit"
            if counter.restores:
                return (
                    f"{also} they stay within the yardstick (largest deviation {float_text(counter.worst)} "
                    f"instead of {float_text(ref_worst)})"
                )
            if counter.parts > ref_parts:
                return (
                    f"{also} they part later: first at t = {float(t[counter.parts]):.6g} instead of t = "
                    f"{float(t[ref_parts]):.6g}, where another cause takes over"
                )
            return (
                f"{also} they come closer (largest deviation {float_text(counter.worst)} instead of "
                f"{float_text(ref_worst)}) but still part at t = {float(t[counter.parts]):.6g}"
            )

        # the limits' counter-run only where no other restores the run on its own: a humanoid's seventeen limits
        # would cost a run in every diagnosis, to be said at most "brings the runs closer"
        first = {k: v for k, v in variants.items() if k != "limits"}
        results = dict(zip(first, with_base(*first.values()), strict=True)) if first else {}
        if "limits" in variants and not any(c.restores for c in results.values()):
            results["limits"] = with_base(variants["limits"])[0]
        found: list[tuple[Cause, dict]] = []  # each cause a counter-run shows, with its options
        if "tolerance" in results and results["tolerance"].shows:
            names = ", ".join(f"option {k} = {float_text(v)}" for k, v in solver.items())
            found.append(
                (
                    Cause(
                        "solver",
                        names,
                        "a stopping rule of no pure dimension: the scaled run stops after "
                        f"other iterations; with it at 0 in both runs{shown(results['tolerance'])}; load with "
                        f"with_values({', '.join(f'{k}=0' for k in solver)})",
                    ),
                    variants["tolerance"],
                )
            )
        for cause in to_show:  # a number the copy holds wrong: the copy run again with it set right
            counter = results[f"repaired {cause.element}"]
            if counter.shows:
                detail = (
                    f"{cause.detail}; with it set right in the copy (the original's times its factor){shown(counter)}"
                )
                found.append((Cause(cause.kind, cause.element, detail), {"repaired": (cause.element,)}))
        for cause, options in removable:  # a setting the engine ignores: the counter-run that removes its effect
            counter = results[f"removed {cause.element}"]
            if counter.shows:
                words = _in_words(options, original, equalities, limited)
                found.append(
                    (
                        Cause(cause.kind, cause.element, f"{cause.detail}; with {words} in both runs{shown(counter)}"),
                        options,
                    )
                )
        # two numbers held wrong that each part the runs from the same step: set right together, or neither shows
        # (those that change the copy's run at all: one whose copy set right runs the same bits acts on nothing)
        acting = [c for c in to_show if not counters({"repaired": (c.element,)})[0].unchanged]  # alone: round one's
        if len(acting) > 1 and not any("repaired" in o for _c, o in found):
            every = with_base({"repaired": tuple(c.element for c in acting)})[0]
            if every.shows:
                for cause in acting:
                    detail = f"{cause.detail}; with every number the copy holds wrong set right{shown(every)}"
                    found.append((Cause(cause.kind, cause.element, detail), {"repaired": (cause.element,)}))
        newton = results.get("newton")  # only where the runner names its solver (SolverDiagnosis)
        remedy = original.solver_remedy(tolerance_zero=False) if newton is not None else ""
        newton_options = variants.get("newton")
        if newton is not None and not (newton.exact or (newton.shows and not exact_expected)):
            # the solver's own stopping rule may stop it at another iteration too: with it at 0, bit for bit
            zero = {"solver": original.scale_free_solver, "tolerance": 0.0}
            stopped = with_base(zero)[0]
            if stopped.exact or (stopped.shows and not newton.shows):
                newton, remedy, newton_options = stopped, original.solver_remedy(tolerance_zero=True), zero
        if newton is not None and newton.shows:
            found.append(
                (
                    Cause(
                        "solver",
                        f"option solver = {original.solver_name()}",
                        "this solver's iterations are "
                        f"not scale-free; with {original.scale_free_solver}'s in both runs{shown(newton)}: "
                        f"{remedy} to scale it",
                    ),
                    newton_options,
                )
            )
        if "equalities" in results and results["equalities"].shows:  # which of them: each one off alone
            alone = with_base(*({"inactive_equalities": (i,)} for i in range(len(equalities))))
            shows = [i for i, counter in enumerate(alone) if counter.shows]
            named = ", ".join(equalities[i] for i in shows)
            kinds = original.equality_kinds()
            welds = [i for i in (shows or range(len(equalities))) if kinds[i] == "weld"]
            weld = (
                f"; {'it is a weld' if len(shows) == 1 else 'welds among them'}: MuJoCo's approximate weight of a "
                "weld's rotational rows leaves out torquescale squared (a length squared), so their softness is "
                "not the original's times its factor (mujoco_weld_rotational_weight)"
                if welds
                else ""
            )
            cause = Cause(
                "solver",
                named or "the equality constraints together",
                "an equality constraint the solver does not treat scale-free: with "
                f"{'it' if len(shows) == 1 else 'them'} inactive in both runs"
                f"{shown(results['equalities'])}{weld}",
            )
            found.append((cause, {"inactive_equalities": tuple(shows) or tuple(range(len(equalities)))}))
        if "limits" in results and results["limits"].shows:
            # which of them, each one off alone, where all off restore the run: not to say of each of a
            # humanoid's seventeen only that it brings the runs closer
            refine = results["limits"].restores
            alone = with_base(*({"unlimited": (i,)} for i in range(len(limited)))) if refine else []
            shows = [i for i, counter in enumerate(alone) if counter.shows]
            cause = Cause(
                "solver",
                f"the limit of {', '.join(limited[i] for i in shows)}" if shows else "the limits together",
                "a limit (a joint's or tendon's range) whose constraint force the solver does not find "
                f"scale-free: with {'it' if len(shows) == 1 else 'them'} off in both runs{shown(results['limits'])}",
            )
            found.append((cause, {"unlimited": tuple(shows) or tuple(range(len(limited)))}))
        if "velocity_clamp" in results and results["velocity_clamp"].shows:
            _clamp, what = original.velocity_clamp()
            cause = Cause(
                "threshold",
                "velocity clamp",
                f"{what}: a run reaches it, and a clamp on speeds that no scaling changes cuts the copy's at "
                f"another point of its motion; with it lifted in both runs{shown(results['velocity_clamp'])}",
            )
            found.append((cause, variants["velocity_clamp"]))
        if not diagnosable:
            if "contacts" in results and results["contacts"].shows:  # all of them: no pair is named here
                detail = (
                    "the engine's contacts are not computed scale-free: with contacts off in both runs"
                    f"{shown(results['contacts'])}"
                )
                found.append((Cause("contact", "every contact", detail), {"contacts": False}))
            return found
        # a contact is looked for in the runs as `base` leaves them (stepped again with its options)
        pair = runners(base) if base else (original, copy)
        found.extend(
            _contact_causes(*pair, results, shown, with_base, n_steps, ref_parts, u_original, u_scaled, t, model.engine)
        )
        return found

    def found_together() -> list[tuple[Cause, dict]]:
        """Where no counter-run shows a cause alone: the fewest counter-runs that together restore the run (none
        where all of them do not), each shown with the others removed in both runs.  Two causes that part the runs
        from the same step by like amounts hide each other: removing either leaves the other's share (ABB's IRB
        140 in MuJoCo, mesh contacts and the masses the compiler rounds otherwise at s = 4)."""
        kept = list(variants.values())
        if len(kept) < 2 or not counters(_merged(kept))[0].restores:
            return []
        # the broadest dropped first (contacts off, then native CCD, ...), a number the copy holds wrong last: it is
        # a fault of the copy, named even where a broader counter-run covers it too (as _restoring keeps it)
        kept = _fewest(kept, sorted(reversed(kept), key=lambda o: "repaired" in o), lambda o: o, counters)
        out: list[tuple[Cause, dict]] = []
        for options in kept:
            base = _merged(o for o in kept if o is not options)
            if not base:  # one counter-run restores alone after all: the first round would have shown it
                continue
            with_it = counters(base)[0]
            if with_it.parts is None:  # the others restore the run without it after all: it shows nothing more
                continue
            besides = _in_words(base, original, equalities, limited)
            for cause, own in shown_causes(base, with_it.parts, with_it.worst, besides):
                if _merged([base, own]) != base and all(cause != c for c, _o in out):
                    out.append((cause, own))
        return out

    # A cause that parts the runs first hides the others: with it removed, the runs may part later by another
    # that removed alone changed nothing (a weld from the first step, contacts from the third).  So the
    # counter-runs are made again with the causes found removed in both runs, until they restore the run, part
    # no later, or show nothing new.
    found = shown_causes({}, verdict_parts, report.max_deviation, "") or found_together()
    ref_parts, ref_worst = verdict_parts, report.max_deviation
    while found and not any(c.restores for c in counters(*(o for _c, o in found))):  # (alone: as _restoring)
        base = _merged(o for _c, o in found)
        together = counters(base)[0]
        # another round where the causes found moved the parting on: later, or a thousand times closer at the same
        # step (Meta-World's Sawyer with a hammer: the weld inactive leaves 4e-6 from step 1, the contacts' share)
        moved = _shows(together.parts, together.worst, ref_parts, ref_worst)
        if together.restores or together.parts is None or not moved:
            break
        besides = _in_words(base, original, equalities, limited)
        more = [
            (c, o) for c, o in shown_causes(base, together.parts, together.worst, besides) if _merged([base, o]) != base
        ]
        if not more:
            break
        found, ref_parts, ref_worst = [*found, *more], together.parts, together.worst
    # a number held wrong whose counter-run never showed it: where the copy set right runs the very same bits, it
    # does not act on this run and is no cause of it (engines.audit still lists it); else it stays as the audit
    # found it, with what setting it right did
    shown_fields = {f for _c, o in found for f in o.get("repaired", ())}
    for cause in to_show:
        if cause.element in shown_fields:
            continue
        counter = counters({"repaired": (cause.element,)})[0]
        if not counter.unchanged:
            detail = f"{cause.detail}; set right in the copy alone, the run changes but parts no later"
            causes.append(Cause(cause.kind, cause.element, detail))
    # a setting the engine ignores that no counter-run showed: where removing its effect leaves both runs the very
    # same bits (no contact in either run, for a margin), it acts on nothing here (engines.audit still lists it)
    shown_settings = {c.element for c, _o in found}
    for cause, options in removable:
        if cause.element in shown_settings:
            continue
        counter = counters(options)[0]
        if not (counter.unchanged and counter.original_unchanged):
            words = _in_words(options, original, equalities, limited)
            causes.append(
                Cause(
                    cause.kind,
                    cause.element,
                    f"{cause.detail}; with {words} in both runs, the runs change but part no later",
                )
            )
    found = [(_with_constants(c, o, model.engine), o) for c, o in found]
    static = bool(causes)  # the audit's: numbers the copy holds wrong, which no counter-run removes
    # a counter-run whose original breaks down (NaN, infinity) before the verdict's runs part shows nothing: said so
    tried, said_before = [], set()
    for name, options in variants.items():
        key = tuple(sorted(options.items()))
        if key in said_before:  # the same counter-run as one said (a margin's effect removed: contacts off)
            continue
        said_before.add(key)
        counter = done.get(key)
        broken = counter.broken if counter is not None else None
        said = _TRIED.get(name) or (
            f"{name.removeprefix('repaired ')} set right"
            if name.startswith("repaired ")
            else f"{name.removeprefix('removed ')} removed"
        )
        tried.append(
            said
            if broken is None or broken > verdict_parts
            else f"{said} (with it, the original's run breaks down at step {broken}, before the runs part)"
        )
    return sorted_causes([*causes, *_restoring(found, counters, report, verdict_parts, bits, tried, static)])


def _restoring(found, counters, report, verdict_parts, bits, tried, static: bool) -> list[Cause]:
    """The smallest set of the causes found whose counter-runs together restore the run, each marked so.

    A cause whose counter-run restores the run on its own is named alone (a specific one before native
    CCD, and both before contacts off, the broadest), and the others that would do so alone are said in
    its detail: removing two of them at once need not restore the run (with the solver's tolerance at 0
    the scale-free solver may stop one iteration apart).  Else all the counter-runs' options at once:
    when they restore the run, each cause is dropped in turn (the broadest first) whose removal the
    others do not need, and each one kept ``restores``.  When even all of them do not, each is named as
    found (``restores=False``) and, unless the audit named a number the copy holds wrong (`static`), the
    run's parting is a cause of kind ``"unknown"``.

    A number the copy holds wrong that a run showed (set right in the copy, option ``repaired``) is never
    dropped: it is a fault of the copy, even where a broader counter-run (contacts off) covers it too.
    """
    unknown = [] if static else [_unknown(report, verdict_parts, bits, tried)]
    if not found:
        return unknown
    broad = sorted(found, key=lambda f: ("contacts" in f[1], "native_ccd" in f[1]))  # specific ones first
    held_wrong = [f for f in broad if "repaired" in f[1]]
    alone = counters(*(o for _c, o in broad))
    restoring = [f for f, counter in zip(broad, alone, strict=True) if counter.restores]
    if restoring:
        (cause, _o), others = restoring[0], restoring[1:]
        others = [f for f in others if f not in held_wrong]
        partial = [
            f[0].element for f, counter in zip(broad, alone, strict=True) if not (counter.restores or f in held_wrong)
        ]
        also = "".join(
            [
                f"; removed alone, each of these restores it too: {', '.join(c.element for c, _ in others)}"
                if others
                else "",
                f"; removing {', '.join(partial)} alone brings the runs closer or parts them later, but does not "
                "restore them"
                if partial
                else "",
            ]
        )
        # with it removed, the run is restored whatever else is: each number held wrong is named beside it
        return [_marked(cause, True, also), *(_marked(c, True) for c, o in held_wrong if c is not cause)]
    together = counters(_merged(o for _c, o in found))[0]
    if not together.restores:
        # where the runs still part with every cause found removed: that parting, not the first, is unexplained
        later = together.parts if together.parts is not None and together.parts > verdict_parts else None
        unknown = [] if static else [_unknown(report, verdict_parts, bits, tried, later)]
        return [*(_marked(c, False) for c, _o in found), *unknown]
    droppable = [f for f in reversed(broad) if f not in held_wrong]  # the broadest first
    return [_marked(c, True) for c, _o in _fewest(found, droppable, lambda f: f[1], counters)]


#: each counter-run, as the cause that names the runs' parting says it was tried (one per ``variants`` key; a
#: number set right is "FIELD set right", a setting removed "SETTING removed")
_TRIED = {
    "tolerance": "the tolerance at 0",
    "newton": "the scale-free solver",
    "equalities": "the equality constraints inactive",
    "limits": "the limits off",
    "native_ccd": "native CCD off",
    "contacts": "contacts off",
    "velocity_clamp": "the velocity clamp lifted",
}


def _fewest(kept: list, droppable, options, counters) -> list:
    """`kept` less each of `droppable`, in turn, whose counter-run the others' together do not need to restore
    the run (``options(item)``: an item's options); at least one is kept."""
    kept = list(kept)
    for candidate in droppable:
        trial = [k for k in kept if k is not candidate]
        if trial and counters(_merged(options(k) for k in trial))[0].restores:
            kept = trial
    return kept


#: the catalogue's cause path (``engines.constants.CAUSE_PATHS``) of each counter-run's option
_PATHS = {"native_ccd": "native_ccd", "tolerance": "solver_tolerance", "inactive_equalities": "equality"}


def _with_constants(cause: Cause, options: dict, engine: str) -> Cause:
    """The cause with the engine's fixed constants its counter-run's path meets, from the catalogue."""
    return _with_paths(cause, [_PATHS[key] for key in options if key in _PATHS], engine)


def _with_paths(cause: Cause, paths, engine: str) -> Cause:
    """The cause with the engine's fixed constants on some cause paths, from the catalogue."""
    from ..constants import constants_for

    names = list(dict.fromkeys(c.name for p in paths for c in constants_for(engine, p)))
    if not names:
        return cause
    shown = ", ".join(names[:4]) + (f" and {len(names) - 4} more" if len(names) > 4 else "")
    return Cause(cause.kind, cause.element, f"{cause.detail}; the engine's constants on this path: {shown}")


def _merged(options) -> dict:
    """The options of several counter-runs as one: every equality inactive (every geom out of collision) that
    any makes so."""
    out: dict = {}
    for o in options:
        for key, value in o.items():
            many = key in ("inactive_equalities", "contactless_geoms", "unlimited", "repaired")
            out[key] = tuple(sorted(set(out.get(key, ())) | set(value))) if many else value
    return out


def _in_words(options: dict, runner, equalities, limited) -> str:
    """The options of a counter-run in words: ``equality #0 inactive, contacts off``."""
    parts = []
    if "solver" in options:
        parts.append(f"{options['solver']}'s solver")
    if "tolerance" in options:
        parts.append(f"the tolerance at {float_text(options['tolerance'])}")
    if options.get("repaired"):
        parts.append(f"the copy's {', '.join(options['repaired'])} set right")
    if options.get("inactive_equalities"):
        parts.append(f"{', '.join(equalities[i] for i in options['inactive_equalities'])} inactive")
    if options.get("unlimited"):
        parts.append(f"the limit of {', '.join(limited[i] for i in options['unlimited'])} off")
    if "velocity_clamp" in options:
        parts.append("the velocity clamp lifted")
    if options.get("contacts") is False:  # every contact off: the collision paths below with it
        parts.append("contacts off")
    else:
        if options.get("native_ccd") is False:
            parts.append("native CCD off")
        if options.get("contactless_geoms"):
            geoms = ", ".join(runner.element_name("geom_size", g) for g in options["contactless_geoms"])
            parts.append(f"{geoms} out of collision")
    return ", ".join(parts[:-1]) + f" and {parts[-1]}" if len(parts) > 1 else "".join(parts)


def _marked(cause: Cause, restores: bool, also: str = "") -> Cause:
    """The cause with what its counter-run, with the other causes named, did to the run."""
    how = "restores the run" if restores else "does not restore the run"
    return Cause(
        cause.kind, cause.element, f"{cause.detail} (removed with the other causes named, it {how}{also})", restores
    )


def _unknown(report, verdict_parts: int, bits: bool, tried, later: int | None = None) -> Cause:
    """The runs part and no counter-run removes it: where, in which coordinate, and what was tried.

    `later`: the step at which they still part with every cause found removed in both runs, when that is
    later than the verdict's: the first parting is explained, that one is not."""
    t, diff = report.original.t, np.abs(report.mapped.y - report.original.y)
    row = diff[verdict_parts]
    j = int(np.nanargmax(np.where(np.isnan(row), np.inf, row))) if row.size else 0
    name = report.original.states[j]
    how = "differ in a bit" if bits else "leave the yardstick"
    counter = f"; the counter-runs tried ({', '.join(tried)}) do not restore it" if tried else ""
    if later is not None:
        return Cause(
            "unknown",
            f"step {later}",
            f"the runs first {how} at step {verdict_parts} (t = {float(t[verdict_parts]):.6g}), in {name}, "
            f"by the causes above; with all of them removed in both runs they still part at step {later} "
            f"(t = {float(t[later]):.6g}){counter}",
            False,
        )
    return Cause(
        "unknown",
        name,
        f"the runs first {how} at step {verdict_parts} (t = {float(t[verdict_parts]):.6g}), in {name}{counter}",
        False,
    )


#: when the same pairs touch in both runs, each pair's geom gets a counter-run of its own if there are at most
#: this many (besides one per collision function)
CONTACT_CANDIDATES = 6


def _contact_causes(
    original, copy, results, shown, counters, n_steps, verdict_parts, u_original, u_scaled, t, engine: str
):
    """The contact causes a counter-run shows, by geom pair and collision path: (cause, options) each."""
    out = []
    ccd = results.get("native_ccd")
    if ccd is not None and ccd.shows:
        out.append(
            (
                Cause(
                    "contact",
                    "native CCD (convex pairs: meshes, boxes)",
                    "MuJoCo's own convex collision (GJK/EPA, stopped by ccd_tolerance and ccd_iterations) finds "
                    f"other contacts in the scaled run; with it off in both runs{shown(ccd)}: set "
                    '<flag nativeccd="disable"/> in both, or see the hidden constants page',
                ),
                {"native_ccd": False},
            )
        )
    contacts = results["contacts"]
    if not contacts.shows:
        return out
    # a contact can explain the runs' parting only if it differs before they part: after that, other contacts
    # are what parted runs do (and stepping in Python past that point would cost a whole run)
    until = min(n_steps, verdict_parts + 1)
    step, only_scaled, only_original, touched = _contact_steps(original, copy, until, u_original, u_scaled)
    if step is not None:
        pair = (only_scaled or only_original)[0]
        where = "the scaled run only" if only_scaled else "the original only"
        extra = len(only_scaled) + len(only_original) - 1
        more = f" (and {extra} other pair{'s' if extra > 1 else ''})" if extra else ""
        detail = (
            f"in contact in {where} after step {step} (t = {float(t[step]):.6g}){more}: a contact that starts "
            f"or ends at another step; with contacts off in both runs{shown(contacts)}"
        )
        return [*out, (Cause("contact", " / ".join(pair), detail), {"contacts": False})]
    # the same pairs touch at every step before the runs part: the contact computed for some pair is not
    # scale-free.  Counter-runs take out of collision, in both runs, the moving geoms of all pairs that one
    # collision function computes (the path, with the catalogue's constants on it), and, for few pairs, each
    # pair's geom alone
    candidates = original.contact_candidates(touched)
    groups: dict[str, list] = {}
    for candidate in candidates:
        groups.setdefault(candidate[2], []).append(candidate)
    trials = []
    for function, members in groups.items():
        pairs = [pair for _g, pair, _f, _p in members]
        shown_pairs = ", ".join(pairs[:2]) + (f" and {len(pairs) - 2} more" if len(pairs) > 2 else "")
        label = f"{function}: {shown_pairs}" if len(members) > 1 else f"{pairs[0]} ({function})"
        trials.append((label, members[0][3], {"contactless_geoms": tuple(sorted(g for g, *_ in members))}))
    if len(candidates) <= CONTACT_CANDIDATES and len(groups) < len(candidates):
        trials += [
            (f"{pair} ({function})", paths, {"contactless_geoms": (g,)}) for g, pair, function, paths in candidates
        ]
    trials = list({tuple(sorted(o.items())): (label, paths, o) for label, paths, o in reversed(trials)}.values())[::-1]
    # the pairs are those that touch before the runs part: after it, other contacts are what parted runs do
    parted = f"until the runs part (step {verdict_parts}, t = {float(t[verdict_parts]):.6g})"
    for (label, paths, option), counter in zip(trials, counters(*(o for *_, o in trials)), strict=True):
        if counter.shows:
            detail = (
                f"the same pairs touch in both runs {parted}, but the contacts computed here are not "
                f"scale-free: with these contacts off in both runs{shown(counter)}"
            )
            out.append((_with_paths(Cause("contact", label, detail), paths, engine), option))
    touch = "1 pair touches" if len(touched) == 1 else f"{len(touched)} pairs touch"
    everything = f"every contact ({touch} {parted}, alike in both runs)"
    detail = f"the same pairs touch in both runs {parted}; with contacts off in both runs{shown(contacts)}"
    return [*out, (Cause("contact", everything, detail), {"contacts": False})]


def _contact_steps(original, copy, n_steps, u_original, u_scaled):
    """``first_contact_difference`` over the first `n_steps` steps of each run's inputs."""

    def first(rows):
        return None if rows is None else rows[:n_steps]

    return original.first_contact_difference(copy, n_steps, first(u_original), first(u_scaled))


class Counter(NamedTuple):
    """What one counter-run showed: whether its runs part later than the verdict's (or never), whether they
    never part (bit for bit where every factor is a power of two, else within the yardstick), the largest
    deviation, the step at which they first part (None: never), whether they are equal bit for bit, whether
    the copy ran the very bits of the verdict's copy (a number set right in it that does not act on the run) and
    the original the very bits of the verdict's original (with the copy's: what it removes acts on neither run),
    and the step at which the original's run breaks down (a NaN or an infinity; None: never)."""

    shows: bool
    restores: bool
    worst: float
    parts: int | None
    exact: bool
    unchanged: bool = False  # the copy ran the very bits of the verdict's copy
    original_unchanged: bool = False  # the original ran the very bits of the verdict's original
    broken: int | None = None  # the first step at which the original's run holds a NaN or an infinity


def _shows(parts: int | None, worst: float, ref_parts: int, ref_worst: float) -> bool:
    """Whether a counter-run shows a cause against reference runs that part at step `ref_parts` by `ref_worst`:
    its runs part later (or never), or stay a thousand times closer."""
    return parts is None or parts > ref_parts or worst < ref_worst / SHRINK


def _largest(diff: np.ndarray) -> float:
    diff = np.abs(diff)
    return float(diff.max()) if diff.size and np.all(np.isfinite(diff)) else float("inf")
