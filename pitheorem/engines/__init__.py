"""Physics engines: MJCF and URDF models, the paper's rod and robot, hidden constants.

An optional part of pitheorem: ``import pitheorem`` never imports it, and
nothing here imports an engine until a model is read or a simulation is
asked for.  Install the engines with ``pip install "pitheorem[engines]"``
(``pybullet`` and ``mujoco``).

* ``pitheorem.engines.enginemodel``, ``mjcf`` and ``urdf``: ``load`` reads an
  MJCF (MuJoCo) or URDF (PyBullet) file as an ``EngineModel``, every
  dimensional number a ``Parameter`` with its dimension; its system,
  a scaled copy and the file the engine loads;
* ``pitheorem.engines.verify``: runs a model and its scaled copy in the
  engine and compares them against the model's own one-ulp sensitivity;
* ``pitheorem.engines.verdicts.sweep``: :func:`sweep`, the verification at many
  scale factors, on every core or on a Dask cluster;
* ``pitheorem.engines.cli``: the command line on MJCF and URDF files;
* ``pitheorem.engines.paper.superball``: SUPERball, the white paper's robot, as a
  MuJoCo tensegrity;
* ``pitheorem.engines.constants``: the catalogue of each engine's
  built-in dimensional constants and searches that hold them fixed;
* ``pitheorem.engines.paper.rod``: the hinged rod of the white paper built in
  each engine, run, and compared after a similarity scaling;
* ``pitheorem.engines.rules``: the engines' published rules for scaling
  the world, checked as changes of units;
* ``pitheorem.engines.thresholds``: the numbers at which an engine stops
  taking a model's numbers as they are (floors, ceilings, refusals), and
  :func:`check`, the thresholds a model sits beyond or near;
* ``pitheorem.engines.packages``: the Python package each engine needs,
  imported when a simulation asks for it.

Examples
--------
>>> import pitheorem as pt
>>> from pitheorem.engines import broken_constants
>>> rod = pt.models.hinged_rod()
>>> fig5 = pt.search(rod.system, scale={"g": 1, "l": -1}, fixed=("m", "k_theta")).scalings[0]
>>> [c.name for c in broken_constants(fig5, "pybullet", names=["bullet_time_step", "bullet_erp"])]
['bullet_time_step']
"""

from .constants import (
    CATALOGUE,
    ENGINES,
    HiddenConstant,
    broken_constants,
    engine_search,
    hidden_constants,
    with_hidden_constants,
)
from .enginemodel import EngineModel, EngineModelError, InputsNotKeptError, UnscalableParameterError, example_path
from .loading import load
from .paper.rod import EngineSimilarityReport, simulate_rod, verify_engine_similarity
from .parameters import Parameter, UnscalableModelWarning
from .registry import backends, formats
from .rules import (
    BULLET_SCALE_THE_WORLD,
    MUJOCO_FRAME_SIMILAR,
    RULES,
    RuleOfThumb,
    RuleQuantity,
    RuleVerdict,
    check_rule,
)
from .thresholds import check
from .verdicts.audit import Audit, audit
from .verdicts.causes import CAUSE_KINDS, Cause
from .verdicts.sweep import Sweep, SweepRow, sweep
from .verdicts.verify import smooth_controls, verify

__all__ = [
    "BULLET_SCALE_THE_WORLD",
    "CATALOGUE",
    "CAUSE_KINDS",
    "ENGINES",
    "MUJOCO_FRAME_SIMILAR",
    "RULES",
    "Audit",
    "Cause",
    "EngineModel",
    "EngineModelError",
    "EngineSimilarityReport",
    "HiddenConstant",
    "InputsNotKeptError",
    "Parameter",
    "RuleOfThumb",
    "RuleQuantity",
    "RuleVerdict",
    "Sweep",
    "SweepRow",
    "UnscalableModelWarning",
    "UnscalableParameterError",
    "audit",
    "backends",
    "broken_constants",
    "check",
    "check_rule",
    "engine_search",
    "example_path",
    "formats",
    "hidden_constants",
    "load",
    "simulate_rod",
    "smooth_controls",
    "sweep",
    "verify",
    "verify_engine_similarity",
    "with_hidden_constants",
]
