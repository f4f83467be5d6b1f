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
    "progress": 5,
    "__main__": 5,
    "": 5,  # "" is the package itself
    "engines": 6,
}

#: the upward imports allowed, (importer, imported) -> why
UPWARD = {
    ("", "engines.fitting"): "pt.fit_units(engine=...) reads that engine's thresholds, imported inside the "
    "function only when an engine or an engine model is given",
    ("modelfile", "engines.registry"): "a file's format is the engines' registry's data (which imports no engine): "
    "model_kind asks it, so that a new format is one registry line",
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
    engine_modules = {_module(p) for p in (PACKAGE / "engines").rglob("*.py") if p.name != "__init__.py"}
    assert engine_modules == rows[6]


#: the Python packages of the engines: only a runner module (and engines.packages, which imports them by
#: name for the runners) may import one or ask engine_module for one, with one exception below
ENGINE_PACKAGES = ("mujoco", "pybullet", "pybullet_data", "jax", "jaxlib", "warp", "mujoco_warp")

#: the modules besides the runners that use an engine's package, and why
PARSERS = {
    "engines.fileformats.mjcf": "MJCF's reference parser is MuJoCo's MjSpec (defaults, includes, compiled masses): "
    "the format reads and writes through it and never steps a model",
}


def _registered() -> tuple[set[str], set[str], dict[str, str]]:
    """The runner modules, the format modules, and each engine's runner module, from the registry."""
    from pitheorem.engines.registry import FORMATS, REGISTRY

    runners = {f"engines.{e.module}" for e in REGISTRY}
    formats = {f"engines.{f.module}" for f in FORMATS}
    return runners, formats, {e.name: f"engines.{e.module}" for e in REGISTRY}


def _graph() -> dict[str, set[str]]:
    """Each module's imports of package modules; the loader imports each registered runner by name."""
    runners, _formats, _of = _registered()
    graph = {_module(p): _imports(p) - {_module(p)} for p in sorted(PACKAGE.rglob("*.py"))}
    graph["engines.loading"] |= runners
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
    # the check finds one: the circle that load's if-chain in the model's module once closed with the backends
    graph = _graph()
    graph["engines.enginemodel"] = graph["engines.enginemodel"] | {"engines.runners.mujoco"}
    assert ["engines.enginemodel", "engines.runners.mujoco"] in [
        [m for m in c if m in ("engines.enginemodel", "engines.runners.mujoco")] for c in _cycles(graph)
    ]


def test_runners_and_formats_keep_apart():
    # a runner imports no other runner but the one its registry line builds on (MJX on MuJoCo's compilation);
    # a format imports no runner and no verdict: it reads and writes files, whoever runs them
    from pitheorem.engines.registry import REGISTRY

    runners, formats, module_of = _registered()
    graph = _graph()
    for e in REGISTRY:
        others = runners - {module_of[e.name], module_of.get(e.base)}
        assert not graph[module_of[e.name]] & others, e.name
    assert graph["engines.runners.mjx"] & runners == {"engines.runners.mujoco"}
    for fmt in formats:
        assert not {m for m in graph[fmt] if m.startswith(("engines.runners", "engines.verdicts"))}, fmt


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


def test_only_runners_import_an_engine():
    runners, _formats, _of = _registered()
    users = {_module(p) for p in sorted(PACKAGE.rglob("*.py")) if _engine_users(p)}
    # the paper's rod and SUPERball run through the runners too: no module runs an engine by hand
    assert users <= runners | set(PARSERS) | {"engines.packages"}, users - runners
    assert runners <= users  # each runner runs its engine
    assert set(PARSERS) <= users  # no stale exception


def test_the_engine_check_sees_a_statement_and_a_call(tmp_path):
    sample = tmp_path / "sample.py"
    sample.write_text("import jax.numpy as jnp\n")
    assert _engine_users(sample)
    sample.write_text("def f():\n    return engine_module('mujoco')\n")
    assert _engine_users(sample)
    sample.write_text("from .packages import quiet_stdout\n")
    assert not _engine_users(sample)


#: the modules that may name an engine in their code (not only in docstrings), and why; everything else of
#: pitheorem.engines (the analysis: verdicts, thresholds, fitting, units, the model, the loader, the command
#: line) reaches an engine only through the registry and the runner protocols
NAMES_ENGINES = {
    "engines.registry": "the one table of the engines' names",
    "engines.rules": "the engines' published rules of thumb, each its engine's",
    "engines.paper.rod": "the paper's rod is shipped as one file per engine",
    "engines.paper.superball": "SUPERball is shipped as a MuJoCo file",
    "engines.fileformats.mjcfunits": "the MJCF format's table of units is MuJoCo's own, and the models it "
    "generates to hold the reader against it are MJCF files (a <mujoco> root); it imports no engine",
    **PARSERS,
}


def _names_an_engine(path: Path) -> list[tuple[int, str]]:
    """The engine names in a module's string constants (its docstrings left out): (line, name) each."""
    from pitheorem.engines.registry import ALIASES, REGISTRY

    names = {e.name for e in REGISTRY} | set(ALIASES)
    tree = ast.parse(path.read_text())
    docstrings = {
        id(node.body[0].value)
        for node in ast.walk(tree)
        if isinstance(node, ast.Module | ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef)
        and node.body
        and isinstance(node.body[0], ast.Expr)
        and isinstance(node.body[0].value, ast.Constant)
    }
    return [
        (node.lineno, word)
        for node in ast.walk(tree)
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings
        for word in sorted(set(re.findall(r"[a-z_]+", node.value)) & names)
    ]


#: private attributes of other libraries' objects that have no public name, and why they are read
FOREIGN_PRIVATE = {"_prec": "sympy.Float's binary precision (exact.read_number reads a Float as the double it holds)"}


def _reads_a_private_attribute(path: Path) -> list[tuple[int, str]]:
    """``obj._name`` where `obj` is not self or cls and no code of the module defines ``_name``: (line, name) each."""
    tree = ast.parse(path.read_text())
    defined = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            defined.add(node.name)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store):
            defined.add(node.attr)
        elif isinstance(node, ast.Constant) and isinstance(node.value, str):
            defined.add(node.value)  # __slots__ and object.__setattr__(self, "_name", ...)
    return [
        (node.lineno, node.attr)
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute)
        and node.attr.startswith("_")
        and not node.attr.startswith("__")
        and not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"))
        and node.attr not in defined
        and node.attr not in FOREIGN_PRIVATE
    ]


def test_no_module_outside_a_runner_names_an_engine():
    runners, _formats, _of = _registered()
    found = {}
    for path in sorted((PACKAGE / "engines").rglob("*.py")):
        module = _module(path)
        if module not in runners and module not in NAMES_ENGINES and (named := _names_an_engine(path)):
            found[module] = named
    assert found == {}
    assert all(
        _names_an_engine(PACKAGE / Path(*m.split("."))).__len__() or m.startswith("engines.paper") for m in ()
    )  # (nothing more: a stale exception is caught below)
    stale = [m for m in NAMES_ENGINES if not _names_an_engine((PACKAGE / Path(*m.split("."))).with_suffix(".py"))]
    assert stale == []


def test_no_module_reads_a_private_attribute_of_another_modules_object():
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        if reads := _reads_a_private_attribute(path):
            found[_module(path)] = reads
    assert found == {}


def test_the_two_checks_find_what_they_look_for(tmp_path):
    sample = tmp_path / "sample.py"
    sample.write_text(
        '"""Runs in mujoco (a docstring may say so)."""\n\ndef f(model):\n    if model.engine == "mjx":\n'
        "        return model._runner\n    return model.runner\n"
    )
    assert _names_an_engine(sample) == [(4, "mjx")]
    assert _reads_a_private_attribute(sample) == [(5, "_runner")]
    sample.write_text(
        "class A:\n    def __init__(self):\n        self._x = 1\n\n    def same(self, other):\n"
        "        return other._x + self._x\n"
    )
    assert _reads_a_private_attribute(sample) == []  # its own class's attribute, on another instance
    sample.write_text('x = "bulleted list, a mujocoid"\n')
    assert _names_an_engine(sample) == []  # whole words only
