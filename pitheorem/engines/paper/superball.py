"""SUPERball, the white paper's robot, as a MuJoCo tensegrity.

The white paper exists because NTRT simulates SUPERball, a six-bar tensegrity
robot, in a decimetre world with g = 98.1.  This module writes that robot as
an MJCF model so that the paper's Section 4 scaling can be checked in a real
engine, together with the closed-loop controller that Section 6 warns about.

* :data:`PARAMETERS` lists every parameter with its value, dimension and
  source (NTRT's ``T6Model`` configuration, converted from decimetres to
  metres, or a value chosen here, said so);
* :func:`superball_mjcf` writes the model: six capsule bars (density
  ``rho``, length ``l``, radius ``r``) joined by 24 cables, MuJoCo spatial
  tendons that pull only (stiffness ``k``, damping ``c``, rest length
  ``x_r``), each with a reel motor, dropped onto a ground plane;
* :class:`CableController` is a proportional law on cable strain that makes
  the robot lean and tip forward; its gain ``K_eps`` is a length per time,
  so a similarity scaling must scale it (Section 6 made concrete).  Its
  parameters are stored in the model file (MJCF ``<custom>`` numerics, with
  their dimensions beside them), so scaling the file scales the controller;
* :func:`superball_system` is the dimensional analysis of all of it, and
  :func:`write_superball` regenerates ``pitheorem/examples/superball.xml``
  (``python -m pitheorem.engines.paper.superball``).

The file is an ordinary MJCF model: :func:`pitheorem.engines.load` reads it
(the controller's numbers with their declared dimensions among its
parameters), ``model.scaled(...)`` scales it, and
``engines.verify(model, scaling, s, controller=CableController)`` runs the
original, its one-ulp twin and the scaled copy, each with a controller built
from its own file.

Examples
--------
>>> from fractions import Fraction
>>> from pitheorem.engines.paper.superball import superball_system, PAPER_SCALING
>>> import pitheorem as pt
>>> res = pt.search(superball_system(), scale={"g": 1})
>>> PAPER_SCALING in [{n: Fraction(e) for n, e in sc.exponents.items()} for sc in res.scalings]
True
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import numpy as np

from ...dimensions import Dimension
from ...errors import InvalidRequestError
from ...immutable import immutable
from ...modelfile import EXAMPLES
from ...system import System
from ..enginemodel import EngineModel
from ..parameters import attribute_text, dim

__all__ = [
    "PAPER_SCALING",
    "PARAMETERS",
    "CableController",
    "SuperballParameter",
    "bar_ends",
    "bar_nodes",
    "cable_pairs",
    "draw_superball",
    "superball_mjcf",
    "superball_parameters",
    "superball_system",
    "write_superball",
]


@immutable
@dataclass(frozen=True, slots=True)
class SuperballParameter:
    """One parameter of the SUPERball model.

    Parameters
    ----------
    name : str
        The symbol used in the System and the docs.
    value : float
        Its value in SI units (kg, m, s).
    dimension : Dimension
        Its dimension over M, L, T.
    description : str
        What it is, and where it appears in the MJCF file.
    source : str
        Where the value comes from.

    Examples
    --------
    >>> from pitheorem.engines.paper.superball import PARAMETERS
    >>> PARAMETERS[0].name, PARAMETERS[0].dimension
    ('g', Dimension.parse('L T^-2'))
    """

    name: str
    value: float
    dimension: Dimension
    description: str
    source: str


_NTRT = "NTRT T6Model (SUPERball) config"
_CHOSEN = "chosen here"

#: Every parameter of the model, in the order of the System.  NTRT's SUPERball
#: runs in decimetres (its g is 98.1), so its lengths are divided by 10 here,
#: its density multiplied by 1000 and its forces divided by 10; stiffness and
#: damping (M T^-2 and M T^-1) have no length and keep their values.
PARAMETERS: tuple[SuperballParameter, ...] = (
    SuperballParameter(
        "g", 9.81, dim("L T^-2"), "gravitational acceleration (option gravity)", "Earth; NTRT uses 98.1 dm/s^2"
    ),
    SuperballParameter("rho", 688.0, dim("M L^-3"), "density of the bars (geom density)", _NTRT + ": 0.688 kg/dm^3"),
    SuperballParameter("l", 1.684, dim("L"), "length of a bar (geom fromto)", _NTRT + ": 16.84 dm"),
    SuperballParameter("r", 0.031, dim("L"), "radius of a bar (geom size)", _NTRT + ": 0.31 dm"),
    SuperballParameter(
        "a", 0.75, dim("L"), "offset of each bar from the centre (body pos)", _NTRT + ": rod_space 7.5 dm"
    ),
    SuperballParameter("k", 613.0, dim("M T^-2"), "cable stiffness (tendon stiffness)", _NTRT + ": 613 kg/s^2"),
    SuperballParameter("c", 200.0, dim("M T^-1"), "cable damping (tendon damping)", _NTRT + ": 200 kg/s"),
    SuperballParameter(
        "F", 245.2, dim("M L T^-2"), "cable pretension, k (span - x_r)", _NTRT + ": pretension 2452 kg dm/s^2"
    ),
    SuperballParameter("x_r", math.nan, dim("L"), "cable rest length (tendon springlength)", "from F: span - F/k"),
    SuperballParameter(
        "F_max",
        10000.0,
        dim("M L T^-2"),
        "largest cable tension a reel motor adds (actuator ctrlrange)",
        _NTRT + ": maxTens 100000 kg dm/s^2",
    ),
    SuperballParameter(
        "v",
        0.5,
        dim("L T^-1"),
        "fastest reel speed, the target actuator velocity (custom numeric)",
        _CHOSEN + " (NTRT's 10000 dm/s never binds)",
    ),
    SuperballParameter(
        "K_eps", 4.0, dim("L T^-1"), "controller gain: reel speed per unit of cable strain (custom numeric)", _CHOSEN
    ),
    SuperballParameter("A", 0.5, dim("1"), "largest strain the controller asks of a cable (custom numeric)", _CHOSEN),
    SuperballParameter("t_on", 1.0, dim("T"), "time the controller starts (custom numeric)", _CHOSEN),
    SuperballParameter(
        "t_ramp", 0.5, dim("T"), "time its targets take to reach full strength (custom numeric)", _CHOSEN
    ),
    SuperballParameter("mu", 0.99, dim("1"), "sliding friction (geom friction)", _NTRT + ": friction 0.99"),
    SuperballParameter(
        "mu_roll",
        0.001,
        dim("L"),
        "torsional and rolling friction, lengths in MuJoCo (geom friction)",
        _NTRT + ": rollFriction 0.01, read as decimetres",
    ),
    SuperballParameter("t_c", 0.02, dim("T"), "contact time constant (geom solref)", "MuJoCo's default, written out"),
    SuperballParameter("w", 0.001, dim("L"), "contact impedance width (geom solimp)", "MuJoCo's default, written out"),
    SuperballParameter("h0", 0.2, dim("L"), "drop height of the lowest point (body pos)", _CHOSEN),
    SuperballParameter("dt", 0.001, dim("T"), "time step (option timestep)", _CHOSEN),
    SuperballParameter("t", math.nan, dim("T"), "time", "the simulation clock"),
)

#: The exponents of the white paper's Section 4 answer, x_r included: g and
#: lengths times s, F and v times s, rho times s^-3, time, k and c unchanged.
PAPER_SCALING: dict[str, Fraction] = {
    name: Fraction(power)
    for name, power in {
        "g": 1,
        "rho": -3,
        "l": 1,
        "r": 1,
        "a": 1,
        "k": 0,
        "c": 0,
        "F": 1,
        "x_r": 1,
        "F_max": 1,
        "v": 1,
        "K_eps": 1,
        "A": 0,
        "t_on": 0,
        "t_ramp": 0,
        "mu": 0,
        "mu_roll": 1,
        "t_c": 0,
        "w": 1,
        "h0": 1,
        "dt": 0,
        "t": 0,
    }.items()
}

# The controller's parameters, stored as MJCF custom numerics.
_CONTROLLER = ("v", "K_eps", "A", "t_on", "t_ramp")
# The two angles (radians) that tip the robot so it lands on a face.
_TILT = (0.5, 0.3)


def superball_parameters() -> dict[str, float]:
    """The parameter values of the model, SI units, ``x_r`` computed from ``F``.

    Returns
    -------
    dict of str to float
        Every parameter of :data:`PARAMETERS` except the time ``t``.

    Examples
    --------
    >>> from pitheorem.engines.paper.superball import superball_parameters
    >>> p = superball_parameters()
    >>> round(p["x_r"], 4), p["k"]
    (0.7313, 613.0)
    """
    values = {p.name: p.value for p in PARAMETERS if p.name != "t"}
    values["x_r"] = _span(values) - values["F"] / values["k"]
    return values


def superball_system() -> System:
    """The dimensional analysis of the model: every parameter, controller included.

    Returns
    -------
    System
        The variables of :data:`PARAMETERS`, in that order, ``t`` last.

    Examples
    --------
    >>> from pitheorem.engines.paper.superball import superball_system
    >>> sb = superball_system()
    >>> sb.rank, len(sb.variables)
    (3, 22)
    """
    return System({p.name: p.dimension for p in PARAMETERS})


def bar_nodes(a: float, l: float) -> list[tuple[np.ndarray, np.ndarray]]:  # noqa: E741
    """The two end points of each of the six bars, before the tilt.

    Three pairs of parallel bars lie along the x, y and z axes, each pair at
    distance ``a`` on either side of the centre, as in NTRT's six-bar model.

    Parameters
    ----------
    a : float
        Offset of each bar from the centre.
    l : float
        Length of a bar.

    Returns
    -------
    list of (ndarray, ndarray)

    Examples
    --------
    >>> from pitheorem.engines.paper.superball import bar_nodes
    >>> [tuple(float(x) for x in end) for end in bar_nodes(1.0, 4.0)[0]]
    [(1.0, -2.0, 0.0), (1.0, 2.0, 0.0)]
    """
    h = l / 2
    ends = (
        ((a, -h, 0), (a, h, 0)),
        ((-a, -h, 0), (-a, h, 0)),
        ((0, a, -h), (0, a, h)),
        ((0, -a, -h), (0, -a, h)),
        ((-h, 0, a), (h, 0, a)),
        ((-h, 0, -a), (h, 0, -a)),
    )
    return [(np.array(e0, float), np.array(e1, float)) for e0, e1 in ends]


def cable_pairs(a: float, l: float) -> tuple[list[tuple[tuple[int, int], tuple[int, int]]], float]:  # noqa: E741
    """The 24 cables as pairs of bar ends, and their common length (the span).

    Each bar end is tied to the four nearest ends of bars that are not
    parallel to its own: the edges of an icosahedron less the six short
    edges between parallel bars.

    Parameters
    ----------
    a, l : float
        As in :func:`bar_nodes`.

    Returns
    -------
    pairs : list of ((bar, end), (bar, end))
    span : float

    Examples
    --------
    >>> from pitheorem.engines.paper.superball import cable_pairs
    >>> pairs, span = cable_pairs(0.75, 1.684)
    >>> len(pairs), round(span, 4)
    (24, 1.1313)
    """
    bars = bar_nodes(a, l)
    ends = [(i, j, bars[i][j]) for i in range(6) for j in range(2)]
    candidates = [
        ((i, j), (k, m), float(np.linalg.norm(x - y)))
        for (i, j, x), (k, m, y) in itertools.combinations(ends, 2)
        if i // 2 != k // 2
    ]
    span = min(d for _, _, d in candidates)
    pairs = [(e0, e1) for e0, e1, d in candidates if d <= span * (1 + 1e-9)]
    if len(pairs) != 24:
        raise InvalidRequestError(
            f"bar offset a={a} and length l={l} do not give a six-bar tensegrity "
            f"(found {len(pairs)} nearest cables, need 24); use a between l/4 and l/2"
        )
    return pairs, span


def _span(params) -> float:
    return cable_pairs(params["a"], params["l"])[1]


def _rotation(ax: float, ay: float) -> np.ndarray:
    cx, sx, cy, sy = math.cos(ax), math.sin(ax), math.cos(ay), math.sin(ay)
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    return ry @ rx


def superball_mjcf(params=None) -> str:
    """The MJCF text of SUPERball with the given parameter values.

    Parameters
    ----------
    params : mapping of str to float, optional
        Values for the names of :data:`PARAMETERS`; missing ones take
        :func:`superball_parameters`.  ``x_r`` given here wins over ``F``.

    Returns
    -------
    str
        A model MuJoCo loads as is: 6 bodies with free joints, 24 spatial
        tendons and 24 motors, and the controller's parameters in ``<custom>``.

    Examples
    --------
    >>> import mujoco
    >>> from pitheorem.engines.paper.superball import superball_mjcf
    >>> m = mujoco.MjModel.from_xml_string(superball_mjcf())
    >>> m.nbody - 1, m.ntendon, m.nu
    (6, 24, 24)
    """
    p = superball_parameters()
    if params is not None:
        unknown = sorted(set(params) - set(p))
        if unknown:
            raise InvalidRequestError(
                f"unknown SUPERball parameter {unknown[0]!r}; use names of PARAMETERS: " + ", ".join(sorted(p))
            )
        p.update({n: float(v) for n, v in params.items()})
        if "x_r" not in params:
            p["x_r"] = _span(p) - p["F"] / p["k"]
    pairs, _ = cable_pairs(p["a"], p["l"])
    turn = _rotation(*_TILT)
    bars = [(turn @ e0, turn @ e1) for e0, e1 in bar_nodes(p["a"], p["l"])]
    lift = p["h0"] + p["r"] - min(min(e0[2], e1[2]) for e0, e1 in bars)
    friction = f"{p['mu']!r} {p['mu_roll']!r} {p['mu_roll']!r}"
    contact = f'condim="6" friction="{friction}" solref="{p["t_c"]!r} 1" solimp="0.9 0.95 {p["w"]!r} 0.5 2"'
    lines = [
        '<mujoco model="superball">',
        '  <compiler angle="radian"/>',
        # tolerance 0: the solver always runs its iterations, so its stopping
        # test (normalised by the model's mean inertia) cannot break similarity.
        f'  <option timestep="{p["dt"]!r}" gravity="0 0 {-p["g"]!r}" integrator="implicitfast" cone="elliptic" '
        'iterations="50" ls_iterations="50" tolerance="0"/>',
        "  <custom>",
    ]
    for name in _CONTROLLER:
        lines.append(f'    <numeric name="{name}" data="{p[name]!r}"/>')
        lines.append(f'    <text name="dimension:{name}" data="{_dimension(name)}"/>')
    lines += ["  </custom>", "  <worldbody>", f'    <geom name="ground" type="plane" size="0 0 1" {contact}/>']
    for i, (e0, e1) in enumerate(bars):
        centre = (e0 + e1) / 2
        end0, end1 = attribute_text(e0 - centre), attribute_text(e1 - centre)
        lines += [
            f'    <body name="bar{i}" pos="{attribute_text(centre + np.array([0.0, 0.0, lift]))}">',
            f'      <freejoint name="bar{i}"/>',
            f'      <geom name="bar{i}" type="capsule" fromto="{end0} {end1}" '
            f'size="{p["r"]!r}" density="{p["rho"]!r}" {contact}/>',
            f'      <site name="bar{i}_end0" pos="{end0}"/>',
            f'      <site name="bar{i}_end1" pos="{end1}"/>',
            "    </body>",
        ]
    lines += ["  </worldbody>", "  <tendon>"]
    for n, ((i, j), (k, m)) in enumerate(pairs):
        # springlength "0 x_r": no force between 0 and x_r, so a cable pulls but never pushes
        lines.append(
            f'    <spatial name="cable{n}" stiffness="{p["k"]!r}" damping="{p["c"]!r}" '
            f'springlength="0 {p["x_r"]!r}"><site site="bar{i}_end{j}"/><site site="bar{k}_end{m}"/>'
            "</spatial>"
        )
    lines += ["  </tendon>", "  <actuator>"]
    for n in range(len(pairs)):
        lines.append(f'    <motor name="reel{n}" tendon="cable{n}" ctrlrange="{-p["F_max"]!r} 0"/>')
    lines += ["  </actuator>", "</mujoco>", ""]
    return "\n".join(lines)


def _dimension(name: str) -> str:
    return str(next(p.dimension for p in PARAMETERS if p.name == name))


def _compiled(model):
    """The compiled MuJoCo model: an EngineModel's, or `model` itself (a ``mujoco.MjModel``)."""
    return model.runner.mjmodel if isinstance(model, EngineModel) else model


class CableController:
    """Closed-loop reel control: a proportional law on cable strain.

    Each cable ``i`` has a reeled-in length ``d_i >= 0`` (the controller's
    state, starting at 0), so its rest length is ``x_r - d_i``; its motor
    adds the tension ``k d_i``.  From ``t_on`` on, the controller asks the cables that
    lie ahead (+x) of and below the robot's centre to shorten by up to ``A``
    of their span, and reels at the speed ``K_eps (eps_i - eps_target_i)``,
    limited to ``v``, where ``eps_i`` is the cable's measured strain.  The
    robot leans forward and tips over onto its next face.

    The parameters are read from the compiled model (custom numerics, the
    tendon stiffness and the initial tendon lengths), so a scaled model file
    carries a scaled controller; the controller itself holds no number.

    Parameters
    ----------
    model : mujoco.MjModel or EngineModel
        A model written by :func:`superball_mjcf`, or a scaled copy of it;
        an :class:`~pitheorem.engines.EngineModel` of one works too, so
        ``engines.verify(model, scaling, s, controller=CableController)``
        builds one controller per run from that run's own (scaled) model.

    Examples
    --------
    >>> import mujoco
    >>> from pitheorem.engines.paper.superball import CableController, superball_mjcf
    >>> m = mujoco.MjModel.from_xml_string(superball_mjcf())
    >>> d = mujoco.MjData(m)
    >>> control = CableController(m)
    >>> mujoco.mj_forward(m, d)
    >>> float(control(m, d).sum())     # before t_on nothing is reeled in
    0.0
    """

    def __init__(self, model):
        model = _compiled(model)

        def numeric(name: str) -> float:
            try:
                return float(model.numeric(name).data[0])
            except KeyError:
                raise InvalidRequestError(
                    f"model has no custom numeric {name!r}; write it with superball_mjcf", culprit=name
                ) from None

        self.v, self.gain, self.amplitude = numeric("v"), numeric("K_eps"), numeric("A")
        self.t_on, self.t_ramp = numeric("t_on"), numeric("t_ramp")
        self.stiffness = np.array(model.tendon_stiffness, dtype=float)
        # each cable's length in the robot's starting pose, as MuJoCo's compiler measured it
        self.span = np.array(model.tendon_length0, dtype=float)
        self._first = model.wrap_objid[model.tendon_adr]
        self._second = model.wrap_objid[model.tendon_adr + 1]
        self.reeled = np.zeros(model.ntendon)
        self._last_time = 0.0

    def targets(self, data) -> np.ndarray:
        """The target strain of each cable, from the robot's current pose.

        Parameters
        ----------
        data : mujoco.MjData

        Returns
        -------
        ndarray
            Zero or negative strains, one per cable.

        Examples
        --------
        >>> import mujoco
        >>> from pitheorem.engines.paper.superball import CableController, superball_mjcf
        >>> m = mujoco.MjModel.from_xml_string(superball_mjcf())
        >>> d = mujoco.MjData(m); mujoco.mj_forward(m, d)
        >>> CableController(m).targets(d).shape
        (24,)
        """
        sites = data.site_xpos
        middle = (sites[self._first] + sites[self._second]) / 2
        centre = sites.mean(axis=0)
        scale = 0.25 * self.span
        # smooth weights (no switching, so nearby runs stay nearby): ahead of and below the centre
        ahead = 0.5 * (1 + np.tanh((middle[:, 0] - centre[0]) / scale))
        below = 0.5 * (1 + np.tanh((centre[2] - middle[:, 2]) / scale))
        ramp = min(1.0, max(0.0, (data.time - self.t_on) / self.t_ramp))
        return -self.amplitude * ramp * ahead * below

    def __call__(self, model, data) -> np.ndarray:
        """Advance the reels by one step and return the motor forces.

        Parameters
        ----------
        model : mujoco.MjModel
        data : mujoco.MjData

        Returns
        -------
        ndarray
            ``data.ctrl`` for this step: zero or negative tensions.

        Examples
        --------
        See the class.
        """
        step = data.time - self._last_time
        self._last_time = data.time
        strain = data.ten_length / self.span - 1
        speed = np.clip(self.gain * (strain - self.targets(data)), -self.v, self.v)
        # a reel shortens its cable and lets it back out to the rest length x_r, never further: the motor
        # only adds tension (ctrlrange [-F_max, 0]), so a negative reeled length would only wind up unseen
        self.reeled = np.maximum(self.reeled + speed * step, 0.0)
        return -self.stiffness * self.reeled


def bar_ends(model, rows) -> np.ndarray:
    """The twelve bar ends of each recorded state of a run: where the bars' end sites are.

    A run (:meth:`pitheorem.engines.EngineModel.run`) records each bar's
    free joint: its centre and its orientation as a unit quaternion.  An
    end sits at a fixed place in its bar's frame (the site ``bar<i>_end<j>``
    of the file), so its position is the centre plus that place turned by
    the quaternion, the kinematics MuJoCo computes for the site.

    Parameters
    ----------
    model : EngineModel
        SUPERball loaded by :func:`pitheorem.engines.load` (the shipped
        file, a file of :func:`superball_mjcf`, or a scaled copy).
    rows : array_like, shape (n, n_coordinates) or (n_coordinates,)
        States as ``model.run`` returns them.

    Returns
    -------
    ndarray, shape (n, 6, 2, 3)
        The positions of the twelve bar ends, in the model's own units.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.paper.superball import CableController, bar_ends
    >>> model = engines.load(engines.example_path("superball.xml"))
    >>> rows = model.run(500, policy=CableController(model))
    >>> ends = bar_ends(model, rows)
    >>> ends.shape, bool(ends[-1, :, :, 2].min() < ends[0, :, :, 2].min())   # it fell
    ((501, 6, 2, 3), True)
    """
    m = _compiled(model)
    rows = np.atleast_2d(np.asarray(rows, dtype=float))
    out = np.empty((len(rows), 12, 3))
    for k in range(12):
        body = m.site_bodyid[k]
        address = m.jnt_qposadr[m.body_jntadr[body]]
        centre, quat = rows[:, address : address + 3], rows[:, address + 3 : address + 7]
        quat = quat / np.linalg.norm(quat, axis=1, keepdims=True)
        w, axis = quat[:, :1], quat[:, 1:]
        place = np.broadcast_to(m.site_pos[k], axis.shape)
        # v turned by the unit quaternion (w, u): v + 2 w (u x v) + 2 u x (u x v)
        turn = np.cross(axis, place)
        out[:, k] = centre + place + 2 * w * turn + 2 * np.cross(axis, turn)
    return out.reshape(len(rows), 6, 2, 3)


def draw_superball(ends, ax=None, *, a: float | None = None, l: float | None = None, color="C0"):  # noqa: E741
    """Draw one pose of the robot in 3-D: bars as thick lines, cables as thin ones.

    Parameters
    ----------
    ends : array_like, shape (6, 2, 3)
        Bar end positions, one sample of :func:`bar_ends`.
    ax : matplotlib 3-D axes, optional
        Drawn into a new figure when omitted.
    a, l : float, optional
        Bar offset and length that fix which ends the cables join; the
        defaults of :data:`PARAMETERS` when omitted.
    color : str
        Colour of the bars.

    Returns
    -------
    matplotlib 3-D axes

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from pitheorem import engines
    >>> from pitheorem.engines.paper.superball import bar_ends, draw_superball
    >>> model = engines.load(engines.example_path("superball.xml"))
    >>> ax = draw_superball(bar_ends(model, model.run(0))[0])
    >>> len(ax.lines)    # 6 bars and 24 cables
    30
    """
    import matplotlib.pyplot as plt

    values = superball_parameters()
    pairs, _ = cable_pairs(values["a"] if a is None else a, values["l"] if l is None else l)
    ends = np.asarray(ends, dtype=float)
    if ax is None:
        ax = plt.figure(figsize=(4.5, 4.5)).add_subplot(projection="3d")
    for bar in ends:
        ax.plot(*bar.T, color=color, linewidth=4, solid_capstyle="round")
    for (i, j), (k, m) in pairs:
        ax.plot(*np.array([ends[i, j], ends[k, m]]).T, color="0.35", linewidth=0.8)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.set_aspect("equal")
    return ax


def write_superball(path=None) -> Path:
    """Write the model with its default parameters; by default the shipped example.

    Parameters
    ----------
    path : str or Path, optional
        Where to write; ``pitheorem/examples/superball.xml`` when omitted.

    Returns
    -------
    Path

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from pitheorem.engines.paper.superball import write_superball, superball_mjcf
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     written = write_superball(pathlib.Path(folder) / "sb.xml")
    ...     written.read_text() == superball_mjcf()
    True
    """
    target = Path(path) if path is not None else EXAMPLES / "superball.xml"
    target.write_text(superball_mjcf(), encoding="utf-8")
    return target


if __name__ == "__main__":  # pragma: no cover - the documented way to regenerate the shipped file
    print(write_superball())
