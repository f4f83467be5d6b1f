"""Why a scaled run is not exact or not similar: causes found by counter-runs, not guessed.

:func:`pitheorem.engines.verify` calls :func:`find_causes` when a run at a
power of four is not bit for bit the original, or a run is not similar.
Each cause is established, not presumed:

* the static ones by :func:`pitheorem.engines.audit` (numbers the engine
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

import numpy as np

from ..simulation import allowed_deviation
from .audit import audit
from .backend import CounterRuns, SolverDiagnosis
from .causes import Cause, sorted_causes

__all__ = ["find_causes"]


def find_causes(model, scaled, scaling, s, n_steps, u_original, u_scaled, factors, report,
                exact_expected: bool) -> tuple[Cause, ...]:
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
    original, copy = model.backend, scaled.backend
    causes = [c for c in audit(model, scaling, s, scaled=scaled).causes if c.kind != "solver"]
    limits = allowed_deviation(report.original, report.sensitivity, report.baseline_factor)

    def counters(*variants) -> list[tuple[bool, float]]:
        """Both runs again under each variant's options, all in one batch: (agree, largest deviation) each."""
        jobs = []
        for options in variants:
            jobs += [(original.variant(**options), u_original, False, None),
                     (copy.variant(**options), u_scaled, False, None)]
        runs = jobs[0][0].run_many(n_steps, jobs)
        out = []
        for run, other in zip(runs[::2], runs[1::2], strict=True):
            back = other / factors
            if exact_expected:
                agree = bool(np.array_equal(run, back))
            else:
                agree = bool(np.all(np.abs(back - run).max(axis=0) <= limits))
            out.append((agree, _largest(back - run)))
        return out

    def instead() -> str:
        return f"instead of {report.max_deviation:.3g}"

    if not isinstance(original, CounterRuns):
        return sorted_causes(causes)
    solver = original.solver_settings()
    mujoco_like = isinstance(original, SolverDiagnosis)  # PyBullet: no solver to switch, no contact list
    # every counter-run a cause may need, in one batch (MuJoCo's rollout spreads them over the cores)
    variants = {}
    if solver:
        variants["tolerance"] = {"tolerance": 0.0}
    equalities = original.equality_names() if mujoco_like else ()
    if mujoco_like:
        if original.solver_name() != "Newton":
            variants["newton"] = {"solver": "Newton"}
        if equalities:
            variants["equalities"] = {"inactive_equalities": tuple(range(len(equalities)))}
        variants["contacts"] = {"contacts": False}
    results = dict(zip(variants, counters(*variants.values()), strict=True)) if variants else {}

    if "tolerance" in results and results["tolerance"][0]:
        names = ", ".join(f"option {k} = {v:g}" for k, v in solver.items())
        causes.append(Cause("solver", names, "a stopping rule of no pure dimension: the scaled run stops after "
                            "other iterations; with it at 0 in both runs they agree (largest deviation "
                            f"{results['tolerance'][1]:.3g} {instead()}); load with with_values({next(iter(solver))}=0)"))
    if not mujoco_like:
        return sorted_causes(causes)
    newton = results.get("newton")
    if newton is not None and not newton[0]:  # Newton's own stopping rule may stop it at another iteration too
        newton = counters({"solver": "Newton", "tolerance": 0.0})[0]
    if newton is not None and newton[0]:
        causes.append(Cause("solver", f"option solver = {original.solver_name()}", "this solver's iterations are "
                            f"not scale-free; with Newton's in both runs they agree (largest deviation {newton[1]:.3g} "
                            f'{instead()}): load the file with <option solver="Newton"/> to scale it'))
    if "equalities" in results and results["equalities"][0]:  # which of them: each one off alone
        alone = counters(*({"inactive_equalities": (i,)} for i in range(len(equalities))))
        named = ", ".join(name for name, (agree, _) in zip(equalities, alone, strict=True) if agree)
        causes.append(Cause("solver", named or "the equality constraints together", "an equality constraint the "
                            "solver does not treat scale-free (a weld with an offset is one): with it inactive in both "
                            f"runs they agree (largest deviation {results['equalities'][1]:.3g} {instead()})"))
    agree, worst = results["contacts"]
    contact = _contact_difference(original, copy, n_steps, u_original, u_scaled, report.original.t)
    # the same pairs touching throughout, and a solver cause shown: the contacts are only where that solver's
    # iterations act (without contacts there is nothing to iterate on), no cause of their own
    explained = contact is None and any(c.kind == "solver" for c in causes)
    if (contact is not None or agree) and not explained:
        pairs, detail = contact if contact is not None else ("every contact", "the same pairs touch at every step")
        verdict = "agree" if agree else "still differ"
        causes.append(Cause("contact", pairs, f"{detail}; with contacts off in both runs they {verdict} (largest "
                            f"deviation {worst:.3g} {instead()})"))
    return sorted_causes(causes)


def _largest(diff: np.ndarray) -> float:
    diff = np.abs(diff)
    return float(diff.max()) if diff.size and np.all(np.isfinite(diff)) else float("inf")


def _contact_difference(original, copy, n_steps, u_original, u_scaled, t):
    """The first step at which other geom pairs touch in the scaled run: (pairs, detail), or None."""
    found = original.first_contact_difference(copy, n_steps, u_original, u_scaled)
    if found is None:
        return None
    step, only_scaled, only_original = found
    pair = (only_scaled or only_original)[0]
    where = "the scaled run only" if only_scaled else "the original only"
    extra = len(only_scaled) + len(only_original) - 1
    more = f" (and {extra} other pair{'s' if extra > 1 else ''})" if extra else ""
    return " / ".join(pair), (f"in contact in {where} after step {step} (t = {float(t[step]):.6g}){more}: a "
                              "contact that starts or ends at another step")
