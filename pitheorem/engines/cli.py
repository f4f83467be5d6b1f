"""The command line on engine model files: ``params``, and ``groups``/``bases``/``search``/``apply`` on MJCF and URDF.

:mod:`pitheorem.cli` dispatches here by file kind (:func:`is_engine_file`):
an engine model becomes a :class:`~pitheorem.modelfile.ModelFile` of its
system and its one-number values (:func:`engine_model_file`), so the TOML
commands work on it unchanged, and ``apply`` writes the scaled file the
engine loads (:func:`apply_engine`).
"""

from __future__ import annotations

import json
from pathlib import Path

from ..display import power_text
from ..errors import InvalidRequestError
from ..modelfile import ModelFile
from .model import EngineModel, load, model_kind

__all__ = ["apply_engine", "engine_model_file", "is_engine_file", "print_params"]


def is_engine_file(path: str) -> bool:
    """Whether a command-line FILE is an MJCF or URDF model (by suffix and root element).

    Examples
    --------
    >>> from pitheorem.engines.cli import is_engine_file
    >>> is_engine_file("robot.urdf"), is_engine_file("rod.toml"), is_engine_file("example:hinged_rod")
    (True, False, False)
    """
    return not str(path).startswith("example:") and model_kind(path) in ("mjcf", "urdf")


def engine_model_file(path: str) -> tuple[ModelFile, EngineModel]:
    """The engine model and a :class:`~pitheorem.modelfile.ModelFile` of its system and scalar values.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import engine_model_file
    >>> mf, model = engine_model_file(str(engines.example_path("pendulum.xml")))
    >>> mf.roles["t"], mf.values["g"]
    ('time', 9.81)
    """
    model = load(path)
    system = model.system()
    values = {p.name: p.value[0] for p in model.parameters if not p.mixed and len(p.value) == 1}
    roles = {n: "time" if n == "t" else "parameter" for n in system.variables}
    name = Path(path).name
    return ModelFile(name=name, description=f"{model.engine} model {name}", system=system, values=values,
                     roles=roles, path=str(path)), model


def print_params(path: str, fmt: str) -> int:
    """Print the parameter table of an engine model file (``pitheorem params FILE``).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import print_params
    >>> code = print_params(str(engines.example_path("pendulum.xml")), "json")  # doctest: +ELLIPSIS
    {...
    """
    model = load(path)
    if fmt == "json":
        doc = {"model": str(path), "engine": model.engine, "parameters": [
            {"name": p.name, "path": p.path, "value": list(p.value), "dimension": p.dimension_text,
             "source": p.source, "settable": p.settable, "note": p.note} for p in model.parameters]}
        print(json.dumps(doc, indent=2))
        return 0
    if fmt == "latex":
        raise InvalidRequestError("params prints text or json")
    print(f"{path}: {model.engine} model, {len(model.parameters)} parameters")
    print(model.table())
    return 0


def apply_engine(path: str, scaling, s, output: str | None) -> list[str]:
    """Scale an engine model file and write it (``pitheorem apply FILE ... --output OUT``); lines to print.

    Examples
    --------
    >>> import os, tempfile
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import apply_engine, engine_model_file
    >>> path = str(engines.example_path("pendulum.xml"))
    >>> mf, _ = engine_model_file(path)
    >>> sc = pt.search(mf.system, scale={"g": 1}).scalings[0]
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     lines = apply_engine(path, sc, 10, os.path.join(tmp, "p10.xml"))
    >>> lines[-1].startswith("wrote")
    True
    """
    model = load(path)
    scaled = model.scaled(scaling, s)
    lines = [f"{Path(path).name}, s = {s}: {scaling}"]
    changed = [p for p in model.parameters if not p.mixed and scaling.exponent_of(p.dimension) != 0
               and any(v != 0 for v in p.value)]
    lines.append(f"{len(changed)} of {len(model.parameters)} parameters change, e.g.")
    for p in changed[:8]:
        lines.append(f"  {p.name}: x {power_text(scaling.exponent_of(p.dimension))}")
    if output:
        out = Path(output)
        if out.exists() and out.resolve() == Path(path).resolve():
            raise InvalidRequestError(f"--output {output!r} is the input file; choose another name")
        scaled.save(out)
        lines.append(f"wrote {out}" + (f" (and {out}.settings.json, {out}.settings.py)"
                                       if model.engine == "pybullet" else ""))
    return lines
