"""Every public name has a numpydoc docstring with a summary and a runnable example."""

from __future__ import annotations

import inspect

import pytest
from numpydoc.docscrape import ClassDoc, FunctionDoc

import pitheorem as pt

PUBLIC = [name for name in pt.__all__ if not name.startswith("_") and name != "DEFAULT_BASE_DIMENSIONS"]


def public_objects():
    for name in PUBLIC:
        obj = getattr(pt, name)
        if inspect.ismodule(obj):
            for sub in getattr(obj, "__all__", ()):
                yield f"{name}.{sub}", getattr(obj, sub)
        else:
            yield name, obj


OBJECTS = dict(public_objects())


@pytest.mark.parametrize("name", sorted(OBJECTS))
def test_public_docstring(name):
    obj = OBJECTS[name]
    doc = ClassDoc(obj) if inspect.isclass(obj) else FunctionDoc(obj)
    summary = " ".join(doc["Summary"])
    assert summary, f"{name} has no summary line"
    assert len(summary) < 80, f"{name}: summary too long ({len(summary)} chars)"
    assert any(">>>" in line for line in doc["Examples"]), f"{name} has no runnable example"
    if inspect.isfunction(obj):
        documented = {p.name.split(":")[0].strip() for p in doc["Parameters"]}
        for param in inspect.signature(obj).parameters:
            if param not in ("self", "cls"):
                assert any(param in d for d in documented), f"{name}: parameter {param!r} undocumented"


@pytest.mark.parametrize("name", sorted(n for n, o in OBJECTS.items() if inspect.isclass(o)))
def test_public_methods_have_examples(name):
    cls = OBJECTS[name]
    for attr, member in vars(cls).items():
        if attr.startswith("_") or not (inspect.isfunction(member) or isinstance(member, classmethod | property)):
            continue
        func = member.__func__ if isinstance(member, classmethod) else member.fget if isinstance(member, property) else member
        text = inspect.getdoc(func) or ""
        assert text, f"{name}.{attr} has no docstring"
