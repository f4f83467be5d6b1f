"""A parameter of an engine model: one number of a file or an engine, with its dimension.

What the formats and runners share, and :class:`~pitheorem.engines.EngineModel`
builds on: :class:`Parameter` (a row of a model's table), the dimensions
of a joint's coordinate and force (:class:`JointKind`), how a parameter is
named (:func:`identifier`, :func:`unique_name`), the factor of a dimension
under a scaling (:func:`dimension_factor`), how a number is written back
(:func:`attribute_text`, :func:`exact_product`), and the warning for an
element copied unchanged (:func:`warn_unscalable`).  Nothing here imports
an engine.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import re
import warnings
from dataclasses import dataclass
from fractions import Fraction
from typing import ClassVar

from ..dimensions import Dimension
from ..errors import UnscalableParameterError
from ..exact import read_number
from ..immutable import immutable
from ..scaling import float_power

__all__ = [
    "SOURCES",
    "JointKind",
    "Parameter",
    "UnscalableModelWarning",
    "attribute_text",
    "dim",
    "dimension_factor",
    "dimension_factors",
    "exact_product",
    "identifier",
    "new_parameter",
    "unique_name",
    "warn_unscalable",
]

#: where a parameter's value comes from
SOURCES = ("file", "default", "derived", "engine")


class UnscalableModelWarning(UserWarning):
    """An element whose scaling the package cannot check (it is copied unchanged).

    Examples
    --------
    >>> from pitheorem.engines import UnscalableModelWarning
    >>> issubclass(UnscalableModelWarning, UserWarning)
    True
    """


@immutable
@dataclass(frozen=True, slots=True)
class Parameter:
    """One number (or vector of numbers of one dimension) of an engine model.

    Parameters
    ----------
    name : str
        Identifier, used as the variable name in :meth:`EngineModel.system`.
    path : str
        Where it lives: element and attribute in the file, or the engine call.
    value : tuple of float
        The value(s), as the engine resolved them.
    dimension : Dimension or None
        None for a number that mixes dimensions; see `parts`.
    source : {"file", "default", "derived", "engine"}
        The file (or its default classes) set it; the engine's built-in
        default applies; the engine computed it (e.g. an inertia from geoms);
        an engine setting outside the file.
    settable : str
        How to change it: ``"file"`` or the engine call; ``""`` if it
        cannot be changed.
    parts : tuple of (str, Dimension)
        For a mixed number: the dimension each part of it acts with.
    note : str

    Examples
    --------
    >>> from pitheorem.engines import Parameter
    >>> from pitheorem import Dimension
    >>> p = Parameter("body_torso_mass", "body 'torso' mass", (3.5,), Dimension.parse("M"), "derived", "file")
    >>> p.mixed, str(p.dimension)
    (False, 'M')
    """

    name: str
    path: str
    value: tuple[float, ...]
    dimension: Dimension | None
    source: str
    settable: str
    parts: tuple[tuple[str, Dimension], ...] = ()
    note: str = ""

    @property
    def mixed(self) -> bool:
        """Whether the number acts with more than one dimension.

        Examples
        --------
        >>> from pitheorem.engines import Parameter
        >>> from pitheorem import Dimension
        >>> Parameter("d", "joint 'root' damping", (1.0,), None, "file", "file",
        ...           parts=(("lin", Dimension.parse("M T^-1")), ("rot", Dimension.parse("M L^2 T^-1")))).mixed
        True
        """
        return self.dimension is None

    def variables(self) -> dict[str, Dimension]:
        """The system variables this parameter stands for: one, or one per part.

        Examples
        --------
        >>> from pitheorem.engines import Parameter
        >>> from pitheorem import Dimension
        >>> p = Parameter("d", "", (1.0,), None, "file", "file",
        ...               parts=(("lin", Dimension.parse("M T^-1")), ("rot", Dimension.parse("M L^2 T^-1"))))
        >>> sorted(p.variables())
        ['d_lin', 'd_rot']
        """
        if self.dimension is not None:
            return {self.name: self.dimension}
        return {f"{self.name}_{part}": dim for part, dim in self.parts}

    def factor(self, scaling, s) -> float:
        """The factor the scaling multiplies this number by.

        Parameters
        ----------
        scaling : Scaling
            A scaling of a system that holds this number's dimension.
        s : float or Fraction
            The scale factor, as :func:`pitheorem.exact.read_scale_factor`
            reads it.

        Returns
        -------
        float

        Raises
        ------
        UnscalableParameterError
            For a mixed number whose parts need different factors and whose
            value is not zero.

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem.engines import Parameter
        >>> p = Parameter("l", "", (2.0,), pt.Dimension.parse("L"), "file", "file")
        >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1})
        >>> p.factor(sc, 10.0)
        10.0
        """
        if self.dimension is not None:
            return dimension_factor(scaling, s, self.dimension)
        if not self.parts:  # no dimension at all: copied unchanged (see the note)
            return 1.0
        exponents = {part: scaling.exponent_of(dim) for part, dim in self.parts}
        if len(set(exponents.values())) > 1 and any(v != 0 for v in self.value):
            needs = ", ".join(f"s^{Fraction(e)} as {part}" for part, e in exponents.items())
            raise UnscalableParameterError(
                self.name,
                f"the one number {self.path} acts with dimensions {self.dimension_text}, so the scaling "
                f"needs {needs}; set it to 0 or hold the base units it mixes fixed",
            )
        return float_power(s, next(iter(exponents.values())), f"the factor of {self.name!r}")

    @property
    def dimension_text(self) -> str:
        """The dimension as text; for a mixed number, its parts.

        Examples
        --------
        >>> from pitheorem.engines import Parameter
        >>> from pitheorem import Dimension
        >>> Parameter("x", "", (1.0,), Dimension.parse("M L^2"), "file", "file").dimension_text
        'M L^2'
        """
        if self.dimension is not None:
            return str(self.dimension)
        if not self.parts:
            return "mixed"
        return " | ".join(f"{dim} ({part})" for part, dim in self.parts)


#: each field of a :class:`Parameter`, in order: its slot's setter, for :func:`new_parameter`
_FIELD_SETTERS = tuple(Parameter.__dict__[f.name].__set__ for f in dataclasses.fields(Parameter))


def new_parameter(name, path, value, dimension, source, settable, parts=(), note="") -> Parameter:
    """``Parameter(name, path, ...)``, made in half the time, for a reader's table of thousands.

    A frozen dataclass's constructor sets each field through ``object.__setattr__``, a lookup
    of the name per field; here each field's slot is written directly.  The result is the
    same immutable, equal :class:`Parameter` (the class has no checks of its own to skip).

    Parameters
    ----------
    name, path, value, dimension, source, settable, parts, note
        The fields of :class:`Parameter`, in its order.

    Returns
    -------
    Parameter

    Examples
    --------
    >>> from pitheorem.engines.parameters import Parameter, dim, new_parameter
    >>> args = ("body_torso_mass", "body 'torso' mass", (3.5,), dim("M"), "derived", "file")
    >>> new_parameter(*args) == Parameter(*args)
    True
    """
    p = _new(Parameter)
    set_name, set_path, set_value, set_dimension, set_source, set_settable, set_parts, set_note = _FIELD_SETTERS
    set_name(p, name)
    set_path(p, path)
    set_value(p, value)
    set_dimension(p, dimension)
    set_source(p, source)
    set_settable(p, settable)
    set_parts(p, parts)
    set_note(p, note)
    return p


_new = object.__new__


def dimension_factor(scaling, s, dimension) -> float:
    """The factor a scaling multiplies every number of one dimension by.

    Parameters
    ----------
    scaling : Scaling
    s : float or Fraction
        The scale factor, as :func:`pitheorem.exact.read_scale_factor` reads it.
    dimension : Dimension

    Returns
    -------
    float
        ``s`` to the dimension's exponent, by :func:`pitheorem.scaling.float_power`.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines.parameters import dim, dimension_factor
    >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1, "T": 1})
    >>> dimension_factor(sc, 10, dim("L T^-2"))
    0.1
    """
    return float_power(s, scaling.exponent_of(dimension), f"the factor of {dimension}")


def dimension_factors(scaling, s):
    """``factor(d)``, :func:`dimension_factor` of each dimension computed once, and the exponents found.

    A model has hundreds of numbers and coordinates but a handful of dimensions.

    Parameters
    ----------
    scaling : Scaling
    s : float or Fraction
        The scale factor, as :func:`pitheorem.exact.read_scale_factor` reads it.

    Returns
    -------
    (callable, dict)
        ``factor(dimension) -> float``, and the exponent of each dimension asked about so far.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines.parameters import dim, dimension_factors
    >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1, "T": 1})
    >>> factor, exponents = dimension_factors(sc, 10)
    >>> factor(dim("L T^-2")), exponents
    (0.1, {Dimension.parse('L T^-2'): Fraction(-1, 1)})
    """
    factor_of, exponent_of = {}, {}

    def factor(d):
        if d not in factor_of:
            exponent_of[d] = scaling.exponent_of(d)
            factor_of[d] = float_power(s, exponent_of[d], f"the factor of {d}")
        return factor_of[d]

    return factor, exponent_of


def attribute_text(values, factor=None) -> str:
    """Numbers as the text of an XML attribute, each at full precision (its shortest exact repr).

    Parameters
    ----------
    values : iterable of float
        The numbers, as read from the file.
    factor : float, optional
        Multiply each number by it first, exactly: the number read as the
        decimal it prints as (``9.81``, the text of the file), times the
        factor read the same way, rounded once to a float.  So 9.81 times
        10 is written ``98.1``, where the float product is
        98.10000000000001 (9.81 is a hair above its double's neighbour).
        A number that is no finite decimal is multiplied as a float.

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.engines.parameters import attribute_text
    >>> attribute_text([0.1, 2, -1 / 3])
    '0.1 2.0 -0.3333333333333333'
    >>> attribute_text([0, 0, -9.81], 10), repr(-9.81 * 10)
    ('0.0 0.0 -98.1', '-98.10000000000001')
    """
    if factor is None:
        return " ".join(repr(float(v)) for v in values)
    return " ".join(repr(exact_product(v, factor)) for v in values)


def exact_product(value, factor) -> float:
    """A file's number times a factor, as the float nearest the exact product of their decimals.

    The float product rounds twice (once each when the decimals were read,
    once when multiplied); this rounds once, so a scaled value prints as
    the decimal a person would write (98.1 for 9.81 times 10).

    Examples
    --------
    >>> from pitheorem.engines.parameters import exact_product
    >>> exact_product(9.81, 10), 9.81 * 10
    (98.1, 98.10000000000001)
    """
    value, factor = float(value), float(factor)
    if not (math.isfinite(value) and math.isfinite(factor)):
        return value * factor
    return _exact_product(value, factor)


@functools.lru_cache(maxsize=8192)
def _exact_product(value: float, factor: float) -> float:
    """:func:`exact_product` of two finite floats, remembered: a model repeats its numbers and factors."""
    if _power_of_two(factor) and value != 0 and _NORMAL <= abs(value) and _NORMAL <= abs(value * factor) < math.inf:
        # a factor of 2**k read as itself shifts every rounding interval by k binary places: the written
        # number times it rounds to the float product, with no fraction to find (72195 skin vertices)
        return value * factor
    # read as the decimal each prints as (its shortest repr): the number as the file wrote it
    exact = _as_written(value) * _as_written(factor)
    try:
        return float(exact)
    except OverflowError:  # beyond the largest double: the float product is infinite too
        return value * factor


#: the smallest positive normal double: below it the rounding intervals are no longer shifted by a power of two
_NORMAL = 2.2250738585072014e-308


@functools.lru_cache(maxsize=256)
def _power_of_two(factor: float) -> bool:
    """Whether a factor is a power of two that the package's rule reads as exactly itself."""
    mantissa, _ = math.frexp(factor)
    return mantissa == 0.5 and abs(factor) >= _NORMAL and _as_written(factor) == Fraction(factor)


@functools.lru_cache(maxsize=4096)
def _as_written(value: float) -> Fraction:
    """A finite float read by the package's rule (:func:`pitheorem.exact.read_number`), remembered.

    A model repeats its numbers (a robot's six equal struts, one factor for every length), and the
    rule's search for the simplest fraction of a long float is the slow part of writing a scaled file.
    """
    return read_number(value, "a file's number")


@functools.lru_cache(maxsize=256)
def dim(text: str) -> Dimension:
    """Shorthand: parse a dimension formula (each formula parsed once: a Dimension never changes).

    Examples
    --------
    >>> from pitheorem.engines.parameters import dim
    >>> str(dim("M L^2 T^-1"))
    'M L^2 T^-1'
    """
    return Dimension.parse(text)


@immutable
@dataclass(frozen=True, slots=True)
class JointKind:
    """Coordinate and generalised-force dimensions of one joint type, in either engine.

    A hinge (MuJoCo's hinge and ball, URDF's revolute and continuous) turns
    by a dimensionless angle under a torque; a slide (MuJoCo's slide, URDF's
    prismatic) moves by a length under a force.

    Examples
    --------
    >>> from pitheorem.engines.parameters import JointKind
    >>> slide, hinge = JointKind.SLIDE, JointKind.HINGE
    >>> str(slide.q), str(hinge.force), str(slide.per(slide.force, 1, rate=1))
    ('L', 'M L^2 T^-2', 'M T^-1')
    """

    q: Dimension
    force: Dimension
    HINGE: ClassVar[JointKind]
    SLIDE: ClassVar[JointKind]

    def per(self, numerator: Dimension, power: int, rate: int = 0) -> Dimension:
        """``numerator / (q T^-rate)^power``: the dimension of a polynomial coefficient.

        Examples
        --------
        >>> from pitheorem.engines.parameters import JointKind
        >>> str(JointKind.SLIDE.per(JointKind.SLIDE.force, 2))
        'M L^-1 T^-2'
        """
        # remembered by the identities of the two dimensions, which the memo keeps alive (so no other object
        # takes their ids): a model's joints and tendons ask the same few questions thousands of times, and a
        # cache keyed by the dimensions themselves would hash their Fractions each time
        key = (id(self.q), id(numerator), power, rate)
        known = _PER.get(key)
        if known is None:
            if len(_PER) >= 1024:
                _PER.clear()
            known = _PER[key] = (self.q, numerator, numerator * (self.q * _TIME ** (-rate)) ** (-power))
        return known[2]


#: JointKind.per's answers: (id of q, id of the numerator, power, rate) -> (q, the numerator, the answer)
_PER: dict[tuple, tuple[Dimension, Dimension, Dimension]] = {}


_TIME = dim("T")
JointKind.HINGE = JointKind(dim("1"), dim("M L^2 T^-2"))
JointKind.SLIDE = JointKind(dim("L"), dim("M L T^-2"))


def identifier(text: str) -> str:
    """A parameter name made of `text`: other characters become ``_``, a leading digit gets one.

    Examples
    --------
    >>> from pitheorem.engines.parameters import identifier
    >>> identifier("joint 'left hip'"), identifier("3d")
    ('joint__left_hip_', '_3d')
    """
    if text.isascii() and text.isidentifier():  # most names: letters, digits and _ only, not a digit first
        return text
    out = _NOT_WORD.sub("_", text)
    return out if out and not out[0].isdigit() else f"_{out}"


#: a character that is neither alphanumeric (``str.isalnum``) nor ``_``: what ``\w`` matches in a str
#: pattern, one substitution where a generator over the characters took a microsecond per name
_NOT_WORD = re.compile(r"\W")


def unique_name(ident: str, taken: set[str]) -> str:
    """`ident`, or ``ident_2``, ``ident_3``, ...: the first name not in `taken`, which it joins.

    Examples
    --------
    >>> from pitheorem.engines.parameters import unique_name
    >>> taken = {"geom_size"}
    >>> unique_name("geom_size", taken), unique_name("geom_size", taken), sorted(taken)
    ('geom_size_2', 'geom_size_3', ['geom_size', 'geom_size_2', 'geom_size_3'])
    """
    out, k = ident, 2
    while out in taken:
        out, k = f"{ident}_{k}", k + 1
    taken.add(out)
    return out


def warn_unscalable(path: str, element: str, reason: str) -> None:
    """Warn that an element is copied unchanged because its scaling is unknown.

    Examples
    --------
    >>> import warnings
    >>> from pitheorem.engines.parameters import warn_unscalable
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_unscalable("a.xml", "sensor 'x'", "unknown type")
    >>> str(caught[0].message)
    "a.xml: sensor 'x': unknown type"
    """
    warnings.warn(f"{path}: {element}: {reason}", UnscalableModelWarning, stacklevel=3)
