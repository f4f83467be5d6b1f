"""pitheorem.errors: every error class is a PiTheoremError and a builtin, keeps its fields, names its culprit, pickles.

Each class is provoked once through the public API where it can be; which
input each module refuses, and with what message, is tested in that
module's file.
"""

from __future__ import annotations

import pickle

import pytest
import sympy

import pitheorem as pt
from pitheorem.engines.paper.rod import EngineUnavailableError
from tests.conftest import ROD


def test_errors_are_builtin_subclasses():
    assert issubclass(pt.DimensionSyntaxError, ValueError)
    assert issubclass(pt.UnknownVariableError, KeyError)
    assert issubclass(pt.DependentRepeatingSetError, pt.PiTheoremError)


@pytest.mark.parametrize(
    "error",
    [
        pt.DimensionSyntaxError("M^^", 2, "bad"),
        pt.UnknownVariableError("x", ("a", "b"), "repeating"),
        pt.DuplicateVariableError("a", "the system"),
        pt.EmptySystemError(),
        pt.RepeatingCountError(("a",), 2),
        pt.DependentRepeatingSetError(("a", "b"), "a/b"),
        pt.InvalidRequestError("nope"),
        pt.UnitError("nope"),
    ],
)
def test_errors_pickle_with_their_message(error):
    copy = pickle.loads(pickle.dumps(error))
    assert type(copy) is type(error)
    assert str(copy) == str(error)


def _every_error_with_every_field_set():
    from pitheorem import errors

    return [
        errors.DimensionSyntaxError("M^^", 2, "bad"),
        errors.UnknownVariableError("x", ("a", "b"), "repeating"),
        errors.DuplicateVariableError("a", "the system"),
        errors.EmptySystemError("nothing here", culprit="{}"),
        errors.RepeatingCountError(("a",), 2),
        errors.DependentRepeatingSetError(("a", "b"), "a/b"),
        errors.InvalidRequestError("nope", culprit="n"),
        errors.UnitError("furlongz is no unit", culprit="furlongz"),
        errors.CommandLineError("--s twice", culprit="--s"),
        errors.SystemMismatchError("m", "no variable 'm'"),
        errors.ModelEquationError("Eq(x, 1)", "it holds no derivative", 2),
        errors.NumberError("1/0", "exponent of 'g'", "a finite number"),
        errors.LimitError("L^5000", "exponent", "too big", "use a smaller one"),
        errors.ModelFileError("rod.toml", "unknown role 'clock'", variable="t", line=4),
        errors.EngineModelError("robot.xml", "mesh 'torso'", "not found"),
        errors.UnscalableParameterError("joint_root_damping", "needs s^1 and s^3"),
        errors.EngineUnavailableError("bullet", "pybullet"),
        errors.InputsNotKeptError("bullet", "its inputs are forces"),
    ]


#: the culprit each error of _every_error_with_every_field_set names
CULPRITS = {
    "DimensionSyntaxError": "^",
    "UnknownVariableError": "x",
    "DuplicateVariableError": "a",
    "EmptySystemError": "{}",
    "RepeatingCountError": ("a",),
    "DependentRepeatingSetError": ("a", "b"),
    "InvalidRequestError": "n",
    "UnitError": "furlongz",
    "CommandLineError": "--s",
    "SystemMismatchError": "m",
    "ModelEquationError": "Eq(x, 1)",
    "NumberError": "1/0",
    "LimitError": "L^5000",
    "ModelFileError": "t",
    "EngineModelError": "robot.xml",
    "UnscalableParameterError": "joint_root_damping",
    "EngineUnavailableError": "bullet",
    "InputsNotKeptError": "bullet",
}


def test_every_error_class_is_built_with_every_field():
    from pitheorem import errors

    assert {type(e).__name__ for e in _every_error_with_every_field_set()} == set(errors.__all__) - {"PiTheoremError"}
    assert set(CULPRITS) == set(errors.__all__) - {"PiTheoremError"}


@pytest.mark.parametrize("error", _every_error_with_every_field_set(), ids=lambda e: type(e).__name__)
def test_errors_keep_each_constructor_argument_and_pickle_all_of_them(error):
    import inspect

    fields = [name for name in inspect.signature(type(error)).parameters]
    copy = pickle.loads(pickle.dumps(error))
    # the fields are the constructor's arguments, each kept under its own name, and come back as they were
    assert [getattr(copy, name) for name in fields] == [getattr(error, name) for name in fields]
    assert all(getattr(error, name) is not None for name in fields)
    assert (copy.culprit, copy.message, copy.args) == (error.culprit, error.message, error.args)
    assert error.args == (str(error),) == (error.message,)
    assert error.culprit == CULPRITS[type(error).__name__]
    # rebuilding from the fields gives the same error: what pickling does
    again = type(error)(*(getattr(error, name) for name in fields))
    assert (str(again), again.culprit) == (str(error), error.culprit)


def provoked_errors():
    """One real instance of every error class, provoked through the public API where possible."""
    from pitheorem import engines, errors
    from pitheorem.cli import _parse_scale

    def catch(call):
        try:
            call()
        except pt.PiTheoremError as err:
            return err
        raise AssertionError(f"{call} raised nothing")

    rod = pt.System(ROD)
    return {
        errors.DimensionSyntaxError: (catch(lambda: pt.Dimension.parse("M L^^2")), "^2"),
        errors.UnknownVariableError: (catch(lambda: rod.pi_groups(repeating=("mass", "l", "t"))), "mass"),
        errors.DuplicateVariableError: (catch(lambda: rod.pi_groups(repeating=("m", "m", "t"))), "m"),
        errors.EmptySystemError: (catch(lambda: pt.System({})), None),
        errors.RepeatingCountError: (catch(lambda: rod.pi_groups(repeating=("m", "l"))), ("m", "l")),
        errors.DependentRepeatingSetError: (catch(lambda: rod.pi_groups(repeating=("l", "t", "g"))), ("l", "t", "g")),
        errors.InvalidRequestError: (catch(lambda: pt.System({"x": "L"}, base_dimensions="LT")), "LT"),
        errors.UnitError: (catch(lambda: pt.System.from_units({"x": "furlongs per flibber"})), None),
        errors.SystemMismatchError: (
            catch(
                lambda: pt.verify_similarity(
                    pt.models.projectile(),
                    pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1}),
                    s=2,
                    t_final=0.1,
                )
            ),
            "m",
        ),
        errors.ModelEquationError: (
            catch(
                lambda: pt.Model(
                    pt.System({"x": "L", "t": "T"}), [sympy.Eq(sympy.Function("x")(sympy.Symbol("t")).diff("t", 2), 0)]
                )
            ),
            "Eq(Derivative(x(t), (t, 2)), 0)",
        ),
        errors.NumberError: (
            catch(lambda: pt.search(pt.System({"l": "L", "t": "T"}), scale={"l": float("nan")})),
            "nan",
        ),
        errors.LimitError: (catch(lambda: pt.Dimension.parse("L^5000")), "5000"),
        errors.ModelFileError: (catch(lambda: pt.load_model_file("example:nope")), "example:nope"),
        errors.CommandLineError: (catch(lambda: _parse_scale(["g=1", "g=2"])), "g"),
        errors.EngineUnavailableError: (errors.EngineUnavailableError("bullet", "pybullet"), "bullet"),
        errors.EngineModelError: (catch(lambda: engines.load("no_such_robot.xml")), "no_such_robot.xml"),
        errors.UnscalableParameterError: (
            errors.UnscalableParameterError("joint_root_damping", "needs s^1 and s^3"),
            "joint_root_damping",
        ),
        # provoked through the public API in test_engines_pybullet.py (a PyBullet model keeps no inputs)
        errors.InputsNotKeptError: (errors.InputsNotKeptError("bullet", "its inputs are forces"), "bullet"),
    }


PROVOKED = provoked_errors()


def test_every_error_class_is_provoked_here():
    from pitheorem import errors

    names = {n for n in errors.__all__ if n != "PiTheoremError"}
    assert {c.__name__ for c in PROVOKED} == names


@pytest.mark.parametrize("cls", sorted(PROVOKED, key=lambda c: c.__name__), ids=lambda c: c.__name__)
def test_error_contract(cls):
    from pitheorem import errors

    err, culprit = PROVOKED[cls]
    assert type(err) is cls
    assert cls.__module__ == errors.__name__  # every error class lives in errors.py
    assert isinstance(err, pt.PiTheoremError)
    assert isinstance(err, ValueError | KeyError | TypeError | ImportError)
    if culprit is not None:
        shown = err.culprit if isinstance(err.culprit, str | tuple) else repr(err.culprit)
        assert shown == culprit or str(culprit) in str(shown)
    copy = pickle.loads(pickle.dumps(err))
    assert type(copy) is cls
    assert str(copy) == str(err)
    assert copy.culprit == err.culprit or repr(copy.culprit) == repr(err.culprit)
    assert str(err).strip(), "an error must say what is wrong"


def test_message_only_errors_pickle_their_culprit():
    err = pt.InvalidRequestError("bad thing", culprit="thing")
    copy = pickle.loads(pickle.dumps(err))
    assert (copy.culprit, str(copy)) == ("thing", "bad thing")


def test_engine_unavailable_error_message_and_pickle():
    err = EngineUnavailableError("mujoco", "mujoco")
    assert isinstance(err, pt.PiTheoremError)
    assert isinstance(err, ImportError)
    assert "pitheorem[engines]" in str(err)
    assert str(pickle.loads(pickle.dumps(err))) == str(err)
