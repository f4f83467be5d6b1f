"""pitheorem: exact dimensional analysis and similarity scaling for simulations.

Examples
--------
>>> import pitheorem as pt
>>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2"})
>>> rod.rank
3
"""

# The exact core (System, its groups, dimensions, errors: sympy and no more) loads at once.
# Everything else loads on first use through __getattr__ below, so that `import pitheorem`
# and a command-line call of groups, bases or search pay for neither scipy nor matplotlib.
from importlib import import_module

from .dimensions import DEFAULT_BASE_DIMENSIONS, Dimension
from .errors import (
    DependentRepeatingSetError,
    DimensionSyntaxError,
    DuplicateVariableError,
    EmptySystemError,
    InvalidRequestError,
    LimitError,
    ModelEquationError,
    NumberError,
    PiTheoremError,
    RepeatingCountError,
    SystemMismatchError,
    UnitError,
    UnknownVariableError,
)
from .groups import PiGroup, PiSet
from .system import System

__version__ = "0.1.0"

# public name -> module that defines it (a module itself when the name is a submodule)
_LAZY = {
    "DimensionReport": "equations",
    "SymmetryReport": "equations",
    "check_dimensions": "equations",
    "scaling_symmetries": "equations",
    "ModelFile": "modelfile",
    "ModelFileError": "modelfile",
    "load_model_file": "modelfile",
    "Model": "model",
    "Scaling": "scaling",
    "SearchNote": "scalesearch",
    "SearchResult": "scalesearch",
    "search": "scalesearch",
    "SimilarityReport": "simulation",
    "Trajectory": "simulation",
    "simulate": "simulation",
    "verify_similarity": "simulation",
    "RangeBound": "unitfit",
    "UnitFit": "unitfit",
    "fit_units": "unitfit",
    "formatting": None,
    "models": None,
    "plotting": None,
}


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module 'pitheorem' has no attribute {name!r}")
    module = import_module(f".{_LAZY[name] or name}", __name__)
    value = module if _LAZY[name] is None else getattr(module, name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


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
    "ModelEquationError",
    "ModelFile",
    "ModelFileError",
    "NumberError",
    "PiGroup",
    "PiSet",
    "PiTheoremError",
    "RangeBound",
    "RepeatingCountError",
    "Scaling",
    "SearchNote",
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
    "formatting",
    "load_model_file",
    "models",
    "plotting",
    "scaling_symmetries",
    "search",
    "simulate",
    "verify_similarity",
]
