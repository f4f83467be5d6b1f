"""The file formats and the engines by name: which module reads which file, which runs it, what is installed.

Two tables of data, one line per format and one per engine:

* :data:`FORMATS`: each file format (``"mjcf"``, ``"urdf"``): its module
  under ``pitheorem.engines.fileformats``, how its files are recognised (their
  suffixes and root element) and the engine its files run in by default;
* :data:`REGISTRY`: each engine (its one name everywhere:
  ``EngineModel.engine``, the catalogue, the command line): its runner
  module under ``pitheorem.engines.runners``, the loader of that module for
  each format it compiles, the Python modules it needs, the ``pip`` extra
  that installs them, and, for an engine built on another's compilation
  (MJX on MuJoCo's), that engine.

:func:`pitheorem.engines.loading.load` finds a file's format here
(:func:`file_format`), its engine (the format's default, or the one
asked for), imports that engine's runner module and calls its loader for
the format.  Adding a format is one line of :data:`FORMATS` and its
module; adding an engine is one line of :data:`REGISTRY` and its runner
module (``docs/explanation/architecture.md`` has both recipes).

The registry is data: it imports no format or runner module and no
engine's package (the runners reach it through
:mod:`pitheorem.engines.packages`, so a registry that imported them would
close a circle).

Examples
--------
>>> from pitheorem.engines.registry import FORMATS, REGISTRY
>>> [(f.name, f.engine) for f in FORMATS]
[('mjcf', 'mujoco'), ('urdf', 'pybullet')]
>>> [(e.name, e.formats) for e in REGISTRY]
[('pybullet', ('urdf',)), ('mujoco', ('mjcf', 'urdf')), ('mjx', ('mjcf', 'urdf')), ('warp', ('mjcf', 'urdf'))]
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType

from ..errors import InvalidRequestError

__all__ = [
    "ALIASES",
    "FORMATS",
    "REGISTRY",
    "Engine",
    "Format",
    "backends",
    "check_written_suffix",
    "file_format",
    "formats",
    "registered",
]


@dataclass(frozen=True, slots=True)
class Format:
    """One file format: its module, how its files are recognised, the engine they run in by default.

    Parameters
    ----------
    name : str
        The format's one name (``"mjcf"``).
    module : str
        Its module, under ``pitheorem.engines``.
    title : str
        How the text names it (``"MJCF"``).
    suffixes : tuple of str
        The file suffixes it reads, lower case.
    root : str
        The root element of its files, which tells it from another format
        of the same suffix (an ``.xml`` file may be MJCF or URDF).
    engine : str
        The engine its files load in when ``load`` names none.

    Examples
    --------
    >>> from pitheorem.engines.registry import FORMATS
    >>> FORMATS[1].title, FORMATS[1].suffixes
    ('URDF', ('.urdf', '.xml'))
    """

    name: str
    module: str
    title: str
    suffixes: tuple[str, ...]
    root: str
    engine: str


@dataclass(frozen=True, slots=True)
class Engine:
    """One engine: its runner module and a loader for each format it compiles, the packages it needs.

    Parameters
    ----------
    name : str
        The engine's one name.
    module : str
        Its runner module, under ``pitheorem.engines``.
    loaders : tuple of (str, str)
        Each format it compiles, and the function of the runner module that
        loads a file of that format: ``loader(path, **options)``.
    packages : tuple of str
        The Python modules it imports to run; the last is the engine's own
        (the module ``pitheorem.engines.packages.engine_module`` returns).
    extra : str
        The extra of ``pip install "pitheorem[extra]"`` that installs them.
    base : str
        The engine whose runner module this one builds on (``""``: none).
    precision : {"float64", "float32"}
        The precision it computes in by default (MJX's can be asked for
        float64; a model's runner says its own).

    Examples
    --------
    >>> from pitheorem.engines.registry import registered
    >>> registered("mjx").base, registered("mjx").extra, registered("mjx").loader("mjcf")
    ('mujoco', 'mjx', 'load_mjx')
    """

    name: str
    module: str
    loaders: tuple[tuple[str, str], ...]
    packages: tuple[str, ...]
    extra: str = "engines"
    base: str = ""
    precision: str = "float64"

    @property
    def formats(self) -> tuple[str, ...]:
        """The formats this engine compiles."""
        return tuple(fmt for fmt, _loader in self.loaders)

    def loader(self, fmt: str) -> str:
        """The name of the runner module's function that loads a file of format `fmt`."""
        return dict(self.loaders)[fmt]

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


#: every file format pitheorem reads, one line each
FORMATS: tuple[Format, ...] = (
    Format("mjcf", "fileformats.mjcf", "MJCF", (".xml", ".mjcf"), "mujoco", "mujoco"),
    Format("urdf", "fileformats.urdf", "URDF", (".urdf", ".xml"), "robot", "pybullet"),
)

#: every engine pitheorem runs, one line each
REGISTRY: tuple[Engine, ...] = (
    Engine("pybullet", "runners.pybullet", (("urdf", "load_urdf"),), ("pybullet",)),
    Engine("mujoco", "runners.mujoco", (("mjcf", "load_mjcf"), ("urdf", "load_urdf")), ("mujoco",)),
    Engine(
        "mjx",
        "runners.mjx",
        (("mjcf", "load_mjx"), ("urdf", "load_urdf")),
        ("mujoco", "jax", "mujoco.mjx"),
        extra="mjx",
        base="mujoco",
        precision="float32",
    ),
    Engine(
        "warp",
        "runners.warp",
        (("mjcf", "load_warp"), ("urdf", "load_urdf")),
        ("mujoco", "warp", "mujoco_warp"),
        extra="warp",
        base="mujoco",
        precision="float32",
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
    unknown engine 'ode'; use 'pybullet', 'mujoco', 'mjx' or 'warp'
    """
    name = ALIASES.get(name, name) if isinstance(name, str) else name
    if not isinstance(name, str) or name not in _BY_NAME:
        names = [repr(e.name) for e in REGISTRY]
        raise InvalidRequestError(f"unknown engine {name!r}; use {', '.join(names[:-1])} or {names[-1]}", culprit=name)
    return _BY_NAME[name]


def formats() -> tuple[str, ...]:
    """The file formats read here, in the registry's order.

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> from pitheorem import engines
    >>> engines.formats()
    ('mjcf', 'urdf')
    """
    return tuple(f.name for f in FORMATS)


def file_format(path) -> Format | None:
    """The format of a model file, by its suffix and, where formats share one, its root element.

    Only the first few kilobytes of a file are read (a root element is
    near the top of a large model); a file that does not exist is judged
    by its suffix alone.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    Format or None
        None when no format reads files of this suffix.

    Examples
    --------
    >>> from pitheorem.engines.registry import file_format
    >>> file_format("robot.urdf").name, file_format("hopper.xml").name, file_format("model.toml")
    ('urdf', 'mjcf', None)
    """
    path = Path(path)
    suffix = path.suffix.lower()
    candidates = [f for f in FORMATS if suffix in f.suffixes]
    if len(candidates) > 1 and path.is_file():
        with path.open("rb") as file:  # the root element is near the top: read no more of a large model
            head = file.read(4096).decode("utf-8", "replace")
        roots = [f for f in candidates if f"<{f.root}" in head]
        if len(roots) == 1:
            return roots[0]
    return candidates[0] if candidates else None


def check_written_suffix(path, name: str) -> None:
    """Refuse to write a file of format `name` under a suffix that format is not read by.

    Such a file would not load again, or would be read as another format (an MJCF
    model named ``.urdf`` is read as a URDF file, and refused).

    Raises
    ------
    InvalidRequestError

    Examples
    --------
    >>> from pitheorem.engines.registry import check_written_suffix
    >>> check_written_suffix("copy.XML", "mjcf")
    >>> try:
    ...     check_written_suffix("copy.urdf", "mjcf")
    ... except ValueError as err:
    ...     print(err)
    copy.urdf: the MJCF format names its files .xml or .mjcf, not .urdf; a file named so would not load again as this model
    """
    written = next(f for f in FORMATS if f.name == name)
    suffix = Path(path).suffix
    if suffix.lower() not in written.suffixes:
        raise InvalidRequestError(
            f"{path}: the {written.title} format names its files {' or '.join(written.suffixes)}, "
            f"not {suffix or 'without a suffix'}; a file named so would not load again as this model"
        )


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
