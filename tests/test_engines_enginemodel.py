"""pitheorem.engines.enginemodel: EngineModel, the one type every engine file loads into.

What a model does whatever its engine: it cannot be changed, it reads s and
every value through the one number reader, takes a change of units over M,
L and T only, and makes copies by value or by factor.  The example is the
shipped MJCF pendulum; each backend's own reading is in test_engines_mjcf
and test_engines_urdf.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt
from pitheorem import engines
from pitheorem.modelfile import ModelFileError

mujoco = pytest.importorskip("mujoco", reason="the models below are MuJoCo's (pip install 'pitheorem[engines]')")


def test_with_values_is_multiplied_by_the_ratio_and_may_reach_zero_or_change_sign():
    model = engines.load(engines.example_path("pendulum.xml"))
    # one copy by either route (19.62 / 9.81 is 2 exactly in floats)
    doubled = model.with_values(g=19.62)
    assert doubled.parameters == model.multiplied(g=2).parameters
    assert doubled.parameter("g").value == (19.62,)
    assert doubled.parameter("timestep").value == model.parameter("timestep").value
    # a value of 0, or of the other sign: with_values reaches it, multiplied refuses the factor
    assert model.with_values(tolerance=0).parameter("tolerance").value == (0.0,)
    assert model.with_values(actuator_torque_gainprm_gain=-2).parameter("actuator_torque_gainprm_gain").value == (-2.0,)
    for bad in (0, -2, math.inf, math.nan, True):
        with pytest.raises(pt.InvalidRequestError, match="positive finite"):
            model.multiplied(actuator_torque_gainprm_gain=bad)
    # a vector entry by entry with multiplied; with_values sets one nonzero number only
    assert model.multiplied(body_arm_pos=3).parameter("body_arm_pos").value == (0.0, 0.0, 3.0)
    with pytest.raises(pt.InvalidRequestError, match="one nonzero number"):
        model.with_values(body_arm_pos=1)
    with pytest.raises(pt.InvalidRequestError, match="one nonzero number"):
        model.with_values(tolerance=0).with_values(tolerance=1e-8)
    for route in (model.with_values, model.multiplied):
        with pytest.raises(pt.UnknownVariableError):
            route(no_such=2)
    assert model.parameter("g").value == (9.81,)  # the original is untouched
    assert model.with_values(g=19.62).path == model.multiplied(g=2).path == ""


def test_an_engine_model_cannot_be_changed_by_assignment():
    import copy
    from dataclasses import FrozenInstanceError

    model = engines.load(engines.example_path("pendulum.xml"))
    for name in ("engine", "path", "parameters", "_runner", "anything"):
        with pytest.raises(FrozenInstanceError, match=repr(name)):
            setattr(model, name, None)
        with pytest.raises(FrozenInstanceError):
            delattr(model, name)
    assert (model.engine, model.path.endswith("pendulum.xml"), len(model.parameters)) == ("mujoco", True, 49)
    assert copy.copy(model) is model
    assert copy.deepcopy(model) is model


def test_a_model_runs_in_its_engine_without_handing_out_the_engine_object():
    mujoco = pytest.importorskip("mujoco")
    path = engines.example_path("pendulum.xml")
    model = engines.load(path)
    assert not hasattr(model, "backend")  # the engine's mutable object stays inside
    native = mujoco.MjModel.from_xml_path(str(path))
    assert model.timestep() == native.opt.timestep
    names, dims = model.coordinates()
    assert len(names) == len(dims) == native.nq + native.nv + native.na
    assert [str(d) for d in dims] == ["1", "T^-1"]  # a hinge's angle and its rate
    dims, low, high = model.inputs()
    assert [str(d) for d in dims] == ["M L^2 T^-2"]  # the motor drives the hinge with a torque
    assert (low.tolist(), high.tolist()) == (
        native.actuator_ctrlrange[:, 0].tolist(),
        native.actuator_ctrlrange[:, 1].tolist(),
    )
    # the run is MuJoCo's own stepping: the oracle steps mj_step in Python
    rows = model.run(20, controls=lambda t: [0.3])
    data = mujoco.MjData(native)
    for step in range(20):
        data.ctrl[:] = 0.3
        mujoco.mj_step(native, data)
        assert rows[step + 1].tolist() == [*data.qpos, *data.qvel, *data.act], step
    assert rows[0].tolist() == [*native.qpos0, 0.0]
    # a closed-loop controller gives the same run as the open-loop rows it would give
    assert np.array_equal(model.run(20, policy=lambda m, d: [0.3]), rows)


@pytest.mark.parametrize(
    ("n_steps", "initial", "says"),
    [
        (-1, None, "n_steps must be a whole number from 0 to 10000000, got -1"),
        (2.5, None, "n_steps must be a whole number from 0 to 10000000, got 2.5"),
        (True, None, "n_steps must be a whole number from 0 to 10000000, got True"),
        (3, (0.1,), "initial is a row of 2 finite numbers (qpos[hinge], qvel[hinge]), got [0.1]"),
        (3, (0.1, float("nan")), "got [0.1, nan]"),
        (3, ("up", 0), "initial is a row of 2 numbers, got ('up', 0)"),
    ],
)
def test_a_bad_run_is_refused_by_name(n_steps, initial, says):
    pytest.importorskip("mujoco")
    model = engines.load(engines.example_path("pendulum.xml"))
    with pytest.raises(pt.InvalidRequestError) as err:
        model.run(n_steps, initial=initial)
    assert says in str(err.value)


def test_an_unknown_example_names_the_shipped_ones():
    assert engines.example_path("superball.xml").name == "superball.xml"
    with pytest.raises(ModelFileError) as caught:
        engines.example_path("hopper.xml")
    assert "example:hopper.xml" in str(caught.value)
    assert (
        "the shipped examples are hinged_rod, hinged_rod.urdf, hinged_rod.xml, pendulum.xml, superball, superball.xml;"
    ) in str(caught.value)


def test_engines_read_s_and_every_number_through_the_one_reader():
    from fractions import Fraction

    model = engines.load(engines.example_path("pendulum.xml"))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    # an exact s however written gives one copy; a float s the same numbers for this model
    exact = model.scaled(sc, 10).parameters
    assert model.scaled(sc, "10").parameters == model.scaled(sc, Fraction(10)).parameters == exact
    assert model.scaled(sc, 10.0).parameters == exact
    assert model.scaled(sc, "1/2").parameter("g").value == (9.81 / 2,)
    for bad in (True, 0, -1, "ten", math.nan):
        for call in (lambda s: model.scaled(sc, s), lambda s: engines.verify(model, sc, s, duration=0.01)):
            with pytest.raises(pt.NumberError) as caught:
                call(bad)
            assert str(caught.value) == (
                f"the scale factor s must be a positive finite number such as 2, 0.5 or '1/3', got {bad!r}"
            )
    # a value and a factor: each names its parameter
    assert model.with_values(g="19.62").parameters == model.with_values(g=19.62).parameters
    with pytest.raises(pt.NumberError, match="the value of 'g' must be a finite real number"):
        model.with_values(g="heavy")
    with pytest.raises(pt.NumberError) as caught:
        model.multiplied(g=True)
    assert str(caught.value) == "the factor for 'g' must be a positive finite number such as 2, 0.5 or '1/3', got True"
    # a factor beyond floating point is a LimitError naming the dimension, not a bare OverflowError
    heavy = pt.Scaling.from_unit_change(model.system(), {"M": 5})
    with pytest.raises(pt.LimitError, match=r"the factor of M L\^-3 is s\^5 with s = about 10\^100"):
        model.scaled(heavy, 10**100)


def test_an_engine_takes_a_change_of_units_over_m_l_and_t():
    from pitheorem.engines.enginemodel import check_scaling

    model = engines.load(engines.example_path("pendulum.xml"))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    assert check_scaling(sc) is sc
    lengths = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1})
    for call in (
        lambda: model.scaled(lengths, 2),
        lambda: engines.verify(model, lengths, 2, duration=0.01),
        lambda: engines.verify(model, lengths, 2, duration=0.01, scaled=model),
    ):
        with pytest.raises(pt.InvalidRequestError) as caught:
            call()
        assert str(caught.value) == "the scaling's system has no base dimension 'M'; search on model.system()"


def test_a_models_system_is_built_once_and_holds_every_parameter():
    model = engines.load(engines.example_path("pendulum.xml"))
    system = model.system()
    assert model.system() is system  # the model never changes, so neither does its system
    expected = {name for p in model.parameters for name in p.variables()} | {"t"}
    assert set(system.variables) == expected
    scaled = model.scaled(pt.Scaling.from_unit_change(system, {"L": 1}), 2)
    assert scaled.system() is not system  # a copy is another model, with its own


@pytest.mark.parametrize(
    "name",
    [
        "causes/contact.xml",
        "causes/hanging.xml",
        "causes/hand.xml",
        "causes/mesh_drop.xml",
        "causes/quadruped.urdf",
        "causes/walker_on_floor.xml",
    ],
)
def test_the_how_to_models_ship_with_their_meshes_and_load(name):
    # docs/howto/why_not_similar.md runs these from an installed package: nothing from tests/
    path = engines.example_path(name)
    assert path.parent == engines.example_path("pendulum.xml").parent / "causes"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        model = engines.load(path, **({"ground": True} if name.endswith(".urdf") else {}))
    assert model.parameters


# -- keep_inputs: the actuators' factors on their gains, every input unchanged ---------------------------------

ACTUATED = Path(__file__).parent / "data" / "engines" / "actuated.xml"


def _inputs_moving_every_actuator(t):
    return [0.5 * math.sin(5 * t), 0.05 * math.cos(3 * t), 0.7 * math.sin(2 * t), 0.1 * math.sin(4 * t), 0.5, 0.3]


def test_keep_inputs_keeps_every_control_range_keyframe_and_activation_range():
    model = engines.load(ACTUATED)
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1, "M": 3})
    dims, low, high = model.inputs()
    assert [str(d) for d in dims] == ["M L^2 T^-2", "L", "M L T^-2", "L", "L T^-1", "L T^-1"]
    for s in (4, 10):
        default, kept = model.scaled(sc, s), model.scaled(sc, s, keep_inputs=True)
        # the default scales each input by its dimension; kept, every range is the original's, exactly
        assert not np.array_equal(default.inputs()[2], high)
        assert np.array_equal(kept.inputs()[1], low)
        assert np.array_equal(kept.inputs()[2], high)
        m, m0 = kept.runner.mjmodel, model.runner.mjmodel
        assert np.array_equal(m.actuator_ctrlrange, m0.actuator_ctrlrange)  # the inherited range too
        assert np.array_equal(m.actuator_actrange, m0.actuator_actrange)
        assert np.array_equal(m.key_ctrl, m0.key_ctrl)
        assert np.array_equal(m.key_act, m0.key_act)
        # the gains carry the factor: the motor's by the torque's (s^2 s^3 = s^5), the servos' by the force's
        force = s ** (1 + 3)
        assert m.actuator_gainprm[0, 0] == pytest.approx(m0.actuator_gainprm[0, 0] * s**5, rel=1e-15)
        assert m.actuator_gainprm[1, 0] == pytest.approx(m0.actuator_gainprm[1, 0] * force, rel=1e-15)
        # a bias takes its own factor, as always (force per length: s^3)
        assert m.actuator_biasprm[1, 1] == pytest.approx(m0.actuator_biasprm[1, 1] * s**3, rel=1e-15)
        # the damping ratio, read by MuJoCo only while gain and bias are opposite, is written as its damping
        assert m.actuator_biasprm[3, 2] < 0
        assert m.actuator_biasprm[3, 2] == pytest.approx(m0.actuator_biasprm[3, 2] * s**3, rel=1e-12)


@pytest.mark.parametrize("s", [4, 10])
def test_a_copy_that_keeps_its_inputs_verifies_with_the_very_same_inputs(tmp_path, s):
    model = engines.load(ACTUATED)
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1, "M": 3})
    rep = engines.verify(model, sc, s=s, duration=0.3, controls=_inputs_moving_every_actuator, keep_inputs=True)
    assert rep.excited
    assert rep.similar
    assert rep.exact == (s == 4)
    # saved and read back, the same
    saved = model.scaled(sc, s, keep_inputs=True).save(tmp_path / "kept.xml")
    again = engines.verify(
        model,
        sc,
        s=s,
        duration=0.3,
        controls=_inputs_moving_every_actuator,
        keep_inputs=True,
        scaled=engines.load(saved),
    )
    assert again.similar
    assert again.exact == (s == 4)
    # the kept copy driven as if its inputs were scaled is no longer the same motion
    wrong = engines.verify(
        model,
        sc,
        s=4,
        duration=0.3,
        controls=_inputs_moving_every_actuator,
        scaled=model.scaled(sc, 4, keep_inputs=True),
    )
    assert not wrong.exact


def test_converted_keeps_the_inputs_on_request_and_by_default_converts_them():
    model = engines.load(ACTUATED)
    mm = model.converted(L="mm", M="g")
    kept = model.converted(L="mm", M="g", keep_inputs=True)
    assert mm.inputs()[2][0] == model.inputs()[2][0] * 1e9  # g mm^2 s^-2 per kg m^2 s^-2
    assert np.array_equal(kept.inputs()[1], model.inputs()[1])
    assert np.array_equal(kept.inputs()[2], model.inputs()[2])
    assert kept.units == mm.units == {"M": "g", "L": "mm", "T": "s"}


def test_a_urdf_compiled_by_mujoco_refuses_to_keep_its_inputs_as_pybullet_does():
    # its motors (one per joint, gear 1) take the joint's force itself: no number of the file carries a factor
    model = engines.load(engines.example_path("hinged_rod.urdf"), engine="mujoco")
    assert [str(d) for d in model.inputs()[0]] == ["M L^2 T^-2"]
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    with pytest.raises(pt.errors.InputsNotKeptError, match="joint forces, with no gain to carry a factor"):
        model.scaled(sc, 4, keep_inputs=True)
    model.scaled(sc, 4)  # the default stays as it is


def test_save_names_a_path_it_cannot_write_before_writing(tmp_path):
    """An API fuzz's save("/nonexistent/x.xml") raised Python's FileNotFoundError from deep in the writer; a folder
    given as the path, or a folder that does not exist, is refused by name, and nothing is written."""
    import pitheorem as pt

    model = engines.load(engines.example_path("pendulum.xml"))
    with pytest.raises(pt.InvalidRequestError, match="is a folder"):
        model.save(tmp_path)
    with pytest.raises(pt.InvalidRequestError, match="folder that does not exist"):
        model.save(tmp_path / "missing" / "copy.xml")
    assert list(tmp_path.iterdir()) == []
