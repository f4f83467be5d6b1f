"""pitheorem.engines.registry: one line per engine and engines.backends()."""

from __future__ import annotations

import sys

import pytest

from pitheorem import engines
from pitheorem.engines.registry import FORMATS, REGISTRY, Engine, file_format, formats, registered
from tests.conftest import REPO

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")


def test_one_line_per_engine_with_one_name_and_its_module():
    names = [e.name for e in REGISTRY]
    assert names == ["pybullet", "mujoco", "mjx", "warp"]
    for e in REGISTRY:
        module = REPO / "pitheorem" / "engines" / (e.module.replace(".", "/") + ".py")
        assert module.is_file(), e
        assert e.module.startswith("runners."), e  # an engine's module is a runner
        for fmt in e.formats:
            assert f"def {e.loader(fmt)}(" in module.read_text()
            assert fmt in formats()
        assert e.base in ("", *names)
        assert e.base != e.name
        assert e.precision in ("float64", "float32")
    # each format has one default engine, which compiles it
    for f in FORMATS:
        assert f.name in registered(f.engine).formats, f
        assert (REPO / "pitheorem" / "engines" / (f.module.replace(".", "/") + ".py")).is_file(), f
        assert f.module.startswith("fileformats."), f


def test_a_files_format_is_its_suffix_and_where_formats_share_one_its_root_element(tmp_path):
    assert file_format("arm.URDF").name == "urdf"
    assert file_format("model.toml") is None
    assert file_format("robot.sdf") is None
    robot = tmp_path / "robot.xml"
    robot.write_text('<?xml version="1.0"?>\n<robot name="r"><link name="a"/></robot>')
    assert file_format(robot).name == "urdf"
    robot.write_text("<mujoco><worldbody/></mujoco>")
    assert file_format(robot).name == "mjcf"
    assert file_format(tmp_path / "absent.xml").name == "mjcf"  # no file to read: the suffix's first format


def test_backends_lists_the_installed_engines_sorted(monkeypatch):
    installed = engines.backends()
    assert installed == tuple(sorted(installed))
    assert "mujoco" in installed
    expected = {e.name for e in REGISTRY if all(_importable(p) for p in e.packages)}
    assert set(installed) == expected
    monkeypatch.setitem(sys.modules, "pybullet", None)  # as if pybullet were missing: find_spec refuses it
    assert "pybullet" not in engines.backends()


def _importable(name: str) -> bool:
    import importlib

    try:
        importlib.import_module(name)
    except ImportError:
        return False
    return True


def test_installed_is_false_for_a_module_that_cannot_be_found():
    assert not Engine("x", "x", (), ("no_such_module_here",)).installed()
    assert not Engine("x", "x", (), ("no_such_module_here.sub",)).installed()
    assert registered("bullet") is registered("pybullet")


def test_a_model_is_written_only_under_a_suffix_its_format_reads(tmp_path):
    """An MJCF copy saved as ``copy.urdf`` was written (``apply --output x.urdf``) and then read as a URDF file and
    refused; a URDF saved as ``.mjcf`` would not load at all.  Both are refused by name before anything is written,
    and the suffixes each format reads are written, in any case."""
    import pitheorem as pt
    from pitheorem import engines

    mjcf = engines.load(engines.example_path("pendulum.xml"))
    urdf = engines.load(engines.example_path("hinged_rod.urdf"), engine="mujoco")
    for model, bad, good in ((mjcf, "copy.urdf", "copy.MJCF"), (urdf, "copy.mjcf", "copy.xml")):
        with pytest.raises(pt.InvalidRequestError, match="format names its files"):
            model.save(tmp_path / bad)
        assert not (tmp_path / bad).exists()
        out = model.save(tmp_path / good)
        assert engines.load(out, engine="mujoco").parameter("g").value == model.parameter("g").value
