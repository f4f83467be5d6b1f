"""Vertical spring-mass-damper under scaling: port of ``example_code/scaling_counterexample.m``.

The linear example of the white paper's Section 5.  A mass ``m`` hangs on a spring (constant
``k``, rest length ``y_rest``) and damper (``c``) under gravity ``g``; with the state
``x = [y, y_dot]``::

    x_dot = A x + C,   A = [[0, 1], [-k/m, -c/m]],   C = [0, -g + k y_rest / m]

integrated with forward Euler, ``x_i = (A x_{i-1} + C) dt + x_{i-1}``, ``dt = 0.01`` on
``t = 0:dt:4``, from ``y(0) = y0``, ``y_dot(0) = 0``.  Three runs:

1. "Original, unscaled simulation": ``m=2, y0=1, y_rest=1, g=9.81, k=150, c=10``.
2. "With only gravity scaled": ``g`` times 10 -- a different response.
3. "With both gravity and initial length constants scaled": ``y0`` and ``y_rest`` also times
   ``g_scaled / g`` (10), and the result divided by that factor.  By superposition (the
   system is linear and ``g``, ``y0``, ``y_rest`` enter only as inputs) this equals run 1 up
   to rounding: here the naive "scale gravity with length" rule works, for a reason that has
   nothing to do with similitude.

The update is transcribed element by element from MATLAB's ``(A * y(:, i-1) + C) * dt +
y(:, i-1)``: row ``j`` is ``(A(j,1) y + A(j,2) y_dot + C(j)) dt + x_j``, in that order.  (A
matrix product, ``A @ x``, may sum in another order and differs in the last bits, by up to
1.8e-15 here.)

Each plot shows ``y`` (default colour) and ``y_dot`` (red) against time, with the MATLAB
program's title and axis labels ("time, sec", "Vertical height of particle, meters"; the
label names only ``y``).  The legend is the port's one addition.  The MATLAB file also keeps a
commented-out rest length, ``%y_rest = 0.50;``, which the port leaves out as the program does.
"""

from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

try:
    from ._matlab import colon, write_figures_main
except ImportError:  # run as a script: python matlab_ports/scaling_counterexample.py
    from _matlab import colon, write_figures_main

__all__ = ["PARAMS", "TITLES", "XLABEL", "YLABEL", "euler", "main", "plot_runs", "simulate"]

#: parameters of the original, unscaled run
PARAMS = {"m": 2.0, "y0": 1.0, "y_rest": 1.0, "g": 9.81, "k": 150.0, "c": 10.0}
DT = 0.01
T_END = 4.0
SCALE = 10.0

XLABEL = "time, sec"
YLABEL = "Vertical height of particle, meters"  # as in the MATLAB program, for all three plots
TITLES = {
    "original": "Original, unscaled simulation",
    "gravity": "With only gravity scaled",
    "gravity_length": "With both gravity and initial length constants scaled",
}


def euler(params, t, dt=DT):
    """Forward Euler on ``x_dot = A x + C`` from ``x = [y0, 0]``, as the MATLAB loop.

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
    >>> bool(np.allclose(x[0], p["y0"], rtol=0, atol=1e-15))
    True
    >>> bool(np.allclose(x[1], 0, atol=1e-13))
    True
    """
    m, k, c, g = params["m"], params["k"], params["c"], params["g"]
    # A = [0, 1; -k/m, -c/m] and C = [0; -g + k*y_rest/m], entry by entry as MATLAB forms them
    a11, a12, a21, a22 = 0.0, 1.0, -k / m, -c / m
    c1, c2 = 0.0, -g + k * params["y_rest"] / m
    y, y_dot = float(params["y0"]), 0.0
    x = np.empty((2, len(t)))
    x[:, 0] = (y, y_dot)
    for i in range(1, len(t)):
        # y(:, i) = (A * y(:, i-1) + C) * dt + y(:, i-1), one row at a time
        y, y_dot = (a11 * y + a12 * y_dot + c1) * dt + y, (a21 * y + a22 * y_dot + c2) * dt + y_dot
        x[:, i] = (y, y_dot)
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
    >>> # superposition: equal up to rounding
    >>> bool(np.allclose(runs["gravity_length"][1], x, rtol=1e-12, atol=1e-12))
    True
    >>> bool(np.allclose(runs["gravity"][1], x))
    False
    """
    t = colon(0.0, DT, T_END)
    p = dict(PARAMS)
    runs = {"original": (t, euler(p, t))}
    g_scaled = SCALE * p["g"]
    length_scaling_factor = g_scaled / p["g"]  # as the MATLAB program computes it (10.0)
    p["g"] = g_scaled
    runs["gravity"] = (t, euler(p, t))
    p["y0"] = length_scaling_factor * p["y0"]
    p["y_rest"] = length_scaling_factor * p["y_rest"]
    runs["gravity_length"] = (t, euler(p, t) / length_scaling_factor)
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
        ax.set_xlabel(XLABEL)
        ax.set_ylabel(YLABEL)
        ax.legend()  # the port's addition: the MATLAB plots have no legend
        figs[name] = fig
    return figs


def main(argv=None):
    """Command line: simulate the three runs, write ``linear_<run>.png``.

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
    ['linear_original.png', 'linear_gravity.png', 'linear_gravity_length.png']
    """
    return write_figures_main(__doc__.splitlines()[0], lambda: plot_runs(simulate()), "linear_", argv)


if __name__ == "__main__":
    main()
