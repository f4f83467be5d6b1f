"""Every public value type refuses attribute assignment and deletion (pitheorem/immutable.py).

One test walks every class that ``pitheorem`` and ``pitheorem.engines``
export: each is either built here as a real instance and probed, or
excluded below with a reason.  A class added to either ``__all__`` later
fails until it is one or the other.

The module's file (pitheorem.immutable, the decorator), and across modules: the
walk over every exported class keeps the rule true wherever a value type lives.
"""

from __future__ import annotations

import dataclasses
import inspect
import pickle
from fractions import Fraction

import numpy as np
import pytest

import pitheorem as pt
from pitheorem import engines
from pitheorem.basis_sequence import BasisSequence
from pitheorem.immutable import immutable

ROD = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "t": "T"})


def _search():
    return pt.search(ROD, scale={"g": 1})


def _symmetries():
    import sympy

    t, g = sympy.symbols("t g")
    x = sympy.Function("x")(t)
    return pt.scaling_symmetries([sympy.Eq(x.diff(t, 2), -g)], pt.System({"g": "L T^-2", "x": "L", "t": "T"}))


def _similarity_report():
    smd = pt.models.spring_mass_damper()
    return pt.verify_similarity(smd, pt.Scaling.from_unit_change(smd.system, {"L": 1}), s=2, t_final=0.05)


def _engine_report():
    rod = pt.models.hinged_rod()
    return engines.verify_engine_similarity(
        "mujoco", pt.search(rod.system, scale={"g": 1}).scalings[0], s=2, t_final=0.02, compare_ode=False
    )


def _engine_model():
    return engines.load(engines.example_path("pendulum.xml"))


#: class -> (a real instance, a public attribute to try besides the first field or slot)
VALUE_TYPES = {
    pt.System: (lambda: ROD, "variables"),
    pt.Dimension: (lambda: pt.Dimension.parse("M L^2 T^-2"), "exponents"),
    pt.PiGroup: (lambda: ROD.pi_groups()[0], "variable"),
    pt.PiSet: (lambda: ROD.pi_groups(), "repeating"),
    BasisSequence: (lambda: ROD.bases(), "indices"),
    pt.Scaling: (lambda: _search().scalings[0], "exponents"),
    pt.SearchResult: (_search, "feasible"),
    pt.SearchNote: (lambda: _search().notes[0], "kind"),
    pt.DimensionReport: (lambda: pt.check_dimensions(__import__("sympy").Symbol("m"), ROD), "consistent"),
    pt.SymmetryReport: (_symmetries, "basis"),
    pt.UnitFit: (lambda: pt.fit_units(ROD, {"l": 0.02}, ranges={"l": (0.05, 10)}), "scaled"),
    pt.RangeBound: (lambda: pt.RangeBound("l", "low", Fraction(1, 20)), "bound"),
    pt.ModelFile: (lambda: pt.load_model_file("example:hinged_rod"), "values"),
    pt.Model: (pt.models.hinged_rod, "parameters"),
    pt.Trajectory: (lambda: pt.Trajectory(np.array([0.0, 1.0]), np.array([[1.0], [2.0]]), ("x",)), "y"),
    pt.SimilarityReport: (_similarity_report, "passed"),
    engines.EngineSimilarityReport: (_engine_report, "similar"),
    engines.EngineModel: (_engine_model, "parameters"),
    engines.Cause: (lambda: engines.Cause("solver", "option tolerance", "no pure dimension"), "detail"),
    engines.Audit: (lambda: engines.Audit((), 3, 4.0), "compared"),
    engines.SweepRow: (lambda: engines.SweepRow(4, "exact", 0.0, 1e-12, None, True, None, (), ()), "verdict"),
    engines.Sweep: (
        lambda: engines.Sweep(
            "", "mujoco", None, 1.0, (engines.SweepRow(4, "exact", 0.0, 0.0, None, True, None, (), ()),)
        ),
        "rows",
    ),
    engines.Parameter: (lambda: _engine_model().parameters[0], "value"),
    engines.HiddenConstant: (lambda: engines.CATALOGUE[0], "dimension"),
    engines.RuleOfThumb: (lambda: engines.BULLET_SCALE_THE_WORLD, "quantities"),
    engines.RuleQuantity: (lambda: engines.BULLET_SCALE_THE_WORLD.quantities[0], "exponent"),
    engines.RuleVerdict: (lambda: engines.check_rule(engines.BULLET_SCALE_THE_WORLD), "unit_change"),
}

_ERROR = "an exception: Python itself sets __traceback__, __context__ and __cause__ on it as it propagates"

#: exported classes that are no value types, with the reason
NOT_VALUE_TYPES = {
    "PiTheoremError": _ERROR,
    "DependentRepeatingSetError": _ERROR,
    "DimensionSyntaxError": _ERROR,
    "DuplicateVariableError": _ERROR,
    "EmptySystemError": _ERROR,
    "InvalidRequestError": _ERROR,
    "LimitError": _ERROR,
    "ModelEquationError": _ERROR,
    "ModelFileError": _ERROR,
    "NumberError": _ERROR,
    "RepeatingCountError": _ERROR,
    "SystemMismatchError": _ERROR,
    "UnitError": _ERROR,
    "UnknownVariableError": _ERROR,
    "EngineModelError": _ERROR,
    "InputsNotKeptError": _ERROR,
    "UnscalableParameterError": _ERROR,
    "UnscalableModelWarning": "a warning category: warnings.warn instantiates it, nobody holds one as a value",
}


def _exported_classes() -> dict[str, type]:
    found = {}
    for module in (pt, engines):
        for name in module.__all__:
            value = getattr(module, name)
            if inspect.isclass(value):  # modules (pt.models, pt.plotting) and constants are no classes
                found[f"{module.__name__}.{name}"] = value
    return found


def _storage(obj) -> str:
    """The first attribute the object's data lives in: a dataclass field or a slot."""
    if dataclasses.is_dataclass(obj):
        return dataclasses.fields(obj)[0].name
    for klass in type(obj).__mro__:
        slots = getattr(klass, "__slots__", ())
        if slots:
            return (slots,)[0] if isinstance(slots, str) else slots[0]
    raise AssertionError(f"{type(obj).__name__} keeps its data neither in fields nor in slots")


def test_every_exported_class_is_a_probed_value_type_or_excluded_with_a_reason():
    exported = _exported_classes()
    unaccounted = [
        name for name, cls in exported.items() if cls not in VALUE_TYPES and cls.__name__ not in NOT_VALUE_TYPES
    ]
    assert not unaccounted, f"add these to VALUE_TYPES (and protect them) or to NOT_VALUE_TYPES: {unaccounted}"
    # the exclusions are what they claim, and none is stale
    for name, cls in exported.items():
        if cls.__name__ in NOT_VALUE_TYPES:
            assert issubclass(cls, BaseException), name
    assert set(NOT_VALUE_TYPES) <= {cls.__name__ for cls in exported.values()}


@pytest.mark.parametrize("cls", list(VALUE_TYPES), ids=lambda cls: cls.__name__)
def test_value_types_refuse_assignment_and_deletion(cls):
    factory, public = VALUE_TYPES[cls]
    obj = factory()
    assert type(obj) is cls
    for name in (_storage(obj), public):
        before = getattr(obj, name)
        with pytest.raises(AttributeError, match=repr(name)):
            setattr(obj, name, before)
        with pytest.raises(AttributeError, match=repr(name)):
            delattr(obj, name)
        after = getattr(obj, name)
        assert after is before or after == before  # a property may build a new (equal) value
    with pytest.raises(AttributeError, match="'brand_new_attribute'"):
        obj.brand_new_attribute = 1
    assert not hasattr(obj, "brand_new_attribute")


def test_the_decorator_names_the_attribute_and_the_type():
    @immutable
    @dataclasses.dataclass(frozen=True, slots=True)
    class Point:
        x: int

    p = Point(1)
    # without the decorator, Python 3.11 answers the new name with a TypeError about super()
    with pytest.raises(dataclasses.FrozenInstanceError, match=r"cannot assign or delete 'y': a Point is immutable"):
        p.y = 2
    with pytest.raises(dataclasses.FrozenInstanceError, match="'x'"):
        del p.x
    assert p.x == 1


@pytest.mark.parametrize(
    "make",
    [
        lambda: ROD,
        lambda: ROD.pi_groups(),
        lambda: ROD.bases(),
        lambda: pt.Dimension.parse("L T^-2"),
        lambda: _search().scalings[0],
    ],
    ids=["System", "PiSet", "BasisSequence", "Dimension", "Scaling"],
)
def test_protected_types_still_pickle(make):
    # unpickling must not assign attributes the ordinary way, which the protection refuses
    obj = make()
    again = pickle.loads(pickle.dumps(obj))
    assert again == obj
    assert type(again) is type(obj)
