"""PyBullet as a runner: a URDF document with the settings PyBullet runs it with, scaled copies, runs.

The file is loaded by PyBullet itself (so its defaults apply: inertia
computed from the collision shapes, default collision margins); the
numbers it states are the URDF format's (:mod:`pitheorem.engines.fileformats.urdf`).

What a URDF cannot hold goes into :meth:`~pitheorem.engines.EngineModel.settings`:
gravity (PyBullet's own default is 0; the model runs with 9.81 m s^-2
unless told otherwise), the time step, ``setPhysicsEngineParameter``
values of dimension (``contactSlop``, ``restitutionVelocityThreshold``,
``solverResidualThreshold``) and per-link ``changeDynamics`` values
(collision margin, rolling and spinning friction, joint speed cap, the
multibody damping) and joint springs (URDF has none: pitheorem applies the
torque ``-k (q - q_0)`` before every step, as a PyBullet user does by hand).
PyBullet's default velocity motors on every joint
are switched off (``VELOCITY_CONTROL`` with ``force=0``) in every run, as
the PyBullet guide advises for torque control: their impulse cap has no
documented value to scale.  A spherical joint's motor, which pulls it back
to rest, is switched off too (``POSITION_CONTROL`` with no gain and no
force); its coordinates are its quaternion and angular velocity, and it
takes three torques.  A link whose file states no mass has PyBullet's own
(1 kg): the table lists it, and a scaled copy sets it with
``changeDynamics(mass=...)``.

The multibody damping ``linearDamping`` (default 0.04) enters as ``m v (d +
d |v|)``: one number that is a rate (T^-1) and an inverse length (L^-1)
at once, a mixed number; likewise ``angularDamping`` (T^-1 and 1).  The
split-impulse threshold (-0.04, a length) cannot be set from Python;
``useSplitImpulse=0`` removes it.
"""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path
from types import MappingProxyType

import numpy as np

from pitheorem.formatting.pieces import float_text, names_text

from ...errors import InvalidRequestError, UnscalableParameterError
from ...exact import read_number
from ...simulation import nudged
from ..constants import hidden_constants
from ..enginemodel import EngineModel, EngineModelError
from ..fileformats.urdf import UrdfDocument, joint_kind, read_urdf, refuse_units
from ..packages import engine_module, quiet_stdout
from ..parameters import Parameter, attribute_text, dim, identifier

__all__ = ["MAX_LINKS", "SCENE_OPTIONS", "PybulletRunner", "load_urdf", "scene_option"]

_ONE, _L, _T, _M = dim("1"), dim("L"), dim("T"), dim("M")

#: PyBullet's defaults and their dimensions: the hidden-constant catalogue is their one home
_BULLET = {c.name: c for c in hidden_constants("pybullet")}

#: PyBullet's engine parameters with a dimension: the ``setPhysicsEngineParameter`` name, the
#: catalogue's constant (its default and dimension) and what it does
ENGINE_PARAMETERS = (
    ("contactSlop", "bullet_contact_slop", "allowed penetration before contacts push back"),
    ("restitutionVelocityThreshold", "bullet_restitution_velocity_threshold", "impacts slower than this do not bounce"),
    (
        "solverResidualThreshold",
        "bullet_solver_residual_threshold",
        "the solver stops below this squared velocity residual",
    ),
)
#: the multibody damping of every link: one number acting with two dimensions, the catalogue's two
#: constants (the same default)
MIXED_DAMPING = (
    ("linearDamping", (("rate", "bullet_linear_damping_k1"), ("per_length", "bullet_linear_damping_k2"))),
    ("angularDamping", (("rate", "bullet_angular_damping_k1"), ("per_radian", "bullet_angular_damping_k2"))),
)

#: The scene a URDF model runs in: the keyword options of :func:`load_urdf` and of
#: :func:`pitheorem.engines.load`, and the command line's ``--scene NAME=VALUE``.  Each name has a
#: kind ("flag": true or false; "number": one number, not negative; "point": three numbers) and a
#: default (``damping`` None: PyBullet's own, which mixes dimensions).
SCENE_OPTIONS = {
    "fixed_base": ("flag", False),
    "ground": ("flag", False),
    "split_impulse": ("flag", True),
    "g": ("number", 9.81),
    "damping": ("number", None),
    "base_position": ("point", (0.0, 0.0, 0.0)),
}


def _pybullet():
    return engine_module("pybullet")


#: the suffixes of a spherical joint's coordinates: its quaternion (PyBullet's order), its angular velocity
_QUATERNION, _VECTOR = (":x", ":y", ":z", ":w"), (":x", ":y", ":z")


def _axes(jtype: str, axes: tuple[str, ...]) -> tuple[str, ...]:
    """A joint's coordinate suffixes: `axes` for a spherical joint, one unnamed coordinate for any other."""
    return axes if jtype == "spherical" else ("",)


def _link_parameter(link: str, setting: str) -> str:
    """The parameter name of a link's ``changeDynamics`` setting, as the table and a scaled copy know it."""
    return f"{identifier(f'link_{link}')}_{setting}"


def _joint_speed_parameter(joint: str) -> str:
    """The parameter name of a joint's ``maxJointVelocity``."""
    return identifier(f"joint_{joint}_maxJointVelocity")


def _spring_parameters(joint: str) -> tuple[str, str]:
    """The parameter names of a joint spring's stiffness and rest position."""
    return identifier(f"joint_{joint}_spring_stiffness"), identifier(f"joint_{joint}_spring_rest")


#: the element of the cause "these links keep another collision margin than the one set" (ignored_settings)
_MARGINS = "changeDynamics(collisionMargin)"

#: the element of the cause "these joints are set another velocity clamp than the body's one" (ignored_settings)
_CLAMPS = "changeDynamics(maxJointVelocity)"

#: the most links of a body, its base among them, whose state PyBullet reports (MAX_NUM_LINKS in its
#: SharedMemoryPublic.h; measured: 127 joints are reported, 128 are not): example-robot-data's TIAGo with two
#: arms has 130
MAX_LINKS = 128


class PybulletRunner:
    """A URDF file with the PyBullet settings it runs with.

    Examples
    --------
    >>> from pitheorem.engines.runners.pybullet import PybulletRunner
    >>> PybulletRunner.__name__
    'PybulletRunner'
    """

    #: PyBullet computes in double precision
    precision = "float64"
    #: PyBullet runs every file it loads
    refusal = None

    def __init__(self, document: UrdfDocument, settings: dict, *, scene: dict, info: dict | None = None):
        self.document = document  # the file's numbers; never changed once read (a copy is a new document)
        self.tree, self.path, self.source_dir = document.tree, document.path, document.source_dir
        self.scene = scene  # base position, fixed base, ground plane
        self._settings = settings
        # PyBullet's reading of the links and joints; a twin (the same file, every number one ulp off)
        # shares its original's instead of loading the file again
        self._info = self._probe() if info is None else info
        self.nudge_start = False  # a twin starts one ulp off
        self._clamp = None  # a counter-run's velocity clamp, written last (None: the file's and PyBullet's)
        self._contacts = True  # False: a counter-run's, with every contact off (the robot's and the ground's)

    # -- reading -------------------------------------------------------------------------------

    def _connect(self):
        pb = _pybullet()
        with quiet_stdout():
            client = pb.connect(pb.DIRECT)
        return pb, client

    def _load(self, pb, client):
        """Load the URDF from a temporary copy, its mesh files named by their absolute paths.

        The copy goes to the system's temporary folder, never the user's; only a file whose meshes
        cannot be found from here is copied beside the original, where PyBullet's own search starts.
        """
        import os
        import tempfile

        if "_portable" not in self.__dict__:  # the tree never changes: its text is made once
            self._portable = self.document.portable_text()
        text = self._portable if self._portable is not None else self.document.text()
        fd, tmp = tempfile.mkstemp(suffix=".urdf", dir=None if self._portable is not None else self.source_dir)
        try:
            with os.fdopen(fd, "w") as fh:
                fh.write(text)
            with quiet_stdout():
                body = pb.loadURDF(
                    tmp,
                    basePosition=list(self.scene["base_position"]),
                    useFixedBase=self.scene["fixed_base"],
                    physicsClientId=client,
                )
        finally:
            os.unlink(tmp)
        if body < 0:
            raise EngineModelError(self.path, "", "PyBullet could not load the file")
        return body

    def _probe(self) -> dict:
        pb, client = self._connect()
        try:
            try:
                body = self._load(pb, client)
            except pb.error as err:
                raise EngineModelError(self.path, "", f"PyBullet could not load the file: {err}") from None
            try:  # PyBullet reports no state of a body of more links than its shared memory holds (128)
                pb.getBasePositionAndOrientation(body, physicsClientId=client)
            except pb.error:
                raise EngineModelError(
                    self.path,
                    "<robot>",
                    f"PyBullet loads this body of {pb.getNumJoints(body, physicsClientId=client) + 1} links (its "
                    "base and a link per joint, fixed ones too) but cannot report its state "
                    f"(getBasePositionAndOrientation fails): its shared memory holds {MAX_LINKS} links at most "
                    "(MAX_NUM_LINKS); merge links joined by fixed joints in the file, or run it in another engine",
                ) from None
            links = [(-1, pb.getBodyInfo(body, physicsClientId=client)[0].decode())]
            joints = []
            for j in range(pb.getNumJoints(body, physicsClientId=client)):
                info = pb.getJointInfo(body, j, physicsClientId=client)
                links.append((j, info[12].decode()))
                kind = {pb.JOINT_REVOLUTE: "revolute", pb.JOINT_PRISMATIC: "prismatic", pb.JOINT_SPHERICAL: "spherical"}
                if info[2] in kind:
                    joints.append((j, info[1].decode(), kind[info[2]]))
            dynamics = {index: pb.getDynamicsInfo(body, index, physicsClientId=client) for index, _ in links}
            shapes = {index: pb.getCollisionShapeData(body, index, physicsClientId=client) for index, _ in links}
            return {"links": links, "joints": joints, "dynamics": dynamics, "shapes": shapes}
        finally:
            pb.disconnect(physicsClientId=client)

    def parameters(self):
        out = self.document.parameters()
        st = self._settings
        out.append(
            Parameter(
                "g",
                "setGravity (magnitude)",
                (st["g"],),
                dim("L T^-2"),
                "engine",
                "setGravity",
                note="PyBullet's own default is 0",
            )
        )
        out.append(Parameter("timestep", "setTimeStep", (st["timestep"],), _T, "engine", "setTimeStep"))
        for name, constant, note in ENGINE_PARAMETERS:
            out.append(
                Parameter(
                    name,
                    f"setPhysicsEngineParameter({name}=...)",
                    (st[name],),
                    _BULLET[constant].dimension,
                    "engine",
                    f"setPhysicsEngineParameter({name}=...)",
                    note=note,
                )
            )

        def setting(lname, suffix, what, value, dimension, key, note):  # a link's changeDynamics number
            return Parameter(
                _link_parameter(lname, suffix),
                f"link {lname!r} {what}",
                (value,),
                dimension,
                "engine",
                f"changeDynamics({key}=...)",
                note=note,
            )

        for index, lname in self._info["links"]:
            link = self._link_dynamics(index)
            if "collisionMargin" in link:
                margin = "0.001 for boxes and meshes, the radius for spheres"
                out.append(
                    setting(
                        lname,
                        "collision_margin",
                        "collision margin",
                        link["collisionMargin"],
                        _L,
                        "collisionMargin",
                        margin,
                    )
                )
            for key in ("rollingFriction", "spinningFriction"):
                out.append(setting(lname, key, key, link[key], _L, key, "a torque per normal force"))
            if "mass" in link:
                unstated = "PyBullet's own for a link whose file states no mass"
                out.append(setting(lname, "mass", "mass", link["mass"], _M, "mass", unstated))
            if self._info["dynamics"][index][0] > 0:
                out.append(
                    Parameter(
                        _link_parameter(lname, "inertia"),
                        f"link {lname!r} inertia (principal)",
                        tuple(link["localInertiaDiagonal"]),
                        dim("M L^2"),
                        "derived",
                        "changeDynamics(localInertiaDiagonal=...)",
                        note="computed by Bullet from the collision shapes' bounding boxes, margins "
                        "included; scaled copies set it explicitly",
                    )
                )
            for key, parts in MIXED_DAMPING:
                out.append(
                    Parameter(
                        _link_parameter(lname, key),
                        f"link {lname!r} {key}",
                        (link[key],),
                        None,
                        "engine",
                        f"changeDynamics({key}=...)",
                        parts=tuple((part, _BULLET[constant].dimension) for part, constant in parts),
                        note="Bullet multiplies m v by (d + d |v|)",
                    )
                )
        for j, jname, jtype in self._info["joints"]:
            out.append(
                Parameter(
                    _joint_speed_parameter(jname),
                    f"joint {jname!r} maxJointVelocity",
                    (self._max_joint_velocity(j),),
                    joint_kind(jtype).q / _T,
                    "engine",
                    "changeDynamics(maxJointVelocity=...)",
                    note="Bullet holds one clamp per body, the last one written, for every coordinate velocity (the "
                    "base's too): a run that reaches it is diagnosed with it lifted (velocity_clamp)",
                )
            )
        for j, jname, jtype in self._info["joints"]:
            if str(j) in st["springs"]:
                kind, (k, rest) = joint_kind(jtype), st["springs"][str(j)]
                stiffness, rest_name = _spring_parameters(jname)
                out.append(
                    Parameter(
                        stiffness,
                        f"joint {jname!r} spring stiffness",
                        (k,),
                        kind.force / kind.q,
                        "engine",
                        "joint spring (a torque each step)",
                        note="URDF has no joint spring: pitheorem applies -k (q - q0) before every step",
                    )
                )
                out.append(
                    Parameter(
                        rest_name,
                        f"joint {jname!r} spring rest position",
                        (rest,),
                        kind.q,
                        "engine",
                        "joint spring (a torque each step)",
                    )
                )
        if st["useSplitImpulse"]:
            out.append(
                Parameter(
                    "splitImpulsePenetrationThreshold",
                    "btContactSolverInfo",
                    (_BULLET["bullet_split_impulse_penetration_threshold"].default,),
                    _L,
                    "engine",
                    "",
                    note="negative values cannot be set from Python; "
                    "setPhysicsEngineParameter(useSplitImpulse=0) removes it",
                )
            )
        if self.scene["ground"]:
            out.append(
                Parameter(
                    "ground_collision_margin",
                    "ground plane collision margin",
                    (st["ground_margin"],),
                    _L,
                    "engine",
                    "changeDynamics(collisionMargin=...)",
                )
            )
        if any(self.scene["base_position"]):
            out.append(
                Parameter(
                    "base_position",
                    "loadURDF(basePosition=...)",
                    tuple(self.scene["base_position"]),
                    _L,
                    "engine",
                    "loadURDF(basePosition=...)",
                )
            )
        return out

    def settings(self) -> dict:
        st = self._settings
        return {
            "gravity": [0.0, 0.0, -st["g"]],
            "timeStep": st["timestep"],
            "setPhysicsEngineParameter": {
                **{n: st[n] for n, *_ in ENGINE_PARAMETERS},
                "useSplitImpulse": st["useSplitImpulse"],
            },
            "changeDynamics": self._dynamics_calls(),
            "jointSprings": [
                {"jointIndex": int(key), "stiffness": k, "restPosition": rest}
                for key, (k, rest) in sorted(st["springs"].items(), key=lambda item: int(item[0]))
            ],
            "disableDefaultMotors": True,
            "loadURDF": {"basePosition": list(self.scene["base_position"]), "useFixedBase": self.scene["fixed_base"]},
            "ground": {"collisionMargin": st["ground_margin"]} if self.scene["ground"] else None,
        }

    def _link_dynamics(self, index: int) -> dict:
        """The ``changeDynamics`` values a link runs with: those set (by a scaling or a saved file), else PyBullet's.

        In the order the calls set them: the inertia last, after the margin, for Bullet computed the
        inertia with the margin at load.
        """
        st, key, dyn = self._settings, str(index), self._info["dynamics"][index]
        values = {}
        if index in self._unstated_masses():  # first: setting a mass makes Bullet compute the inertia again
            values["mass"] = st.get("mass", {}).get(key, dyn[0])
        if self._info["shapes"][index]:
            values["collisionMargin"] = st["margins"].get(key, dyn[11])
        for k, name in enumerate(("rollingFriction", "spinningFriction")):
            values[name] = st["friction"].get(key, {}).get(name, dyn[6 + k])
        for name, parts in MIXED_DAMPING:
            values[name] = st["damping"].get(key, {}).get(name, _BULLET[parts[0][1]].default)
        values["localInertiaDiagonal"] = st["inertia"].get(key, dyn[2])
        return values

    def _unstated_masses(self) -> frozenset[int]:
        """The links whose file states no mass: PyBullet gives each its own (1 kg), a number the table must hold."""
        if "_unstated" not in self.__dict__:
            stated = {p.name for p in self.document.parameters() if p.name.endswith("_mass")}
            self._unstated = frozenset(
                index
                for index, lname in self._info["links"]
                if _link_parameter(lname, "mass") not in stated and self._info["dynamics"][index][0] > 0
            )
        return self._unstated

    def _max_joint_velocity(self, j: int) -> float:
        return self._settings["max_joint_velocity"].get(str(j), _BULLET["bullet_max_joint_velocity"].default)

    def _dynamics_calls(self) -> list[dict]:
        calls = []
        for index, _lname in self._info["links"]:
            call = {"linkIndex": index, **self._link_dynamics(index)}
            if str(index) not in self._settings["inertia"]:  # Bullet's own, computed at load: not set again
                del call["localInertiaDiagonal"]
            if "mass" in call and str(index) not in self._settings.get("mass", {}):  # likewise PyBullet's own
                del call["mass"]
            calls.append(call)
        for j, _jname, _jtype in self._info["joints"]:
            calls.append({"linkIndex": j, "maxJointVelocity": self._max_joint_velocity(j)})
        if self._clamp is not None:  # one number per body: the last written holds for every coordinate
            calls.append({"linkIndex": -1, "maxJointVelocity": self._clamp})
        return calls

    # -- scaling --------------------------------------------------------------------------------

    def scaled(self, factors, scaling, s, *, info: dict | None = None, text=attribute_text) -> PybulletRunner:
        document = self.document.scaled(factors, text=text)  # by default the exact decimal products
        st = json.loads(json.dumps(self._settings))
        st["g"] *= factors.get("g", 1.0)
        st["timestep"] *= factors.get("timestep", 1.0)
        for name, *_ in ENGINE_PARAMETERS:
            st[name] *= factors.get(name, 1.0)
        params = {p.name: p for p in self.parameters()}
        for index, lname in self._info["links"]:
            key = str(index)
            if self._info["shapes"][index]:
                name = _link_parameter(lname, "collision_margin")
                st["margins"][key] = params[name].value[0] * factors.get(name, 1.0)
            name = _link_parameter(lname, "inertia")
            if name in params:
                st["inertia"][key] = [v * factors.get(name, 1.0) for v in params[name].value]
            name = _link_parameter(lname, "mass")
            if index in self._unstated_masses():
                st.setdefault("mass", {})[key] = params[name].value[0] * factors.get(name, 1.0)
            for fname in ("rollingFriction", "spinningFriction", *(n for n, *_ in MIXED_DAMPING)):
                name = _link_parameter(lname, fname)
                group = "damping" if "Damping" in fname else "friction"
                st[group].setdefault(key, {})[fname] = params[name].value[0] * factors.get(name, 1.0)
        for j, jname, _jtype in self._info["joints"]:
            name = _joint_speed_parameter(jname)
            st["max_joint_velocity"][str(j)] = params[name].value[0] * factors.get(name, 1.0)
            if str(j) in st["springs"]:
                names = _spring_parameters(jname)
                st["springs"][str(j)] = [params[n].value[0] * factors.get(n, 1.0) for n in names]
        for err in self.unscalable(factors):
            raise err
        if self.scene["ground"]:
            st["ground_margin"] *= factors.get("ground_collision_margin", 1.0)
        scene = dict(self.scene)
        if any(scene["base_position"]):
            scene["base_position"] = tuple(v * factors.get("base_position", 1.0) for v in scene["base_position"])
        if info is None and all(0 < f < math.inf for f in factors.values()):
            # the same links, joints and shapes, none of them massless that was not: PyBullet's reading of
            # this file serves the copy (every dynamics value the copy runs with is set above, none falls
            # back to the load's), and the copy is not loaded once more just to be read
            info = self._info
        return PybulletRunner(document, st, scene=scene, info=info)

    #: the one line that removes every refusal of PyBullet's default scene at once
    unscalable_remedy = (
        "In one go: engines.load(path, damping=0.0, split_impulse=False) (on the command line: "
        "--scene damping=0 split_impulse=false), the same in the original and the scaled run"
    )

    #: the scene in which every number follows every scaling: no link damping (its rate and per-length
    #: parts need different factors) and no split impulse (its threshold cannot be set from Python)
    remedy_scene = MappingProxyType({"damping": 0.0, "split_impulse": False})

    def command_line_remedy(self, name: str) -> tuple[str, str]:
        """The ``--scene`` option that removes the refusal of `name`, and its flag (("", "") for none)."""
        if name.endswith("Damping"):
            return "damping", "--scene damping=0"
        if name.startswith("splitImpulse"):
            return "split_impulse", "--scene split_impulse=false"
        return "", ""

    def unscalable(self, factors) -> list[UnscalableParameterError]:
        """The settings the factors would change but no PyBullet call can: the split-impulse threshold."""
        params = {p.name for p in self.parameters()}
        if "splitImpulsePenetrationThreshold" in params and factors.get("splitImpulsePenetrationThreshold", 1) != 1:
            threshold = _BULLET["bullet_split_impulse_penetration_threshold"].default
            return [
                UnscalableParameterError(
                    "splitImpulsePenetrationThreshold",
                    f"Bullet's split-impulse threshold ({float_text(threshold)}, a length) "
                    "cannot be set from Python; load the model with split_impulse=False (useSplitImpulse=0) in both runs",
                )
            ]
        return []

    def check_units(self, units) -> None:
        """Refuse units other than SI: a URDF file is in SI units by its specification."""
        if dict(units) != dict(self.document.fixed_units):
            refuse_units(self.path, units)

    def in_units(self, units) -> PybulletRunner:
        self.check_units(units)
        return self

    def recorded_units(self) -> dict[str, str] | None:
        """None: a URDF file records no units (it is in SI)."""
        return None

    def written_beside(self, path) -> tuple[str, ...]:
        """The settings :meth:`save` writes beside the file: a JSON file and a script that applies it."""
        return (f"{path}.settings.json", f"{path}.settings.py")

    def save(self, path: Path, *, copy_assets: bool = False) -> None:
        path = Path(path)
        self.document.save(path, copy_assets=copy_assets)
        settings = self.settings()
        Path(f"{path}.settings.json").write_text(json.dumps(settings, indent=2))
        Path(f"{path}.settings.py").write_text(_snippet(path.name, settings))

    # -- running ---------------------------------------------------------------------------------

    def timestep(self) -> float:
        return float(self._settings["timestep"])

    def coordinate_dimensions(self):
        """The base's 13 numbers, then each movable joint's position, then its velocity.

        A spherical joint's position is its quaternion (``q[NAME:x]`` ... ``q[NAME:w]``,
        PyBullet's order) and its velocity an angular velocity of three (``qdot[NAME:x]`` ...).
        """
        names, dims = [], []
        for k, d in enumerate([_L] * 3 + [_ONE] * 4 + [dim("L T^-1")] * 3 + [dim("T^-1")] * 3):
            names.append(f"base[{k}]")
            dims.append(d)
        for _j, jname, jtype in self._info["joints"]:
            for axis in _axes(jtype, _QUATERNION):
                names.append(f"q[{jname}{axis}]")
                dims.append(joint_kind(jtype).q)
        for _j, jname, jtype in self._info["joints"]:
            for axis in _axes(jtype, _VECTOR):
                names.append(f"qdot[{jname}{axis}]")
                dims.append(joint_kind(jtype).q / _T)
        return names, dims

    def control_dimensions(self):
        """One force or torque per movable joint; three torques for a spherical joint."""
        return [joint_kind(jtype).force for _j, _n, jtype in self._info["joints"] for _axis in _axes(jtype, _VECTOR)]

    def _layout(self) -> list[tuple[int, str, slice, slice, slice]]:
        """Each movable joint: its index, type, and its columns among the positions, velocities and inputs."""
        out, pos, vel = [], 0, 0
        for j, _n, jtype in self._info["joints"]:
            npos, nvel = len(_axes(jtype, _QUATERNION)), len(_axes(jtype, _VECTOR))
            out.append((j, jtype, slice(pos, pos + npos), slice(vel, vel + nvel), slice(vel, vel + nvel)))
            pos, vel = pos + npos, vel + nvel
        return out

    def _setup(self, pb, client) -> int:
        """The scene, the robot and every setting, as a run starts them; the robot's body id."""
        st = self._settings
        pb.setGravity(0.0, 0.0, -st["g"], physicsClientId=client)
        pb.setTimeStep(st["timestep"], physicsClientId=client)
        pb.setPhysicsEngineParameter(
            numSubSteps=0,
            useSplitImpulse=int(st["useSplitImpulse"]),
            **{n: st[n] for n, *_ in ENGINE_PARAMETERS},
            physicsClientId=client,
        )
        ground = None
        if self.scene["ground"]:
            plane = pb.createCollisionShape(pb.GEOM_PLANE, physicsClientId=client)
            ground = pb.createMultiBody(0, plane, physicsClientId=client)
            pb.changeDynamics(ground, -1, collisionMargin=st["ground_margin"], physicsClientId=client)
        body = self._load(pb, client)
        for call in self._dynamics_calls():
            call = dict(call)
            index = call.pop("linkIndex")
            for key, value in call.items():  # one setting per call (see rod.py on pybullet 3.2.7)
                pb.changeDynamics(body, index, **{key: value}, physicsClientId=client)
        if not self._contacts:  # in no collision group and colliding with none: no contact is made
            shapes = [(body, link) for link, _name in self._info["links"]] + (
                [(ground, -1)] if ground is not None else []
            )
            for owner, link in shapes:
                pb.setCollisionFilterGroupMask(owner, link, 0, 0, physicsClientId=client)
        for j, _n, jtype in self._info["joints"]:
            if jtype == "spherical":  # its default motor pulls it to rest: no force, no gain on position
                pb.setJointMotorControlMultiDof(
                    body,
                    j,
                    pb.POSITION_CONTROL,
                    targetPosition=[0.0, 0.0, 0.0, 1.0],
                    targetVelocity=[0.0, 0.0, 0.0],
                    positionGain=0.0,
                    velocityGain=1.0,
                    force=[0.0, 0.0, 0.0],
                    physicsClientId=client,
                )
            else:
                pb.setJointMotorControl2(body, j, pb.VELOCITY_CONTROL, force=0.0, physicsClientId=client)
        return body

    # -- what the engine holds: the audit's numbers, the yardstick's twins ------------------------

    def _held(self) -> tuple[list, list]:
        """What PyBullet holds once the robot is loaded and set: each link's dynamics, each movable joint's
        info.  Loaded once (the audit asks for the numbers and for the margins)."""
        if getattr(self, "_held_info", None) is None:
            pb, client = self._connect()
            try:
                body = self._setup(pb, client)
                dynamics = [pb.getDynamicsInfo(body, i, physicsClientId=client) for i, _ in self._info["links"]]
                joints = [pb.getJointInfo(body, j, physicsClientId=client) for j, _n, _t in self._info["joints"]]
            finally:
                pb.disconnect(physicsClientId=client)
            self._held_info = dynamics, joints
        return self._held_info

    def stored_numbers(self) -> dict[str, np.ndarray]:
        """What PyBullet holds once the robot is loaded and set: each link's dynamics, each joint's info.

        Fields are ``link.<quantity>`` (one row per link, the base first), ``joint.<quantity>`` (one
        row per movable joint) and ``spring.<quantity>`` (one row per joint spring, which the run applies
        as a torque); the collision margins are left to :meth:`ignored_settings`.
        """
        dyn, joints = self._held()
        out = {
            f"link.{name}": np.array([np.atleast_1d(d[k]) for d in dyn], dtype=float) for k, name in _DYNAMICS_FIELDS
        }
        if joints:
            out.update(
                {
                    f"joint.{name}": np.array([np.atleast_1d(info[k]) for info in joints], dtype=float)
                    for k, name in _JOINT_FIELDS
                }
            )
        sprung, stiffness, rest = self._springs()
        if sprung:  # not PyBullet's but the run's: the torque -k (q - q0) applied before every step
            out["spring.stiffness"], out["spring.restPosition"] = stiffness[:, None], rest[:, None]
        return out

    def element_name(self, field: str, row: int) -> str:
        """A row of a stored field, named by its link or joint."""
        if field.startswith("link."):
            return f"link {self._info['links'][row][1]!r} {field[5:]}"
        if field.startswith("spring."):
            place = self._springs()[0][row]
            return f"joint {self._info['joints'][place][1]!r} spring {field[7:]}"
        return f"joint {self._info['joints'][row][1]!r} {field[6:]}"

    def ignored_settings(self) -> tuple:
        """The ``changeDynamics`` settings PyBullet does not take: each as a ``setting`` Cause."""
        from ..verdicts.causes import Cause

        compound = [
            Cause(
                "setting",
                f"link {link!r} collision mesh {Path(filename).name!r}",  # its name: no machine's path
                f"its {parts} convex parts "
                "load as a compound whose collision margins changeDynamics cannot reach: they keep "
                "PyBullet's default margin, a length no scaling changes, so the copy's contacts are off "
                "by it",
            )
            for link, filename, parts in self.document.compound_meshes()
        ]
        return tuple(compound) + self._ignored_margins() + self._ignored_clamps()

    def _ignored_clamps(self) -> tuple:
        """The joints whose maxJointVelocity is not the one clamp PyBullet holds for the body (the last written): a
        scaled copy asks a prismatic joint's in m/s times its factor and a revolute joint's in rad/s."""
        from ..verdicts.causes import Cause

        held = self.velocity_clamp()[0]
        missed = [(jname, v) for j, jname, _t in self._info["joints"] if (v := self._max_joint_velocity(j)) != held]
        if not missed:
            return ()
        jname, wanted = missed[0]
        names = names_text((n for n, _v in missed), code=repr, shown=3, in_all=False)
        return (
            Cause(
                "setting",
                _CLAMPS,
                f"{len(missed)} joint(s) ({names}) are set another velocity clamp than the one PyBullet holds (joint "
                f"{jname!r}: set {float_text(wanted)}, PyBullet keeps {float_text(held)}, the last one written, for "
                "every coordinate velocity of the body): Bullet holds one clamp per body, so a clamp in m/s and one "
                "in rad/s cannot both be scaled",
            ),
        )

    def _ignored_margins(self) -> tuple:
        """The links whose margin PyBullet keeps other than the one set."""
        from ..verdicts.causes import Cause

        dynamics, _ = self._held()
        missed = []
        for (index, lname), held in zip(self._info["links"], dynamics, strict=True):
            wanted = self._link_dynamics(index).get("collisionMargin")
            if wanted is not None and held[11] != wanted:
                missed.append((lname, wanted, held[11]))
        if not missed:
            return ()
        lname, wanted, held = missed[0]
        names = names_text((n for n, *_ in missed), code=repr, shown=3, in_all=False)
        return (
            Cause(
                "setting",
                _MARGINS,
                f"{len(missed)} link(s) ({names}) keep "
                f"another margin than the one set (link {lname!r}: set {float_text(wanted)}, PyBullet keeps "
                f"{float_text(held)}): the call does not reach these links' shapes, so their margins are not "
                "scaled",
            ),
        )

    def twin(self, seed: int) -> PybulletRunner:
        """A copy with every parameter moved by about one ulp (random signs from `seed`) and its start nudged."""
        rng = np.random.default_rng(seed)
        factors = {
            p.name: 1.0 + float(rng.choice((-1.0, 1.0))) * 2.0**-52 for p in self.parameters() if p.name != "timestep"
        }
        # the float products, not their exact decimals: a twin is never saved
        out = self.scaled(factors, None, None, info=self._info, text=_float_products)
        out.nudge_start = True
        return out

    def solver_settings(self) -> dict[str, float]:
        """The solver's stopping rule of no pure dimension (the residual threshold), when nonzero."""
        value = float(self._settings["solverResidualThreshold"])
        return {"solverResidualThreshold": value} if value else {}

    def variant(
        self,
        *,
        tolerance: float | None = None,
        velocity_clamp: float | None = None,
        contacts: bool | None = None,
        inactive_equalities: tuple = (),
        unlimited: tuple = (),
    ) -> PybulletRunner:
        """A copy run with another residual threshold, another velocity clamp, or every contact off: a
        counter-run's model.  A URDF has no equality constraint, and no limit is switched off here
        (:meth:`equality_names` and :meth:`limit_names` are empty)."""
        if inactive_equalities or unlimited:
            raise InvalidRequestError(
                f"{self.path}: PyBullet's runner has no equality constraint and switches no limit off "
                f"(asked for {inactive_equalities or unlimited})"
            )
        out = copy.copy(self)
        if tolerance is not None:
            out._settings = {**self._settings, "solverResidualThreshold": float(tolerance)}
        if velocity_clamp is not None:
            out._clamp = float(velocity_clamp)
        if contacts is not None:
            out._contacts = bool(contacts)
        return out

    def equality_names(self) -> list[str]:
        """None: a URDF states no equality constraint (a mimic joint is no constraint PyBullet makes)."""
        return []

    def equality_kinds(self) -> list[str]:
        """None, as :meth:`equality_names`."""
        return []

    def limit_names(self) -> list[str]:
        """None: no counter-run switches a joint's limit off in PyBullet here."""
        return []

    def removed_by(self, cause) -> dict | None:
        """The counter-run's options that remove an ignored setting's effect from both runs: contacts off for a
        collision margin (it acts through contacts only), the velocity clamp lifted for a clamp (it acts on a
        run that reaches it only); None for another setting.

        Examples
        --------
        >>> from pitheorem import engines
        >>> from pitheorem.engines.verdicts.causes import Cause
        >>> runner = engines.load(engines.example_path("causes/quadruped.urdf"), engine="pybullet").runner
        >>> runner.removed_by(Cause("setting", "changeDynamics(collisionMargin)", "..."))
        {'contacts': False}
        >>> runner.removed_by(Cause("setting", "changeDynamics(maxJointVelocity)", "..."))
        {'velocity_clamp': inf}
        """
        if cause.kind != "setting":
            return None
        if cause.element == _CLAMPS:  # the clamp acts on a run that reaches it only: lifted in both runs
            return {"velocity_clamp": math.inf}
        margin = cause.element == _MARGINS or " collision mesh " in cause.element  # as ignored_settings names them
        return {"contacts": False} if margin else None

    def velocity_clamp(self) -> tuple[float, str]:
        """The velocity clamp in effect, and what it is.

        Bullet clamps every coordinate velocity of a multibody (the base's three
        linear and three angular ones, each joint's) at one number, its
        ``m_maxCoordinateVelocity`` (100).  PyBullet's
        ``changeDynamics(maxJointVelocity=...)`` sets that number whatever link
        it names, so the last call holds for all: a speed for the base and
        prismatic joints, an angular speed for the base's turning and the
        revolute joints.  A run that never reaches it does not feel it.

        Examples
        --------
        >>> from pitheorem import engines
        >>> model = engines.load(engines.example_path("causes/quadruped.urdf"), engine="pybullet")
        >>> model.runner.velocity_clamp()[0]
        100.0
        >>> engines.load(engines.example_path("hinged_rod.urdf"), engine="pybullet").runner.velocity_clamp()[0]
        1e+30
        """
        if self._clamp is not None:
            value = self._clamp
        elif self._info["joints"]:
            value = float(self._max_joint_velocity(self._info["joints"][-1][0]))  # the last one written
        else:
            value = _BULLET["bullet_max_joint_velocity"].default
        return value, (
            f"Bullet's clamp on every coordinate velocity of a body (m_maxCoordinateVelocity, {float_text(value)}: "
            "the base's linear and angular velocities and each joint's, one number of no one dimension, set by "
            "changeDynamics(maxJointVelocity) whatever link it names; bullet_max_joint_velocity)"
        )

    def reaches_velocity_clamp(self, rows) -> bool:
        """Whether a run may have met the clamp: a joint's speed, or the size of the base's linear or angular
        velocity, at or beyond it (Bullet clamps the base's in the base's own frame; a run records them in the
        world's, whose size is no smaller than any of its components).

        Examples
        --------
        >>> import numpy as np
        >>> from pitheorem import engines
        >>> runner = engines.load(engines.example_path("causes/quadruped.urdf"), engine="pybullet").runner
        >>> run = runner.run(3)
        >>> runner.reaches_velocity_clamp(run), runner.reaches_velocity_clamp(run * 1e6)
        (False, True)
        """
        rows = np.asarray(rows, dtype=float)
        nvel = self._layout()[-1][3].stop if self._info["joints"] else 0
        clamp = self.velocity_clamp()[0] * (1 - 1e-12)
        with np.errstate(invalid="ignore"):
            base = np.maximum(np.linalg.norm(rows[:, 7:10], axis=1), np.linalg.norm(rows[:, 10:13], axis=1))
            joints = np.abs(rows[:, rows.shape[1] - nvel :]) if nvel else np.zeros((len(rows), 0))
            return bool((base >= clamp).any() or (joints >= clamp).any())

    def run_many(self, n_steps: int, jobs) -> list[np.ndarray]:
        """The runs of ``(backend, controls, nudge, state)`` jobs, one after the other, in one PyBullet client.

        PyBullet has no batch; connecting costs more than a small robot's whole run, so the client is
        connected once and its world reset between the runs (each run sets every setting again).
        """
        pb, client = self._connect()
        try:
            out = []
            for backend, controls, nudge, initial in jobs:
                pb.resetSimulation(physicsClientId=client)
                out.append(backend._run_in(pb, client, n_steps, controls, nudge, initial=initial))
            return out
        finally:
            pb.disconnect(physicsClientId=client)

    def control_ranges(self) -> tuple[np.ndarray, np.ndarray]:
        """Unlimited for every movable joint: under torque control PyBullet applies no effort limit."""
        high = np.full(len(self.control_dimensions()), np.inf)
        return -high, high

    def run(self, n_steps: int, controls=None, nudge: bool = False, policy=None, initial=None):
        pb, client = self._connect()
        try:
            return self._run_in(pb, client, n_steps, controls, nudge, policy, initial)
        finally:
            pb.disconnect(physicsClientId=client)

    def _run_in(self, pb, client, n_steps: int, controls=None, nudge: bool = False, policy=None, initial=None):
        """One run in a connected client whose world is empty, from `initial` (a first row) if given."""
        nudge = nudge or self.nudge_start
        st = self._settings
        body = self._setup(pb, client)
        layout = self._layout()
        joints = [j for j, *_ in layout]
        single = [(j, where) for j, jtype, where, _v, _c in layout if jtype != "spherical"]
        spherical = [(j, where) for j, jtype, where, _v, _c in layout if jtype == "spherical"]
        npos = layout[-1][2].stop if layout else 0
        nvel = layout[-1][3].stop if layout else 0
        if initial is not None:  # the row's layout: base position, orientation, velocities; positions; velocities
            pb.resetBasePositionAndOrientation(
                body, initial[:3].tolist(), initial[3:7].tolist(), physicsClientId=client
            )
            pb.resetBaseVelocity(body, initial[7:10].tolist(), initial[10:13].tolist(), physicsClientId=client)
            q, qdot = initial[13 : 13 + npos], initial[13 + npos : 13 + npos + nvel]
            for j, jtype, pos, vel, _c in layout:
                if jtype == "spherical":
                    pb.resetJointStateMultiDof(body, j, q[pos].tolist(), qdot[vel].tolist(), physicsClientId=client)
                else:
                    pb.resetJointState(body, j, float(q[pos][0]), float(qdot[vel][0]), physicsClientId=client)
        if nudge:
            pos, orn = pb.getBasePositionAndOrientation(body, physicsClientId=client)
            pb.resetBasePositionAndOrientation(body, nudged(pos).tolist(), orn, physicsClientId=client)
            for j, _where in single:
                q, qdot = pb.getJointState(body, j, physicsClientId=client)[:2]
                pb.resetJointState(body, j, float(nudged([q])[0]), qdot, physicsClientId=client)
            for j, _where in spherical:
                q, qdot = pb.getJointStateMultiDof(body, j, physicsClientId=client)[:2]
                pb.resetJointStateMultiDof(body, j, nudged(q).tolist(), list(qdot), physicsClientId=client)
        out = np.empty((n_steps + 1, 13 + npos + nvel))

        def record(i):
            pos, orn = pb.getBasePositionAndOrientation(body, physicsClientId=client)
            lin, ang = pb.getBaseVelocity(body, physicsClientId=client)
            if spherical:  # positions and velocities of several numbers each
                states = pb.getJointStatesMultiDof(body, joints, physicsClientId=client)
                q = [x for state in states for x in state[0]]
                qdot = [x for state in states for x in state[1]]
            else:
                states = pb.getJointStates(body, joints, physicsClientId=client) if joints else []
                q, qdot = [x[0] for x in states], [x[1] for x in states]
            out[i] = [*pos, *orn, *lin, *ang, *q, *qdot]

        record(0)
        dt = st["timestep"]
        sprung, stiffness, rest = self._springs()
        # a spring's joint by its column among the positions and among the inputs
        sprung_q = [layout[place][2].start for place in sprung]
        sprung_u = [layout[place][4].start for place in sprung]
        single_joints = [j for j, _where in single]
        single_u = [layout[place][4].start for place, (_j, jtype, *_r) in enumerate(layout) if jtype != "spherical"]
        for i in range(1, n_steps + 1):
            if (controls is not None or policy is not None or sprung) and joints:
                t = (i - 1) * dt
                if controls is None and policy is None:
                    u = np.zeros(nvel)
                elif controls is None:
                    u = policy(client, body, t)
                else:  # an array of rows, one per step, or a function of time
                    u = controls(t) if callable(controls) else controls[i - 1]
                u = np.array(u, dtype=float)
                if sprung:  # the springs' torques from the state this step starts from
                    q = out[i - 1, 13 : 13 + npos]
                    u[sprung_u] += -stiffness * (q[sprung_q] - rest)
                if single_joints:
                    pb.setJointMotorControlArray(
                        body, single_joints, pb.TORQUE_CONTROL, forces=u[single_u].tolist(), physicsClientId=client
                    )
                for j, jtype, _p, _v, inputs in layout:
                    if jtype == "spherical":
                        pb.setJointMotorControlMultiDof(
                            body, j, pb.TORQUE_CONTROL, force=u[inputs].tolist(), physicsClientId=client
                        )
            pb.stepSimulation(physicsClientId=client)
            record(i)
        return out

    def _springs(self) -> tuple[list[int], np.ndarray, np.ndarray]:
        """The movable joints with a spring (by their place among the movable joints), stiffnesses, rests."""
        places = {str(j): place for place, (j, _n, _t) in enumerate(self._info["joints"])}
        springs = sorted((places[key], k, rest) for key, (k, rest) in self._settings["springs"].items())
        return (
            [place for place, _k, _r in springs],
            np.array([k for _p, k, _r in springs]),
            np.array([r for _p, _k, r in springs]),
        )

    def with_settings(self, **changes) -> PybulletRunner:
        st = json.loads(json.dumps(self._settings))
        scene = dict(self.scene)
        for key, value in changes.items():
            if key not in ("split_impulse", "damping", "joint_springs", *scene):
                raise InvalidRequestError(
                    f"unknown setting {key!r}; use split_impulse, damping, joint_springs, "
                    "ground, fixed_base or base_position",
                    culprit=key,
                )
            if key == "split_impulse":
                st["useSplitImpulse"] = int(scene_option(key, value))
            elif key == "damping":  # None: PyBullet's own
                st["damping"] = self._damping(None if value is None else scene_option(key, value))
            elif key == "joint_springs":
                st["springs"] = self._joint_springs(value)
            else:
                scene[key] = scene_option(key, value)
        # the same file (a tree is never changed once read), other settings
        # the same links and joints unless the scene moved or fixed the base: PyBullet's reading is kept
        info = self._info if scene == self.scene else None
        return PybulletRunner(self.document, st, scene=scene, info=info)

    def _damping(self, value: float | None) -> dict:
        """The settings' multibody damping: `value` for both numbers of every link, or {} (PyBullet's own)."""
        if value is None:
            return {}
        return {str(index): {name: value for name, *_ in MIXED_DAMPING} for index, _ in self._info["links"]}

    def _joint_springs(self, springs) -> dict:
        """``{joint name: (stiffness, rest position)}`` read into the settings' ``{joint index: [k, q0]}``."""
        movable = {name: j for j, name, _t in self._info["joints"]}
        spherical = {name for _j, name, jtype in self._info["joints"] if jtype == "spherical"}
        if not isinstance(springs, dict):
            raise InvalidRequestError(
                f"joint_springs maps a joint's name to (stiffness, rest position), got {springs!r}", culprit=springs
            )
        out = {}
        for name, spring in springs.items():
            if name not in movable:
                raise InvalidRequestError(
                    f"no movable joint {name!r} for a spring; the movable joints are "
                    f"{', '.join(sorted(movable)) or 'none'}",
                    culprit=name,
                )
            if name in spherical:
                raise InvalidRequestError(
                    f"joint {name!r} is spherical; a spring takes a revolute, continuous or prismatic joint",
                    culprit=name,
                )
            if isinstance(spring, str | bytes) or np.ndim(spring) != 1 or len(spring) != 2:
                raise InvalidRequestError(
                    f"the spring of joint {name!r} is (stiffness, rest position), got {spring!r}", culprit=spring
                )
            stiffness = float(read_number(spring[0], f"the spring stiffness of joint {name!r}"))
            if stiffness < 0:
                raise InvalidRequestError(
                    f"the spring stiffness of joint {name!r} cannot be negative, got {spring[0]!r}", culprit=spring[0]
                )
            out[str(movable[name])] = [stiffness, float(read_number(spring[1], f"the rest position of {name!r}"))]
        return out


#: getDynamicsInfo's numbers (index, name), the margin (11) aside; getJointInfo's for a movable joint
_DYNAMICS_FIELDS = (
    (0, "mass"),
    (1, "lateralFriction"),
    (2, "localInertiaDiagonal"),
    (3, "localInertialPos"),
    (5, "restitution"),
    (6, "rollingFriction"),
    (7, "spinningFriction"),
    (8, "contactDamping"),
    (9, "contactStiffness"),
)
_JOINT_FIELDS = (
    (6, "damping"),
    (7, "friction"),
    (8, "lowerLimit"),
    (9, "upperLimit"),
    (10, "maxForce"),
    (11, "maxVelocity"),
    (14, "parentFramePos"),
)


def _float_products(values, factor: float) -> str:
    """Numbers times a factor as the text of an XML attribute: each float product at full precision."""
    return " ".join(repr(float(v) * factor) for v in values)


def _snippet(name: str, settings: dict) -> str:
    """A runnable Python script that loads the saved URDF with its PyBullet settings."""
    lines = [
        '"""Load the scaled model in PyBullet with the settings its URDF cannot hold (written by pitheorem)."""',
        "import os",
        "",
        "import pybullet as p",
        "",
        "here = os.path.dirname(os.path.abspath(__file__))",
        "client = p.connect(p.DIRECT)",
        f"p.setGravity(*{settings['gravity']!r})",
        f"p.setTimeStep({settings['timeStep']!r})",
        f"p.setPhysicsEngineParameter(numSubSteps=0, **{settings['setPhysicsEngineParameter']!r})",
    ]
    if settings["ground"] is not None:
        lines += [
            "ground = p.createMultiBody(0, p.createCollisionShape(p.GEOM_PLANE))",
            f"p.changeDynamics(ground, -1, collisionMargin={settings['ground']['collisionMargin']!r})",
        ]
    load = settings["loadURDF"]
    lines.append(
        f"body = p.loadURDF(os.path.join(here, {name!r}), basePosition={load['basePosition']!r}, "
        f"useFixedBase={load['useFixedBase']!r})"
    )
    lines.append(f"for call in {settings['changeDynamics']!r}:")
    lines.append("    index = call.pop('linkIndex')")
    lines.append("    for key, value in call.items():")
    lines.append("        p.changeDynamics(body, index, **{key: value})")
    lines.append("for j in range(p.getNumJoints(body)):  # PyBullet's default motors off")
    lines.append("    if p.getJointInfo(body, j)[2] == p.JOINT_SPHERICAL:")
    lines.append("        p.setJointMotorControlMultiDof(body, j, p.POSITION_CONTROL, targetPosition=[0, 0, 0, 1],")
    lines.append("                                       positionGain=0, velocityGain=1, force=[0, 0, 0])")
    lines.append("    else:")
    lines.append("        p.setJointMotorControl2(body, j, p.VELOCITY_CONTROL, force=0)")
    if settings["jointSprings"]:
        lines += [
            "",
            "# URDF has no joint spring: call apply_springs() before every p.stepSimulation()",
            "# (a torque of your own on a sprung joint is added to the spring's, not set instead)",
            f"springs = {settings['jointSprings']!r}",
            "",
            "",
            "def apply_springs():",
            "    for spring in springs:",
            "        q = p.getJointState(body, spring['jointIndex'])[0]",
            "        torque = -spring['stiffness'] * (q - spring['restPosition'])",
            "        p.setJointMotorControl2(body, spring['jointIndex'], p.TORQUE_CONTROL, force=torque)",
        ]
    return "\n".join(lines) + "\n"


def load_urdf(
    path, *, settings=None, base_position=None, fixed_base=None, ground=None, split_impulse=None, g=None, damping=None
) -> EngineModel:
    """Read a URDF file through PyBullet.

    A file written by :meth:`~pitheorem.engines.EngineModel.save` has its
    engine settings beside it (``NAME.urdf.settings.json``); they are read
    with it, so a saved scaled model reloads as it was saved.

    Parameters
    ----------
    path : str or Path
    settings : str, Path or bool, optional
        The settings file to read: by default ``<path>.settings.json`` if
        it exists; ``False`` ignores it.  When settings are read they fix
        the scene, and the scene options below may not be given.
    base_position : sequence of 3 float, optional
        Where ``loadURDF`` puts the base (default: the origin).
    fixed_base : bool, optional
        ``loadURDF(useFixedBase=...)`` (default False).
    ground : bool, optional
        Add a static ground plane at z = 0 (default False).
    split_impulse : bool, optional
        Bullet's split impulse (default True, PyBullet's own); its
        threshold is a length that cannot be set from Python, so scalings
        of length need ``False``.
    g : float, optional
        Gravity magnitude (default 9.81; PyBullet's own default is 0).
    damping : float, optional
        ``linearDamping`` and ``angularDamping`` of every link (default:
        PyBullet's 0.04, which mixes dimensions; 0 makes lengths scalable).

    Returns
    -------
    EngineModel
        Of engine ``"pybullet"``, with the scene and settings it runs in
        (:meth:`~pitheorem.engines.EngineModel.settings`).

    Raises
    ------
    EngineModelError
        For a file that is not XML, not a URDF, has an absent mesh, an
        unknown geometry or joint type, or that PyBullet rejects.

    Examples
    --------
    >>> import pybullet_data, os
    >>> from pitheorem.engines.runners.pybullet import load_urdf
    >>> model = load_urdf(os.path.join(pybullet_data.getDataPath(), "cartpole.urdf"))
    >>> str(model.parameter("joint_slider_to_cart_velocity").dimension)
    'L T^-1'

    A saved model reloads with its settings:

    >>> import tempfile, pitheorem as pt
    >>> model = load_urdf(os.path.join(pybullet_data.getDataPath(), "cartpole.urdf"), damping=0.0,
    ...                   split_impulse=False)
    >>> sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     again = load_urdf(model.scaled(sc, 10).save(os.path.join(tmp, "cartpole10.urdf")))
    >>> round(again.parameter("joint_slider_to_cart_velocity").value[0] / model.parameter(
    ...     "joint_slider_to_cart_velocity").value[0], 12)
    10.0
    """
    path = Path(path)
    given = {
        "base_position": base_position,
        "fixed_base": fixed_base,
        "ground": ground,
        "split_impulse": split_impulse,
        "g": g,
        "damping": damping,
    }
    scene = {name: value for name, value in given.items() if value is not None}  # None: not given
    saved = Path(f"{path}.settings.json") if settings is None or settings is True else settings
    if saved is not False and Path(saved).is_file():
        if scene:
            raise InvalidRequestError(
                f"{saved} fixes the scene of {path.name}; drop the options {sorted(scene)} or pass settings=False"
            )
        return _load_saved(path, Path(saved))
    if saved is not False and settings not in (None, True):
        raise EngineModelError(str(saved), "", "no such settings file")
    defaults = {name: default for name, (_kind, default) in SCENE_OPTIONS.items()}
    return EngineModel(_scene_backend(path, {**defaults, **scene}), "pybullet", str(path))


def scene_option(name: str, value):
    """One option of the scene, read by its kind in :data:`SCENE_OPTIONS`.

    The one reader of the scene: :func:`load_urdf`'s keyword options, the
    command line's ``--scene NAME=VALUE`` and a saved settings file all go
    through it.

    Parameters
    ----------
    name : str
        A name of :data:`SCENE_OPTIONS`.
    value : bool, number, str or sequence of three
        A flag is ``True`` or ``False``; a number is read by
        :func:`pitheorem.exact.read_number` and may not be negative; a point
        is three numbers.

    Returns
    -------
    bool, float or tuple of 3 float

    Raises
    ------
    InvalidRequestError
        For an unknown name or a value of the wrong kind (a
        :class:`~pitheorem.NumberError` for one that is no finite number).

    Examples
    --------
    >>> from pitheorem.engines.runners.pybullet import scene_option
    >>> scene_option("ground", True), scene_option("damping", "0"), scene_option("base_position", (0, "0.5", 1))
    (True, 0.0, (0.0, 0.5, 1.0))
    """
    if name not in SCENE_OPTIONS:
        raise InvalidRequestError(
            f"unknown scene option {name!r}; the options are {', '.join(SCENE_OPTIONS)}", culprit=name
        )
    kind = SCENE_OPTIONS[name][0]
    if kind == "flag":
        if not isinstance(value, bool | np.bool_):
            raise InvalidRequestError(f"{name} is true or false, got {value!r}", culprit=value)
        return bool(value)
    if kind == "point":
        if isinstance(value, str | bytes) or np.ndim(value) != 1 or len(value) != 3:
            raise InvalidRequestError(f"{name} takes three numbers such as (0, 0, 1), got {value!r}", culprit=value)
        return tuple(float(read_number(v, name)) for v in value)
    number = float(read_number(value, name))
    if number < 0:
        raise InvalidRequestError(f"{name} cannot be negative, got {value!r}", culprit=value)
    return number


def _scene_backend(path: Path, scene: dict) -> PybulletRunner:
    """The backend of a URDF in a scene: each of :data:`SCENE_OPTIONS` given (``damping`` may be None)."""
    scene = {name: None if value is None else scene_option(name, value) for name, value in scene.items()}
    document = read_urdf(path)
    settings = {
        "g": scene["g"],
        "timestep": _BULLET["bullet_time_step"].default,
        **{name: _BULLET[constant].default for name, constant, _note in ENGINE_PARAMETERS},
        "useSplitImpulse": int(scene["split_impulse"]),
        "margins": {},
        "friction": {},
        "damping": {},
        "max_joint_velocity": {},
        "inertia": {},
        "mass": {},
        "springs": {},
        "ground_margin": _BULLET["bullet_collision_margin"].default,
    }
    placed = {name: scene[name] for name in ("base_position", "fixed_base", "ground")}
    backend = PybulletRunner(document, settings, scene=placed)
    document.warn_compound_meshes()
    backend._settings["damping"] = backend._damping(scene["damping"])
    return backend


def _load_saved(path: Path, saved: Path) -> EngineModel:
    """The model of a saved URDF with the settings :meth:`PybulletRunner.save` wrote beside it."""

    def malformed(err) -> EngineModelError:
        what = f"key {err}" if isinstance(err, KeyError) else str(err).splitlines()[0]
        return EngineModelError(str(saved), "settings", f"not a settings file written by pitheorem ({what})")

    try:
        doc = json.loads(saved.read_text())
        gravity, load = doc["gravity"], doc["loadURDF"]
        engine = doc["setPhysicsEngineParameter"]
        sideways = gravity[0] or gravity[1] or gravity[2] > 0
    except (OSError, ValueError, KeyError, TypeError, IndexError) as err:
        raise malformed(err) from None
    if sideways:
        raise EngineModelError(str(saved), "gravity", "pitheorem's URDF models have gravity along -z only")
    try:  # the scene's one reader, as for engines.load's options: a bad value is the settings file's fault
        given = {
            "base_position": load["basePosition"],
            "fixed_base": load["useFixedBase"],
            "ground": doc["ground"] is not None,
            "split_impulse": bool(engine["useSplitImpulse"]),
            "g": -float(gravity[2]),
        }
        scene = {**{name: scene_option(name, value) for name, value in given.items()}, "damping": None}
    except (ValueError, KeyError, TypeError, IndexError) as err:
        raise malformed(err) from None
    # the URDF's own errors (bad XML, a missing mesh) are raised here as they are, not as the settings file's
    backend = _scene_backend(path, scene)
    st = backend._settings
    try:
        st["timestep"] = float(doc["timeStep"])
        for name, *_ in ENGINE_PARAMETERS:
            st[name] = float(engine[name])
        if doc["ground"] is not None:
            st["ground_margin"] = float(doc["ground"]["collisionMargin"])
        joints = {str(j) for j, _n, _t in backend._info["joints"]}
        for call in doc["changeDynamics"]:
            key = str(call["linkIndex"])
            if "maxJointVelocity" in call and key in joints:
                st["max_joint_velocity"][key] = float(call["maxJointVelocity"])
            if "collisionMargin" in call:
                st["margins"][key] = float(call["collisionMargin"])
            if "localInertiaDiagonal" in call:
                st["inertia"][key] = [float(v) for v in call["localInertiaDiagonal"]]
            if "mass" in call:
                st["mass"][key] = float(call["mass"])
            for name in ("rollingFriction", "spinningFriction"):
                if name in call:
                    st["friction"].setdefault(key, {})[name] = float(call[name])
            for name, *_ in MIXED_DAMPING:
                if name in call:
                    st["damping"].setdefault(key, {})[name] = float(call[name])
        for spring in doc.get("jointSprings", []):  # a file saved before springs existed has none
            key = str(spring["jointIndex"])
            if key not in joints:
                raise ValueError(f"jointSprings: joint {key} is not a movable joint")
            st["springs"][key] = [float(spring["stiffness"]), float(spring["restPosition"])]
    except (ValueError, KeyError, TypeError, IndexError) as err:
        raise malformed(err) from None
    return EngineModel(backend, "pybullet", str(path))
