"""Projectile under scaled gravity: port of ``backup/scaling_counterexample_backup.m``.

The MATLAB program sits in the ``backup/`` folder of the paper's sources (NTRTsim,
``src/dev/apsabelhaus/scaling_analysis/backup/scaling_counterexample_backup.m``); it shares its
header with ``scaling_counterexample.m`` and is the projectile example that the white paper's
Section 5 mentions.  This module keeps the descriptive name ``scaling_counterexample_projectile``.

A point mass (``m = 2``, unused by the kinematics) is launched at speed ``v0 = 10`` and angle
``pi/2`` (straight up) under gravity ``g = 9.81``.  The flight time is
``tf = 2 v0 sin(angle) / g``, sampled at 100 points (``linspace(0, tf, 100)``)::

    y = v0 sin(angle) t - 0.5 g t^2
    x = v0 sin(angle) t        # QUIRK: sin, not cos

QUIRK (kept): the original computes the horizontal position with ``sin(angle)`` instead of
``cos(angle)``.  With the vertical launch the true ``x`` would be (numerically) zero; the port
keeps ``x = v0 sin(angle) t``, so the plotted "trajectory" is an arc whose width is ``v0 tf``.

Three plots of ``y`` against ``x``, with the MATLAB program's titles and axis labels:

1. "Original, unscaled simulation" ("Horizontal length, meters", "Vertical length, meters").
2. "With only gravity scaled": ``g`` times 10 (and the new, 10 times shorter ``tf``).
3. "With both gravity and length scaled, post-hoc": the gravity-scaled ``x`` and ``y`` times
   ``g_scaled / g`` (10), which lands back on the original arc (``10 y(t/10)`` with ``10 g``
   equals ``y(t)`` with ``g``); its axes read "... units of meters * scaling const".
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

try:  # imported as part of the matlab_ports package, or run as a script
    from ._matlab import write_figures_main
except ImportError:
    from _matlab import write_figures_main

__all__ = ["PARAMS", "TITLES", "XLABELS", "YLABELS", "flight_time", "main", "plot_runs", "simulate", "trajectory"]

PARAMS = {"m": 2.0, "v0": 10.0, "g": 9.81, "angle": math.pi / 2}
N_POINTS = 100
SCALE = 10.0

TITLES = {
    "original": "Original, unscaled simulation",
    "gravity": "With only gravity scaled",
    "gravity_length": "With both gravity and length scaled, post-hoc",
}


#: axis labels as the MATLAB program sets them; the post-hoc plot reads in scaled units
XLABELS = {
    "original": "Horizontal length, meters",
    "gravity": "Horizontal length, meters",
    "gravity_length": "Horizontal length, units of meters * scaling const",
}
YLABELS = {
    "original": "Vertical length, meters",
    "gravity": "Vertical length, meters",
    "gravity_length": "Vertical length, units of meters * scaling const",
}


def flight_time(v0, g, angle):
    """Time of flight back to launch height, ``2 v0 sin(angle) / g``.

    Parameters
    ----------
    v0, g, angle : float
        Launch speed, gravitational acceleration and launch angle from the horizontal.

    Returns
    -------
    float

    Examples
    --------
    >>> flight_time(10.0, 10.0, math.pi / 2)
    2.0
    """
    return 2 * v0 * math.sin(angle) / g


def trajectory(v0, g, angle, n=N_POINTS):
    """Sample times and positions over the flight, as in the original.

    Parameters
    ----------
    v0, g, angle : float
        Launch speed, gravitational acceleration and launch angle from the horizontal.
    n : int
        Number of samples, ``linspace(0, tf, n)``.

    Returns
    -------
    t, x, y : numpy.ndarray
        ``x = v0 sin(angle) t`` (QUIRK: sin, as in the original) and
        ``y = v0 sin(angle) t - 0.5 g t^2``.

    Examples
    --------
    >>> t, x, y = trajectory(10.0, 10.0, math.pi / 2, n=3)
    >>> t.tolist(), x.tolist(), y.tolist()
    ([0.0, 1.0, 2.0], [0.0, 10.0, 20.0], [0.0, 5.0, 0.0])
    """
    t = np.linspace(0.0, flight_time(v0, g, angle), n)
    y = v0 * math.sin(angle) * t - 0.5 * g * t**2  # y = v0 * sin(theta) .* t - 0.5 * g * t.^2
    x = v0 * math.sin(angle) * t  # QUIRK: the original uses sin here too (cos would be correct)
    return t, x, y


def simulate():
    """The three runs of the original script.

    Returns
    -------
    dict
        ``{"original": (t, x, y), "gravity": (t, x, y), "gravity_length": (t, x, y)}``; the last
        is the gravity-scaled run with ``x`` and ``y`` multiplied by 10 (``t`` unchanged).

    Examples
    --------
    >>> runs = simulate()
    >>> t, x, y = runs["original"]
    >>> len(t), bool(t[-1] == 2 * 10.0 * math.sin(math.pi / 2) / 9.81)
    (100, True)
    >>> _, x3, y3 = runs["gravity_length"]
    >>> bool(np.allclose(x3, x) and np.allclose(y3, y, atol=1e-12))
    True
    """
    p = dict(PARAMS)
    runs = {"original": trajectory(p["v0"], p["g"], p["angle"])}
    g_scaled = SCALE * p["g"]
    length_scaling_factor = g_scaled / p["g"]  # as the MATLAB program computes it (10.0)
    t, x, y = trajectory(p["v0"], g_scaled, p["angle"])
    runs["gravity"] = (t, x, y)
    runs["gravity_length"] = (t, length_scaling_factor * x, length_scaling_factor * y)  # post hoc
    return runs


def plot_runs(runs):
    """One Figure per run, ``y`` against ``x``.

    Parameters
    ----------
    runs : dict
        Output of :func:`simulate`.

    Returns
    -------
    dict of matplotlib.figure.Figure
        Same keys as ``runs``.

    Examples
    --------
    >>> figs = plot_runs(simulate())
    >>> figs["gravity_length"].axes[0].get_title()
    'With both gravity and length scaled, post-hoc'
    """
    figs = {}
    for name, (_t, x, y) in runs.items():
        fig = Figure(figsize=(8, 6))
        FigureCanvasAgg(fig)
        ax = fig.add_subplot()
        ax.plot(x, y)
        ax.set_title(TITLES[name])
        ax.set_xlabel(XLABELS[name])
        ax.set_ylabel(YLABELS[name])
        figs[name] = fig
    return figs


def main(argv=None):
    """Command line: write ``projectile_<run>.png`` for the three runs.

    The files go to ``--outdir`` (default: the current folder).

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default ``sys.argv[1:]``).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     [p.name for p in main(["--outdir", folder])]
    ['projectile_original.png', 'projectile_gravity.png', 'projectile_gravity_length.png']
    """
    return write_figures_main(__doc__.splitlines()[0], lambda: plot_runs(simulate()), "projectile_", argv)


if __name__ == "__main__":
    main()
