"""The engines' Python packages: which engine needs which, imported on demand and kept quiet.

Nothing in :mod:`pitheorem.engines` imports an engine at import time: every
module that runs one (the rod, MJCF and URDF models) asks
:func:`engine_module` for it when a simulation needs it, and gets an
:class:`~pitheorem.EngineUnavailableError` naming the package to install
when it is missing.  PyBullet prints a banner from C on import and on
connecting; :func:`quiet_stdout` silences such C-level output.
"""

from __future__ import annotations

import contextlib
import importlib
import os
import sys
from collections.abc import Iterator
from types import MappingProxyType

from ..errors import EngineUnavailableError
from .registry import ALIASES, REGISTRY, registered

__all__ = ["ALIASES", "PACKAGES", "check_engine", "engine_module", "quiet_stdout"]

#: the Python module of each engine (the last of its registry line's packages), imported by
#: :func:`engine_module`; an engine is named as :attr:`pitheorem.engines.EngineModel.engine` names it, everywhere
PACKAGES = MappingProxyType({e.name: e.packages[-1] for e in REGISTRY})


def check_engine(engine) -> str:
    """An engine's name, or an error that lists the engines.

    Parameters
    ----------
    engine : str
        A name of :data:`pitheorem.engines.registry.REGISTRY` (``"bullet"``
        is read as ``"pybullet"``).

    Returns
    -------
    str
        The engine's one name.

    Raises
    ------
    InvalidRequestError
        For any other name.

    Examples
    --------
    >>> from pitheorem.engines.packages import check_engine
    >>> check_engine("mujoco"), check_engine("bullet")
    ('mujoco', 'pybullet')
    >>> try:
    ...     check_engine("ode")
    ... except ValueError as err:
    ...     print(err)
    unknown engine 'ode'; use 'pybullet', 'mujoco', 'mjx' or 'warp'
    """
    return registered(engine).name


def engine_module(engine: str):
    """The engine's Python module, imported now.

    Parameters
    ----------
    engine : str
        As for :func:`check_engine`.

    Returns
    -------
    module
        ``pybullet`` for ``"pybullet"``, ``mujoco`` for ``"mujoco"``.

    Raises
    ------
    InvalidRequestError
        For an unknown engine.
    EngineUnavailableError
        When its package is not installed.

    Examples
    --------
    >>> from pitheorem.engines.packages import engine_module
    >>> engine_module("mujoco").__name__
    'mujoco'
    """
    line = registered(engine)
    package = PACKAGES[line.name]
    loaded = sys.modules.get(package)  # None also where an import is blocked: then import, and fail, below
    if loaded is not None:  # imported already: nothing to print, nothing to silence
        return loaded
    for needed in line.packages:
        try:
            with quiet_stdout():  # pybullet prints a banner on import, mujoco.mjx a note on a missing warp
                module = importlib.import_module(needed)
        except ImportError:
            raise EngineUnavailableError(line.name, needed, line.extra) from None
    return module


@contextlib.contextmanager
def quiet_stdout() -> Iterator[None]:
    """Silence what is written to the file descriptors of stdout and stderr while the block runs.

    That is what C libraries print (PyBullet's banner); where the
    descriptors cannot be duplicated, nothing is silenced.

    Examples
    --------
    >>> import os
    >>> from pitheorem.engines.packages import quiet_stdout
    >>> with quiet_stdout():
    ...     written = os.write(1, b"not shown")
    >>> written
    9
    """
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(AttributeError, OSError, ValueError):
            stream.flush()
    saved = []
    try:
        for fd in (1, 2):
            saved.append((fd, os.dup(fd)))
    except OSError:
        for _, copy in saved:
            os.close(copy)
        yield
        return
    try:
        # the descriptors for what C prints, and Python's streams for what Python prints where they are not
        # the descriptors (a notebook's, pytest's): mujoco.mjx prints its note on a missing warp from Python
        with open(os.devnull, "w") as devnull, contextlib.redirect_stdout(devnull), contextlib.redirect_stderr(devnull):
            for fd, _ in saved:
                os.dup2(devnull.fileno(), fd)
            yield
    finally:
        _flush_c_stdout()  # C's buffer may still hold the text when the stream is a pipe
        for fd, copy in saved:
            os.dup2(copy, fd)
            os.close(copy)


def _flush_c_stdout() -> None:
    try:
        import ctypes

        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError, TypeError):  # no C library to flush (e.g. some Windows builds)
        pass
