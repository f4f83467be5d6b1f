"""Hidden dimensional constants of physics engines, and searches that hold them fixed.

Every engine carries numbers that users rarely set: a default time step, a
collision margin, sleep thresholds, constraint time constants.  Each has a
dimension, and a scaled model is only similar to the original if every such
constant scales like its dimension demands.  An engine that keeps them at
their defaults silently holds them *fixed*: this module lists them
(:data:`CATALOGUE`), adds them to a :class:`~pitheorem.System`
(:func:`with_hidden_constants`), searches with them held fixed
(:func:`engine_search`), and names the ones a given scaling breaks
(:func:`broken_constants`).

Nothing here imports an engine; the values were read from the sources named
in each entry (and, where stated, measured with pybullet 3.2.7 and mujoco
4.0.0).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from fractions import Fraction

from ..dimensions import Dimension
from ..errors import DuplicateVariableError, InvalidRequestError, UnknownVariableError
from ..immutable import immutable
from ..scalesearch import SearchResult, search
from ..scaling import Scaling
from ..system import System

__all__ = [
    "CATALOGUE",
    "ENGINES",
    "HiddenConstant",
    "broken_constants",
    "engine_search",
    "hidden_constants",
    "with_hidden_constants",
]

#: engines with a catalogue
ENGINES = ("bullet", "mujoco")


@immutable
@dataclass(frozen=True, slots=True)
class HiddenConstant:
    """One built-in constant of an engine, with its dimension and default.

    Parameters
    ----------
    engine : str
        ``"bullet"`` or ``"mujoco"``.
    name : str
        Identifier used as a variable name, e.g. ``"bullet_time_step"``.
    dimension : Dimension
        Its dimension over M, L, T (a formula string is parsed; ``"1"`` for
        dimensionless).
    default : float
        The value the engine uses unless told otherwise.
    where : str
        Where a user sets it (API call or MJCF attribute).
    source : str
        Where the default comes from: header or documentation page, version.
    note : str
        What it does and how it interacts with scaling.

    Examples
    --------
    >>> from pitheorem.engines import hidden_constants
    >>> dt = hidden_constants("bullet", names=["bullet_time_step"])[0]
    >>> dt.dimension, round(1 / dt.default)
    (Dimension.parse('T'), 240)
    """

    engine: str
    name: str
    dimension: Dimension
    default: float
    where: str
    source: str
    note: str

    def __post_init__(self):
        if not isinstance(self.dimension, Dimension):
            object.__setattr__(self, "dimension", Dimension.parse(self.dimension))


_PYBULLET = "measured with pybullet 3.2.7 (getPhysicsEngineParameters / getDynamicsInfo)"
_MUJOCO = "mujoco 4.0.0 model defaults (MjModel.opt, MjSpec.default); MuJoCo XML Reference (mujoco.readthedocs.io)"
_MULTIBODY = "bullet3 src/BulletDynamics/Featherstone/btMultiBody.cpp, btMultiBody constructor"

CATALOGUE: tuple[HiddenConstant, ...] = (
    # -- Bullet / pybullet ------------------------------------------------------------------
    HiddenConstant(
        "bullet", "bullet_time_step", "T", 1 / 240, "pybullet.setTimeStep",
        f"pybullet Quickstart Guide (setTimeStep: default 1/240 s); {_PYBULLET}: fixedTimeStep = 1/240",
        "fixed integration step (semi-implicit Euler); any scaling of time must scale it too"),
    HiddenConstant(
        "bullet", "bullet_collision_margin", "L", 0.001, "pybullet.changeDynamics(bodyId, link, collisionMargin=...)",
        f"{_PYBULLET}: getDynamicsInfo(...)[11] = 0.001 for URDF and box shapes (a sphere's margin is its radius; "
        "bullet3's CONVEX_DISTANCE_MARGIN 0.04 is not what PyBullet uses)",
        "contacts start this far out; Bullet also adds it to bounding boxes, and so to the inertia it derives "
        "from them at load: a scaled copy must set the margin and the inertia"),
    HiddenConstant(
        "bullet", "bullet_contact_breaking_threshold", "1", 0.02,
        "pybullet.setPhysicsEngineParameter(contactBreakingThreshold=...) (process-wide, every client)",
        "bullet3 src/BulletCollision/NarrowPhaseCollision/btPersistentManifold.cpp: gContactBreakingThreshold = "
        f"0.02; {_PYBULLET}",
        "with Bullet's default dispatcher flag a dimensionless factor times each shape's bounding radius, and a "
        "global of the process: leave it alone (scaling it as a length moved a dropped ball by 0.44 m)"),
    HiddenConstant(
        "bullet", "bullet_contact_slop", "L", 1e-5, "pybullet.setPhysicsEngineParameter(contactSlop=...)",
        "bullet3 src/BulletDynamics/ConstraintSolver/btContactSolverInfo.h: m_linearSlop; PyBullet default 1e-5",
        "penetration allowed before contacts push back"),
    HiddenConstant(
        "bullet", "bullet_solver_residual_threshold", "L^2 T^-2", 1e-7,
        "pybullet.setPhysicsEngineParameter(solverResidualThreshold=...)",
        "bullet3 btContactSolverInfo.h: m_leastSquaresResidualThreshold; PyBullet default 1e-7",
        "the iterative solver stops when the squared velocity residual falls below this"),
    HiddenConstant(
        "bullet", "bullet_default_motor_impulse", "M L^2 T^-1", math.nan,
        "pybullet.setJointMotorControl2(body, joint, VELOCITY_CONTROL, force=0) switches it off",
        "PyBullet Quickstart Guide: every revolute and prismatic joint of a URDF gets a velocity motor",
        "an impulse cap (M L T^-1 on prismatic joints) with no documented value: switch the motors off, as "
        "pitheorem.engines does in every run"),
    HiddenConstant(
        "bullet", "bullet_linear_sleep_threshold", "L T^-1", 0.8, "btRigidBody::setSleepingThresholds",
        "bullet3 src/BulletDynamics/Dynamics/btRigidBody.h: btRigidBodyConstructionInfo m_linearSleepingThreshold(0.8)",
        "rigid bodies (maximal coordinates) slower than this may fall asleep"),
    HiddenConstant(
        "bullet", "bullet_angular_sleep_threshold", "T^-1", 1.0, "btRigidBody::setSleepingThresholds",
        "bullet3 src/BulletDynamics/Dynamics/btRigidBody.h: btRigidBodyConstructionInfo m_angularSleepingThreshold(1)",
        "rigid bodies turning slower than this may fall asleep"),
    HiddenConstant(
        "bullet", "bullet_multibody_sleep_epsilon", "L^2 T^-2", 0.05,
        "pybullet.changeDynamics(activationState=...)",
        f"{_MULTIBODY}: SLEEP_EPSILON = 0.05 ('a squared velocity (m^2 s^-2)')",
        "multibodies (pybullet's default for URDF and createMultiBody) sleep below this squared speed"),
    HiddenConstant(
        "bullet", "bullet_multibody_sleep_timeout", "T", 2.0, "pybullet.changeDynamics(activationState=...)",
        f"{_MULTIBODY}: SLEEP_TIMEOUT = 2 (seconds)",
        "time a multibody must stay below the sleep threshold before it sleeps"),
    HiddenConstant(
        "bullet", "bullet_linear_damping_k1", "T^-1", 0.04, "pybullet.changeDynamics(bodyId, -1, linearDamping=...)",
        f"{_MULTIBODY}: m_linearDamping(0.04); used as DAMPING_K1_LINEAR in "
        "computeAccelerationsArticulatedBodyAlgorithmMultiDof",
        "the damping force is m v (d + d |v|): the same number d acts as a rate (T^-1) ..."),
    HiddenConstant(
        "bullet", "bullet_linear_damping_k2", "L^-1", 0.04, "pybullet.changeDynamics(bodyId, -1, linearDamping=...)",
        f"{_MULTIBODY}: m_linearDamping(0.04); used as DAMPING_K2_LINEAR",
        "... and as an inverse length (L^-1): no change of length or time units keeps both; set it to 0"),
    HiddenConstant(
        "bullet", "bullet_angular_damping_k1", "T^-1", 0.04, "pybullet.changeDynamics(bodyId, -1, angularDamping=...)",
        f"{_MULTIBODY}: m_angularDamping(0.04); used as DAMPING_K1_ANGULAR",
        "damping torque I w (d + d |w|) on every link: a rate (T^-1) ..."),
    HiddenConstant(
        "bullet", "bullet_angular_damping_k2", "1", 0.04, "pybullet.changeDynamics(bodyId, -1, angularDamping=...)",
        f"{_MULTIBODY}: m_angularDamping(0.04); used as DAMPING_K2_ANGULAR",
        "... and a per-radian coefficient (dimensionless)"),
    HiddenConstant(
        "bullet", "bullet_max_joint_velocity", "T^-1", 100.0, "pybullet.changeDynamics(maxJointVelocity=...)",
        f"{_MULTIBODY}: m_maxCoordinateVelocity(100)",
        "revolute joint speeds are clipped to this (rad/s); prismatic ones: bullet_max_prismatic_joint_velocity"),
    HiddenConstant(
        "bullet", "bullet_max_prismatic_joint_velocity", "L T^-1", 100.0,
        "pybullet.changeDynamics(maxJointVelocity=...)",
        f"{_MULTIBODY}: m_maxCoordinateVelocity(100), the same number for a prismatic joint",
        "prismatic joint speeds are clipped to this (m/s)"),
    HiddenConstant(
        "bullet", "bullet_max_applied_impulse", "M L T^-1", 1000.0, "btMultiBody::setMaxAppliedImpulse",
        f"{_MULTIBODY}: m_maxAppliedImpulse(1000)",
        "cap on the impulse of multibody constraints and contacts (M L^2 T^-1 for angular rows)"),
    HiddenConstant(
        "bullet", "bullet_erp", "1", 0.2, "pybullet.setPhysicsEngineParameter(erp=...)",
        "bullet3 src/BulletDynamics/ConstraintSolver/btContactSolverInfo.h (commit 0bdd9ace): m_erp = 0.2",
        "fraction of a joint error corrected per step: a hidden time constant dt/erp, tied to the time step"),
    HiddenConstant(
        "bullet", "bullet_contact_erp", "1", 0.08, "pybullet.setPhysicsEngineParameter(contactERP=...)",
        "PyBullet's default (measured with pybullet 3.2.7; bullet3's btContactSolverInfo m_erp2 = 0.2 is overridden)",
        "fraction of penetration corrected per step: hidden time constant dt/erp2"),
    HiddenConstant(
        "bullet", "bullet_global_cfm", "M^-1 T", 0.0, "pybullet.setPhysicsEngineParameter(globalCFM=...)",
        "bullet3 src/BulletDynamics/ConstraintSolver/btContactSolverInfo.h (commit 0bdd9ace): m_globalCfm = 0",
        "constraint force mixing (softness), added to an inverse mass per step; 0 breaks no scaling"),
    HiddenConstant(
        "bullet", "bullet_solver_iterations", "1", 50.0, "pybullet.setPhysicsEngineParameter(numSolverIterations=...)",
        f"{_PYBULLET}: numSolverIterations = 50 (Bullet's own btContactSolverInfo default is 10)",
        "an iteration count: dimensionless, but an unconverged solve differs between scaled runs in rounding"),
    HiddenConstant(
        "bullet", "bullet_split_impulse_penetration_threshold", "L", -0.04,
        "not reachable from Python (a negative value cannot be set); setPhysicsEngineParameter(useSplitImpulse=0) "
        "removes it",
        "bullet3 src/BulletDynamics/ConstraintSolver/btContactSolverInfo.h: m_splitImpulsePenetrationThreshold = -0.04",
        "penetrations deeper than this are resolved by split impulses"),
    HiddenConstant(
        "bullet", "bullet_restitution_velocity_threshold", "L T^-1", 0.2,
        "pybullet.setPhysicsEngineParameter(restitutionVelocityThreshold=...)",
        "bullet3 src/BulletDynamics/ConstraintSolver/btContactSolverInfo.h: m_restitutionVelocityThreshold = 0.2",
        "impacts slower than this do not bounce"),
    # -- MuJoCo ------------------------------------------------------------------------------
    HiddenConstant(
        "mujoco", "mujoco_timestep", "T", 0.002, "<option timestep=...>",
        f"{_MUJOCO}, option/timestep",
        "fixed integration step; any scaling of time must scale it too"),
    HiddenConstant(
        "mujoco", "mujoco_solref_timeconst", "T", 0.02, "solref=... on geoms, joints (solreflimit), <option o_solref>",
        f"{_MUJOCO}, solref default (0.02, 1)",
        "time constant of every soft constraint (contacts, limits, equalities); with the refsafe flag MuJoCo "
        "raises it to at least 2 timesteps"),
    HiddenConstant(
        "mujoco", "mujoco_solref_dampratio", "1", 1.0, "solref=...",
        f"{_MUJOCO}, solref default (0.02, 1)",
        "damping ratio of the constraint's reference spring-damper"),
    HiddenConstant(
        "mujoco", "mujoco_solimp_width", "L", 0.001, "solimp=... (third number)",
        f"{_MUJOCO}, solimp default (0.9, 0.95, 0.001, 0.5, 2)",
        "penetration over which the impedance ramps from dmin to dmax (radians for joint limits)"),
    HiddenConstant(
        "mujoco", "mujoco_solimp_dmin", "1", 0.9, "solimp=... (first number)",
        f"{_MUJOCO}, solimp default (0.9, 0.95, 0.001, 0.5, 2)",
        "constraint impedance at zero violation"),
    HiddenConstant(
        "mujoco", "mujoco_geom_margin", "L", 0.0, "<geom margin=...>, <option o_margin>",
        f"{_MUJOCO}, geom/margin",
        "contacts activate this far apart; 0 breaks no scaling"),
    HiddenConstant(
        "mujoco", "mujoco_torsional_friction", "L", 0.005, "<geom friction=...> (second number)",
        f"{_MUJOCO}, geom/friction default (1, 0.005, 0.0001)",
        "torsional friction coefficient: a torque per normal force, so a length"),
    HiddenConstant(
        "mujoco", "mujoco_rolling_friction", "L", 0.0001, "<geom friction=...> (third number)",
        f"{_MUJOCO}, geom/friction default (1, 0.005, 0.0001)",
        "rolling friction coefficient: a length"),
    HiddenConstant(
        "mujoco", "mujoco_sliding_friction", "1", 1.0, "<geom friction=...> (first number)",
        f"{_MUJOCO}, geom/friction default (1, 0.005, 0.0001)",
        "Coulomb friction coefficient"),
    HiddenConstant(
        "mujoco", "mujoco_geom_density", "M L^-3", 1000.0, "<geom density=...>",
        f"{_MUJOCO}, geom/density",
        "gives geoms their mass when a body has no explicit inertial"),
    HiddenConstant(
        "mujoco", "mujoco_ccd_tolerance", "L", 1e-6, "<option ccd_tolerance=...>",
        f"{_MUJOCO}, option/ccd_tolerance",
        "distance tolerance of the convex collision search"),
    HiddenConstant(
        "mujoco", "mujoco_joint_margin", "L", 0.0, "<joint margin=...>",
        f"{_MUJOCO}, joint/margin",
        "limits activate this far from the range (radians on hinges: dimensionless; a length on slides); "
        "0 breaks no scaling"),
    HiddenConstant(
        "mujoco", "mujoco_stiffness_poly", "M L^2 T^-2", 0.0, "<joint stiffness='k0 k1 k2'>",
        f"{_MUJOCO}, joint/stiffness (a polynomial in |q|: k1 and k2 divide by one and two more powers of q)",
        "higher polynomial terms of a joint spring; 0 breaks no scaling"),
    HiddenConstant(
        "mujoco", "mujoco_damping_poly", "M L^2", 0.0, "<joint damping='d0 d1 d2'>",
        f"{_MUJOCO}, joint/damping (a polynomial in |qdot|: d1 and d2 divide by one and two more powers of qdot)",
        "higher polynomial terms of a joint damper (hinge shown); 0 breaks no scaling"),
    HiddenConstant(
        "mujoco", "mujoco_tolerance", "1", 1e-8, "<option tolerance=...>",
        f"{_MUJOCO}, option/tolerance; measured: gymnasium's humanoid, hopper and walker2d scaled with g and "
        "lengths by 2 or 10 differ unless it is 0",
        "stops the solver relative to a normalisation that mixes M and M L^2 (no pure dimension): set 0 for "
        "exact similarity (the solver then runs all its iterations)"),
    HiddenConstant(
        "mujoco", "mujoco_sleep_tolerance", "1", 1e-3, "<option sleep_tolerance=...>",
        f"{_MUJOCO}, option/sleep_tolerance",
        "compared with velocities of every joint type (mixed dimension); only acts when sleeping is enabled"),
    HiddenConstant(
        "mujoco", "mujoco_iterations", "1", 100.0, "<option iterations=...>",
        f"{_MUJOCO}, option/iterations",
        "constraint solver iterations (dimensionless)"),
    HiddenConstant(
        "mujoco", "mujoco_angle_unit", "1", 0.017453292519943295, "<compiler angle=...>",
        f"{_MUJOCO}, compiler/angle (default 'degree' for MJCF)",
        "MJCF reads angles (springref, ranges, euler) in degrees unless angle='radian': a hidden factor pi/180"),
)


def _check_engine(engine) -> str | None:
    if engine is None:
        return None
    if engine not in ENGINES:
        raise InvalidRequestError(f"unknown engine {engine!r}; the catalogue has {', '.join(map(repr, ENGINES))}")
    return engine


def hidden_constants(engine: str | None = None, *, names: Iterable[str] | None = None,
                     dimensional: bool | None = None) -> tuple[HiddenConstant, ...]:
    """The catalogued hidden constants of one engine (or of all).

    Parameters
    ----------
    engine : {"bullet", "mujoco"}, optional
        Default: every engine.
    names : iterable of str, optional
        Only these entries, in the order given.
    dimensional : bool, optional
        ``True``: only constants with a dimension; ``False``: only
        dimensionless ones; default both.

    Returns
    -------
    tuple of HiddenConstant

    Raises
    ------
    InvalidRequestError
        For an unknown engine.
    UnknownVariableError
        For a name that is not in the catalogue.

    Examples
    --------
    >>> from pitheorem.engines import hidden_constants
    >>> [c.name for c in hidden_constants("mujoco", dimensional=True)][:3]
    ['mujoco_timestep', 'mujoco_solref_timeconst', 'mujoco_solimp_width']
    """
    engine = _check_engine(engine)
    pool = [c for c in CATALOGUE if engine is None or c.engine == engine]
    if names is not None:
        by_name = {c.name: c for c in pool}
        picked = []
        for n in names:
            if n not in by_name:
                raise UnknownVariableError(str(n), tuple(by_name), f"the hidden constants of {engine or 'any engine'}")
            picked.append(by_name[n])
        pool = picked
    if dimensional is not None:
        pool = [c for c in pool if c.dimension.is_dimensionless != bool(dimensional)]
    return tuple(pool)


def with_hidden_constants(system: System, engine: str, *, names: Iterable[str] | None = None,
                          include_dimensionless: bool = False) -> System:
    """The system extended by an engine's hidden constants as variables.

    Parameters
    ----------
    system : System
    engine : {"bullet", "mujoco"}
    names : iterable of str, optional
        Only these constants (default: all of the engine's).
    include_dimensionless : bool
        Also add dimensionless constants (no unit change moves them, so
        they never constrain a search).

    Returns
    -------
    System

    Raises
    ------
    DuplicateVariableError
        When the system already has a variable of a constant's name.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines import with_hidden_constants
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})
    >>> ext = with_hidden_constants(rod, "mujoco", names=["mujoco_timestep", "mujoco_solimp_width"])
    >>> ext.variables
    ('m', 'l', 'g', 't', 'mujoco_timestep', 'mujoco_solimp_width')
    """
    if not isinstance(system, System):
        raise InvalidRequestError(f"with_hidden_constants needs a System, got {type(system).__name__}")
    consts = hidden_constants(engine, names=names)
    if not include_dimensionless and names is None:
        consts = tuple(c for c in consts if not c.dimension.is_dimensionless)
    dims = dict(system.dimensions)
    for c in consts:
        if c.name in dims:
            raise DuplicateVariableError(c.name, "the system and the hidden constants")
        dims[c.name] = c.dimension
    return System(dims)


def engine_search(system: System, engine: str, scale: Mapping[str, object], fixed: Iterable[str] | None = None,
                  *, names: Iterable[str] | None = None, allow: Iterable[str] | None = None) -> SearchResult:
    """Search scalings while an engine's hidden constants stay at their defaults.

    Runs :func:`pitheorem.search` on :func:`with_hidden_constants` with
    every added constant held fixed, besides `fixed`.  An infeasible result
    means the engine silently breaks every such scaling unless some of its
    constants are changed too; the certificate says which.

    Parameters
    ----------
    system : System
    engine : {"bullet", "mujoco"}
    scale : mapping of str to number
        As in :func:`pitheorem.search`.
    fixed : iterable of str, optional
        Further fixed variables; default: the system's time variables, as
        in :func:`pitheorem.search`.
    names : iterable of str, optional
        Hold only these constants (default: all dimensional ones).
    allow : iterable of str, optional
        As in :func:`pitheorem.search`.

    Returns
    -------
    SearchResult

    Examples
    --------
    The paper's rod with gravity doubled: impossible while the engine's
    time step and collision margin keep their values.

    >>> import pitheorem as pt
    >>> from pitheorem.engines import engine_search
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "t": "T"})
    >>> res = engine_search(rod, "bullet", {"g": 1}, fixed=(),
    ...                     names=["bullet_time_step", "bullet_collision_margin"])
    >>> res.feasible, str(res.certificate)
    (False, 'Pi = bullet_time_step**2*g/bullet_collision_margin')
    """
    ext = with_hidden_constants(system, engine, names=names)
    added = tuple(n for n in ext.variables if n not in system.variables)
    if fixed is None:
        time = Dimension({"T": 1})
        fixed = tuple(n for n in system.variables if system.dimension(n) == time)
    fixed = tuple(fixed)
    return search(ext, scale, fixed=(*fixed, *(n for n in added if n not in fixed)), allow=allow)


def broken_constants(scaling, engine: str, *, names: Iterable[str] | None = None) -> tuple[HiddenConstant, ...]:
    """The hidden constants a scaling would have to change, but the engine keeps.

    A constant is broken when its dimension gets a nonzero exponent under
    the scaling's change of units and its default is not zero (zero is
    invariant under every scaling).

    Parameters
    ----------
    scaling : Scaling
        A change-of-units scaling (from :func:`pitheorem.search` or
        :meth:`pitheorem.Scaling.from_unit_change`).
    engine : {"bullet", "mujoco"}
    names : iterable of str, optional
        Check only these constants.

    Returns
    -------
    tuple of HiddenConstant

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines import broken_constants
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})
    >>> lengths_only = pt.Scaling.from_unit_change(rod, {"L": 1})
    >>> [c.name for c in broken_constants(lengths_only, "mujoco")]
    ['mujoco_solimp_width', 'mujoco_torsional_friction', 'mujoco_rolling_friction', 'mujoco_geom_density', \
'mujoco_ccd_tolerance']
    """
    if not isinstance(scaling, Scaling):
        raise InvalidRequestError(f"broken_constants needs a Scaling, got {type(scaling).__name__}")
    units = scaling.unit_change  # raises for a symmetry that is no change of units
    out = []
    for c in hidden_constants(engine, names=names):
        if c.default == 0 or c.dimension.is_dimensionless:
            continue
        # a base the system lacks keeps its unit: it contributes nothing
        exponent = sum((p * units[b] for b, p in c.dimension.exponents.items() if b in units), Fraction(0))
        if exponent != 0:
            out.append(c)
    return tuple(out)
