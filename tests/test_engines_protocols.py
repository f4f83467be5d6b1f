"""pitheorem.engines.protocols: every backend provides the protocol, and the optional parts are what they say."""

from __future__ import annotations

import ast

import pytest

from pitheorem import engines
from pitheorem.engines.protocols import (
    OPTIONAL,
    REQUIRED,
    ClampsVelocities,
    CounterRuns,
    CountsIterations,
    HasSceneSettings,
    IgnoredSettings,
    NamesElements,
    RefusesScalings,
    Runner,
    Runs,
    SolverDiagnosis,
    StoresCopies,
    SwitchesConstraints,
)
from tests.conftest import REPO

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

ENGINES = REPO / "pitheorem" / "engines"


def test_the_required_methods_are_the_runner_and_the_model_file():
    assert set(REQUIRED) == {
        "timestep",
        "coordinate_dimensions",
        "control_dimensions",
        "control_ranges",
        "run",
        "run_many",
        "twin",
        "parameters",
        "settings",
        "scaled",
        "save",
        "stored_numbers",
        "precision",
        "refusal",
        "check_units",
        "in_units",
        "recorded_units",
        "written_beside",
    }
    assert OPTIONAL["RefusesScalings"] == ("command_line_remedy", "remedy_scene", "unscalable", "unscalable_remedy")
    assert OPTIONAL["CounterRuns"] == ("solver_settings", "variant")
    optional = {m for members in OPTIONAL.values() for m in members}
    assert not optional & set(REQUIRED)


def test_mujocos_backend_has_every_part_but_the_scene_and_the_refusals():
    backend = engines.load(engines.example_path("pendulum.xml")).runner
    for protocol in (Runs, Runner, CounterRuns, CountsIterations, SolverDiagnosis, NamesElements, StoresCopies):
        assert isinstance(backend, protocol), protocol
    for protocol in (HasSceneSettings, RefusesScalings, IgnoredSettings):
        assert not isinstance(backend, protocol), protocol


def test_pybullets_backend_has_the_scene_the_refusals_and_no_solver_diagnosis(tmp_path):
    pytest.importorskip("pybullet", reason="pybullet is not installed (pip install 'pitheorem[engines]')")
    urdf = tmp_path / "box.urdf"
    urdf.write_text(
        '<robot name="box"><link name="base"><inertial><mass value="1"/>'
        '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>'
    )
    backend = engines.load(urdf).runner
    for protocol in (
        Runner,
        HasSceneSettings,
        RefusesScalings,
        IgnoredSettings,
        CounterRuns,
        NamesElements,
        SwitchesConstraints,
        ClampsVelocities,
    ):
        assert isinstance(backend, protocol), protocol
    assert not isinstance(backend, SolverDiagnosis)
    assert not isinstance(backend, CountsIterations)


def test_every_optional_method_is_asked_for_through_its_protocol_not_hasattr():
    # the rest of the package asks a backend for an optional part with isinstance(backend, Protocol):
    # no hasattr or getattr with a default on a backend in the modules that use one
    optional = {m for members in OPTIONAL.values() for m in members}
    analysis = [
        ENGINES / "enginemodel.py",
        *(ENGINES / "verdicts").glob("*.py"),
        ENGINES / "thresholds.py",
        ENGINES / "fitting.py",
        ENGINES / "units.py",
        ENGINES / "cli.py",
    ]
    for name in analysis:
        for node in ast.walk(ast.parse(name.read_text())):
            if isinstance(node, ast.Call) and getattr(node.func, "id", "") in ("hasattr", "getattr"):
                args = node.args
                probed = args[1].value if len(args) > 1 and isinstance(args[1], ast.Constant) else None
                assert probed not in optional | {"run_many"}, (name, probed)


def test_mujocos_runners_keep_inputs_and_pybullets_does_not():
    from pitheorem.engines.protocols import KeepsInputs

    assert isinstance(engines.load(engines.example_path("pendulum.xml")).runner, KeepsInputs)
    assert isinstance(engines.load(engines.example_path("hinged_rod.urdf"), engine="mujoco").runner, KeepsInputs)
    pytest.importorskip("pybullet")
    assert not isinstance(engines.load(engines.example_path("hinged_rod.urdf")).runner, KeepsInputs)
