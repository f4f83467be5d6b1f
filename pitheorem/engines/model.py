"""A user's own engine model: its parameters with dimensions, scaled copies, saved files.

:func:`pitheorem.engines.load` reads an MJCF file (in MuJoCo or MJX) or a
URDF file (in PyBullet) and returns an :class:`EngineModel`.  Its :attr:`~EngineModel.parameters`
table lists every number of the model that has a dimension (one
:class:`Parameter` each), next to the engine's hidden constants;
:meth:`~EngineModel.system` turns the table into a :class:`pitheorem.System`
for :func:`pitheorem.search`; :meth:`~EngineModel.scaled` applies a
similarity scaling to every number at once; :meth:`~EngineModel.save`
writes a file the engine loads as it is.

The engine-specific work (reading, writing, running) lives in the backend
modules (``pitheorem.engines.mjcf``, ``urdf``, ``mjx``), each an
implementation of ``pitheorem.engines.backend.EngineBackend``
registered in :mod:`pitheorem.engines.registry`; this module imports none
of them and only holds what they share: besides the model and its parameters, the
dimensions of a joint's coordinate and force (``JointKind``), how a
parameter is named (``identifier``, ``unique_name``), which scalings a
model takes (``check_scaling``), the factor of a dimension under a scaling
(``dimension_factor``) and how a number is written back
(``attribute_text``).  The engines' errors live with every other error, in
:mod:`pitheorem.errors`.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, ClassVar

from ..dimensions import Dimension
from ..errors import EngineModelError, InvalidRequestError, UnscalableParameterError
from ..exact import read_count, read_number, read_scale_factor, read_value
from ..formatting import TableDisplay
from ..immutable import immutable
from ..modelfile import example_path
from ..scaling import Scaling, float_power
from ..simulation import positive_float
from ..system import System
from .backend import HasSceneSettings, RefusesScalings

if TYPE_CHECKING:  # numpy only for the annotations: loading a model's table needs none of it
    import numpy as np

__all__ = [
    "EngineModel",
    "EngineModelError",
    "Parameter",
    "UnscalableModelWarning",
    "UnscalableParameterError",
    "example_path",
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
    >>> from pitheorem.engines.model import dim, dimension_factor
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
    >>> from pitheorem.engines.model import dim, dimension_factors
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
    >>> from pitheorem.engines.model import attribute_text
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
    >>> from pitheorem.engines.model import exact_product
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
    # read as the decimal each prints as (its shortest repr): the number as the file wrote it
    exact = _as_written(value) * _as_written(factor)
    try:
        return float(exact)
    except OverflowError:  # beyond the largest double: the float product is infinite too
        return value * factor


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
    >>> from pitheorem.engines.model import dim
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
    >>> from pitheorem.engines.model import JointKind
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
        >>> from pitheorem.engines.model import JointKind
        >>> str(JointKind.SLIDE.per(JointKind.SLIDE.force, 2))
        'M L^-1 T^-2'
        """
        return _per(self.q, numerator, power, rate)


@functools.lru_cache(maxsize=256)
def _per(q: Dimension, numerator: Dimension, power: int, rate: int) -> Dimension:
    """:meth:`JointKind.per`, remembered: a model's joints and tendons ask the same few questions."""
    return numerator * (q * _TIME ** (-rate)) ** (-power)


_TIME = dim("T")
JointKind.HINGE = JointKind(dim("1"), dim("M L^2 T^-2"))
JointKind.SLIDE = JointKind(dim("L"), dim("M L T^-2"))


def identifier(text: str) -> str:
    """A parameter name made of `text`: other characters become ``_``, a leading digit gets one.

    Examples
    --------
    >>> from pitheorem.engines.model import identifier
    >>> identifier("joint 'left hip'"), identifier("3d")
    ('joint__left_hip_', '_3d')
    """
    out = "".join(c if c.isalnum() or c == "_" else "_" for c in text)
    return out if out and not out[0].isdigit() else f"_{out}"


def unique_name(ident: str, taken: set[str]) -> str:
    """`ident`, or ``ident_2``, ``ident_3``, ...: the first name not in `taken`, which it joins.

    Examples
    --------
    >>> from pitheorem.engines.model import unique_name
    >>> taken = {"geom_size"}
    >>> unique_name("geom_size", taken), unique_name("geom_size", taken), sorted(taken)
    ('geom_size_2', 'geom_size_3', ['geom_size', 'geom_size_2', 'geom_size_3'])
    """
    out, k = ident, 2
    while out in taken:
        out, k = f"{ident}_{k}", k + 1
    taken.add(out)
    return out


@immutable
class EngineModel(TableDisplay):
    """A MuJoCo or PyBullet model read from its file, with its numbers.

    Every dimensional number of the file and of the engine's settings is a
    :class:`Parameter`.

    Build one with :func:`pitheorem.engines.load`; :meth:`scaled` returns
    another.  The engine-specific part is a backend object (an
    ``pitheorem.engines.backend.EngineBackend``).  A model
    is not changed after it is made: :meth:`scaled`, :meth:`with_values`,
    :meth:`multiplied` and :meth:`with_settings` return new models.

    Attributes
    ----------
    engine : {"mujoco", "mjx", "pybullet"}
    path : str
        The file it was read from ("" for a scaled copy not yet saved).
    parameters : tuple of Parameter
        Every dimensional number of the file and of the engine settings.

    Examples
    --------
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> model.engine, "g" in model.system().variables
    ('mujoco', True)
    """

    __slots__ = ("_backend", "_groups", "_origin", "_parameters", "_system", "_units", "engine", "path")

    def __init__(self, backend, engine: str, path: str, units=None, origin: tuple | None = None):
        units = tuple((units or {"M": "kg", "L": "m", "T": "s"}).items())
        # origin: (the model this one is a copy of, the factor of each of its parameters), for a copy made
        # by scaled(), with_values() or multiplied(); its table is then known without reading the copy
        for name, value in (
            ("_backend", backend),
            ("engine", engine),
            ("path", path),
            ("_parameters", None),
            ("_units", units),
            ("_groups", None),
            ("_origin", origin),
            ("_system", None),
        ):
            object.__setattr__(self, name, value)

    @property
    def units(self) -> dict[str, str]:
        """The units the model's numbers are in: a unit name for each of M, L and T.

        SI (``kg``, ``m``, ``s``) unless :func:`load` was told otherwise, or
        the file records its own (a file :meth:`converted` wrote).

        Examples
        --------
        >>> from pitheorem import engines
        >>> engines.load(engines.example_path("pendulum.xml")).units
        {'M': 'kg', 'L': 'm', 'T': 's'}
        """
        return dict(self._units)

    def converted(self, **units) -> EngineModel:
        """The same model in other units: every number by its dimension.

        A change of units is a similarity scaling, so this is
        :meth:`scaled` with :meth:`pitheorem.Scaling.from_unit_change`
        (see ``pitheorem.engines.units``): gravity, densities,
        viscosity, stiffness, damping, gains, margins and solref time
        constants, the time step and the keyframes all follow.

        Parameters
        ----------
        **units : str or number
            New units for some of ``M``, ``L`` and ``T``: a name pint
            reads (``L="mm"``), or the unit's size in SI units
            (``L=0.001``).  The others keep the model's.

        Returns
        -------
        EngineModel
            Unsaved; :meth:`save` writes a file that records its units.

        Raises
        ------
        UnitError
            For a unit name pint does not read as that dimension.
        EngineModelError
            For a URDF model and units other than SI (URDF is SI by its
            specification).

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> cm = model.converted(L="cm", M="g")
        >>> cm.units, cm.parameter("g").value
        ({'M': 'g', 'L': 'cm', 'T': 's'}, (981.0,))
        """
        from .units import convert

        return convert(self, units)

    def in_units(self, units) -> EngineModel:
        """This model's numbers, unchanged, declared to be in other units.

        What ``load(..., units=...)`` does; :meth:`converted` changes the
        numbers instead.

        Parameters
        ----------
        units : mapping of str to str
            The units of M, L and T (``pitheorem.engines.units.read_units``).

        Returns
        -------
        EngineModel

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml")).in_units({"L": "cm"})
        >>> model.units, model.parameter("g").value
        ({'M': 'kg', 'L': 'cm', 'T': 's'}, (9.81,))
        """
        import copy

        from .units import SI, read_units, record, refuse_urdf

        units = read_units(units)
        if self.engine == "pybullet" and units != SI:
            refuse_urdf(self, units)
        if units == self.units:
            return self
        backend = copy.copy(self._backend)  # an MJCF model records its units in its spec, so a save keeps them
        backend.spec = self._backend.spec.copy()
        record(backend.spec, units)
        return EngineModel(backend, self.engine, self.path, units)

    @property
    def parameters(self) -> tuple[Parameter, ...]:
        """Every dimensional number of the file and the engine settings, read when asked.

        Examples
        --------
        >>> from pitheorem import engines
        >>> engines.load(engines.example_path("pendulum.xml")).parameters[1].name
        'g'
        """
        if self._parameters is None:  # a scaled copy that is only run never lists its numbers
            object.__setattr__(self, "_parameters", tuple(self._backend.parameters()))
        return self._parameters

    def _by_dimension(self) -> tuple[tuple, tuple[Parameter, ...]]:
        """The parameters' names grouped by dimension, and the mixed parameters; found once.

        Hundreds of parameters share a handful of dimensions: a scaling computes each factor once.
        """
        if self._groups is None:
            groups: dict = {}
            for p in self.parameters:
                if p.dimension is not None:
                    groups.setdefault(p.dimension, []).append(p.name)
            mixed = tuple(p for p in self.parameters if p.dimension is None)
            object.__setattr__(self, "_groups", (tuple((d, tuple(n)) for d, n in groups.items()), mixed))
        return self._groups

    def __copy__(self) -> EngineModel:
        return self  # nothing of it changes, so a copy is the model itself

    def __deepcopy__(self, memo) -> EngineModel:
        return self

    def __repr__(self) -> str:
        return f"<EngineModel {self.engine} {self.path or '(unsaved)'}: {len(self.parameters)} parameters>"

    def parameter(self, name: str) -> Parameter:
        """The parameter of a given name.

        Parameters
        ----------
        name : str
            A name of :attr:`parameters` (e.g. ``"g"``).

        Returns
        -------
        Parameter

        Raises
        ------
        UnknownVariableError
            For a name that is no parameter.

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> model.parameter("g").value
        (9.81,)
        """
        for p in self.parameters:
            if p.name == name:
                return p
        from ..errors import UnknownVariableError

        raise UnknownVariableError(name, tuple(p.name for p in self.parameters), "the model's parameters")

    def system(self) -> System:
        """The :class:`pitheorem.System` of every parameter and hidden constant.

        ``g`` is the magnitude of gravity and ``t`` is time; a mixed number
        contributes one variable per part (``name_lin``, ``name_rot``).

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> res = pt.search(model.system(), scale={"g": 1})
        >>> res.feasible
        True
        """
        if self._system is None:  # built once: a System never changes, and neither does this model
            dims: dict[str, Dimension] = {}
            for p in self.parameters:
                dims.update(p.variables())
            dims["t"] = _TIME
            object.__setattr__(self, "_system", System(dims))
        return self._system

    def table(self) -> str:
        """The parameters as aligned plain text: name, dimension, value, source, path.

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> model.table().splitlines()[0].split()
        ['name', 'dimension', 'value', 'source', 'path']
        """
        from ..formatting.text import parameter_table

        return parameter_table(self)

    def scaled(self, scaling, s) -> EngineModel:
        """A copy with every parameter multiplied by ``s`` to its exponent.

        Parameters
        ----------
        scaling : Scaling
            A change of units of :meth:`system` (e.g. from
            :func:`pitheorem.search`).
        s : float
            The scale factor, positive.

        Returns
        -------
        EngineModel

        Raises
        ------
        UnscalableParameterError
            For a mixed number the scaling would split, or an engine
            constant the scaling must change but no call can.

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
        >>> round(model.scaled(sc, 10).parameter("g").value[0], 12)
        98.1
        """
        s = read_scale_factor(s)
        check_scaling(scaling)
        factors, refused = {}, []
        by_dimension, mixed = self._by_dimension()
        for dimension, names in by_dimension:
            factor = dimension_factor(scaling, s, dimension)
            factors.update(dict.fromkeys(names, factor))
        for p in mixed:  # every number the scaling cannot reach, not only the first
            try:
                factors[p.name] = p.factor(scaling, s)
            except UnscalableParameterError as err:
                refused.append(err)
        refuses = isinstance(self._backend, RefusesScalings)
        if refuses:
            refused.extend(self._backend.unscalable(factors))
        if len(refused) > 1:
            names = ", ".join(repr(err.name) for err in refused[:6])
            more = f" and {len(refused) - 6} more" if len(refused) > 6 else ""
            reasons = {}  # one reason per kind: the damping of every link reads alike but for the link's name
            for err in refused:
                reasons.setdefault(err.reason.split(";")[0].split(" acts ", 1)[-1], err.reason.split(";")[0])
            remedy = self._backend.unscalable_remedy if refuses else ""
            raise UnscalableParameterError(
                refused[0].name,
                f"{len(refused)} numbers cannot follow the scaling: {names}{more}. "
                + "; ".join(reasons.values())
                + (f". {remedy}" if remedy else ""),
            )
        if refused:
            raise refused[0]
        return self._times(factors, scaling, s)

    def with_values(self, **values) -> EngineModel:
        """A copy with some parameters set to new values (each must be one number).

        Parameters
        ----------
        **values : float
            Parameter name to its new value, e.g. ``tolerance=0``.

        Returns
        -------
        EngineModel
            An unsaved copy with those values (``path`` is ``""``); this
            model keeps its own.

        Raises
        ------
        UnknownVariableError
            For a name that is no parameter.
        InvalidRequestError
            For a vector parameter, or one whose value is 0 now (it cannot
            be reached by a factor).

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> model.with_values(tolerance=0).parameter("tolerance").value
        (0.0,)
        """
        factors = {}
        for name, value in values.items():
            p = self.parameter(name)
            if len(p.value) != 1 or p.value[0] == 0:
                raise InvalidRequestError(f"with_values sets one nonzero number; {name} is {p.value}")
            factors[name] = float(read_value(value, f"the value of {name!r}")) / p.value[0]
        # multiplied(...) by value / current value, except that the factor may be 0 or negative
        return self._times(factors)

    def multiplied(self, **factors) -> EngineModel:
        """A copy with some parameters multiplied by factors (a vector entry by entry).

        For the runs a similarity scaling is *not*: scale some numbers and
        leave others alone, then compare with :func:`~pitheorem.engines.verify`
        (``scaled=``) to see what breaks.

        Parameters
        ----------
        **factors : float
            Parameter name to a positive, finite factor.

        Returns
        -------
        EngineModel
            An unsaved copy (``path`` is ``""``).

        Raises
        ------
        UnknownVariableError
            For a name that is no parameter.
        InvalidRequestError
            For a factor that is not a positive, finite number.

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> model.multiplied(g=2).parameter("g").value
        (19.62,)
        """
        for name, factor in factors.items():
            self.parameter(name)
            factors[name] = positive_float(factor, f"the factor for {name!r}")
        return self._times(factors)

    def _times(self, factors: dict[str, float], scaling=None, s=None) -> EngineModel:
        """The copy of :meth:`scaled`, :meth:`with_values` and :meth:`multiplied`: checked factors applied."""
        return EngineModel(
            self._backend.scaled(factors, scaling, s), self.engine, "", self.units, origin=(self, dict(factors))
        )

    def save(self, path) -> Path:
        """Write the model as a file the engine loads as is.

        For PyBullet, the settings a URDF cannot hold (gravity, time step,
        engine parameters, per-link dynamics) go beside it, as data
        (``<path>.settings.json``) and as a runnable snippet
        (``<path>.settings.py``).

        Parameters
        ----------
        path : str or Path

        Returns
        -------
        Path

        Examples
        --------
        >>> import os, tempfile
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> with tempfile.TemporaryDirectory() as tmp:
        ...     out = model.save(os.path.join(tmp, "copy.xml"))
        ...     engines.load(out).parameter("g").value
        (9.81,)
        """
        path = Path(path)
        self._backend.save(path)
        return path

    def with_settings(self, **changes) -> EngineModel:
        """A copy with other engine settings (PyBullet only).

        Parameters
        ----------
        **changes
            ``split_impulse`` (bool), ``ground`` (bool: add a ground plane),
            ``fixed_base`` (bool) and ``base_position`` (three floats).

        Returns
        -------
        EngineModel

        Raises
        ------
        InvalidRequestError
            For an MJCF model (its settings are parameters: use
            :meth:`with_values`) or an unknown setting.

        Examples
        --------
        >>> import tempfile, pathlib
        >>> from pitheorem import engines
        >>> urdf = pathlib.Path(tempfile.mkdtemp()) / "box.urdf"
        >>> _ = urdf.write_text('<robot name="box"><link name="base"><inertial><mass value="1"/>'
        ...                     '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>')
        >>> engines.load(urdf).with_settings(fixed_base=True).settings()["loadURDF"]["useFixedBase"]
        True
        >>> import pitheorem as pt
        >>> try:
        ...     engines.load(engines.example_path("pendulum.xml")).with_settings(ground=True)
        ... except pt.InvalidRequestError as err:
        ...     print(err)
        an MJCF model keeps its settings in the file; use with_values(...)
        """
        if not isinstance(self._backend, HasSceneSettings):
            raise InvalidRequestError("an MJCF model keeps its settings in the file; use with_values(...)")
        return EngineModel(self._backend.with_settings(**changes), self.engine, self.path, self.units)

    def settings(self) -> dict:
        """Engine settings the file cannot hold, as data (empty for MuJoCo).

        Examples
        --------
        >>> from pitheorem import engines
        >>> engines.load(engines.example_path("pendulum.xml")).settings()
        {}
        """
        return self._backend.settings()

    # -- running it: what a user needs of the engine, without handing out the engine's object ----------

    def timestep(self) -> float:
        """The engine's time step, in the model's time unit.

        Examples
        --------
        >>> from pitheorem import engines
        >>> engines.load(engines.example_path("pendulum.xml")).timestep()
        0.002
        """
        return self._backend.timestep()

    def run(self, n_steps: int, controls=None, *, policy=None, initial=None) -> np.ndarray:
        """Step the model ``n_steps`` times from its initial state, in its engine.

        Parameters
        ----------
        n_steps : int
        controls : array_like or callable, optional
            The actuators' inputs: rows (one per step), or a function of
            the step's start time giving one row.  None: no input.
        policy : callable, optional
            A closed-loop controller giving the inputs of each step
            (MuJoCo's ``policy(mjmodel, mjdata)``, called with everything
            in ``mjdata`` computed for the state it acts on; PyBullet's
            ``policy(client, body, t)``; MJX runs open loop).
        initial : array_like, optional
            The state to start from, as a first row of the result (the
            columns :meth:`coordinates` names); default the model's own
            start (MuJoCo: its reference pose at rest; PyBullet: the pose
            the file loads in).

        Returns
        -------
        numpy.ndarray
            One row per state, ``n_steps + 1`` of them: the coordinates,
            their rates, and the actuators' activations (MuJoCo, MJX) as
            :meth:`coordinates` names them.

        Raises
        ------
        InvalidRequestError
            For an ``n_steps`` that is no whole number of 0 or more, or
            an ``initial`` of the wrong length or with a number that is
            not finite.

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> model.run(10, controls=lambda t: [0.1]).shape
        (11, 2)
        >>> model.run(1, initial=[0.5, 0.0])[0]
        array([0.5, 0. ])
        """
        import numpy as np

        n_steps = read_count(n_steps, "n_steps")
        if initial is not None:
            names = self.coordinates()[0]
            try:
                initial = np.array(initial, dtype=float).reshape(-1)
            except (TypeError, ValueError):
                raise InvalidRequestError(
                    f"initial is a row of {len(names)} numbers, got {initial!r}", culprit=initial
                ) from None
            if len(initial) != len(names) or not np.all(np.isfinite(initial)):
                raise InvalidRequestError(
                    f"initial is a row of {len(names)} finite numbers ({', '.join(names)}), got {initial.tolist()!r}",
                    culprit=initial,
                )
        return self._backend.run(n_steps, controls, policy=policy, initial=initial)

    def coordinates(self) -> tuple[list[str], list[Dimension]]:
        """The names and dimensions of the columns :meth:`run` returns.

        Examples
        --------
        >>> from pitheorem import engines
        >>> names, dims = engines.load(engines.example_path("pendulum.xml")).coordinates()
        >>> names, [str(d) for d in dims]
        (['qpos[hinge]', 'qvel[hinge]'], ['1', 'T^-1'])
        """
        return self._backend.coordinate_dimensions()

    def inputs(self) -> tuple[list[Dimension], np.ndarray, np.ndarray]:
        """The actuators' inputs: each one's dimension, and their lower and upper limits.

        A limit is infinite where the engine sets none (a URDF's joint
        torques are unlimited as PyBullet runs them).

        Examples
        --------
        >>> from pitheorem import engines
        >>> dims, low, high = engines.load(engines.example_path("pendulum.xml")).inputs()
        >>> [str(d) for d in dims], low, high
        (['M L^2 T^-2'], array([-1.]), array([1.]))
        """
        low, high = self._backend.control_ranges()
        return list(self._backend.control_dimensions()), low, high


def check_scaling(scaling) -> Scaling:
    """A scaling an engine model can take: a change of units over M, L and T.

    Parameters
    ----------
    scaling : Scaling
        From :func:`pitheorem.search` on :meth:`EngineModel.system`.

    Returns
    -------
    Scaling
        The same scaling.

    Raises
    ------
    InvalidRequestError
        For anything else: no Scaling, a symmetry of particular equations
        (no change of units), or a system without one of M, L and T.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines.model import check_scaling
    >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L"}), {"L": 1})
    >>> try:
    ...     check_scaling(sc)
    ... except pt.InvalidRequestError as err:
    ...     print(err)
    the scaling's system has no base dimension 'M'; search on model.system()
    """
    if not isinstance(scaling, Scaling):
        raise InvalidRequestError(f"scaling must be a pitheorem Scaling, got {type(scaling).__name__}")
    if not scaling.is_unit_change:
        raise InvalidRequestError(
            "the scaling is no change of units; an engine model needs one "
            "(use a scaling from pt.search(model.system(), ...))"
        )
    missing = [b for b in ("M", "L", "T") if b not in scaling.system.base_dimensions]
    if missing:
        raise InvalidRequestError(
            f"the scaling's system has no base dimension {missing[0]!r}; search on model.system()"
        )
    return scaling


def warn_unscalable(path: str, element: str, reason: str) -> None:
    """Warn that an element is copied unchanged because its scaling is unknown.

    Examples
    --------
    >>> import warnings
    >>> from pitheorem.engines.model import warn_unscalable
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_unscalable("a.xml", "sensor 'x'", "unknown type")
    >>> str(caught[0].message)
    "a.xml: sensor 'x': unknown type"
    """
    warnings.warn(f"{path}: {element}: {reason}", UnscalableModelWarning, stacklevel=3)
