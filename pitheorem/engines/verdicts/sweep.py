"""Where does similarity hold: one model verified at many scale factors, on every core or on a cluster.

:func:`sweep` asks, for each scale factor ``s`` of a list, what
:func:`~pitheorem.engines.verify` answers at that ``s`` alone: the scaled
copy is built (or refused by the engine's compiler, which is a row too),
its numbers are held against the engine's thresholds
(:func:`~pitheorem.engines.thresholds.crossed`), and the copy is verified
against the original.  The answer is a :class:`Sweep`, whose
:attr:`~Sweep.rows` give per ``s`` the verdict, the largest deviation, the
yardstick, the causes and the thresholds crossed, and whose
:meth:`~Sweep.plot` draws them on one figure.

The verifications are independent, so they run in parallel: on the
machine's cores by default (a process pool of the standard library, its
workers forked from this process, so that each inherits the model as it
is), or on a Dask cluster when ``client=`` is a
``dask.distributed.Client`` (``pip install "pitheorem[cluster]"``).  The
rows come back in the order of ``s`` either way.  A cluster's workers
read the model from its file (a copy without one is saved to a temporary
file first), so the file must be readable there, and the controls must
pickle (Dask pickles closures and lambdas with cloudpickle).

The original's run and its twins' do not depend on ``s``: they run once
(:func:`~pitheorem.engines.verdicts.verify.baseline`), and each ``s``
runs only its copy and its negative controls.  An engine built on JAX
(MJX, float32), and any process that has loaded JAX, does not fork
(:data:`NO_FORK_PACKAGES`); such sweeps, and any with ``workers=1``, run
in this process, where the copies of every ``s`` share one call of the
engine (MJX's vectorised call, MuJoCo Warp's worlds, MuJoCo's rollout
threads): a scaled copy keeps its original's sizes.
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
import warnings
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path

from ...errors import EngineModelError, InvalidRequestError
from ...exact import read_count, read_scale_factor
from ...formatting import TableDisplay, TextDisplay
from ...immutable import immutable
from ...simulation import positive_float
from ..enginemodel import EngineModel, check_scaling
from .causes import Cause

__all__ = ["MAX_WORKERS", "NO_FORK_PACKAGES", "VERDICTS", "Sweep", "SweepRow", "sweep"]

#: the most worker processes a sweep starts on this machine (each loads the engine and the model)
MAX_WORKERS = 1024

#: the verdicts of a row: a report's own (``SimilarityReport.verdict``), or a refusal of the copy
VERDICTS = ("exact", "similar", "not similar", "inconclusive", "refused")

#: the Python packages that do not survive a fork (JAX is multithreaded): an engine that needs one, or a
#: process that has loaded one, runs its sweep in this process
NO_FORK_PACKAGES = ("jax",)


@immutable
@dataclass(frozen=True, slots=True)
class SweepRow(TextDisplay):
    """One scale factor of a :class:`Sweep`: what verify says there.

    Attributes
    ----------
    s : Fraction or float
        The scale factor, as :func:`pitheorem.exact.read_scale_factor`
        reads it.
    verdict : str
        One of ``pitheorem.engines.verdicts.sweep.VERDICTS``.
    max_deviation : float or None
        The largest deviation of the copy, mapped back, from the original,
        in original units; None for a refused copy.
    yardstick : float or None
        The largest spread of the original's one-ulp twins (the report's
        largest ``sensitivity``); None for a refused copy.
    horizon : float or None
        The report's horizon (seconds the twins stay close), where the
        report has one.
    excited : bool or None
        Whether the original moved beyond its yardstick.
    first_divergence : tuple of (float, str) or None
        Where the runs first differ.
    causes : tuple of Cause
        The report's causes; for a refused copy, the refusal.
    thresholds : tuple of str
        The engine thresholds (``pitheorem.engines.thresholds.thresholds``)
        that a number of the copy is beyond, by name.

    Examples
    --------
    >>> from pitheorem.engines import SweepRow
    >>> row = SweepRow(4, "exact", 0.0, 1e-12, None, True, None, (), ())
    >>> print(row)
    s = 4: exact, deviation 0, yardstick 1e-12
    """

    s: object
    verdict: str
    max_deviation: float | None
    yardstick: float | None
    horizon: float | None
    excited: bool | None
    first_divergence: tuple | None
    causes: tuple[Cause, ...]
    thresholds: tuple[str, ...]

    def __post_init__(self) -> None:
        if self.verdict not in VERDICTS:
            raise InvalidRequestError(
                f"unknown verdict {self.verdict!r}; the verdicts are {', '.join(VERDICTS)}", culprit=self.verdict
            )


@immutable
@dataclass(frozen=True, slots=True)
class Sweep(TableDisplay):
    """The answer of :func:`sweep`: one row per scale factor, in the order asked.

    Attributes
    ----------
    model : str
        The model's file ("" for an unsaved copy).
    engine : str
    scaling : Scaling
    duration : float
        Simulated time of each original run, in the model's units.
    rows : tuple of SweepRow
    baseline_factor : float
        The margin of every verdict: how many times its yardstick a
        coordinate's deviation may reach.
    units : mapping of str to str
        The units the model is written in (``{"M": "kg", ...}``).
    fitted_units : mapping of str to str or None
        The units :func:`pitheorem.fit_units` chooses for the engine, or
        None where it was not asked (``fit=False``) or found none.
    fitted_s : float or None
        The ``s`` at which this scaling changes the units as the fit does,
        along the base dimensions the scaling moves (least squares in
        ``log s`` where they disagree); None without a fit or for a scaling
        that moves no base unit.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> sw = engines.sweep(model, sc, s=(1 / 4, 1, 4), duration=0.2, controls=lambda t: [0.1], workers=1, fit=False)
    >>> [float(s) for s in sw.s], sw.verdicts
    ([0.25, 1.0, 4.0], ('exact', 'exact', 'exact'))
    """

    model: str
    engine: str
    scaling: object
    duration: float
    rows: tuple[SweepRow, ...]
    baseline_factor: float = 10.0
    units: Mapping[str, str] = field(default_factory=lambda: {"M": "kg", "L": "m", "T": "s"})
    fitted_units: Mapping[str, str] | None = None
    fitted_s: float | None = None

    @property
    def s(self) -> tuple:
        """The scale factors, in the order of the rows.

        Examples
        --------
        >>> from pitheorem.engines import Sweep, SweepRow
        >>> Sweep("", "mujoco", None, 1.0, (SweepRow(2, "similar", 0.1, 0.1, None, True, None, (), ()),)).s
        (2,)
        """
        return tuple(row.s for row in self.rows)

    @property
    def verdicts(self) -> tuple[str, ...]:
        """The verdicts, in the order of the rows.

        Examples
        --------
        >>> from pitheorem.engines import Sweep, SweepRow
        >>> Sweep("", "mujoco", None, 1.0, (SweepRow(2, "refused", None, None, None, None, None, (), ()),)).verdicts
        ('refused',)
        """
        return tuple(row.verdict for row in self.rows)

    def plot(self, ax=None):
        """Deviation and yardstick against ``s``, verdicts and thresholds.

        See :func:`pitheorem.plotting.plot_sweep`.

        Parameters
        ----------
        ax : matplotlib Axes, optional

        Returns
        -------
        matplotlib.figure.Figure

        Examples
        --------
        >>> from pitheorem.engines import Sweep, SweepRow
        >>> rows = tuple(SweepRow(s, "similar", 1e-9 * s, 1e-10, None, True, None, (), ()) for s in (0.1, 1, 10))
        >>> fig = Sweep("robot.xml", "mujoco", None, 1.0, rows).plot()
        >>> fig.axes[0].get_xscale(), fig.axes[0].get_yscale()
        ('log', 'log')
        """
        from ...plotting import plot_sweep

        return plot_sweep(self, ax=ax)


def sweep(
    model: EngineModel,
    scaling,
    s: Iterable = (1e-3, 1e-2, 0.1, 1, 10, 100, 1e3),
    duration: float = 1.0,
    controls=None,
    engine: str | None = None,
    client=None,
    *,
    workers: int | None = None,
    fit: bool = True,
    progress: Callable[[int, int], None] | None = None,
    baseline_factor: float = 10.0,
    ensemble: int = 3,
    seed: int = 0,
    diagnose: bool = True,
) -> Sweep:
    """Verify a scaling at many scale factors: where similarity holds.

    Parameters
    ----------
    model : EngineModel
        From :func:`pitheorem.engines.load`.
    scaling : Scaling
        A scaling of ``model.system()`` (from :func:`pitheorem.search`).
    s : iterable of float or Fraction
        The scale factors, each read by
        :func:`pitheorem.exact.read_scale_factor`; the rows keep their
        order.  Powers of four give exact verdicts (bit for bit).
    duration : float
        Simulated time of each original run, in the model's units.
    controls : callable, optional
        ``t -> array`` of inputs in original units, as for
        :func:`~pitheorem.engines.verify`; it must pickle for a cluster.
    engine : str, optional
        Run the model's file in this engine instead of its own (an MJCF
        file in ``"mjx"``): ``engines.load(model.path, engine=engine)``.
    client : dask.distributed.Client, optional
        Send the verifications to this Dask cluster.
    workers : int, optional
        Local processes (default: one per core, at most one per ``s``);
        1 runs everything in this process.  Ignored with `client`.
    fit : bool
        Ask :func:`pitheorem.fit_units` for the engine's units, and mark
        them on the figure (default True).
    progress : callable, optional
        ``progress(done, total)``, called as each verification finishes.
    baseline_factor, ensemble, seed, diagnose
        Passed to :func:`~pitheorem.engines.verify` for every ``s``.

    Returns
    -------
    Sweep

    Raises
    ------
    InvalidRequestError
        For something that is no EngineModel, no scaling of it, no scale
        factor, an empty `s`, a bad duration or worker count, or a client
        that is no Dask client.
    EngineUnavailableError
        For a client given where Dask is not installed.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> sw = engines.sweep(model, sc, s=(1e-3, 1, 4, 1e3), duration=0.2, controls=lambda t: [0.1], workers=1)
    >>> print(sw)  # doctest: +ELLIPSIS
    pendulum.xml in mujoco, units of M by 1/s^2, L by s: 4 scale factors, 0.2 s each
    s      verdict  deviation  yardstick  thresholds crossed
    0.001  similar  ...mujoco_minmu
    1      exact    0          ...
    4      exact    0          ...
    1000   similar  ...
    fit_units chooses M = kg, L = m, T = s for mujoco: this scaling reaches them at s = 1
    """
    if not isinstance(model, EngineModel):
        raise InvalidRequestError(f"sweep needs an EngineModel (engines.load(...)), got {type(model).__name__}")
    check_scaling(scaling)
    if engine is not None and engine != model.engine:
        if not model.path:
            raise InvalidRequestError("engine= reads the model's file again; this model has none (save it first)")
        from ..loading import load

        model = load(model.path, engine=engine, units=model.units)
    factors = _read_factors(s)
    duration = positive_float(duration, "duration")
    if controls is not None and not callable(controls):
        raise InvalidRequestError(f"controls must be a callable t -> inputs, got {type(controls).__name__}")
    if workers is not None:
        workers = read_count(workers, "workers", least=1, most=MAX_WORKERS)
    baseline_factor = positive_float(baseline_factor, "baseline_factor")
    from .verify import baseline

    # the original's run and its twins' do not depend on s: run once here, shared by every verification
    base = baseline(model, duration, controls, ensemble=ensemble, seed=seed)
    options = {
        "baseline_factor": baseline_factor,
        "ensemble": ensemble,
        "seed": seed,
        "diagnose": diagnose,
        "baseline": base,
    }
    job = (model, scaling, duration, controls, options)
    report = progress if progress is not None else (lambda done, total: None)
    if client is not None:
        outcomes = _on_cluster(client, job, factors, report)
    else:
        outcomes = _on_this_machine(job, factors, workers, report)
    crossings = _thresholds_crossed(model, scaling, factors)
    rows = tuple(
        SweepRow(f, *outcome, crossing) for f, outcome, crossing in zip(factors, outcomes, crossings, strict=True)
    )
    fitted_units, fitted_s = _fit(model, scaling) if fit else (None, None)
    return Sweep(
        model.path,
        model.engine,
        scaling,
        duration,
        rows,
        baseline_factor,
        dict(model.units),
        fitted_units,
        fitted_s,
    )


def _read_factors(s) -> tuple:
    if isinstance(s, str) or not isinstance(s, Iterable):
        raise InvalidRequestError(f"s must be a sequence of scale factors, got {s!r}", culprit=s)
    factors = tuple(read_scale_factor(v) for v in s)
    if not factors:
        raise InvalidRequestError("s is empty; give at least one scale factor", culprit=s)
    return factors


# -- one verification ------------------------------------------------------------------------


def _outcome(model: EngineModel, scaling, s, duration: float, controls, options: dict) -> tuple:
    """What :func:`verify` says at one ``s``, as the fields of a row after ``s`` and before the thresholds.

    A copy the engine's compiler refuses is a row of its own: verdict ``"refused"``, the refusal its cause.
    """
    from .verify import verify

    copy = _copy_or_refusal(model, scaling, s)
    if isinstance(copy, tuple):
        return copy
    return _fields(verify(model, scaling, s, duration=duration, controls=controls, scaled=copy, **options))


def _copy_or_refusal(model: EngineModel, scaling, s):
    """The scaled copy, or the row of a copy the engine's compiler refuses."""
    try:
        return model.scaled(scaling, s)
    except EngineModelError as err:
        cause = Cause("threshold", err.element or "the scaled copy", f"{model.engine} refuses the copy: {err.reason}")
        return "refused", None, None, None, None, None, (cause,)


def _fields(rep) -> tuple:
    """A report as the fields of a row after ``s`` and before the thresholds."""
    yardstick = max(rep.sensitivity.values(), default=0.0) if rep.sensitivity else 0.0
    horizon = rep.horizon
    return (
        rep.verdict,
        float(rep.max_deviation),
        float(yardstick),
        None if horizon is None else float(horizon),
        rep.excited,
        rep.first_divergence,
        tuple(rep.causes),
    )


def _batched_outcomes(job: tuple, factors: tuple, report) -> list:
    """Every ``s`` in this process, the first batch of each verification in one call of the engine.

    The copies of one model share its sizes, so the engine runs all their first batches (each copy and its
    first negative controls; the original and its twins are the baseline's) at once: MuJoCo's rollout over
    its threads, MJX as one vectorised call, MuJoCo Warp as the worlds of one model.  What a verification
    needs after that (a control's larger errors, the scale-free proof, the causes) runs s by s.
    """
    from .verify import judge, prepare

    model, scaling, duration, controls, options = job
    total = len(factors)
    outcomes: list = [None] * total
    plans = {}
    for k, f in enumerate(factors):
        copy = _copy_or_refusal(model, scaling, f)
        if isinstance(copy, tuple):
            outcomes[k] = copy
        else:
            plans[k] = prepare(model, scaling, f, duration, controls, scaled=copy, **options)
    jobs = [j for plan in plans.values() for j in plan.jobs()] if all(p.batched for p in plans.values()) else []
    rows = model.runner.run_many(next(iter(plans.values())).n_steps, jobs) if jobs else []
    done = total - len(plans)  # the refused copies: done
    if done:
        report(done, total)
    for k, plan in plans.items():
        mine = None
        if jobs:
            size = len(plan.jobs())
            mine, rows = rows[:size], rows[size:]
        outcomes[k] = _fields(judge(plan, mine))
        done += 1
        report(done, total)
    return outcomes


#: the jobs of the sweeps in flight in this process, by key: forked workers inherit them
_SHARED: dict[int, tuple] = {}


def _shared_outcome(key: int, s) -> tuple:
    """In a forked worker: the outcome at ``s`` of the job it inherited under `key`."""
    return _outcome(*_with_s(_SHARED[key], s))


def _with_s(job: tuple, s) -> tuple:
    model, scaling, duration, controls, options = job
    return model, scaling, s, duration, controls, options


def _forks(model: EngineModel) -> bool:
    """Whether this process may fork workers that inherit the model (POSIX, and no JAX loaded)."""
    import multiprocessing

    from ..registry import registered

    needs = registered(model.engine).packages
    return "fork" in multiprocessing.get_all_start_methods() and not any(
        p in needs or p in sys.modules for p in NO_FORK_PACKAGES
    )


def _on_this_machine(job: tuple, factors: tuple, workers: int | None, report) -> list:
    total = len(factors)
    n = min(total, workers if workers is not None else (os.cpu_count() or 1))
    if n <= 1 or not _forks(job[0]):
        return _batched_outcomes(job, factors, report)
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    key = id(job)
    _SHARED[key] = job
    try:
        with warnings.catch_warnings():
            # Python 3.12 and later warn that a fork beside other threads (a notebook's, a test runner's)
            # may deadlock: the workers only verify, in MuJoCo thread pools they make afresh, and take no
            # lock another thread of this process may hold
            warnings.simplefilter("ignore", DeprecationWarning)
            with ProcessPoolExecutor(max_workers=n, mp_context=multiprocessing.get_context("fork")) as pool:
                futures = [pool.submit(_shared_outcome, key, f) for f in factors]
                for done, _ in enumerate(as_completed(futures), 1):
                    report(done, total)
                return [f.result() for f in futures]
    finally:
        del _SHARED[key]


# -- a Dask cluster --------------------------------------------------------------------------

#: the models a cluster worker has read, by recipe: each file is read once per worker process
_READ: dict[tuple, EngineModel] = {}


def _recipe(model: EngineModel) -> tuple:
    """How a worker elsewhere reads the same model: its file (saved first if it has none), engine, units."""
    from ..registry import FORMATS, registered

    path = model.path
    if not path:
        folder = tempfile.mkdtemp(prefix="pitheorem-sweep-")
        written = registered(model.engine).formats[0]  # the format a model of this engine saves as
        suffix = next(f.suffixes[0] for f in FORMATS if f.name == written)
        path = str(model.save(Path(folder) / f"model{suffix}"))
    settings = model.settings()
    options = {"precision": settings["precision"]} if "precision" in settings else {}
    return path, model.engine, tuple(sorted(model.units.items())), tuple(sorted(options.items()))


def _remote_outcome(recipe: tuple, scaling, s, duration: float, controls, options: dict) -> tuple:
    """On a cluster worker: read the model by its recipe (once per worker) and verify it at ``s``."""
    model = _READ.get(recipe)
    if model is None:
        from ..loading import load

        path, engine, units, engine_options = recipe
        model = _READ[recipe] = load(path, engine=engine, units=dict(units), **dict(engine_options))
    return _outcome(model, scaling, s, duration, controls, options)


def _on_cluster(client, job: tuple, factors: tuple, report) -> list:
    try:
        from distributed import Client, as_completed
    except ImportError:
        from ...errors import EngineUnavailableError
        from ..registry import backends

        raise EngineUnavailableError("dask cluster", "distributed", "cluster", backends()) from None
    if not isinstance(client, Client):
        raise InvalidRequestError(f"client must be a dask.distributed.Client, got {type(client).__name__}")
    model, scaling, duration, controls, options = job
    recipe = _recipe(model)
    futures = [
        client.submit(_remote_outcome, recipe, scaling, f, duration, controls, options, pure=False) for f in factors
    ]
    for done, _ in enumerate(as_completed(futures), 1):
        report(done, len(factors))
    return client.gather(futures)


# -- thresholds and units --------------------------------------------------------------------


def _thresholds_crossed(model: EngineModel, scaling, factors: tuple) -> list[tuple[str, ...]]:
    """Per ``s``: the engine thresholds a number of the copy is beyond, by name, in the catalogue's order.

    The copy's numbers are the original's times their factors (what ``model.scaled`` writes), so a copy
    the compiler refuses has its crossings too.
    """
    from ..thresholds import crossed, held_against, thresholds

    table = held_against(model, model.engine)
    precision = model.settings().get("precision", "float32")
    catalogue = thresholds(model.engine)
    out = []
    for s in factors:
        scaled = {}
        for p in table:
            try:
                scaled[p.name] = p.factor(scaling, s)
            except InvalidRequestError:  # a mixed number the scaling splits: model.scaled refuses it too
                continue
        causes = crossed(model.engine, table, scaled, near=1.0, precision=precision)
        out.append(tuple(t.name for t in catalogue if any(f" {t.name} (" in c.detail for c in causes)))
    return out


def _fit(model: EngineModel, scaling) -> tuple[dict | None, float | None]:
    """The units ``pitheorem.fit_units(model, engine=...)`` picks for the model's engine, and the ``s`` that reaches them."""
    from ...errors import PiTheoremError
    from ..fitting import engine_fit, fitted_units

    try:
        fitted = engine_fit(model, engine=model.engine, nice=10)
    except PiTheoremError:
        return None, None
    units = {b: str(u) for b, u in fitted_units(model, fitted).items()}
    moved = {b: float(u) for b, u in (scaling.unit_change or {}).items() if u}
    if not moved:
        return units, None
    # readings of base b are multiplied by s**u_b along the sweep and by f_b in the fitted units
    logs = {b: math.log(float(fitted.factors.get(b, Fraction(1)))) for b in moved}
    log_s = sum(u * logs[b] for b, u in moved.items()) / sum(u * u for u in moved.values())
    return units, math.exp(log_s)
