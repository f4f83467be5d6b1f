"""Verify a scaled engine model against the original, next to the model's own sensitivity.

:func:`verify` runs the original and the scaled model in their engine step
for step (the scaled time step is the original's times ``s`` to the power
of time), feeds both the same controls in original units, maps every
recorded coordinate of the scaled run back by its own dimension, and
hands both runs to ``pitheorem.simulation.similarity_report``, the one
comparison every simulator of pitheorem shares.  Next to them runs the
original once more with its initial state nudged by one ulp: a chaotic
model (a bouncing ball, a walker falling over) moves that far on its own,
so a scaled run is judged against that baseline, not against zero.

Controls come in two kinds.  Open-loop ``controls`` are a function of time
in original units, converted for the scaled run by each input's dimension.
A closed-loop ``controller`` is built afresh for each run from that run's
own model and works in that model's units: it reads its gains from the
model (an MJCF custom numeric with a declared dimension, say), so a scaled
file carries a scaled controller, and a gain the scaling leaves alone
shows up as a broken similarity (Section 6 of the white paper).

A backend (see ``pitheorem.engines.mjcf``, ``pitheorem.engines.urdf``)
provides ``timestep()``, ``coordinate_dimensions()``,
``control_dimensions()`` and ``run(n_steps, controls, nudge, policy)``; one
that also has ``run_many(n_steps, jobs)`` (MuJoCo's) gets the three
open-loop runs in one batch, which its engine may spread over the cores.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Protocol, runtime_checkable

import numpy as np

from ..errors import InvalidRequestError
from ..exact import read_scale_factor
from ..scaling import float_power
from ..simulation import SimilarityReport, Trajectory, positive_float, similarity_report
from .model import EngineModel, check_scaling, dim

__all__ = ["EngineRunner", "verify"]


@runtime_checkable
class EngineRunner(Protocol):
    """What :func:`verify` needs of an engine: the simulator protocol of MuJoCo's and PyBullet's backends.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.verify import EngineRunner
    >>> isinstance(engines.load(engines.example_path("pendulum.xml")).backend, EngineRunner)
    True
    """

    def timestep(self) -> float:
        """The fixed step of the engine, in the model's units."""

    def coordinate_dimensions(self) -> tuple[list[str], list]:
        """Names and dimensions of the recorded coordinates, in column order."""

    def control_dimensions(self) -> list:
        """The dimension of each control input."""

    def run(self, n_steps: int, controls: Callable | None = None, nudge: bool = False,
            policy: Callable | None = None) -> np.ndarray:
        """Rows of coordinates after 0..n_steps steps; ``nudge`` moves the start by one ulp.

        ``controls(t)`` gives the inputs at time ``t``; ``policy`` is a
        closed-loop law called with the engine's live state (see
        :func:`verify`).
        """


def verify(model: EngineModel, scaling, s, duration: float = 1.0, controls=None, *, controller=None,
           scaled: EngineModel | None = None, baseline_factor: float = 10.0) -> SimilarityReport:
    """Run a model and its scaled copy and compare them in original units.

    Parameters
    ----------
    model : EngineModel
    scaling : Scaling
        A scaling of ``model.system()``.
    s : float
        The scale factor.
    duration : float
        Simulated time of the original run, in its units.
    controls : callable, optional
        ``t -> array`` of actuator inputs in original units (MuJoCo:
        ``data.ctrl``; PyBullet: one torque or force per movable joint).
        Default: zero input.  It is called once per step, at the start
        ``t = i dt`` of step ``i`` of the original run; the scaled run gets
        the same inputs, each times its own factor (its step ``i`` starts at
        the same original time).
    controller : callable, optional
        A closed-loop controller instead of `controls`:
        ``controller(run_model)`` is called once per run (the original, its
        one-ulp nudged twin and the scaled copy) with that run's
        EngineModel and returns a policy giving the inputs at each step in
        that model's own units.  MuJoCo calls ``policy(mjmodel, mjdata)``
        (the arguments of MuJoCo's control callback; return ``data.ctrl``);
        PyBullet calls ``policy(client, body, t)`` (return one torque or
        force per movable joint).  A controller whose numbers live in the
        model file is scaled with it; one whose numbers live in Python is
        not, and the report shows it.
    scaled : EngineModel, optional
        The scaled model (e.g. a saved and reloaded file); default
        ``model.scaled(scaling, s)``.
    baseline_factor : float
        How many times the one-ulp sensitivity a deviation may reach.

    Returns
    -------
    SimilarityReport
        ``.similar``, ``.max_deviation``, ``.deviation`` and
        ``.sensitivity`` per coordinate, the runs as trajectories.

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
    >>> rep = engines.verify(model, sc, s=10, duration=0.5, controls=lambda t: [0.1])
    >>> rep.similar
    True
    """
    if not isinstance(model, EngineModel):
        raise InvalidRequestError(f"verify needs an EngineModel (engines.load(...)), got {type(model).__name__}")
    s = read_scale_factor(s)
    check_scaling(scaling)
    duration = positive_float(duration, "duration")
    if scaled is None:
        scaled = model.scaled(scaling, s)
    elif not isinstance(scaled, EngineModel) or scaled.engine != model.engine:
        raise InvalidRequestError("scaled must be an EngineModel of the same engine as model")
    if controls is not None and controller is not None:
        raise InvalidRequestError("give controls (open loop, a function of time) or controller (closed loop), not both")
    if controller is not None and not callable(controller):
        raise InvalidRequestError(f"controller must be callable (run_model -> policy), got {type(controller).__name__}")
    original, copy = model.backend, scaled.backend

    factor_of, exponent_of = {}, {}  # a model has hundreds of coordinates but a handful of dimensions

    def factor(d):
        if d not in factor_of:
            exponent_of[d] = scaling.exponent_of(d)
            factor_of[d] = float_power(s, exponent_of[d], f"the factor of {d}")
        return factor_of[d]

    f_time = factor(dim("T"))
    dt = original.timestep()
    if not math.isclose(copy.timestep(), dt * f_time, rel_tol=1e-12):
        raise InvalidRequestError(
            f"the scaled model's time step {copy.timestep()!r} is not the original's {dt!r} times {f_time!r}")
    n_steps = max(1, round(duration / dt))
    names, dims = original.coordinate_dimensions()
    if len(copy.coordinate_dimensions()[0]) != len(names):
        raise InvalidRequestError("the scaled model has other coordinates than the original")
    factors = np.array([factor(d) for d in dims])
    control_factors = np.array([factor(d) for d in original.control_dimensions()])

    # open-loop inputs once, at the start of each step in original time; the scaled run gets the same
    # rows times each input's factor (its step i starts at i dt s^a_T, which is original time i dt)
    if controls is None:
        u_original = u_scaled = None
    else:
        u_original = np.empty((n_steps, control_factors.size))
        for i in range(n_steps):
            u = np.asarray(controls(i * dt), dtype=float).reshape(-1)
            if u.shape != control_factors.shape:
                raise InvalidRequestError(f"controls(t) must give {control_factors.size} inputs, got {u.size}")
            u_original[i] = u
        u_scaled = u_original * control_factors

    def policy(run_model):  # a fresh controller per run: controllers keep state (a reel, an integral)
        if controller is None:
            return None
        law = controller(run_model)
        if not callable(law):
            raise InvalidRequestError(f"controller(model) must return a callable policy, got {type(law).__name__}")

        def checked(*state):
            u = np.asarray(law(*state), dtype=float).reshape(-1)
            if u.shape != control_factors.shape:
                raise InvalidRequestError(f"the controller's policy must give {control_factors.size} inputs, "
                                          f"got {u.size}")
            return u

        return checked

    t = np.arange(n_steps + 1) * dt
    if controller is None and hasattr(original, "run_many") and type(copy) is type(original):
        # one batch: the engine may run the three at once (MuJoCo's rollout spreads them over the cores)
        jobs = [(original, u_original, False, None), (original, u_original, True, None), (copy, u_scaled, False, None)]
        run, nudged, scaled_run = original.run_many(n_steps, jobs)
    else:
        run = original.run(n_steps, u_original, policy=policy(model))
        nudged = original.run(n_steps, u_original, nudge=True, policy=policy(model))
        scaled_run = copy.run(n_steps, u_scaled, policy=policy(scaled))
    back = scaled_run / factors
    return similarity_report(
        Trajectory(t, run, tuple(names)), Trajectory(t, back, tuple(names)), s=float(s), scaling=scaling,
        exponents={n: exponent_of[d] for n, d in zip(names, dims, strict=True)},
        nudged=Trajectory(t, nudged, tuple(names)), baseline_factor=baseline_factor, method=model.engine,
    )
