"""Dynamics of a rod on a hinge: port of the MATLAB function ``rod_hinge_dynamics``.

A uniform rod of mass ``m`` and length ``l`` is hinged at the origin; ``theta`` is its angle to the
horizontal.  Gravity acts at the centre of mass.  The active variant of the original has a
rotational spring (constant ``k``, rest angle ``theta_r``) and a rotational damper (``c``) at the
hinge; it is Eq. (1) of the white paper with the spring sign corrected (see
:func:`rod_hinge_dynamics`).  The original file also carried two commented-out variants with a
longitudinal spring and damper; they are ported as separate functions, exactly as written,
dimensional errors included.

The MATLAB function is ``theta_result = rod_hinge_dynamics(theta_t, theta_dot_t, p)``: the
angle, the angular rate and a struct ``p`` with the fields ``m, x_r, l, g, k, c, theta_r``; it
returns the column ``[theta_dot; theta_ddot]``.  The three Python functions take the state as
one vector and the fields of ``p`` as arguments of the same names,
``f(y, m, x_r, l, g, k, c, theta_r)`` with ``y = [theta, theta_dot]``, and return
``[theta_dot, theta_ddot]``; the arithmetic is the MATLAB expression's, in its order.  ``x_r``
(rest length of a longitudinal spring) is unused by the active variant and ``theta_r`` by the
longitudinal ones, as in the original.
"""

# ruff: noqa: E741  -- `l` (rod length) is the MATLAB name, kept in the ported signatures

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "rod_hinge_dynamics",
    "rod_hinge_dynamics_longitudinal",
    "rod_hinge_dynamics_longitudinal_rotational_damper",
    "theta_ddot",
]


def theta_ddot(theta, theta_dot, m, l, g, k, c, theta_r):
    """Angular acceleration of the active (rotational spring and damper) variant.

    Scalar helper for :func:`rod_hinge_dynamics`; the simulation loop calls it directly on Python
    floats, which gives the same IEEE-754 results as the array version, only faster.

    Parameters
    ----------
    theta, theta_dot : float
        Angle to the horizontal (rad) and angular rate (rad/s).
    m, l, g, k, c, theta_r : float
        Mass, rod length, gravitational acceleration, rotational spring constant, rotational
        damping coefficient and spring rest angle.

    Returns
    -------
    float
        ``3/(m l^2) * ((m g l / 2) cos(theta) - c theta_dot - k theta + k theta_r)``.

    Examples
    --------
    With gravity off, the rod at its rest angle and at rest does not accelerate:

    >>> theta_ddot(0.5, 0.0, m=1.0, l=2.0, g=0.0, k=3.0, c=1.0, theta_r=0.5)
    0.0
    """
    # Operation order as MATLAB evaluates 3/(m*l^2)*((m*g*l/2)*cos(theta) - c*theta_dot
    # - k*theta + k*theta_r): left to right.  Changing it changes the last bits of the result.
    return 3 / (m * l**2) * ((m * g * l / 2) * math.cos(theta) - c * theta_dot - k * theta + k * theta_r)


def rod_hinge_dynamics(y, m, x_r, l, g, k, c, theta_r):
    """Rod on a hinge with a rotational spring and damper (the active variant).

    ``theta_ddot = 3/(m l^2) * ((m g l / 2) cos(theta) - c theta_dot - k theta + k theta_r)``

    ERRATUM: the white paper's Eq. (1) writes ``+ k theta - k theta_r``, an anti-restoring spring.
    The MATLAB code, and this port, use the restoring sign ``- k theta + k theta_r``, which is what
    produced the paper's figures.

    Parameters
    ----------
    y : array_like, shape (2,)
        State ``[theta, theta_dot]``.
    m, x_r, l, g, k, c, theta_r : float
        Mass, (unused) longitudinal rest length, rod length, gravitational acceleration,
        rotational spring constant (torque per radian), rotational damping coefficient and
        spring rest angle.

    Returns
    -------
    numpy.ndarray, shape (2,)
        ``[theta_dot, theta_ddot]``.

    Examples
    --------
    >>> p = dict(m=1.0, x_r=1.0, l=1.0, g=0.0, k=3.0, c=1.0, theta_r=0.5)
    >>> rod_hinge_dynamics([0.5, 2.0], **p)
    array([ 2., -6.])
    """
    theta, theta_dot = y
    return np.array([theta_dot, theta_ddot(theta, theta_dot, m, l, g, k, c, theta_r)])


def rod_hinge_dynamics_longitudinal(y, m, x_r, l, g, k, c, theta_r):
    """Commented-out variant 1 of the original: longitudinal spring and damper.

    ``theta_ddot = 3/(m l^3) * ((m g l/2) cos(theta) - c l theta_dot sin(theta)^2
    + k l^2 sin(theta) cos(theta) - k x_r l sin(theta))``

    Ported as written.  It is DIMENSIONALLY INCONSISTENT: with ``k ~ M T^-2`` and ``c ~ M T^-1``
    (longitudinal constants) the bracket is a torque ``M L^2 T^-2`` except the damping term
    ``c l theta_dot``, which is ``M L T^-2`` (one length short), and the prefactor ``3/(m l^3)``
    has one length too many for ``1/I``.  The package's dimension checker should flag both.

    Parameters
    ----------
    y : array_like, shape (2,)
        State ``[theta, theta_dot]``.
    m, x_r, l, g, k, c, theta_r : float
        As in :func:`rod_hinge_dynamics`; ``x_r`` is the spring's rest length, ``theta_r`` is
        unused.

    Returns
    -------
    numpy.ndarray, shape (2,)
        ``[theta_dot, theta_ddot]``.

    Examples
    --------
    Horizontal rod (``sin(theta) = 0``), no gravity: only the spring term survives, and it is
    zero there.

    >>> rod_hinge_dynamics_longitudinal([0.0, 1.0], 1.0, 1.0, 1.0, 0.0, 2.0, 3.0, 0.0)
    array([1., 0.])
    """
    theta, theta_dot = y
    s, co = math.sin(theta), math.cos(theta)
    # QUIRK (kept): prefactor 3/(m*l^3) and damping term c*l*theta_dot*sin^2 are dimensionally
    # inconsistent with the other terms; see the docstring.
    acc = 3 / (m * l**3) * ((m * g * l / 2) * co - c * l * theta_dot * s**2 + k * l**2 * s * co - k * x_r * l * s)
    return np.array([theta_dot, acc])


def rod_hinge_dynamics_longitudinal_rotational_damper(y, m, x_r, l, g, k, c, theta_r):
    """Commented-out variant 2: longitudinal spring, rotational damper.

    ``theta_ddot = 3/(m l^3) * ((m g l/2) cos(theta) - c theta_dot
    + k l^2 sin(theta) cos(theta) - k x_r l sin(theta))``

    Ported as written.  The prefactor ``3/(m l^3)`` is DIMENSIONALLY INCONSISTENT (``1/I`` is
    ``3/(m l^2)``); the damping term is a proper torque if ``c`` is a rotational damping
    coefficient (``M L^2 T^-1``).  The package's dimension checker should flag the prefactor.

    Parameters
    ----------
    y : array_like, shape (2,)
        State ``[theta, theta_dot]``.
    m, x_r, l, g, k, c, theta_r : float
        As in :func:`rod_hinge_dynamics`; ``x_r`` is the spring's rest length, ``theta_r`` is
        unused.

    Returns
    -------
    numpy.ndarray, shape (2,)
        ``[theta_dot, theta_ddot]``.

    Examples
    --------
    >>> f = rod_hinge_dynamics_longitudinal_rotational_damper
    >>> f([0.0, 1.0], 1.0, 1.0, 1.0, 0.0, 2.0, 3.0, 0.0)
    array([ 1., -9.])
    """
    theta, theta_dot = y
    s, co = math.sin(theta), math.cos(theta)
    # QUIRK (kept): prefactor 3/(m*l^3) is dimensionally inconsistent; see the docstring.
    acc = 3 / (m * l**3) * ((m * g * l / 2) * co - c * theta_dot + k * l**2 * s * co - k * x_r * l * s)
    return np.array([theta_dot, acc])
