"""Matplotlib figures.  Functions return a Figure; none calls ``plt.show``."""

from __future__ import annotations

import math
from fractions import Fraction

from .formatting.pieces import UNCHANGED, power_latex, scale_text

__all__ = ["plot_search", "plot_similarity"]


def plot_search(result, ax=None):
    """Chart of a search result: variables down, minimal solutions across.

    Each cell is coloured by the exponent of ``s`` (blue shrinks, red
    grows, white unchanged; the colour bar beside the chart says so) and
    labelled with the power of ``s`` in mathtext (:math:`s^{2}`), or ``-``
    where the variable is unchanged.

    Parameters
    ----------
    result : SearchResult
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import pitheorem as pt
    >>> s = pt.System({"l": "L", "g": "L T^-2", "t": "T"})
    >>> fig = pt.plotting.plot_search(pt.search(s, scale={"g": 1}))
    >>> fig.axes[0].get_xlabel(), fig.axes[0].get_title(), fig.axes[1].get_ylabel()
    ('minimal scaling', 'g by s: 1 minimal scaling', 'exponent of $s$')
    """
    import matplotlib.pyplot as plt
    import numpy as np

    names = result.system.variables
    points = [s.vector for s in result.iter_scalings()]
    data = np.array([[float(p[i]) for p in points] for i in range(len(names))]).reshape(len(names), len(points))
    if ax is None:
        fig, ax = plt.subplots(figsize=(1.2 + 0.9 * max(len(points), 1), 0.9 + 0.42 * len(names)), layout="constrained")
    else:
        fig = ax.figure
    limit = max(1.0, float(np.abs(data).max()) if data.size else 1.0)
    image = ax.imshow(
        data if data.size else np.zeros((len(names), 1)), cmap="RdBu_r", vmin=-limit, vmax=limit, aspect="auto"
    )
    bar = fig.colorbar(image, ax=ax, shrink=min(1.0, 4 / max(len(names), 1)) if len(names) > 4 else 1.0)
    bar.set_label("exponent of $s$")
    bar.set_ticks([-limit, 0, limit], labels=[f"{-limit:g} shrinks", "0 same", f"{limit:g} grows"])
    for i in range(len(names)):
        for j in range(len(points)):
            p = Fraction(points[j][i])
            dark = abs(float(p)) > 0.6 * limit
            label = UNCHANGED if p == 0 else f"${power_latex(p)}$"
            ax.text(j, i, label, ha="center", va="center", fontsize=10, color="white" if dark else "black")
    ax.set_yticks(range(len(names)), [n if role == "free" else f"{n} ({role})" for n, role in result.roles.items()])
    ax.set_xticks(range(len(points)), [f"#{k + 1}" for k in range(len(points))])
    ax.set_xlabel("minimal scaling")
    request = scale_text(result)
    if result.feasible:
        title = f"{request}: {len(points)} minimal scaling{'' if len(points) == 1 else 's'}"
    else:
        title = f"{request}: impossible, {result.certificate.expr} would change"
    ax.set_title(title, fontsize=10)
    return fig


def _unit_label(name, report, units) -> str:
    """``name [unit]``: the unit given, else the dimension from the scaling's system."""
    if units and name in units:
        return f"{name} [{units[name]}]"
    if report.is_similarity and name in report.scaling.system.variables:  # a Scaling knows its system
        return f"{name} [{report.scaling.system.dimension(name)}]"
    return f"{name}, original units"


def plot_similarity(report, states=None, units=None):
    """Figure comparing the original run with the scaled run mapped back.

    Top axes: each state of the original run (solid) and of the scaled run
    mapped back to original units (dashed), against original time. Bottom
    axes: the absolute difference of each state. Every axis names its unit:
    the one given in `units`, else the dimension of the variable (``[1]``
    for a dimensionless one, such as an angle in radians).

    Parameters
    ----------
    report : SimilarityReport
    states : sequence of str, optional
        States to show (default all).
    units : mapping of str to str, optional
        Unit to print for a state or the time, e.g. ``{"theta": "rad",
        "omega": "rad/s", "t": "s"}``.

    Returns
    -------
    matplotlib.figure.Figure
        A pyplot figure, which Jupyter's inline backend shows once.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.models.hinged_rod()
    >>> sc = pt.search(rod.system, scale={"g": 1}).scalings[0]
    >>> rep = pt.verify_similarity(rod, sc, s=2, t_final=0.2)
    >>> fig = pt.plotting.plot_similarity(rep, units={"theta": "rad", "t": "s"})
    >>> fig.axes[0].get_ylabel(), fig.axes[1].get_xlabel()
    ('theta [rad], omega [T^-1]', 't [s]')
    """
    import matplotlib.pyplot as plt  # a pyplot figure, so Jupyter's inline backend shows it
    import numpy as np

    from .errors import UnknownVariableError

    names = report.original.states if states is None else tuple(states)
    for n in names:
        if n not in report.original.states:
            raise UnknownVariableError(str(n), report.original.states, "plot states")
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 6), layout="constrained")
    t = report.original.t
    for n in names:
        line = top.plot(t, report.original[n], label=f"{n} (original)")[0]
        top.plot(t, report.mapped[n], "--", color=line.get_color(), label=f"{n} (scaled, mapped back)")
        bottom.plot(t, np.abs(report.mapped[n] - report.original[n]), color=line.get_color(), label=f"|{n} difference|")
    quantities = ", ".join(_unit_label(n, report, units) for n in names)
    top.set_ylabel(quantities)
    top.legend(loc="best", fontsize="small")
    verdict = "similar" if report.passed else "NOT similar"
    top.set_title(f"s = {report.s:g}: {verdict} (max deviation {report.max_deviation:.2g})")
    if math.isfinite(report.tol):  # a report judged against its one-ulp baseline has no tolerance (NaN)
        bottom.axhline(report.tol, color="0.5", linestyle=":", label=f"tol = {report.tol:g}")
    bottom.set_xlabel(_unit_label(report.original.time, report, units))
    bottom.set_ylabel(f"|difference|: {quantities}")
    bottom.legend(loc="best", fontsize="small")
    return fig
