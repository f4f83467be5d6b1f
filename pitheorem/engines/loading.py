"""Read a model file in an engine: the file's format and the registry pick the runner module.

:func:`load` is ``pitheorem.engines.load``.  It finds the file's format
(:func:`pitheorem.engines.registry.file_format`) and runs it in that
format's default engine unless ``engine=`` names another (an MJCF file
runs in ``"mujoco"`` or ``"mjx"``), checks that the engine is installed,
compiles that format and takes the options given, imports the engine's
runner module (named by its line of
:data:`pitheorem.engines.registry.REGISTRY`) and calls its loader for the
format.  This is the one module that imports the runners by name: nothing
a runner imports leads back here.
"""

from __future__ import annotations

import importlib
import inspect
from pathlib import Path

from ..errors import EngineModelError, EngineUnavailableError, InvalidRequestError
from .registry import FORMATS, REGISTRY, Engine, backends, file_format, registered
from .units import declared_units

__all__ = ["load", "runner_module", "scene_options"]


def load(path, engine=None, units=None, **options):
    """Read an MJCF or URDF model file in an engine.

    Parameters
    ----------
    path : str or Path
        ``.xml``/``.mjcf`` (MJCF), ``.urdf`` (URDF); an ``.xml`` file
        whose root is ``<robot>`` is read as URDF.
    engine : str, optional
        The engine to run it in: by default the file's own (MJCF in
        ``"mujoco"``, URDF in ``"pybullet"``); an MJCF file also runs in
        ``"mjx"``.
    units : mapping of str to str, optional
        The units the file is written in, for some of ``M``, ``L`` and
        ``T`` (``{"L": "cm", "M": "g"}``); the others are SI.  Default: SI,
        or the units a file written by pitheorem records.
    **options
        The engine loader's options: for PyBullet those of
        ``pitheorem.engines.runners.pybullet.load_urdf`` (``settings`` and the scene);
        for MJX ``precision`` (``"float32"``, the default, or
        ``"float64"``); MuJoCo takes none (the file holds its settings).

    Returns
    -------
    EngineModel
        Of the engine asked for.

    Raises
    ------
    EngineModelError
        For a missing or unreadable file, an element the engine rejects
        or does not support, or one the package cannot scale faithfully
        (named in the message).
    InvalidRequestError
        For an unknown engine, one that does not read this kind of file,
        or options the engine does not take.
    EngineUnavailableError
        For an engine whose Python package is not installed; the message
        names the extra to install and the engines installed here.

    Examples
    --------
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> model.engine, [p.name for p in model.parameters][:2]
    ('mujoco', ['timestep', 'g'])
    >>> import pitheorem as pt
    >>> try:
    ...     engines.load(engines.example_path("pendulum.xml"), engine="pybullet")
    ... except pt.InvalidRequestError as err:
    ...     print(err)
    engine 'pybullet' does not read MJCF files; an MJCF file runs in 'mujoco' or 'mjx'
    """
    path = Path(path)
    names = ", ".join(f"{f.title} ({' '.join(f.suffixes)})" for f in FORMATS)
    if not path.is_file():
        raise EngineModelError(str(path), "", f"no such file; give a model file of a format read here: {names}")
    fmt = file_format(path)
    if fmt is None:
        raise EngineModelError(str(path), "", f"no format read here has this suffix; the formats: {names}")
    readers = [e for e in REGISTRY if fmt.name in e.formats]
    chosen = registered(fmt.engine if engine is None else engine)
    if chosen not in readers:
        runs_in = " or ".join(repr(e.name) for e in readers)
        article = "an" if fmt.title[0] in "AEFHILMNORSX" else "a"  # as the letters are spoken: an MJCF, a URDF
        raise InvalidRequestError(
            f"engine {chosen.name!r} does not read {fmt.title} files; {article} {fmt.title} file runs in {runs_in}",
            culprit=chosen.name,
        )
    if not chosen.installed():
        missing = next(p for p in chosen.packages if not Engine("", "", (), (p,)).installed())
        raise EngineUnavailableError(chosen.name, missing, chosen.extra, backends())
    loader = _loader(chosen, fmt.name)
    taken = _options(chosen, fmt.name)
    wrong = sorted(set(options) - set(taken))
    if wrong:
        valid = ", ".join(sorted(taken)) or f"none, {fmt.title} files in {chosen.name!r} take no options"
        elsewhere = [
            (e, f) for e in REGISTRY for f in e.formats if (e, f) != (chosen, fmt.name) and wrong[0] in _options(e, f)
        ]
        where = "".join(f"; {wrong[0]!r} is for {f.upper()} files in {e.name!r}" for e, f in elsewhere)
        raise InvalidRequestError(
            f"engine {chosen.name!r} takes no option {wrong[0]!r} (its options: {valid}){where}", culprit=wrong[0]
        )
    model = loader(path, **options)
    return model.in_units(declared_units(model, units))


def _loader(line: Engine, fmt: str):
    """The engine's loader of a format, its runner module imported now (which imports no engine package yet)."""
    return getattr(importlib.import_module(f"{__package__}.{line.module}"), line.loader(fmt))


def _options(line: Engine, fmt: str) -> tuple[str, ...]:
    """The options the engine's loader of a format takes (its keyword parameters)."""
    return tuple(name for name in inspect.signature(_loader(line, fmt)).parameters if name != "path")


def runner_module(engine: str):
    """The runner module of an engine, imported now (which imports no engine package yet).

    For an optional hook of a runner module (``threshold_numbers``: the
    numbers an engine's own thresholds are held against), asked for by
    :mod:`pitheorem.engines.thresholds` without naming any engine.

    Examples
    --------
    >>> from pitheorem.engines.loading import runner_module
    >>> runner_module("mjx").__name__
    'pitheorem.engines.runners.mjx'
    """
    return importlib.import_module(f"{__package__}.{registered(engine).module}")


def scene_options() -> dict[str, tuple[str, str, object, object]]:
    """Every runner's scene options (settings outside the file, given to ``load``), by name.

    A runner module that takes such options says so with ``SCENE_OPTIONS``
    (name -> (kind, default)) and ``scene_option(name, value)``, its reader
    of one; the command line's ``--scene`` offers them all, each with its
    engine, without naming any.

    Returns
    -------
    dict
        name -> (engine, kind, default, reader).

    Examples
    --------
    >>> from pitheorem.engines.loading import scene_options
    >>> engine, kind, default, read = scene_options()["ground"]
    >>> engine, kind, default, read("ground", True)
    ('pybullet', 'flag', False, True)
    """
    out = {}
    for line in REGISTRY:
        module = runner_module(line.name)
        for name, (kind, default) in getattr(module, "SCENE_OPTIONS", {}).items():
            out.setdefault(name, (line.name, kind, default, module.scene_option))
    return out
