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
    "formatting": None,
    "models": None,
    "plotting": None,
}


def fit_units(
    system, values=None, *, ranges=None, dimension_ranges=None, fixed=(), fixed_units=(), nice=None, engine=None
):
    """Find the change of base units that brings values into ranges.

    The ranges are given, or those an engine's thresholds leave (`engine`).

    A change of base units moves every value at once: a value of
    dimension ``prod_b b^(d_b)`` reads ``x * prod_b f_b^(d_b)`` in the new
    units, ``f_b`` the factor of base ``b`` (``f_L = 100``: lengths read
    100 times larger, metres to centimetres).  Without `engine` the fit
    (``pitheorem.unitfit.fit_units``) first minimises the worst distance,
    in decades, of a value outside its range, then pulls each value
    towards the middle of its range, then keeps the unit change smallest;
    when nothing fits, ``conflict`` names a minimal set of bounds that
    fight.  With ``engine="mujoco"`` (or ``"pybullet"``; ``"mjx"``
    computes in float32), or given an engine model itself, the ranges are
    those the engine's thresholds leave each number, a factor 10 clear of
    them, and the fit is the smallest unit change that meets them, keeping
    the time unit where that suffices (``pitheorem.engines.fitting``).

    Parameters
    ----------
    system : System or EngineModel
        The variables; an :class:`~pitheorem.engines.EngineModel` brings
        its own values and engine.
    values : mapping of str to number, optional
        The values in the current units (not needed with a model).
    ranges : mapping of str to (low, high) or None, optional
        Range per variable.
    dimension_ranges : mapping of str to (low, high), optional
        Range for every variable of a dimension (not with an engine).
    fixed : iterable of str, optional
        Variables whose value must not change.
    fixed_units : iterable of str, optional
        Base dimensions whose unit must not change.
    nice : int, optional
        Factors restricted to integer powers of `nice` (with an engine:
        10 unless given).
    engine : str, optional
        Fit the numbers clear of this engine's thresholds.  The kind of
        each variable of a System is read from its name, as
        :meth:`~pitheorem.engines.EngineModel.system` names them.

    Returns
    -------
    UnitFit

    Raises
    ------
    UnknownVariableError
        For a name in `values`, `ranges` or `fixed` the system lacks.
    InvalidRequestError
        For a bad range (``low >= high``, a bound not positive, no value),
        an unknown base in `fixed_units`, a fixed variable outside its own
        range, a bad `nice`, an unknown engine, or `dimension_ranges` with
        an engine.

    Examples
    --------
    >>> import pitheorem as pt
    >>> ball = pt.System({"r": "L", "m": "M", "t": "T"})
    >>> pt.fit_units(ball, {"r": 0.02, "m": 0.17, "t": 1}, dimension_ranges={"L": (0.05, 10)}, nice=10).factors["L"]
    Fraction(100, 1)
    >>> from pitheorem import engines
    >>> worm = engines.load(engines.example_path("pendulum.xml")).converted(L=100, M=1e6)
    >>> pt.fit_units(worm, engine="mujoco").factors
    {'M': Fraction(1, 1), 'L': Fraction(100, 1), 'T': Fraction(1, 1)}
    """
    if engine is None and not hasattr(system, "parameters"):  # a System (unitfit refuses anything else)
        from .unitfit import fit_units as fit

        return fit(
            system,
            values,
            ranges=ranges,
            dimension_ranges=dimension_ranges,
            fixed=fixed,
            fixed_units=fixed_units,
            nice=nice,
        )
    if dimension_ranges:
        raise InvalidRequestError("dimension_ranges is not for an engine fit; give ranges per parameter")
    from .engines.fitting import engine_fit

    return engine_fit(
        system,
        values,
        engine=engine,
        ranges=ranges,
        fixed=fixed,
        fixed_units=fixed_units,
        nice=10 if nice is None else nice,
    )


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
