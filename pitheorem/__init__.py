"""pitheorem: exact dimensional analysis and similarity scaling for simulations.

Examples
--------
>>> import pitheorem as pt
>>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2"})
>>> rod.rank
3
"""

from . import models, plotting
from .dimensions import DEFAULT_BASE_DIMENSIONS, Dimension
from .equations import DimensionReport, SymmetryReport, check_dimensions, scaling_symmetries
from .errors import (
    DependentRepeatingSetError,
    DimensionSyntaxError,
    DuplicateVariableError,
    EmptySystemError,
    InvalidRequestError,
    LimitError,
    NumberError,
    PiTheoremError,
    RepeatingCountError,
    SystemMismatchError,
    UnitError,
    UnknownVariableError,
)
from .groups import PiGroup, PiSet
from .modelfile import ModelFile, ModelFileError, load_model_file
from .models import Model
from .scaling import Scaling
from .search import SearchResult, search
from .simulate import SimilarityReport, Trajectory, simulate, verify_similarity
from .system import System
from .unitfit import RangeBound, UnitFit, fit_units

__version__ = "0.1.0"

__all__ = [
    "DEFAULT_BASE_DIMENSIONS",
    "DependentRepeatingSetError",
    "Dimension",
    "DimensionReport",
    "DimensionSyntaxError",
    "DuplicateVariableError",
    "EmptySystemError",
    "InvalidRequestError",
    "LimitError",
    "Model",
    "ModelFile",
    "ModelFileError",
    "NumberError",
    "PiGroup",
    "PiSet",
    "PiTheoremError",
    "RangeBound",
    "RepeatingCountError",
    "Scaling",
    "SearchResult",
    "SimilarityReport",
    "SymmetryReport",
    "System",
    "SystemMismatchError",
    "Trajectory",
    "UnitError",
    "UnitFit",
    "UnknownVariableError",
    "__version__",
    "check_dimensions",
    "fit_units",
    "load_model_file",
    "models",
    "plotting",
    "scaling_symmetries",
    "search",
    "simulate",
    "verify_similarity",
]
