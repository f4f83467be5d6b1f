"""The URDF format: every number a URDF file states, with its dimension and its address; written back by address.

Read with :mod:`xml.etree.ElementTree`, by the URDF specification (SI
units: metres, kilograms, seconds, radians).  A number is read as it is
written, and text that is not plain numbers as PyBullet reads it (C's
``atof``: :func:`bullet_numbers`), with one warning.  Mesh files are found
as PyBullet finds them (beside the file and in every folder above it,
``package://`` dropped) and, first, in a mesh folder the file names where
a runner says where it does (MuJoCo's runner: its extension
``<mujoco><compiler meshdir="..."/></mujoco>``).  Dimensions follow the
joint type: a revolute, continuous or spherical joint has coordinate ``q``
= 1 and generalised force ``Q`` = M L^2 T^-2, a prismatic one ``q`` = L and
``Q`` = M L T^-2; a fixed or floating joint states no number but its
origin.  A scaled copy is the parsed file with each number rewritten
at its address (its element's place in document order), never walked
again.  What a URDF cannot hold (gravity, the time step, contact and
solver settings) is the runner's: :mod:`pitheorem.engines.runners.pybullet`
keeps PyBullet's beside the file.  Nothing here imports an engine.
"""

from __future__ import annotations

import copy
import functools
import math
import os
import re
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path

from ...formatting.pieces import float_text, names_text
from ..enginemodel import EngineModelError
from ..parameters import JointKind, Parameter, attribute_text, dim, identifier, unique_name, warn_unscalable
from ..registry import check_written_suffix
from .assets import AssetCopies, assets_folder
from .numbers import check_model_file, check_numbers

__all__ = ["SI", "UrdfDocument", "bullet_numbers", "joint_kind", "read_urdf", "refuse_units"]

_ONE, _L, _T, _M = dim("1"), dim("L"), dim("T"), dim("M")

#: the units of every URDF file, by its specification
SI = {"M": "kg", "L": "m", "T": "s"}


#: what C's ``atof`` reads at the start of a text: the longest prefix that is a decimal number
_ATOF = re.compile(r"\s*[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan)", re.IGNORECASE)

#: the attributes PyBullet reads as three numbers (its ``parseVector3``); every other one is one number
_VECTORS = frozenset({"xyz", "size", "scale"})


def _atof(text: str) -> float:
    """C's ``atof``: the number a text starts with, 0.0 where it starts with none (``"1.57."`` -> 1.57)."""
    match = _ATOF.match(text)
    return 0.0 if match is None else float(match.group())  # "1e" matches as "1": an exponent needs digits


def bullet_numbers(attr: str, text: str) -> tuple[float, ...] | None:
    """The numbers PyBullet's URDF reader takes from an attribute's text; None where it takes none.

    PyBullet reads one number with C's ``atof`` (the number the text starts
    with: ``"-1.57."`` is -1.57) and three numbers (``xyz``, ``size``,
    ``scale``) by splitting the text at spaces and reading each piece with
    ``atof``, keeping the first three (``"0.07, 0, -0.69"`` is 0.07 0 -0.69);
    with fewer than three pieces it reads none.

    Examples
    --------
    >>> from pitheorem.engines.fileformats.urdf import bullet_numbers
    >>> bullet_numbers("xyz", "0.07, 0, -0.69"), bullet_numbers("lower", "-1.57.")
    ((0.07, 0.0, -0.69), (-1.57,))
    >>> bullet_numbers("xyz", "$(optenv XYZ 0.19 0 0.149)"), bullet_numbers("xyz", "1 2")
    ((0.0, 0.0, 0.19), None)
    """
    if attr not in _VECTORS:
        return (_atof(text),)
    pieces = [piece for piece in text.split(" ") if piece]
    if len(pieces) < 3:
        return None
    return tuple(_atof(piece) for piece in pieces[:3])


def _read_numbers(attr: str, text: str) -> tuple[tuple[float, ...], bool]:
    """An attribute's numbers, and whether they were read as PyBullet reads a text that is not plain numbers.

    Plain numbers are read as they are written; any other text as
    :func:`bullet_numbers` reads it (the text of a file that PyBullet loads).
    """
    try:
        plain = tuple(float(v) for v in text.split())
    except ValueError:
        plain = ()
    if plain and (attr in _VECTORS or len(plain) == 1):
        return plain, False
    numbers = bullet_numbers(attr, text)
    return (numbers, True) if numbers is not None else ((), False)


def joint_kind(jtype: str) -> JointKind | None:
    """The coordinate and force of a URDF joint type: None for a fixed (or unknown) joint.

    Examples
    --------
    >>> from pitheorem.engines.fileformats.urdf import joint_kind
    >>> str(joint_kind("prismatic").force), str(joint_kind("spherical").q), joint_kind("fixed")
    ('M L T^-2', '1', None)
    """
    if jtype == "prismatic":
        return JointKind.SLIDE
    if jtype in ("revolute", "continuous", "spherical"):
        return JointKind.HINGE  # a spherical joint turns by angles under torques, as MuJoCo's ball does
    return None


class _Attr:
    """One dimensional attribute of one URDF element (its ``value`` attribute or another one).

    ``index`` is the element's address: its place in the document's order
    (``root.iter()``), the same in every copy of the parsed file.
    ``default`` is the text the engine reads when the attribute is absent
    (a mesh's scale), so that reading a file never adds anything to it.
    """

    def __init__(self, name, path, element, attr, dimension, note="", index=-1, default=None):
        self.name, self.path, self.element, self.attr, self.dimension, self.note = (
            name,
            path,
            element,
            attr,
            dimension,
            note,
        )
        self.index, self.default = index, default

    def read(self):
        return _read_numbers(self.attr, self.element.get(self.attr, self.default))[0]

    def in_copy(self, elements: list) -> _Attr:
        """The same attribute in a copy of the file, whose elements in document order are `elements`."""
        return _Attr(
            self.name, self.path, elements[self.index], self.attr, self.dimension, self.note, self.index, self.default
        )


def _attributes(tree: ET.ElementTree, path: str, source_dir: Path, folder_at=None) -> list[_Attr]:
    """Every dimensional number the URDF states, in document order."""
    root = tree.getroot()
    if root.tag != "robot":
        raise EngineModelError(path, f"<{root.tag}>", "a URDF file's root element must be <robot>")
    out: list[_Attr] = []
    read_loosely: list[tuple[str, str, str, tuple[float, ...]]] = []
    names: set[str] = set()
    address = {id(element): i for i, element in enumerate(root.iter())}
    mesh_folder = _mesh_folder(root, source_dir, folder_at)

    def add(ident, where, element, attr, dimension, note="", default=None):
        if element is None or element.get(attr, default) is None:
            return
        text = element.get(attr, default)
        numbers, loose = _read_numbers(attr, text)
        if loose and _has_number(attr, text):  # not plain numbers, but PyBullet loads it: read as it reads it
            if not all(math.isfinite(x) and (x >= 0 or dimension != _M) for x in numbers):
                check_numbers(path, where, attr, text, nonnegative=dimension == _M)  # refused, named as written
            read_loosely.append((where, attr, text, numbers))
        else:
            check_numbers(path, where, attr, text, nonnegative=dimension == _M)  # a mass cannot be < 0
        out.append(
            _Attr(unique_name(ident, names), where, element, attr, dimension, note, address[id(element)], default)
        )

    for link in root.findall("link"):
        lname = link.get("name", "")
        ident = identifier(f"link_{lname}")
        where = f"link {lname!r}"
        inertial = link.find("inertial")
        if inertial is not None:
            add(f"{ident}_com", f"{where} inertial origin xyz", inertial.find("origin"), "xyz", _L)
            add(f"{ident}_mass", f"{where} inertial mass", inertial.find("mass"), "value", _M)
            inertia = inertial.find("inertia")
            for a in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
                add(
                    f"{ident}_{a}",
                    f"{where} inertia {a}",
                    inertia,
                    a,
                    dim("M L^2"),
                    note="PyBullet recomputes the inertia from the collision shapes unless "
                    "URDF_USE_INERTIA_FROM_FILE is given",
                )
        for kind in ("collision", "visual"):
            for k, shape in enumerate(link.findall(kind)):
                sid = f"{ident}_{kind}{k}"
                swhere = f"{where} {kind} #{k}"
                add(f"{sid}_xyz", f"{swhere} origin xyz", shape.find("origin"), "xyz", _L)
                geometry = shape.find("geometry")
                if geometry is None:
                    continue
                for g in geometry:
                    if g.tag == "box":
                        add(f"{sid}_size", f"{swhere} box size", g, "size", _L)
                    elif g.tag in ("cylinder", "capsule", "sphere"):
                        add(f"{sid}_radius", f"{swhere} {g.tag} radius", g, "radius", _L)
                        add(f"{sid}_length", f"{swhere} {g.tag} length", g, "length", _L)
                    elif g.tag == "mesh":
                        filename = g.get("filename", "")
                        resolved = _mesh_path(filename, source_dir, mesh_folder)
                        if resolved is None:
                            where_looked = "the URDF's folder" + (
                                f" or its mesh folder {str(mesh_folder)!r}, its "
                                f"<{'><'.join(folder_at[0].split('/'))} {folder_at[1]}>"
                                if mesh_folder
                                else ""
                            )
                            raise EngineModelError(
                                path,
                                f"{swhere} mesh {filename!r}",
                                f"mesh file not found (relative to {where_looked})",
                            )
                        add(
                            f"{sid}_scale",
                            f"{swhere} mesh scale",
                            g,
                            "scale",
                            _L,
                            note="a factor times the mesh file's units, a length",
                            default="1 1 1",
                        )
                    elif g.tag == "plane":
                        pass  # an infinite plane: nothing to scale
                    elif kind == "visual":
                        pass  # something PyBullet draws nothing from (a <material> put inside <geometry>)
                    else:
                        raise EngineModelError(
                            path,
                            f"{swhere} <{g.tag}>",
                            "unknown geometry; use box, cylinder, capsule, sphere, mesh or plane",
                        )
        contact = link.find("contact")
        if contact is not None:
            for tag, d in (
                ("rolling_friction", _L),
                ("spinning_friction", _L),
                ("stiffness", dim("M T^-2")),
                ("damping", dim("M T^-1")),
            ):
                add(f"{ident}_{tag}", f"{where} contact {tag}", contact.find(tag), "value", d)
            for tag in contact:
                if tag.tag not in (
                    "lateral_friction",
                    "rolling_friction",
                    "spinning_friction",
                    "restitution",
                    "stiffness",
                    "damping",
                    "contact_cfm",
                    "contact_erp",
                    "inertia_scaling",
                    "friction_anchor",
                ):
                    raise EngineModelError(path, f"{where} contact <{tag.tag}>", "unknown contact parameter")
    for joint in root.findall("joint"):
        jname, jtype = joint.get("name", ""), joint.get("type", "")
        ident = identifier(f"joint_{jname}")
        where = f"joint {jname!r}"
        add(f"{ident}_xyz", f"{where} origin xyz", joint.find("origin"), "xyz", _L)
        if jtype in ("fixed", "floating"):  # a floating joint states no number (PyBullet loads it as fixed)
            continue
        kind = joint_kind(jtype)
        if kind is None:
            raise EngineModelError(
                path,
                f"{where} (type {jtype!r})",
                "joint type not supported by pitheorem's scaling; use revolute, continuous, prismatic, "
                "spherical, floating or fixed",
            )
        q, force = kind.q, kind.force
        limit = joint.find("limit")
        add(f"{ident}_lower", f"{where} limit lower", limit, "lower", q)
        add(f"{ident}_upper", f"{where} limit upper", limit, "upper", q)
        add(f"{ident}_effort", f"{where} limit effort", limit, "effort", force)
        add(f"{ident}_velocity", f"{where} limit velocity", limit, "velocity", q / _T)
        dynamics = joint.find("dynamics")
        add(f"{ident}_damping", f"{where} dynamics damping", dynamics, "damping", force * _T / q)
        add(f"{ident}_friction", f"{where} dynamics friction", dynamics, "friction", force)
        if jtype == "spherical":
            add(f"{ident}_twist", f"{where} limit twist", limit, "twist", q)
    _warn_loose(path, read_loosely)
    return out


def _has_number(attr: str, text: str) -> bool:
    """Whether PyBullet reads a number from `text` at all: a scalar's text starts with one, a vector's has one."""
    if attr not in _VECTORS:
        return _ATOF.match(text) is not None
    return any(_ATOF.match(piece) for piece in text.split(" ") if piece)


def _warn_loose(path: str, read_loosely: list) -> None:
    """One warning for every attribute that is not plain numbers, read as PyBullet reads it: the first named."""
    if not read_loosely:
        return
    where, attr, text, numbers = read_loosely[0]
    more = f" (and {len(read_loosely) - 1} more)" if len(read_loosely) > 1 else ""
    shown = " ".join(float_text(x) for x in numbers)
    hint = "; an unexpanded xacro macro: run xacro first" if "$(" in text else ""
    warnings.warn(
        f"{Path(path).name}: {where}: {attr}={text!r} is not plain numbers; read as PyBullet reads it, "
        f"{shown}{more}{hint}",
        UserWarning,
        stacklevel=4,
    )


def _compound_meshes(tree: ET.ElementTree, source_dir: Path, folder_at=None) -> list[tuple[str, str, int]]:
    """The OBJ collision meshes of several objects (convex decompositions such as V-HACD's).

    PyBullet loads such a mesh as a compound of convex hulls, and
    ``changeDynamics(collisionMargin=...)`` does not reach the parts: a margin
    of 0.05 moves pybullet_data's duck at rest by 8e-5 m, not 0.05 m.  The
    parts keep their default margin, a length no scaling can change, so the
    contacts of a scaled copy are off by it.  Returns (link, file, parts) each.
    """
    found = []
    mesh_folder = _mesh_folder(tree.getroot(), source_dir, folder_at)
    for link in tree.getroot().iter("link"):
        for collision in link.findall("collision"):
            for mesh in collision.iter("mesh"):
                filename = mesh.get("filename", "")
                resolved = _mesh_path(filename, source_dir, mesh_folder)
                if resolved is None or resolved.suffix.lower() != ".obj":
                    continue
                with open(resolved, encoding="utf-8", errors="replace") as lines:
                    parts = sum(1 for line in lines if line.startswith("o "))
                if parts > 1:
                    found.append((link.get("name"), filename, parts))
    return found


def _warn_compound_meshes(tree: ET.ElementTree, path: str, source_dir: Path, folder_at=None) -> None:
    """Warn once about the collision meshes of :func:`_compound_meshes`: the first named, the others counted."""
    found = _compound_meshes(tree, source_dir, folder_at)
    if not found:
        return
    link, filename, parts = found[0]
    more = f" (and {len(found) - 1} more such meshes)" if len(found) > 1 else ""
    warn_unscalable(
        path,
        f"link {link!r} collision mesh {filename!r}{more}",
        f"its {parts} convex parts load as a compound whose collision margins "
        "changeDynamics cannot reach; contacts of a scaled copy are off by that margin",
    )


def _xml_text(tree: ET.ElementTree) -> str:
    return ET.tostring(tree.getroot(), encoding="unicode")


def _mesh_folder(root: ET.Element, source_dir: Path, folder_at) -> Path | None:
    """The mesh folder the file names at `folder_at` (an element's path and its attribute); None without one.

    A relative folder is relative to the URDF's folder.
    """
    if folder_at is None:
        return None
    element_path, attribute = folder_at
    for element in root.findall(element_path):
        if element.get(attribute):
            return source_dir / element.get(attribute)
    return None


def _without_mesh_folder(root: ET.Element, folder_at) -> None:
    """Drop the mesh folder the file names at `folder_at`: every mesh is then named from the file itself."""
    if folder_at is not None:
        for element in root.findall(folder_at[0]):
            element.attrib.pop(folder_at[1], None)


def _mesh_path(filename: str, source_dir: Path, mesh_folder: Path | None = None) -> Path | None:
    """The file a URDF's mesh or texture names, searched as MuJoCo and PyBullet do; None if there is none.

    A relative mesh name is looked for in `mesh_folder` first (a folder the file names for an
    engine that reads it, such as MuJoCo's ``<mujoco><compiler meshdir>``), then as PyBullet does
    (its ``UrdfFindMeshFile``): ``package://`` and ``model://`` dropped, the name is looked for in
    the URDF's folder and in every folder above it, nearest first (a ROS package's meshes sit
    beside its ``urdf`` folder; pybullet_data's ``differential/diff_ring.urdf`` names
    ``differential/diff_ring.stl`` from the folder above), then as given.  A
    ``package://NAME/rest`` path is then looked for as ROS finds the package (:func:`_ros_packages`),
    and last as ``rest`` in the URDF's folder and each folder above it:
    the package's root, where its folder is not named as the package (robotics-toolbox's KUKA
    KR16 in ``kuka_kr16/`` names ``package://kuka_kr16_support/meshes/...``).
    """
    name, package = filename, None
    for scheme in ("package://", "model://"):
        if name.startswith(scheme):
            name = name[len(scheme) :]
            package = name.partition("/") if scheme == "package://" else None
            break
    above = (source_dir, *source_dir.parents)
    candidates = [folder / name for folder in above] + [Path(name)]
    if mesh_folder is not None and name == filename:
        candidates.insert(0, mesh_folder / name)
    if package is not None and package[2]:
        found = [folder / package[2] for folder in _ros_packages(package[0])]
        candidates += found + [folder / package[2] for folder in above]
    for c in candidates:
        if c.is_file():
            return c
    return None


def _ros_packages(name: str) -> list[Path]:
    """The folders of the ROS package `name` as ROS finds them: ``NAME`` in each folder of ``ROS_PACKAGE_PATH``, a
    folder below one whose ``package.xml`` names it (ROS 1's crawl), and ``share/NAME`` under each prefix of
    ``AMENT_PREFIX_PATH`` (ROS 2's)."""
    roots = [Path(p) for p in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
    prefixes = [Path(p) for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    named = [folder for root in roots for folder in _manifests(str(root)).get(name, ())]
    return [root / name for root in roots] + named + [prefix / "share" / name for prefix in prefixes]


@functools.lru_cache(maxsize=16)
def _manifests(root: str) -> dict[str, tuple[Path, ...]]:
    """Package name -> its folders under `root`: each folder with a ``package.xml``, not looked into further (as
    ROS's crawl does).  Read once per root and process."""
    out: dict[str, list[Path]] = {}
    for folder, subfolders, files in os.walk(root):
        if "package.xml" in files:
            subfolders.clear()
            try:
                text = (Path(folder) / "package.xml").read_text(errors="replace")
                package = ET.fromstring(text).findtext("name")
            except (OSError, ET.ParseError):
                continue
            if package:
                out.setdefault(package.strip(), []).append(Path(folder))
    return {k: tuple(v) for k, v in out.items()}


def _portable_text(tree: ET.ElementTree, source_dir: Path, folder_at=None) -> str | None:
    """The URDF's text with every mesh and texture file named by its absolute path, to load from any folder.

    None when one of them cannot be found (PyBullet may still find it from the file's own folder).
    """
    tree = copy.deepcopy(tree)
    mesh_folder = _mesh_folder(tree.getroot(), source_dir, folder_at)
    for element in tree.getroot().iter():
        if element.tag in ("mesh", "texture") and element.get("filename"):
            found = _mesh_path(element.get("filename"), source_dir, mesh_folder if element.tag == "mesh" else None)
            if found is None:
                return None
            element.set("filename", str(found.resolve()))
    return _xml_text(tree)


class UrdfDocument:
    """A URDF file: its parsed tree and every number it states, each with its address.

    Parameters
    ----------
    tree : xml.etree.ElementTree.ElementTree
        The parsed file; never changed (a scaled copy is a new tree).
    path : str
        The file it was read from.
    source_dir : Path
        The folder its mesh and texture files are relative to.
    mesh_folder : tuple of (str, str), optional
        Where the file names a folder its meshes are looked for in first:
        an element's path below ``<robot>`` and its attribute (MuJoCo's
        runner gives ``("mujoco/compiler", "meshdir")``).  A saved copy
        names every mesh relative to itself and drops that attribute.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.fileformats.urdf import read_urdf
    >>> document = read_urdf(engines.example_path("hinged_rod.urdf"))
    >>> [p.name for p in document.parameters()][:2]
    ['link_base_mass', 'link_base_ixx']
    """

    #: the units a URDF file is in, whatever a caller declares (its specification's)
    fixed_units = SI

    def __init__(
        self,
        tree: ET.ElementTree,
        path: str,
        source_dir: Path,
        *,
        attrs: list[_Attr] | None = None,
        mesh_folder: tuple[str, str] | None = None,
    ):
        self.tree, self.path, self.source_dir, self.mesh_folder = tree, path, source_dir, mesh_folder
        # a copy gets its attributes by address from its original's: the file is not walked again
        self.attrs = _attributes(tree, path, source_dir, mesh_folder) if attrs is None else attrs

    def parameters(self) -> list[Parameter]:
        """Every dimensional number the file states, in document order."""
        return [Parameter(a.name, a.path, a.read(), a.dimension, "file", "file", note=a.note) for a in self.attrs]

    def scaled(self, factors: Mapping[str, float], *, text=attribute_text) -> UrdfDocument:
        """A copy with each number multiplied by its factor, written as `text` writes it (the exact decimal product)."""
        tree = copy.deepcopy(self.tree)
        elements = list(tree.getroot().iter())
        attrs = [a.in_copy(elements) for a in self.attrs]
        for a in attrs:
            f = factors.get(a.name, 1.0)
            if f != 1.0:
                a.element.set(a.attr, text(a.read(), f))
        return UrdfDocument(tree, self.path, self.source_dir, attrs=attrs, mesh_folder=self.mesh_folder)

    def text(self) -> str:
        """The file's text as it stands."""
        return _xml_text(self.tree)

    def portable_text(self) -> str | None:
        """The file's text with every mesh and texture named by its absolute path (None: one is missing)."""
        return _portable_text(self.tree, self.source_dir, self.mesh_folder)

    def compound_meshes(self) -> list[tuple[str, str, int]]:
        """The OBJ collision meshes of several convex parts: (link, file, parts) each."""
        return _compound_meshes(self.tree, self.source_dir, self.mesh_folder)

    def warn_compound_meshes(self) -> None:
        """Warn about each collision mesh of several convex parts, whose margins no call reaches."""
        _warn_compound_meshes(self.tree, self.path, self.source_dir, self.mesh_folder)

    def save(self, path, *, copy_assets: bool = False) -> None:
        """Write the file, its meshes and textures named relative to it: the folder holding both can move.

        With `copy_assets` the mesh and texture files are copied into
        ``<stem>_assets`` beside the file, and the file names the copies.
        """
        check_written_suffix(path, "urdf")  # else it would not load again, or load as another format
        tree = copy.deepcopy(self.tree)
        folder = Path(os.path.abspath(path)).parent
        copies = AssetCopies(assets_folder(os.path.abspath(path))) if copy_assets else None
        mesh_folder = _mesh_folder(tree.getroot(), self.source_dir, self.mesh_folder)
        for g in tree.getroot().iter():
            if g.tag not in ("mesh", "texture") or not g.get("filename"):
                continue
            resolved = _mesh_path(g.get("filename", ""), self.source_dir, mesh_folder if g.tag == "mesh" else None)
            if resolved is not None:
                if copies is not None:
                    resolved = copies.copy(resolved)
                g.set("filename", Path(os.path.relpath(os.path.abspath(resolved), folder)).as_posix())
        _without_mesh_folder(tree.getroot(), self.mesh_folder)  # each mesh now named relative to the saved file
        Path(path).write_text(_xml_text(tree))


def read_urdf(path, *, mesh_folder: tuple[str, str] | None = None) -> UrdfDocument:
    """Read a URDF file: its tree and every number it states.

    Parameters
    ----------
    path : str or Path
    mesh_folder : tuple of (str, str), optional
        Where the file may name a folder its meshes are looked for in
        first: an element's path below ``<robot>`` and its attribute, as a
        runner reads the file (MuJoCo's: ``("mujoco/compiler", "meshdir")``).

    Returns
    -------
    UrdfDocument

    Raises
    ------
    EngineModelError
        For a file that is no URDF (the root must be ``<robot>``), a number
        that is not finite or a negative mass, a missing mesh, an unknown
        geometry, contact parameter or joint type.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.fileformats.urdf import read_urdf
    >>> read_urdf(engines.example_path("hinged_rod.urdf")).path.endswith("hinged_rod.urdf")
    True
    """
    path = Path(path)
    root = check_model_file(path)  # the file parsed once, its numbers checked
    if root is not None:
        tree = ET.ElementTree(root)
    else:  # not well-formed: parse it again for the line of the fault
        try:
            tree = ET.parse(path)
        except ET.ParseError as err:
            raise EngineModelError(str(path), f"line {err.position[0]}", f"not well-formed XML ({err})") from None
    if tree.getroot().tag == "robot":  # another root is refused by name when the file is read
        _check_tree(tree.getroot(), str(path))
    # a symbolic link not followed
    return UrdfDocument(tree, str(path), Path(os.path.abspath(path)).parent, mesh_folder=mesh_folder)


def _check_tree(root: ET.Element, path: str) -> None:
    """Refuse, by name, a URDF whose links and joints make no tree, as ROS's URDF parser does.

    PyBullet crashes the whole process (a segmentation fault) on a joint given
    twice or on two root links, and MuJoCo compiles an empty world from a file
    with no link, so these are refused before an engine reads the file: no link,
    names given twice, a joint without a parent or a child link or naming a link
    the file has not, a link that is the child of two joints, and links that make
    no single tree (no root: a loop; several roots: unconnected parts).  Links are
    named in the file's order.
    """
    if root.find("link") is None:
        raise EngineModelError(path, "<robot>", "a URDF file needs at least one <link>; this one has none")
    names: dict[str, list[str]] = {}
    for kind in ("link", "joint"):
        names[kind] = []
        for element in root.findall(kind):
            name = element.get("name")
            if not name:
                raise EngineModelError(path, f"<{kind}>", f"a {kind} needs a name; this one has none")
            if name in names[kind]:
                raise EngineModelError(
                    path, f"{kind} {name!r}", f"two {kind}s are named {name!r}: names must be unique"
                )
            names[kind].append(name)
    links = names["link"]
    known = set(links)
    parent_of: dict[str, str] = {}
    children: dict[str, list[str]] = {}
    for joint in root.findall("joint"):
        where = f"joint {joint.get('name')!r}"
        ends = {}
        for end in ("parent", "child"):
            element = joint.find(end)
            name = element.get("link") if element is not None else None
            if not name:
                raise EngineModelError(path, where, f"a joint needs a <{end} link=...>; this one has none")
            if name not in known:
                raise EngineModelError(path, where, f"its {end} link {name!r} is no link of the file")
            ends[end] = name
        if ends["child"] in parent_of:
            raise EngineModelError(
                path,
                where,
                f"link {ends['child']!r} is the child of two joints (this one and the one from "
                f"{parent_of[ends['child']]!r}): the links must make a tree",
            )
        parent_of[ends["child"]] = ends["parent"]
        children.setdefault(ends["parent"], []).append(ends["child"])
    roots = [link for link in links if link not in parent_of]
    if len(roots) != 1:
        reason = (
            "every link is some joint's child: the joints make a loop"
            if not roots
            else f"{len(roots)} links are no joint's child ({names_text(roots, code=repr, shown=4, in_all=False)}): "
            "the links must make one tree, with one root"
        )
        raise EngineModelError(path, "<robot>", reason)
    reached, todo = set(roots), list(roots)
    while todo:  # down from the root: a link it never reaches is in a loop of its own below it
        for child in children.get(todo.pop(), ()):
            reached.add(child)
            todo.append(child)
    looped = next((link for link in links if link not in reached), None)
    if looped is not None:
        raise EngineModelError(path, f"link {looped!r}", "its joints make a loop: the links must make a tree")


def refuse_units(path: str, units: Mapping[str, str]) -> None:
    """Refuse units other than SI for a URDF file, by name (an :class:`~pitheorem.errors.EngineModelError`).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.fileformats.urdf import refuse_units
    >>> try:
    ...     refuse_units("arm.urdf", {"M": "g", "L": "cm", "T": "s"})
    ... except engines.EngineModelError as err:
    ...     print(str(err)[:60])
    arm.urdf: units: a URDF file is in SI units, not g cm s: sca
    """
    raise EngineModelError(
        path or "the URDF model",
        "units",
        f"a URDF file is in SI units, not {' '.join(units.values())}: scale it instead",
    )
