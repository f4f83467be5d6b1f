"""The numbers of an MJCF or URDF file, checked before an engine reads them.

MuJoCo reads ``damping="nan"`` as "unset" and drops it, and ``stiffness="inf"``
as infinity; Python's ``float()`` takes ``"nan"``, ``"inf"`` and ``"1e999"``
too.  A model holds neither, so the loaders refuse them up front, naming the
file, the element and the attribute:

* :func:`check_model_file` reads the whole file: it must be UTF-8 text, and
  no attribute may hold NaN or an infinity;
* :func:`check_numbers` reads one attribute that must be numbers (a URDF
  mass, inertia, damping ...): finite, at least one, and not negative where
  the quantity cannot be.

Nothing here imports an engine.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path

from ...errors import EngineModelError

__all__ = ["check_model_file", "check_numbers"]

# attributes that name things (other elements, files, classes): "nan" there is a name, not a number
_NAMES = frozenset(
    {
        "name",
        "class",
        "childclass",
        "prefix",
        "content_type",
        "model",
        "link",
        "material",
        "texture",
        "mesh",
        "hfield",
        "joint",
        "joint1",
        "joint2",
        "body",
        "body1",
        "body2",
        "site",
        "site1",
        "site2",
        "tendon",
        "geom",
        "geom1",
        "geom2",
        "target",
        "objname",
        "refname",
        "actuator",
        "slidersite",
        "cranksite",
        "key",
        "plugin",
        "instance",
        "skin",
        "camera",
        "light",
        "flex",
        "sensor",
        "meshdir",
        "texturedir",
        "assetdir",
        "type",
    }
)


def _element(element: ET.Element, parents: dict) -> str:
    """``<joint name='h'>``, or an unnamed element with its nearest named ancestor: ``<mass> in <link name='b'>``.

    A default class names itself by its class: ``<joint> in <default class='soft'>``.
    """

    def named(e):
        return e.get("name") or (e.tag == "default" and e.get("class"))

    def label(e):
        if e.get("name"):
            return f"<{e.tag} name={e.get('name')!r}>"
        return f"<{e.tag} class={e.get('class')!r}>" if named(e) else f"<{e.tag}>"

    ancestor = element
    while ancestor is not None and not named(ancestor):
        ancestor = parents.get(ancestor)
    if ancestor is None or ancestor is element:
        return label(element)
    return f"{label(element)} in {label(ancestor)}"


def _line(text: str, root: ET.Element, element: ET.Element) -> int | None:
    """The line `element` of `root` (parsed from `text`) starts on: read again, only for a message."""
    import xml.parsers.expat

    order = {id(e): k for k, e in enumerate(root.iter())}
    starts: list[int] = []
    parser = xml.parsers.expat.ParserCreate()
    parser.StartElementHandler = lambda _tag, _attrs: starts.append(parser.CurrentLineNumber)
    try:  # the same text ElementTree read, its starts in the same order as root.iter()
        parser.Parse(text.strip().rstrip("\x00").strip(), True)
    except xml.parsers.expat.ExpatError:
        return None
    k = order.get(id(element))
    return starts[k] if k is not None and k < len(starts) else None


def _where(path, text: str, root: ET.Element, element: ET.Element) -> str:
    """The element of a message, after its line where it is known: ``line 5, <joint> in <default class='soft'>``."""
    line = _line(text, root, element)
    parents = {child: parent for parent in root.iter() for child in parent}  # only for a message
    return (f"line {line}, " if line is not None else "") + _element(element, parents)


#: a value of ASCII digits, points, signs and blanks, 300 characters at most: no number in it is NaN, and none
#: is infinite (one of 300 digits at most is below 1e300); most of a file's values, so they skip the loop that
#: reads each number (a tenth of the time of reading a file)
_PLAIN = re.compile(r"[0-9 \t\n\r.+-]{0,300}")


def check_model_file(path, *, nonnegative: Mapping[str, tuple[str, ...]] | None = None) -> ET.Element | None:
    """Refuse a model file that is not UTF-8 text, or whose attributes hold NaN or an infinity.

    A file that cannot be read, or is not well-formed XML, passes: the
    engine's own reader names its fault.  The parsed root element is
    returned (None for such a file), so a loader reads the file once.

    Parameters
    ----------
    path : str or Path
        The MJCF or URDF file.
    nonnegative : mapping of str to tuple of str, optional
        Per element tag, attributes whose numbers must not be negative
        (the MJCF reader's :data:`~pitheorem.engines.fileformats.mjcf.NONNEGATIVE`:
        ``<inertial>``'s mass and principal inertias, which MuJoCo's
        compiler turns to 0 without a word).

    Returns
    -------
    xml.etree.ElementTree.Element or None
        The file's root element; None where it cannot be read or parsed.

    Raises
    ------
    EngineModelError
        Naming the file, the line, the element (with its default class)
        and the attribute; also for a negative number `nonnegative` names.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from pitheorem.engines.fileformats.numbers import check_model_file
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "m.xml"
    >>> _ = path.write_text('<mujoco><option timestep="nan"/></mujoco>')
    >>> try:
    ...     check_model_file(path)
    ... except Exception as err:
    ...     print(str(err).replace(str(path), "m.xml"))
    m.xml: line 1, <option>: timestep='nan' is not a finite number; a model holds finite numbers only
    >>> rows = ['<mujoco>', '<default>', '<default class="soft">', '<joint damping="nan"/>', '</default>']
    >>> _ = path.write_text(chr(10).join([*rows, '</default>', '</mujoco>']))
    >>> try:
    ...     check_model_file(path)
    ... except Exception as err:
    ...     print(str(err).replace(str(path), "m.xml"))
    m.xml: line 4, <joint> in <default class='soft'>: damping='nan' is not a finite number; a model holds finite numbers only
    """
    try:
        raw = Path(path).read_bytes()
    except OSError:
        return None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        line = raw[: err.start].count(b"\n") + 1
        raise EngineModelError(
            str(path),
            f"line {line}",
            f"byte {raw[err.start]:#04x} at offset {err.start} is not UTF-8; save the file as UTF-8 text",
        ) from None
    try:  # as the engines' own XML readers do: blank lines before the declaration, NUL bytes after the end
        root = ET.fromstring(text.strip().rstrip("\x00").strip())
    except ET.ParseError:
        return None  # the engine's reader names the fault, with its own words
    for element in root.iter():
        for attr, value in element.attrib.items():
            if attr in _NAMES or attr.startswith("file") or _PLAIN.fullmatch(value):
                continue
            for token in value.split():
                try:
                    number = float(token)
                except ValueError:
                    break  # not a list of numbers: text of some kind, which the engine reads
                if not math.isfinite(number):
                    raise EngineModelError(
                        str(path),
                        _where(path, text, root, element),
                        f"{attr}={value!r} is not a finite number; a model holds finite numbers only",
                    )
    for tag, attrs in (nonnegative or {}).items():
        for element in root.iter(tag):
            for attr in attrs:
                if any(x < 0 for x in _numbers(element.get(attr))):
                    raise EngineModelError(
                        str(path),
                        _where(path, text, root, element),
                        f"{attr}={element.get(attr)!r} is negative, which the engine's compiler would make 0 "
                        "without a word; give 0 or more",
                    )
    return root


def _numbers(text: str | None) -> list[float]:
    """An attribute's numbers, or none where it is absent or not numbers."""
    try:
        return [float(token) for token in (text or "").split()]
    except ValueError:
        return []


def check_numbers(path, element: str, attr: str, text: str | None, *, nonnegative: bool = False) -> None:
    """Refuse an attribute that should be numbers and is not: empty, not numbers, NaN, infinite (or negative).

    Parameters
    ----------
    path : str or Path
        The file, for the message.
    element : str
        The element, for the message (``"link 'arm' inertial mass"``).
    attr : str
        The attribute's name.
    text : str or None
        Its text as the file has it (None: absent, which passes).
    nonnegative : bool
        Refuse negative numbers too (a mass).

    Raises
    ------
    EngineModelError

    Examples
    --------
    >>> from pitheorem.engines.fileformats.numbers import check_numbers
    >>> check_numbers("r.urdf", "link 'a' inertial mass", "value", "2.5")
    >>> try:
    ...     check_numbers("r.urdf", "link 'a' inertial mass", "value", "heavy", nonnegative=True)
    ... except Exception as err:
    ...     print(err)
    r.urdf: link 'a' inertial mass: value='heavy' must be a finite number, such as 1.5, and not negative
    """
    if text is None:
        return
    expected = "a finite number, such as 1.5" + (", and not negative" if nonnegative else "")
    tokens = text.split()
    try:
        numbers = [float(token) for token in tokens]
    except ValueError:
        numbers = []
    if not numbers or not all(math.isfinite(x) and (x >= 0 or not nonnegative) for x in numbers):
        plural = "finite numbers" if len(tokens) > 1 else expected
        raise EngineModelError(str(path), element, f"{attr}={text!r} must be {plural}")
