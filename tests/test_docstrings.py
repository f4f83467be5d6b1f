"""Every public function, class and method has a numpydoc docstring with a runnable example.

The public objects are the names in ``__all__`` of three namespaces: ``pitheorem``
(``import pitheorem as pt``, with the submodules it lists, such as ``pt.models``),
``pitheorem.engines``, and each public module of ``matlab_ports``. For each of them,
and for each public method, property, classmethod and staticmethod its classes define:

* a summary line, shorter than 80 characters;
* an ``Examples`` section with at least one ``>>>`` line and no ``+SKIP``; pytest
  collects these examples as doctests (``--doctest-modules`` over ``pitheorem`` and
  ``matlab_ports``, see ``testpaths`` in ``pyproject.toml``), so they run;
* a ``Parameters`` section naming exactly the parameters of the signature (``self``
  and ``cls`` aside): none missing, none extra, none twice. ``a, b : int`` documents
  ``a`` and ``b``; ``*args`` and ``**kwargs`` are written with their stars. A class
  is checked against its constructor when its docstring has a ``Parameters`` section.

Modelled on python-control's ``docstrings_test.py``.

Cross-cutting: a meta-test over every public object of every namespace, not the
behaviour of one module.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import tomllib
import warnings
from pathlib import Path

import pytest
from numpydoc.docscrape import ClassDoc, FunctionDoc, NumpyDocString

import pitheorem as pt
from tests.conftest import REPO

#: folders whose modules pytest collects doctests from (pyproject.toml, testpaths)
DOCTEST_ROOTS = (REPO / "pitheorem", REPO / "matlab_ports")


def _namespaces():
    from pitheorem import engines

    yield "pt", pt
    yield "engines", engines
    import matlab_ports

    for info in pkgutil.iter_modules(matlab_ports.__path__):
        if not info.name.startswith("_"):
            yield f"matlab_ports.{info.name}", importlib.import_module(f"matlab_ports.{info.name}")


def _documentable(obj) -> bool:
    return inspect.isclass(obj) or inspect.isfunction(obj)


def public_objects():
    """``{qualified name: function or class}`` for every public name of the three namespaces."""
    found = {}
    for prefix, module in _namespaces():
        for name in module.__all__:
            obj = getattr(module, name)
            if inspect.ismodule(obj):  # pt.models, pt.plotting: their own public names
                for sub in obj.__all__:
                    if _documentable(getattr(obj, sub)):
                        found[f"{prefix}.{name}.{sub}"] = getattr(obj, sub)
            elif _documentable(obj):
                found[f"{prefix}.{name}"] = obj
    return found


def public_members(cls):
    """``{name: function}`` for the public methods and properties that `cls` itself defines."""
    members = {}
    for attr, member in vars(cls).items():
        if attr.startswith("_"):
            continue
        if isinstance(member, classmethod | staticmethod):
            members[attr] = member.__func__
        elif isinstance(member, property):
            members[attr] = member.fget
        elif inspect.isfunction(member):
            members[attr] = member
    return members


OBJECTS = public_objects()
MEMBERS = {
    f"{name}.{attr}": (func, not isinstance(inspect.getattr_static(cls, attr), property))
    for name, cls in OBJECTS.items()
    if inspect.isclass(cls)
    for attr, func in public_members(cls).items()
}


def documented_names(doc: NumpyDocString) -> list[str]:
    """Parameter names as documented, one per name: ``a, b : int`` gives a and b."""
    names = []
    for param in doc["Parameters"]:
        names += [part.strip() for part in param.name.split(",") if part.strip()]
    return names


def signature_names(func) -> list[str]:
    """Parameter names of the signature as numpydoc writes them (``*args``, ``**kwargs``)."""
    names = []
    for p in inspect.signature(func).parameters.values():
        if p.name in ("self", "cls"):
            continue
        star = "*" if p.kind is p.VAR_POSITIONAL else "**" if p.kind is p.VAR_KEYWORD else ""
        names.append(star + p.name)
    return names


def check_parameters(name, doc, func):
    documented = documented_names(doc)
    expected = signature_names(func)
    twice = sorted({n for n in documented if documented.count(n) > 1})
    assert not twice, f"{name}: parameters documented twice: {twice}"
    missing = [n for n in expected if n not in documented]
    extra = [n for n in documented if n not in expected]
    assert not missing, f"{name}: parameters not documented: {missing}"
    assert not extra, f"{name}: documented parameters not in the signature: {extra}"


def check_summary_and_example(name, doc, obj):
    summary = " ".join(doc["Summary"])
    assert summary, f"{name} has no summary line"
    assert len(summary) < 80, f"{name}: summary too long ({len(summary)} chars)"
    assert any(line.lstrip().startswith(">>>") for line in doc["Examples"]), f"{name} has no >>> example"
    skipped = [line.strip() for line in doc["Examples"] if "+SKIP" in line]
    assert not skipped, f"{name}: skipped example lines do not run: {skipped}"
    source = Path(inspect.getsourcefile(obj)).resolve()
    assert any(source.is_relative_to(root) for root in DOCTEST_ROOTS), f"{name}: {source} is not doctest-collected"


def _doc(obj, cls=False):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numpydoc warns about sections it does not know; the checks say more
        return ClassDoc(obj) if cls else FunctionDoc(obj)


def test_the_examples_are_collected_as_doctests():
    options = tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["pytest"]["ini_options"]
    assert "--doctest-modules" in options["addopts"]
    for root in DOCTEST_ROOTS:
        assert root.name in options["testpaths"]


def test_the_namespaces_are_all_covered():
    prefixes = {name.split(".")[0] for name in OBJECTS}
    assert prefixes == {"pt", "engines", "matlab_ports"}
    assert "pt.search" in OBJECTS
    assert "pt.SearchResult.scalings" in MEMBERS
    assert "engines.EngineModel.scaled" in MEMBERS
    assert "matlab_ports.figdata.read_fig_lines" in OBJECTS


@pytest.mark.parametrize("name", sorted(OBJECTS))
def test_public_docstring(name):
    obj = OBJECTS[name]
    is_class = inspect.isclass(obj)
    doc = _doc(obj, cls=is_class)
    check_summary_and_example(name, doc, obj)
    if not is_class:
        check_parameters(name, doc, obj)
    elif doc["Parameters"]:
        check_parameters(name, doc, obj)


@pytest.mark.parametrize("name", sorted(MEMBERS))
def test_public_method_docstring(name):
    func, is_callable = MEMBERS[name]
    doc = _doc(func)
    check_summary_and_example(name, doc, func)
    if is_callable:
        check_parameters(name, doc, func)
