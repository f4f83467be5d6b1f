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

The catalogue itself is data, ``constants.toml`` beside this module: one
entry per constant with its dimension, default, where a user sets it and
the source its value was read from (and, where stated, measured with
pybullet 3.2.7 and mujoco 4.0.0).  A new constant, or a new engine's
table, goes there; so do the engines' thresholds (floors, ceilings,
refusals), which :mod:`pitheorem.engines.thresholds` reads.  Nothing here
imports an engine.
"""

from __future__ import annotations

import tomllib
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

from ..dimensions import Dimension
from ..errors import DuplicateVariableError, InvalidRequestError, UnknownVariableError
from ..formatting import TextDisplay
from ..immutable import immutable
from ..scalesearch import SearchResult, search
from ..scaling import Scaling
from ..system import System
from .packages import check_engine

__all__ = [
    "CATALOGUE",
    "CAUSE_PATHS",
    "ENGINES",
    "HiddenConstant",
    "broken_constants",
    "constants_for",
    "engine_search",
    "hidden_constants",
    "with_hidden_constants",
]


@immutable
@dataclass(frozen=True, slots=True)
class HiddenConstant(TextDisplay):
    """One built-in constant of an engine, with its dimension and default.

    Parameters
    ----------
    engine : str
        ``"pybullet"`` or ``"mujoco"``.
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
    location : str, optional
        Where the engine's code uses it: file and function, and the
        version read (empty where only the documentation was read).
    measured : str, optional
        Its effect on a scaled run, measured with a small model and the
        counter-run that removes it (the test that asserts it is named).
    paths : tuple of str, optional
        The cause paths (``CAUSE_PATHS`` of this module) on which a run meets it.
    remedy : str, optional
        What a user can do about it: the setting that keeps a scaled copy
        clear of it, or why nothing is needed.

    Examples
    --------
    >>> from pitheorem.engines import hidden_constants
    >>> dt = hidden_constants("pybullet", names=["bullet_time_step"])[0]
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
    location: str = ""
    measured: str = ""
    paths: tuple[str, ...] = ()
    remedy: str = ""

    def __post_init__(self):
        if not isinstance(self.dimension, Dimension):
            object.__setattr__(self, "dimension", Dimension.parse(self.dimension))
        object.__setattr__(self, "paths", tuple(self.paths))
        unknown = [p for p in self.paths if p not in CAUSE_PATHS]
        if unknown:
            raise InvalidRequestError(
                f"hidden constant {self.name!r}: unknown cause path {unknown[0]!r}; valid: {', '.join(CAUSE_PATHS)}"
            )


#: the paths by which a run meets an engine's constants, as a diagnosis names a cause: contacts found by
#: native convex collision detection (GJK/EPA: meshes, ellipsoids, cylinders), contacts of primitive pairs
#: (analytic sphere, capsule, box, plane functions), contact margins, the constraint solver's stopping
#: rules, the noslip post-solver, equality constraints (and welds, whose rotational rows are soft by a
#: term of their own), the impedance and softness of every constraint, friction, and the compiler's
#: processing of meshes
CAUSE_PATHS = (
    "native_ccd",
    "primitive",
    "margin",
    "solver_tolerance",
    "noslip",
    "equality",
    "weld",
    "impedance",
    "friction",
    "mesh",
)


def _catalogue(path: Path) -> tuple[HiddenConstant, ...]:
    """The entries of the catalogue file, engine by engine, in the file's order."""
    doc = tomllib.loads(path.read_text(encoding="utf-8"))
    sources = doc.pop("sources")
    doc.pop("thresholds")  # read by pitheorem.engines.thresholds
    texts = ("source", "location", "measured")
    return tuple(
        HiddenConstant(engine, **{**entry, **{k: entry[k].format_map(sources) for k in texts if k in entry}})
        for engine, entries in doc.items()
        for entry in entries
    )


#: every catalogued constant, read from ``constants.toml`` beside this module (with each
#: value's dimension and the source it was read from)
CATALOGUE: tuple[HiddenConstant, ...] = _catalogue(Path(__file__).with_name("constants.toml"))

#: engines with a catalogue
ENGINES = tuple(dict.fromkeys(c.engine for c in CATALOGUE))


def hidden_constants(
    engine: str | None = None, *, names: Iterable[str] | None = None, dimensional: bool | None = None
) -> tuple[HiddenConstant, ...]:
    """The catalogued hidden constants of one engine (or of all).

    Parameters
    ----------
    engine : {"pybullet", "mujoco", "mjx"}, optional
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
    engine = None if engine is None else check_engine(engine)
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


def constants_for(engine: str, path: str) -> tuple[HiddenConstant, ...]:
    """The catalogued constants of an engine that a run meets on one cause path.

    A diagnosis that has shown a cause (contacts of a geom pair found by
    native CCD, the solver's tolerance, an equality, ...) names with this
    the engine's fixed constants behind it, in the catalogue's order.

    Parameters
    ----------
    engine : {"pybullet", "mujoco", "mjx"}
    path : str
        One of ``CAUSE_PATHS``.

    Returns
    -------
    tuple of HiddenConstant
        Empty where the catalogue names none on that path for the engine.

    Raises
    ------
    InvalidRequestError
        For an unknown engine or path.

    Examples
    --------
    >>> from pitheorem.engines.constants import constants_for
    >>> [c.name for c in constants_for("mujoco", "native_ccd")]
    ['mujoco_ccd_tolerance', 'mujoco_ccd_iterations', 'mujoco_ccd_discrete_tolerance']
    >>> constants_for("mujoco", "native_ccd")[0].location.split(" (")[0]
    'engine_collision_convex.c mjc_penetration'
    >>> [c.name for c in constants_for("mujoco", "noslip")]
    ['mujoco_noslip_tolerance']
    """
    engine = check_engine(engine)
    if path not in CAUSE_PATHS:
        raise InvalidRequestError(f"unknown cause path {path!r}; valid: {', '.join(CAUSE_PATHS)}")
    return tuple(c for c in CATALOGUE if c.engine == engine and path in c.paths)


def with_hidden_constants(
    system: System, engine: str, *, names: Iterable[str] | None = None, include_dimensionless: bool = False
) -> System:
    """The system extended by an engine's hidden constants as variables.

    Parameters
    ----------
    system : System
    engine : {"pybullet", "mujoco", "mjx"}
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


def engine_search(
    system: System,
    engine: str,
    scale: Mapping[str, object],
    fixed: Iterable[str] | None = None,
    *,
    names: Iterable[str] | None = None,
    allow: Iterable[str] | None = None,
) -> SearchResult:
    """Search scalings while an engine's hidden constants stay at their defaults.

    Runs :func:`pitheorem.search` on :func:`with_hidden_constants` with
    every added constant held fixed, besides `fixed`.  An infeasible result
    means the engine silently breaks every such scaling unless some of its
    constants are changed too; the certificate says which.

    Parameters
    ----------
    system : System
    engine : {"pybullet", "mujoco", "mjx"}
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
    >>> res = engine_search(rod, "pybullet", {"g": 1}, fixed=(),
    ...                     names=["bullet_time_step", "bullet_collision_margin"])
    >>> res.feasible, str(res.certificate)
    (False, 'Pi = bullet_time_step**2*g/bullet_collision_margin')
    """
    ext = with_hidden_constants(system, engine, names=names)
    added = tuple(n for n in ext.variables if n not in system.variables)
    fixed = system.time_variables if fixed is None else tuple(fixed)
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
    engine : {"pybullet", "mujoco", "mjx"}
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
'mujoco_ccd_tolerance', 'mujoco_ccd_discrete_tolerance', 'mujoco_minval_normal', 'mujoco_weld_rotational_weight']
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
