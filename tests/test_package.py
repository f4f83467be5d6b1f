"""The package as pytest sees it: one installed copy, shared by tests and doctests.

``isinstance`` checks in pitheorem compare against its own classes; they
only hold if every module is imported once.  pyproject.toml configures
pytest for that (``--import-mode=append``); this test checks the result.

Cross-cutting: the package as a whole (how pytest imports it, what ``import
pitheorem`` loads, which module may import which name) and the layout of these
tests: each module of ``pitheorem`` and ``pitheorem.engines`` has its test file.
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import sys
import types
from pathlib import Path

import pytest
from _pytest.pathlib import import_path

import pitheorem as pt
from tests.conftest import REPO, loaded_after

#: the package in this checkout, whose doctests pytest collects
ROOT = REPO / "pitheorem"


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
        theirs = import_path(
            path,
            mode=request.config.getoption("importmode"),
            root=request.config.rootpath,
            consider_namespace_packages=False,
        )
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
    for module_name, function in (
        ("scalesearch", "search"),
        ("simulation", "simulate"),
        ("simulation", "verify_similarity"),
    ):
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
        found += [
            name
            for name in names
            if any(part.startswith("_") and not part.startswith("__") for part in name.split("."))
        ]
    return found


def test_no_module_imports_another_modules_private_names(tmp_path):
    offenders = {
        str(path.relative_to(ROOT.parent)): found
        for path in sorted(ROOT.rglob("*.py"))
        if (found := _private_imports(path))
    }
    assert offenders == {}
    # the check finds each form it looks for: relative, absolute, a private module, and a package's own name
    sample = tmp_path / "pitheorem" / "engines" / "sample.py"
    sample.parent.mkdir(parents=True)
    sample.write_text(
        "from .rod import _quiet\nfrom ..bases import LaplaceTables, _Descent\n"
        "from pitheorem.engines.enginemodel import _check_s\nimport pitheorem._hidden\n"
        "from . import _private\nfrom os import _exit\nfrom .model import __all__\n"
    )
    assert _private_imports(sample, tmp_path / "pitheorem") == [
        "pitheorem.engines.rod._quiet",
        "pitheorem.bases._Descent",
        "pitheorem.engines.enginemodel._check_s",
        "pitheorem._hidden",
        "pitheorem.engines._private",
    ]


def test_import_loads_neither_numpy_scipy_nor_matplotlib_nor_the_engines():
    loaded = loaded_after(
        "import pitheorem", ("numpy", "scipy", "matplotlib", "pitheorem.engines", "pybullet", "mujoco")
    )
    assert not loaded & {"numpy", "scipy", "matplotlib"}, loaded
    assert not loaded & {"pitheorem.engines", "pybullet", "mujoco"}, loaded


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


#: test files that test no single module, and why (each says so in its docstring too)
CROSS_CUTTING = {
    "test_properties.py": "hypothesis properties tying system, groups, bases and linalg together on one random system",
    "test_fuzz.py": "one fuzz test drawing from every public entry point at once",
    "test_docstrings.py": "a meta-test over every public object of pitheorem, pitheorem.engines and matlab_ports",
    "test_package.py": "the package as a whole: its import, its private names, this layout",
    "test_check_pages.py": "docs tooling (docs/check_pages.py), not a module of pitheorem",
    "test_corpus_robots.py": "docs tooling (docs/corpus_verdicts.py and the JSON file it writes), not a module",
    "test_matlab_ports.py": "the matlab_ports namespace, not a module of pitheorem",
    "test_architecture.py": "the layers of docs/explanation/architecture.md: every import of every module",
    "test_engines_corpus.py": "the whole engine path on the corpus of gymnasium's and pybullet_data's models",
}


def module_test_files(root: Path = ROOT) -> dict[str, str]:
    """The test file each module of the package must have: tests/test_<module>.py, test_engines_<module>.py for
    pitheorem.engines; a subpackage (formatting) has one file, or one per part (test_formatting_<part>.py)."""
    files = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]  # a subpackage is its __init__
        if parts in ((), ("__main__",), ("engines",)):
            continue
        if parts[0] == "engines" and len(parts) == 2 and path.name == "__init__.py":
            continue  # engines' subpackages (formats, runners, verdicts, paper) only group their modules  # the package itself: test_package; `python -m pitheorem`: test_cli; engines re-exports
        if parts[0] == "engines":
            files[".".join(parts)] = f"test_engines_{parts[-1]}.py"
        else:
            files[".".join(parts)] = f"test_{parts[0]}.py"
    return files


def test_every_module_has_its_test_file_and_every_test_file_a_module_or_a_reason():
    tests = Path(__file__).resolve().parent
    present = {path.name for path in tests.glob("test_*.py")}
    wanted = module_test_files()
    # formatting's parts may have files of their own: test_formatting_<part>.py
    parts_covered = {
        name
        for name in wanted
        if name.startswith("formatting.") and f"test_formatting_{name.split('.')[-1]}.py" in present
    }
    assert {name: file for name, file in wanted.items() if file not in present and name not in parts_covered} == {}
    allowed = (
        set(wanted.values())
        | {f"test_formatting_{name.split('.')[-1]}.py" for name in wanted if name.startswith("formatting.")}
        | set(CROSS_CUTTING)
    )
    assert sorted(present - allowed) == []
    assert set(CROSS_CUTTING) <= present  # no stale reason
    assert not set(CROSS_CUTTING) & set(wanted.values())
    # the modules of the list, so that a rename shows up here
    assert {file for file in wanted.values() if not file.startswith("test_engines_")} == {
        f"test_{m}.py"
        for m in (
            "answers",
            "bases",
            "basis_sequence",
            "cli",
            "dimensions",
            "equations",
            "errors",
            "exact",
            "family",
            "formatting",
            "groups",
            "immutable",
            "linalg",
            "model",
            "modelfile",
            "models",
            "plotting",
            "progress",
            "scalesearch",
            "scaling",
            "simulation",
            "system",
            "unitfit",
        )
    }
    assert {name: file for name, file in wanted.items() if file.startswith("test_engines_")} == {
        f"engines.{m}": f"test_engines_{m.split('.')[-1]}.py"
        for m in (
            "cli",
            "constants",
            "enginemodel",
            "fileformats.assets",
            "fileformats.mjcf",
            "fileformats.mjcfunits",
            "fileformats.numbers",
            "fileformats.urdf",
            "fitting",
            "loading",
            "packages",
            "paper.rod",
            "paper.superball",
            "parameters",
            "protocols",
            "registry",
            "rules",
            "runners.mjx",
            "runners.mujoco",
            "runners.pybullet",
            "runners.warp",
            "thresholds",
            "units",
            "verdicts.audit",
            "verdicts.binary",
            "verdicts.causes",
            "verdicts.diagnose",
            "verdicts.probes",
            "verdicts.scalefree",
            "verdicts.strength",
            "verdicts.sweep",
            "verdicts.verify",
        )
    }


def test_the_layout_check_finds_a_missing_file_and_a_stray_one(tmp_path):
    package = tmp_path / "pitheorem"
    (package / "engines").mkdir(parents=True)
    for name in ("__init__.py", "__main__.py", "alpha.py", "engines/__init__.py", "engines/beta.py"):
        (package / name).write_text("")
    (package / "formatting").mkdir()
    (package / "formatting" / "__init__.py").write_text("")
    (package / "formatting" / "gamma.py").write_text("")
    assert module_test_files(package) == {
        "alpha": "test_alpha.py",
        "engines.beta": "test_engines_beta.py",
        "formatting": "test_formatting.py",
        "formatting.gamma": "test_formatting.py",
    }
