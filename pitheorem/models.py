"""The white paper's models and parameter lists, in its notation.

Each model is defined once, by its sympy equations of motion: a
:class:`pitheorem.Model` solves them and generates the numeric right-hand
side that :func:`pitheorem.simulate` integrates, and ``model.equations``
gives them to :func:`pitheorem.check_dimensions` and
:func:`pitheorem.scaling_symmetries`.

* :func:`hinged_rod`: the rod on a hinge with a rotational spring and damper
  (Eq. 1 of the paper, with the restoring spring sign of its MATLAB code);
* :func:`hinged_rod_longitudinal`: the same rod held by a longitudinal spring
  (and optionally a longitudinal damper), in a dimensionally correct form;
* :func:`spring_mass_damper`: the vertical spring-mass-damper of Section 5;
* :func:`projectile`: a point mass under gravity.

It also holds the paper's parameter lists as systems: :func:`rod_system`
(Section 2.1) and :func:`superball_parameters` (Section 4, NTRT SUPERball).
The :class:`~pitheorem.Model` type itself is in ``pitheorem.model``;
simulation and similarity checks are in ``pitheorem.simulation``.
"""

from __future__ import annotations

import math

import sympy

from .model import Model
from .system import System

__all__ = [
    "hinged_rod",
    "hinged_rod_longitudinal",
    "projectile",
    "rod_system",
    "spring_mass_damper",
    "superball_parameters",
]


# -- parameter lists of the paper ------------------------------------------------------------

_ROD = {
    "m": "M",
    "theta_r": "1",
    "l": "L",
    "g": "L T^-2",
    "k_theta": "M L^2 T^-2",
    "c_theta": "M L^2 T^-1",
    "t": "T",
    "F": "M L T^-2",
    "tau": "M L^2 T^-2",
}

_SUPERBALL = {
    "m": "M",
    "l": "L",
    "k": "M T^-2",
    "x_r": "L",
    "g": "L T^-2",
    "c": "M T^-1",
    "F": "M L T^-2",
    "t": "T",
    "G": "M L^-1 T^-2",
    "E": "M L^-1 T^-2",
    "v": "L T^-1",
    "rho": "M L^-3",
}


def rod_system() -> System:
    """The paper's nine rod variables (Section 2.1).

    Force and torque included: ``m, theta_r, l, g, k_theta, c_theta, t, F, tau``, in the paper's order.

    Returns
    -------
    System
        Nine variables, rank 3: six dimensionless groups.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.models.rod_system()
    >>> len(rod), rod.rank, rod.n_groups
    (9, 3, 6)
    """
    return System(_ROD)


def superball_parameters() -> System:
    """The NTRT SUPERball parameters of Section 4, plus m and l.

    Longitudinal spring ``k ~ M T^-2`` and damper ``c ~ M T^-1``, rest length
    ``x_r``, gravity, pretension ``F``, time, the Corde moduli ``G`` and
    ``E``, actuator speed ``v`` and density ``rho``.

    Returns
    -------
    System
        Twelve variables, rank 3: nine dimensionless groups.

    Examples
    --------
    >>> from pitheorem.models import superball_parameters
    >>> sb = superball_parameters()
    >>> sb.variables
    ('m', 'l', 'k', 'x_r', 'g', 'c', 'F', 't', 'G', 'E', 'v', 'rho')
    >>> sb.n_groups
    9
    """
    return System(_SUPERBALL)


# -- the models, each by its equations --------------------------------------------------------


def _symbols(states: str, parameters: str):
    """The time ``t``, the states as functions of it, and the parameters, all positive but the states."""
    t = sympy.Symbol("t", positive=True)
    return t, [sympy.Function(n)(t) for n in states.split()], sympy.symbols(parameters, positive=True)


def hinged_rod() -> Model:
    r"""The paper's hinged rod, rotational spring and damper (Eq. 1).

    A uniform rod (mass ``m``, length ``l``, ``I = m l^2 / 3`` about the
    hinge) makes the angle ``theta`` with the horizontal, measured in the
    direction gravity turns it; a rotational spring ``k_theta`` (rest angle
    ``theta_r``) and damper ``c_theta`` act at the hinge::

        theta'' = 3/(m l^2) ((m g l / 2) cos(theta) - c_theta theta'
                             - k_theta (theta - theta_r))

    ERRATUM: the paper's Eq. (1) prints ``+ k_theta theta - k_theta theta_r``
    (an anti-restoring spring); its MATLAB code, which made the figures,
    and this model use the restoring sign above.

    States ``theta`` (dimensionless) and ``omega = theta'`` (``T^-1``).
    Defaults are those of the paper's MATLAB program: ``m=1.5, l=2,
    g=9.81, k_theta=100, c_theta=10, theta_r=pi/3``, from ``theta=pi/4``,
    ``omega=0``.

    Returns
    -------
    Model
        States ``theta``, ``omega``; parameters in the order of Eq. 1.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.models.hinged_rod()
    >>> rod.parameters, rod.states
    (('m', 'l', 'g', 'k_theta', 'c_theta', 'theta_r'), ('theta', 'omega'))
    >>> rod.rhs(0.0, [rod.defaults["theta_r"], 0.0], {**rod.defaults, "g": 0.0}).tolist()
    [0.0, 0.0]
    """
    t, (theta, omega), (m, l, g, k, c, theta_r) = _symbols("theta omega", "m l g k_theta c_theta theta_r")  # noqa: E741
    torque = m * g * l / 2 * sympy.cos(theta) - c * omega - k * (theta - theta_r)
    return Model(
        System(
            {
                "m": "M",
                "l": "L",
                "g": "L T^-2",
                "k_theta": "M L^2 T^-2",
                "c_theta": "M L^2 T^-1",
                "theta_r": "1",
                "t": "T",
                "theta": "1",
                "omega": "T^-1",
            }
        ),
        [sympy.Eq(theta.diff(t), omega), sympy.Eq(omega.diff(t), 3 / (m * l**2) * torque)],
        defaults={"m": 1.5, "l": 2.0, "g": 9.81, "k_theta": 100.0, "c_theta": 10.0, "theta_r": math.pi / 3},
        initial={"theta": math.pi / 4, "omega": 0.0},
        name="hinged_rod",
        description="rod on a hinge with rotational spring and damper (white paper Eq. 1, restoring sign)",
    )


def hinged_rod_longitudinal(damper: bool = True) -> Model:
    r"""The hinged rod held by a longitudinal spring (and damper).

    Geometry (derived here; the paper's commented-out MATLAB variants are
    dimensionally inconsistent, see :mod:`matlab_ports.rod_hinge_dynamics`):
    the hinge is at the origin, ``theta`` is the rod's angle to the
    horizontal, positive in the direction gravity turns it, so the tip is
    at ``l (cos theta, sin theta)`` with the second axis pointing down.  A
    spring (constant ``k ~ M T^-2``, rest length ``x_r ~ L``) joins the tip
    to an anchor a distance ``2 l`` above the hinge, at ``(0, -2 l)``, out
    of the tip's reach.  The spring's length and its rate of change with
    the angle are::

        x = l sqrt(5 + 4 sin(theta)),     dx/dtheta = 2 l^2 cos(theta) / x

    The tension ``T = k (x - x_r) + c x'`` (``x' = dx/dtheta * omega``; the
    damper ``c ~ M T^-1`` only with ``damper=True``) acts along the spring.
    Its torque about the hinge, force times lever arm (the cross product of
    the tip position with the force), is ``-T dx/dtheta``, as virtual work
    requires.  With ``I = m l^2 / 3``::

        theta'' = 3/(m l^2) ((m g l / 2) cos(theta) - 2 T l^2 cos(theta) / x)

    Every term in the bracket is a torque ``M L^2 T^-2``, and ``x >= l``
    never vanishes, so the model has no singular angle.

    Parameters
    ----------
    damper : bool
        Include the longitudinal damper ``c``.

    Returns
    -------
    Model
        Parameters ``m, l, g, k, x_r`` (and ``c``); states ``theta``,
        ``omega``.  Defaults ``m=1.5, l=2, g=9.81`` as for
        :func:`hinged_rod`, ``k=20, x_r=4, c=2`` (equilibrium close to the
        horizontal, ``theta = -0.037``), from ``theta=pi/4``, ``omega=0``.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.models.hinged_rod_longitudinal(damper=False)
    >>> rod.parameters
    ('m', 'l', 'g', 'k', 'x_r')
    >>> str(rod.system.dimension("k")), str(rod.system.dimension("x_r"))
    ('M T^-2', 'L')
    """
    dims = {"m": "M", "l": "L", "g": "L T^-2", "k": "M T^-2", "x_r": "L", "c": "M T^-1"}
    defaults = {"m": 1.5, "l": 2.0, "g": 9.81, "k": 20.0, "x_r": 4.0, "c": 2.0}
    t, (theta, omega), (m, l, g, k, x_r, c) = _symbols("theta omega", "m l g k x_r c")  # noqa: E741
    length = l * sympy.sqrt(5 + 4 * sympy.sin(theta))  # tip to the anchor at (0, -2 l)
    arm = 2 * l**2 * sympy.cos(theta) / length  # d length / d theta: a tension T has torque -T arm
    tension = k * (length - x_r) + (c * arm * omega if damper else 0)  # the damper acts on length'
    if not damper:
        del dims["c"], defaults["c"]
    return Model(
        System({**dims, "t": "T", "theta": "1", "omega": "T^-1"}),
        [
            sympy.Eq(theta.diff(t), omega),
            sympy.Eq(omega.diff(t), 3 / (m * l**2) * (m * g * l / 2 * sympy.cos(theta) - tension * arm)),
        ],
        defaults=defaults,
        initial={"theta": math.pi / 4, "omega": 0.0},
        name="hinged_rod_longitudinal",
        description=f"hinged rod held by a longitudinal spring{' and damper' if damper else ''} from its tip "
        "to an anchor a distance 2 l above the hinge",
    )


def spring_mass_damper() -> Model:
    """Vertical spring-mass-damper under gravity (Section 5).

    ``m y'' = -k (y - y_rest) - c y' - m g`` with states ``y`` (position,
    ``L``) and ``v = y'`` (``L T^-1``).  Defaults as in the paper's linear
    MATLAB program: ``m=2, k=150, c=10, g=9.81, y_rest=1``, from ``y=1``,
    ``v=0``.

    Returns
    -------
    Model
        Newton's law in the form ``m v' = F``, solved for ``v'`` once.

    Examples
    --------
    >>> import pitheorem as pt
    >>> smd = pt.models.spring_mass_damper()
    >>> y_static = 1.0 - 2.0 * 9.81 / 150.0   # y_rest - m g / k
    >>> abs(float(smd.rhs(0.0, [y_static, 0.0], dict(smd.defaults))[1])) < 1e-12  # at rest there
    True
    """
    t, (y, v), (m, k, c, g, y_rest) = _symbols("y v", "m k c g y_rest")
    return Model(
        System(
            {"m": "M", "k": "M T^-2", "c": "M T^-1", "g": "L T^-2", "y_rest": "L", "t": "T", "y": "L", "v": "L T^-1"}
        ),
        [sympy.Eq(y.diff(t), v), sympy.Eq(m * v.diff(t), -k * (y - y_rest) - c * v - m * g)],
        defaults={"m": 2.0, "k": 150.0, "c": 10.0, "g": 9.81, "y_rest": 1.0},
        initial={"y": 1.0, "v": 0.0},
        name="spring_mass_damper",
        description="vertical spring-mass-damper under gravity (white paper Section 5)",
    )


def projectile() -> Model:
    """A point mass under gravity, without drag.

    States ``x, y`` (``L``) and ``vx, vy`` (``L T^-1``); parameters ``m``
    (which the motion does not depend on) and ``g``.  Defaults ``m=2,
    g=9.81``; launch from the origin at ``v0 = 10`` and 45 degrees:
    ``vx = vy = 10 cos(pi/4)``.  (The paper's MATLAB program launches
    straight up; see :mod:`matlab_ports.scaling_counterexample_projectile`.)

    Returns
    -------
    Model
        Parameters ``m, g``; states ``x, y, vx, vy``.

    Examples
    --------
    >>> import pitheorem as pt
    >>> proj = pt.models.projectile()
    >>> proj.states
    ('x', 'y', 'vx', 'vy')
    >>> round(proj.initial["vx"], 6), round(proj.initial["vy"], 6)
    (7.071068, 7.071068)
    """
    t, (x, y, vx, vy), g = _symbols("x y vx vy", "g")
    v0, angle = 10.0, math.pi / 4
    return Model(
        System({"m": "M", "g": "L T^-2", "t": "T", "x": "L", "y": "L", "vx": "L T^-1", "vy": "L T^-1"}),
        [sympy.Eq(x.diff(t), vx), sympy.Eq(y.diff(t), vy), sympy.Eq(vx.diff(t), 0), sympy.Eq(vy.diff(t), -g)],
        parameters=("m", "g"),  # m too, though the motion does not depend on it
        defaults={"m": 2.0, "g": 9.81},
        initial={"x": 0.0, "y": 0.0, "vx": v0 * math.cos(angle), "vy": v0 * math.sin(angle)},
        name="projectile",
        description="point mass under gravity, launched at 10 m/s and 45 degrees",
    )
