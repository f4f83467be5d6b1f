"""The numbers at which an engine stops taking a model's numbers as they are, and the models that reach them.

An engine computes in floating point and guards itself with constants:
MuJoCo refuses masses below ``mjMINVAL`` (1e-15), floors the softness of
constraints at the same number, raises torsional and rolling friction to
``mjMINMU`` (1e-5 m), zeroes controls beyond ``mjMAXVAL`` (1e10) and
stiffens no constraint beyond two time steps; PyBullet lets boxes smaller
than twice its collision margin fall through the ground.  Such a constant
is a number of fixed size: a model scaled far enough crosses it, and a
change of units is a similarity scaling, so the *units* a model is
written in decide whether the engine simulates it faithfully (issue 24).

Each threshold is a :class:`Threshold` read from the catalogue
``constants.toml`` (its ``[thresholds]`` tables), with the value measured
against the installed engine.  :func:`crossed` holds a table of
:class:`~pitheorem.engines.Parameter` (optionally multiplied by the
factors of a scaling) against them; :func:`check` does it for a model.
Both answer with :class:`~pitheorem.engines.Cause` records of kind
``"threshold"``.

Which parameters a threshold is compared with goes by the parameter's
kind (:data:`KINDS`), read from its name, path and dimension as the MJCF
and URDF readers write them (``body_torso_mass``, ``geom 'floor' friction
torsional rolling``, ``actuator0_ctrlrange``, ...).
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

from pitheorem.formatting.pieces import float_text

from ..dimensions import Dimension
from ..errors import InvalidRequestError
from ..immutable import immutable
from ..simulation import positive_float
from .enginemodel import EngineModel
from .loading import runner_module
from .packages import check_engine
from .parameters import Parameter
from .protocols import ReadsSomeNumbers
from .registry import registered
from .verdicts.causes import Cause, sorted_causes

__all__ = [
    "BOUNDS",
    "KINDS",
    "THRESHOLDS",
    "Threshold",
    "check",
    "check_summary",
    "crossed",
    "held_against",
    "thresholds",
]

#: how a threshold acts: on numbers below it, above it, on numbers the engine computes as it runs (a solver's
#: residual, a contact's separation: nothing in a model's table), or as a setting the engine does not apply
BOUNDS = ("below", "above", "internal", "unapplied")

_M, _ML2, _L, _T = (Dimension.parse(d) for d in ("M", "M L^2", "L", "T"))
_PRODUCTS = (" inertia ixy", " inertia ixz", " inertia iyz")  # a URDF's products of inertia, by their paths

#: the kinds of parameter a threshold is compared with: a description, and the test on a Parameter
KINDS: Mapping[str, tuple[str, Callable]] = {
    "mass": ("a body's or link's mass", lambda p: p.dimension == _M and p.name.endswith("_mass")),
    "inertia": (
        "a body's or link's inertia; not a URDF's products of inertia (ixy, ixz, iyz), which are no principal "
        "moments: MuJoCo holds its floor against the principal moments, and a product of any size, 0 or "
        "1e-22, compiles",
        lambda p: p.dimension == _ML2 and "inertia" in p.path and not p.path.endswith(_PRODUCTS),
    ),
    "friction_length": (
        "torsional and rolling friction (MJCF friction's second and third numbers)",
        lambda p: p.dimension == _L and p.path.endswith("friction torsional rolling"),
    ),
    "solref_timeconst": ("the time constant of a solref", lambda p: p.dimension == _T and p.name.endswith("timeconst")),
    "control_range": ("an actuator's ctrlrange", lambda p: p.name.endswith("_ctrlrange")),
    "collision_size": (
        "a URDF collision geometry's size, radius or length",
        lambda p: p.dimension == _L and " collision #" in p.path and p.name.endswith(("_size", "_radius", "_length")),
    ),
    "capsule_segment": (
        "the half-length of a capsule (the compiled geom size's second number, or half its "
        "fromto's length) that collides with a sphere, capsule, box, mesh or height field: "
        "the collisions MJX computes with the closest point on its segment "
        "(mjx_parameters)",
        lambda p: p.dimension == _L and p.path.endswith(" capsule half-length"),
    ),
    "cylinder_on_plane": (
        "the half-length of a cylinder (the compiled geom size's second number) that "
        "collides with a plane (mjx_parameters)",
        lambda p: p.dimension == _L and p.path.endswith(" cylinder half-length"),
    ),
    "fluid_mass": (
        "a body's mass, with the fluid model on (mjx_parameters)",
        lambda p: p.dimension == _M and p.path.endswith(" mass in the fluid model"),
    ),
    "fluid_box_moments": (
        "the sums I1 + I2 - I0, I0 + I2 - I1 and I0 + I1 - I2 of a body's principal moments "
        "of inertia, which give its equivalent box in the fluid model (mjx_parameters)",
        lambda p: p.dimension == _ML2 and p.path.endswith(" fluid box moments"),
    ),
    "number": ("every number of the model, of any dimension (an engine that stores them in float32)", lambda p: True),
}


@immutable
@dataclass(frozen=True, slots=True)
class Threshold:
    """One threshold of an engine: a number beyond which the engine changes or refuses a model's numbers.

    Parameters
    ----------
    engine : {"pybullet", "mujoco", "mjx"}
    name : str
        Identifier, prefixed as the engine's constants are (``mujoco_minmu``).
    value : float
        The threshold; with `relative_to`, a multiple of that parameter.
    dimension : Dimension or None
        None when the numbers it is compared with have no one dimension
        (MuJoCo holds ``mjMINVAL`` against masses and inertias alike).
    bound : {"below", "above", "internal", "unapplied"}
        Numbers below it, or above it, are changed or refused;
        ``"internal"``: held against numbers the engine computes as it runs
        (a solver's residual); ``"unapplied"``: a setting the engine
        ignores.
    applies : tuple of str
        The kinds of parameter it is compared with (keys of :data:`KINDS`).
    crossed_by : str
        What crosses it, in words.
    effect : str
        What the engine does then.
    source : str
        The engine's source, and the measurement that shows the clamp.
    relative_to : str
        The parameter whose value multiplies `value` (``"timestep"``), or "".
    precision : str
        ``"float32"``: held only against a model the engine computes in
        float32 (float32's range); "" for every model.

    Examples
    --------
    >>> from pitheorem.engines.thresholds import thresholds
    >>> mu = thresholds("mujoco", names=["mujoco_minmu"])[0]
    >>> mu.value, mu.dimension, mu.bound, mu.applies
    (1e-05, None, 'below', ('friction_length',))
    """

    engine: str
    name: str
    value: float
    dimension: Dimension | None
    bound: str
    applies: tuple[str, ...]
    crossed_by: str
    effect: str
    source: str
    relative_to: str = ""
    precision: str = ""

    def __post_init__(self) -> None:
        if isinstance(self.dimension, str):
            object.__setattr__(self, "dimension", None if self.dimension == "none" else Dimension.parse(self.dimension))
        object.__setattr__(self, "applies", tuple(self.applies))
        if self.bound not in BOUNDS:
            raise InvalidRequestError(
                f"threshold {self.name!r}: unknown bound {self.bound!r}; valid: {', '.join(BOUNDS)}"
            )
        unknown = [k for k in self.applies if k not in KINDS]
        if unknown:
            raise InvalidRequestError(
                f"threshold {self.name!r}: unknown kind {unknown[0]!r}; valid: {', '.join(KINDS)}"
            )

    def limit(self, parameters: Mapping[str, float] | None = None) -> float | None:
        """The threshold's value for a model: `value`, or `value` times the `relative_to` parameter.

        Parameters
        ----------
        parameters : mapping of str to float, optional
            The model's numbers by name (only `relative_to` is read).

        Returns
        -------
        float or None
            None when the threshold is relative to a parameter the model
            lacks.

        Examples
        --------
        >>> from pitheorem.engines.thresholds import thresholds
        >>> refsafe = thresholds("mujoco", names=["mujoco_refsafe"])[0]
        >>> refsafe.limit({"timestep": 0.002}), refsafe.limit({}) is None
        (0.004, True)
        """
        if not self.relative_to:
            return self.value
        base = (parameters or {}).get(self.relative_to)
        return None if base is None else self.value * base


def _read(path: Path) -> tuple[Threshold, ...]:
    """The ``[thresholds]`` tables of the catalogue file, engine by engine, in the file's order."""
    doc = tomllib.loads(path.read_text(encoding="utf-8"))
    sources = doc["sources"]
    return tuple(
        Threshold(engine, **{**entry, "source": entry["source"].format_map(sources)})
        for engine, entries in doc["thresholds"].items()
        for entry in entries
    )


#: every catalogued threshold, read from ``constants.toml`` beside this module
THRESHOLDS: tuple[Threshold, ...] = _read(Path(__file__).with_name("constants.toml"))


def thresholds(engine: str | None = None, *, names: Iterable[str] | None = None) -> tuple[Threshold, ...]:
    """The catalogued thresholds of one engine (or of all).

    Parameters
    ----------
    engine : {"pybullet", "mujoco", "mjx"}, optional
        Default: every engine.
    names : iterable of str, optional
        Only these, in the order given.

    Returns
    -------
    tuple of Threshold

    Raises
    ------
    InvalidRequestError
        For an unknown engine, or a name that is no threshold of it.

    Examples
    --------
    >>> from pitheorem.engines.thresholds import thresholds
    >>> [t.name for t in thresholds("mujoco")][:3]
    ['mujoco_minval_mass', 'mujoco_minval_softness', 'mujoco_minmu']
    >>> mjx = thresholds("mjx")  # MJX compiles with MuJoCo's compiler: MuJoCo's, then its own
    >>> mjx[:len(thresholds("mujoco"))] == thresholds("mujoco")
    True
    >>> [t.name for t in mjx[len(thresholds("mujoco")):]]  # doctest: +NORMALIZE_WHITESPACE
    ['mjx_segment_regularizer_float32', 'mjx_cylinder_plane_parallel', 'mjx_fluid_moments_floor',
     'mjx_fluid_mass_floor', 'mjx_float32_min_normal', 'mjx_float32_max']
    """
    engine = None if engine is None else check_engine(engine)
    # an engine built on another (MJX on MuJoCo, whose compiler it uses) has that engine's thresholds too
    lineage = {engine, registered(engine).base} if engine is not None else set()
    pool = [t for t in THRESHOLDS if engine is None or t.engine in lineage]
    if names is None:
        return tuple(pool)
    by_name = {t.name: t for t in pool}
    for n in names:
        if n not in by_name:
            raise InvalidRequestError(
                f"no threshold {n!r} of {engine or 'any engine'}; valid: {', '.join(by_name)}", culprit=n
            )
    return tuple(by_name[n] for n in names)


def _read_near(near) -> float:
    near = positive_float(near, "near")
    if near < 1:
        raise InvalidRequestError(f"near must be a factor of at least 1, got {near!r}", culprit=near)
    return near


def _read_table(parameters) -> tuple[Parameter, ...]:
    table = tuple(parameters)
    for p in table:
        if not isinstance(p, Parameter):
            raise InvalidRequestError(
                f"crossed needs a table of Parameter (EngineModel.parameters), got {type(p).__name__}", culprit=p
            )
    return table


def _read_factors(factors, names) -> dict[str, float]:
    if factors is None:
        return {}
    if not isinstance(factors, Mapping):
        raise InvalidRequestError(f"factors must map parameter names to numbers, got {type(factors).__name__}")
    for name in factors:
        if name not in names:
            raise InvalidRequestError(f"factors names {name!r}, which is no parameter of the table", culprit=name)
    # a scaling's own factors are positive finite floats already; anything else is read and checked
    return {
        name: f if type(f) is float and 0 < f < math.inf else positive_float(f, f"the factor of {name!r}")
        for name, f in factors.items()
    }


def crossed(
    engine: str,
    parameters,
    factors: Mapping[str, float] | None = None,
    *,
    near: float = 2.0,
    fixed_only: bool = False,
    grouped: bool = False,
    precision: str = "float32",
) -> tuple[Cause, ...]:
    """The parameters beyond or near a threshold of the engine, as causes of kind ``"threshold"``.

    Each parameter of a kind a threshold applies to (:data:`KINDS`) is
    compared, number by number, with the threshold: a number past it is
    *beyond*; one on the right side but within a factor `near` of it is
    *near* (a scaling by that factor would cross it).  Zeros are left
    out (a zero is scale-free: no scaling moves it), and so are the
    option's override values (``o_friction``, ``o_solref``: used only
    with the override flag).  One cause per parameter and threshold, for
    its worst number.

    Parameters
    ----------
    engine : {"pybullet", "mujoco", "mjx"}
    parameters : iterable of Parameter
        A model's table (:attr:`pitheorem.engines.EngineModel.parameters`).
    factors : mapping of str to float, optional
        A factor per parameter name: the numbers are compared as a scaled
        copy would hold them (each value times its factor; default 1).
    near : float
        The factor within which a number counts as near (default 2:
        MuJoCo's own defaults sit a factor 5 and 10 from their floors,
        the solref time constant 0.02 from two steps of 0.002 and rolling
        friction 1e-4 from ``mjMINMU``).
    fixed_only : bool
        Only the thresholds that are fixed constants.  A threshold that is
        a multiple of another of the model's numbers of the same dimension
        (two time steps) moves with it under every change of units, so it
        clamps a model and its scaled copy alike and breaks no similarity.
    grouped : bool
        One cause per threshold and dimension instead of one per parameter:
        the parameters named (the first three and how many more), the
        detail that of the worst of them (a verdict's causes stay short on
        a robot whose hundred geoms all sit below one floor).
    precision : {"float32", "float64"}
        The precision the engine computes the model in: with
        ``"float64"`` the thresholds of float32's range (MJX's
        ``mjx_float32_*``) are left out.  Engines that compute in float64
        have none.

    Returns
    -------
    tuple of Cause
        In a deterministic order (by parameter name).

    Raises
    ------
    InvalidRequestError
        For an unknown engine, a table that holds no Parameter, a factor
        that is no positive number or names no parameter, or a `near`
        below 1.

    Examples
    --------
    >>> from pitheorem import Dimension
    >>> from pitheorem.engines import Parameter
    >>> from pitheorem.engines.thresholds import crossed
    >>> mass = Parameter("body_ant_mass", "body 'ant' mass", (1e-16,), Dimension.parse("M"), "file", "file")
    >>> for cause in crossed("mujoco", [mass]):
    ...     print(cause.element, "|", cause.detail.split(":")[0])
    body_ant_mass | body 'ant' mass = 1e-16 is below mujoco_minval_mass (1e-15)
    >>> crossed("mujoco", [mass], factors={"body_ant_mass": 100.0})
    ()
    """
    engine = check_engine(engine)
    table = _read_table(parameters)
    near = _read_near(near)
    factors = _read_factors(factors, {p.name for p in table})
    found = _crossings(engine, table, factors, near, fixed_only, precision)
    if not grouped:
        return sorted_causes(
            Cause("threshold", p.name, _detail(p, t, worst, limit, near, beyond))
            for t, p, worst, limit, beyond in found
        )
    groups: dict = {}
    for t, p, worst, limit, beyond in found:
        groups.setdefault((t.name, p.dimension_text, beyond), []).append((p.name, worst, t, p, limit))
    out = []
    for (_name, _dimension, beyond), members in groups.items():
        members.sort(key=lambda m: m[0])  # by parameter name
        _, worst, t, p, limit = (min if t.bound == "below" else max)(members, key=lambda m: m[1])
        detail = _detail(p, t, worst, limit, near, beyond)
        names = ", ".join(name for name, *_ in members[:3])
        if len(members) > 3:
            names += f" and {len(members) - 3} more"
        out.append(
            Cause("threshold", names, f"{len(members)} numbers; the worst: {detail}" if len(members) > 1 else detail)
        )
    return sorted_causes(out)


def _crossings(engine, table, factors, near, fixed_only, precision) -> list:
    """(threshold, parameter, its worst number, the limit, whether beyond it) for each number beyond or near."""
    scalars = {p.name: p.value[0] * factors.get(p.name, 1.0) for p in table if len(p.value) == 1}
    found = []
    if precision not in ("float32", "float64"):
        raise InvalidRequestError(f"precision must be 'float32' or 'float64', got {precision!r}", culprit=precision)
    compared = [
        t for t in thresholds(engine) if t.bound in ("below", "above") and (not t.precision or t.precision == precision)
    ]
    for p in table:
        if p.path.startswith("option o_"):
            continue
        values = [abs(v) * factors.get(p.name, 1.0) for v in p.value if math.isfinite(v) and v != 0]
        if not values:
            continue
        kinds = {k for k, (_, is_kind) in KINDS.items() if is_kind(p)}  # each kind asked once per number
        for t in compared:
            if kinds.isdisjoint(t.applies):
                continue
            if fixed_only and t.relative_to:
                continue
            limit = t.limit(scalars)
            if limit is None:
                continue
            worst = min(values) if t.bound == "below" else max(values)
            beyond = worst < limit if t.bound == "below" else worst > limit
            close = worst < limit * near if t.bound == "below" else worst > limit / near
            if beyond or close:
                found.append((t, p, worst, limit, beyond))
    return found


def _detail(p, t: Threshold, worst: float, limit: float, near: float, beyond: bool) -> str:
    """What a cause says: the number, the threshold, what the engine does, and the way out."""
    where = f"is {t.bound}" if beyond else f"is within a factor {near:g} of"
    of = f" = {float_text(t.value)} {t.relative_to}" if t.relative_to else ""
    # the factor that puts the number a factor `near` clear of the threshold
    need = limit * near / worst if t.bound == "below" else limit / (near * worst)
    if t.relative_to:  # a multiple of another number of the same dimension: units move both alike
        remedy = f"no change of units clears it; change it or {t.relative_to} by a factor {need:.3g}"
    else:
        remedy = f"a change of units that multiplies numbers of dimension {p.dimension_text} by {need:.3g} clears it"
    return f"{p.path} = {float_text(worst)} {where} {t.name} ({float_text(limit)}{of}): {t.effect}; {remedy}"


def held_against(model, engine: str) -> tuple[Parameter, ...]:
    """The numbers of `model` that `engine`'s thresholds are held against (:func:`check`, the fit).

    The model's table; for MJX, with the numbers its own constants read
    (:func:`mjx_parameters`: capsules' and cylinders' half-lengths, the
    fluid model's masses and moments).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.thresholds import held_against
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> held_against(model, "mjx") == model.parameters  # its rod touches nothing: nothing more for MJX
    True
    """
    table = tuple(model.parameters)
    own = getattr(runner_module(check_engine(engine)), "threshold_numbers", None)  # a runner's optional hook
    return table if own is None else (*table, *own(model))


def check(model, engine: str | None = None) -> tuple[Cause, ...]:
    """The engine thresholds a model sits beyond or near: a tuple of Cause.

    ``pitheorem.engines.thresholds.crossed`` on the model's own parameters, against the thresholds
    of the model's engine (or of `engine`).  For MJX, the numbers its own
    constants are held against join them (``thresholds.mjx_parameters``: the
    half-lengths of capsules and cylinders, the fluid model's masses and
    moments), and every number is held to float32's range unless the
    model runs in float64.

    Parameters
    ----------
    model : EngineModel
    engine : {"pybullet", "mujoco", "mjx"}, optional
        Default: the model's engine.

    Returns
    -------
    tuple of Cause
        Of kind ``"threshold"``; ``()`` when the model is clear of every
        catalogued threshold.  A file the engine refused to compile (read
        as a parameter table) has the refusal first.

    Raises
    ------
    InvalidRequestError
        When `model` is no EngineModel.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> engines.check(model)
    ()
    >>> lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    >>> for cause in engines.check(model.scaled(lengths, 1e-3)):
    ...     print(cause.element, "|", cause.detail.split(" is ")[1].split(":")[0])
    geom_rod_friction_torsional_rolling | below mujoco_minmu (1e-05)
    """
    engine, table, precision, refused = _checked(model, engine)
    return (*refused, *crossed(engine, table, precision=precision))


def _checked(model, engine):
    """The engine, the numbers it reads, its precision, and the engine's refusal of the file (as causes)."""
    if not isinstance(model, EngineModel):
        raise InvalidRequestError(f"check needs an EngineModel (from engines.load), got {type(model).__name__}")
    engine = model.engine if engine is None else check_engine(engine)
    table = held_against(model, engine)
    if isinstance(model.runner, ReadsSomeNumbers):  # numbers the engine never reads cross nothing
        unread = model.runner.unread()
        table = tuple(p for p in table if p.name not in unread)
    # a model says its precision; one held against another engine's thresholds gets that engine's default
    precision = model.runner.precision if engine == model.engine else registered(engine).precision
    refusal = model.runner.refusal  # a file the engine refused to compile (read as a table)
    refused = ()
    if refusal is not None:
        refused = (
            Cause(
                "threshold",
                refusal.element or Path(refusal.path).name,
                f"{model.engine} refuses the file: {refusal.reason}",
            ),
        )
    return engine, table, precision, refused


def check_summary(model, engine: str | None = None, *, near: float = 2.0) -> tuple[tuple[Cause, ...], bool]:
    """What :func:`check` finds, one cause per threshold and value: the command line's ``check``.

    The numbers that sit at, beyond or near the same threshold with the same
    value are one cause, whatever elements hold them, with their count and
    the kinds of element (``solref timeconst of 14 geoms``).  A number
    exactly at a floor is said to be *at* it (the engine leaves it as it
    is); a remedy is named only where one exists (a change of units clears
    a fixed threshold; none moves a number away from a threshold that is a
    multiple of another of the model's numbers, such as two time steps).
    Numbers the engine never reads (the contact numbers of a geom that
    never collides) are left out.

    Parameters
    ----------
    model : EngineModel
    engine : str, optional
        Default: the model's engine.
    near : float
        The factor within which a number counts as near (default 2).

    Returns
    -------
    (tuple of Cause, bool)
        The causes (the engine's refusal of the file first, if any), and
        whether a change of units would clear some of them.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.thresholds import check_summary
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    >>> causes, units_help = check_summary(model.scaled(lengths, 1e-3))
    >>> print(causes[0].element); units_help
    1 number (friction torsional rolling of 1 geom)
    True
    """
    engine, table, precision, refused = _checked(model, engine)
    near = _read_near(near)
    groups: dict = {}
    for t, p, worst, limit, beyond in _crossings(engine, table, {}, near, False, precision):
        at = not beyond and worst == limit
        relation = "beyond" if beyond else "at" if at else "near"
        groups.setdefault((t.name, worst, relation), []).append((t, p, limit))
    out, units_help = [], False
    for (_name, worst, relation), members in sorted(groups.items(), key=lambda g: (g[0][0], g[0][2], g[0][1])):
        t, p, limit = members[0]
        holders: dict[tuple[str, str], int] = {}
        for _t, q, _limit in members:
            kind, _, rest = q.path.partition(" ")
            attribute = rest.split("' ", 1)[-1] if rest.startswith("'") else rest.partition(" ")[2]
            holders[(attribute, kind)] = holders.get((attribute, kind), 0) + 1
        kinds = [f"{a} of {n} {k}{'s' if n > 1 else ''}" for (a, k), n in sorted(holders.items())]
        if len(kinds) > 3:
            kinds = [*kinds[:3], f"{len(kinds) - 3} more"]
        count = len(members)
        element = f"{count} {'number' if count == 1 else 'numbers'} ({', '.join(kinds)})"
        of = f" = {t.value!r} {t.relative_to}" if t.relative_to else ""
        head = f"{worst!r} is {t.bound if relation == 'beyond' else relation if relation == 'at' else 'within a factor ' + format(near, 'g') + ' of'} {t.name} ({limit!r}{of})"
        need = limit * near / worst if t.bound == "below" else limit / (near * worst)
        if relation == "beyond":
            detail = f"{head}: {t.effect}"
        else:
            detail = f"{head}: left as it is; {t.bound} it, {t.effect.split(': ')[0]}"
        if not t.relative_to:
            detail += f"; units that multiply {p.dimension_text} by {need:.3g} clear it"
            units_help = True
        elif relation == "beyond":
            detail += f"; change it or {t.relative_to} by a factor {need:.3g} (a change of units moves both alike)"
        out.append(Cause("threshold", element, detail))
    return (*refused, *out), units_help
