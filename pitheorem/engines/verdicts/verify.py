"""Verify a scaled engine model against the original, next to the model's own sensitivity.

:func:`verify` runs the original and the scaled model in their engine step
for step (the scaled time step is the original's times ``s`` to the power
of time), feeds both the same controls in original units, maps every
recorded coordinate of the scaled run back by its own dimension, and
hands both runs to ``pitheorem.simulation.similarity_report``, the one
comparison every simulator of pitheorem shares.  Next to them run *twins*
of the original: copies in which every number the engine stores for the
model (parameters, compiled values such as mesh vertices and inertias, the
initial pose) is moved by one unit in its own last place, float32 where
the engine keeps float32, with random signs from a fixed seed.  How far
the twins drift from the original is the model's own sensitivity to
rounding, the yardstick a scaled run is judged by: a chaotic model (a
bouncing ball, a walker falling over) moves that far on its own.

At ``s`` a power of four every factor is exact in binary, so a faithful
engine reproduces the original bit for bit (``rep.exact``): a proof.
When a run is not exact where it should be, or not similar, ``verify``
finds out why (``rep.causes``): :func:`pitheorem.engines.audit` holds
every stored number against the original times its factor, and
counter-runs test the dynamic causes: contacts switched off, the
solver's tolerance set to 0.

Controls come in two kinds.  Open-loop ``controls`` are a function of time
in original units, converted for the scaled run by each input's dimension.
A closed-loop ``controller`` is built afresh for each run from that run's
own model and works in that model's units: it reads its gains from the
model (an MJCF custom numeric with a declared dimension, say), so a scaled
file carries a scaled controller, and a gain the scaling leaves alone
shows up as a broken similarity (Section 6 of the white paper).

A backend provides what :class:`~pitheorem.engines.protocols.Runs`
names (``timestep()``, ``coordinate_dimensions()``, ``control_dimensions()``,
``run``, ``run_many`` and ``twin``): the open-loop runs of a verification
go to ``run_many`` in one batch, which MuJoCo spreads over the cores and
MJX runs as one vectorised call.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ...errors import InvalidRequestError
from ...exact import read_count, read_scale_factor
from ...simulation import (
    SimilarityReport,
    Trajectory,
    allowed_deviation,
    first_broken_row,
    positive_float,
    similarity_report,
)
from ..enginemodel import MAX_STEPS, EngineModel, check_scaling
from ..parameters import dim, dimension_factors
from ..protocols import KeepsInputs, MultipliesInPlace, Runs
from .binary import every_factor_a_power_of_two
from .scalefree import scale_free_run
from .strength import Control, caught_or_hidden, control_factors, horizon, unseen_groups

__all__ = [
    "MAX_TWINS",
    "STAGES",
    "Baseline",
    "Plan",
    "Runs",
    "baseline",
    "judge",
    "prepare",
    "smooth_controls",
    "steps_of",
    "verify",
]


def verify(
    model: EngineModel,
    scaling,
    s,
    duration: float = 1.0,
    controls=None,
    *,
    controller=None,
    scaled: EngineModel | None = None,
    baseline_factor: float = 10.0,
    ensemble: int = 3,
    seed: int = 0,
    diagnose: bool = True,
    strength: bool = True,
    baseline: Baseline | None = None,
    keep_inputs: bool = False,
    progress=None,
) -> SimilarityReport:
    """Run a model and its scaled copy, compare them, and say why they differ.

    Parameters
    ----------
    model : EngineModel
    scaling : Scaling
        A scaling of ``model.system()``.
    s : float
        The scale factor.  A power of four (4, 16, 1/4, ...) makes every
        factor exact in binary: the scaled run must then reproduce the
        original bit for bit (``exact``).
    duration : float
        Simulated time of the original run, in its units.
    controls : callable, optional
        ``t -> array`` of actuator inputs in original units (MuJoCo:
        ``data.ctrl``; PyBullet: one torque or force per movable joint).
        Default: zero input (see :func:`smooth_controls` for an input that
        moves the model).  It is called once per step, at the start
        ``t = i dt`` of step ``i`` of the original run; the scaled run gets
        the same inputs, each times its own factor.
    controller : callable, optional
        A closed-loop controller instead of `controls`:
        ``controller(run_model)`` is called once per run with that run's
        EngineModel and returns a policy giving the inputs at each step in
        that model's own units.  MuJoCo calls ``policy(mjmodel, mjdata)``
        with everything in ``mjdata`` (poses, tendon lengths, sensors)
        computed for the state the inputs act on (return ``data.ctrl``);
        PyBullet calls ``policy(client, body, t)``
        (return one torque or force per movable joint).  A controller
        whose numbers live in the model file is scaled with it; one whose
        numbers live in Python is not, and the report shows it.
    scaled : EngineModel, optional
        The scaled model (e.g. a saved and reloaded file); default
        ``model.scaled(scaling, s, keep_inputs=keep_inputs)``.
    baseline_factor : float
        The margin: how many times its yardstick a coordinate's deviation
        may reach (default 10).
    ensemble : int
        How many twins make the yardstick (default 3, at least 1).
    seed : int
        The seed of the twins' random signs.
    diagnose : bool
        Look for causes when the runs are not exact at a power of four or
        not similar, and run the scale-free proof (default True); False
        gives the verdict alone, in the fewest runs.
    strength : bool
        Say how strong the verdict is (default True): the twins'
        ``horizon`` and the ``detection_limit`` of negative controls (the
        copy with gravity times 1 + e for e = 1e-4, 1e-2 and 1, and with
        every mass doubled; see ``pitheorem.engines.verdicts.strength``).
        Each group's smallest error runs in the verdict's batch; its larger
        ones only when that passes unnoticed.  A verdict that cannot see a
        group's error (none of its controls caught: gravity on a
        gravity-compensated arm) is ``inconclusive``, never similar.
    baseline : Baseline, optional
        The original's run and its twins' under the same inputs, from
        ``pitheorem.engines.verdicts.verify.baseline``: they do not
        depend on ``s``, so copies of one model at many scale factors (a
        sweep) run them once.  Open loop only; its duration, inputs,
        ensemble and seed must be these.
    keep_inputs : bool
        Compare with a copy whose inputs keep their values
        (:meth:`~pitheorem.engines.EngineModel.scaled` with
        ``keep_inputs=True``): the scaled run gets the very same inputs,
        and its activations are compared in their inputs' units.
    progress : callable, optional
        ``progress(done, total)``, called as each of its ``STAGES`` (4)
        ends (the copies made, the first batch run, the controls and the
        scale-free proof, the causes).

    Returns
    -------
    SimilarityReport
        ``.exact``, ``.first_divergence``, ``.similar``, ``.excited``,
        ``.causes``, ``.max_deviation``, ``.deviation`` and
        ``.sensitivity`` per coordinate, the runs as trajectories.  Where
        every factor is a power of two and the runs are not bit for bit,
        ``.scale_free`` says whether they are with the settings of no pure
        dimension made scale-free in both (``pitheorem.engines.verdicts.scalefree``;
        with `diagnose`, whose counter-runs reuse its runs).

    Raises
    ------
    InvalidRequestError
        For a bad duration, a scaled model of another engine or size,
        controls of the wrong length, or both `controls` and `controller`.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> proof = engines.verify(model, sc, s=4, duration=0.5, controls=lambda t: [0.1])
    >>> proof.exact, proof.excited
    (True, True)
    >>> rep = engines.verify(model, sc, s=10, duration=0.5, controls=lambda t: [0.1])
    >>> rep.exact, rep.similar, rep.causes
    (False, True, ())
    >>> rep.verdict, rep.detection_limit, rep.horizon
    ('similar', 0.0001, 0.5)
    """
    plan = prepare(
        model,
        scaling,
        s,
        duration,
        controls,
        controller=controller,
        scaled=scaled,
        baseline_factor=baseline_factor,
        ensemble=ensemble,
        seed=seed,
        diagnose=diagnose,
        strength=strength,
        baseline=baseline,
        keep_inputs=keep_inputs,
    )
    step = progress if progress is not None else (lambda done, total: None)
    step(1, STAGES)
    rows = plan.original.run_many(plan.n_steps, plan.jobs()) if plan.batched else None
    step(2, STAGES)
    return judge(plan, rows, step)


#: the stages a verification reports to its `progress`: copies made, first batch run, controls and the
#: scale-free proof, causes
STAGES = 4


@dataclasses.dataclass(frozen=True, eq=False)
class Plan:
    """A verification made ready to run: its inputs checked, its copies made, its first batch of runs named.

    :func:`prepare` makes one and :func:`judge` finishes it with the rows of
    :meth:`jobs` (one ``run_many`` call, or None for closed-loop runs, which
    it runs itself).  A sweep puts the jobs of every ``s`` into one call.
    """

    model: EngineModel
    scaled: EngineModel
    scaling: object
    s: object
    n_steps: int
    names: tuple
    dims: tuple
    factors: np.ndarray
    u_original: np.ndarray | None
    u_scaled: np.ndarray | None
    policy: object
    controller: object
    baseline: Baseline | None
    twins: tuple
    first_rungs: tuple
    later_rungs: tuple
    first: tuple
    t: np.ndarray
    batched: bool
    exponents: dict
    exact_expected: bool
    baseline_factor: float
    ensemble: int
    strength: bool
    diagnose: bool
    keep_inputs: bool = False

    @property
    def original(self):
        return self.model.runner

    @property
    def copy(self):
        return self.scaled.runner

    def jobs(self) -> list:
        """The open-loop runs of the first batch: the original (unless a baseline has it), the copy, the twins
        (unless a baseline has them) and each group's first negative control."""
        return [
            *(() if self.baseline is not None else ((self.original, self.u_original, False, None),)),
            (self.copy, self.u_scaled, False, None),
            *((twin, self.u_original, False, None) for twin in self.twins),
            *((w, self.u_scaled, False, None) for w in self.first),
        ]


def prepare(
    model: EngineModel,
    scaling,
    s,
    duration: float = 1.0,
    controls=None,
    *,
    controller=None,
    scaled: EngineModel | None = None,
    baseline_factor: float = 10.0,
    ensemble: int = 3,
    seed: int = 0,
    diagnose: bool = True,
    strength: bool = True,
    baseline: Baseline | None = None,
    keep_inputs: bool = False,
) -> Plan:
    """The checks and copies of :func:`verify`, its runs not yet run (the arguments are verify's)."""
    if not isinstance(model, EngineModel):
        raise InvalidRequestError(f"verify needs an EngineModel (engines.load(...)), got {type(model).__name__}")
    s = read_scale_factor(s)
    check_scaling(scaling)
    duration = positive_float(duration, "duration")
    baseline_factor = positive_float(baseline_factor, "baseline_factor")
    ensemble = read_count(ensemble, "ensemble", least=1, most=MAX_TWINS)
    seed = read_count(seed, "seed")
    if scaled is None:
        scaled = model.scaled(scaling, s, keep_inputs=keep_inputs)
    elif not isinstance(scaled, EngineModel) or scaled.engine != model.engine:
        raise InvalidRequestError("scaled must be an EngineModel of the same engine as model")
    if controls is not None and controller is not None:
        raise InvalidRequestError("give controls (open loop, a function of time) or controller (closed loop), not both")
    if controller is not None and not callable(controller):
        raise InvalidRequestError(f"controller must be callable (run_model -> policy), got {type(controller).__name__}")
    original, copy = model.runner, scaled.runner
    factor, exponent_of = dimension_factors(scaling, s)

    f_time = factor(dim("T"))
    dt = original.timestep()
    if not math.isclose(copy.timestep(), dt * f_time, rel_tol=1e-12):
        raise InvalidRequestError(
            f"the scaled model's time step {copy.timestep()!r} is not the original's {dt!r} times {f_time!r}"
        )
    n_steps = steps_of(duration, dt)
    names, dims = original.coordinate_dimensions()
    if len(copy.coordinate_dimensions()[0]) != len(names):
        raise InvalidRequestError("the scaled model has other coordinates than the original")
    factors = np.array([factor(d) for d in dims])
    input_dims = list(original.control_dimensions())
    input_factors = np.array([factor(d) for d in input_dims])
    if keep_inputs:  # the same inputs; an activation is in its input's unit, which is kept
        inputs = original.coordinate_inputs() if isinstance(original, KeepsInputs) else [None] * len(factors)
        factors = factors / np.array([1.0 if i is None else input_factors[i] for i in inputs])
        input_factors = np.ones_like(input_factors)
    u_original = _open_loop_rows(controls, n_steps, dt, input_factors.size)
    u_scaled = None if u_original is None else u_original * input_factors
    policy = _policies(controller, input_factors.size)

    if baseline is not None:
        _check_baseline(baseline, n_steps, u_original, ensemble, seed, controller)
    twins = () if baseline is not None else tuple(original.twin(seed + k) for k in range(ensemble))
    # the negative controls: the copy with one group wrong by a known error, judged like the copy itself
    # (none for a file the engine refuses to run: the runs say so).  The inputs that act carry their
    # dimensions into the groups: a motor's force makes the masses matter
    acting = () if u_original is None else [d for d, col in zip(input_dims, u_original.T, strict=True) if col.any()]
    if controller is not None:
        acting = input_dims
    strong = strength and original.refusal is None and copy.refusal is None
    ladder = control_factors(model, acting) if strong else []
    batched = controller is None and type(copy) is type(original)
    # each group's first control (its smallest error) runs in the verdict's batch; a group's others only if it
    # passes unnoticed, for a control caught at a group's smallest error says what the larger ones would
    first_rungs, later_rungs = _rungs(ladder)
    first = (
        tuple(_wrong_copy(model, scaled, g, times, compiled=True) for g, _e, times in first_rungs) if batched else ()
    )
    return Plan(
        model=model,
        scaled=scaled,
        scaling=scaling,
        s=s,
        n_steps=n_steps,
        names=tuple(names),
        dims=tuple(dims),
        factors=factors,
        u_original=u_original,
        u_scaled=u_scaled,
        policy=policy,
        controller=controller,
        baseline=baseline,
        twins=twins,
        first_rungs=tuple(first_rungs),
        later_rungs=tuple(later_rungs),
        first=first,
        t=np.arange(n_steps + 1) * dt,
        batched=batched,
        exponents={n: exponent_of[d] for n, d in zip(names, dims, strict=True)},
        exact_expected=every_factor_a_power_of_two(model, factor),
        baseline_factor=baseline_factor,
        ensemble=ensemble,
        strength=strength,
        diagnose=diagnose,
        keep_inputs=keep_inputs,
    )


def judge(plan: Plan, rows: list | None, progress=None) -> SimilarityReport:
    """Finish a verification: the rows of ``plan.jobs()`` (None: closed loop, run here) compared and judged,
    the controls' larger errors run where needed, the scale-free proof and the causes found."""
    p = plan
    original, copy, model, scaled, n_steps = p.original, p.copy, p.model, p.scaled, p.n_steps
    factors, u_original, u_scaled, policy = p.factors, p.u_original, p.u_scaled, p.policy

    def wrong_runs(rungs):
        """The runs of some controls: in one batch open loop, else one by one with their own policies."""
        wrong = [_wrong_copy(model, scaled, g, times, compiled=p.batched) for g, _e, times in rungs]
        if p.batched:
            return original.run_many(n_steps, [(w, u_scaled, False, None) for w in wrong])
        return [w.runner.run(n_steps, u_scaled, policy=policy(w)) for w in wrong]

    if rows is not None:
        if p.baseline is not None:  # the original's run and its twins' are the baseline's
            rows = [p.baseline.run, *rows[:1], *p.baseline.twins, *rows[1:]]
        run, scaled_run, *rest = rows
        twin_runs, control_runs = rest[: p.ensemble], rest[p.ensemble :]
    else:
        base = p.baseline
        run = base.run if base is not None else original.run(n_steps, u_original, policy=policy(model))
        scaled_run = copy.run(n_steps, u_scaled, policy=policy(scaled))
        twin_runs = (
            list(base.twins)
            if base is not None
            else [twin.run(n_steps, u_original, policy=policy(model)) for twin in p.twins]
        )
        control_runs = wrong_runs(p.first_rungs)

    # A run the engine gave up on (MuJoCo resets an unstable run; NaN elsewhere) is compared only before it:
    # a copy that breaks down at the same step would match its rows bit for bit, and that proves nothing.
    broken = first_broken_row(run)
    cut = len(p.t) if broken is None else max(broken, 1)
    reset = None if broken is None else (float(p.t[broken]), "original")
    if reset is None and (copy_broken := first_broken_row(scaled_run)) is not None:
        reset = (float(p.t[copy_broken]), "copy")
    run, scaled_run = run[:cut], scaled_run[:cut]
    twin_runs, control_runs = [r[:cut] for r in twin_runs], [r[:cut] for r in control_runs]

    def trajectory(values):
        return Trajectory(p.t[:cut], values, p.names)

    report = similarity_report(
        trajectory(run),
        trajectory(scaled_run / factors),
        s=float(p.s),
        scaling=p.scaling,
        exponents=p.exponents,
        twins=[trajectory(r) for r in twin_runs],
        baseline_factor=p.baseline_factor,
        method=model.engine,
    )
    exact_expected = p.exact_expected
    limits = allowed_deviation(report.original, report.sensitivity, p.baseline_factor)

    # a control is caught only beyond the right copy's own deviation (strength.caught): where the engine parts the
    # copy from the original on its own, every wrong copy differs by as much, and that is no error seen
    mapped = scaled_run / factors

    def judged(rungs, rows_of_each):
        out = []
        for (group, error, _f), values in zip(rungs, rows_of_each, strict=True):
            back = values / factors
            seen, hidden = caught_or_hidden(run, back, limits, exact_expected, copy=mapped)
            out.append(Control(group, error, seen, hidden=hidden))
        return out

    controls = judged(p.first_rungs, control_runs)
    unseen = {c.group for c in controls if not c.caught}
    later = [rung for rung in p.later_rungs if rung[0] in unseen]
    if later:
        controls += judged(later, [r[:cut] for r in wrong_runs(later)])
    controls = tuple(sorted(controls, key=lambda c: (c.group != "g", c.error)))
    seen = [c.error for c in controls if c.caught]
    report = dataclasses.replace(
        report,
        horizon=horizon(p.t[:cut], run, twin_runs) if p.strength else None,
        detection_limit=min(seen) if seen else None,
        controls=controls,
        inconclusive=bool(unseen_groups(controls)) or broken is not None,
        engine_reset=reset,
    )
    # no proof and no cause is looked for in a run that is not one (the engine gave up on the original's)
    diagnose = p.diagnose and p.controller is None and broken is None
    ran: dict = {}  # the scale-free runs, by their options: counter-runs the diagnosis need not run again
    if exact_expected and not report.exact and diagnose:
        # the proof of the scaling beside the verdict on the model as written: settings of no pure dimension
        # (the solver's tolerance, a solver whose steps are not scale-free) made scale-free in both runs
        free = scale_free_run(original, copy, n_steps, u_original, u_scaled, factors, p.t, p.names, ran)
        report = dataclasses.replace(report, scale_free=free)
    step = progress if progress is not None else (lambda done, total: None)
    step(3, STAGES)
    if not diagnose or (report.similar and (report.exact or not exact_expected)):
        step(4, STAGES)
        return report
    from .diagnose import find_causes

    causes = find_causes(
        model,
        scaled,
        p.scaling,
        p.s,
        n_steps,
        u_original,
        u_scaled,
        factors,
        report,
        exact_expected,
        ran=ran,
        keep_inputs=p.keep_inputs,
    )
    step(4, STAGES)
    return dataclasses.replace(report, causes=causes)


@dataclasses.dataclass(frozen=True, eq=False)
class Baseline:
    """The original's own runs in a verification, which no scale factor changes: its run and its twins'.

    Make one with ``baseline(...)``; ``verify`` (``baseline=``) and
    :func:`~pitheorem.engines.sweep` then run only the copies.

    Attributes
    ----------
    n_steps : int
        Steps of each run.
    inputs : ndarray or None
        The open-loop inputs, one row per step (None: zero input).
    run : ndarray
        The original's run, one row per sample.
    twins : tuple of ndarray
        The twins' runs, of seeds ``seed``, ``seed + 1``, ...
    seed : int
    """

    n_steps: int
    inputs: np.ndarray | None
    run: np.ndarray
    twins: tuple
    seed: int


def baseline(model: EngineModel, duration: float = 1.0, controls=None, *, ensemble: int = 3, seed: int = 0) -> Baseline:
    """Run a model and its one-ulp twins once, for verifications of its copies at several scale factors.

    Parameters
    ----------
    model : EngineModel
    duration : float
        Simulated time of the runs, in the model's units.
    controls : callable, optional
        ``t -> array`` of inputs, as for :func:`verify`.
    ensemble, seed : int
        The twins, as for :func:`verify`.

    Returns
    -------
    Baseline

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verdicts.verify import baseline
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> u = lambda t: [0.1]
    >>> base = baseline(model, 0.5, u)
    >>> [engines.verify(model, sc, s, duration=0.5, controls=u, baseline=base).verdict for s in (4, 10)]
    ['exact', 'similar']
    """
    if not isinstance(model, EngineModel):
        raise InvalidRequestError(f"baseline needs an EngineModel (engines.load(...)), got {type(model).__name__}")
    duration = positive_float(duration, "duration")
    ensemble = read_count(ensemble, "ensemble", least=1, most=MAX_TWINS)
    seed = read_count(seed, "seed")
    runner = model.runner
    dt = runner.timestep()
    n_steps = steps_of(duration, dt)
    inputs = _open_loop_rows(controls, n_steps, dt, len(runner.control_dimensions()))
    twins = [runner.twin(seed + k) for k in range(ensemble)]
    run, *twin_runs = runner.run_many(n_steps, [(r, inputs, False, None) for r in (runner, *twins)])
    for rows in (run, *twin_runs, *(() if inputs is None else (inputs,))):
        rows.setflags(write=False)  # shared by every verification that reuses it
    return Baseline(n_steps, inputs, run, tuple(twin_runs), seed)


def _check_baseline(base, n_steps: int, inputs, ensemble: int, seed: int, controller) -> None:
    """Refuse a baseline made for other runs than this verification's."""
    if not isinstance(base, Baseline):
        raise InvalidRequestError(f"baseline must come from baseline(...), got {type(base).__name__}")
    if controller is not None:
        raise InvalidRequestError("a baseline holds open-loop runs; a closed-loop controller runs its own")
    same_inputs = (base.inputs is None and inputs is None) or (
        base.inputs is not None and inputs is not None and np.array_equal(base.inputs, inputs)
    )
    if base.n_steps != n_steps or not same_inputs or len(base.twins) != ensemble or base.seed != seed:
        raise InvalidRequestError(
            "the baseline was run for another duration, other inputs or other twins than this verification "
            f"({base.n_steps} steps, {len(base.twins)} twins from seed {base.seed}; this one: {n_steps} steps, "
            f"{ensemble} twins from seed {seed})"
        )


#: the most twins of a yardstick: each is a copy of the model, run in full
MAX_TWINS = 100


def steps_of(duration: float, dt: float) -> int:
    """The steps of a run of `duration` at the model's time step `dt` (at least one), or an error that names both.

    Examples
    --------
    >>> from pitheorem.engines.verdicts.verify import steps_of
    >>> steps_of(1.0, 0.002), steps_of(0.0001, 0.002)
    (500, 1)
    >>> try:
    ...     steps_of(0.02, 1e-320)
    ... except ValueError as err:
    ...     print(str(err)[:75])
    duration 0.02 s at the model's time step 1e-320 s is more than 1e+07 steps:
    """
    if not dt > 0:  # MuJoCo compiles a time step of 0, or below: a run that never advances
        raise InvalidRequestError(f"the model's time step is {dt!r} s: a run needs a positive one")
    steps = duration / dt
    if not steps <= MAX_STEPS:  # NaN and infinity too
        raise InvalidRequestError(
            f"duration {duration!r} s at the model's time step {dt!r} s is more than {MAX_STEPS:.0e} steps: "
            "give a shorter duration, or a model with a longer time step"
        )
    return max(1, round(steps))


def _rungs(ladder: list) -> tuple[list, list]:
    """The controls of the first batch (each group's smallest error) and the others, in the ladder's order."""
    firsts, later, groups = [], [], set()
    for rung in ladder:
        (later if rung[0] in groups else firsts).append(rung)
        groups.add(rung[0])
    return firsts, later


def _wrong_copy(model: EngineModel, scaled: EngineModel, group: str, wrong: dict[str, float], *, compiled: bool):
    """A negative control's copy: the scaled copy with some parameters times a known factor.

    Gravity, or the masses, on a runner that multiplies them in its
    compiled model (:class:`~pitheorem.engines.protocols.MultipliesInPlace`),
    are changed there, not compiled again (``compiled=True``: a runner, for
    a batch).
    Otherwise an EngineModel: made from the original with the copy's
    factors (one compilation) where the copy is ``model.scaled(...)``,
    else from the copy itself.
    """
    if compiled and isinstance(scaled.runner, MultipliesInPlace):
        if set(wrong) == {"g"}:
            return scaled.runner.with_gravity_times(wrong["g"])
        if group == "masses":
            return scaled.runner.with_masses_times(next(iter(wrong.values())))
    origin = scaled.copied_from
    if origin is not None and origin[0] is model:
        factors = dict(origin[1])
        for name, f in wrong.items():
            factors[name] = factors.get(name, 1.0) * f
        made = model.multiplied(**factors)
    else:
        made = scaled.multiplied(**wrong)
    return made.runner if compiled else made


def smooth_controls(model: EngineModel, amplitude: float = 0.3, period: float = 0.5):
    """A smooth open-loop input that moves a model: a sine per actuator.

    The input of actuator ``i`` is ``amplitude * sin(2 pi t / period + i)``,
    times the half-width of its control range where the file limits it
    (about the range's middle), so that a position servo sweeps part of its
    range and a motor pushes with part of its force.  A verdict on a model
    that does not move proves nothing (``rep.excited``).

    Parameters
    ----------
    model : EngineModel
    amplitude : float
        The fraction of each range (or, unlimited, the input itself).
    period : float
        In the model's time unit.

    Returns
    -------
    callable
        ``t -> array`` for :func:`verify`'s `controls`.

    Examples
    --------
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> u = engines.smooth_controls(model)
    >>> [round(float(v), 3) for v in u(0.125)]
    [0.3]
    """
    if not isinstance(model, EngineModel):
        raise InvalidRequestError(f"smooth_controls needs an EngineModel, got {type(model).__name__}")
    amplitude = positive_float(amplitude, "amplitude")
    period = positive_float(period, "period")
    _dims, low, high = model.inputs()
    limited = np.isfinite(low) & np.isfinite(high)
    low, high = np.where(limited, low, 0.0), np.where(limited, high, 0.0)
    middle = np.where(limited, (low + high) / 2, 0.0)
    half = np.where(limited, (high - low) / 2, 1.0)
    phase = np.arange(middle.size)

    def controls(time):
        return middle + amplitude * half * np.sin(2 * np.pi * time / period + phase)

    return controls


def _open_loop_rows(controls, n_steps: int, dt: float, size: int):
    """The open-loop inputs once, at the start of each step in original time (None for zero input).

    The scaled run gets the same rows times each input's factor: its step ``i`` starts at
    ``i dt s^a_T``, which is original time ``i dt``.
    """
    if controls is None:
        return None
    if not callable(controls):
        raise InvalidRequestError(f"controls must be a callable t -> inputs, got {type(controls).__name__}")
    rows = np.empty((n_steps, size))
    for i in range(n_steps):
        u = _numbers(controls(i * dt), size, f"controls(t) at t = {i * dt:.6g}")
        if not np.isfinite(u).all():
            raise InvalidRequestError(f"controls(t) at t = {i * dt:.6g} gave {u.tolist()}: every input must be finite")
        rows[i] = u
    return rows


def _numbers(value, size: int, what: str) -> np.ndarray:
    """`value` as `size` floats, or an error that says what gave what."""
    try:
        u = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise InvalidRequestError(f"{what} must give {size} numbers, got {value!r:.60}") from None
    if u.shape != (size,):
        raise InvalidRequestError(f"{what} must give {size} inputs, got {u.size}")
    return u


def _policies(controller, size: int):
    """``policy(run_model)``: a fresh closed-loop law per run (controllers keep state: a reel, an integral)."""

    def policy(run_model):
        if controller is None:
            return None
        law = controller(run_model)
        if not callable(law):
            raise InvalidRequestError(f"controller(model) must return a callable policy, got {type(law).__name__}")

        def checked(*state):
            return _numbers(law(*state), size, "the controller's policy")

        return checked

    return policy
