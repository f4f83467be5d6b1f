"""The white paper's hinged rod in PyBullet and in MuJoCo, and similarity checks of both.

The rod (mass ``m``, length ``l``, hinged at one end, a rotational spring
``k_theta`` with rest angle ``theta_r`` and a damper ``c_theta`` at the
hinge, gravity ``g``) is :func:`pitheorem.models.hinged_rod`; here it is
built in a real engine:

* **PyBullet**: a fixed base with one link on a revolute joint about the
  y axis (so a positive angle turns the rod towards -z, the way gravity
  pulls), the link's centre of mass at ``l/2`` and its inertia set to
  ``m l^2 / 12`` about the centre of mass (so ``m l^2 / 3`` about the
  hinge), no collision shapes.  The default velocity motor is disabled and
  the spring-damper torque ``-k_theta (theta - theta_r) - c_theta omega``
  is applied before every step with ``TORQUE_CONTROL``.  Unless
  ``engine_defaults=True``, the multibody's built-in damping (0.04, see
  :mod:`pitheorem.engines.constants`) is set to zero, sleeping is disabled
  and the joint-speed cap is lifted.
* **MuJoCo**: an MJCF model with one hinge joint carrying ``stiffness``,
  ``springref`` and ``damping``, an explicit ``fullinertia``, contacts
  disabled and angles read in radians (MJCF's default is degrees).

:func:`verify_engine_similarity` runs the engine on the original and on
the scaled parameters (time step scaled with time, or not), maps the
scaled run back to original units (the mapping of
:meth:`pitheorem.Scaling.map_back`) and compares, next to the pure-ODE
answer of :func:`pitheorem.verify_similarity`.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from types import MappingProxyType

import numpy as np

from ..errors import EngineUnavailableError, InvalidRequestError, PiTheoremError
from ..models import hinged_rod
from ..simulation import (
    ModelScaling,
    SimilarityReport,
    Trajectory,
    fixed_steps,
    positive_float,
    similarity_report,
    verify_similarity,
)
from ..simulation import simulate as simulate_ode
from .constants import hidden_constants
from .packages import check_engine, engine_module, quiet_stdout

#: the paper's rod, built once: solving and compiling its equations costs more than a short engine run
_rod_model = functools.cache(hinged_rod)

__all__ = ["DEFAULT_TIME_STEP", "EngineSimilarityReport", "EngineUnavailableError", "simulate_rod",
           "verify_engine_similarity"]

#: each engine's own default time step, as the catalogue of pitheorem.engines.constants has it
DEFAULT_TIME_STEP = MappingProxyType({engine: hidden_constants(engine, names=[name])[0].default
                                      for engine, name in (("pybullet", "bullet_time_step"),
                                                           ("mujoco", "mujoco_timestep"))})

_MUJOCO_INTEGRATORS = ("Euler", "RK4", "implicit", "implicitfast")


# -- the rod in each engine --------------------------------------------------------------------


def _rod_engine(engine) -> str:
    """The engine's one name, if the rod is built in it (PyBullet and MuJoCo; not MJX: load an MJCF file)."""
    engine = check_engine(engine)
    if engine not in DEFAULT_TIME_STEP:
        raise InvalidRequestError(f"the rod is built in 'pybullet' and 'mujoco', not {engine!r}; run an MJCF file "
                                  f"in {engine!r} with engines.load(path, engine={engine!r})", culprit=engine)
    return engine


def _run_bullet(p, y0, dt, n_steps, engine_defaults):
    pb = engine_module("pybullet")
    with quiet_stdout():
        client = pb.connect(pb.DIRECT)
    try:
        m, l, g = p["m"], p["l"], p["g"]  # noqa: E741
        k, c, theta_r = p["k_theta"], p["c_theta"], p["theta_r"]
        i_com = m * l * l / 12.0
        ident = [0.0, 0.0, 0.0, 1.0]
        body = pb.createMultiBody(
            baseMass=0.0, baseCollisionShapeIndex=-1, baseVisualShapeIndex=-1, basePosition=[0.0, 0.0, 0.0],
            linkMasses=[m], linkCollisionShapeIndices=[-1], linkVisualShapeIndices=[-1],
            linkPositions=[[0.0, 0.0, 0.0]], linkOrientations=[ident],
            linkInertialFramePositions=[[l / 2.0, 0.0, 0.0]], linkInertialFrameOrientations=[ident],
            linkParentIndices=[0], linkJointTypes=[pb.JOINT_REVOLUTE], linkJointAxis=[[0.0, 1.0, 0.0]],
            physicsClientId=client,
        )
        # one setting per call: pybullet 3.2.7 applies localInertiaDiagonal to the base instead of the
        # link when it is combined with body-wide settings (damping, activation state) in one call
        pb.changeDynamics(body, 0, jointDamping=0.0, physicsClientId=client)
        if not engine_defaults:
            pb.changeDynamics(body, -1, linearDamping=0.0, angularDamping=0.0, physicsClientId=client)
            pb.changeDynamics(body, -1, activationState=pb.ACTIVATION_STATE_DISABLE_SLEEPING, physicsClientId=client)
            pb.changeDynamics(body, 0, maxJointVelocity=1e30, physicsClientId=client)
        pb.changeDynamics(body, 0, localInertiaDiagonal=[i_com, i_com, i_com], physicsClientId=client)
        got = pb.getDynamicsInfo(body, 0, physicsClientId=client)[2]
        if not np.allclose(got, i_com, rtol=1e-12, atol=0.0):
            raise PiTheoremError(f"pybullet did not take the rod's inertia {i_com!r} (it reports {got!r})")
        pb.setGravity(0.0, 0.0, -g, physicsClientId=client)
        pb.setTimeStep(dt, physicsClientId=client)
        pb.setPhysicsEngineParameter(numSubSteps=0, physicsClientId=client)
        pb.resetJointState(body, 0, float(y0[0]), float(y0[1]), physicsClientId=client)
        pb.setJointMotorControl2(body, 0, pb.VELOCITY_CONTROL, force=0.0, physicsClientId=client)
        out = np.empty((n_steps + 1, 2))
        theta, omega = pb.getJointState(body, 0, physicsClientId=client)[:2]
        out[0] = theta, omega
        for i in range(1, n_steps + 1):
            torque = -k * (theta - theta_r) - c * omega
            pb.setJointMotorControl2(body, 0, pb.TORQUE_CONTROL, force=torque, physicsClientId=client)
            pb.stepSimulation(physicsClientId=client)
            theta, omega = pb.getJointState(body, 0, physicsClientId=client)[:2]
            out[i] = theta, omega
        return out
    finally:
        pb.disconnect(physicsClientId=client)


def rod_mjcf(params: Mapping[str, float], *, dt: float = DEFAULT_TIME_STEP["mujoco"], integrator: str = "Euler") -> str:
    """The MJCF text of the hinged rod for MuJoCo.

    Parameters
    ----------
    params : mapping of str to float
        ``m, l, g, k_theta, c_theta, theta_r`` (all needed).
    dt : float
        MuJoCo's time step.
    integrator : {"Euler", "RK4", "implicit", "implicitfast"}

    Returns
    -------
    str

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines.rod import rod_mjcf
    >>> text = rod_mjcf(pt.models.hinged_rod().defaults)
    >>> 'angle="radian"' in text, 'contact="disable"' in text
    (True, True)
    """
    if integrator not in _MUJOCO_INTEGRATORS:
        raise InvalidRequestError(f"unknown MuJoCo integrator {integrator!r}; use one of {', '.join(_MUJOCO_INTEGRATORS)}")
    missing = [n for n in ("m", "l", "g", "k_theta", "c_theta", "theta_r") if n not in params]
    if missing:
        raise InvalidRequestError(f"rod_mjcf needs parameter {missing[0]!r}")
    m, l, g = (float(params[n]) for n in ("m", "l", "g"))  # noqa: E741
    k, c, theta_r = (float(params[n]) for n in ("k_theta", "c_theta", "theta_r"))
    i_com = m * l * l / 12.0
    return (
        '<mujoco model="hinged_rod">\n'
        '  <compiler angle="radian"/>\n'
        f'  <option timestep="{float(dt)!r}" gravity="0 0 {-g!r}" integrator="{integrator}">\n'
        '    <flag contact="disable"/>\n'
        "  </option>\n"
        "  <worldbody>\n"
        '    <body name="rod">\n'
        f'      <joint name="hinge" type="hinge" axis="0 1 0" stiffness="{k!r}" springref="{theta_r!r}" '
        f'damping="{c!r}"/>\n'
        f'      <inertial pos="{l / 2.0!r} 0 0" mass="{m!r}" fullinertia="{i_com!r} {i_com!r} {i_com!r} 0 0 0"/>\n'
        "    </body>\n"
        "  </worldbody>\n"
        "</mujoco>\n"
    )


def _run_mujoco(p, y0, dt, n_steps, integrator):
    mj = engine_module("mujoco")
    model = mj.MjModel.from_xml_string(rod_mjcf(p, dt=dt, integrator=integrator))
    data = mj.MjData(model)
    data.qpos[0], data.qvel[0] = float(y0[0]), float(y0[1])
    mj.mj_forward(model, data)
    out = np.empty((n_steps + 1, 2))
    out[0] = data.qpos[0], data.qvel[0]
    for i in range(1, n_steps + 1):
        mj.mj_step(model, data)
        out[i] = data.qpos[0], data.qvel[0]
    return out


def simulate_rod(engine: str, params=None, y0=None, t_final: float = 5.0, *, dt: float | None = None,
                 integrator: str | None = None, engine_defaults: bool = False) -> Trajectory:
    """Run the paper's hinged rod in PyBullet or MuJoCo.

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
    dt : float, optional
        Time step; default the engine's own (1/240 s, 0.002 s).
    integrator : str, optional
        MuJoCo only: ``"Euler"`` (its default), ``"RK4"``, ``"implicit"`` or
        ``"implicitfast"``.
    engine_defaults : bool
        Bullet only: keep the multibody's built-in damping, sleeping and
        joint-speed cap instead of switching them off.

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
    engine = _rod_engine(engine)
    if engine == "pybullet" and integrator is not None:
        raise InvalidRequestError("integrator is a MuJoCo option; Bullet always uses semi-implicit Euler")
    if engine == "mujoco" and engine_defaults:
        raise InvalidRequestError("engine_defaults is a Bullet option; the MuJoCo rod has no hidden setting to keep")
    model = _rod_model()
    p = model.resolve_params(params)
    y = model.resolve_initial(y0)
    t_final = positive_float(t_final, "t_final")
    dt = DEFAULT_TIME_STEP[engine] if dt is None else positive_float(dt, "dt")
    n_steps = fixed_steps(t_final, dt)
    if engine == "pybullet":
        states = _run_bullet(p, y, dt, n_steps, engine_defaults)
    else:
        states = _run_mujoco(p, y, dt, n_steps, integrator or "Euler")
    return Trajectory(np.arange(n_steps + 1) * dt, states, model.states, model.time)


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


def verify_engine_similarity(engine: str, scaling, s, params=None, y0=None, t_final: float = 5.0, *,
                             dt: float | None = None, scale_dt: bool = True, tol: float = 1e-9,
                             check: bool = True, integrator: str | None = None, engine_defaults: bool = False,
                             compare_ode: bool = True) -> EngineSimilarityReport:
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
    run = simulate_rod(engine, scaled.scale_params(p), scaled.scale_state(y_init), t_final * f_t, dt=dt_scaled,
                       **opts)
    mapped = scaled.map_back(run, original.t)
    base = similarity_report(original, mapped, s=scaled.s, scaling=scaled.scaling, exponents=scaled.exponents,
                             tol=tol, is_similarity=scaled.is_similarity, method=engine)

    engine_vs_ode, ode_report = None, None
    if compare_ode:
        exact = simulate_ode(model, p, y_init, float(original.t[-1]), t_eval=original.t)
        engine_vs_ode = float(np.abs(exact.y - original.y).max())
        ode_report = verify_similarity(model, scaled.scaling, scaled.s, p, y_init, t_final,
                                       check=check, tol=max(tol, 1e-6))  # of() has refused a non-similarity
    shared = {f.name: getattr(base, f.name) for f in fields(SimilarityReport)}
    shared["scaled_dt"] = not math.isclose(dt, dt_scaled, rel_tol=1e-15, abs_tol=0.0)
    return EngineSimilarityReport(**shared, engine=engine, dt=float(dt), dt_scaled=float(dt_scaled),
                                  engine_vs_ode=engine_vs_ode, ode_report=ode_report)
