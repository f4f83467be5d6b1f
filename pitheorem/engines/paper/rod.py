"""The white paper's hinged rod in PyBullet and in MuJoCo, from shipped model files.

The rod (mass ``m``, length ``l``, hinged at one end, a rotational spring
``k_theta`` with rest angle ``theta_r`` and a damper ``c_theta`` at the
hinge, gravity ``g``) is :func:`pitheorem.models.hinged_rod`.  In an engine
it is a model file shipped with pitheorem, loaded by
:func:`pitheorem.engines.load` and run by the engine's backend, as a user's
file is:

* ``hinged_rod.xml`` (MuJoCo): one hinge joint carrying ``stiffness``,
  ``springref`` and ``damping``, an explicit inertia ``m l^2 / 12`` about
  the centre of mass at ``l/2``, contacts disabled, angles in radians;
* ``hinged_rod.urdf`` (PyBullet): a fixed base and one link on a
  continuous joint about the y axis (a positive angle turns the rod towards
  -z, the way gravity pulls) with URDF's joint damping, which PyBullet
  applies.  URDF holds neither a joint spring nor, for a link without
  collision shapes, its inertia: both are in the settings file beside it
  (``hinged_rod.urdf.settings.json``), with the fixed base, gravity, the
  multibody damping switched off and the joint-speed cap lifted.  The
  backend applies the spring as the torque ``-k_theta (theta - theta_r)``
  before every step.

:func:`rod_model` sets the paper's parameters into the numbers of a file
(:func:`rod_file_numbers` says which number each one sets);
:func:`simulate_rod` runs it; :func:`verify_engine_similarity` runs the
original and the scaled parameters (time step scaled with time, or not),
maps the scaled run back to original units (the mapping of
:meth:`pitheorem.Scaling.map_back`) and compares, next to the pure-ODE
answer of :func:`pitheorem.verify_similarity`.  The files themselves
scale like any other: ``engines.verify(engines.load(path), scaling, s)``.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from types import MappingProxyType

import numpy as np

from ...errors import EngineUnavailableError, InvalidRequestError
from ...modelfile import example_path
from ...models import hinged_rod
from ...simulation import (
    ModelScaling,
    SimilarityReport,
    Trajectory,
    fixed_steps,
    positive_float,
    similarity_report,
    verify_similarity,
)
from ...simulation import simulate as simulate_ode
from ..constants import hidden_constants
from ..enginemodel import EngineModel
from ..loading import load
from ..packages import check_engine

#: the paper's rod, built once: solving and compiling its equations costs more than a short engine run
_rod_model = functools.cache(hinged_rod)

__all__ = [
    "DEFAULT_TIME_STEP",
    "ROD_FILES",
    "EngineSimilarityReport",
    "EngineUnavailableError",
    "rod_file_numbers",
    "rod_model",
    "simulate_rod",
    "verify_engine_similarity",
]

#: each engine's own default time step, as the catalogue of pitheorem.engines.constants has it
DEFAULT_TIME_STEP = MappingProxyType(
    {
        engine: hidden_constants(engine, names=[name])[0].default
        for engine, name in (("pybullet", "bullet_time_step"), ("mujoco", "mujoco_timestep"))
    }
)

#: the shipped file of the rod in each engine (in ``pitheorem/examples``)
ROD_FILES = MappingProxyType({"mujoco": "hinged_rod.xml", "pybullet": "hinged_rod.urdf"})

_MUJOCO_INTEGRATORS = ("Euler", "RK4", "implicit", "implicitfast")

#: the joint's coordinate and rate, as each engine's runs name them
_COLUMNS = {"mujoco": ("qpos[hinge]", "qvel[hinge]"), "pybullet": ("q[hinge]", "qdot[hinge]")}


# -- the rod in each engine --------------------------------------------------------------------


def _rod_engine(engine) -> str:
    """The engine's one name, if the rod is built in it (PyBullet and MuJoCo; not MJX: load an MJCF file)."""
    engine = check_engine(engine)
    if engine not in DEFAULT_TIME_STEP:
        raise InvalidRequestError(
            f"the rod is built in 'pybullet' and 'mujoco', not {engine!r}; run an MJCF file "
            f"in {engine!r} with engines.load(path, engine={engine!r})",
            culprit=engine,
        )
    return engine


@functools.cache
def _shipped(engine: str) -> EngineModel:
    """The shipped file of the rod, loaded once (a model never changes)."""
    return load(example_path(ROD_FILES[engine]))


def rod_file_numbers(engine: str, params: Mapping[str, float]) -> dict[str, tuple[float, ...]]:
    """The numbers of the rod's file that the paper's parameters set, by parameter name.

    One parameter of the paper sets several numbers of a file: the length
    ``l`` places the centre of mass at ``l/2``, enters the inertia
    ``m l^2 / 12`` and draws the rod; the others set one number each.

    Parameters
    ----------
    engine : {"mujoco", "pybullet"}
    params : mapping of str to float
        ``m, l, g, k_theta, c_theta, theta_r``, all of them.

    Returns
    -------
    dict of str to tuple of float
        The file's parameter name (as ``model.parameters`` names it) to
        its values.

    Raises
    ------
    InvalidRequestError
        For an engine other than the two, or a missing parameter.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines.paper.rod import rod_file_numbers
    >>> numbers = rod_file_numbers("mujoco", pt.models.hinged_rod().defaults)
    >>> numbers["body_rod_ipos"], numbers["body_rod_inertia"]
    ((1.0, 0.0, 0.0), (0.5, 0.5, 0.5))
    """
    engine = _rod_engine(engine)
    missing = [n for n in ("m", "l", "g", "k_theta", "c_theta", "theta_r") if n not in params]
    if missing:
        raise InvalidRequestError(f"the rod's file needs parameter {missing[0]!r}", culprit=missing[0])
    m, l, g, k, c, theta_r = (float(params[n]) for n in ("m", "l", "g", "k_theta", "c_theta", "theta_r"))  # noqa: E741
    i_com = m * l * l / 12.0
    if engine == "mujoco":
        return {
            "g": (g,),
            "body_rod_mass": (m,),
            "body_rod_ipos": (l / 2.0, 0.0, 0.0),
            "body_rod_inertia": (i_com,) * 3,
            "geom_rod_fromto": (0.0, 0.0, 0.0, l, 0.0, 0.0),
            "joint_hinge_stiffness": (k,),
            "joint_hinge_springref": (theta_r,),
            "joint_hinge_damping": (c,),
        }
    return {
        "g": (g,),
        "link_rod_mass": (m,),
        "link_rod_com": (l / 2.0, 0.0, 0.0),
        "link_rod_ixx": (i_com,),
        "link_rod_iyy": (i_com,),
        "link_rod_izz": (i_com,),
        "link_rod_inertia": (i_com,) * 3,
        "link_rod_visual0_xyz": (l / 2.0, 0.0, 0.0),
        "link_rod_visual0_length": (l,),
        "joint_hinge_damping": (c,),
        "joint_hinge_spring_stiffness": (k,),
        "joint_hinge_spring_rest": (theta_r,),
    }


def _with_numbers(model: EngineModel, numbers: dict[str, tuple[float, ...]]) -> EngineModel:
    """`model` with its parameters set to `numbers`: a number by its value, a vector by its one factor."""
    values, factors = {}, {}
    for name, wanted in numbers.items():
        now = model.parameter(name).value
        if wanted == now:
            continue
        if len(now) == 1:
            values[name] = wanted[0]
            continue
        f = next(w / n for w, n in zip(wanted, now, strict=True) if n != 0)  # the rod's vectors: (x, 0, 0) ...
        factors[name] = f
    if factors:
        model = model.multiplied(**factors)
    return model.with_values(**values) if values else model


def rod_model(
    engine: str, params=None, *, dt: float | None = None, integrator: str | None = None, engine_defaults: bool = False
) -> EngineModel:
    """The rod's shipped file with the paper's parameters set into it, ready to run.

    Parameters
    ----------
    engine : {"pybullet", "mujoco"}
    params : mapping of str to float, optional
        Rod parameters; unlisted ones take the defaults of
        :func:`pitheorem.models.hinged_rod` (the file's own values).
    dt : float, optional
        Time step; default the file's (the engine's own: 1/240 s, 0.002 s).
    integrator : str, optional
        MuJoCo only: ``"Euler"`` (the file's), ``"RK4"``, ``"implicit"``
        or ``"implicitfast"``.
    engine_defaults : bool
        PyBullet only: keep the multibody's built-in damping and joint
        speed cap instead of the settings file's (switched off).

    Returns
    -------
    EngineModel
        An unsaved copy of the shipped file (or the file itself, for its
        own values).

    Raises
    ------
    InvalidRequestError
        For an unknown engine or integrator, an option of the other
        engine, or a bad number.
    EngineUnavailableError
        When the engine's package is not installed.

    Examples
    --------
    >>> from pitheorem.engines.paper.rod import rod_model
    >>> model = rod_model("mujoco", {"l": 1.0})
    >>> model.parameter("body_rod_ipos").value
    (0.5, 0.0, 0.0)
    """
    engine = _rod_engine(engine)
    if engine == "pybullet" and integrator is not None:
        raise InvalidRequestError("integrator is a MuJoCo option; Bullet always uses semi-implicit Euler")
    if engine == "mujoco" and engine_defaults:
        raise InvalidRequestError("engine_defaults is a Bullet option; the MuJoCo rod has no hidden setting to keep")
    if integrator is not None and integrator not in _MUJOCO_INTEGRATORS:
        raise InvalidRequestError(
            f"unknown MuJoCo integrator {integrator!r}; use one of {', '.join(_MUJOCO_INTEGRATORS)}", culprit=integrator
        )
    model = _shipped(engine)
    numbers = rod_file_numbers(engine, _rod_model().resolve_params(params))
    if dt is not None:
        numbers["timestep"] = (positive_float(dt, "dt"),)
    if engine_defaults:  # PyBullet's own multibody damping and joint speed cap, as a URDF loads without settings
        model = model.with_settings(damping=None)
        cap = hidden_constants("pybullet", names=["bullet_max_joint_velocity"])[0].default
        numbers["joint_hinge_maxJointVelocity"] = (cap,)
    model = _with_numbers(model, numbers)
    if integrator not in (None, "Euler"):
        model = EngineModel(model.runner.variant(integrator=integrator), model.engine, "", model.units)
    return model


def simulate_rod(
    engine: str,
    params=None,
    y0=None,
    t_final: float = 5.0,
    *,
    dt: float | None = None,
    integrator: str | None = None,
    engine_defaults: bool = False,
) -> Trajectory:
    """Run the paper's hinged rod in PyBullet or MuJoCo, from its shipped file.

    Parameters
    ----------
    engine : {"pybullet", "mujoco"}
    params : mapping of str to float, optional
        Rod parameters; unlisted ones take the defaults of
        :func:`pitheorem.models.hinged_rod`.
    y0 : mapping or sequence of float, optional
        Initial ``theta`` and ``omega`` (default ``pi/4, 0``).
    t_final : float
        End time; the run takes ``t_final / dt`` steps (rounded up).
    dt, integrator, engine_defaults
        As in :func:`~pitheorem.engines.paper.rod.rod_model`.

    Returns
    -------
    Trajectory
        States ``theta`` and ``omega`` after every step.

    Raises
    ------
    EngineUnavailableError
        When the engine's package is not installed.
    InvalidRequestError
        For an unknown engine or integrator, or a bad number.

    Examples
    --------
    >>> from pitheorem.engines import simulate_rod
    >>> tr = simulate_rod("mujoco", t_final=0.01)
    >>> len(tr)
    6
    """
    model = rod_model(engine, params, dt=dt, integrator=integrator, engine_defaults=engine_defaults)
    rod = _rod_model()
    y = rod.resolve_initial(y0)
    t_final = positive_float(t_final, "t_final")
    dt = model.timestep()
    n_steps = fixed_steps(t_final, dt)
    names = model.coordinates()[0]
    columns = [names.index(c) for c in _COLUMNS[model.engine]]
    first = model.run(0)[0]
    first[columns] = y
    states = model.run(n_steps, initial=first)[:, columns]
    return Trajectory(np.arange(n_steps + 1) * dt, states, rod.states, rod.time)


@dataclass(frozen=True, eq=False)
class EngineSimilarityReport(SimilarityReport):
    """Result of :func:`verify_engine_similarity`, with the engine's details.

    A :class:`pitheorem.SimilarityReport` and more.  The comparison itself is ``pitheorem.simulation.similarity_report``,
    shared with :func:`pitheorem.verify_similarity` and
    :func:`pitheorem.engines.verify`; this subclass only adds what the
    rod's engine runs know besides.

    Attributes
    ----------
    engine : str
    dt, dt_scaled : float
        Time step of the original and of the scaled run.
    engine_vs_ode : float or None
        Largest difference between the engine's original run and the exact
        ODE solution (scipy, tight tolerances): the engine's own error.
    ode_report : SimilarityReport or None
        :func:`pitheorem.verify_similarity` on the same request (pure ODE).

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines import EngineSimilarityReport
    >>> issubclass(EngineSimilarityReport, pt.SimilarityReport)
    True
    """

    engine: str = ""
    dt: float = math.nan
    dt_scaled: float = math.nan
    engine_vs_ode: float | None = None
    ode_report: SimilarityReport | None = field(default=None, repr=False)


def verify_engine_similarity(
    engine: str,
    scaling,
    s,
    params=None,
    y0=None,
    t_final: float = 5.0,
    *,
    dt: float | None = None,
    scale_dt: bool = True,
    tol: float = 1e-9,
    check: bool = True,
    integrator: str | None = None,
    engine_defaults: bool = False,
    compare_ode: bool = True,
) -> EngineSimilarityReport:
    """Check in a real engine that a scaled rod reproduces the original.

    Runs the rod in `engine` with `params`, then with the parameters
    scaled (as ``scaling.apply(params, s)`` scales them), the initial state and end time scaled,
    and the time step multiplied by ``s^(a_t)`` (``scale_dt=True``) or kept;
    maps the scaled run back to original units and compares step by step
    (interpolating when the grids differ).

    Parameters
    ----------
    engine : {"pybullet", "mujoco"}
    scaling : Scaling or mapping of str to number
        As in :func:`pitheorem.verify_similarity`, for the system of
        :func:`pitheorem.models.hinged_rod`.
    s : float
        Scale factor.
    params, y0, t_final, dt, integrator, engine_defaults
        As in :func:`simulate_rod`, for the original run.
    scale_dt : bool
        Scale the time step with time (default) or keep the engine's.
    tol : float
        Largest deviation that passes.
    check : bool
        With ``False`` a dict that is not a similarity scaling is applied
        as given (to show wrong scalings).
    compare_ode : bool
        Also run :func:`pitheorem.verify_similarity` and measure the
        engine's error against the exact ODE.

    Returns
    -------
    EngineSimilarityReport

    Raises
    ------
    EngineUnavailableError, InvalidRequestError, SystemMismatchError

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines import verify_engine_similarity
    >>> rod = pt.models.hinged_rod()
    >>> sc = pt.search(rod.system, scale={"g": 1}).scalings[0]   # time-free
    >>> rep = verify_engine_similarity("pybullet", sc, s=2, t_final=1.0)
    >>> rep.passed
    True
    """
    engine = _rod_engine(engine)
    model = _rod_model()
    scaled = ModelScaling.of(model, scaling, s, check=check)
    tol = positive_float(tol, "tol")
    p = model.resolve_params(params)
    y_init = model.resolve_initial(y0)
    t_final = positive_float(t_final, "t_final")
    dt = DEFAULT_TIME_STEP[engine] if dt is None else positive_float(dt, "dt")
    opts = {"integrator": integrator, "engine_defaults": engine_defaults}
    original = simulate_rod(engine, p, y_init, t_final, dt=dt, **opts)

    f_t = scaled.factor(model.time)
    dt_scaled = dt * f_t if scale_dt else dt
    run = simulate_rod(engine, scaled.scale_params(p), scaled.scale_state(y_init), t_final * f_t, dt=dt_scaled, **opts)
    mapped = scaled.map_back(run, original.t)
    base = similarity_report(
        original,
        mapped,
        s=scaled.s,
        scaling=scaled.scaling,
        exponents=scaled.exponents,
        tol=tol,
        is_similarity=scaled.is_similarity,
        method=engine,
    )

    engine_vs_ode, ode_report = None, None
    if compare_ode:
        exact = simulate_ode(model, p, y_init, float(original.t[-1]), t_eval=original.t)
        engine_vs_ode = float(np.abs(exact.y - original.y).max())
        ode_report = verify_similarity(
            model, scaled.scaling, scaled.s, p, y_init, t_final, check=check, tol=max(tol, 1e-6)
        )  # of() has refused a non-similarity
    shared = {f.name: getattr(base, f.name) for f in fields(SimilarityReport)}
    shared["scaled_dt"] = not math.isclose(dt, dt_scaled, rel_tol=1e-15, abs_tol=0.0)
    return EngineSimilarityReport(
        **shared,
        engine=engine,
        dt=float(dt),
        dt_scaled=float(dt_scaled),
        engine_vs_ode=engine_vs_ode,
        ode_report=ode_report,
    )
