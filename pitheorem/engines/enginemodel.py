"""A user's own engine model: its parameters with dimensions, scaled copies, saved files.

:func:`pitheorem.engines.load` reads an MJCF file (in MuJoCo or MJX) or a
URDF file (in PyBullet) and returns an :class:`EngineModel`.  Its :attr:`~EngineModel.parameters`
table lists every number of the model that has a dimension (one
:class:`Parameter` each), next to the engine's hidden constants;
:meth:`~EngineModel.system` turns the table into a :class:`pitheorem.System`
for :func:`pitheorem.search`; :meth:`~EngineModel.scaled` applies a
similarity scaling to every number at once; :meth:`~EngineModel.save`
writes a file the engine loads as it is.

The work that depends on a file format (reading, writing) lives in
:mod:`pitheorem.engines.fileformats`, and the work that depends on an engine
(compiling, running) in :mod:`pitheorem.engines.runners`, each module
registered in :mod:`pitheorem.engines.registry`; this module imports
none of them.  A parameter of the table is a
:class:`~pitheorem.engines.parameters.Parameter`; which scalings a model
takes is :func:`check_scaling`.  The engines' errors live with every
other error, in :mod:`pitheorem.errors`.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from ..dimensions import Dimension
from ..errors import EngineModelError, InputsNotKeptError, InvalidRequestError, UnscalableParameterError
from ..exact import read_count, read_scale_factor, read_value
from ..formatting import TableDisplay
from ..immutable import immutable
from ..modelfile import example_path
from ..scaling import Scaling
from ..simulation import positive_float
from ..system import System
from .parameters import Parameter, UnscalableModelWarning, dim, dimension_factor
from .protocols import HasSceneSettings, KeepsInputs, RefusesScalings

if TYPE_CHECKING:  # numpy only for the annotations: loading a model's table needs none of it
    import numpy as np

__all__ = [
    "MAX_STEPS",
    "EngineModel",
    "EngineModelError",
    "InputsNotKeptError",
    "Parameter",
    "UnscalableModelWarning",
    "UnscalableParameterError",
    "example_path",
]

#: the most steps a run is asked for (``run``, ``verify``): a run keeps a row of every coordinate per step (10**7
#: rows of a humanoid's 55 are 4.4 GB), and a verification makes ten runs and more
MAX_STEPS = 10**7

_TIME = dim("T")


@immutable
class EngineModel(TableDisplay):
    """A MuJoCo or PyBullet model read from its file, with its numbers.

    Every dimensional number of the file and of the engine's settings is a
    :class:`Parameter`.

    Build one with :func:`pitheorem.engines.load`; :meth:`scaled` returns
    another.  The engine-specific part is a backend object (an
    ``pitheorem.engines.protocols.Runner``).  A model
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

    __slots__ = ("_by_name", "_groups", "_origin", "_parameters", "_runner", "_system", "_units", "engine", "path")

    def __init__(self, backend, engine: str, path: str, units=None, origin: tuple | None = None):
        units = tuple((units or {"M": "kg", "L": "m", "T": "s"}).items())
        # origin: (the model this one is a copy of, the factor of each of its parameters), for a copy made
        # by scaled(), with_values() or multiplied(); its table is then known without reading the copy
        for name, value in (
            ("_runner", backend),
            ("engine", engine),
            ("path", path),
            ("_parameters", None),
            ("_units", units),
            ("_groups", None),
            ("_by_name", None),
            ("_origin", origin),
            ("_system", None),
        ):
            object.__setattr__(self, name, value)

    @property
    def runner(self):
        """What runs this model: its engine's runner, holding the format's document.

        The analysis (:func:`~pitheorem.engines.verify`, :func:`~pitheorem.engines.audit`,
        :func:`~pitheorem.engines.check`, the fit) asks it only what
        ``pitheorem.engines.protocols.Runner`` and its optional
        capabilities name (tests/test_architecture.py holds them to it).

        Examples
        --------
        >>> from pitheorem import engines
        >>> from pitheorem.engines.protocols import Runner
        >>> runner = engines.load(engines.example_path("pendulum.xml")).runner
        >>> isinstance(runner, Runner), runner.precision
        (True, 'float64')
        """
        return self._runner

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

    def converted(self, fit=None, /, *, keep_inputs: bool = False, **units) -> EngineModel:
        """The same model in other units: every number by its dimension.

        A change of units is a similarity scaling, so this is
        :meth:`scaled` with :meth:`pitheorem.Scaling.from_unit_change`
        (see ``pitheorem.engines.units``): gravity, densities,
        viscosity, stiffness, damping, gains, margins and solref time
        constants, the time step and the keyframes all follow.

        Parameters
        ----------
        fit : UnitFit, optional
            The units :func:`pitheorem.fit_units` chose for this model
            (its :attr:`~pitheorem.UnitFit.units`), instead of
            `units`.
        keep_inputs : bool
            Keep the value of every control input: each actuator's factor
            goes on its gain instead of its input range (see
            :meth:`scaled`).  Default False: the inputs are converted too.
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
        InvalidRequestError
            For a `fit` that is no UnitFit of an engine model, or both a
            `fit` and `units`.
        InputsNotKeptError
            With `keep_inputs`, for an engine whose inputs have no gain
            to carry the factors (PyBullet's).

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> cm = model.converted(L="cm", M="g")
        >>> cm.units, cm.parameter("g").value
        ({'M': 'g', 'L': 'cm', 'T': 's'}, (981.0,))
        >>> cm.inputs()[1:], model.converted(L="cm", M="g", keep_inputs=True).inputs()[1:]
        ((array([-10000000.]), array([10000000.])), (array([-1.]), array([1.])))
        """
        from ..unitfit import UnitFit
        from .units import convert

        if fit is not None:
            if not isinstance(fit, UnitFit) or fit.units is None:
                raise InvalidRequestError(
                    f"converted takes the fit of an engine model (pt.fit_units(model)), got {type(fit).__name__}",
                    culprit=fit,
                )
            if units:
                raise InvalidRequestError(
                    f"give converted a fit or units, not both (units {', '.join(sorted(units))})", culprit=fit
                )
            units = fit.units
        return convert(self, units, keep_inputs=keep_inputs)

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
        from .units import read_units

        units = read_units(units)
        self._runner.check_units(units)  # a format fixed in its units (URDF: SI) refuses others, by name
        if units == self.units:
            return self
        backend = self._runner.in_units(units)  # an MJCF model records its units in its spec: a save keeps them
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
            object.__setattr__(self, "_parameters", tuple(self._runner.parameters()))
        return self._parameters

    @property
    def copied_from(self) -> tuple | None:
        """The model this one is a copy of, and each parameter's factor.

        ``(original, factors)`` for a copy made by :meth:`scaled`,
        :meth:`with_values` or :meth:`multiplied`: the model it is a copy of and the factor of each of its parameters
        (its table is then known without reading the copy); None for a
        model read from a file.

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> copy = model.multiplied(timestep=0.5)
        >>> copy.copied_from[0] is model, copy.copied_from[1]["timestep"], model.copied_from
        (True, 0.5, None)
        """
        return self._origin

    def by_dimension(self) -> tuple[tuple, tuple[Parameter, ...]]:
        """The parameters' names grouped by dimension, and the mixed ones; found once.

        Hundreds of parameters share a handful of dimensions: a scaling
        computes each factor once.

        Returns
        -------
        tuple
            ``((dimension, names), ...)`` in the table's order, and the
            mixed parameters.

        Examples
        --------
        >>> from pitheorem import engines
        >>> groups, mixed = engines.load(engines.example_path("pendulum.xml")).by_dimension()
        >>> str(groups[0][0]), groups[0][1][:1], [p.name for p in mixed][:1]
        ('T', ('timestep',), ['tolerance'])
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
        if self._by_name is None:  # a dictionary once: a negative control names thousands of masses
            object.__setattr__(self, "_by_name", {p.name: p for p in self.parameters})
        found = self._by_name.get(name) if isinstance(name, str) else None
        if found is not None:
            return found
        from ..errors import UnknownVariableError

        raise UnknownVariableError(name, tuple(p.name for p in self.parameters), "the model's parameters")

    def system(self) -> System:
        """The :class:`pitheorem.System` of every parameter and hidden constant.

        ``g`` is the magnitude of gravity and ``t`` is time; a mixed number
        contributes one variable per part (``name_lin``, ``name_rot``).  Its
        default repeaters are the robot's numbers (:meth:`default_repeating`),
        so that ``system().pi_groups()`` gives the groups ``pitheorem groups``
        prints.

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> res = pt.search(model.system(), scale={"g": 1})
        >>> res.feasible
        True
        >>> model.system().pi_groups().repeating
        ('g', 'body_arm_mass', 'geom_rod_density')
        """
        if self._system is None:  # built once: a System never changes, and neither does this model
            dims: dict[str, Dimension] = {}
            for p in self.parameters:
                dims.update(p.variables())
            dims["t"] = _TIME
            system = System(dims)
            object.__setattr__(self, "_system", system.with_repeating(self._robot_repeaters(system)))
        return self._system

    def default_repeating(self) -> tuple[str, ...]:
        """The repeaters ``pitheorem groups`` takes: the robot's numbers, no solver's.

        The first valid set (in :meth:`pitheorem.System.bases` order) of
        :meth:`system` that uses none of the engine's settings (MJCF's
        ``<option>`` numbers but gravity, wind, density and viscosity:
        ``ccd_tolerance``, ``o_margin``, ...; the engine parameters and
        per-link defaults a URDF file does not state), no time variable, no
        number that is 0 and no vector; the conditions are dropped, last
        first, where no set meets them.

        Returns
        -------
        tuple of str

        The system carries them: :meth:`system` ``.pi_groups()`` uses them
        when given no repeaters.

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> model.default_repeating()
        ('g', 'body_arm_mass', 'geom_rod_density')
        >>> model.system().pi_groups().repeating
        ('g', 'body_arm_mass', 'geom_rod_density')
        """
        return self.system().default_repeating()

    def _robot_repeaters(self, system: System) -> tuple[str, ...]:
        """:meth:`default_repeating`, found in the system without default repeaters of its own."""
        settings = {p.name for p in self.parameters if _engine_setting(p)}
        zero = {p.name for p in self.parameters if not p.mixed and all(v == 0 for v in p.value)}
        vectors = {p.name for p in self.parameters if len(p.value) != 1}
        time = set(system.time_variables)
        for avoid in (settings | zero | time | vectors, settings | zero | time, zero | time, zero):
            first = system.first_basis(exclude=[n for n in system.variables if n in avoid])
            if first is not None:
                return first
        return system.default_repeating()

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

    def scaled(self, scaling, s, *, keep_inputs: bool = False) -> EngineModel:
        """A copy with every parameter multiplied by ``s`` to its exponent.

        Parameters
        ----------
        scaling : Scaling
            A change of units of :meth:`system` (e.g. from
            :func:`pitheorem.search`).
        s : float
            The scale factor, positive.
        keep_inputs : bool
            Keep the value of every control input (an actuator's
            ``ctrl``): each actuator's factor goes on the gain that turns
            its input into a force (its ``gainprm``), its control and
            activation ranges keep their values, and so do the keyframes'
            inputs; biases and force ranges take their own factors as
            always.  For a policy that acts in normalised inputs.
            Default False: an input is scaled by its dimension (a motor's
            by the force's factor, a position servo's by the length's),
            for inputs that are physical commands.

        Returns
        -------
        EngineModel

        Raises
        ------
        UnscalableParameterError
            For a mixed number the scaling would split, or an engine
            constant the scaling must change but no call can.
        InputsNotKeptError
            With `keep_inputs`, for an engine whose inputs have no gain
            to carry the factors (PyBullet's: a joint's force, applied as
            given).

        Examples
        --------
        >>> import pitheorem as pt
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
        >>> round(model.scaled(sc, 10).parameter("g").value[0], 12)
        98.1
        >>> longer = pt.Scaling.from_unit_change(model.system(), {"L": 1})  # lengths x s: torques x s^2
        >>> model.scaled(longer, 4).inputs()[2], model.scaled(longer, 4).parameter("actuator_torque_gainprm_gain").value
        (array([16.]), (1.0,))
        >>> kept = model.scaled(longer, 4, keep_inputs=True)
        >>> kept.inputs()[2], kept.parameter("actuator_torque_gainprm_gain").value
        (array([1.]), (16.0,))
        """
        s = read_scale_factor(s)
        check_scaling(scaling)
        factors, refused = {}, []
        by_dimension, mixed = self.by_dimension()
        for dimension, names in by_dimension:
            factor = dimension_factor(scaling, s, dimension)
            factors.update(dict.fromkeys(names, factor))
        for p in mixed:  # every number the scaling cannot reach, not only the first
            try:
                factors[p.name] = p.factor(scaling, s)
            except UnscalableParameterError as err:
                refused.append(err)
        refuses = isinstance(self._runner, RefusesScalings)
        if refuses:
            refused.extend(self._runner.unscalable(factors))
        if len(refused) > 1:
            names = ", ".join(repr(err.name) for err in refused[:6])
            more = f" and {len(refused) - 6} more" if len(refused) > 6 else ""
            reasons, remedies = {}, {}  # one of each kind: every link's damping reads alike but for its name
            for err in refused:
                reason, _, remedy = err.reason.partition(";")
                reasons.setdefault(reason.split(" acts ", 1)[-1], reason.strip())
                if remedy.strip():
                    remedies.setdefault(remedy.strip(), None)
            if refuses and self._runner.unscalable_remedy:
                remedies = {self._runner.unscalable_remedy: None}
            sentences = ["; ".join(reasons.values()), *remedies]
            raise UnscalableParameterError(
                refused[0].name,
                f"{len(refused)} numbers cannot follow the scaling: {names}{more}. "
                + " ".join(f"{text[:1].upper()}{text[1:].rstrip('.')}." for text in sentences),
            )
        if refused:
            raise refused[0]
        if keep_inputs:
            return self._keeping_inputs(factors, scaling, s)
        return self._times(factors, scaling, s)

    def _keeping_inputs(self, factors: dict[str, float], scaling, s) -> EngineModel:
        """:meth:`scaled` with ``keep_inputs``: each number an input passes through divided by the input's factor."""
        controls = self._runner.control_dimensions()
        carriers = self._runner.input_parameters() if isinstance(self._runner, KeepsInputs) else None
        if carriers is None or len(carriers) != len(controls):  # a URDF's joint motors: no gain in the file
            raise InputsNotKeptError(self.engine, "its inputs are joint forces, with no gain to carry a factor")
        factors = dict(factors)
        dimensions = {p.name: p.dimension for p in self.parameters}
        for ctrl, powers in zip(controls, carriers, strict=True):
            for name, power in powers.items():  # the factor of the dimension with the input's taken out, exactly
                factors[name] = dimension_factor(scaling, s, dimensions[name] / ctrl**power)
        runner = self._runner.scaled_keeping_inputs(factors, scaling, s)
        # no origin: the copy states numbers its factors alone do not give (a compiled range, a damping for a
        # damping ratio), so a copy of it is made from it, not from this model times the factors
        return EngineModel(runner, self.engine, "", self.units)

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
            self._runner.scaled(factors, scaling, s), self.engine, "", self.units, origin=(self, dict(factors))
        )

    def save(self, path, *, copy_assets: bool = False) -> Path:
        """Write the model as a file the engine loads as is.

        Its mesh, texture and height-field files are named relative to the
        written file, so the folder holding both can move; with
        `copy_assets` they are copied into ``<stem>_assets`` beside it, and
        the written file and that folder travel alone.  For PyBullet, the
        settings a URDF cannot hold (gravity, time step, engine
        parameters, per-link dynamics) go beside it, as data
        (``<path>.settings.json``) and as a runnable snippet
        (``<path>.settings.py``).

        Parameters
        ----------
        path : str or Path
        copy_assets : bool
            Copy the asset files beside the written file (default False:
            name the originals, relative to it).

        Returns
        -------
        Path

        Raises
        ------
        InvalidRequestError
            For a path that is a folder, or in a folder that does not exist,
            or whose suffix the model's format does not read.

        Examples
        --------
        >>> import os, tempfile
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("pendulum.xml"))
        >>> with tempfile.TemporaryDirectory() as tmp:
        ...     out = model.save(os.path.join(tmp, "copy.xml"))
        ...     engines.load(out).parameter("g").value
        (9.81,)
        >>> try:
        ...     model.save("/no/such/folder/copy.xml")
        ... except ValueError as err:
        ...     print(err)
        /no/such/folder/copy.xml is in a folder that does not exist (/no/such/folder): give the path of the file to write
        """
        path = Path(path)
        if path.is_dir() or not path.parent.is_dir():  # named before anything is written beside it
            where = "is a folder" if path.is_dir() else f"is in a folder that does not exist ({path.parent})"
            raise InvalidRequestError(f"{path} {where}: give the path of the file to write")
        self._runner.save(path, copy_assets=copy_assets)
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
        if not isinstance(self._runner, HasSceneSettings):
            raise InvalidRequestError("an MJCF model keeps its settings in the file; use with_values(...)")
        return EngineModel(self._runner.with_settings(**changes), self.engine, self.path, self.units)

    def settings(self) -> dict:
        """Engine settings the file cannot hold, as data (empty for MuJoCo).

        Examples
        --------
        >>> from pitheorem import engines
        >>> engines.load(engines.example_path("pendulum.xml")).settings()
        {}
        """
        return self._runner.settings()

    # -- running it: what a user needs of the engine, without handing out the engine's object ----------

    def timestep(self) -> float:
        """The engine's time step, in the model's time unit.

        Examples
        --------
        >>> from pitheorem import engines
        >>> engines.load(engines.example_path("pendulum.xml")).timestep()
        0.002
        """
        return self._runner.timestep()

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

        n_steps = read_count(n_steps, "n_steps", most=MAX_STEPS)
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
        return self._runner.run(n_steps, controls, policy=policy, initial=initial)

    def coordinates(self) -> tuple[list[str], list[Dimension]]:
        """The names and dimensions of the columns :meth:`run` returns.

        Examples
        --------
        >>> from pitheorem import engines
        >>> names, dims = engines.load(engines.example_path("pendulum.xml")).coordinates()
        >>> names, [str(d) for d in dims]
        (['qpos[hinge]', 'qvel[hinge]'], ['1', 'T^-1'])
        """
        return self._runner.coordinate_dimensions()

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
        low, high = self._runner.control_ranges()
        return list(self._runner.control_dimensions()), low, high


#: the numbers of an engine's settings that describe the robot's world, not the solver: fit repeaters
_WORLD = frozenset({"g", "wind", "density", "viscosity"})


def _engine_setting(p: Parameter) -> bool:
    """Whether a parameter is a setting of the engine (its solver's, or a default it applies), not the robot's."""
    return p.name not in _WORLD and (p.path.startswith("option ") or p.source == "engine")


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
    >>> from pitheorem.engines.enginemodel import check_scaling
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
