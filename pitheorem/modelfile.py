"""Model files: a system, its roles and its parameter values in plain TOML.

This module owns the model-file format read by the ``pitheorem`` command
line (:mod:`pitheorem.cli`): :func:`load_model_file` reads one into a
:class:`ModelFile`, :func:`dump_values` and :func:`write_model_file` write a
copy with other (e.g. scaled) values, and :func:`example_path` finds the
model files shipped in ``pitheorem/examples/`` (the engine models among
them too: ``pitheorem.engines.example_path`` is the same function).

The format
----------
A model file is a TOML document::

    name = "hinged rod"                 # optional; default: the file name
    description = "rod on a hinge"      # optional
    base_dimensions = ["M", "L", "T"]   # optional; default M L T Theta I (N, J, A must be listed)

    [variables]
    m = { dimension = "M", value = 1.5, role = "parameter" }
    l = { unit = "m", value = 2 }
    g = { dimension = "L T^-2", value = 9.81 }
    t = { dimension = "T", role = "time" }
    theta = { dimension = "1", role = "state", description = "angle" }

Each entry of ``[variables]`` is one variable, in the order of the file, with
these keys:

``dimension``
    A formula over the base dimensions, as :class:`~pitheorem.Dimension`
    reads it: ``"M L^2 T^-2"``, ``"L/T^2"``, ``"1"`` for dimensionless.
``unit``
    Instead of ``dimension``: a unit string read by pint, as in
    :meth:`System.from_units <pitheorem.System.from_units>` (``"N*m/rad"``).
    Give exactly one of ``dimension`` and ``unit``.
``value``
    Optional.  An integer, a float, or a string holding an exact rational
    such as ``"1/3"``.  In Python a float stays a float and every other
    value is an exact :class:`~fractions.Fraction`
    (:func:`pitheorem.exact.read_value`).  A value is in whatever unit the
    file uses: scaling multiplies it by a power of ``s``, which no choice of
    unit changes.
``role``
    Optional: ``"parameter"`` (the default), ``"time"`` (at most one
    variable, of dimension ``T``) or ``"state"``.
``description``
    Optional free text.

Every problem raises :class:`ModelFileError`, whose one-line message names
the file, the variable and what is wrong.
"""

from __future__ import annotations

import dataclasses
import difflib
import json
import os
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path

from .dimensions import DEFAULT_BASE_DIMENSIONS, OPT_IN_BASE_DIMENSIONS, Dimension
from .errors import DimensionSyntaxError, LimitError, ModelFileError, PiTheoremError
from .exact import read_value
from .formatting.pieces import json_number
from .immutable import immutable
from .system import System

__all__ = [
    "EXAMPLES",
    "ROLES",
    "ModelFile",
    "ModelFileError",
    "dump_values",
    "example_path",
    "examples",
    "load_model_file",
    "model_kind",
    "write_model_file",
]

#: the roles a variable can have; the first is the default
ROLES = ("parameter", "time", "state")

_TOP_KEYS = ("name", "description", "base_dimensions", "variables")
_VARIABLE_KEYS = ("dimension", "unit", "value", "role", "description")
#: the folder of the model files shipped with pitheorem: TOML model files and engine models
EXAMPLES = Path(__file__).resolve().parent / "examples"
_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


@immutable
@dataclass(frozen=True)
class ModelFile:
    """The contents of a model file: a system, roles and values.

    Parameters
    ----------
    name : str
    description : str
    system : System
        Variables and dimensions, in the order of the file.
    values : dict of str to Fraction or float
        Values given in the file: floats as floats, every other number as
        an exact Fraction; variables without a value are absent.
    roles : dict of str to str
        ``"parameter"``, ``"time"`` or ``"state"`` for every variable.
    units : dict of str to str
        The unit string of each variable declared with ``unit``.
    descriptions : dict of str to str
        The description of each variable that has one.
    path : str
        Where the file was read from (empty when built in code).

    Examples
    --------
    >>> from pitheorem.modelfile import example_path, load_model_file
    >>> rod = load_model_file(example_path("hinged_rod"))
    >>> rod.name, rod.system.rank, rod.values["m"], rod.roles["t"]
    ('hinged rod', 3, 1.5, 'time')
    """

    name: str
    description: str
    system: System
    values: dict = field(default_factory=dict)
    roles: dict = field(default_factory=dict)
    units: dict = field(default_factory=dict, repr=False)
    descriptions: dict = field(default_factory=dict, repr=False)
    path: str = field(default="", repr=False)

    __hash__ = None  # dict fields: a model file is a record, not a key

    @property
    def time(self) -> str | None:
        """The variable with role ``"time"``, or None.

        Examples
        --------
        >>> from pitheorem.modelfile import example_path, load_model_file
        >>> load_model_file(example_path("hinged_rod")).time
        't'
        """
        return next((n for n, r in self.roles.items() if r == "time"), None)

    def with_values(self, values: Mapping[str, object], *, name: str | None = None) -> ModelFile:
        """A copy with other values (e.g. scaled ones), checked like a file's.

        Parameters
        ----------
        values : mapping of str to number
            New values, read like a file's: floats (and irrational sympy
            numbers) become floats, every other number a Fraction.
        name : str, optional
            New name (default: unchanged).

        Returns
        -------
        ModelFile

        Examples
        --------
        >>> from pitheorem.modelfile import example_path, load_model_file
        >>> rod = load_model_file(example_path("hinged_rod"))
        >>> rod.with_values({"m": 3, "l": 2.5}).values
        {'m': Fraction(3, 1), 'l': 2.5}
        """
        clean = {}
        for n, v in values.items():
            if n not in self.system.variables:
                raise ModelFileError(self.path or "<model>", "no such variable in the model", variable=n)
            clean[n] = _value(v, self.path or "<model>", n)
        ordered = {n: clean[n] for n in self.system.variables if n in clean}
        return dataclasses.replace(self, values=ordered, name=self.name if name is None else name)


# -- reading ---------------------------------------------------------------------------------


def example_path(name: str) -> Path:
    """Path of a model file shipped with pitheorem.

    Parameters
    ----------
    name : str
        A TOML model file by its name, ``"hinged_rod"`` or ``"superball"``
        (the ``.toml`` suffix is optional), or an engine model by its file
        name, ``"pendulum.xml"`` or ``"superball.xml"``: one of
        ``pitheorem.modelfile.examples()``.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ModelFileError
        For a name that is no shipped file; the message lists the ones
        that are.

    Examples
    --------
    >>> from pitheorem.modelfile import example_path
    >>> example_path("superball").name, example_path("superball.xml").name
    ('superball.toml', 'superball.xml')

    The engine models that the how-to "Why is my scaled model not similar?"
    runs, each showing one cause, are shipped too, in the folder ``causes``:

    >>> example_path("causes/hand.xml").parent.name
    'causes'
    """
    text = str(name)
    stem = text.removesuffix(".toml")
    if stem in (shipped := examples()) and (stem == text or not Path(stem).suffix):
        return EXAMPLES / (stem if Path(stem).suffix else f"{stem}.toml")
    if text in (extra := _cause_examples()):
        return EXAMPLES / text
    raise ModelFileError(
        f"example:{text}",
        f"no such example; the shipped examples are {', '.join(shipped)}; the how-to's models are {', '.join(extra)}",
    )


def _cause_examples() -> tuple[str, ...]:
    """The engine models of the folder ``causes`` (the how-to on causes), as ``causes/NAME``, sorted."""
    return tuple(sorted(f"causes/{p.name}" for p in (EXAMPLES / "causes").iterdir() if p.suffix in (".xml", ".urdf")))


def examples() -> tuple[str, ...]:
    """Names of the shipped model files, sorted, as :func:`example_path` takes them.

    TOML model files by their name without ``.toml`` (as the command line
    reads them, ``example:hinged_rod``), engine models by their file name.

    Examples
    --------
    >>> from pitheorem.modelfile import examples
    >>> examples()
    ('hinged_rod', 'hinged_rod.urdf', 'hinged_rod.xml', 'pendulum.xml', 'superball', 'superball.xml')
    """
    return tuple(
        sorted(
            p.stem if p.suffix == ".toml" else p.name
            for p in EXAMPLES.iterdir()
            if p.is_file() and p.suffix in (".toml", ".xml", ".urdf")
        )
    )


def model_kind(path) -> str:
    """``"mjcf"``, ``"urdf"`` or ``"toml"``: the kind of a model file, by suffix and root element.

    The command line reads a TOML (or JSON) model file itself and an MJCF
    or URDF file through :mod:`pitheorem.engines`; a shipped example
    (``example:NAME``) is a TOML model file.

    Parameters
    ----------
    path : str or os.PathLike
        The file as the user named it.

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.modelfile import model_kind
    >>> model_kind("robot.urdf"), model_kind("model.toml"), model_kind("example:hinged_rod")
    ('urdf', 'toml', 'toml')
    >>> model_kind("example:robot.urdf")
    'toml'
    """
    if str(path).startswith("example:"):  # whatever the name ends with: the command line lists the examples
        return "toml"
    if Path(path).suffix.lower() == ".toml":
        return "toml"
    # the formats of engine model files are the engines' registry's data (it imports no engine)
    from .engines.registry import file_format

    found = file_format(path)
    return "toml" if found is None else found.name


def load_model_file(path) -> ModelFile:
    """Read and check a TOML model file.

    The format is described in the docstring of the module
    ``pitheorem.modelfile`` and in the how-to guide on the command line.

    Parameters
    ----------
    path : str or os.PathLike
        The file.  ``example:NAME`` reads a shipped example, e.g.
        ``example:hinged_rod`` (see ``pitheorem.modelfile.example_path``).

    Returns
    -------
    ModelFile

    Raises
    ------
    ModelFileError
        For anything wrong inside the file; the message names the file, the
        variable and the problem.
    OSError
        When the file cannot be read at all (e.g. it does not exist).

    Examples
    --------
    >>> from pitheorem.modelfile import load_model_file
    >>> sb = load_model_file("example:superball")
    >>> sb.system.variables[:4], sb.system.n_groups
    (('g', 'rho', 'x_r', 'k'), 9)
    >>> load_model_file("example:hinged_rod").values["theta_r"]
    1.0471975511965976
    """
    if not isinstance(path, str | os.PathLike):
        raise ModelFileError(
            repr(path), f"a model file is named by a path (str or pathlib.Path), not a {type(path).__name__}"
        )
    text_path = str(path)
    if text_path.startswith("example:"):
        path = example_path(text_path.removeprefix("example:"))
        if path.suffix != ".toml":
            raise ModelFileError(text_path, f"is an engine model, not a TOML model file; pass its path, {path}")
    raw = Path(path).read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise ModelFileError(text_path, f"not UTF-8 text (byte {err.start}); a model file is TOML text") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise _toml_error(text_path, text, err) from None
    model = _read(text_path, data, default_name=Path(path).stem)
    return dataclasses.replace(model, path=str(path))


def _toml_error(path: str, text: str, err: tomllib.TOMLDecodeError) -> ModelFileError:
    message = str(err)
    found = re.search(r"\s*\(at line (\d+), column (\d+)\)", message)
    line = int(found.group(1)) if found else None
    reason = message[: found.start()] if found else message
    reason = reason[0].lower() + reason[1:] if reason else "malformed document"
    if line is not None and ("overwrite" in reason or "twice" in reason):
        lines = text.splitlines()
        source = lines[line - 1] if 0 < line <= len(lines) else ""
        header = re.match(r"^\s*\[+\s*([^\]]+?)\s*\]+", source)
        key = re.match(r"""^\s*["']?([^"'=\s]+)["']?\s*=""", source)
        section = _section_at(lines, line)
        if header:
            name = header.group(1).strip()
            variable = name.split(".", 1)[1] if name.startswith("variables.") else None
            what = f"table [{name}] is declared twice" if variable is None else "is declared twice"
            return ModelFileError(path, f"{what}; TOML allows each table once", variable=variable, line=line)
        if key and section == "variables":
            return ModelFileError(
                path,
                "is defined twice in [variables]; each variable may appear once",
                variable=key.group(1),
                line=line,
            )
        if key:
            return ModelFileError(path, f"key {key.group(1)!r} is defined twice; TOML allows each key once", line=line)
    return ModelFileError(path, f"invalid TOML: {reason}", line=line)


def _section_at(lines: list[str], line: int) -> str:
    for source in reversed(lines[: line - 1]):
        header = re.match(r"^\s*\[+\s*([^\]]+?)\s*\]+", source)
        if header:
            return header.group(1).strip()
    return ""


def _suggest(word: str, options) -> str:
    close = difflib.get_close_matches(word, list(options), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _read(path: str, data: dict, *, default_name: str) -> ModelFile:
    for key in data:
        if key not in _TOP_KEYS:
            raise ModelFileError(
                path, f"unknown top-level key {key!r}{_suggest(key, _TOP_KEYS)}; allowed: {', '.join(_TOP_KEYS)}"
            )
    name = data.get("name", default_name)
    description = data.get("description", "")
    for key, value in (("name", name), ("description", description)):
        if not isinstance(value, str):
            raise ModelFileError(path, f"{key} must be a string, got {value!r}")
    allowed = data.get("base_dimensions", DEFAULT_BASE_DIMENSIONS)
    if not isinstance(allowed, list | tuple) or not all(isinstance(b, str) and b.isidentifier() for b in allowed):
        raise ModelFileError(path, f'base_dimensions must be a list of names such as ["M", "L", "T"], got {allowed!r}')
    allowed = tuple(allowed)
    if "variables" not in data:
        raise ModelFileError(path, 'no [variables] table; declare each variable there, e.g. m = { dimension = "M" }')
    variables = data["variables"]
    if not isinstance(variables, dict):
        raise ModelFileError(path, f"variables must be a table, got {variables!r}")
    if not variables:
        raise ModelFileError(path, "the [variables] table is empty; a model needs at least one variable")
    dims, values, roles, units, descriptions = {}, {}, {}, {}, {}
    for var, entry in variables.items():
        if not var.isidentifier():
            raise ModelFileError(path, "is not a valid name; use letters, digits and _ (e.g. k_theta)", variable=var)
        if not isinstance(entry, dict):
            raise ModelFileError(path, f'must be a table such as {{ dimension = "M" }}, got {entry!r}', variable=var)
        for key in entry:
            if key not in _VARIABLE_KEYS:
                raise ModelFileError(
                    path,
                    f"unknown key {key!r}{_suggest(key, _VARIABLE_KEYS)}; allowed: {', '.join(_VARIABLE_KEYS)}",
                    variable=var,
                )
        has_dim, has_unit = "dimension" in entry, "unit" in entry
        if has_dim == has_unit:
            both = "both dimension and unit" if has_dim else "neither dimension nor unit"
            raise ModelFileError(path, f"has {both}; give exactly one of them", variable=var)
        if has_dim:
            dims[var] = _read_dimension(path, var, entry["dimension"], allowed)
        else:
            unit = entry["unit"]
            dims[var] = _read_unit(path, var, unit)
            units[var] = unit
        role = entry.get("role", ROLES[0])
        if role not in ROLES:
            raise ModelFileError(
                path,
                f"unknown role {role!r}{_suggest(str(role), ROLES)}; valid roles: {', '.join(ROLES)}",
                variable=var,
            )
        if role == "time" and dims[var] != Dimension({"T": 1}):
            raise ModelFileError(
                path, f"has role 'time' but dimension {dims[var]}; time must have dimension T", variable=var
            )
        roles[var] = role
        if "value" in entry:
            values[var] = _value(entry["value"], path, var)
        if "description" in entry:
            if not isinstance(entry["description"], str):
                raise ModelFileError(path, f"description must be a string, got {entry['description']!r}", variable=var)
            descriptions[var] = entry["description"]
    times = [n for n, r in roles.items() if r == "time"]
    if len(times) > 1:
        raise ModelFileError(
            path, f"has role 'time' as well as {times[0]!r}; at most one variable is time", variable=times[1]
        )
    if "base_dimensions" not in data:  # a unit such as "mol" brings its opt-in base (N) with it
        used = {b for var in units for b in dims[var].base_dimensions}
        allowed += tuple(b for b in OPT_IN_BASE_DIMENSIONS if b in used)
    try:
        system = System(dims, base_dimensions=allowed)
    except PiTheoremError as err:
        raise ModelFileError(path, str(err).splitlines()[0]) from None
    return ModelFile(name, description, system, values, roles, units, descriptions)


def _read_dimension(path: str, var: str, text, allowed) -> Dimension:
    if not isinstance(text, str):
        raise ModelFileError(path, f'dimension must be a string such as "M L^2 T^-2", got {text!r}', variable=var)
    try:
        dim = Dimension.parse(text, base_dimensions=allowed)
    except DimensionSyntaxError as err:
        raise ModelFileError(
            path, f"cannot read dimension {text!r} at position {err.position}: {err.reason}", variable=var
        ) from None
    except LimitError as err:
        raise ModelFileError(path, f"cannot read dimension: {err}", variable=var) from None
    unknown = [b for b in dim.base_dimensions if b not in allowed]
    if unknown:
        raise ModelFileError(
            path, f"unknown base dimension {unknown[0]!r} in {text!r}; allowed: {', '.join(allowed)}", variable=var
        )
    return dim


def _read_unit(path: str, var: str, unit) -> Dimension:
    if not isinstance(unit, str):
        raise ModelFileError(path, f'unit must be a string such as "N*m/rad", got {unit!r}', variable=var)
    try:
        return System.from_units({var: unit}).dimension(var)
    except PiTheoremError as err:
        raise ModelFileError(path, str(err).splitlines()[0], variable=var) from None


def _value(value, path: str, var: str) -> float | Fraction:
    """:func:`pitheorem.exact.read_value`, its errors told as the file's."""
    if isinstance(value, bool):  # spelled as the file spells it
        raise ModelFileError(path, f"value must be a number, got {str(value).lower()}", variable=var)
    try:
        return read_value(value, "value")
    except PiTheoremError as err:
        raise ModelFileError(
            path, f'{str(err).splitlines()[0]} (numbers may also be exact strings such as "1/3")', variable=var
        ) from None


# -- writing ---------------------------------------------------------------------------------


def _toml_string(text: str) -> str:
    return json.dumps(text, ensure_ascii=False)  # JSON string escapes are valid TOML basic strings


def _toml_key(name: str) -> str:
    return name if _BARE_KEY.match(name) else _toml_string(name)


def _toml_value(value) -> str:
    if isinstance(value, int) and not isinstance(value, bool):
        value = Fraction(value)
    if isinstance(value, Fraction) and value.denominator == 1 and -(2**63) <= value < 2**63:
        return str(value.numerator)  # TOML integers are 64-bit: bigger ones are written as exact strings
    if isinstance(value, Fraction):
        return _toml_string(str(value))
    if isinstance(value, float):
        return repr(value)
    return str(value)


def dump_values(model: ModelFile, values: Mapping[str, object] | None = None, *, format: str = "toml") -> str:
    """Text of a model file like `model`, with other values.

    TOML output is itself a model file: :func:`load_model_file` reads it
    back exactly (rationals are written as strings such as ``"1/3"``).
    JSON output holds the same information, with rationals as strings.

    Parameters
    ----------
    model : ModelFile
    values : mapping of str to number, optional
        Values to write (default: ``model.values``).
    format : {"toml", "json"}

    Returns
    -------
    str

    Examples
    --------
    >>> from fractions import Fraction
    >>> import pitheorem as pt
    >>> from pitheorem.modelfile import ModelFile, dump_values
    >>> model = ModelFile("pendulum", "", pt.System({"l": "L", "g": "L T^-2", "t": "T"}),
    ...                   roles={"l": "parameter", "g": "parameter", "t": "time"})
    >>> print(dump_values(model, {"l": Fraction(1, 3), "g": 9.81}))
    name = "pendulum"
    <BLANKLINE>
    [variables]
    l = { dimension = "L", value = "1/3" }
    g = { dimension = "L T^-2", value = 9.81 }
    t = { dimension = "T", role = "time" }
    <BLANKLINE>
    """
    if values is not None:
        model = model.with_values(values)
    if format not in ("toml", "json"):
        raise ModelFileError(model.path or "<model>", f"unknown output format {format!r}; use 'toml' or 'json'")
    entries = {}
    for n in model.system.variables:
        entry = {"unit": model.units[n]} if n in model.units else {"dimension": str(model.system.dimension(n))}
        if n in model.values:
            entry["value"] = model.values[n]
        role = model.roles.get(n, ROLES[0])
        if role != ROLES[0]:
            entry["role"] = role
        if n in model.descriptions:
            entry["description"] = model.descriptions[n]
        entries[n] = entry
    if format == "json":
        doc = {
            "name": model.name,
            "description": model.description,
            "variables": {n: {k: json_number(v) for k, v in e.items()} for n, e in entries.items()},
        }
        return json.dumps(doc, indent=2, ensure_ascii=False) + "\n"
    lines = [f"name = {_toml_string(model.name)}"]
    if model.description:
        lines.append(f"description = {_toml_string(model.description)}")
    lines += ["", "[variables]"]
    for n, entry in entries.items():
        body = ", ".join(f"{k} = {_toml_value(v) if k == 'value' else _toml_string(v)}" for k, v in entry.items())
        lines.append(f"{_toml_key(n)} = {{ {body} }}")
    return "\n".join(lines) + "\n"


def write_model_file(model: ModelFile, path, values: Mapping[str, object] | None = None) -> Path:
    """Write a model file (``.toml``) or its JSON form (``.json``).

    Parameters
    ----------
    model : ModelFile
    path : str or os.PathLike
        Output file; its suffix chooses the format.
    values : mapping of str to number, optional
        Values to write (default: ``model.values``).

    Returns
    -------
    pathlib.Path
        The file written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from pitheorem.modelfile import load_model_file, write_model_file
    >>> rod = load_model_file("example:hinged_rod")
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     out = write_model_file(rod, pathlib.Path(folder) / "heavy.toml", {**rod.values, "m": 3})
    ...     load_model_file(out).values["m"]
    Fraction(3, 1)
    """
    out = Path(path)
    suffix = out.suffix.lower()
    if suffix not in (".toml", ".json"):
        raise ModelFileError(str(path), f"unknown output suffix {out.suffix!r}; use .toml or .json")
    out.write_text(dump_values(model, values, format=suffix[1:]), encoding="utf-8")
    return out
