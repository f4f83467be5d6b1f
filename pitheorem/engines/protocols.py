"""What a runner provides: the protocols between the analysis and the engines.

A format (``pitheorem.engines.fileformats``) reads a file into a *document*:
the file's numbers with their dimensions and addresses, written back by
address.  A runner (``pitheorem.engines.runners``) compiles a document in
its engine and runs it; each runner module has one line in
:mod:`pitheorem.engines.registry`.  An :class:`~pitheorem.engines.EngineModel`
holds a runner (:attr:`~pitheorem.engines.EngineModel.runner`), and
everything the analysis (verify, audit, diagnose, check, fit) asks of it
is named here:

* :class:`Runs`: what :func:`~pitheorem.engines.verify` needs
  to run a model and its scaled copy (a time step, the recorded
  coordinates and inputs with their dimensions, open-loop and closed-loop
  runs, a batch of runs, the yardstick's twins);
* :class:`Runner`: all of that, and the parameter table, scaled
  copies, saved files, the numbers the engine stores (for
  :func:`~pitheorem.engines.audit`), the engine settings a file cannot
  hold, the precision it computes in, the units its format allows;
* optional capabilities, each its own small protocol, checked with
  ``isinstance`` where they are used: :class:`RefusesScalings` (numbers a
  scaling cannot reach, named before a copy is made),
  :class:`HasSceneSettings` (settings outside the file, changed by
  ``with_settings``), :class:`KeepsInputs` (copies whose control inputs
  keep their values, the factors on the gains), :class:`CounterRuns` (copies run with another
  solver tolerance, for the diagnosis), :class:`CountsIterations` (the solver's
  iterations of a run counted, and copies run with a fixed count), :class:`SolverDiagnosis`
  (solver, equality constraints and contacts, named),
  :class:`MultipliesInPlace` (a copy with other gravity or masses, not compiled again),
  :class:`NamesElements` (a stored number's element),
  :class:`StoresCopies` (the stored numbers that are the file's, with
  their parameters) and :class:`IgnoredSettings` (settings the engine
  does not apply).

``controls`` is ``None`` (zero input), an array of inputs with one row
per step, or a callable of the step's start time; ``policy`` is a
closed-loop law the engine calls with its live state.

Examples
--------
>>> from pitheorem import engines
>>> from pitheorem.engines.protocols import CounterRuns, Runner, HasSceneSettings
>>> runner = engines.load(engines.example_path("pendulum.xml")).runner
>>> isinstance(runner, Runner), isinstance(runner, CounterRuns)
(True, True)
>>> isinstance(runner, HasSceneSettings)
False
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

import numpy as np

__all__ = [
    "OPTIONAL",
    "REQUIRED",
    "ClampsVelocities",
    "Controls",
    "CounterRuns",
    "CountsIterations",
    "EngineNotes",
    "HasSceneSettings",
    "IgnoredSettings",
    "KeepsInputs",
    "MultipliesInPlace",
    "NamesElements",
    "ReadsSomeNumbers",
    "RefusesScalings",
    "Runner",
    "Runs",
    "SolverDiagnosis",
    "StoresCopies",
    "SwitchesConstraints",
    "WritesStored",
]

#: open-loop inputs: None (zero input), rows of inputs (one per step) or ``t -> inputs``
Controls = np.ndarray | Callable[[float], Sequence[float]] | None

#: a run of a batch: (backend, controls, nudge, first row or None)
Job = tuple[Any, Controls, bool, Any]


@runtime_checkable
class Runs(Protocol):
    """What :func:`~pitheorem.engines.verify` needs of an engine to run a model.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.protocols import Runs
    >>> isinstance(engines.load(engines.example_path("pendulum.xml")).runner, Runs)
    True
    """

    def timestep(self) -> float:
        """The fixed step of the engine, in the model's units."""

    def coordinate_dimensions(self) -> tuple[list[str], list]:
        """Names and dimensions of the recorded coordinates, in column order."""

    def control_dimensions(self) -> list:
        """The dimension of each control input."""

    def control_ranges(self) -> tuple[np.ndarray, np.ndarray]:
        """Each input's lower and upper limit; -inf and inf where it has none."""

    def run(
        self,
        n_steps: int,
        controls: Controls = None,
        nudge: bool = False,
        policy: Callable | None = None,
        initial: np.ndarray | None = None,
    ) -> np.ndarray:
        """Rows of coordinates after 0..n_steps steps from `initial` (a first row; None: the model's own).

        ``nudge`` moves the start by one ulp.
        """

    def run_many(self, n_steps: int, jobs: Sequence[Job]) -> list[np.ndarray]:
        """Several open-loop runs of models of the same sizes at once: the rows of each."""

    def twin(self, seed: int) -> Runs:
        """A copy whose every stored number is one unit in its own last place off (signs from `seed`)."""


@runtime_checkable
class Runner(Runs, Protocol):
    """Everything a runner provides that the rest of the package calls.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.protocols import Runner
    >>> isinstance(engines.load(engines.example_path("pendulum.xml")).runner, Runner)
    True
    """

    def parameters(self) -> list:
        """Every dimensional number of the file and the engine settings, as Parameters."""

    def settings(self) -> dict:
        """The engine settings the file cannot hold, as data (empty where the file holds them all)."""

    def scaled(self, factors: dict[str, float], scaling, s) -> Runner:
        """A copy with each parameter multiplied by its factor (`scaling` and `s` None for a plain product)."""

    def save(self, path: Path, *, copy_assets: bool = False) -> None:
        """Write the model as a file the engine loads as it is (its asset files copied beside it on request)."""

    def stored_numbers(self) -> dict[str, np.ndarray]:
        """Every floating-point number the engine holds for the model, by field, in its own precision."""

    #: ``"float64"`` or ``"float32"``: the precision the engine computes this model in
    precision: str

    #: None, or the EngineModelError of a file the engine refuses to run (read as a table only)
    refusal: Any

    def check_units(self, units: dict[str, str]) -> None:
        """Refuse, by name, units the format does not allow (a URDF file is in SI)."""

    def in_units(self, units: dict[str, str]) -> Runner:
        """This model declared in other units (its numbers unchanged; a saved file records them)."""

    def recorded_units(self) -> dict[str, str] | None:
        """The units the file records (one pitheorem wrote), or None."""

    def written_beside(self, path) -> tuple[str, ...]:
        """The files :meth:`save` writes beside `path` (settings a format cannot hold)."""


@runtime_checkable
class RefusesScalings(Protocol):
    """Optional: numbers a scaling cannot reach, named before a copy is made (PyBullet's).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.protocols import RefusesScalings
    >>> isinstance(engines.load(engines.example_path("pendulum.xml")).runner, RefusesScalings)
    False
    """

    unscalable_remedy: str

    #: the scene options (:func:`pitheorem.engines.loading.scene_options`) that remove every refusal
    #: at once, chosen by the command line when the user set none of them
    remedy_scene: Mapping[str, object]

    def command_line_remedy(self, name: str) -> tuple[str, str]:
        """The command line's option that removes the refusal of parameter `name`, and the flag that sets it."""

    def unscalable(self, factors: dict[str, float]) -> list:
        """An UnscalableParameterError for each number the factors would need changed and no call can."""


@runtime_checkable
class KeepsInputs(Protocol):
    """Optional: scaled copies whose control inputs keep their values (MuJoCo's actuators have gains).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.protocols import KeepsInputs
    >>> isinstance(engines.load(engines.example_path("pendulum.xml")).runner, KeepsInputs)
    True
    """

    def input_parameters(self) -> list[dict[str, int]]:
        """Per control input: each parameter that carries it, with the power of the input in its dimension."""

    def scaled_keeping_inputs(self, factors: dict[str, float], scaling, s) -> KeepsInputs:
        """A scaled copy (as ``scaled``) where `factors` keep every input: keyframes and compiled ranges kept too."""

    def coordinate_inputs(self) -> list[int | None]:
        """Per recorded coordinate: the input whose unit it is in (an actuator's activation), else None."""


@runtime_checkable
class ReadsSomeNumbers(Protocol):
    """Optional: numbers of the file the engine never reads (MuJoCo's contact numbers of geoms that never collide).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.protocols import ReadsSomeNumbers
    >>> isinstance(engines.load(engines.example_path("pendulum.xml")).runner, ReadsSomeNumbers)
    True
    """

    def unread(self) -> frozenset[str]:
        """The names of the parameters the engine holds but never reads in a run."""


@runtime_checkable
class StoresUnreadNumbers(Protocol):
    """Optional: stored numbers no step of a run reads, by field (MuJoCo's geoms that never collide, and their meshes).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.protocols import StoresUnreadNumbers
    >>> isinstance(engines.load(engines.example_path("pendulum.xml")).runner, StoresUnreadNumbers)
    True
    """

    def unread_stored(self) -> dict:
        """Per field of :meth:`stored_numbers`, a mask of its rows that no step of a run reads."""


@runtime_checkable
class HasSceneSettings(Protocol):
    """Optional: settings outside the file, changed by ``EngineModel.with_settings`` (PyBullet's).

    Examples
    --------
    >>> from pitheorem.engines.protocols import HasSceneSettings
    >>> HasSceneSettings.__name__
    'HasSceneSettings'
    """

    def with_settings(self, **changes) -> HasSceneSettings:
        """A copy with other scene settings."""


@runtime_checkable
class CounterRuns(Protocol):
    """Optional: copies run with other solver options, and the solver's scale-free-less stopping rules.

    Examples
    --------
    >>> from pitheorem.engines.protocols import CounterRuns
    >>> CounterRuns.__name__
    'CounterRuns'
    """

    def variant(self, *, tolerance: float | None = None) -> CounterRuns:
        """A copy run with another tolerance (MuJoCo's also take contacts, solver, inactive_equalities, unlimited)."""

    def solver_settings(self) -> dict[str, float]:
        """The solver's stopping rules that have no pure dimension, nonzero ones only."""


@runtime_checkable
class WritesStored(Protocol):
    """Optional: a copy with some stored numbers set (MuJoCo's): a static cause's counter-run, the copy repaired.

    Examples
    --------
    >>> from pitheorem.engines.protocols import WritesStored
    >>> WritesStored.__name__
    'WritesStored'
    """

    def with_stored(self, values) -> WritesStored:
        """A copy whose stored numbers (fields of ``stored_numbers``) are `values`, nothing derived again."""


@runtime_checkable
class CountsIterations(Protocol):
    """Optional: the solver's iterations of a run counted, and copies run with a fixed count (MuJoCo's).

    A fixed count of iterations is a pure number: with no tolerance to stop
    them, the original and its scaled copy do the same iterations every
    step.  A runner with it also takes ``iterations`` in ``variant``
    (:class:`CounterRuns`).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.protocols import CountsIterations
    >>> runner = engines.load(engines.example_path("causes/contact.xml")).runner  # a box on the floor
    >>> isinstance(runner, CountsIterations)
    True
    >>> runner.solver_iterations(200), runner.variant(iterations=3).solver_iterations(200)
    (100, 3)
    """

    def solver_iterations(self, n_steps: int, controls: Controls = None) -> int:
        """The most iterations the constraint solver takes in a step of an open-loop run from rest (0: none)."""


@runtime_checkable
class MultipliesInPlace(Protocol):
    """Optional: copies with gravity, or every body's mass and inertia, times a factor, not compiled again.

    The negative controls of :func:`~pitheorem.engines.verify` are such
    copies; a runner without it gets them through ``EngineModel.multiplied``
    (one compilation each).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.protocols import MultipliesInPlace
    >>> isinstance(engines.load(engines.example_path("pendulum.xml")).runner, MultipliesInPlace)
    True
    """

    def with_gravity_times(self, factor: float) -> Runs:
        """This runner with its gravity times `factor` (gravity enters no other compiled number)."""

    def with_masses_times(self, factor: float) -> Runs:
        """This runner with every body's mass and inertia times `factor`, the constants derived from them
        computed again."""


@runtime_checkable
class ClampsVelocities(Protocol):
    """Optional: a clamp on every coordinate's velocity, and counter-runs with it raised (PyBullet's).

    Its ``variant`` also takes ``velocity_clamp`` (a float: the clamp in
    both runs; ``math.inf`` lifts it).

    Examples
    --------
    >>> from pitheorem.engines.protocols import ClampsVelocities
    >>> ClampsVelocities.__name__
    'ClampsVelocities'
    """

    def velocity_clamp(self) -> tuple[float, str]:
        """The clamp in effect, and what it is in the engine's words (its name, what it acts on)."""

    def reaches_velocity_clamp(self, rows) -> bool:
        """Whether a run (its rows, as ``run`` records them) may have met the clamp: a velocity at or beyond it."""


@runtime_checkable
class SwitchesConstraints(Protocol):
    """Optional: counter-runs with contacts off, equality constraints inactive, limits off (MuJoCo's, MJX's, Warp's).

    Its ``variant`` also takes ``contacts`` (False: every contact off),
    ``inactive_equalities`` (indices into :meth:`equality_names`) and
    ``unlimited`` (indices into :meth:`limit_names`).

    Examples
    --------
    >>> from pitheorem.engines.protocols import SwitchesConstraints
    >>> SwitchesConstraints.__name__
    'SwitchesConstraints'
    """

    def equality_names(self) -> list[str]:
        """Each equality constraint, named as the reports name it."""

    def equality_kinds(self) -> list[str]:
        """Each equality constraint's kind, in the engine's words (``"weld"``, ``"connect"``, ...)."""

    def limit_names(self) -> list[str]:
        """Each joint and tendon whose range is a constraint (``variant(unlimited=...)`` indexes them), named as
        the reports name it."""


@runtime_checkable
class SolverDiagnosis(Protocol):
    """Optional: the solver and the contacts of each step, named (MuJoCo's).

    Examples
    --------
    >>> from pitheorem.engines.protocols import SolverDiagnosis
    >>> SolverDiagnosis.__name__
    'SolverDiagnosis'
    """

    #: the solver whose iterations are scale-free, by name
    scale_free_solver: str

    def solver_remedy(self, *, tolerance_zero: bool) -> str:
        """How a user runs a model with the scale-free solver (with its tolerance at 0), in the format's words."""

    def solver_name(self) -> str:
        """The constraint solver's name (``"Newton"``, ...)."""

    def uses_native_ccd(self) -> bool:
        """Whether convex pairs collide through the engine's own convex collision (``variant(native_ccd=False)``)."""

    def first_contact_difference(self, other, n_steps: int, controls: Controls = None, other_controls: Controls = None):
        """The first step after which other pairs touch in `other`'s run: (step or None, pairs only there, only
        here, pairs touched in this run so far)."""

    def contact_candidates(self, pairs) -> list[tuple[int, str, str, tuple[str, ...]]]:
        """Per pair that touches, the geom a counter-run takes out of collision: (id, pair, collision function,
        cause paths)."""


@runtime_checkable
class NamesElements(Protocol):
    """Optional: the element a row of a stored field belongs to.

    Examples
    --------
    >>> from pitheorem.engines.protocols import NamesElements
    >>> NamesElements.__name__
    'NamesElements'
    """

    def element_name(self, field: str, row: int) -> str:
        """A row of a field of ``stored_numbers()``, named by its element."""


@runtime_checkable
class StoresCopies(Protocol):
    """Optional: which stored numbers are the file's numbers, each with the parameter it belongs to.

    Examples
    --------
    >>> from pitheorem.engines.protocols import StoresCopies
    >>> StoresCopies.__name__
    'StoresCopies'
    """

    def stored_copies(self) -> list:
        """Records with ``parameter``, ``element``, ``attribute``, ``field`` and ``index`` (flat, in the field)."""


@runtime_checkable
class IgnoredSettings(Protocol):
    """Optional: settings the engine keeps but does not apply, as causes (PyBullet's).

    Examples
    --------
    >>> from pitheorem.engines.protocols import IgnoredSettings
    >>> IgnoredSettings.__name__
    'IgnoredSettings'
    """

    def ignored_settings(self) -> tuple:
        """A Cause for each setting the engine ignores."""

    def removed_by(self, cause) -> dict | None:
        """The options of a counter-run (:class:`CounterRuns`) that remove an ignored setting's effect from both
        runs (contacts off, for a collision margin), or None where none does."""


@runtime_checkable
class EngineNotes(Protocol):
    """Optional: what the engine says of itself that can touch a verdict on this model (a known bug).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.protocols import EngineNotes
    >>> isinstance(engines.load(engines.example_path("pendulum.xml")).runner, EngineNotes)
    True
    """

    def engine_notes(self) -> tuple[str, ...]:
        """One sentence per note, empty where none applies to this model."""


def _members(protocol) -> tuple[str, ...]:
    own = [name for name in vars(protocol) if not name.startswith("_")]
    own.extend(vars(protocol).get("__annotations__", {}))
    return tuple(sorted(set(own)))


#: the methods every backend has
REQUIRED = tuple(sorted({*_members(Runs), *_members(Runner)}))

#: the optional capabilities: protocol -> its members
OPTIONAL = {
    p.__name__: _members(p)
    for p in (
        RefusesScalings,
        HasSceneSettings,
        KeepsInputs,
        CounterRuns,
        CountsIterations,
        ClampsVelocities,
        WritesStored,
        MultipliesInPlace,
        SwitchesConstraints,
        SolverDiagnosis,
        NamesElements,
        StoresCopies,
        IgnoredSettings,
        EngineNotes,
    )
}
