"""The engines by name: which module reads which files, and which engines are installed.

Each engine is one line of :data:`REGISTRY`: its name (the one name it
has everywhere: ``EngineModel.engine``, the catalogue, the command line),
its backend module under ``pitheorem.engines`` and that module's loader,
the file kinds it reads (as :func:`pitheorem.modelfile.model_kind` names
them), the Python modules it needs, the ``pip`` extra that installs them,
and, for an engine built on another's reading of a file, that engine.
:func:`pitheorem.engines.loading.load` finds the engine of a file here,
imports its backend module and calls its loader.

The registry is data: it imports no backend module and no engine's
package (the backends reach it through :mod:`pitheorem.engines.packages`,
so a registry that imported them would close a circle).

Examples
--------
>>> from pitheorem.engines.registry import REGISTRY
>>> [(e.name, e.kinds) for e in REGISTRY]
[('pybullet', ('urdf',)), ('mujoco', ('mjcf',)), ('mjx', ('mjcf',))]
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass
from types import MappingProxyType

from ..errors import InvalidRequestError

__all__ = ["ALIASES", "REGISTRY", "Engine", "backends", "registered"]


@dataclass(frozen=True, slots=True)
class Engine:
    """One engine: its backend module and loader, the files it reads, the packages it needs.

    Parameters
    ----------
    name : str
        The engine's one name.
    module : str
        Its backend module, under ``pitheorem.engines``.
    loader : str
        The function of that module that reads a file: ``loader(path, **options)``.
    kinds : tuple of str
        The file kinds it reads (``"mjcf"``, ``"urdf"``).
    packages : tuple of str
        The Python modules it imports to run; the last is the engine's own
        (the module ``pitheorem.engines.packages.engine_module`` returns).
    extra : str
        The extra of ``pip install "pitheorem[extra]"`` that installs them.
    default : bool
        Whether a file of its kinds loads in it when ``load`` names no engine.
    base : str
        The engine whose backend module this one builds on (``""``: none).

    Examples
    --------
    >>> from pitheorem.engines.registry import registered
    >>> registered("mjx").base, registered("mjx").extra
    ('mujoco', 'mjx')
    """

    name: str
    module: str
    loader: str
    kinds: tuple[str, ...]
    packages: tuple[str, ...]
    extra: str = "engines"
    default: bool = True
    base: str = ""

    def installed(self) -> bool:
        """Whether every Python module the engine needs can be imported here (none is imported).

        Examples
        --------
        >>> from pitheorem.engines.registry import registered
        >>> registered("mujoco").installed()
        True
        """
        for package in self.packages:
            try:
                if importlib.util.find_spec(package) is None:
                    return False
            except (ImportError, ValueError):  # a dotted name whose parent is missing or broken
                return False
        return True


#: every engine pitheorem knows, one line each
REGISTRY: tuple[Engine, ...] = (
    Engine("pybullet", "urdf", "load_urdf", ("urdf",), ("pybullet",)),
    Engine("mujoco", "mjcf", "load_mjcf", ("mjcf",), ("mujoco",)),
    Engine(
        "mjx", "mjx", "load_mjx", ("mjcf",), ("mujoco", "jax", "mujoco.mjx"), extra="mjx", default=False, base="mujoco"
    ),
)

_BY_NAME = {e.name: e for e in REGISTRY}
#: older spellings still read ("bullet" was PyBullet's name before each engine had one); never answered back
ALIASES = MappingProxyType({"bullet": "pybullet"})


def registered(name) -> Engine:
    """The registry line of an engine, by name.

    Parameters
    ----------
    name : str
        An engine's name (``"bullet"`` is read as ``"pybullet"``).

    Returns
    -------
    Engine

    Raises
    ------
    InvalidRequestError
        For a name that is no engine; the message lists the engines.

    Examples
    --------
    >>> from pitheorem.engines.registry import registered
    >>> registered("bullet").name
    'pybullet'
    >>> try:
    ...     registered("ode")
    ... except ValueError as err:
    ...     print(err)
    unknown engine 'ode'; use 'pybullet', 'mujoco' or 'mjx'
    """
    name = ALIASES.get(name, name) if isinstance(name, str) else name
    if not isinstance(name, str) or name not in _BY_NAME:
        names = [repr(e.name) for e in REGISTRY]
        raise InvalidRequestError(f"unknown engine {name!r}; use {', '.join(names[:-1])} or {names[-1]}", culprit=name)
    return _BY_NAME[name]


def backends() -> tuple[str, ...]:
    """The engines installed here, sorted by name.

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> from pitheorem import engines
    >>> {"mujoco", "pybullet"} <= set(engines.backends())
    True
    """
    return tuple(sorted(e.name for e in REGISTRY if e.installed()))
