"""The MJCF format: every attribute with its dimension, read through MuJoCo's parser, and written back by address.

The file is read with MuJoCo's own ``MjSpec`` parser, so default classes,
includes and units (``compiler angle``) resolve as MuJoCo resolves them,
and compiled once, so masses and inertias computed from geoms are the
engine's own.  Each dimensional attribute of each element becomes one
:class:`~pitheorem.engines.Parameter` (one per component group where the
components of a vector differ, as for ``friction`` or ``solimp``).

Dimensions that depend on a joint's type use its coordinate ``q`` and its
generalised force ``Q``: hinge and ball joints have ``q`` = 1 (radians)
and ``Q`` = M L^2 T^-2; slide joints ``q`` = L and ``Q`` = M L T^-2.  A free
joint mixes both, so its damping, armature and friction loss are mixed
numbers.  Actuators follow MuJoCo's transmission: the actuator length is
``gear * q`` and its force acts as ``gear * force``; ``gear`` is taken as
dimensionless, so the actuator force has the joint's ``Q`` and the length
its ``q``.  The control input ``ctrl`` then has: for a motor (fixed gain, no
bias) the dimension of the force; for a position servo (bias on the length)
that of the length; for a velocity servo (bias on the velocity) that of
``q/T``; for a damper (gain on the velocity) none.

``opt.tolerance`` and ``noslip_tolerance`` stop the solver's iterations
relative to MuJoCo's own normalisation: they are listed as mixed numbers
and copied unchanged.  Files are written uncompiled (``savecompiled`` and
``savecanonical`` off), the only way MuJoCo writes every number at full
precision.
"""

from __future__ import annotations

import gc
import math
import os
import warnings
from collections.abc import Callable, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple
from xml.sax.saxutils import escape

import numpy as np

from pitheorem.formatting.pieces import float_text

from ...dimensions import Dimension
from ...errors import PiTheoremError, UnscalableParameterError
from ..enginemodel import EngineModelError
from ..packages import engine_module
from ..parameters import (
    JointKind,
    dim,
    dimension_factors,
    exact_product,
    identifier,
    new_parameter,
    unique_name,
    warn_unscalable,
)
from ..registry import check_written_suffix
from .assets import AssetCopies, assets_folder
from .numbers import check_model_file

__all__ = [
    "NONNEGATIVE",
    "UNITS_TEXT",
    "AttributeDimension",
    "MjcfDocument",
    "RefusedMjcfDocument",
    "StoredCopy",
    "read_mjcf",
    "record_units",
    "recorded_units",
    "spec_from_file",
]

#: attributes that MuJoCo's compiler turns to 0 when negative, without a word: refused when the file is read
NONNEGATIVE = {"inertial": ("mass", "diaginertia")}

#: a custom ``<text>`` element named this prefix plus a numeric's name declares that numeric's dimension
DIMENSION_TEXT = "dimension:"

_ONE = dim("1")
#: every entry of an attribute (a slice, no key before Python 3.12: :data:`_FORMS` keys its bounds)
_EVERY = slice(None)
_L, _M, _T = dim("L"), dim("M"), dim("T")
_FORCE, _TORQUE = dim("M L T^-2"), dim("M L^2 T^-2")


def _mujoco():
    return engine_module("mujoco")


def _joint_kind(mj, jtype) -> JointKind | None:
    """The kind of a joint of MuJoCo's type `jtype`; None for a free joint."""
    if not _JOINT_KINDS:  # by the type's number: comparing MuJoCo's enums takes a tenth of a microsecond each
        _JOINT_KINDS.update(
            {
                int(mj.mjtJoint.mjJNT_SLIDE): JointKind.SLIDE,
                int(mj.mjtJoint.mjJNT_HINGE): JointKind.HINGE,
                int(mj.mjtJoint.mjJNT_BALL): JointKind.HINGE,
            }
        )
    return _JOINT_KINDS.get(int(jtype))  # None: free


_JOINT_KINDS: dict[int, JointKind] = {}


#: a free joint's numbers that act on its translation and its rotation alike: (attribute, the dimension
#: of each part, the entries read)
_FREE_JOINT_MIXED = (
    ("damping", (("lin", dim("M T^-1")), ("rot", dim("M L^2 T^-1"))), slice(0, 1)),
    ("armature", (("lin", dim("M")), ("rot", dim("M L^2"))), _EVERY),
    ("frictionloss", (("lin", dim("M L T^-2")), ("rot", dim("M L^2 T^-2"))), _EVERY),
)


@dataclass(slots=True)  # a file has a slot per number: no dict per slot for the collector to scan
class Slot:
    """One dimensional attribute of one element: how to read it, and how to scale it by address.

    ``where`` is the element's address in a spec (a collection and an index, or ``("option",)``), so a
    copy of the spec is scaled by looking each element up, with no second walk of the file.  Scaling
    multiplies the entries ``attrs`` names, ``(attribute, index)`` pairs (which a saved file also
    rewrites as exact decimals); a slot that is no such product gives its own ``write``.  Its numbers
    (:meth:`values`) are its ``read()``, or else ``value``: for most slots, its one attribute's entries
    as the walk read them from ``element`` (to tell a set number from an absent one, and the file's
    from MuJoCo's default), kept, so that the table made later does not read each through MuJoCo's
    bindings again; for a body's mass and inertia, read from the compiled model with every other
    body's.  A slot with neither (a custom numeric's data) reads its attribute from ``element`` when
    asked.  A file has a slot per number: a function per slot would be five more objects each.
    """

    name: str
    path: str
    #: the numbers, where they are no entries of ``element``'s attribute, nor ``value`` (None: they are)
    read: Callable[[], tuple] | None
    attrs: tuple
    where: tuple
    dimension: object
    source: str
    parts: tuple = ()
    note: str = ""
    #: ``write(element, factor)``, where scaling is not the product of `attrs` (a refusal, or nothing)
    write: Callable[[object, float], None] | None = None
    #: the element whose attribute ``attrs`` names holds the numbers, where ``read`` is None
    element: object = None
    #: the numbers, where ``read`` is None: the element's entries as the walk read them, or computed ones;
    #: empty where ``element``'s attribute is read when asked
    value: tuple = ()

    def values(self) -> tuple:
        """The slot's numbers: read now, or as the walk read them (the spec is not changed after its walk)."""
        if self.read is not None:
            return self.read()
        if self.value or self.element is None:
            return self.value
        ((attr, index),) = self.attrs
        return _floats(getattr(self.element, attr))[index]

    def write_on(self, element, factor: float) -> None:
        """Scale this slot's number on `element`, the element found at its address in some spec."""
        if self.write is not None:
            self.write(element, factor)
            return
        for attr, index in self.attrs:
            value = getattr(element, attr)
            if np.ndim(value) == 0:
                setattr(element, attr, float(value) * factor)
                continue
            value = np.array(value, dtype=float)
            value[index] = value[index] * factor
            setattr(element, attr, value)


#: the spec's collections of elements a slot's address names (``spec.<name>[index]``)
_COLLECTIONS = (
    "meshes",
    "hfields",
    "bodies",
    "geoms",
    "frames",
    "sites",
    "cameras",
    "lights",
    "joints",
    "tendons",
    "actuators",
    "equalities",
    "pairs",
    "sensors",
    "numerics",
    "skins",
)
#: the spec's single elements, addressed by their kind
_SINGLES = ("option", "compiler", "stat")
#: the collections whose elements live in the body tree, each listed by a body in the spec's own order
_TREE = ("bodies", "geoms", "frames", "sites", "cameras", "lights", "joints")


def _listed(spec, collection: str) -> list:
    """``list(spec.<collection>)``, in the spec's order, in time linear in the size of the spec.

    MuJoCo's ``spec.geoms`` (and the other collections of the body tree) takes time quadratic in
    the number of elements: 0.5 s for 4,000 geoms.  A walk of the tree lists the same elements in
    the same order (each body's own elements, frames included, then its children depth first), in
    milliseconds; tests/test_engines_mjcf.py holds the two equal on every corpus file.  A spec whose
    compile failed refuses a body's children; its collections are MuJoCo's own listing.
    """
    if collection not in _TREE:
        return list(getattr(spec, collection))
    return _tree_listed(spec)[collection]


def _tree_listed(spec) -> dict[str, list]:
    """Every collection of the body tree, each as :func:`_listed` lists it, in one walk of the tree."""
    found: dict[str, list] = {collection: [] for collection in _TREE}
    owned = [found[collection].extend for collection in _TREE[1:]]  # each body's own elements, by collection
    stack = [spec.worldbody]
    try:
        while stack:
            body = stack.pop()
            found["bodies"].append(body)
            for collection, extend in zip(_TREE[1:], owned, strict=True):
                extend(getattr(body, collection))
            stack.extend(reversed(body.bodies))
    except ValueError:  # a body's children are refused while the spec holds a compiler error: MuJoCo's lists
        return {collection: list(getattr(spec, collection)) for collection in _TREE}
    return found


class _Elements:
    """The elements of one spec by address, each collection listed once."""

    def __init__(self, spec):
        self.spec, self.lists = spec, {}

    def get(self, where: tuple):
        if len(where) == 1:
            return getattr(self.spec, where[0])
        collection, index = where
        if collection not in self.lists:
            self.lists.update(
                _tree_listed(self.spec) if collection in _TREE else {collection: _listed(self.spec, collection)}
            )
        return self.lists[collection][index]

    @staticmethod
    def addresses(spec, lists: dict) -> dict[int, tuple]:
        """``id(element) -> address`` for the elements of `lists` (collection name -> the listed elements)."""
        return {id(item): (collection, i) for collection, items in lists.items() for i, item in enumerate(items)}


#: a body's numbers MuJoCo's compiler computes (from its geoms, unless the file gives them): its mass, its
#: inertia and the inertia's position, each with its dimension and the spec attributes a scaling multiplies
_BODY_COMPUTED = (
    ("mass", _M, (("mass", _EVERY),)),
    ("inertia", dim("M L^2"), (("inertia", _EVERY), ("fullinertia", _EVERY))),
    ("ipos", _L, (("ipos", _EVERY),)),
)


class _Walker:
    """Walk a spec's elements in a fixed order and list their dimensional attributes."""

    def __init__(self, mj, spec, model, path: str, *, warn: bool = False):
        self.mj, self.spec, self.model, self.path, self.warn = mj, spec, model, path, warn
        self.slots: list[Slot] = []
        self.names: set[str] = set()
        self.tendon_kinds: dict[str, JointKind] = {}  # tendon name -> its kind, found when it is walked
        self.inputs: list = []  # per actuator walked: its control's and its activation's dimensions
        self.input_powers: list = []  # per actuator walked: its parameters that carry its input, with the power
        self.targets: list = []  # per actuator walked: the dimensions of its length and its force
        self.computed_rows = None  # the compiled bodies' masses, inertias and their positions, when first asked
        self.inertia_from_geoms = False
        self.meshes = None  # the meshes' names, when first asked
        # every element listed once, kept alive, so that an element's id gives its address
        tree = _tree_listed(spec)
        self.lists = {c: tree[c] if c in _TREE else _listed(spec, c) for c in _COLLECTIONS}
        self.where_of = _Elements.addresses(spec, self.lists)

    def where(self, kind: str, elem) -> tuple:
        """The address of an element this walk visits (a collection and index, or its kind)."""
        return (kind,) if kind in _SINGLES else self.where_of[id(elem)]

    # -- helpers ------------------------------------------------------------------------------

    def label(self, kind: str, elem, index: int) -> tuple[str, str]:
        name = getattr(elem, "name", "") or ""
        ident = identifier(f"{kind}_{name}" if name else f"{kind}{index}")
        path = f"{kind} {name!r}" if name else f"{kind} #{index}"
        return ident, path

    def unique(self, ident: str) -> str:
        return unique_name(ident, self.names)

    def source(self, kind, elem, attr, values: tuple | None = None) -> str:
        """``"default"`` when the attribute holds MuJoCo's built-in default, else ``"file"``.

        `values` is the attribute already read as floats (:func:`_floats`), if it was.
        """
        default, default_has_nan = _default_floats(self.mj, kind, attr)
        if default is None:
            return "file"
        if values is None:
            values = _floats(getattr(elem, attr))
        if values == default:
            return "default"
        if not default_has_nan or len(values) != len(default):
            return "file"
        # NaN equals itself here (an unset value is NaN in both): tuples of distinct NaN objects compare unequal
        same = all(a == b or (a != a and b != b) for a, b in zip(values, default, strict=True))
        return "default" if same else "file"

    def add(self, kind, elem, ident, path, attr, dimension, index=_EVERY, suffix="", parts=(), note=""):
        """A slot for the entries `index` of `elem`'s `attr`, unless they are absent (or NaN: not set)."""
        form = _FORMS.get(
            (kind, attr, suffix) if index is _EVERY else (kind, attr, index.start, index.stop, index.step, suffix)
        ) or _form(self.mj, kind, attr, index, suffix)
        self.add_forms(kind, elem, ident, path, ((attr, index, dimension, *form),), parts, note)

    def add_each(self, kind, elem, ident, path, plan: tuple, read: dict | None = None):
        """:meth:`add` for each ``(attribute, dimension, entries, suffix)`` of `plan`, in its order.

        `plan` is a tuple kept for the life of the process (a module's constant, or one the functions
        ``_*_plan`` made once), whose forms are found once; `read` holds attributes already read.
        """
        known = _PLANS.get((kind, id(plan)))
        if known is None or known[0] is not plan:
            known = _PLANS[(kind, id(plan))] = (plan, _resolved(self.mj, kind, plan))
        self.add_forms(kind, elem, ident, path, known[1], read=read)

    def add_forms(self, kind, elem, ident, path, forms: tuple, parts=(), note="", read: dict | None = None):
        """The slots of `elem`'s entries that `forms` names, each an attribute, its entries, its dimension and
        its :class:`_Form`; absent entries (or NaN: not set) are skipped."""
        # called for nearly every number of a file: :meth:`unique`, :meth:`where`, :func:`_floats` and the
        # common cases of :meth:`source` are written out here, and an attribute several entries share is read
        # once, each call saved being a tenth of the time of a slot
        names, slots, where = self.names, self.slots, None
        if read is None:
            read = {}
        for attr, index, dimension, tail, tail_path, attrs, default, entrywise in forms:
            values = read.get(attr)
            if values is None:
                value = getattr(elem, attr)
                if value.__class__ is float:  # most numbers
                    values = (value,)
                elif value.__class__ is np.ndarray and value.dtype is _FLOAT64 and value.ndim == 1:  # most vectors
                    values = tuple(value.tolist())
                else:
                    values = _floats(value)
                read[attr] = values
            chosen = values[index]
            # absent, or NaN: "not set" (MuJoCo's mark of an unset vector is a NaN first entry: a geom's fromto
            # is nan 0 0 0 0 0 until the file gives one)
            if not chosen or values[0] != values[0] or (chosen[0] != chosen[0] and all(v != v for v in chosen)):
                continue
            name = f"{ident}_{tail}" if ident else tail
            if name in names:
                name = unique_name(name, names)
            else:
                names.add(name)
            if values == default:
                source = "default"
            elif not entrywise:
                source = "file"
            else:  # a NaN in the default after its first entry: entry by entry (:meth:`source`)
                source = self.source(kind, elem, attr, values)
            if where is None:
                where = (kind,) if kind in _SINGLES else self.where_of[id(elem)]
            slots.append(
                Slot(name, path + tail_path, None, attrs, where, dimension, source, parts, note, None, elem, chosen)
            )

    def add_set(self, kind, elem, ident, path, attr, dimension, index=_EVERY, suffix="", note=""):
        """:meth:`add` where the entries are set (nonzero): an attribute most files leave at zero, kept out
        of their tables."""
        if any(v != 0 for v in _floats(getattr(elem, attr))[index]):  # NaN is set, too
            self.add(kind, elem, ident, path, attr, dimension, index, suffix, note=note)

    def add_solref(self, kind, elem, ident, path, attr):
        ref = _floats(getattr(elem, attr))
        # time constant and damping ratio; or (negative) direct stiffness and damping of the reference acceleration
        self.add_each(kind, elem, ident, path, _solref_plan(attr, direct=ref[0] < 0), read={attr: ref})

    def add_solimp(self, kind, elem, ident, path, attr, violation):
        self.add_each(kind, elem, ident, path, _solimp_plan(attr, violation))

    def spring_and_drive(self, kind, elem, ident, path, joint_kind: JointKind):
        """A joint's or a tendon's spring and damper polynomials, armature, friction loss and force range."""
        # a polynomial shorter than three terms stops early (absent entries are skipped)
        self.add_each(kind, elem, ident, path, _spring_plan(joint_kind))

    def limit_and_friction_softness(self, kind, elem, ident, path, q):
        """The soft-constraint parameters of a joint's or a tendon's limit and of its friction loss."""
        plan, read = _softness(elem, q)
        self.add_each(kind, elem, ident, path, plan, read=read)

    def refuse(self, elem, path, attrs):
        """Fail on any of these attributes when it is set (nonzero): their scaling is not known yet."""
        for attr in attrs:
            value = getattr(elem, attr, None)  # None: no such attribute (a spec's numbers are never None)
            if value is not None and _set(value):
                self.fail(path, f"attribute {attr} is not supported by pitheorem's scaling yet")

    def mesh_names(self) -> set[str]:
        """The names of the spec's meshes, listed once (asked by every mesh geom)."""
        if self.meshes is None:
            self.meshes = {mesh.name for mesh in self.lists["meshes"]}
        return self.meshes

    def named_joint_kind(self, name) -> JointKind | None:
        """The kind of the joint of that name; None for a free joint (or no joint of that name)."""
        joint = self.spec.joint(name)
        return _joint_kind(self.mj, joint.type) if joint is not None else None

    def warning(self, element: str, reason: str):
        if self.warn:  # once, when the file is read; not again for each copy
            warn_unscalable(self.path, element, reason)

    def fail(self, element: str, reason: str):
        raise EngineModelError(self.path, element, reason)

    # -- elements -----------------------------------------------------------------------------

    def walk(self):
        spec, lists = self.spec, self.lists
        self.option()
        self.compiler()
        for i, mesh in enumerate(lists["meshes"]):
            ident, path = self.label("mesh", mesh, i)
            # MuJoCo multiplies the vertices by scale, whether they come from a file or from the element:
            # scale one of the two, never both (inline vertices scaled and scale scaled: s^2)
            if len(mesh.uservert):
                self.add("mesh", mesh, ident, path, "uservert", _L)
                # subtracted from the vertices before scale multiplies them: in the vertices' units
                self.add("mesh", mesh, ident, path, "refpos", _L)
            else:
                self.add(
                    "mesh",
                    mesh,
                    ident,
                    path,
                    "scale",
                    _L,
                    note="a dimensionless factor times the file's vertex units, a length",
                )
                # refpos is then in the file's vertex units, before scale: dimensionless, copied
        for i, hfield in enumerate(lists["hfields"]):
            ident, path = self.label("hfield", hfield, i)
            self.add("hfield", hfield, ident, path, "size", _L)
        for i, body in enumerate(lists["bodies"]):
            self.body(body, i)
        for i, geom in enumerate(lists["geoms"]):
            self.geom(geom, i)
        # frames, sites, cameras and lights: positions (and a site's size, a camera's sensor) are lengths
        for kind, items, attrs in (
            ("frame", lists["frames"], ("pos",)),
            ("site", lists["sites"], ("pos", "size", "fromto")),
            ("camera", lists["cameras"], ("pos",)),
            ("light", lists["lights"], ("pos",)),
        ):
            # the attributes this MuJoCo's elements of the kind have (a site's fromto is recent), all lengths
            plan = _lengths_plan(kind, attrs, items[0]) if items else ()
            for i, item in enumerate(items):
                ident, path = self.label(kind, item, i)
                self.add_each(kind, item, ident, path, plan)
                if kind == "light":  # 1 / (a0 + a1 d + a2 d^2): a1 per length, a2 per area
                    self.add_set(kind, item, ident, path, "attenuation", _L**-1, slice(1, 2), "_linear")
                    self.add_set(kind, item, ident, path, "attenuation", _L**-2, slice(2, 3), "_quadratic")
                if kind == "camera":  # the sensor of a camera given by its intrinsics (camprojection reads it)
                    for attr in ("focal_length", "principal_length", "sensor_size"):
                        self.add_set(kind, item, ident, path, attr, _L)
        for i, joint in enumerate(lists["joints"]):
            self.joint(joint, i)
        for i, tendon in enumerate(lists["tendons"]):
            self.tendon(tendon, i)
        for i, act in enumerate(lists["actuators"]):
            self.actuator(act, i)
        for i, eq in enumerate(lists["equalities"]):
            self.equality(eq, i)
        for i, pair in enumerate(lists["pairs"]):
            ident, path = self.label("pair", pair, i)
            self.friction("pair", pair, ident, path, 5)
            for attr in ("margin", "gap"):
                self.add("pair", pair, ident, path, attr, _L)
            self.add_solref("pair", pair, ident, path, "solref")
            self.add_solref("pair", pair, ident, path, "solreffriction")
            self.add_solimp("pair", pair, ident, path, "solimp", _L)
            self.add_set("pair", pair, ident, path, "adhesion", _FORCE)
        for i, sensor in enumerate(lists["sensors"]):
            self.sensor(sensor, i)
        for i, skin in enumerate(self.lists["skins"]):  # render-only: its vertices and bind positions are lengths
            ident, path = self.label("skin", skin, i)
            for attr in ("vert", "bindpos", "inflate"):
                self.add("skin", skin, ident, path, attr, _L)
        for kind, items in (("flex", spec.flexes), ("plugin", spec.plugins)):
            for i, item in enumerate(items):
                _, path = self.label(kind, item, i)
                self.fail(path, f"{kind} elements cannot be scaled by pitheorem yet; remove it or scale it by hand")
        self.numerics()
        return self.slots

    def numerics(self):
        """Custom numerics: scaled by the dimension a ``<text name="dimension:NAME">`` declares, else copied."""
        declared = {}
        for text in self.spec.texts:
            if text.name.startswith(DIMENSION_TEXT):
                where = f"text {text.name!r}"
                try:
                    declared[text.name[len(DIMENSION_TEXT) :]] = Dimension.parse(text.data)
                except PiTheoremError as err:
                    self.fail(where, f"{_first_line(str(err))} (data must be a dimension formula such as 'L T^-1')")
        names = {numeric.name for numeric in self.spec.numerics}
        for name in declared:
            if name not in names:
                self.fail(
                    f"text '{DIMENSION_TEXT}{name}'",
                    f"declares the dimension of a custom numeric {name!r} "
                    f"that the file does not have (its numerics: {', '.join(map(repr, sorted(names))) or 'none'})",
                )
        for i, numeric in enumerate(self.lists["numerics"]):
            ident, path = self.label("numeric", numeric, i)
            dimension = declared.get(numeric.name)
            if dimension is None:
                self.warning(
                    path,
                    "custom numeric data has no known dimension; copied unchanged (declare it "
                    f'with <text name="{DIMENSION_TEXT}{numeric.name}" data="L T^-1"/>, say)',
                )
                continue
            self.slots.append(
                Slot(
                    self.unique(ident),
                    f"{path} data",
                    None,
                    (("data", slice(None)),),
                    self.where("numeric", numeric),
                    dimension,
                    "file",
                    note="dimension declared in the file",
                    element=numeric,
                )
            )

    def option(self):
        opt = self.spec.option
        self.add("option", opt, "", "option", "timestep", _T)

        def read_g():
            return (float(np.linalg.norm(np.asarray(opt.gravity, dtype=float))),)

        self.names.add("g")
        self.slots.append(
            Slot(
                "g",
                "option gravity (magnitude)",
                read_g,
                (("gravity", slice(None)),),
                ("option",),
                dim("L T^-2"),
                self.source("option", opt, "gravity"),
                note="the direction is dimensionless",
            )
        )
        self.add("option", opt, "", "option", "wind", dim("L T^-1"))
        self.add("option", opt, "", "option", "density", dim("M L^-3"))
        self.add("option", opt, "", "option", "viscosity", dim("M L^-1 T^-1"))
        for attr in ("tolerance", "noslip_tolerance"):
            self.add(
                "option",
                opt,
                "",
                "option",
                attr,
                None,
                note="a solver's stopping rule relative to MuJoCo's own "
                "normalisation; no pure dimension, copied unchanged",
            )
        self.add("option", opt, "", "option", "ccd_tolerance", _L)
        self.add("option", opt, "", "option", "o_margin", _L)
        self.add_solref("option", opt, "", "option", "o_solref")
        self.add_solimp("option", opt, "", "option", "o_solimp", _L)
        self.add("option", opt, "", "option", "o_friction", _L, slice(2, 5), "_torsional_rolling")
        if np.any(np.asarray(opt.magnetic) != 0) and any(
            s.type == self.mj.mjtSensor.mjSENS_MAGNETOMETER for s in self.spec.sensors
        ):
            self.warning(
                "option magnetic",
                "the magnetic field has no dimension over M, L, T; magnetometer readings are copied unchanged",
            )
        self.add(
            "option",
            opt,
            "",
            "option",
            "sleep_tolerance",
            None,
            note="compared with velocities of every joint type (mixed); sleeping is off unless enabled",
        )
        stat = self.spec.stat
        for attr, d in (("meanmass", _M), ("meaninertia", dim("M L^2")), ("meansize", _L), ("extent", _L)):
            if not math.isnan(getattr(stat, attr)):
                self.add("stat", stat, "stat", "statistic", attr, d)
        if not math.isnan(stat.center[0]):
            self.add("stat", stat, "stat", "statistic", "center", _L)

    def compiler(self):
        comp = self.spec.compiler
        for attr, d in (("boundmass", _M), ("boundinertia", dim("M L^2"))):
            if getattr(comp, attr) > 0:
                self.add("compiler", comp, "compiler", "compiler", attr, d)
        if comp.settotalmass > 0:
            self.add("compiler", comp, "compiler", "compiler", "settotalmass", _M)

    def body(self, body, index):
        if index == 0:
            return  # the world
        ident, path = self.label("body", body, index)
        self.add("body", body, ident, path, "pos", _L)
        bid = body.id
        if bid < 0:
            bid = index
        if self.computed_rows is None:  # each compiled field listed once, as rows of floats
            model, self.computed_rows = self.model, []
            for compiled in ("body_mass", "body_inertia", "body_ipos"):
                rows = getattr(model, compiled).tolist()
                self.computed_rows.append([(row,) if isinstance(row, float) else tuple(row) for row in rows])
            self.inertia_from_geoms = (
                self.spec.compiler.inertiafromgeom == self.mj.mjtInertiaFromGeom.mjINERTIAFROMGEOM_TRUE
            )
        derived = not body.explicitinertial or self.inertia_from_geoms
        source, note = ("derived", "computed by MuJoCo from the geoms") if derived else ("file", "")
        where = self.where_of[id(body)]
        for (attr, d, spec_attrs), rows in zip(_BODY_COMPUTED, self.computed_rows, strict=True):
            name = self.unique(f"{ident}_{attr}")
            self.slots.append(
                Slot(name, f"{path} {attr}", None, spec_attrs, where, d, source, (), note, None, None, rows[bid])
            )

    def friction(self, kind, elem, ident, path, n):
        # sliding is dimensionless; torsional and rolling are torques per normal force: lengths
        first = 2 if n == 5 else 1
        self.add(kind, elem, ident, path, "friction", _L, slice(first, n), "_torsional_rolling")

    def geom(self, geom, index):
        ident, path = self.label("geom", geom, index)
        mj = self.mj
        if geom.type == mj.mjtGeom.mjGEOM_MESH and geom.meshname and geom.meshname not in self.mesh_names():
            self.fail(path, f"mesh {geom.meshname!r} is not defined")
        solref = _floats(geom.solref)
        self.add_each("geom", geom, ident, path, _geom_plan(direct=solref[0] < 0), read={"solref": solref})
        if _set(geom.surfacevel):  # a linear velocity, then an angular one
            self.add("geom", geom, ident, path, "surfacevel", dim("L T^-1"), slice(0, 3), "_linear")
            self.add("geom", geom, ident, path, "surfacevel", _T**-1, slice(3, 6), "_angular")
        self.add_set("geom", geom, ident, path, "adhesion", _FORCE)

    def joint(self, joint, index):
        mj = self.mj
        ident, path = self.label("joint", joint, index)
        kind = _joint_kind(mj, joint.type)
        self.add("joint", joint, ident, path, "pos", _L)
        self.refuse(joint, path, ("springyield",))
        if _set(joint.springdamper):  # a time constant and a damping ratio (dimensionless)
            self.add(
                "joint",
                joint,
                ident,
                path,
                "springdamper",
                _T,
                slice(0, 1),
                "_time",
                note="the compiler turns it and the damping ratio into stiffness and damping",
            )
        if kind is None:  # free joint: translation and rotation share each number
            for attr, parts, index_ in _FREE_JOINT_MIXED:
                self.add(
                    "joint",
                    joint,
                    ident,
                    path,
                    attr,
                    None,
                    index_,
                    parts=parts,
                    note="one number for the translational and the rotational coordinates",
                )
                if attr == "damping" and any(v != 0 for v in _floats(joint.damping)[1:]):
                    self.fail(path, "damping polynomial terms on a free joint mix dimensions; not supported")
            return
        # its coordinates, its spring and drive (:meth:`spring_and_drive`), and the softness of its limit and
        # friction loss (:meth:`limit_and_friction_softness`), in one plan
        softness, read = _softness(joint, kind.q)
        self.add_each("joint", joint, ident, path, _joint_plan(kind, softness), read=read)

    def tendon_kind(self, tendon) -> JointKind:
        """A spatial tendon measures a length; a fixed one the first joint's coordinate.  Found when the tendon
        was walked (before the actuators, equalities and sensors that ask, each naming it)."""
        return self.tendon_kinds[tendon.name]

    def wrapped_joints(self, tid: int, path) -> list[tuple[int, JointKind]]:
        """The entries of the compiled tendon `tid`'s path that are joints: (place in the path, joint kind) each.

        Read from the compiled model (the spec's ``tendon.path`` takes about 70 microseconds a tendon to
        read); a free joint would mix dimensions, and is refused.
        """
        model = self.model
        first, count = int(model.tendon_adr[tid]), int(model.tendon_num[tid])
        joint = int(self.mj.mjtWrap.mjWRAP_JOINT)
        types, objects = model.wrap_type[first : first + count].tolist(), model.wrap_objid[first : first + count]
        joints = []
        for k, kind in enumerate(types):
            if kind == joint:
                jk = _joint_kind(self.mj, model.jnt_type[objects[k]])
                if jk is None:
                    self.fail(path, "a fixed tendon over a free joint mixes dimensions")
                joints.append((k, jk))
        return joints

    def fixed_coefficient(self, coef: float, ident, path, k, dimension):
        """A fixed tendon's coefficient between joints of two types: MjSpec cannot rewrite it."""
        name = self.unique(f"{ident}_coef{k}")

        def write(_element, factor):
            if factor != 1.0:
                raise UnscalableParameterError(
                    name,
                    f"{path} joins a slide and a hinge joint, so its coefficient "
                    f"has dimension {dimension}, and MuJoCo's MjSpec cannot rewrite it",
                )

        self.slots.append(
            Slot(
                name,
                f"{path} joint #{k} coef",
                lambda: (coef,),
                (),
                ("option",),
                dimension,
                "file",
                write=write,
            )
        )

    def tendon(self, tendon, index):
        ident, path = self.label("tendon", tendon, index)
        # the path's joints and their kinds from the compiled model: the spec's path is slow to read
        tid = tendon.id if tendon.id >= 0 else index
        joints = self.wrapped_joints(tid, path)
        over_joints = bool(joints)
        kind = joints[0][1] if joints else JointKind.SLIDE
        self.tendon_kinds[tendon.name] = kind  # asked again by name (an unnamed tendon is never asked for)
        q = kind.q
        first = int(self.model.tendon_adr[tid])
        for k, jk in joints:  # a pulley's divisor is a dimensionless ratio, a site or geom no number
            if jk.q != q:  # coefficient converts this joint's coordinate into the tendon's length
                self.fixed_coefficient(float(self.model.wrap_prm[first + k]), ident, path, k, q / jk.q)
        self.add("tendon", tendon, ident, path, "range", q)
        self.add("tendon", tendon, ident, path, "margin", q)
        if np.all(np.asarray(tendon.springlength, dtype=float) == -1):
            # MuJoCo's sentinel: the spring's rest length is the tendon's length at qpos0, computed by the
            # compiler from the scaled geometry; scaling the -1 itself would turn it into a real length
            rest = tuple(float(v) for v in self.model.tendon_lengthspring[tid])
            self.slots.append(
                Slot(
                    self.unique(f"{ident}_springlength"),
                    f"{path} springlength",
                    lambda: rest,
                    (),
                    ("option",),
                    q,
                    "derived",
                    write=lambda _element, _factor: None,
                    note="springlength -1: computed by MuJoCo from the pose, scaled with it",
                )
            )
        else:
            self.add("tendon", tendon, ident, path, "springlength", q)
        self.spring_and_drive("tendon", tendon, ident, path, kind)
        if not over_joints:  # a spatial tendon's drawn width; MJCF gives a fixed tendon none (nor writes one back)
            self.add("tendon", tendon, ident, path, "width", _L)
        self.limit_and_friction_softness("tendon", tendon, ident, path, q)
        self.refuse(tendon, path, ("springyield",))

    def actuator_target(self, act, path, trn=None) -> tuple[object, object]:
        """Dimensions of the actuator's length and force (gear taken dimensionless).  `trn` is its
        transmission's type, if it was already read."""
        mj, spec = self.mj, self.spec
        if trn is None:
            trn = act.trntype
        if trn in (mj.mjtTrn.mjTRN_JOINT, mj.mjtTrn.mjTRN_JOINTINPARENT):
            joint = spec.joint(act.target)
            jtype = joint.type if joint is not None else None
            kind = _joint_kind(mj, jtype) if joint is not None else None
            if kind is None:
                self.fail(path, "an actuator on a free joint mixes forces and torques; not supported")
            if jtype == mj.mjtJoint.mjJNT_BALL and any(v != 0 for v in _floats(act.gear)[3:]):
                self.fail(path, "ball-joint gear beyond three components is not supported")
            return kind.q, kind.force
        if trn == mj.mjtTrn.mjTRN_TENDON:
            tendon = spec.tendon(act.target)
            kind = self.tendon_kind(tendon)
            return kind.q, kind.force
        if trn == mj.mjtTrn.mjTRN_SLIDERCRANK:
            return _L, _FORCE
        if trn == mj.mjtTrn.mjTRN_SITE:
            return _L, _FORCE
        if trn == mj.mjtTrn.mjTRN_BODY:
            return _L, _FORCE
        self.fail(path, f"transmission type {trn} is not known to pitheorem")
        raise AssertionError  # pragma: no cover

    def control_dimension(self, act, path, types=None):
        """Dimensions of ctrl, of the activation, and of the gain's unit input.

        `types` is the actuator's transmission, gain, bias and dynamics types, if they were already read.
        """
        mj = self.mj
        trn, gain, bias, dyn = types or (act.trntype, act.gaintype, act.biastype, act.dyntype)
        length, force = self.actuator_target(act, path, trn)
        biasprm = _floats(act.biasprm)
        if gain == mj.mjtGain.mjGAIN_FIXED:
            if trn == mj.mjtTrn.mjTRN_BODY and bias == mj.mjtBias.mjBIAS_NONE:
                ctrl = _ONE  # adhesion: MuJoCo's gain is the force, the input a nonnegative fraction of it
            elif bias == mj.mjtBias.mjBIAS_NONE or (biasprm[1] == 0 and biasprm[2] == 0):
                ctrl = force  # a motor: the input is the force
            elif biasprm[1] != 0:
                ctrl = length  # a position servo: the input is a target length
            else:
                ctrl = length / _T  # a velocity servo: a target velocity
        elif gain == mj.mjtGain.mjGAIN_AFFINE:
            ctrl = _ONE  # a damper-like gain: the input is a dimensionless fraction
        elif gain == mj.mjtGain.mjGAIN_MUSCLE:
            ctrl = _ONE  # a muscle's excitation, between 0 and 1
        else:
            self.fail(path, f"gain type {gain.name} is not supported by pitheorem's scaling")
        muscle = gain == mj.mjtGain.mjGAIN_MUSCLE
        if bias not in (mj.mjtBias.mjBIAS_NONE, mj.mjtBias.mjBIAS_AFFINE) and not (
            muscle and bias == mj.mjtBias.mjBIAS_MUSCLE
        ):
            self.fail(path, f"bias type {bias.name} is not supported by pitheorem's scaling")
        if dyn == mj.mjtDyn.mjDYN_MUSCLE:
            act_dim = _ONE  # the activation, between 0 and 1
        elif dyn == mj.mjtDyn.mjDYN_INTEGRATOR:
            act_dim = ctrl * _T
            if gain == mj.mjtGain.mjGAIN_FIXED and bias == mj.mjtBias.mjBIAS_AFFINE and biasprm[1] != 0:
                # intvelocity: the activation is the target length, so ctrl is a velocity
                ctrl, act_dim = length / _T, length
        elif dyn in (mj.mjtDyn.mjDYN_NONE, mj.mjtDyn.mjDYN_FILTER, mj.mjtDyn.mjDYN_FILTEREXACT):
            act_dim = ctrl
        else:
            self.fail(path, f"dynamics type {dyn.name} is not supported by pitheorem's scaling")
        return length, force, ctrl, act_dim

    def actuator(self, act, index):
        mj = self.mj
        ident, path = self.label("actuator", act, index)
        # each type read once: a read through MuJoCo's bindings and a comparison of its enums take a few
        # tenths of a microsecond each, asked of every actuator
        trn, gain, bias, dyn = types = act.trntype, act.gaintype, act.biastype, act.dyntype
        length, force, ctrl, act_dim = self.control_dimension(act, path, types)
        # the input of the force: the activation when there are dynamics, else ctrl
        dynamic = dyn != mj.mjtDyn.mjDYN_NONE
        driven = act_dim if dynamic else ctrl
        self.inputs.append((ctrl, act_dim if dynamic else None))
        self.targets.append((length, force))
        first = len(self.slots)
        if trn == mj.mjtTrn.mjTRN_SITE:
            self.add("actuator", act, ident, path, "gear", _L, slice(3, 6), "_torque")
        if trn == mj.mjtTrn.mjTRN_SLIDERCRANK:
            self.add("actuator", act, ident, path, "cranklength", _L)
        self.add("actuator", act, ident, path, "ctrlrange", ctrl)
        self.add("actuator", act, ident, path, "forcerange", force)
        self.add("actuator", act, ident, path, "actrange", act_dim)
        self.lengthrange(act, index, ident, path, length)
        self.add_set("actuator", act, ident, path, "delay", _T)
        if dyn in (mj.mjtDyn.mjDYN_FILTER, mj.mjtDyn.mjDYN_FILTEREXACT):
            self.add("actuator", act, ident, path, "dynprm", _T, slice(0, 1), "_timeconst")
        muscle = gain == mj.mjtGain.mjGAIN_MUSCLE
        if muscle:
            self.muscle(act, ident, path, force)
        elif gain == mj.mjtGain.mjGAIN_FIXED:
            self.add("actuator", act, ident, path, "gainprm", force / driven, slice(0, 1), "_gain")
        else:
            self.add("actuator", act, ident, path, "gainprm", force, slice(0, 1), "_gain")
            self.add("actuator", act, ident, path, "gainprm", force / length, slice(1, 2), "_length")
            self.add("actuator", act, ident, path, "gainprm", force * _T / length, slice(2, 3), "_velocity")
        if bias == mj.mjtBias.mjBIAS_AFFINE:
            self.add("actuator", act, ident, path, "biasprm", force, slice(0, 1), "_offset")
            self.add("actuator", act, ident, path, "biasprm", force / length, slice(1, 2), "_length")
            if _damping_ratio(mj, act):
                self.add(
                    "actuator",
                    act,
                    ident,
                    path,
                    "biasprm",
                    _ONE,
                    slice(2, 3),
                    "_dampratio",
                    note="a damping ratio: the compiler turns it into kv from kp and the joint's inertia",
                )
            else:
                self.add("actuator", act, ident, path, "biasprm", force * _T / length, slice(2, 3), "_velocity")
        self.refuse(act, path, ("damping", "armature", "ffrange", "velrange"))
        # the numbers the input passes through: its range and the activation's (an activation is the input
        # filtered or integrated), and the gain that turns it into a force (a muscle's input has no unit)
        powers = _MUSCLE_INPUT_POWERS if muscle else _INPUT_POWERS
        self.input_powers.append(
            {s.name: powers[s.attrs[0][0]] for s in self.slots[first:] if s.attrs and powers.get(s.attrs[0][0])}
        )

    def lengthrange(self, act, index, ident, path, length) -> None:
        """The actuator's length range: as the file gives it, or as MuJoCo's compiler found it.

        A range the file leaves out (0 0) is found by the compiler, for a muscle, by simulating the
        model with accelerations and times of its own (``<compiler><lengthrange>``), which no change
        of units reaches; a scaled copy is given the original's range times its factor instead, as
        the file could have said.
        """
        aid = act.id if act.id >= 0 else index
        found = self.model.actuator_lengthrange[aid].tolist()  # floats, not arrays: asked for every actuator
        if any(v != 0 for v in _floats(act.lengthrange)) or not any(v != 0 for v in found):
            self.add("actuator", act, ident, path, "lengthrange", length)
            return
        found = np.array(found, dtype=float)
        name = self.unique(f"{ident}_lengthrange")

        def write(element, factor, found=found):
            element.lengthrange = found * factor

        self.slots.append(
            Slot(
                name,
                f"{path} lengthrange",
                lambda: tuple(float(v) for v in found),
                (),
                self.where("actuator", act),
                length,
                "derived",
                write=write,
                note="found by MuJoCo's compiler; a scaled copy states it",
            )
        )

    def muscle(self, act, ident, path, force) -> None:
        """A muscle (MuJoCo's model): its peak force, its speed limit and its time constants.

        Its lengths are in units of the optimal length L0 and its forces in units of the peak force:
        the range, lmin, lmax, fpmax and fvmax are dimensionless.  A peak force left to MuJoCo
        (``force`` negative: ``scale`` over the actuator's ``acc0``) is refused, for ``acc0`` mixes
        the dimensions of the joints the muscle spans.
        """
        mj = self.mj
        for attr in ("gainprm", "biasprm"):  # MuJoCo's muscle reads both; the <muscle> element sets them alike
            prm = np.asarray(getattr(act, attr), dtype=float)
            if prm[2] < 0:
                self.fail(
                    path,
                    f"a muscle whose peak force MuJoCo derives from scale and acc0 ({attr}[2] = "
                    f'{float_text(prm[2])}) cannot be scaled: give its force explicitly (force="...")',
                )
            self.add("actuator", act, ident, path, attr, force, slice(2, 3), "_peak_force")
            self.add(
                "actuator", act, ident, path, attr, _T**-1, slice(6, 7), "_vmax", note="optimal lengths per unit time"
            )
        if act.dyntype == mj.mjtDyn.mjDYN_MUSCLE:
            self.add(
                "actuator",
                act,
                ident,
                path,
                "dynprm",
                _T,
                slice(0, 3),
                "_timeconst",
                note="activation, deactivation, smoothing width",
            )

    def equality(self, eq, index):
        mj = self.mj
        ident, path = self.label("equality", eq, index)
        t = eq.type
        if t == mj.mjtEq.mjEQ_CONNECT:
            self.add("equality", eq, ident, path, "data", _L, slice(0, 6), "_anchor")
            width = _L
        elif t == mj.mjtEq.mjEQ_WELD:
            self.add("equality", eq, ident, path, "data", _L, slice(0, 6), "_anchor_relpos")
            self.add(
                "equality",
                eq,
                ident,
                path,
                "data",
                _L,
                slice(10, 11),
                "_torquescale",
                note="converts the angular residual into a length",
            )
            width = _L
        elif t in (mj.mjtEq.mjEQ_JOINT, mj.mjtEq.mjEQ_TENDON):
            if t == mj.mjtEq.mjEQ_JOINT:
                k1 = self.named_joint_kind(eq.name1)
                k2 = self.named_joint_kind(eq.name2) if eq.name2 else k1
            else:
                k1 = self.tendon_kind(self.spec.tendon(eq.name1))
                k2 = self.tendon_kind(self.spec.tendon(eq.name2)) if eq.name2 else k1
            if k1 is None or k2 is None:
                self.fail(path, "an equality on a free joint is not supported")
            for i in range(5):  # q1 = c0 + c1 q2 + c2 q2^2 + ...
                self.add("equality", eq, ident, path, "data", k1.q * k2.q ** (-i), slice(i, i + 1), f"_polycoef{i}")
            width = k1.q
        else:
            self.fail(path, f"equality type {t.name} is not supported by pitheorem's scaling")
        self.add_solref("equality", eq, ident, path, "solref")
        self.add_solimp("equality", eq, ident, path, "solimp", width)

    def sensor_dimension(self, sensor, path):
        """The dimension of a sensor's reading (so of its cutoff and noise); None where it is not known."""
        known = _sensor_types(self.mj).get(int(sensor.type))
        if known is None:
            return None
        owner, what, rate = known
        if owner == "reading":
            return what
        if owner == "joint":
            kind = self.named_joint_kind(sensor.objname)
            if kind is None:
                return None
            q, force = kind.q, kind.force
        elif owner == "tendon":
            tendon = self.spec.tendon(sensor.objname)
            if tendon is None:
                return None
            kind = self.tendon_kind(tendon)
            q, force = kind.q, kind.force
        else:
            act = self.spec.actuator(sensor.objname)
            if act is None:
                return None
            q, force = self.actuator_target(act, path)
        if what == "force":
            return force
        return q / _T if rate else q

    def sensor(self, sensor, index):
        ident, path = self.label("sensor", sensor, index)
        self.add_set("sensor", sensor, ident, path, "delay", _T)
        self.add_set("sensor", sensor, ident, path, "interval", _T, note="the sampling period and its phase")
        d = self.sensor_dimension(sensor, path)
        busy = sensor.cutoff != 0 or _set(sensor.noise)
        if d is None:
            if busy:
                self.warning(
                    path,
                    f"sensor type {sensor.type.name}: its cutoff and noise have no "
                    "known dimension and are copied unchanged",
                )
            return
        self.add("sensor", sensor, ident, path, "cutoff", d)
        self.add("sensor", sensor, ident, path, "noise", d)


#: the dimension of a sensor's reading, by MuJoCo's name of its type: each of one dimension whatever it reads
_SENSOR_READINGS = {
    "mjSENS_TOUCH": _FORCE,
    "mjSENS_ACCELEROMETER": dim("L T^-2"),
    "mjSENS_VELOCIMETER": dim("L T^-1"),
    "mjSENS_GYRO": dim("T^-1"),
    "mjSENS_FORCE": _FORCE,
    "mjSENS_TORQUE": _TORQUE,
    "mjSENS_RANGEFINDER": _L,
    "mjSENS_FRAMEPOS": _L,
    "mjSENS_FRAMEQUAT": _ONE,
    "mjSENS_FRAMEXAXIS": _ONE,
    "mjSENS_FRAMEYAXIS": _ONE,
    "mjSENS_FRAMEZAXIS": _ONE,
    "mjSENS_FRAMELINVEL": dim("L T^-1"),
    "mjSENS_FRAMEANGVEL": dim("T^-1"),
    "mjSENS_FRAMELINACC": dim("L T^-2"),
    "mjSENS_FRAMEANGACC": dim("T^-2"),
    "mjSENS_SUBTREECOM": _L,
    "mjSENS_SUBTREELINVEL": dim("L T^-1"),
    "mjSENS_SUBTREEANGMOM": dim("M L^2 T^-1"),
    "mjSENS_BALLQUAT": _ONE,
    "mjSENS_BALLANGVEL": dim("T^-1"),
    "mjSENS_GEOMDIST": _L,
    "mjSENS_GEOMFROMTO": _L,
    "mjSENS_E_POTENTIAL": _TORQUE,
    "mjSENS_E_KINETIC": _TORQUE,
    "mjSENS_CLOCK": _T,
}

#: sensors of a joint's, a tendon's or an actuator's coordinate (``"q"``) or force, by MuJoCo's name of their
#: type: (what they read, the power of T^-1 on it)
_OWNED_SENSORS = {
    "joint": {
        "mjSENS_JOINTPOS": ("q", 0),
        "mjSENS_JOINTVEL": ("q", 1),
        "mjSENS_JOINTLIMITPOS": ("q", 0),
        "mjSENS_JOINTLIMITVEL": ("q", 1),
        "mjSENS_JOINTLIMITFRC": ("force", 0),
        "mjSENS_JOINTACTFRC": ("force", 0),
    },
    "tendon": {
        "mjSENS_TENDONPOS": ("q", 0),
        "mjSENS_TENDONLIMITPOS": ("q", 0),
        "mjSENS_TENDONVEL": ("q", 1),
        "mjSENS_TENDONLIMITVEL": ("q", 1),
        "mjSENS_TENDONLIMITFRC": ("force", 0),
        "mjSENS_TENDONACTFRC": ("force", 0),
    },
    "actuator": {"mjSENS_ACTUATORPOS": ("q", 0), "mjSENS_ACTUATORVEL": ("q", 1), "mjSENS_ACTUATORFRC": ("force", 0)},
}

_SENSOR_TYPES: dict[int, tuple] = {}


def _sensor_types(mj) -> dict[int, tuple]:
    """By the number of MuJoCo's sensor type: ``("reading", its dimension, 0)``, or the element that owns what
    it reads with what and the power of T^-1 (:data:`_OWNED_SENSORS`).  Found once: comparing MuJoCo's
    enums takes a tenth of a microsecond each, and a sensor would ask of 26."""
    if not _SENSOR_TYPES:
        kinds = mj.mjtSensor
        for name, d in _SENSOR_READINGS.items():
            _SENSOR_TYPES[int(getattr(kinds, name))] = ("reading", d, 0)
        for owner, table in _OWNED_SENSORS.items():
            for name, (what, rate) in table.items():
                _SENSOR_TYPES[int(getattr(kinds, name))] = (owner, what, rate)
    return _SENSOR_TYPES


_DEFAULT_FLOATS: dict = {}  # (kind, attr) -> the default as a tuple of floats, and whether it has a NaN
_DEFAULTS_CACHE: dict = {}


#: the power of an actuator's input in each of its numbers that carries it: its range, its activation's
#: range, and its gain (which turns it into a force); a muscle's gain carries none (its input has no unit)
_INPUT_POWERS = {"ctrlrange": 1, "actrange": 1, "gainprm": -1}
_MUSCLE_INPUT_POWERS = {"ctrlrange": 1, "actrange": 1, "gainprm": 0}


def _damping_ratio(mj, act) -> bool:
    """Whether a position servo's ``biasprm[2]`` is a damping ratio (``dampratio``), not ``-kv``.

    MuJoCo's compiler (``set0`` in ``engine_setconst.c``) reads a positive
    ``biasprm[2]`` of a position-like actuator (fixed gain, affine bias,
    ``biasprm[1] == -gainprm[0]``) as a damping ratio, and replaces it by
    ``-2 dampratio sqrt(kp m)``, ``m`` the inertia the actuator moves: a
    dimensionless number, which a change of units leaves alone.
    """
    gain, bias = _floats(act.gainprm), _floats(act.biasprm)
    return bool(act.gaintype == mj.mjtGain.mjGAIN_FIXED and bias[2] > 0 and bias[1] == -gain[0])


class _Form(NamedTuple):
    """What a slot of an attribute's entries takes from its kind, attribute, entries and suffix alone."""

    name: str  #: its name after the element's identifier: ``"solref_timeconst"``
    path: str  #: its path after the element's: ``" solref timeconst"``
    attrs: tuple  #: its ``attrs``, ``((attribute, entries),)``: one tuple for all the slots alike
    default: tuple | None  #: MuJoCo's built-in default of the attribute (:func:`_default_floats`)
    #: whether telling the default needs a comparison entry by entry, NaN equal to NaN: where the default
    #: holds a NaN after its first entry (a first NaN marks an unset attribute, whose slot is never made, so
    #: that a slot of one differs from it and is the file's)
    entrywise: bool


#: each form found, by kind, attribute, the entries' start, stop and step (a slice is no key before Python
#: 3.12; none for :data:`_EVERY`, the whole attribute, most of them), and suffix: a file asks the same few thousands of times, and a slot's ``attrs`` shared by all the
#: slots alike are objects fewer for Python's collector to scan when the walk ends (a file's slots outlive it)
_FORMS: dict[tuple, _Form] = {}


def _form(mj, kind: str, attr: str, index: slice, suffix: str) -> _Form:
    """The form of a slot of the entries `index` of a `kind`'s `attr`, with `suffix` (found once)."""
    key = (kind, attr, suffix) if index is _EVERY else (kind, attr, index.start, index.stop, index.step, suffix)
    if key not in _FORMS:
        tail_path = f" {attr}{suffix.replace('_', ' ')}"
        default, has_nan = _default_floats(mj, kind, attr)
        entrywise = has_nan and default[0] == default[0]
        _FORMS[key] = _Form(f"{attr}{suffix}", tail_path, ((attr, index),), default, entrywise)
    return _FORMS[key]


#: each plan's forms (:meth:`_Walker.add_each`), by the element's kind and the plan's identity: the plan kept
#: beside them, so that no other object takes its id
_PLANS: dict[tuple, tuple] = {}


def _resolved(mj, kind: str, plan: tuple) -> tuple:
    """A plan's entries, ``(attribute, dimension, entries, suffix)`` each, as :meth:`_Walker.add_forms` reads
    them: the attribute, its entries, its dimension and its form's fields."""
    return tuple((attr, index, d, *_form(mj, kind, attr, index, suffix)) for attr, d, index, suffix in plan)


#: the plans made once, by what they are made of: a dimension or a joint kind by its identity, kept beside its
#: plan (as :data:`_PLANS`), an attribute or a form by its value
_MADE: dict[tuple, tuple] = {}


def _made(key: tuple, keep, build) -> tuple:
    """The plan `build()` made once for `key`, which names `keep` by its id (None: `key` names no object by
    its id)."""
    known = _MADE.get(key)
    if known is None or known[0] is not keep:
        known = _MADE[key] = (keep, build())
    return known[1]


def _solref_plan(attr: str, *, direct: bool) -> tuple:
    """The slots of a solref attribute, in one of its two forms: a time constant (its damping ratio has no
    dimension) or, `direct` (negative), a stiffness and a damping of the reference acceleration."""

    def build():
        if direct:
            return ((attr, dim("T^-2"), slice(0, 1), "_stiffness"), (attr, dim("T^-1"), slice(1, 2), "_damping"))
        return ((attr, _T, slice(0, 1), "_timeconst"),)

    return _made(("solref", attr, direct), None, build)


def _solimp_plan(attr: str, violation) -> tuple:
    """A solimp attribute's width, a violation of the constraint: of its dimension (a length, or a joint's
    coordinate); its other entries have none."""
    return _made(("solimp", attr, id(violation)), violation, lambda: ((attr, violation, slice(2, 3), "_width"),))


def _spring_plan(kind: JointKind) -> tuple:
    """A joint kind's spring and damper polynomial terms, armature, friction loss and actuator force range."""

    def build():
        force = kind.force
        terms = []  # the i-th term of each polynomial: a force per coordinate^(i+1) (per its rate, for damping)
        for i in range(3):
            index, suffix = slice(i, i + 1), "" if i == 0 else f"_poly{i}"
            terms.append(("stiffness", kind.per(force, i + 1), index, suffix))
            terms.append(("damping", kind.per(force, i + 1, rate=1), index, suffix))
        armature = ("armature", kind.per(force, 1, rate=2), _EVERY, "")
        return (*terms, armature, ("frictionloss", force, _EVERY, ""), ("actfrcrange", force, _EVERY, ""))

    return _made(("spring", id(kind)), kind, build)


def _softness(elem, q) -> tuple[tuple, dict]:
    """The plan of a joint's or a tendon's limit and friction-loss softness (:func:`_softness_plan`), each
    solref in the form the element gives, and the solrefs as read."""
    read = {attr: _floats(getattr(elem, attr)) for attr in ("solref_limit", "solref_friction")}
    return _softness_plan(q, read["solref_limit"][0] < 0, read["solref_friction"][0] < 0), read


def _softness_plan(q, limit_direct: bool, friction_direct: bool) -> tuple:
    """A limit's and a friction loss's solref (in the form each says) and solimp width (in the coordinate `q`)."""
    return _made(
        ("softness", id(q), limit_direct, friction_direct),
        q,
        lambda: (
            *_solref_plan("solref_limit", direct=limit_direct),
            *_solimp_plan("solimp_limit", q),
            *_solref_plan("solref_friction", direct=friction_direct),
            *_solimp_plan("solimp_friction", q),
        ),
    )


def _joint_plan(kind: JointKind, softness: tuple) -> tuple:
    """A hinge's or a slide's range, reference positions and limit margin (in its coordinate), its spring and
    drive (:func:`_spring_plan`), and its `softness` (one of :func:`_softness_plan`'s)."""

    def build():
        coordinates = tuple((a, kind.q, _EVERY, "") for a in ("range", "ref", "springref", "margin"))
        return (*coordinates, *_spring_plan(kind), *softness)

    return _made(("joint", id(kind), id(softness)), softness, build)


#: a geom's numbers before its solref, in the walk's order: lengths, a mass, a density, and its friction's
#: torsional and rolling coefficients (torques per normal force: lengths; sliding is dimensionless)
_GEOM_PLAN = (
    ("size", _L, _EVERY, ""),
    ("pos", _L, _EVERY, ""),
    ("fromto", _L, _EVERY, ""),
    ("mass", _M, _EVERY, ""),
    ("density", dim("M L^-3"), _EVERY, ""),
    ("friction", _L, slice(1, 3), "_torsional_rolling"),
    ("margin", _L, _EVERY, ""),
    ("gap", _L, _EVERY, ""),
)


def _lengths_plan(kind: str, attrs: tuple, element) -> tuple:
    """The plan of `attrs`, each a length, that `element` (one of its `kind`) has."""
    return _made(("lengths", kind), None, lambda: tuple((a, _L, _EVERY, "") for a in attrs if hasattr(element, a)))


def _geom_plan(*, direct: bool) -> tuple:
    """A geom's numbers: :data:`_GEOM_PLAN`, then its solref in the form `direct` says, and its solimp's width."""
    return _made(
        ("geom", direct),
        _GEOM_PLAN,
        lambda: (*_GEOM_PLAN, *_solref_plan("solref", direct=direct), *_solimp_plan("solimp", _L)),
    )


def _set(value) -> bool:
    """Whether any entry of a spec attribute is nonzero; NaN is.

    Without numpy, whose ``np.any`` of a few numbers takes microseconds: asked of most elements.
    """
    if isinstance(value, float):  # most: one number, no tuple to build
        return value != 0
    if value.__class__ is np.ndarray:  # a Python number is true where it is nonzero, NaN included
        return any(value.ravel().tolist())
    return any(v != 0 for v in _floats(value))


def _floats(value) -> tuple:
    """A spec attribute's numbers as a tuple of Python floats (a scalar as one)."""
    if isinstance(value, float):  # most of a file's attributes: no array to build
        return (value,)
    if type(value) is np.ndarray and value.dtype is _FLOAT64 and value.ndim == 1:  # the others: no copy to make
        return tuple(value.tolist())
    return tuple(np.asarray(value, dtype=float).ravel().tolist())


_FLOAT64 = np.dtype(float)


def _default_floats(mj, kind: str, attr: str) -> tuple:
    """MuJoCo's built-in default of an attribute as :func:`_floats` (None where the kind has no such default),
    and whether it holds a NaN."""
    key = (kind, attr)
    if key not in _DEFAULT_FLOATS:
        default = _builtin_defaults(mj).get(kind)
        floats = _floats(getattr(default, attr)) if hasattr(default, attr) else None
        _DEFAULT_FLOATS[key] = (floats, floats is not None and any(v != v for v in floats))
    return _DEFAULT_FLOATS[key]


def _builtin_defaults(mj) -> dict:
    """One fresh element of each kind: MuJoCo's built-in defaults, to tell file values from defaults."""
    if not _DEFAULTS_CACHE:
        spec = mj.MjSpec()
        body = spec.worldbody.add_body()
        _DEFAULTS_CACHE.update(
            {
                "option": spec.option,
                "geom": body.add_geom(),
                "joint": body.add_joint(),
                "site": body.add_site(),
                "actuator": spec.add_actuator(),
                "tendon": spec.add_tendon(),
                "equality": spec.add_equality(),
                "pair": spec.add_pair(),
                "sensor": spec.add_sensor(),
                "camera": body.add_camera(),
                "light": body.add_light(),
                "body": body,
                "_spec": spec,
            }
        )
    return _DEFAULTS_CACHE


# -- the document ------------------------------------------------------------------------------

#: the kind of element each collection of a spec holds
_KINDS = {
    "meshes": "mesh",
    "hfields": "hfield",
    "bodies": "body",
    "geoms": "geom",
    "frames": "frame",
    "sites": "site",
    "cameras": "camera",
    "lights": "light",
    "joints": "joint",
    "tendons": "tendon",
    "actuators": "actuator",
    "equalities": "equality",
    "pairs": "pair",
    "sensors": "sensor",
    "numerics": "numeric",
}


#: (element kind, spec attribute) -> where MuJoCo's compiled model stores its entries: (first entry, how
#: many, compiled field, the field's column of the first entry) each
_STORED = {
    **{
        ("joint", a): ((0, 6, f"jnt_{b}", 0),)
        for a, b in (
            ("pos", "pos"),
            ("range", "range"),
            ("margin", "margin"),
            ("solref_limit", "solref"),
            ("solimp_limit", "solimp"),
            ("actfrcrange", "actfrcrange"),
        )
    },
    ("joint", "stiffness"): ((0, 1, "jnt_stiffness", 0), (1, 2, "jnt_stiffnesspoly", 0)),
    **{
        ("geom", a): ((0, 6, f"geom_{a}", 0),)
        for a in ("size", "pos", "margin", "gap", "friction", "solref", "solimp", "surfacevel", "adhesion")
    },
    ("site", "pos"): ((0, 3, "site_pos", 0),),
    ("site", "size"): ((0, 3, "site_size", 0),),
    **{("body", a): ((0, 3, f"body_{a}", 0),) for a in ("pos", "mass", "ipos", "inertia")},
    **{
        ("tendon", a): ((0, 5, f"tendon_{b}", 0),)
        for a, b in (
            ("range", "range"),
            ("margin", "margin"),
            ("solref_limit", "solref_lim"),
            ("solimp_limit", "solimp_lim"),
            ("solref_friction", "solref_fri"),
            ("solimp_friction", "solimp_fri"),
            ("frictionloss", "frictionloss"),
            ("armature", "armature"),
            ("actfrcrange", "actfrcrange"),
            ("width", "width"),
            ("springlength", "lengthspring"),
        )
    },
    ("tendon", "stiffness"): ((0, 1, "tendon_stiffness", 0), (1, 2, "tendon_stiffnesspoly", 0)),
    ("tendon", "damping"): ((0, 1, "tendon_damping", 0), (1, 2, "tendon_dampingpoly", 0)),
    **{
        ("actuator", a): ((0, 10, f"actuator_{a}", 0),)
        for a in (
            "gainprm",
            "biasprm",
            "dynprm",
            "ctrlrange",
            "forcerange",
            "actrange",
            "lengthrange",
            "gear",
            "cranklength",
            "delay",
        )
    },
    ("equality", "data"): ((0, 11, "eq_data", 0),),
    ("equality", "solref"): ((0, 2, "eq_solref", 0),),
    ("equality", "solimp"): ((0, 5, "eq_solimp", 0),),
    **{
        ("pair", a): ((0, 5, f"pair_{a}", 0),)
        for a in ("friction", "margin", "gap", "solref", "solreffriction", "solimp", "adhesion")
    },
    **{("sensor", a): ((0, 2, f"sensor_{a}", 0),) for a in ("noise", "cutoff", "delay", "interval")},
    ("camera", "pos"): ((0, 3, "cam_pos", 0),),
    ("camera", "sensor_size"): ((0, 2, "cam_sensorsize", 0),),
    ("light", "pos"): ((0, 3, "light_pos", 0),),
    ("light", "attenuation"): ((0, 3, "light_attenuation", 0),),
    ("hfield", "size"): ((0, 4, "hfield_size", 0),),
    **{
        ("option", a): ((0, 5, f"opt.{a}", 0),)
        for a in ("timestep", "wind", "density", "viscosity", "o_margin", "o_solref", "o_solimp", "o_friction")
    },
}


#: numbers MuJoCo's compiler computes from the file's, each of one dimension whatever the file: held against
#: the probe, they show a wrong dimension of the numbers they are computed from (a geom's size, density)
_COMPUTED = {
    "body_subtreemass": ("body", _M),
    "geom_rbound": ("geom", _L),
}


@dataclass(frozen=True)
class StoredCopy:
    """One number MuJoCo stores: the parameter it copies ("" for a number the compiler computes), its
    element and attribute, the compiled field, the flat index in that field, and its dimension."""

    parameter: str
    element: str
    attribute: str
    field: str
    index: int
    dimension: object


@dataclass(frozen=True)
class AttributeDimension:
    """One attribute's entries as the reader lists them: element kind and name, spec attribute, entries,
    their dimension (None: mixed), and the parameter's name."""

    kind: str
    element: str
    attribute: str
    entries: tuple[int, ...]
    dimension: object
    parameter: str


class MjcfDocument:
    """An MJCF file read through MuJoCo's parser: its spec, the numbers MuJoCo's compiler derives, its table.

    The format's half of a MuJoCo model: it reads the file (``MjSpec``),
    compiles it once for the numbers the compiler derives (masses and
    inertias from geoms, a tendon's rest length), lists every dimensional
    number with its address (:meth:`parameters`), writes a scaled copy by
    address (:meth:`scaled`) and saves it (:meth:`save`).  It never steps
    the model: :class:`pitheorem.engines.runners.mujoco.MujocoRunner` runs it.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.fileformats.mjcf import read_mjcf
    >>> read_mjcf(engines.example_path("pendulum.xml")).mjmodel.nq
    1
    """

    def __init__(self, spec, path: str, source_dir: Path | None, *, warn: bool = True, asset_dirs=None):
        self.spec = spec
        self.path = path
        self.source_dir = source_dir
        #: (kind, name) -> the folder an attached model's asset file is relative to
        self.asset_dirs = dict(asset_dirs or {})
        self._inputs = None  # the actuators' input dimensions, when first asked for
        try:
            with _muted():
                self.mjmodel = spec.compile()
                # a skin's file written into the spec, as this model holds it: scaled as lengths.  The model is
                # not compiled again: a skin is drawn, never simulated, and the second compile only normalised
                # its bone weights again (last bits of float32) and dropped its file's name (dm_control's dog:
                # 130 ms, as long as the file's first compile)
                _inline_skins(spec, self.mjmodel)
        except ValueError as err:
            raise _rejected(path, err, spec) from None
        # warn once, when the file is read; not again for each scaled copy, whose table is read only when
        # asked for (a verification runs a copy without listing its numbers)
        self._walked = self._walk(warn=True) if warn else None

    def _walk(self, warn: bool = False) -> list[Slot]:
        """The slots of the file, walked once; the actuators' input dimensions found on the way."""
        with _collection_paused():
            walker = _Walker(_mujoco(), self.spec, self.mjmodel, self.path, warn=warn)
            slots = walker.walk()
        if self._inputs is None:
            self._inputs = walker.inputs
        self._input_powers, self._actuator_targets = walker.input_powers, walker.targets
        return slots

    @property
    def _slots(self):
        if self._walked is None:
            self._walked = self._walk()
        return self._walked

    def parameters(self):
        # made on first use, from the numbers the walk kept: thousands of objects, and no collection finds
        # any of them free (:func:`_collection_paused`)
        slots = self._slots
        with _collection_paused():
            return [
                new_parameter(s.name, s.path, s.values(), s.dimension, s.source, "file", s.parts, s.note) for s in slots
            ]

    def settings(self) -> dict:
        return {}

    def stored_copies(self) -> list[StoredCopy]:
        """The numbers MuJoCo's compiled model stores as they are in the file: each with its parameter.

        An entry of an attribute the reader lists is matched with the entry of the compiled field
        that holds it (the table ``_STORED``) where the compiled number equals the file's (the compiler
        changed nothing: no ``fromto``, no ``dampratio``), or where the reader took the number from
        the compiled model itself (a body's mass and inertia computed from its geoms).  A probe
        copy of the model shows which power of the scale factor each stored number took, to be
        held against the parameter's dimension (:mod:`pitheorem.engines.verdicts.probes`).

        Examples
        --------
        >>> from pitheorem import engines
        >>> from pitheorem.engines.fileformats.mjcf import read_mjcf
        >>> copies = read_mjcf(engines.example_path("pendulum.xml")).stored_copies()
        >>> [(c.parameter, c.field, c.index) for c in copies if c.attribute == "mass"]
        [('body_arm_mass', 'body_mass', 1)]
        """
        elements, model, out = _Elements(self.spec), self.mjmodel, []
        slots = {slot.name: slot for slot in self._slots}
        for entry in self.attribute_dimensions():
            slot = slots[entry.parameter]
            element = elements.get(slot.where)
            values = _floats(getattr(element, entry.attribute))
            row = None if len(slot.where) == 1 else getattr(element, "id", -1)
            label = f"{entry.kind} {entry.element!r}" if entry.element else entry.kind
            for first, count, field, column in _STORED.get((entry.kind, entry.attribute), ()):
                holder, name = (model.opt, field[4:]) if field.startswith("opt.") else (model, field)
                stored = np.asarray(getattr(holder, name, ()), dtype=float)
                if stored.size == 0 or (row is not None and not 0 <= row < stored.shape[0]):
                    continue
                width = stored.size if row is None else stored[0].size
                for i in entry.entries:
                    col = i - first + column
                    if not first <= i < first + count or col >= width:
                        continue
                    flat = col if row is None else row * width + col
                    if slot.source == "derived" or stored.ravel()[flat] == values[i]:
                        out.append(StoredCopy(entry.parameter, label, entry.attribute, field, flat, slot.dimension))
        mj = _mujoco()
        for field, (kind, dimension) in _COMPUTED.items():  # numbers the compiler computes, of a fixed dimension
            stored = np.asarray(getattr(model, field), dtype=float)
            for row in range(stored.shape[0]):
                name = mj.mj_id2name(model, getattr(mj.mjtObj, f"mjOBJ_{kind.upper()}"), row)
                label = f"{kind} {name!r}" if name else f"{kind} #{row}"
                width = stored[0].size
                out.extend(StoredCopy("", label, field, field, row * width + col, dimension) for col in range(width))
        return out

    def attribute_dimensions(self) -> list[AttributeDimension]:
        """The dimension the reader gives each entry of each spec attribute it lists, element by element.

        Only slots that are entries of an attribute (not a number MuJoCo's compiler found and a copy
        states, nor a fixed tendon's coefficient) are listed.

        Examples
        --------
        >>> from pitheorem import engines
        >>> from pitheorem.engines.fileformats.mjcf import read_mjcf
        >>> entry = read_mjcf(engines.example_path("pendulum.xml")).attribute_dimensions()[0]
        >>> entry.kind, entry.attribute, entry.entries, str(entry.dimension)
        ('option', 'timestep', (0,), 'T')
        """
        elements, out = _Elements(self.spec), []
        for slot in self._slots:
            if not slot.attrs:
                continue
            element = elements.get(slot.where)
            kind = _KINDS.get(slot.where[0], slot.where[0])
            name = getattr(element, "name", "") or ""
            for attr, index in slot.attrs:
                size = len(_floats(getattr(element, attr)))
                entries = tuple(range(size)[index]) if isinstance(index, slice) else (int(index),)
                out.append(AttributeDimension(kind, name, attr, entries, slot.dimension, slot.name))
        return out

    def input_parameters(self) -> list[dict[str, int]]:
        """Per actuator: the parameters its input passes through, each with the power of the input in it.

        The control range and the activation's range (power 1) and the
        gains (power -1): what :meth:`scaled` with ``keep_inputs`` divides
        by the input's factor, so that every input keeps its value.
        """
        self._slots  # noqa: B018 (walked once, which finds them)
        return [dict(p) for p in self._input_powers]

    def scaled(self, factors, scaling, s, *, keep_inputs: bool = False) -> MjcfDocument:
        """A copy with each slot times its factor, and the keyframes scaled (when `scaling` is given).

        With `keep_inputs`, `factors` already keep every input (:meth:`input_parameters`); the
        keyframes' inputs and activations keep theirs too, a control range MuJoCo's compiler would
        derive from a scaled joint range (``inheritrange``) is stated as it is now, and a position
        servo's damping ratio, which MuJoCo reads only while the gain and the bias are equal and
        opposite, is written as the damping it compiles to, times its factor.
        """
        spec = self._portable_spec()
        elements = _Elements(spec)
        for slot in self._slots:
            factor = factors.get(slot.name, 1.0)
            if factor != 1.0:
                slot.write_on(elements.get(slot.where), factor)
        if keep_inputs and scaling is not None:
            self._keep_compiled_inputs(spec, scaling, s)
        if scaling is not None:
            self._scale_keyframes(spec, scaling, s, keep_inputs=keep_inputs)
        copy = MjcfDocument(spec, "", self.source_dir, warn=False, asset_dirs=self.asset_dirs)
        copy._scaled_from = (self, factors)  # for save's exact decimals, read only if the copy is saved
        copy._inputs = self._actuator_inputs()  # the same actuators and joints: the same dimensions
        copy._coordinates = self.coordinate_dimensions()
        return copy

    def in_units(self, units) -> MjcfDocument:
        """A copy whose spec records `units`, so that a saved file declares them (its numbers unchanged)."""
        import copy

        out = copy.copy(self)
        out.spec = self.spec.copy()
        record_units(out.spec, units)
        return out

    def recorded_units(self) -> dict[str, str] | None:
        """The units the file records (one pitheorem wrote), or None."""
        return recorded_units(self.spec, self.path)

    def save(self, path: Path, *, copy_assets: bool = False) -> None:
        """Write the model to `path`; its mesh, texture and height-field files named relative to it.

        A saved file and its assets move together: each asset is named by its
        path relative to the written file's folder (the file's ``meshdir`` and
        ``texturedir`` then name nothing), so copying the folder that holds both
        keeps the copy loading.  With `copy_assets` the asset files are copied
        into ``<stem>_assets`` beside the file
        (:func:`~pitheorem.engines.fileformats.assets.assets_folder`), and the
        file names the copies.
        """
        check_written_suffix(path, "mjcf")  # else it would not load again, or load as another format
        spec = self._portable_spec()
        if copy_assets:
            copies = AssetCopies(assets_folder(os.path.abspath(path)))
            for items in (spec.meshes, spec.hfields, spec.textures):
                for item in items:
                    file = getattr(item, "file", "") or ""
                    if file and Path(file).is_absolute():
                        item.file = str(copies.copy(file))
        # each scaled number as the decimal a person would write: the exact product of the original's
        # decimal and the factor's, rounded once (9.81 times 10 is 98.1, where the float product is
        # 98.10000000000001); at a power-of-two factor the very same double as in memory
        elements = _Elements(spec)
        for where, attr, index, original, factor in self._written():
            element = elements.get(where)
            if np.ndim(original) == 0:
                setattr(element, attr, exact_product(float(original), factor))
                continue
            value = np.array(getattr(element, attr), dtype=float)
            value[index] = [exact_product(v, factor) for v in np.atleast_1d(original[index])]
            setattr(element, attr, value)
        # MuJoCo's canonical, compiled output rounds to 6 digits (and turns fromto and degrees into
        # quaternions and radians); the uncompiled output keeps every value at full precision
        spec.compiler.savecompiled = False
        spec.compiler.savecanonical = False
        spec.meshdir = spec.texturedir = ""  # every asset's path is whole: no folder is put before it
        with _muted():
            spec.compile()
            text = spec.to_xml()
        Path(path).write_text(_relative_assets(spec, text, Path(os.path.abspath(path)).parent))

    def _written(self) -> list:
        """What :meth:`scaled` multiplied: (address, attribute, entries, the original's values, factor) each.

        Empty for a model read from a file.  The original's numbers are read from its spec, which no
        one changes, when the copy is saved (a copy that is only run never needs them).
        """
        source = getattr(self, "_scaled_from", None)
        if source is None:
            return []
        original, factors = source
        mine = _Elements(original.spec)  # the same elements in the same order as the copy's
        written = []
        for slot in original._slots:
            factor = factors.get(slot.name, 1.0)
            if factor != 1.0:
                element = mine.get(slot.where)
                written.extend(
                    (slot.where, attr, index, np.array(getattr(element, attr), dtype=float), factor)
                    for attr, index in slot.attrs
                )
        return written

    def _portable_spec(self):
        """A copy of the spec whose mesh, texture and hfield files load from any folder (absolute paths).

        Each asset's file is made absolute against the folder it was found in: the file's own
        ``meshdir`` or ``texturedir``, or, for an asset of a model brought in with ``<model>`` and
        ``<attach>``, that model's folders (:attr:`asset_dirs`).
        """
        spec = self.spec.copy()
        if self.source_dir is None:
            return spec
        folders = {"mesh": "meshdir", "hfield": "meshdir", "texture": "texturedir"}
        for kind, items in (("mesh", spec.meshes), ("hfield", spec.hfields), ("texture", spec.textures)):
            for item in items:
                file = getattr(item, "file", "") or ""
                if not file or Path(file).is_absolute():
                    continue
                base = self.asset_dirs.get((kind, item.name))
                if base is None:
                    base = self.source_dir / (getattr(self.spec, folders[kind], "") or "")
                # the folder as MuJoCo reads it: a model opened through a symbolic link finds its assets
                # beside the link, not beside the link's target
                item.file = os.path.normpath(os.path.abspath(base / file))
        return spec

    def _keep_compiled_inputs(self, spec, scaling, s) -> None:
        """What MuJoCo's compiler derives from a scaled copy's numbers and must not change with kept inputs.

        Each actuator whose input has a factor other than 1: its control range is stated as compiled
        (a range inherited from the joint's, ``inheritrange``, would follow the scaled joint), and a
        damping ratio is written as the compiled damping times its factor (a kept input makes gain and
        bias differ, and MuJoCo then reads the ratio as a damping).
        """
        mj, model = _mujoco(), self.mjmodel
        factor, _ = dimension_factors(scaling, s)
        self._slots  # noqa: B018 (the walk finds each actuator's dimensions)
        originals = _listed(self.spec, "actuators")
        for i, act in enumerate(_listed(spec, "actuators")):
            ctrl, _act = self._actuator_inputs()[i]
            if factor(ctrl) == 1.0:
                continue
            if model.actuator_ctrllimited[i]:  # the range as compiled, stated: nothing left to derive from the joint
                act.inheritrange = 0
                act.ctrlrange = np.array(model.actuator_ctrlrange[i], dtype=float)
                act.ctrllimited = mj.mjtLimited.mjLIMITED_TRUE
            if act.biastype == mj.mjtBias.mjBIAS_AFFINE and _damping_ratio(mj, originals[i]):
                length, force = self._actuator_targets[i]
                bias = np.array(act.biasprm, dtype=float)
                bias[2] = float(model.actuator_biasprm[i][2]) * factor(force * _T / length)
                act.biasprm = bias

    def _scale_keyframes(self, spec, scaling, s, *, keep_inputs: bool = False) -> None:
        """Scale the keyframes of `spec`, a copy of this model's, coordinate by coordinate.

        With `keep_inputs` each keyframe's inputs keep their values, and its activations the value
        they have in units of their input.
        """
        if not len(spec.keys):
            return
        model = self.mjmodel  # the copy has the same coordinates and actuators as this model

        factor, _ = dimension_factors(scaling, s)

        def factors(dims):
            return np.array([factor(d) for d in dims])

        _, dims = self.coordinate_dimensions()  # qpos, qvel, then the activations
        nq, nv = model.nq, model.nv
        fq, fv, fa = factors(dims[:nq]), factors(dims[nq : nq + nv]), factors(dims[nq + nv :])
        ft, fl = factor(_T), factor(_L)
        fctrl = factors(self.control_dimensions())
        if keep_inputs:  # an activation has its input's dimension times 1 or T: only that part is scaled
            acting = [factor(c) for c, a in self._actuator_inputs() if a is not None]
            fa = fa / np.array(acting) if len(acting) == len(fa) else fa
            fctrl = np.ones_like(fctrl)
        for key in spec.keys:
            if len(key.qpos) == model.nq:
                key.qpos = np.asarray(key.qpos) * fq
            if len(key.qvel) == model.nv:
                key.qvel = np.asarray(key.qvel) * fv
            if len(key.ctrl) == model.nu and model.nu:
                key.ctrl = np.asarray(key.ctrl) * fctrl
            if len(key.mpos):
                key.mpos = np.asarray(key.mpos) * fl
            key.time = key.time * ft
            if len(key.act) and model.na and len(fa) == len(key.act):
                key.act = np.asarray(key.act) * fa

    def coordinate_dimensions(self):
        """Names and dimensions of qpos and qvel entries, and of the activations (found once)."""
        if getattr(self, "_coordinates", None) is None:
            self._coordinates = self._find_coordinates()
        return self._coordinates

    def _find_coordinates(self):
        mj, m = _mujoco(), self.mjmodel
        names, dims = [], []
        for kind_label, rate in (("qpos", 0), ("qvel", 1)):
            rotation = [_ONE] * (4 if rate == 0 else 3)  # a quaternion, or an angular velocity
            for j in range(m.njnt):
                jname = mj.mj_id2name(m, mj.mjtObj.mjOBJ_JOINT, j) or f"joint{j}"
                jtype = int(m.jnt_type[j])
                if jtype == mj.mjtJoint.mjJNT_FREE:  # position, then rotation
                    per = [_L] * 3 + rotation
                elif jtype == mj.mjtJoint.mjJNT_BALL:
                    per = rotation
                else:
                    per = [_joint_kind(mj, jtype).q]
                for k, d in enumerate(per):
                    names.append(f"{kind_label}[{jname}]" + (f"[{k}]" if len(per) > 1 else ""))
                    dims.append(d * _T ** (-rate))
        acting = [i for i in range(m.nu) if m.actuator_dyntype[i] != 0]
        for i, d in zip(acting, self.activation_dimensions(), strict=True):
            names.append(f"act[{mj.mj_id2name(m, mj.mjtObj.mjOBJ_ACTUATOR, i) or i}]")
            dims.append(d)
        return names, dims

    def control_dimensions(self):
        return [ctrl for ctrl, _act in self._actuator_inputs()]

    def coordinate_inputs(self) -> list[int | None]:
        """Per coordinate: None for qpos and qvel, and the actuator of each activation (in its input's unit)."""
        names, _dims = self.coordinate_dimensions()
        acting = [i for i, (_ctrl, act) in enumerate(self._actuator_inputs()) if act is not None]
        return [None] * (len(names) - len(acting)) + acting

    def activation_dimensions(self):
        return [act for _ctrl, act in self._actuator_inputs() if act is not None]

    def _actuator_inputs(self):
        """Per actuator: the dimension of its control input and of its activation (None: no dynamics)."""
        if self._inputs is None:  # found on the walk of the file (a copy is given its original's)
            self._walked = self._walk()
        return self._inputs

    def timestep(self) -> float:
        return float(self.mjmodel.opt.timestep)


@contextmanager
def _muted():
    """MuJoCo's compiler warnings (deprecation notes on the user's own attributes) are not ours to raise."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


@contextmanager
def _collection_paused():
    """Python's cyclic garbage collector paused while a file is read, and restored after.

    Reading a file allocates a few objects per number (its slot, its address, its name) and frees
    none: each collection the allocations trigger finds nothing to free, and the full ones scan
    every object alive, the file's and the interpreter's, so that they took two thirds of the walk
    of a file of 2,000 bodies and grew faster than the file.  Cycles made meanwhile are collected
    once the collector runs again.  A collector the caller disabled stays disabled.
    """
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def _rejected(path: str, err: ValueError, spec=None) -> EngineModelError:
    """MuJoCo's refusal of a file or a spec, naming the element at fault."""
    return EngineModelError(path, _culprit(str(err), spec), _first_line(str(err)))


def spec_from_file(mj, path):
    """MuJoCo's spec of an MJCF file, whatever its suffix: ``.mjcf`` and ``.XML`` too.

    MuJoCo 4.0's ``MjSpec.from_file`` picks a decoder by the file's suffix and has
    one for ``.xml`` alone (``MjModel.from_xml_path`` reads them all).  Another
    suffix is read from the file's text, each ``<include>`` (nested ones too)
    handed over by its contents, and its folder set as the spec's, so that its
    assets are found as from the file.

    Examples
    --------
    >>> import mujoco, pathlib, tempfile
    >>> from pitheorem.engines.fileformats.mjcf import spec_from_file
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "body.xml").write_text('<mujocoinclude><body><geom size="0.1"/></body></mujocoinclude>')
    >>> _ = (folder / "model.mjcf").write_text('<mujoco><worldbody><include file="body.xml"/></worldbody></mujoco>')
    >>> spec_from_file(mujoco, folder / "model.mjcf").compile().nbody
    2
    """
    path = Path(path)
    if path.suffix == ".xml":
        return mj.MjSpec.from_file(str(path))
    text = path.read_text(encoding="utf-8", errors="replace")
    include, todo = {}, [text]
    while todo:  # each included file, found in the text of the files that include it
        for element in _included(todo.pop()):
            name = element.get("file")
            if name and name not in include and (path.parent / name).is_file():  # else MuJoCo names it
                include[name] = (path.parent / name).read_bytes()
                todo.append(include[name].decode("utf-8", errors="replace"))
    spec = mj.MjSpec.from_string(text, include=include)
    spec.modelfiledir = str(path.parent)
    return spec


def _included(text: str) -> list:
    """The ``<include>`` elements of an MJCF text (none in a text that is no XML: MuJoCo says what is wrong)."""
    import xml.etree.ElementTree as ET

    try:
        return list(ET.fromstring(text).iter("include"))
    except ET.ParseError:
        return []


def _first_line(text: str) -> str:
    """MuJoCo's reason, without the element line (named separately)."""
    lines = [ln.strip() for ln in text.strip().splitlines() if ln.strip() and not ln.strip().startswith("Element")]
    return lines[0] if lines else "MuJoCo could not load the model"


def _culprit(text: str, spec=None) -> str:
    """The element MuJoCo names in its message (``Element 'geom', line 7``), or the mesh whose file is missing."""
    for line in text.splitlines():
        if line.strip().startswith("Element"):
            return line.strip().rstrip(":")
    if spec is not None:
        for kind, items in (("mesh", spec.meshes), ("hfield", spec.hfields), ("texture", spec.textures)):
            for item in items:
                f = getattr(item, "file", "")
                if f and Path(f).name in text:
                    return f"{kind} {item.name!r}" if item.name else f"{kind} file {f!r}"
    return ""


#: the mass attributes of a spec that decide the masses and inertias MuJoCo's compiler checks
_MASS_ATTRIBUTES = {"bodies": ("mass", "inertia", "fullinertia"), "geoms": ("mass", "density")}


class _Unprobed:
    """A compiled probe seen as the refused model would be: its masses and inertias divided by the probe's factor."""

    def __init__(self, probe, factor: float):
        self._probe, self.body_mass, self.body_inertia = probe, probe.body_mass / factor, probe.body_inertia / factor

    def __getattr__(self, name):
        return getattr(self._probe, name)


class RefusedMjcfDocument(MjcfDocument):
    """An MJCF model MuJoCo refuses for a threshold (masses below ``mjMINVAL``), held as its parameter table.

    The table is read from a probe: a copy of the spec whose masses and
    densities are multiplied by a power of two (a change of the mass unit,
    exact), compiled, and its computed masses and inertias divided back.
    The model converts, fits and checks like any other; it does not run,
    and its converted copy runs once the new units clear the threshold.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from pitheorem import engines
    >>> speck = pathlib.Path(tempfile.mkdtemp()) / "speck.xml"
    >>> _ = speck.write_text('<mujoco><worldbody><body><freejoint/><geom size="1e-6" density="1000"/>'
    ...                      '</body></worldbody></mujoco>')
    >>> from pitheorem.engines.fileformats.mjcf import read_mjcf
    >>> document = read_mjcf(speck)
    >>> type(document).__name__, next(p.value for p in document.parameters() if p.name == "body1_mass")
    ('RefusedMjcfDocument', (4.18879020478639e-15,))
    """

    def __init__(self, spec, path: str, source_dir, refusal: EngineModelError, *, asset_dirs=None):
        mj = _mujoco()
        self.spec, self.path, self.source_dir = spec, path, source_dir
        self.asset_dirs, self._inputs, self.refusal = dict(asset_dirs or {}), None, refusal
        for power in (50, 100, 200):
            probe = spec.copy()
            for collection, attrs in _MASS_ATTRIBUTES.items():
                for element in getattr(probe, collection):
                    for attr in attrs:
                        setattr(
                            element,
                            attr,
                            np.asarray(getattr(element, attr), dtype=float) * 2.0**power
                            if np.ndim(getattr(element, attr))
                            else getattr(element, attr) * 2.0**power,
                        )
            try:
                with _muted():
                    self.mjmodel = probe.compile()
                break
            except ValueError:
                continue
        else:
            raise refusal
        walker = _Walker(mj, spec, _Unprobed(self.mjmodel, 2.0**power), path, warn=True)
        self._walked, self._inputs = walker.walk(), walker.inputs


def _attached_asset_dirs(mj, path: Path, root=None) -> dict:
    """For the models a file brings in with ``<model>`` and places with ``<attach prefix=...>``: the folder
    each of their mesh, hfield and texture files is relative to, by (kind, name as composed).

    `root` is the file's parsed root element where the caller has it; an attached file is parsed here.
    """
    import xml.etree.ElementTree as ET

    if root is None:
        try:
            root = ET.parse(path).getroot()
        except (ET.ParseError, OSError):
            return {}
    files = {m.get("name"): m.get("file") for m in root.iter("model") if m.get("name") and m.get("file")}
    out = {}
    for attach in root.iter("attach"):
        file = files.get(attach.get("model"))
        if file is None:
            continue
        child_path = (path.resolve().parent / file).resolve()
        try:
            child = spec_from_file(mj, child_path)
        except (ValueError, OSError):
            continue
        prefix = attach.get("prefix", "")
        folders = {"mesh": child.meshdir, "hfield": child.meshdir, "texture": child.texturedir}
        nested = _attached_asset_dirs(mj, child_path)
        for kind, items in (("mesh", child.meshes), ("hfield", child.hfields), ("texture", child.textures)):
            for item in items:
                base = nested.get((kind, item.name), child_path.parent / (folders[kind] or ""))
                out[(kind, prefix + item.name)] = base
    return out


#: the custom text in which a file pitheorem wrote records its units
UNITS_TEXT = "pitheorem:units"


def record_units(spec, units: Mapping[str, str]) -> None:
    """Write the units into an MJCF spec as its ``pitheorem:units`` custom text (replacing an older one).

    Examples
    --------
    >>> import mujoco
    >>> from pitheorem.engines.fileformats.mjcf import record_units, recorded_units
    >>> spec = mujoco.MjSpec()
    >>> record_units(spec, {"M": "g", "L": "mm", "T": "s"})
    >>> [(t.name, t.data) for t in spec.texts]
    [('pitheorem:units', 'M=g; L=mm; T=s')]
    """
    data = "; ".join(f"{b}={u}" for b, u in units.items())
    for text in spec.texts:
        if text.name == UNITS_TEXT:
            text.data = data
            return
    spec.add_text(name=UNITS_TEXT, data=data)


def recorded_units(spec, path: str) -> dict[str, str] | None:
    """The units an MJCF spec records (a file pitheorem wrote), or None.

    Raises
    ------
    EngineModelError
        For a record that is no list of ``BASE=UNIT`` items.

    Examples
    --------
    >>> import mujoco
    >>> from pitheorem.engines.fileformats.mjcf import recorded_units
    >>> spec = mujoco.MjSpec()
    >>> recorded_units(spec, "a.xml") is None
    True
    >>> _ = spec.add_text(name="pitheorem:units", data="L=cm; M=g")
    >>> recorded_units(spec, "a.xml")
    {'M': 'g', 'L': 'cm', 'T': 's'}
    """
    for text in spec.texts:
        if text.name == UNITS_TEXT:
            units = {}
            for item in text.data.split(";"):
                base, sep, unit = (part.strip() for part in item.partition("="))
                if not sep or base not in ("M", "L", "T"):
                    raise EngineModelError(
                        path, f"text {UNITS_TEXT!r}", f"data {text.data!r} is no list of units such as 'M=g; L=mm; T=s'"
                    )
                units[base] = unit
            from ..units import read_units

            return read_units(units, f"the units {path} records")
    return None


def _folder(path: Path) -> Path:
    """The folder MuJoCo reads a file's assets from: the file's own, a symbolic link not followed."""
    return Path(os.path.abspath(path)).parent


def _relative_assets(spec, text: str, folder: Path) -> str:
    """`text`, the XML of `spec`, with each asset's absolute path made relative to `folder`.

    The spec's asset paths are absolute (:meth:`MjcfDocument._portable_spec`); in the written
    file each is relative to the file's folder, so that the folder holding the file and its
    assets can move.
    """
    for items in (spec.meshes, spec.hfields, spec.textures):
        for item in items:
            file = getattr(item, "file", "") or ""
            if file and Path(file).is_absolute():
                relative = Path(os.path.relpath(file, folder)).as_posix()
                text = text.replace(f'file="{escape(file)}"', f'file="{escape(relative)}"')
    return text


def _inline_skins(spec, m) -> None:
    """Write each skin read from a file (``<skin file="dog.skn">``) into the spec, as MuJoCo compiled it.

    A skin is a render-only mesh bound to bodies; its vertices, bind
    positions and inflation are lengths.  MuJoCo's spec holds none of them
    for a skin read from a file (they are read when it compiles), so they are
    taken from the compiled model `m` and the file is no longer needed: the
    scaled copy holds them scaled, and travels without the ``.skn`` file.
    """
    for i, skin in enumerate(spec.skins):
        if not skin.file:
            continue
        va, vn = m.skin_vertadr[i], m.skin_vertnum[i]
        skin.vert = m.skin_vert[va : va + vn].ravel().tolist()
        if m.skin_texcoordadr[i] >= 0:
            ta = m.skin_texcoordadr[i]
            skin.texcoord = m.skin_texcoord[ta : ta + vn].ravel().tolist()
        fa, fn = m.skin_faceadr[i], m.skin_facenum[i]
        skin.face = m.skin_face[fa : fa + fn].ravel().tolist()
        ba, bn = m.skin_boneadr[i], m.skin_bonenum[i]
        skin.bodyname = [m.body(int(b)).name for b in m.skin_bonebodyid[ba : ba + bn]]
        skin.bindpos = m.skin_bonebindpos[ba : ba + bn].ravel().tolist()
        skin.bindquat = m.skin_bonebindquat[ba : ba + bn].ravel().tolist()
        starts, counts = m.skin_bonevertadr[ba : ba + bn], m.skin_bonevertnum[ba : ba + bn]
        skin.vertid = [m.skin_bonevertid[a : a + n].tolist() for a, n in zip(starts, counts, strict=True)]
        skin.vertweight = [m.skin_bonevertweight[a : a + n].tolist() for a, n in zip(starts, counts, strict=True)]
        skin.file = ""


def read_mjcf(path) -> MjcfDocument:
    """Read an MJCF file through MuJoCo's parser and compiler: its document.

    A file MuJoCo refuses for a threshold that units decide (masses below
    ``mjMINVAL``) is still read, as a :class:`RefusedMjcfDocument`, so that
    check, fit and convert can repair it.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    MjcfDocument

    Raises
    ------
    EngineModelError
        When MuJoCo rejects the file (the message names its element), or
        an element cannot be scaled.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.fileformats.mjcf import read_mjcf
    >>> [p.name for p in read_mjcf(engines.example_path("pendulum.xml")).parameters()][:2]
    ['timestep', 'g']
    """
    mj = _mujoco()
    path = Path(path)
    with _collection_paused():  # its parse allocates an object per element and frees none
        root = check_model_file(
            path, nonnegative=NONNEGATIVE
        )  # MuJoCo drops damping="nan" and keeps "inf"; a non-UTF-8 byte breaks its names
    try:
        spec = spec_from_file(mj, path)
    except ValueError as err:
        raise _rejected(str(path), err) from None
    asset_dirs = _attached_asset_dirs(mj, path, root)
    try:
        return MjcfDocument(spec, str(path), _folder(path), asset_dirs=asset_dirs)
    except EngineModelError as err:
        if "mjMINVAL" not in err.reason:
            raise
        # refused for a threshold that units decide: still a table, so check, fit and convert can repair it
        return RefusedMjcfDocument(spec, str(path), _folder(path), err, asset_dirs=asset_dirs)
