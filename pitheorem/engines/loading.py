"""Read a model file in an engine: the file's kind and the registry pick the backend module.

:func:`load` is ``pitheorem.engines.load``.  It finds the engine from the
file's kind (:func:`pitheorem.modelfile.model_kind`) unless ``engine=``
names another (an MJCF file runs in ``"mujoco"`` or ``"mjx"``), checks
that the engine is installed and takes the options given, imports the
engine's backend module (named by its line of
:data:`pitheorem.engines.registry.REGISTRY`) and calls its loader.  This
is the one module that imports the backends by name: nothing a backend
imports leads back here.
"""

from __future__ import annotations

import importlib
import inspect
from pathlib import Path

from ..errors import EngineModelError, EngineUnavailableError, InvalidRequestError
from ..modelfile import model_kind
from .registry import REGISTRY, Engine, backends, registered
from .units import declared_units

__all__ = ["load"]


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
        ``pitheorem.engines.urdf.load_urdf`` (``settings`` and the scene);
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
    if not path.is_file():
        raise EngineModelError(str(path), "", "no such file; give an MJCF (.xml) or URDF (.urdf) model file")
    kind = model_kind(path)
    readers = [e for e in REGISTRY if kind in e.kinds]
    if not readers:  # model_kind calls every other file a TOML model file
        raise EngineModelError(
            str(path), "", "no engine reads this kind of file; give an MJCF (.xml) or URDF (.urdf) model file"
        )
    chosen = next(e for e in readers if e.default) if engine is None else registered(engine)
    if chosen not in readers:
        names = " or ".join(repr(e.name) for e in readers)
        article = "an" if kind.upper()[0] in "AEFHILMNORSX" else "a"  # as the letters are spoken: an MJCF, a URDF
        raise InvalidRequestError(
            f"engine {chosen.name!r} does not read {kind.upper()} files; {article} {kind.upper()} file runs in {names}",
            culprit=chosen.name,
        )
    if not chosen.installed():
        missing = next(p for p in chosen.packages if not Engine("", "", "", (), (p,)).installed())
        raise EngineUnavailableError(chosen.name, missing, chosen.extra, backends())
    loader = _loader(chosen)
    taken = _options(chosen)
    wrong = sorted(set(options) - set(taken))
    if wrong:
        valid = ", ".join(sorted(taken)) or f"none, an {kind.upper()} file holds its settings"
        elsewhere = [e for e in REGISTRY if e is not chosen and wrong[0] in _options(e)]
        where = "".join(f"; {wrong[0]!r} is for {'/'.join(e.kinds).upper()} files in {e.name!r}" for e in elsewhere)
        raise InvalidRequestError(
            f"engine {chosen.name!r} takes no option {wrong[0]!r} (its options: {valid}){where}", culprit=wrong[0]
        )
    model = loader(path, **options)
    return model.in_units(declared_units(model, units))


def _loader(line: Engine):
    """The engine's loader, its backend module imported now (which imports no engine package yet)."""
    return getattr(importlib.import_module(f"{__package__}.{line.module}"), line.loader)


def _options(line: Engine) -> tuple[str, ...]:
    """The options the engine's loader takes (its keyword parameters)."""
    return tuple(name for name in inspect.signature(_loader(line)).parameters if name != "path")
