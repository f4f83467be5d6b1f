"""pitheorem.engines.loading: engines.load(path, engine=...) picks the engine by file kind or by name."""

from __future__ import annotations

import sys

import pytest

import pitheorem as pt
from pitheorem import engines
from pitheorem.errors import EngineUnavailableError

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

PENDULUM = engines.example_path("pendulum.xml")


def test_the_file_kind_picks_the_engine_unless_engine_names_another():
    assert engines.load(PENDULUM).engine == "mujoco"
    assert engines.load(PENDULUM, engine="mujoco").engine == "mujoco"
    with pytest.raises(pt.InvalidRequestError) as caught:
        engines.load(PENDULUM, engine="pybullet")
    assert str(caught.value) == "engine 'pybullet' does not read MJCF files; an MJCF file runs in 'mujoco' or 'mjx'"
    with pytest.raises(pt.InvalidRequestError) as caught:
        engines.load(PENDULUM, engine="genesis")
    assert str(caught.value) == "unknown engine 'genesis'; use 'pybullet', 'mujoco' or 'mjx'"
    assert caught.value.culprit == "genesis"


def test_a_file_runs_only_in_an_engine_that_compiles_its_format(tmp_path):
    # MuJoCo and MJX compile URDF files too (MuJoCo's own URDF reader); PyBullet reads no MJCF
    urdf = tmp_path / "box.urdf"
    urdf.write_text('<robot name="box"><link name="base"/></robot>')
    for engine in ("mujoco", "mjx"):
        assert engines.load(urdf, engine=engine).engine == engine
    with pytest.raises(pt.InvalidRequestError) as caught:
        engines.load(PENDULUM, engine="pybullet")
    assert str(caught.value) == "engine 'pybullet' does not read MJCF files; an MJCF file runs in 'mujoco' or 'mjx'"
    with pytest.raises(pt.InvalidRequestError) as caught:  # PyBullet's scene options are PyBullet's
        engines.load(urdf, engine="mujoco", fixed_base=True)
    assert str(caught.value) == (
        "engine 'mujoco' takes no option 'fixed_base' (its options: settings); 'fixed_base' is for URDF files "
        "in 'pybullet'"
    )


def test_options_an_engine_does_not_take_are_refused_by_name():
    with pytest.raises(pt.InvalidRequestError) as caught:
        engines.load(PENDULUM, fixed_base=True)
    assert str(caught.value) == (
        "engine 'mujoco' takes no option 'fixed_base' (its options: none, MJCF files in 'mujoco' "
        "take no options); 'fixed_base' is for URDF files in 'pybullet'"
    )
    assert caught.value.culprit == "fixed_base"


def test_an_engine_not_installed_is_named_with_its_extra_and_the_engines_installed(monkeypatch):
    monkeypatch.setitem(sys.modules, "jax", None)  # import jax now raises ImportError
    with pytest.raises(EngineUnavailableError) as caught:
        engines.load(PENDULUM, engine="mjx")
    assert isinstance(caught.value, pt.PiTheoremError)
    assert caught.value.package == "jax"
    assert caught.value.extra == "mjx"
    assert "mjx" not in caught.value.installed
    assert "mujoco" in caught.value.installed
    assert 'pip install "pitheorem[mjx]"; installed here: ' in str(caught.value)


def test_a_missing_or_foreign_file_is_refused(tmp_path):
    with pytest.raises(engines.EngineModelError, match="no such file"):
        engines.load(tmp_path / "missing.xml")
    toml = tmp_path / "model.toml"
    toml.write_text("[variables]\n")
    with pytest.raises(engines.EngineModelError, match="no format read here has this suffix; the formats: MJCF"):
        engines.load(toml)
