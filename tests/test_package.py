"""The package as pytest sees it: one installed copy, shared by tests and doctests.

``isinstance`` checks in pitheorem compare against its own classes; they
only hold if every module is imported once.  pyproject.toml configures
pytest for that (``--import-mode=append``); this test checks the result.
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
from pathlib import Path

from _pytest.pathlib import import_path

import pitheorem as pt

#: the package in this checkout, whose doctests pytest collects
ROOT = Path(__file__).resolve().parents[1] / "pitheorem"


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT.parent).with_suffix("").parts
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
