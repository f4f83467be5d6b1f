"""Hinged rod under successive scalings: port of ``example_code/scaling_counterexample_nonlinear.m``.

Reproduces the white paper's Figures 1-5.  The rod of :mod:`matlab_ports.rod_hinge_dynamics` (rotational
spring and damper) is simulated with forward Euler, ``y_i = y_{i-1} + f(y_{i-1}) dt``,
``dt = 1e-4`` on ``t = 0:dt:10`` (100001 samples), and the angle ``theta`` is plotted.  Parameter
changes accumulate on one parameter set, with scale factor ``s = 2``:

========  ==================================================================  ==================
figure    parameters                                                          time axis
========  ==================================================================  ==================
1         ``m=1.5, x_r=1, l=2, g=9.81, k=100, c=10, theta_r=pi/3``            ``t``
2         ``g = s g``                                                         ``t``
3         also ``l = l/s``                                                    ``t``
4         also ``c = c/s``                                                    ``t``
5         as figure 4, simulated again                                        ``t s``
========  ==================================================================  ==================

Initial state ``theta = pi/4``, ``theta_dot = 0``.  Figures 2 and 3 differ from Figure 1,
Figure 4 too (time is not scaled), and Figure 5 reproduces Figure 1: with ``g s``, ``l/s``,
``c/s`` the rod moves ``s`` times faster, so plotting against ``t s`` restores the original --
up to the Euler discretisation, which now takes steps of ``s dt`` in original time (maximum
difference from Figure 1 on ``[0, 10]``: 1.4e-4 rad).

With the same operation order as the MATLAB code, the port matches the curves stored in the
reference ``.fig`` files exactly (maximum absolute difference 0.0 at all 100001 points of all
five figures, on x86-64 with glibc's ``cos``).

QUIRKS of the original, kept:

* Figure 5 keeps the axis ``[0 10 0.5 1.5]`` of the other figures although its time data
  ``t s`` runs to 20, so only the first half of the line is visible (the ``.fig`` file has
  ``XLim = [0 10]`` and the full line to 20).
* Figure 1's y label says "Radial position of rod", the others "Angular position of rod".
* Figure 3 scales length by ``1/s`` (keeping ``g m l/k`` invariant), while the paper's text says
  "gravity multiplied by s, length multiplied by s"; the reference data confirm ``l/s``.

The MATLAB program keeps alternatives commented out, which the port (like the program) does
not run: the rate ``theta_dot`` plotted in red (``%plot(t, y(2,:), 'r')``, in every figure);
for Figure 3 a length ``s l`` or ``sqrt(s) l`` instead of ``l/s``, a spring rest length
``s x_r``, a damping ``sqrt(s) c`` or ``c/s``, a spring ``s k`` and a mass ``m/sqrt(s)`` or
``m/s`` (the same ``k`` and ``m`` lines again before Figure 4, whose active line is
``c/s``, with ``sqrt(s) c`` commented out); and for Figure 5 a time axis ``t/s`` instead of
``t s``, a rescaling ``t = t * s`` and a shortened axis ``floor(t_final / sqrt(s))``.  They
record scalings the author tried on the way to the paper's; only the active lines made the
figures.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

try:
    from ._matlab import colon, write_figures_main
    from .rod_hinge_dynamics import theta_ddot
except ImportError:  # run as a script: python matlab_ports/scaling_counterexample_nonlinear.py
    from _matlab import colon, write_figures_main
    from rod_hinge_dynamics import theta_ddot

__all__ = ["PARAMS", "TITLES", "main", "plot_figures", "simulate", "simulate_figures"]

#: parameters of the original, unscaled simulation (Figure 1)
PARAMS = {"m": 1.5, "x_r": 1.0, "l": 2.0, "g": 9.81, "k": 100.0, "c": 10.0, "theta_r": math.pi / 3}
THETA_0 = math.pi / 4
DT = 1e-4
T_END = 10.0
S = 2.0

TITLES = {
    "figure1": "Original, unscaled simulation",
    "figure2": "With only gravity scaled",
    "figure3": "Gravity and length scale changed",
    "figure4": "Gravity, length, and angular damping constant scale changed",
    "figure5": "Gravity, length, angular damping constant, and time scale changed",
}
XLABEL = "time, sec"
YLABELS = {"figure1": "Radial position of rod, radians"}  # QUIRK: "Radial" only in Figure 1
YLABEL = "Angular position of rod, radians"
AXIS = (0.0, 10.0, 0.5, 1.5)  # MATLAB axis([0 10 0.5 1.5]), also for Figure 5 (QUIRK)


def simulate(params, t, dt=DT, theta_0=THETA_0):
    """Forward Euler simulation of the hinged rod, as in the MATLAB loop.

    Parameters
    ----------
    params : dict
        ``m, x_r, l, g, k, c, theta_r`` (``x_r`` unused by the active dynamics).
    t : numpy.ndarray
        Sample times; only their number is used (the step is ``dt``, as in the original).
    dt : float
        Time step.
    theta_0 : float
        Initial angle; the initial rate is 0.

    Returns
    -------
    numpy.ndarray, shape (2, len(t))
        ``[theta, theta_dot]`` at every sample.

    Examples
    --------
    >>> y = simulate(PARAMS, np.zeros(3))
    >>> y.shape
    (2, 3)
    >>> bool(y[0, 1] == y[0, 0] == THETA_0)  # first step: the rate was still 0
    True
    >>> bool(y[0, 2] > y[0, 1])
    True
    """
    p = params
    m, l, g, k, c, theta_r = p["m"], p["l"], p["g"], p["k"], p["c"], p["theta_r"]  # noqa: E741
    n = len(t)
    y = np.empty((2, n))
    theta, theta_dot = float(theta_0), 0.0
    y[0, 0], y[1, 0] = theta, theta_dot
    for i in range(1, n):
        # MATLAB: y(:,i) = y(:,i-1) + rod_hinge_dynamics(y(:,i-1), ...)*dt -- both components
        # from the previous state, derivative times dt, then added.  Plain floats give the same
        # IEEE results as the vector expression.
        acc = theta_ddot(theta, theta_dot, m, l, g, k, c, theta_r)
        theta, theta_dot = theta + theta_dot * dt, theta_dot + acc * dt
        y[0, i], y[1, i] = theta, theta_dot
    return y


def simulate_figures(n_points=None):
    """Data of the paper's Figures 1-5, in the original order of parameter changes.

    Parameters
    ----------
    n_points : int, optional
        Keep only the first ``n_points`` samples (fast mode); default all 100001.

    Returns
    -------
    dict
        ``{"figure1": (t, theta), ..., "figure5": (t * s, theta)}``.

    Examples
    --------
    >>> data = simulate_figures(n_points=5)
    >>> sorted(data)
    ['figure1', 'figure2', 'figure3', 'figure4', 'figure5']
    >>> data["figure5"][0].tolist()  # t * s
    [0.0, 0.0002, 0.0004, 0.0006000000000000001, 0.0008]
    >>> bool((data["figure5"][1] == data["figure4"][1]).all())
    True
    """
    t = colon(0.0, DT, T_END)
    if n_points is not None:
        t = t[:n_points]
    p = dict(PARAMS)
    s = S
    data = {"figure1": (t, simulate(p, t)[0])}
    p["g"] = s * p["g"]
    data["figure2"] = (t, simulate(p, t)[0])
    p["l"] = p["l"] / s
    data["figure3"] = (t, simulate(p, t)[0])
    p["c"] = p["c"] / s
    data["figure4"] = (t, simulate(p, t)[0])
    # Figure 5: the original simulates the Figure 4 parameters again and plots against t*s.
    data["figure5"] = (t * s, simulate(p, t)[0])
    return data


def plot_figures(data):
    """One matplotlib Figure per curve, titled and labelled as in the original.

    Parameters
    ----------
    data : dict
        Output of :func:`simulate_figures`.

    Returns
    -------
    dict of matplotlib.figure.Figure
        Same keys as ``data``.  Figures use an Agg canvas and are not registered with pyplot.

    Examples
    --------
    >>> figs = plot_figures(simulate_figures(n_points=10))
    >>> ax = figs["figure5"].axes[0]
    >>> ax.get_title()
    'Gravity, length, angular damping constant, and time scale changed'
    >>> [float(v) for v in ax.get_xlim()]  # the original's axis, although t*s runs to 20
    [0.0, 10.0]
    """
    figs = {}
    for name, (t, theta) in data.items():
        fig = Figure(figsize=(8, 6))
        FigureCanvasAgg(fig)
        ax = fig.add_subplot()
        ax.plot(t, theta)
        ax.set_xlim(AXIS[0], AXIS[1])  # QUIRK for figure5: t*s runs to 20, axis stops at 10
        ax.set_ylim(AXIS[2], AXIS[3])
        ax.set_title(TITLES[name])
        ax.set_xlabel(XLABEL)
        ax.set_ylabel(YLABELS.get(name, YLABEL))
        figs[name] = fig
    return figs


def main(argv=None):
    """Command line: simulate, plot, and write ``figure1.png`` ... ``figure5.png``.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default ``sys.argv[1:]``): ``--outdir DIR`` (default ``.``) and
        ``--n-points N`` (fast mode).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Examples
    --------
    Fast mode: the first 200 samples of each run.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     [p.name for p in main(["--outdir", folder, "--n-points", "200"])]
    ['figure1.png', 'figure2.png', 'figure3.png', 'figure4.png', 'figure5.png']
    """
    return write_figures_main(
        __doc__.splitlines()[0], lambda n: plot_figures(simulate_figures(n)), "", argv, fast_mode=True
    )


if __name__ == "__main__":
    main()
