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
    "errors": 0,
    "exact": 0,
    "immutable": 0,
    "linalg": 0,
    "formatting": 1,
    "plotting": 1,
    "dimensions": 2,
    "system": 2,
    "groups": 2,
    "bases": 2,
    "basis_sequence": 2,
    "family": 2,
    "scaling": 3,
    "scalesearch": 3,
    "equations": 3,
    "unitfit": 3,
    "model": 4,
    "models": 4,
    "simulation": 4,
    "modelfile": 5,
    "answers": 5,
    "cli": 5,
    "__main__": 5,
    "": 5,  # "" is the package itself
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
            found.update(
                a.name.removeprefix("pitheorem").lstrip(".") for a in node.names if a.name.split(".")[0] == "pitheorem"
            )
    # `from . import name` may name a module or an attribute of the package: keep modules only
    return {
        t
        for t in found
        if t == ""
        or (PACKAGE / Path(*t.split("."))).with_suffix(".py").exists()
        or (PACKAGE / Path(*t.split("."))).is_dir()
    }


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
    engine_modules = {
        f"engines.{_module(p).split('.')[-1]}" for p in (PACKAGE / "engines").glob("*.py") if p.name != "__init__.py"
    }
    assert engine_modules == rows[6]


#: the Python packages of the engines: only a backend module (and engines.packages, which imports them by
#: name for the backends) may import one or ask engine_module for one
ENGINE_PACKAGES = ("mujoco", "pybullet", "pybullet_data", "jax", "jaxlib")


def _graph() -> dict[str, set[str]]:
    """Each module's imports of package modules; the loader imports each registered backend by name."""
    from pitheorem.engines.registry import REGISTRY

    graph = {_module(p): _imports(p) - {_module(p)} for p in sorted(PACKAGE.rglob("*.py"))}
    graph["engines.loading"] |= {f"engines.{e.module}" for e in REGISTRY}
    return graph


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan), each sorted."""
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_no_import_circle_anywhere():
    assert _cycles(_graph()) == []
    # the check finds one: the circle that load's if-chain in engines.model once closed with the backends
    graph = _graph()
    graph["engines.model"] = graph["engines.model"] | {"engines.mjcf"}
    assert ["engines.mjcf", "engines.model"] in [
        [m for m in c if m in ("engines.mjcf", "engines.model")] for c in _cycles(graph)
    ]


def test_no_backend_imports_another_engines_backend():
    # a backend may build on the one engine its registry line names as its base (MJX on MuJoCo's reading)
    from pitheorem.engines.registry import REGISTRY

    module_of = {e.name: f"engines.{e.module}" for e in REGISTRY}
    graph = _graph()
    for e in REGISTRY:
        others = set(module_of.values()) - {module_of[e.name], module_of.get(e.base)}
        assert not graph[module_of[e.name]] & others, e.name
    assert graph["engines.mjx"] & set(module_of.values()) == {"engines.mjcf"}


def _engine_users(path: Path) -> bool:
    """Whether a module imports an engine's package or asks engine_module for one."""
    for node in ast.walk(ast.parse(path.read_text())):
        names = (
            [a.name for a in node.names]
            if isinstance(node, ast.Import)
            else [node.module or ""]
            if isinstance(node, ast.ImportFrom) and not node.level
            else []
        )
        if any(name.split(".")[0] in ENGINE_PACKAGES for name in names):
            return True
        if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "engine_module":
            return True
    return False


def test_only_backends_import_an_engine():
    from pitheorem.engines.registry import REGISTRY

    backends = {f"engines.{e.module}" for e in REGISTRY}
    users = {_module(p) for p in sorted(PACKAGE.rglob("*.py")) if _engine_users(p)}
    # the paper's rod and SUPERball run through the backends too: no module runs an engine by hand
    assert users <= backends | {"engines.packages"}, users - backends
    assert backends <= users  # each backend runs its engine
    # the model, the registry, the loader, verify, audit and diagnose run engines only through backends
    for module in (
        "engines.model",
        "engines.registry",
        "engines.loading",
        "engines.verify",
        "engines.audit",
        "engines.diagnose",
        "engines.backend",
    ):
        assert module not in users


def test_the_engine_check_sees_a_statement_and_a_call(tmp_path):
    sample = tmp_path / "sample.py"
    sample.write_text("import jax.numpy as jnp\n")
    assert _engine_users(sample)
    sample.write_text("def f():\n    return engine_module('mujoco')\n")
    assert _engine_users(sample)
    sample.write_text("from .packages import quiet_stdout\n")
    assert not _engine_users(sample)
