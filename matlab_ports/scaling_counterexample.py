"""Vertical spring-mass-damper under scaling: port of ``scaling_counterexample.m``.

The linear example of the white paper's Section 5.  A mass ``m`` hangs on a spring (constant
``k``, rest length ``y_rest``) and damper (``c``) under gravity ``g``; with the state
``x = [y, y_dot]``::

    x_dot = A x + C,   A = [[0, 1], [-k/m, -c/m]],   C = [0, -g + k y_rest / m]

integrated with forward Euler, ``x_i = x_{i-1} + (A x_{i-1} + C) dt``, ``dt = 0.01`` on
``t = 0:dt:4``, from ``y(0) = y0``, ``y_dot(0) = 0``.  Three runs:

1. "Original, unscaled simulation": ``m=2, y0=1, y_rest=1, g=9.81, k=150, c=10``.
2. "With only gravity scaled": ``g`` times 10 -- a different response.
3. "With both gravity and initial length constants scaled": ``y0`` and ``y_rest`` also times
   10, and the result divided by 10.  By superposition (the system is linear and ``g``, ``y0``,
   ``y_rest`` enter only as inputs) this equals run 1: here the naive "scale gravity with
   length" rule works, for a reason that has nothing to do with similitude.

Each plot shows ``y`` (default colour) and ``y_dot`` (red) against time.  The axis labels and
legend are additions of this port (the MATLAB script's plots are only specified by their titles
and the red ``y_dot``).
"""

from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

try:
    from ._matlab import colon, write_figures_main
except ImportError:  # run as a script: python matlab_ports/scaling_counterexample.py
    from _matlab import colon, write_figures_main

__all__ = ["PARAMS", "TITLES", "euler", "main", "plot_runs", "simulate"]

#: parameters of the original, unscaled run
PARAMS = {"m": 2.0, "y0": 1.0, "y_rest": 1.0, "g": 9.81, "k": 150.0, "c": 10.0}
DT = 0.01
T_END = 4.0
SCALE = 10.0

TITLES = {
    "original": "Original, unscaled simulation",
    "gravity": "With only gravity scaled",
    "gravity_length": "With both gravity and initial length constants scaled",
}


def euler(params, t, dt=DT):
    """Forward Euler on ``x_dot = A x + C`` from ``x = [y0, 0]``.

    Parameters
    ----------
    params : dict
        ``m, y0, y_rest, g, k, c``.
    t : numpy.ndarray
        Sample times (only their number is used; the step is ``dt``).
    dt : float
        Time step.

    Returns
    -------
    numpy.ndarray, shape (2, len(t))
        ``[y, y_dot]`` at every sample.

    Examples
    --------
    At rest at the static equilibrium ``y_rest - m g / k`` nothing moves:

    >>> p = dict(PARAMS, y0=1.0 - 2.0 * 9.81 / 150.0)
    >>> x = euler(p, np.zeros(4))
    >>> bool(np.allclose(x[0], p["y0"], rtol=0, atol=1e-15)), bool(np.allclose(x[1], 0, atol=1e-13))
    (True, True)
    """
    m, k, c, g = params["m"], params["k"], params["c"], params["g"]
    A = np.array([[0.0, 1.0], [-k / m, -c / m]])
    C = np.array([0.0, -g + k * params["y_rest"] / m])
    x = np.empty((2, len(t)))
    x[:, 0] = (params["y0"], 0.0)
    for i in range(1, len(t)):
        x[:, i] = x[:, i - 1] + (A @ x[:, i - 1] + C) * dt
    return x


def simulate():
    """The three runs of the original script.

    Returns
    -------
    dict
        ``{"original": (t, x), "gravity": (t, x), "gravity_length": (t, x)}`` with
        ``x = [y, y_dot]`` of shape ``(2, 401)``; the last run is already divided by 10.

    Examples
    --------
    >>> runs = simulate()
    >>> t, x = runs["original"]
    >>> len(t), float(t[-1])
    (401, 4.0)
    >>> bool(np.allclose(runs["gravity_length"][1], x, rtol=1e-12, atol=1e-12))  # superposition
    True
    >>> bool(np.allclose(runs["gravity"][1], x))
    False
    """
    t = colon(0.0, DT, T_END)
    p = dict(PARAMS)
    runs = {"original": (t, euler(p, t))}
    p["g"] = SCALE * p["g"]
    runs["gravity"] = (t, euler(p, t))
    p["y0"] = SCALE * p["y0"]
    p["y_rest"] = SCALE * p["y_rest"]
    runs["gravity_length"] = (t, euler(p, t) / SCALE)
    return runs


def plot_runs(runs):
    """One Figure per run: ``y`` and, in red, ``y_dot`` against time.

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
    >>> [figs[k].axes[0].get_title() for k in ("original", "gravity")]
    ['Original, unscaled simulation', 'With only gravity scaled']
    """
    figs = {}
    for name, (t, x) in runs.items():
        fig = Figure(figsize=(8, 6))
        FigureCanvasAgg(fig)
        ax = fig.add_subplot()
        ax.plot(t, x[0], label="y")
        ax.plot(t, x[1], "r", label="y dot")
        ax.set_title(TITLES[name])
        ax.set_xlabel("time, sec")  # labels and legend: additions of the port
        ax.legend()
        figs[name] = fig
    return figs


def main(argv=None):
    """Command line: simulate the three runs and write ``linear_<run>.png`` to ``--outdir``.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default ``sys.argv[1:]``).

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    return write_figures_main(__doc__.splitlines()[0], lambda: plot_runs(simulate()), "linear_", argv)


if __name__ == "__main__":
    main()
