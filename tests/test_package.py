"""The package as pytest sees it: one installed copy, shared by tests and doctests.

``isinstance`` checks in pitheorem compare against its own classes; they
only hold if every module is imported once.  pyproject.toml configures
pytest for that (``--import-mode=append``); this test checks the result.
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import subprocess
import sys
import types
from pathlib import Path

import pytest
from _pytest.pathlib import import_path

import pitheorem as pt
from tests.conftest import REPO, loaded_after

#: the package in this checkout, whose doctests pytest collects
ROOT = Path(__file__).resolve().parents[1] / "pitheorem"


def _module_name(path: Path, root: Path = ROOT) -> str:
    parts = path.relative_to(root.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def test_pytest_imports_every_module_of_the_installed_package_once(request):
    # `import pitheorem` finds this checkout (installed editable), not another copy
    assert Path(importlib.util.find_spec("pitheorem").origin).resolve() == ROOT / "__init__.py"
    assert Path(pt.__file__).resolve() == ROOT / "__init__.py"
    # pytest's own import of a module file (as for its doctests) gives that file, as the module the package has
    for path in sorted(ROOT.rglob("*.py")):
        name = _module_name(path)
        if name == "pitheorem.__main__":
            continue  # running it is the command line
        mine = importlib.import_module(name)
        theirs = import_path(path, mode=request.config.getoption("importmode"), root=request.config.rootpath,
                             consider_namespace_packages=False)
        assert Path(theirs.__file__).resolve() == path, name
        assert theirs is mine, name
    # and no file of the package is loaded twice, under any name
    by_file: dict[Path, list[str]] = {}
    for name, module in list(sys.modules.items()):
        file = getattr(module, "__file__", None)
        if file and Path(file).resolve().is_relative_to(ROOT):
            by_file.setdefault(Path(file).resolve(), []).append(name)
    assert {f: names for f, names in by_file.items() if len(names) > 1} == {}
    assert all(name.startswith("pitheorem") for names in by_file.values() for name in names)
    # so the classes tests see are the classes the package checks against
    assert importlib.import_module("pitheorem.scaling").Scaling is pt.Scaling


def test_submodules_and_the_functions_they_define_keep_apart():
    # a module named like its function would be rebound over the function on import
    for module_name, function in (("scalesearch", "search"), ("simulation", "simulate"),
                                  ("simulation", "verify_similarity")):
        module = importlib.import_module(f"pitheorem.{module_name}")
        assert getattr(pt, module_name) is module
        assert callable(getattr(pt, function))
        assert not isinstance(getattr(pt, function), type(module))
        assert getattr(pt, function) is getattr(module, function)
    # and no public function shares its name with a module of the package
    modules = {path.stem for path in ROOT.glob("*.py")}
    assert modules.isdisjoint(name for name in pt.__all__ if callable(getattr(pt, name)))


def _private_imports(path: Path, root: Path = ROOT) -> list[str]:
    """``module.name`` for every leading-underscore name `path` imports from another pitheorem module."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = _module_name(path, root).split(".")
    if path.name != "__init__.py":
        package = package[:-1]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:  # relative: from the package `level` steps up
                base = package[: len(package) - node.level + 1]
                module = ".".join([*base, *([node.module] if node.module else [])])
            else:
                module = node.module or ""
            if module.split(".")[0] != "pitheorem":
                continue
            names = [f"{module}.{alias.name}" for alias in node.names]
        elif isinstance(node, ast.Import):
            names = [alias.name for alias in node.names if alias.name.split(".")[0] == "pitheorem"]
        else:
            continue
        found += [name for name in names
                  if any(part.startswith("_") and not part.startswith("__") for part in name.split("."))]
    return found


def test_no_module_imports_another_modules_private_names(tmp_path):
    offenders = {str(path.relative_to(ROOT.parent)): found for path in sorted(ROOT.rglob("*.py"))
                 if (found := _private_imports(path))}
    assert offenders == {}
    # the check finds each form it looks for: relative, absolute, a private module, and a package's own name
    sample = tmp_path / "pitheorem" / "engines" / "sample.py"
    sample.parent.mkdir(parents=True)
    sample.write_text("from .rod import _quiet\nfrom ..bases import LaplaceTables, _Descent\n"
                      "from pitheorem.engines.model import _check_s\nimport pitheorem._hidden\n"
                      "from . import _private\nfrom os import _exit\nfrom .model import __all__\n")
    assert _private_imports(sample, tmp_path / "pitheorem") == [
        "pitheorem.engines.rod._quiet", "pitheorem.bases._Descent", "pitheorem.engines.model._check_s",
        "pitheorem._hidden", "pitheorem.engines._private"]


def test_import_loads_neither_numpy_scipy_nor_matplotlib():
    assert loaded_after("import pitheorem") == set()


def test_lazy_names_resolve_to_the_functions_not_the_modules():
    import pitheorem.scalesearch as scalesearch
    import pitheorem.simulation as simulation

    assert scalesearch.__name__ == "pitheorem.scalesearch"  # the module is the module
    assert pt.search is scalesearch.search
    assert pt.search.__name__ == "search"
    assert pt.simulate.__name__ == "simulate"
    assert callable(pt.simulate)
    # the module's name differs from its functions': importing it gives the module
    assert isinstance(simulation, types.ModuleType)
    assert simulation.simulate is pt.simulate
    assert simulation.verify_similarity is pt.verify_similarity
    for name in pt.__all__:
        assert getattr(pt, name) is not None
        assert name in dir(pt)
    with pytest.raises(AttributeError):
        pt.no_such_name  # noqa: B018


def test_core_does_not_import_engines():
    code = "import sys, pitheorem; print(any(m.startswith(('pitheorem.engines', 'pybullet', 'mujoco')) for m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=REPO)
    assert out.stdout.strip() == "False"
