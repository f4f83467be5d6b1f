"""Why a scaled run is not exact or not similar: causes found by counter-runs, not guessed.

:func:`pitheorem.engines.verdicts.verify` calls :func:`find_causes` when a run at a
power of four is not bit for bit the original, or a run is not similar.
Each cause is established, not presumed:

* the static ones by :func:`pitheorem.engines.verdicts.audit` (numbers the engine
  holds that are not the original times their factor, float32 rounding,
  settings the engine ignores);
* ``solver``: the original and the scaled copy run again with the
  solver's tolerance at 0 (every iteration done); it is a cause when
  the pair then agrees (bit for bit at a power of four, or within the
  yardstick) where it did not;
* ``solver`` too: an equality constraint the solver does not treat
  scale-free (a weld with an offset), found by running both with the
  equality constraints inactive, then each one alone inactive;
* ``contact``: the geom pairs in contact after each step, in the original
  and in the scaled run; the first step where they differ is named, and a
  counter-run with contacts switched off says whether the difference goes
  with them.  When the same pairs touch throughout and a solver cause is
  shown, the contacts are only where that solver iterates: no cause.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from pitheorem.formatting.pieces import float_text

from ...simulation import allowed_deviation
from ..protocols import CounterRuns, SolverDiagnosis
from .audit import audit
from .causes import Cause, sorted_causes

__all__ = ["find_causes"]


def find_causes(
    model, scaled, scaling, s, n_steps, u_original, u_scaled, factors, report, exact_expected: bool
) -> tuple[Cause, ...]:
    """The causes of a verdict that is not exact (at a power of four) or not similar.

    Parameters
    ----------
    model, scaled : EngineModel
        The original and its scaled copy.
    scaling, s
        As given to :func:`pitheorem.engines.verdicts.verify`.
    n_steps : int
    u_original, u_scaled : ndarray or None
        The open-loop inputs of each run, one row per step.
    factors : ndarray
        Each recorded coordinate's factor.
    report : SimilarityReport
        The verdict to explain.
    exact_expected : bool
        Whether every factor is a power of two (the runs should be bit for bit equal).

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
    causes = [c for c in audit(model, scaling, s, scaled=scaled).causes if c.kind != "solver"]
    limits = allowed_deviation(report.original, report.sensitivity, report.baseline_factor)

    # Where the runs first part: the first step at which they differ in a bit, when every factor is exact
    # and the verdict was similar (a difference in any bit is then the thing to explain), else the first
    # step at which a coordinate leaves the yardstick.  A counter-run shows a cause when, with the
    # candidate removed from both runs, they never part, or part later than the verdict's runs do: a
    # model with two causes is not repaired by removing one, but its first difference moves.
    bits = exact_expected and report.similar

    def parting(run: np.ndarray, back: np.ndarray) -> int | None:
        with np.errstate(invalid="ignore"):
            off = (run != back) if bits else ~(np.abs(back - run) <= limits)  # a NaN parts
        rows = np.nonzero(off.any(axis=1))[0]
        return int(rows[0]) if rows.size else None

    verdict_parts = parting(report.original.y, report.mapped.y)

    def counters(*variants) -> list[Counter]:
        """Both runs again under each variant's options, all in one batch: what each shows."""
        jobs = []
        for options in variants:
            jobs += [
                (original.variant(**options), u_original, False, None),
                (copy.variant(**options), u_scaled, False, None),
            ]
        runs = jobs[0][0].run_many(n_steps, jobs)
        out = []
        for run, other in zip(runs[::2], runs[1::2], strict=True):
            back = other / factors
            parts = parting(run, back)
            later = parts is None or (verdict_parts is not None and parts > verdict_parts)
            out.append(Counter(later, parts is None, _largest(back - run), parts, bool(np.array_equal(run, back))))
        return out

    t = report.original.t

    def shown(counter: Counter) -> str:
        """What a counter-run that shows a cause showed, in words."""
        if counter.agree:
            return f"they agree (largest deviation {counter.worst:.3g} instead of {report.max_deviation:.3g})"
        return (
            f"they part later: first at t = {float(t[counter.parts]):.6g} instead of t = "
            f"{float(t[verdict_parts]):.6g}, where another cause takes over"
        )

    if not isinstance(original, CounterRuns):
        return sorted_causes(causes)
    solver = original.solver_settings()
    diagnosable = isinstance(original, SolverDiagnosis)  # a runner without: no solver to switch, no contact list
    # every counter-run a cause may need, in one batch (MuJoCo's rollout spreads them over the cores)
    variants = {}
    if solver:
        variants["tolerance"] = {"tolerance": 0.0}
    equalities = original.equality_names() if diagnosable else ()
    if diagnosable:
        if original.solver_name() != original.scale_free_solver:
            variants["newton"] = {"solver": original.scale_free_solver}
        if equalities:
            variants["equalities"] = {"inactive_equalities": tuple(range(len(equalities)))}
        variants["contacts"] = {"contacts": False}
    results = dict(zip(variants, counters(*variants.values()), strict=True)) if variants else {}

    if "tolerance" in results and results["tolerance"].shows:
        names = ", ".join(f"option {k} = {float_text(v)}" for k, v in solver.items())
        causes.append(
            Cause(
                "solver",
                names,
                "a stopping rule of no pure dimension: the scaled run stops after "
                f"other iterations; with it at 0 in both runs {shown(results['tolerance'])}; load with "
                f"with_values({', '.join(f'{k}=0' for k in solver)})",
            )
        )
    if not diagnosable:
        return sorted_causes(causes)
    newton, remedy = results.get("newton"), original.solver_remedy(tolerance_zero=False)
    if newton is not None and not (newton.exact or (newton.shows and not exact_expected)):
        # Newton's own stopping rule may stop it at another iteration too: with it at 0, bit for bit at s = 4
        stopped = counters({"solver": original.scale_free_solver, "tolerance": 0.0})[0]
        if stopped.exact or (stopped.shows and not newton.shows):
            newton, remedy = stopped, original.solver_remedy(tolerance_zero=True)
    if newton is not None and newton.shows:
        causes.append(
            Cause(
                "solver",
                f"option solver = {original.solver_name()}",
                "this solver's iterations are "
                f"not scale-free; with {original.scale_free_solver}'s in both runs {shown(newton)}: "
                f"{remedy} to scale it",
            )
        )
    if "equalities" in results and results["equalities"].shows:  # which of them: each one off alone
        alone = counters(*({"inactive_equalities": (i,)} for i in range(len(equalities))))
        named = ", ".join(name for name, counter in zip(equalities, alone, strict=True) if counter.shows)
        causes.append(
            Cause(
                "solver",
                named or "the equality constraints together",
                "an equality constraint the "
                "solver does not treat scale-free (a weld with an offset is one): with it inactive in both "
                f"runs {shown(results['equalities'])}",
            )
        )
    contacts = results["contacts"]
    # a contact can explain the runs' parting only if it differs before they part: after that, other contacts
    # are what parted runs do (and stepping in Python past that point would cost a whole run)
    until = n_steps if verdict_parts is None else min(n_steps, verdict_parts + 1)
    contact = _contact_difference(original, copy, until, u_original, u_scaled, t)
    # the same pairs touching throughout, and a solver cause shown: the contacts are only where that solver's
    # iterations act (without contacts there is nothing to iterate on), no cause of their own
    explained = contact is None and any(c.kind == "solver" for c in causes)
    if (contact is not None or contacts.shows) and not explained:
        pairs, detail = contact if contact is not None else ("every contact", "the same pairs touch at every step")
        verdict = (
            shown(contacts)
            if contacts.shows
            else (f"they still differ (largest deviation {contacts.worst:.3g} instead of {report.max_deviation:.3g})")
        )
        causes.append(Cause("contact", pairs, f"{detail}; with contacts off in both runs {verdict}"))
    return sorted_causes(causes)


class Counter(NamedTuple):
    """What one counter-run showed: whether its runs part later than the verdict's (or never), whether they
    never part, the largest deviation, the step at which they first part (None: never), and whether they
    are equal bit for bit."""

    shows: bool
    agree: bool
    worst: float
    parts: int | None
    exact: bool


def _largest(diff: np.ndarray) -> float:
    diff = np.abs(diff)
    return float(diff.max()) if diff.size and np.all(np.isfinite(diff)) else float("inf")


def _contact_difference(original, copy, n_steps, u_original, u_scaled, t):
    """The first step at which other geom pairs touch in the scaled run: (pairs, detail), or None."""

    def first(rows):
        return None if rows is None else rows[:n_steps]

    found = original.first_contact_difference(copy, n_steps, first(u_original), first(u_scaled))
    if found is None:
        return None
    step, only_scaled, only_original = found
    pair = (only_scaled or only_original)[0]
    where = "the scaled run only" if only_scaled else "the original only"
    extra = len(only_scaled) + len(only_original) - 1
    more = f" (and {extra} other pair{'s' if extra > 1 else ''})" if extra else ""
    return " / ".join(pair), (
        f"in contact in {where} after step {step} (t = {float(t[step]):.6g}){more}: a "
        "contact that starts or ends at another step"
    )
