"""The proof beside the verdict: both runs again with every setting of no pure dimension made scale-free.

Some engine settings have no pure dimension, so no similarity scaling can
carry them: MuJoCo's solver ``tolerance`` (and ``noslip_tolerance``)
compares a sum of residuals of mixed dimensions with a fixed number, so a
scaled run stops after other iterations; the PGS and CG solvers take
steps that are not invariant under a change of units.  A model that uses
them cannot be bit for bit at a power of four, however right its scaling.

Where every factor is a power of two and the runs as written are not bit
for bit, :func:`scale_free_run` runs the original and the copy again with
those settings made scale-free in both (a tolerance of 0: every
iteration done; the scale-free solver), and says whether the runs are
then exact.  A tolerance of 0 is not the end of it: past convergence the
iterations are rounding noise, and MuJoCo's Newton line search stops an
island's iterations where the norm of its search direction (accelerations
of hinges and slides together) falls under ``mjMINVAL`` = 1e-15
(``mujoco_minval_search`` among the thresholds), which one run meets
and its scaled copy does not.  So, last, where a runner counts its
solver's iterations (:class:`~pitheorem.engines.protocols.CountsIterations`),
both runs are capped at a fixed count of iterations, a pure number: the
most the original takes in a step with its own tolerance, then fewer.  It is a proof *of the scaling*, stated beside the verdict on
the model as written (``rep.scale_free``): the verdict stays what the
model as written does.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...immutable import immutable
from ...simulation import Trajectory, first_divergence
from ..protocols import CounterRuns, CountsIterations, SolverDiagnosis

__all__ = ["ScaleFree", "capped_ways", "scale_free_options", "scale_free_run"]


@immutable
@dataclass(frozen=True, slots=True)
class ScaleFree:
    """Both runs again with the settings of no pure dimension made scale-free.

    Parameters
    ----------
    settings : tuple of (str, str)
        Each setting changed, and its value in both runs
        (``("option tolerance", "0")``, ``("option solver", "Newton")``,
        ``("option iterations", "3")``).
    exact : bool
        Whether the runs are then bit for bit equal (coordinates mapped back).
    first_divergence : tuple of (float, str) or None
        Where they still part: the time and the coordinate.

    Examples
    --------
    >>> from pitheorem.engines.verdicts.scalefree import ScaleFree
    >>> ScaleFree((("option tolerance", "0"),), True, None).text()
    'scale-free: with option tolerance 0 in both runs the copy is bit for bit the original'
    """

    settings: tuple
    exact: bool
    first_divergence: tuple | None

    def text(self) -> str:
        """One line for a report: what was changed, and what the runs then did."""
        changed = ", ".join(f"{name} {value}" for name, value in self.settings)
        if self.exact:
            return f"scale-free: with {changed} in both runs the copy is bit for bit the original"
        t, where = self.first_divergence
        return f"scale-free: with {changed} in both runs the runs still part, first at t = {t:.6g} in {where}"


def scale_free_options(runner) -> list[dict]:
    """The variant options that make a runner's settings of no pure dimension scale-free, each way to try.

    The solver's settings, each alone (the stopping rules at 0; the
    scale-free solver), then together: a solver stopped by a fixed
    tolerance, or a solver whose steps are not scale-free, may each be
    the only cause, and with both changed the scale-free solver may stop
    one iteration apart.  Then, where some pair can collide through it,
    the engine's own convex collision off (MuJoCo's GJK and EPA hold
    lengths against fixed constants), alone and with the solver's
    settings changed too.  Empty where the runner has no such setting.
    The last ways of all, fixed counts of iterations (:func:`capped_ways`),
    need a run to count them, and :func:`scale_free_run` adds them only
    where these fail.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verdicts.scalefree import scale_free_options
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> scale_free_options(model.runner)  # MuJoCo's default tolerance, 1e-8
    [{'tolerance': 0.0}]
    >>> scale_free_options(model.runner.variant(solver="PGS"))
    [{'tolerance': 0.0}, {'solver': 'Newton'}, {'tolerance': 0.0, 'solver': 'Newton'}]
    >>> scale_free_options(model.with_values(tolerance=0).runner)
    []
    """
    if not isinstance(runner, CounterRuns):
        return []
    each = [{"tolerance": 0.0}] if runner.solver_settings() else []
    if isinstance(runner, SolverDiagnosis) and runner.solver_name() != runner.scale_free_solver:
        each.append({"solver": runner.scale_free_solver})
    ways = each if len(each) < 2 else [*each, {k: v for options in each for k, v in options.items()}]
    if isinstance(runner, SolverDiagnosis) and runner.uses_native_ccd():
        # tried after the others, and only where they fail (scale_free_run): another collision path is slow
        # on large meshes, and a run it restores the diagnosis also needs (its native-CCD counter-run)
        ccd = {"native_ccd": False}
        ways += [ccd] if not each else [ccd, {**ways[-1], **ccd}]
    return ways


def capped_ways(original, ways: list[dict], n_steps: int, controls=None) -> list[dict]:
    """The last ways: every setting of `ways` changed, and the solver's iterations capped, each cap a way.

    With the tolerance at 0 nothing stops the solver but its count of
    iterations and its line search's floor on the norm of the search
    direction (``mujoco_minval_search``), which the original and its copy
    meet apart once the iterations are rounding noise.  A fixed count of
    iterations is a pure number: capped at a count that every island
    reaches before its iterations turn to noise, both runs do the same
    iterations.  The caps tried are the most iterations the original takes
    in a step with its own tolerance (and the ways' other settings), then
    that halved, down to 1: the most is what the model as written needs,
    yet its last iterations may be noise already in some island.  Empty
    where the runner does not count its iterations
    (:class:`~pitheorem.engines.protocols.CountsIterations`), where no way
    sets the tolerance to 0, or where the original's solver never runs.

    Parameters
    ----------
    original : Runner
        The original's runner.
    ways : list of dict
        The ways tried before (:func:`scale_free_options`).
    n_steps : int
    controls : ndarray, callable or None
        The original's open-loop inputs.

    Returns
    -------
    list of dict
        The options of each way, ``iterations`` among them, the largest cap first.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verdicts.scalefree import capped_ways, scale_free_options
    >>> model = engines.load(engines.example_path("causes/contact.xml"))  # a box on the floor
    >>> runner = model.runner.variant(tolerance=1e-8)  # the file sets 0
    >>> ways = scale_free_options(runner)
    >>> ways
    [{'tolerance': 0.0}]
    >>> capped_ways(runner, ways, 200)  # one iteration a step with its own tolerance
    [{'tolerance': 0.0, 'iterations': 1}]
    >>> [way["iterations"] for way in capped_ways(model.runner, ways, 200)]  # at 0 it runs all it may
    [100, 50, 25, 12, 6, 3, 1]
    """
    every = {k: v for options in ways for k, v in options.items()}
    if not isinstance(original, CountsIterations) or "tolerance" not in every:
        return []
    own = original.variant(**{k: v for k, v in every.items() if k != "tolerance"})
    cap, caps = own.solver_iterations(n_steps, controls), []
    while cap:
        caps.append(cap)
        cap //= 2
    if caps and caps[-1] != 1:
        caps.append(1)
    return [{**every, "iterations": cap} for cap in caps]


def _parts_later(pair, than) -> bool:
    """Whether the runs of one way part later than another's (or never)."""

    def first_row(run, back):
        differs = np.flatnonzero((run != back).any(axis=1))
        return differs[0] if differs.size else len(run)

    return first_row(*pair) > first_row(*than)


def scale_free_run(
    original, copy, n_steps: int, u_original, u_scaled, factors, t, names, ran: dict | None = None
) -> ScaleFree | None:
    """Run both again under each of :func:`scale_free_options`; None where the runners have no such setting.

    The solver's ways run in one batch; where none of those is bit for
    bit, the collision path's alone, and then, where that parts the runs
    later than the solver's settings did, with every setting changed; and
    where still none is, every setting changed with the solver's
    iterations capped (:func:`capped_ways`: one run of the original to count
    them, then both runs under each cap, the largest first, until one is bit
    for bit or parts the runs no later than the cap before it).  The first
    under which the runs are bit for bit is reported, else the last run
    with where the runs still part.

    Parameters
    ----------
    original, copy : Runner
        The original's runner and its scaled copy's.
    n_steps : int
    u_original, u_scaled : ndarray or None
        The open-loop inputs of each run.
    factors : ndarray
        Each recorded coordinate's factor (the copy's rows are divided by them).
    t : ndarray
        The sample times of the original run.
    names : sequence of str
        The recorded coordinates.
    ran : dict, optional
        Filled with each way's two runs, by its options (sorted items), for
        the diagnosis to reuse as counter-runs.

    Returns
    -------
    ScaleFree or None
    """
    ways = scale_free_options(original)
    if not ways:
        return None
    first = [w for w in ways if "native_ccd" not in w] or ways  # the solver's settings; then the collision path
    rest = ways[len(first) :]
    pairs, tried = [], []  # each way run: (the original's run, the copy's mapped back), and its options

    def run_both(batch):
        """Both runs of every way of `batch`, in one call."""
        jobs = []
        for options in batch:
            jobs += [
                (original.variant(**options), u_original, False, None),
                (copy.variant(**options), u_scaled, False, None),
            ]
        runs = original.run_many(n_steps, jobs)
        for options, mine, its in zip(batch, runs[::2], runs[1::2], strict=True):
            if ran is not None:
                ran[tuple(sorted(options.items()))] = (mine, its)
            pairs.append((mine, its / factors))
            tried.append(options)

    for k, batch in enumerate((first, rest[:1], rest[1:])):
        if not batch or any(np.array_equal(run, back) for run, back in pairs):
            continue
        if k == 2 and not _parts_later(pairs[-1], pairs[len(first) - 1]):
            # the collision path alone parted the runs no later than the solver's settings did: both changed
            # are no nearer, and on a large model (the fruit fly, 10,000 steps a second) its runs are seconds
            break
        run_both(batch)
    if pairs and not any(np.array_equal(run, back) for run, back in pairs):
        # one cap at a time, the largest first: each costs both runs again, so the caps stop at the first that
        # is exact, or at one that parts the runs no later than the runs before it (a cause the iterations do
        # not touch: a contact at MuJoCo's softness floor parts them at step 1 under every cap)
        for options in capped_ways(original, tried, n_steps, u_original):
            before = pairs[-1]
            run_both([options])
            if np.array_equal(*pairs[-1]) or not _parts_later(pairs[-1], before):
                break
    chosen = next((i for i, (run, back) in enumerate(pairs) if np.array_equal(run, back)), len(pairs) - 1)
    options, (run, back) = tried[chosen], pairs[chosen]
    exact = bool(np.array_equal(run, back))
    where = None if exact else first_divergence(Trajectory(t, run, tuple(names)), Trajectory(t, back, tuple(names)))
    zeroed = tuple((f"option {name}", "0") for name in original.solver_settings()) if "tolerance" in options else ()
    solver = (("option solver", options["solver"]),) if "solver" in options else ()
    ccd = (("flag nativeccd", "disable"),) if "native_ccd" in options else ()
    cap = (("option iterations", str(options["iterations"])),) if "iterations" in options else ()
    return ScaleFree(zeroed + solver + ccd + cap, exact, where)
