"""The command line on engine model files: ``params``, and ``groups``/``bases``/``search``/``apply`` on MJCF and URDF.

:mod:`pitheorem.cli` dispatches here by file kind (:func:`pitheorem.modelfile.model_kind`):
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
from .model import EngineModel, UnscalableParameterError, load
from .urdf import SCENE_OPTIONS, scene_option

__all__ = ["apply_engine", "engine_model_file", "parse_scene", "print_params"]


_TRUTH = {"true": True, "yes": True, "1": True, "false": False, "no": False, "0": False}


def parse_scene(items: list[str] | None) -> dict:
    """The ``--scene NAME=VALUE`` items of the command line as options of :func:`pitheorem.engines.load`.

    Parameters
    ----------
    items : list of str or None
        Names of ``pitheorem.engines.urdf.SCENE_OPTIONS``: ``fixed_base``,
        ``ground`` and ``split_impulse`` take true/false; ``g`` and
        ``damping`` a number; ``base_position`` three numbers separated by
        commas.

    Returns
    -------
    dict

    Raises
    ------
    InvalidRequestError
        For an unknown name, a repeated name or a value of the wrong kind.

    Examples
    --------
    >>> from pitheorem.engines.cli import parse_scene
    >>> parse_scene(["ground=true", "damping=0", "base_position=0,0,1"])
    {'ground': True, 'damping': 0.0, 'base_position': (0.0, 0.0, 1.0)}
    """
    options = {}
    for item in items or ():
        name, sep, text = item.partition("=")
        name, text = name.strip(), text.strip()
        if not sep or name not in SCENE_OPTIONS:
            raise InvalidRequestError(f"--scene {item!r}: write NAME=VALUE with NAME one of {', '.join(SCENE_OPTIONS)}")
        if name in options:
            raise InvalidRequestError(f"--scene sets {name!r} twice")
        kind = SCENE_OPTIONS[name][0]
        if kind == "flag":
            if text.lower() not in _TRUTH:
                raise InvalidRequestError(f"--scene {item!r}: {name} is true or false")
            value = _TRUTH[text.lower()]
        else:
            parts = [part.strip() for part in text.split(",")]
            if len(parts) != (3 if kind == "point" else 1):
                raise InvalidRequestError(f"--scene {item!r}: {name} takes "
                                          + ("three numbers such as 0,0,1" if kind == "point" else "one number"))
            value = parts if kind == "point" else parts[0]
        try:
            options[name] = scene_option(name, value)
        except InvalidRequestError as err:
            raise InvalidRequestError(f"--scene {item!r}: {err}", culprit=err.culprit) from None
    return options


def engine_model_file(path: str, **options) -> tuple[ModelFile, EngineModel]:
    """The engine model and a :class:`~pitheorem.modelfile.ModelFile` of its system and scalar values.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import engine_model_file
    >>> mf, model = engine_model_file(str(engines.example_path("pendulum.xml")))
    >>> mf.roles["t"], mf.values["g"]
    ('time', 9.81)
    """
    model = load(path, **options)
    system = model.system()
    values = {p.name: p.value[0] for p in model.parameters if not p.mixed and len(p.value) == 1}
    roles = {n: "time" if n == "t" else "parameter" for n in system.variables}
    name = Path(path).name
    return ModelFile(name=name, description=f"{model.engine} model {name}", system=system, values=values,
                     roles=roles, path=str(path)), model


def print_params(path: str, fmt: str, **options) -> int:
    """Print the parameter table of an engine model file (``pitheorem params FILE``).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import print_params
    >>> code = print_params(str(engines.example_path("pendulum.xml")), "json")  # doctest: +ELLIPSIS
    {...
    """
    model = load(path, **options)
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


def apply_engine(path: str, scaling, s, output: str | None, **options) -> list[str]:
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
    model = load(path, **options)
    try:
        scaled = model.scaled(scaling, s)
    except UnscalableParameterError as err:
        if model.engine == "pybullet" and err.name.endswith("Damping") and "damping" not in options:
            raise InvalidRequestError(f"{err}; on the command line: --scene damping=0") from None
        raise
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
