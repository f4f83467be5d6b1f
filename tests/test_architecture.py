"""The package's layers, as docs/explanation/architecture.md draws them.

Cross-cutting: it reads the imports of every module of the package.  A
module may import from its own layer and the layers below it; the one
upward import allowed is listed in ``UPWARD`` with its reason.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

from tests.conftest import REPO as ROOT

PACKAGE = ROOT / "pitheorem"
PAGE = ROOT / "docs" / "explanation" / "architecture.md"

#: layer of each module (a subpackage's modules take their subpackage's layer unless listed)
LAYERS = {
    "errors": 0, "exact": 0, "immutable": 0, "linalg": 0,
    "formatting": 1, "plotting": 1,
    "dimensions": 2, "system": 2, "groups": 2, "bases": 2, "basis_sequence": 2, "family": 2,
    "scaling": 3, "scalesearch": 3, "equations": 3, "unitfit": 3,
    "model": 4, "models": 4, "simulation": 4,
    "modelfile": 5, "answers": 5, "cli": 5, "__main__": 5, "": 5,  # "" is the package itself
    "engines": 6,
}

#: the upward imports allowed, (importer, imported) -> why
UPWARD = {
    ("", "engines.fitting"): "pt.fit_units(engine=...) reads that engine's thresholds, imported inside the "
                             "function only when an engine or an engine model is given",
    ("cli", "engines.cli"): "the command line reads MJCF and URDF files through the optional engines, "
                            "imported inside the function that handles such a file",
}


def _module(path: Path) -> str:
    parts = path.relative_to(PACKAGE).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _layer(module: str) -> int:
    head = module.split(".")[0]
    return LAYERS[module] if module in LAYERS else LAYERS[head]


def _imports(path: Path) -> set[str]:
    """The package modules `path` imports, at the top or inside a function, relative or absolute."""
    module = _module(path)
    package = module.split(".") if path.name == "__init__.py" else module.split(".")[:-1]
    package = [p for p in package if p]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = package[: len(package) - node.level + 1]
            target = ".".join([*base, *([node.module] if node.module else [])])
            names = [target] if node.module else [a.name for a in node.names]
            found.update(names if node.module else [".".join([*base, n]) for n in names])
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("pitheorem"):
            found.add(node.module.removeprefix("pitheorem").lstrip("."))
        elif isinstance(node, ast.Import):
            found.update(a.name.removeprefix("pitheorem").lstrip(".") for a in node.names
                         if a.name.split(".")[0] == "pitheorem")
    # `from . import name` may name a module or an attribute of the package: keep modules only
    return {t for t in found if t == "" or (PACKAGE / Path(*t.split("."))).with_suffix(".py").exists()
            or (PACKAGE / Path(*t.split("."))).is_dir()}


def test_every_module_has_a_layer():
    for path in sorted(PACKAGE.rglob("*.py")):
        module = _module(path)
        assert module in LAYERS or module.split(".")[0] in LAYERS, f"{module} has no layer; add it here and on the page"


def test_imports_point_down_or_sideways():
    upward = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        importer = _module(path)
        for imported in _imports(path):
            if _layer(imported) > _layer(importer):
                upward[(importer, imported)] = (_layer(importer), _layer(imported))
    assert set(upward) == set(UPWARD), upward


def test_the_exact_core_never_imports_the_engines_or_the_front_ends():
    # a sharper statement of the same rule, for the layers that must stay light
    for path in sorted(PACKAGE.rglob("*.py")):
        importer = _module(path)
        if _layer(importer) <= 3:
            assert all(_layer(imported) <= 3 for imported in _imports(path)), importer


def test_the_page_lists_every_module_in_its_layer():
    rows = {}
    for line in PAGE.read_text().splitlines():
        match = re.match(r"\| (\d)\. [^|]+\| ([^|]+) \|", line)
        if match:
            rows[int(match.group(1))] = set(re.findall(r"`([\w.]+)`", match.group(2)))
    assert sorted(rows) == list(range(7))
    for module, layer in LAYERS.items():
        if module and layer < 6:  # the engines' row names each engines.* module
            assert module in rows[layer], (module, layer)
    engine_modules = {f"engines.{_module(p).split('.')[-1]}" for p in (PACKAGE / "engines").glob("*.py")
                      if p.name != "__init__.py"}
    assert engine_modules == rows[6]


def test_only_engines_packages_imports_an_engine():
    # engines.packages.engine_module imports mujoco or pybullet by name and names a missing
    # package; no module writes an import statement of an engine, save one submodule
    allowed = {"engines.mjcf": "mujoco.rollout, imported only where engine_module has loaded mujoco"}
    importers = set()
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            if any(name.split(".")[0] in ("mujoco", "pybullet", "pybullet_data") for name in names):
                importers.add(_module(path))
    assert importers == set(allowed)
