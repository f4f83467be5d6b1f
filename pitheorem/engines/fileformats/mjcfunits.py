"""MuJoCo's own table of MJCF units, and the MJCF reader held against it attribute by attribute.

Since 3.16 MuJoCo publishes the physical dimension of every MJCF attribute,
generated from its schema, as ``doc/XMLunits.rst`` in its wheel: per
component, with ``A`` for angles, ``Q`` and ``F`` for a joint's (or
tendon's, actuator's) coordinate and generalised force, and the two forms
of ``solref``.  This module reads that table (:func:`read_units_table`),
builds for each attribute a small model that sets it, nonzero, on one
element named ``probe`` (so attributes no corpus file uses are covered),
reads the model with :func:`~pitheorem.engines.fileformats.mjcf.read_mjcf`
and compares the dimension the reader gives each component with the
table's (:func:`check_attribute`).  Angles are dimensionless here, as
radians are everywhere in pitheorem; ``Q`` and ``F`` are a hinge's
(1 and M L^2 T^-2) and a slide's (L and M L T^-2), both tried.

An attribute the reader neither reads with the table's dimension nor
refuses by name (an ``EngineModelError``) is listed in :data:`EXCEPTIONS`,
the one table of exceptions, with the reason.
"""

from __future__ import annotations

import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ...dimensions import Dimension

__all__ = ["EXCEPTIONS", "AttributeCheck", "UnitsRow", "check_attribute", "read_units_table"]

#: attributes of MuJoCo's table the reader does not read with the table's dimension, and why
EXCEPTIONS: dict[str, str] = {
    "compiler/lengthrange/timeconst": "settings of the compiler's search for an actuator's length range: "
    "the reader states the range found, scaled, in the copy, so the search never runs on it",
    "compiler/lengthrange/timestep": "as compiler/lengthrange/timeconst",
    "compiler/lengthrange/inttotal": "as compiler/lengthrange/timeconst",
    "compiler/lengthrange/interval": "as compiler/lengthrange/timeconst",
    "option/sleep_tolerance": "compared with the velocities of every joint type (m/s and rad/s alike): "
    "a mixed number, listed without a dimension and copied; sleeping is off unless enabled",
    "visual/global/ipd": "drawing only: the visual settings are copied unchanged",
    "visual/map/stiffness": "drawing only (the mouse perturbation's spring): copied unchanged",
    "visual/map/stiffnessrot": "drawing only (the mouse perturbation's spring): copied unchanged",
    "visual/map/force": "drawing only (the length of a drawn force): copied unchanged",
    "visual/map/torque": "drawing only (the length of a drawn torque): copied unchanged",
    "asset/skin/inflate": "skins are refused as a whole (EngineModelError naming the skin)",
    "asset/skin/vertex": "skins are refused as a whole (EngineModelError naming the skin)",
    "skin/bone/bindpos": "skins are refused as a whole (EngineModelError naming the skin)",
    "replicate/offset": "expanded by MuJoCo's parser into copies of the body, whose positions are read",
    "body/flexcomp/spacing": "flexes are refused as a whole (EngineModelError naming the flex)",
    "body/flexcomp/radius": "flexes are refused as a whole",
    "body/flexcomp/mass": "flexes are refused as a whole",
    "body/flexcomp/inertiabox": "flexes are refused as a whole",
    "body/flexcomp/scale": "flexes are refused as a whole",
    "body/flexcomp/pos": "flexes are refused as a whole",
    "flexcomp/edge/solref": "flexes are refused as a whole",
    "flexcomp/edge/solimp": "flexes are refused as a whole",
    "flexcomp/edge/stiffness": "flexes are refused as a whole",
    "flexcomp/edge/damping": "flexes are refused as a whole",
    "flexcomp/elasticity/young": "flexes are refused as a whole",
    "flexcomp/elasticity/shear": "flexes are refused as a whole",
    "flexcomp/elasticity/damping": "flexes are refused as a whole",
    "flexcomp/elasticity/thickness": "flexes are refused as a whole",
    "flexcomp/elasticity/sectionsize": "flexes are refused as a whole",
    "flexcomp/contact/friction": "flexes are refused as a whole",
    "flexcomp/contact/solref": "flexes are refused as a whole",
    "flexcomp/contact/solimp": "flexes are refused as a whole",
    "flexcomp/contact/margin": "flexes are refused as a whole",
    "flexcomp/contact/gap": "flexes are refused as a whole",
    "deformable/flex/radius": "flexes are refused as a whole",
    "deformable/flex/vertex": "flexes are refused as a whole",
    "deformable/flex/nodecoord": "flexes are refused as a whole",
    "flex/edge/stiffness": "flexes are refused as a whole",
    "flex/edge/damping": "flexes are refused as a whole",
    "equality/flex/solref": "flexes (and their equalities) are refused as a whole",
    "equality/flexstrain/solref": "flexes (and their equalities) are refused as a whole",
    "keyframe/key/time": "keyframes are states, not parameters: a copy's keyframes are scaled coordinate by "
    "coordinate (time by T) when it is written, outside the parameter table",
    "keyframe/key/mpos": "keyframes are states, not parameters: mocap positions are scaled by L when a copy "
    "is written, outside the parameter table",
    "actuator/cylinder/ctrlrange": "MjSpec keeps no trace of the <cylinder> shortcut: the reader sees a "
    "fixed-gain filter actuator and, as for every fixed gain, gives the input the force's dimension and the "
    "gain (here the area) none; a consistent choice that scales the copy alike (force = area * pressure)",
    "actuator/cylinder/area": "as actuator/cylinder/ctrlrange: the area is the fixed gain, read as dimensionless",
    "actuator/cylinder/diameter": "as actuator/cylinder/ctrlrange: the diameter only sets the area, the gain",
    "actuator/plugin/delay": "plugin actuators need a plugin library; not generated",
    "actuator/plugin/forcerange": "plugin actuators need a plugin library; not generated",
    "actuator/plugin/lengthrange": "plugin actuators need a plugin library; not generated",
    "actuator/plugin/damping": "plugin actuators need a plugin library; not generated",
    "actuator/plugin/armature": "plugin actuators need a plugin library; not generated",
    "actuator/plugin/cranklength": "plugin actuators need a plugin library; not generated",
    "body/camera/ipd": "drawing only (the distance between the eyes of a stereo view), nonzero by MuJoCo's "
    "default in every camera: copied unchanged",
    "body/light/bulbradius": "drawing only (the size of a light's bulb for soft shadows), nonzero by default: "
    "copied unchanged",
    "body/light/range": "drawing only (how far a light's shadows are computed), nonzero by default: copied unchanged",
    "actuator/motor/ctrlrange": "MuJoCo's table takes a motor's input dimensionless and its gear as the force; "
    "the reader takes every gear dimensionless (it is also the length's transmission ratio), so the input "
    "carries the force: a consistent choice that scales the copy alike (force = gear * ctrl)",
    "option/tolerance": "a solver's stopping rule relative to MuJoCo's own normalisation by a mean inertia: "
    "listed as a mixed number (no pure dimension) and copied unchanged, as the table's 1 would be",
    "option/noslip_tolerance": "as option/tolerance",
    "sensor/camprojection/delay": "a camera projection's reading is in pixels; sensors of no known dimension are "
    "copied unchanged with a warning",
    "sensor/camprojection/interval": "as sensor/camprojection/delay",
    "sensor/tactile/delay": "tactile sensors need a mesh with a plugin; not generated",
    "sensor/tactile/interval": "tactile sensors need a mesh with a plugin; not generated",
}


@dataclass(frozen=True)
class UnitsRow:
    """One attribute of MuJoCo's table: its path and its dimension per component, in the table's symbols.

    ``forms`` holds one tuple of component texts per alternative (``solref`` has two), or is empty
    where the table says *other* or *varies* (no dimension).
    """

    attribute: str
    forms: tuple[tuple[str, ...], ...]

    @property
    def dimensional(self) -> bool:
        """Whether some component has a dimension other than 1 (angles counted as 1)."""
        return any(_symbols(c) - {"A", "1"} for form in self.forms for c in form)

    @property
    def uses_joint(self) -> bool:
        """Whether the dimension depends on the joint's type (``Q`` or ``F``)."""
        return any(_symbols(c) & {"Q", "F"} for form in self.forms for c in form)


def _symbols(component: str) -> set[str]:
    return {tok[0] for tok in re.findall(r"[A-Z1](?:\^\{-?\d+\})?", component)}


def read_units_table(text: str) -> list[UnitsRow]:
    """The rows of MuJoCo's ``XMLunits.rst``, in the file's order.

    Parameters
    ----------
    text : str
        The file's text.

    Returns
    -------
    list of UnitsRow

    Examples
    --------
    >>> from pitheorem.engines.fileformats.mjcfunits import read_units_table
    >>> text = '''   * - :ref:`option/timestep<option-timestep>`
    ...      - :math:`T`
    ...    * - :ref:`body/geom/solref<body-geom-solref>`
    ...      - :math:`T,\\\\ 1` or :math:`T^{-2},\\\\ T^{-1}`
    ...    * - :ref:`option/magnetic<option-magnetic>`
    ...      - *other*'''
    >>> [(r.attribute, r.forms) for r in read_units_table(text)]  # doctest: +NORMALIZE_WHITESPACE
    [('option/timestep', (('T',),)), ('body/geom/solref', (('T', '1'), ('T^{-2}', 'T^{-1}'))),
     ('option/magnetic', ())]
    """
    rows, attribute = [], None
    for line in text.splitlines():
        ref = re.match(r"\s*\* - :ref:`([^<`]+)<", line)
        if ref:
            attribute = ref.group(1)
            continue
        cell = re.match(r"\s*- (.*)", line)
        if cell and attribute is not None:
            forms = tuple(
                tuple(c.strip().replace("\\,", " ").replace("  ", " ") for c in re.split(r",\\\s", math))
                for math in re.findall(r":math:`([^`]*)`", cell.group(1))
            )
            rows.append(UnitsRow(attribute, forms))
            attribute = None
    return rows


def component_dimension(text: str, q: Dimension, force: Dimension) -> Dimension:
    """One component's dimension: ``A`` is 1 (radians), ``Q`` and ``F`` the joint's coordinate and force.

    Examples
    --------
    >>> from pitheorem import Dimension
    >>> from pitheorem.engines.fileformats.mjcfunits import component_dimension
    >>> str(component_dimension("F T^{2} Q^{-1}", Dimension.parse("L"), Dimension.parse("M L T^-2")))
    'M'
    >>> str(component_dimension("A T^{-1}", Dimension.parse("1"), Dimension.parse("M L^2 T^-2")))
    'T^-1'
    """
    out = Dimension.parse("1")
    for symbol, power in re.findall(r"([A-Z1])(?:\^\{(-?\d+)\})?", text):
        base = {"Q": q, "F": force, "A": Dimension.parse("1"), "1": Dimension.parse("1")}.get(symbol)
        out = out * ((Dimension.parse(symbol) if base is None else base) ** int(power or 1))
    return out


# -- the models: one element named "probe" that sets the attribute ---------------------------------

#: file attribute -> (spec attribute, the offset of the attribute's first component in it), per element
_ALIASES = {
    "joint": {
        "solreflimit": ("solref_limit", 0),
        "solimplimit": ("solimp_limit", 0),
        "solreffriction": ("solref_friction", 0),
        "solimpfriction": ("solimp_friction", 0),
        "actuatorfrcrange": ("actfrcrange", 0),
    },
    "inertial": {"pos": ("ipos", 0), "diaginertia": ("inertia", 0)},
    "camera": {"focal": ("focal_length", 0), "principal": ("principal_length", 0), "sensorsize": ("sensor_size", 0)},
    "connect": {"anchor": ("data", 0)},
    "weld": {"anchor": ("data", 0), "relpose": ("data", 3), "torquescale": ("data", 10)},
    "position": {"kp": ("gainprm", 0), "kv": ("biasprm", 2), "timeconst": ("dynprm", 0)},
    "velocity": {"kv": ("gainprm", 0)},
    "intvelocity": {"kp": ("gainprm", 0), "kv": ("biasprm", 2)},
    "damper": {"kv": ("gainprm", 2)},
    "muscle": {"force": ("gainprm", 2), "vmax": ("gainprm", 6), "timeconst": ("dynprm", 0)},
    "adhesion": {"gain": ("gainprm", 0)},
    "cylinder": {
        "timeconst": ("dynprm", 0),
        "bias": ("biasprm", 0),
        "area": ("gainprm", 0),
        "diameter": ("gainprm", 0),
    },
}
_ALIASES["spatial"] = _ALIASES["fixed"] = _ALIASES["joint"]

#: the values an attribute is given where distinct increasing positive numbers would not do
_VALUES = {
    "solimp": "0.9 0.95 0.002 0.5 2",
    "friction": "0.8 0.02 0.003 0.004 0.005",
    "relpose": "0.1 0.2 0.3 1 0 0 0",
    "springdamper": "0.2 0.7",
    "axisangle": "0 0 1 0.5",
    "center": "0.1 0.2 0.3",
    "gravity": "0.1 0.2 -9.8",
    "attenuation": "1 0.2 0.3",
    "fullinertia": "0.4 0.5 0.6 0.01 0.02 0.03",
    "interval": "0.2 -0.1",
}

_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"

#: for a sensor type: the attributes that attach it to an object of the generated model
_SENSOR_OBJECTS = {
    **dict.fromkeys(("touch", "accelerometer", "velocimeter", "gyro", "force", "torque", "magnetometer"), 'site="s1"'),
    "rangefinder": 'site="s1"',
    **dict.fromkeys(("jointpos", "jointvel", "jointactuatorfrc", "jointlimitpos", "jointlimitvel"), 'joint="j"'),
    "jointlimitfrc": 'joint="j"',
    **dict.fromkeys(("tendonpos", "tendonvel", "tendonactuatorfrc"), 'tendon="t"'),
    **dict.fromkeys(("tendonlimitpos", "tendonlimitvel", "tendonlimitfrc"), 'tendon="t"'),
    **dict.fromkeys(("actuatorpos", "actuatorvel", "actuatorfrc"), 'actuator="a"'),
    **dict.fromkeys(("ballquat", "ballangvel"), 'joint="jb"'),
    **dict.fromkeys(
        (
            "framepos",
            "framequat",
            "framexaxis",
            "frameyaxis",
            "framezaxis",
            "framelinvel",
            "frameangvel",
            "framelinacc",
            "frameangacc",
        ),
        'objtype="site" objname="s1"',
    ),
    **dict.fromkeys(("subtreecom", "subtreelinvel", "subtreeangmom"), 'body="b"'),
    "insidesite": 'site="s1" objtype="body" objname="b"',
    **dict.fromkeys(("distance", "normal", "fromto"), 'geom1="g" geom2="g2"'),
    "contact": 'geom1="g"',
    **dict.fromkeys(("e_potential", "e_kinetic", "clock"), ""),
}


def _values(attr: str, count: int, negative_solref: bool, element: str = "") -> str:
    if attr == "actuatorfrcrange":
        return "-0.1 0.2"
    if element == "orientation" and attr == "forcerange":  # bounds a norm: from 0
        return "0 0.2"
    if attr.startswith("solref") or attr == "o_solref":
        return "-100 -10" if negative_solref else "0.03 0.9"
    for key, text in _VALUES.items():
        if attr == key or attr.startswith(key) or attr == f"o_{key}":
            return " ".join(text.split()[:count])
    return " ".join(f"{0.1 * (i + 1):g}" for i in range(count))


def _model(attribute: str, values: str, joint: str) -> tuple[str, str, str]:
    """The text of a model that sets `attribute` (a path of the table) to `values` on an element named
    "probe"; the element's kind as the reader's collections name it, and the element's own tag."""
    parts = attribute.split("/")
    element, attr = parts[-2], parts[-1]
    setting = f'{attr}="{values}"'
    if attr == "delay":  # a delay needs a history of samples
        setting += ' nsample="4"'
    limited = 'range="-1 1"' if joint != "ball" else 'range="0 1"'
    body = (
        f'<body name="b" pos="0 0 1"><joint name="j" type="{joint}" {limited}/>'
        '<geom name="g" type="box" size=".1 .1 .1" mass="1"/><site name="s1" pos="0 0 .1"/>'
        '<site name="s2" pos="0 .1 0"/>{inner}</body>'
        '<body name="b2" pos="1 0 1"><joint name="jb" type="ball"/><geom name="g2" size=".1" mass="1"/></body>'
    )
    tendon = '<tendon><fixed name="t" range="-1 1"><joint joint="j" coef="1"/></fixed></tendon>'
    actuator = '<actuator><motor name="a" joint="j"/></actuator>'
    head, inner, after = "", "", tendon + actuator
    kind = element
    if parts[:2] == ["compiler", "lengthrange"]:
        head, kind = f"<compiler><lengthrange {setting}/></compiler>", "compiler"
    elif parts[0] in ("compiler", "option", "statistic"):
        head = f"<{parts[0]} {setting}/>"
        kind = {"statistic": "stat"}.get(parts[0], parts[0])
    elif element == "mesh":
        head = f'<asset><mesh name="probe" file="tet.obj" {setting}/></asset>'
    elif element == "hfield":
        head = f'<asset><hfield name="probe" nrow="2" ncol="2" {setting}/></asset>'
    elif parts[:1] == ["body"] and len(parts) == 2:
        inner, kind = f'<body name="probe" {setting}><geom size=".1"/></body>', "body"
    elif element == "frame":
        inner = f'<frame name="probe" {setting}><geom size=".1"/></frame>'
    elif element == "inertial":
        extra = "" if attr in ("diaginertia", "fullinertia") else 'diaginertia="1 1 1"'
        extra += "" if attr == "mass" else ' mass="1"'
        extra += "" if attr == "pos" else ' pos="0 0 0"'
        inner, kind = f'<body name="probe"><inertial {extra} {setting}/></body>', "body"
    elif element == "joint" and parts[0] == "body":
        inner = f'<body name="bp"><joint name="probe" type="{joint}" {setting}/><geom size=".1" mass="1"/></body>'
    elif element == "geom":
        shape = 'type="capsule" size=".1"' if attr == "fromto" else 'type="box" size=".1 .2 .3"'
        shape = "" if attr == "size" else shape
        inner = f'<geom name="probe" {shape} {setting}/>'
    elif element == "site":
        inner = f'<site name="probe" {"type=" + chr(34) + "capsule" + chr(34) if attr == "fromto" else ""} {setting}/>'
    elif element in ("camera", "light"):
        extra = 'resolution="100 100"' if element == "camera" else ""
        extra += ' sensorsize="0.1 0.1"' if attr in ("focal", "principal") else ""
        inner = f'<{element} name="probe" {extra} {setting}/>'
    elif element == "pair":
        after += f'<contact><pair name="probe" geom1="g" geom2="g2" {setting}/></contact>'
    elif element == "spatial":
        kind = "tendon"
        spatial = f'<spatial name="probe" {setting}><site site="s1"/><site site="s2"/></spatial>'
        after = tendon.replace("<tendon>", "<tendon>" + spatial) + actuator
    elif element == "fixed":
        kind = "tendon"
        after = (
            f'<tendon><fixed name="t" range="-1 1"><joint joint="j" coef="1"/></fixed>'
            f'<fixed name="probe" {setting}><joint joint="j" coef="1"/></fixed></tendon>' + actuator
        )
    elif parts[0] == "equality":
        target = {
            "connect": 'body1="b"' + ("" if attr == "anchor" else ' anchor="0 0 0"'),
            "weld": 'body1="b"',
            "joint": 'joint1="j"',
            "tendon": 'tendon1="t"',
        }[element]
        after += f'<equality><{element} name="probe" {target} {setting}/></equality>'
        kind = "equality"
    elif parts[0] == "actuator":
        if attr == "cranklength":
            target = 'cranksite="s1" slidersite="s2"'
        elif element == "adhesion":
            target = 'body="b"'
        elif element == "orientation":
            target = 'site="s1" refsite="s2"'
        else:
            target = 'joint="j"'
        need = {
            "muscle": ' force="10" lengthrange="0.1 0.2"',
            "cylinder": ' area="0.1"',
            "pid": ' kp="1"',
            "dcmotor": ' motorconst="1" resistance="1"',
        }
        extra = " ".join(a for a in re.findall(r'\w+="[^"]*"', need.get(element, "")) if not a.startswith(f"{attr}="))
        extra = f" {extra}" if extra else ""
        extra += ' ctrlrange="0 1"' if element in ("muscle", "adhesion", "damper") and attr != "ctrlrange" else ""
        after = (
            tendon
            + f'<actuator><motor name="a" joint="j"/><{element} name="probe" {target}{extra} {setting}/></actuator>'
        )
        kind = "actuator"
    elif parts[0] == "sensor":
        objects = _SENSOR_OBJECTS[element]
        after += f'<sensor><{element} name="probe" {objects} {setting}/></sensor>'
        kind = "sensor"
    else:
        raise KeyError(attribute)
    text = f'<mujoco><compiler angle="radian"/>{head}<worldbody>{body.replace("{inner}", inner)}</worldbody>{after}</mujoco>'
    return text, kind, element


@dataclass(frozen=True)
class AttributeCheck:
    """What the reader made of one attribute of MuJoCo's table on its generated model.

    ``status`` is ``"read"`` (every component with the table's dimension, some dimensional),
    ``"dimensionless"`` (the table gives no dimension but 1 and the reader none either),
    ``"refused"`` (an ``EngineModelError`` naming the element), ``"exception"`` (listed in
    :data:`EXCEPTIONS`), ``"no dimension"`` (*other* or *varies*) or ``"disagrees"``, with
    ``problems`` saying how.
    """

    attribute: str
    status: str
    problems: tuple[str, ...] = ()


def check_attribute(row: UnitsRow, folder: Path | None = None) -> AttributeCheck:
    """Set the attribute of `row`, nonzero, on a generated model; compare the reader's dimensions.

    Parameters
    ----------
    row : UnitsRow
        One row of :func:`read_units_table`.
    folder : Path, optional
        Where to write the model (a temporary folder by default).

    Returns
    -------
    AttributeCheck

    Examples
    --------
    >>> from pitheorem.engines.fileformats.mjcfunits import UnitsRow, check_attribute
    >>> check_attribute(UnitsRow("body/joint/range", (("Q",),))).status
    'read'
    >>> check_attribute(UnitsRow("body/geom/surfacevel", (("L T^{-1}",) * 3 + ("A T^{-1}",) * 3,))).status
    'read'
    """
    from ..enginemodel import EngineModelError
    from .mjcf import read_mjcf

    if row.attribute in EXCEPTIONS:
        return AttributeCheck(row.attribute, "exception", (EXCEPTIONS[row.attribute],))
    if not row.forms:
        return AttributeCheck(row.attribute, "no dimension")
    if folder is None:
        folder = Path(tempfile.mkdtemp(prefix="pitheorem-units-"))
    (folder / "tet.obj").write_text(_OBJ)
    problems: list[str] = []
    refused = []
    one, force = Dimension.parse("1"), Dimension.parse("M L T^-2")
    joints = (("hinge", one, force * Dimension.parse("L")), ("slide", Dimension.parse("L"), force))
    for joint, q, f in joints if row.uses_joint else joints[:1]:
        for n_form, form in enumerate(row.forms):
            attr = row.attribute.rsplit("/", 1)[1]
            element = row.attribute.split("/")[-2]
            count = len(form) if len(form) > 1 else _ARITY_OF.get(f"{element}/{attr}", _arity(attr))
            values = _values(attr, count, negative_solref=n_form == 1, element=element)
            try:
                text, kind, element = _model(row.attribute, values, joint)
            except KeyError:
                if not row.dimensional:
                    return AttributeCheck(row.attribute, "not generated", ("dimensionless; no model generated",))
                return AttributeCheck(row.attribute, "disagrees", ("no model is generated for this element",))
            if row.attribute.startswith("tendon/spatial"):
                q, f = Dimension.parse("L"), force
            path = folder / "probe.xml"
            path.write_text(text)
            try:
                document = read_mjcf(path)
            except EngineModelError as err:
                if not _by_the_reader(err):  # MuJoCo's own refusal of the value
                    if row.dimensional:
                        problems.append(f"{joint}, {values!r}: MuJoCo rejects the generated model: {err.reason}")
                    else:
                        return AttributeCheck(row.attribute, "not generated", (f"MuJoCo rejects it: {err.reason}",))
                    continue
                refused.append(f"{joint}: {err}")
                continue
            spec_attr, offset = _ALIASES.get(element, {}).get(attr, (attr, 0))
            read = _read_dimensions(document, kind, spec_attr)
            expected = [component_dimension(c, q, f) for c in form]
            if len(form) == 1:  # one symbol for every component given
                expected = expected * count
            for i, want in enumerate(expected):
                got = read.get(offset + i, "absent")
                if got == "absent":
                    if want != one:
                        problems.append(f"{joint}, {values!r}: component {i} ({want}) not read")
                elif got != want:
                    problems.append(f"{joint}, {values!r}: component {i} read as {got}, the table says {want}")
    if refused and not problems and len(refused) == (2 if row.uses_joint else 1) * len(row.forms):
        return AttributeCheck(row.attribute, "refused", tuple(refused))
    if refused:
        problems.extend(f"refused: {r}" for r in refused)
    if problems:
        return AttributeCheck(row.attribute, "disagrees", tuple(problems))
    return AttributeCheck(row.attribute, "read" if row.dimensional else "dimensionless")


#: the number of values an attribute takes on one element, where it differs from the attribute's elsewhere
_ARITY_OF = {"hfield/size": 4, "muscle/timeconst": 2}


def _by_the_reader(err) -> bool:
    """Whether a refusal is the reader's (a number it cannot scale), not MuJoCo's (a value it rejects)."""
    return any(words in err.reason for words in ("pitheorem", "not supported", "cannot be scaled", "mix", "not known"))


def _arity(attr: str) -> int:
    return {
        "pos": 3,
        "size": 3,
        "fromto": 6,
        "range": 2,
        "ctrlrange": 2,
        "forcerange": 2,
        "actrange": 2,
        "lengthrange": 2,
        "actuatorfrcrange": 2,
        "velrange": 2,
        "ffrange": 2,
        "posrange": 2,
        "gravity": 3,
        "wind": 3,
        "center": 3,
        "scale": 3,
        "refpos": 3,
        "anchor": 3,
        "inertia": 3,
        "fullinertia": 6,
        "diaginertia": 3,
        "springlength": 2,
        "sensorsize": 2,
        "principal": 2,
        "focal": 2,
        "attenuation": 3,
        "offset": 3,
        "mpos": 3,
        "quat": 4,
        "xyaxes": 6,
        "zaxis": 3,
        "euler": 3,
        "rgba": 4,
        "interval": 2,
    }.get(attr, 1)


def _read_dimensions(document, kind: str, spec_attr: str) -> dict[int, object]:
    """Component index -> the dimension the reader gave it, on the element named "probe" (or the single one)."""
    out = {}
    for entry in document.attribute_dimensions():
        if entry.kind != kind or entry.attribute != spec_attr:
            continue
        if entry.element not in ("probe", "") and kind not in ("option", "compiler", "stat"):
            continue
        for index in entry.entries:
            out[index] = entry.dimension
    return out
