"""pitheorem.engines.registry: one line per engine and engines.backends()."""

from __future__ import annotations

import sys

import pytest

from pitheorem import engines
from pitheorem.engines.registry import REGISTRY, Engine, registered
from tests.conftest import REPO

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")


def test_one_line_per_engine_with_one_name_and_its_module():
    names = [e.name for e in REGISTRY]
    assert names == ["pybullet", "mujoco", "mjx"]
    for e in REGISTRY:
        module = REPO / "pitheorem" / "engines" / f"{e.module}.py"
        assert module.is_file(), e
        assert f"def {e.loader}(" in module.read_text()
        assert e.base in ("", *names)
        assert e.base != e.name
    # each file kind has exactly one engine it loads in by default
    for kind in {k for e in REGISTRY for k in e.kinds}:
        assert sum(e.default for e in REGISTRY if kind in e.kinds) == 1, kind


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
    assert not Engine("x", "x", "x", (), ("no_such_module_here",)).installed()
    assert not Engine("x", "x", "x", (), ("no_such_module_here.sub",)).installed()
    assert registered("bullet") is registered("pybullet")
