"""Published rules of thumb for rescaling an engine's world, checked as unit changes.

Engines document how to "scale the world": multiply lengths by ``X``, keep
the mass, multiply torques by ``X^2`` ...  Such a rule is sound exactly when
its exponents are a change of base units (see :mod:`pitheorem.scaling`),
and it is complete for a model only if it names every quantity that the
unit change moves.  A :class:`RuleOfThumb` lists what a rule says, as
quantities with a dimension and a power of ``X``; :func:`check_rule` says
which unit change the rule is (or proves it is none) and what it leaves
out, against a :class:`~pitheorem.System` and the hidden-constant
catalogue of :mod:`pitheorem.engines.constants`.

Two rules are provided:

* :data:`BULLET_SCALE_THE_WORLD`, the Bullet wiki's page "Scaling The
  World" (bulletphysics.org, mediawiki-1.5.8);
* :data:`MUJOCO_FRAME_SIMILAR`, MuJoCo's ``frame/scale`` with the default
  ``similar`` policy, announced in the changelog of MuJoCo 3.16.0
  (mujoco.readthedocs.io, "Changelog", version 3.16.0: "scales all physical quantities so that
  dynamics are preserved under proportionally scaled gravity ... Masses
  scale with volume").  The reference page of ``frame/scale`` was not
  available to us; the powers listed are those the changelog states (length,
  mass with volume, gravity) and those we measured by compiling a model with
  ``<frame scale="2">`` in mujoco 4.0.0 and comparing with ``scale`` absent.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction

from ..dimensions import Dimension
from ..errors import InvalidRequestError
from ..exact import read_exponent
from ..formatting import TextDisplay
from ..groups import PiGroup
from ..immutable import immutable
from ..scalesearch import search
from ..scaling import Scaling
from ..system import System
from .constants import HiddenConstant, broken_constants, hidden_constants

__all__ = [
    "BULLET_SCALE_THE_WORLD",
    "MUJOCO_FRAME_SIMILAR",
    "RULES",
    "RuleOfThumb",
    "RuleQuantity",
    "RuleVerdict",
    "check_rule",
]


@immutable
@dataclass(frozen=True, slots=True)
class RuleQuantity:
    """One line of a rule: a kind of quantity and its power of ``X``.

    Parameters
    ----------
    name : str
        Identifier of the kind of quantity, e.g. ``"torque"``.
    dimension : Dimension
        Its dimension (a formula string is parsed).
    exponent : Fraction
        The rule multiplies it by ``X**exponent``.
    covers : tuple of str
        Hidden constants of the catalogue that this line names explicitly
        (e.g. Bullet's linear sleep threshold).

    Examples
    --------
    >>> from pitheorem.engines.rules import RuleQuantity
    >>> q = RuleQuantity("torque", "M L^2 T^-2", 2)
    >>> q.dimension, q.exponent
    (Dimension.parse('M L^2 T^-2'), Fraction(2, 1))
    """

    name: str
    dimension: Dimension
    exponent: Fraction
    covers: tuple[str, ...] = ()

    def __post_init__(self):
        if not isinstance(self.dimension, Dimension):
            object.__setattr__(self, "dimension", Dimension.parse(self.dimension))
        object.__setattr__(self, "exponent", read_exponent(self.exponent, f"exponent of {self.name!r}"))
        object.__setattr__(self, "covers", tuple(self.covers))


@immutable
@dataclass(frozen=True, slots=True)
class RuleOfThumb:
    """A published rule for rescaling an engine's world by a factor ``X``.

    Parameters
    ----------
    name : str
    engine : str
        ``"pybullet"`` or ``"mujoco"`` (whose hidden constants apply).
    source : str
        Where the rule is stated.
    quantities : tuple of RuleQuantity
        What the rule says, in its own order.
    note : str
        What the rule leaves to the user, or how it was read.

    Examples
    --------
    >>> from pitheorem.engines.rules import BULLET_SCALE_THE_WORLD as rule
    >>> [(q.name, str(q.exponent)) for q in rule.quantities][:3]
    [('mass', '0'), ('length', '1'), ('velocity', '1')]
    """

    name: str
    engine: str
    source: str
    quantities: tuple[RuleQuantity, ...]
    note: str = ""

    @property
    def system(self) -> System:
        """The rule's quantities as a System (one variable per line).

        Examples
        --------
        >>> from pitheorem.engines.rules import BULLET_SCALE_THE_WORLD as rule
        >>> rule.system.variables[:4]
        ('mass', 'length', 'velocity', 'gravity')
        """
        return System({q.name: q.dimension for q in self.quantities})

    @property
    def exponents(self) -> dict[str, Fraction]:
        """The power of ``X`` the rule gives each quantity.

        Examples
        --------
        >>> from pitheorem.engines.rules import BULLET_SCALE_THE_WORLD as rule
        >>> rule.exponents["torque"]
        Fraction(2, 1)
        """
        return {q.name: q.exponent for q in self.quantities}

    def exponent_of(self, dimension) -> Fraction | None:
        """The power of ``X`` the rule gives a dimension, or None if unnamed.

        Parameters
        ----------
        dimension : str or Dimension

        Returns
        -------
        Fraction or None

        Examples
        --------
        >>> from pitheorem.engines.rules import BULLET_SCALE_THE_WORLD as rule
        >>> rule.exponent_of("M L^2 T^-2"), rule.exponent_of("M L T^-2")
        (Fraction(2, 1), None)
        """
        dim = dimension if isinstance(dimension, Dimension) else Dimension.parse(str(dimension))
        for q in self.quantities:
            if q.dimension == dim:
                return q.exponent
        return None


@immutable
@dataclass(frozen=True, eq=False)
class RuleVerdict(TextDisplay):
    """What :func:`check_rule` found about a rule of thumb.

    Attributes
    ----------
    rule : RuleOfThumb
    scaling : Scaling or None
        The rule as a scaling of its own quantities (``s = X``), when it is a
        change of units.
    unit_change : dict of str to Fraction, or None
        Power of ``X`` for each base unit's readings; None when the rule is
        no change of units.
    certificate : PiGroup or None
        When the rule is no change of units: a dimensionless product of its
        quantities that it would change.
    missing : tuple of (str, Dimension, Fraction)
        Variables of the system whose dimension the rule does not name but
        which the unit change moves: name, dimension, required power of X.
    unchanged : tuple of str
        Variables the rule does not name that rightly keep their value.
    broken : tuple of HiddenConstant
        Hidden constants of the rule's engine that the unit change moves
        and that the rule does not name.

    Examples
    --------
    >>> from pitheorem.engines.rules import RuleVerdict
    >>> "missing" in RuleVerdict.__dataclass_fields__
    True
    """

    rule: RuleOfThumb
    scaling: Scaling | None
    unit_change: dict[str, Fraction] | None
    certificate: PiGroup | None
    missing: tuple[tuple[str, str, Fraction], ...]
    unchanged: tuple[str, ...]
    broken: tuple[HiddenConstant, ...]

    @property
    def is_unit_change(self) -> bool:
        """Whether the rule is a change of base units.

        Examples
        --------
        >>> from pitheorem.engines.rules import BULLET_SCALE_THE_WORLD, check_rule
        >>> check_rule(BULLET_SCALE_THE_WORLD).is_unit_change
        True
        """
        return self.unit_change is not None

    @property
    def complete(self) -> bool:
        """Whether the rule names everything the unit change moves.

        Examples
        --------
        >>> from pitheorem.engines.rules import MUJOCO_FRAME_SIMILAR, check_rule
        >>> check_rule(MUJOCO_FRAME_SIMILAR).complete  # the frame leaves option ccd_tolerance
        False
        """
        return self.is_unit_change and not self.missing and not self.broken


BULLET_SCALE_THE_WORLD = RuleOfThumb(
    name="Bullet wiki: Scaling The World",
    engine="pybullet",
    source="Bullet Physics wiki, 'Scaling The World' (bulletphysics.org mediawiki-1.5.8)",
    quantities=(
        RuleQuantity("mass", "M", 0),  # "you should not have to change the mass"
        RuleQuantity("length", "L", 1),  # collision shapes and positions
        RuleQuantity(
            "velocity", "L T^-1", 1, ["bullet_linear_sleep_threshold"]
        ),  # linear velocities, linear sleep threshold
        RuleQuantity("gravity", "L T^-2", 1),
        RuleQuantity("impulse", "M L T^-1", 1),  # "impulses you supply"
        RuleQuantity("torque", "M L^2 T^-2", 2),
        RuleQuantity("inertia", "M L^2", 2),
        RuleQuantity("angular_velocity", "T^-1", 0),  # "should not need to be changed"
        RuleQuantity("damping", "1", 0),  # "damping is a ratio"
    ),
    note="scaling the mass by Y as well is mentioned as an option; the time step is not mentioned",
)

MUJOCO_FRAME_SIMILAR = RuleOfThumb(
    name="MuJoCo frame/scale, policy 'similar'",
    engine="mujoco",
    source="MuJoCo 3.16.0 changelog (frame scale, scaling, massscale); powers measured with mujoco 4.0.0",
    quantities=(
        RuleQuantity(
            "length",
            "L",
            1,
            ["mujoco_solimp_width", "mujoco_torsional_friction", "mujoco_rolling_friction", "mujoco_geom_margin"],
        ),
        RuleQuantity("mass", "M", 3),  # "masses scale with volume"
        RuleQuantity("gravity", "L T^-2", 1),  # the premise: "proportionally scaled gravity" (a model parameter)
        RuleQuantity("inertia", "M L^2", 5),  # measured: body_inertia x 32 at scale 2
        RuleQuantity("force", "M L T^-2", 4),  # measured: slide frictionloss, motor forcerange x 16
        RuleQuantity("torque", "M L^2 T^-2", 5),  # measured: hinge stiffness, frictionloss, forcerange x 32
        RuleQuantity("angular_damping", "M L^2 T^-1", 5),  # measured: hinge damping x 32
        RuleQuantity("linear_stiffness", "M T^-2", 3),  # measured: slide stiffness x 8
        RuleQuantity("linear_damping", "M T^-1", 3),  # measured: slide damping x 8
        RuleQuantity("time", "T", 0, ["mujoco_solref_timeconst", "mujoco_timestep"]),  # measured: solref, timestep x 1
        RuleQuantity("angle", "1", 0),  # measured: hinge springref x 1
    ),
    note="the frame does not touch option/gravity (a global setting): multiply it by X yourself; with "
    "massscale the frame also scales masses independently, which with scale gives any time-free change "
    "of units (M and L), not only this policy's mass by volume",
)

#: every rule provided
RULES = (BULLET_SCALE_THE_WORLD, MUJOCO_FRAME_SIMILAR)


def check_rule(
    rule: RuleOfThumb, system: System | None = None, *, engine: str | None = None, hidden: Iterable[str] | None = None
) -> RuleVerdict:
    """Say which unit change a rule of thumb is, and what it leaves out.

    Parameters
    ----------
    rule : RuleOfThumb
    system : System, optional
        A model's variables; those whose dimension the rule does not name
        are reported as `missing` (when the unit change moves them) or
        `unchanged`.
    engine : str, optional
        Whose hidden constants to check (default: the rule's engine).
    hidden : iterable of str, optional
        Check only these hidden constants.

    Returns
    -------
    RuleVerdict

    Raises
    ------
    InvalidRequestError
        When `rule` is not a RuleOfThumb.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines.rules import BULLET_SCALE_THE_WORLD, check_rule
    >>> v = check_rule(BULLET_SCALE_THE_WORLD, pt.models.rod_system())
    >>> v.unit_change
    {'M': Fraction(0, 1), 'L': Fraction(1, 1), 'T': Fraction(0, 1)}
    >>> [(n, str(p)) for n, _, p in v.missing]
    [('c_theta', '2'), ('F', '1')]
    """
    if not isinstance(rule, RuleOfThumb):
        raise InvalidRequestError(f"check_rule needs a RuleOfThumb, got {type(rule).__name__}")
    rsys = rule.system
    try:
        scaling = Scaling.from_exponents(rsys, rule.exponents)
    except InvalidRequestError:
        res = search(
            rsys,
            scale={n: p for n, p in rule.exponents.items() if p},
            fixed=tuple(n for n, p in rule.exponents.items() if not p),
        )
        return RuleVerdict(rule, None, None, res.certificate, (), (), ())
    units = scaling.unit_change
    missing, unchanged = [], []
    if system is not None:
        for name in system.variables:
            dim = system.dimension(name)
            if rule.exponent_of(dim) is not None:
                continue
            extra = [b for b in dim.base_dimensions if b not in units]
            if extra:
                raise InvalidRequestError(
                    f"variable {name!r} has base dimension {extra[0]!r}, which the rule {rule.name!r} does not use"
                )
            p = scaling.exponent_of(dim)
            if p:
                missing.append((name, dim, p))
            else:
                unchanged.append(name)
    covered = {c for q in rule.quantities for c in q.covers}
    engine = engine or rule.engine
    names = tuple(hidden) if hidden is not None else tuple(c.name for c in hidden_constants(engine))
    broken = tuple(c for c in broken_constants(scaling, engine, names=names) if c.name not in covered)
    return RuleVerdict(rule, scaling, units, None, tuple(missing), tuple(unchanged), broken)
