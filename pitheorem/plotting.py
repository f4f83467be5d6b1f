"""Matplotlib figures.  Functions return a Figure; none calls ``plt.show``."""

from __future__ import annotations

import math
from fractions import Fraction

from .formatting.pieces import UNCHANGED, file_name, power_latex, scale_text, unit_change_text

__all__ = ["plot_search", "plot_similarity", "plot_sweep", "sweep_alt_text"]


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


#: how each verdict of a sweep is drawn: marker, colour, whether filled
_VERDICT_STYLE = {
    "exact": ("o", "#1a7f37", True),
    "similar": ("o", "#0550ae", True),
    "not similar": ("X", "#cf222e", True),
    "inconclusive": ("s", "#6e7781", False),
    "refused": ("v", "#000000", True),
}


def _bands(rows):
    """Per threshold: the runs of consecutive rows (sorted by s) beyond it, as (first, last) indices."""
    out = {}
    for name in dict.fromkeys(n for r in rows for n in r.thresholds):
        inside = [name in r.thresholds for r in rows]
        runs, start = [], None
        for k, flag in enumerate([*inside, False]):
            if flag and start is None:
                start = k
            elif not flag and start is not None:
                runs.append((start, k - 1))
                start = None
        out[name] = runs
    return out


def sweep_alt_text(sweep) -> str:
    """The alt text of a sweep's figure: what it shows, in words.

    Parameters
    ----------
    sweep : Sweep

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.engines import Sweep, SweepRow
    >>> rows = (SweepRow(0.001, "refused", None, None, None, None, None, (), ("mujoco_minval_mass",)),
    ...         SweepRow(1, "exact", 0.0, 1e-12, None, True, None, (), ()))
    >>> from pitheorem.plotting import sweep_alt_text
    >>> sweep_alt_text(Sweep("robot.xml", "mujoco", None, 1.0, rows))
    'Deviation of the scaled copy and the yardstick against the scale factor s from 0.001 to 1 for robot.xml in mujoco; verdicts: s = 0.001 refused, s = 1 exact; beyond mujoco_minval_mass at s = 0.001.'
    """
    rows = sorted(sweep.rows, key=lambda r: float(r.s))
    name = file_name(sweep.model) or "the model"
    if not rows:
        return f"An empty sweep of {name}."
    verdicts = ", ".join(f"s = {float(r.s):.3g} {r.verdict}" for r in rows)
    text = (
        f"Deviation of the scaled copy and the yardstick against the scale factor s from {float(rows[0].s):.3g} "
        f"to {float(rows[-1].s):.3g} for {name} in {sweep.engine}; verdicts: {verdicts}"
    )
    for threshold, runs in _bands(rows).items():
        where = ", ".join(
            f"s = {float(rows[a].s):.3g}" if a == b else f"s = {float(rows[a].s):.3g} to {float(rows[b].s):.3g}"
            for a, b in runs
        )
        text += f"; beyond {threshold} at {where}"
    if sweep.fitted_s is not None:
        text += f"; the units fit_units chooses lie at s = {sweep.fitted_s:.3g}"
    return text + "."


def plot_sweep(sweep, ax=None):
    """Figure of a sweep: where along s the copy stays similar, and why.

    Deviation of the copy (mapped back) and the yardstick (the spread of
    the original's one-ulp twins) against ``s``, both axes logarithmic.
    Each row's verdict is its marker (an exact row, deviation 0, is drawn
    at the bottom of the axes; a refused copy at the top); each engine
    threshold crossed over part of the range is a labelled band; the ``s``
    at which the scaling reaches the units :func:`pitheorem.fit_units`
    chooses is a dotted line.  The figure's label (``fig.get_label()``) is
    its alt text (:func:`sweep_alt_text`).

    Parameters
    ----------
    sweep : Sweep
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.engines import Sweep, SweepRow
    >>> rows = (SweepRow(0.01, "not similar", 1e-3, 1e-9, None, True, None, (), ("mujoco_minmu",)),
    ...         SweepRow(1, "exact", 0.0, 1e-12, None, True, None, (), ()),
    ...         SweepRow(100, "similar", 1e-11, 1e-12, None, True, None, (), ()))
    >>> fig = pt.plotting.plot_sweep(Sweep("robot.xml", "mujoco", None, 1.0, rows))
    >>> ax = fig.axes[0]
    >>> ax.get_xscale(), ax.get_xlabel()
    ('log', 'scale factor s')
    >>> [t.get_text() for t in ax.texts]
    ['beyond mujoco_minmu']
    """
    import matplotlib.pyplot as plt
    import numpy as np

    rows = sorted(sweep.rows, key=lambda r: float(r.s))
    if ax is None:
        fig, ax = plt.subplots(figsize=(5.6, 5.0), layout="constrained")
    else:
        fig = ax.figure
    s = np.array([float(r.s) for r in rows])
    # a copy the engine gave up on deviates without bound (inf): drawn at the top, like a refused one
    positive = [v for r in rows for v in (r.max_deviation, r.yardstick) if v and math.isfinite(v)]
    low = min(positive) / 30 if positive else 1e-17
    high = max(positive) * 30 if positive else 1.0
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(low, high)
    measured = [(float(r.s), r.yardstick) for r in rows if r.yardstick and math.isfinite(r.yardstick)]
    if measured:
        xs, ys = zip(*measured, strict=True)
        ax.plot(xs, ys, "-", color="#8250df", lw=1.5, label="yardstick (spread of one-ulp twins)")
        ax.plot(
            xs,
            [sweep.baseline_factor * y for y in ys],
            "--",
            color="#8250df",
            lw=1,
            label=f"{sweep.baseline_factor:g} x yardstick (margin)",
        )
    deviations = [(float(r.s), r.max_deviation) for r in rows if r.max_deviation and math.isfinite(r.max_deviation)]
    if deviations:
        ax.plot(*zip(*deviations, strict=True), "-", color="0.6", lw=1, zorder=1)
    for v, (marker, colour, filled) in _VERDICT_STYLE.items():
        mine = [r for r in rows if r.verdict == v]
        if not mine:
            continue
        if v == "refused":
            y = [high / 2] * len(mine)
        else:
            y = [
                high / 2 if r.max_deviation and not math.isfinite(r.max_deviation) else r.max_deviation or low * 2
                for r in mine
            ]
        label = {"exact": "exact (bit for bit; drawn at the bottom)", "refused": "refused by the compiler (top)"}.get(
            v, v
        )
        ax.scatter(
            [float(r.s) for r in mine],
            y,
            marker=marker,
            s=70,
            zorder=3,
            facecolors=colour if filled else "white",
            edgecolors=colour,
            linewidths=1.5,
            label=label,
        )
    colours = plt.get_cmap("tab10").colors
    edges = np.sqrt(s[:-1] * s[1:]) if len(s) > 1 else np.array([])
    left = s[0] / 2 if len(s) else 1.0
    right = s[-1] * 2 if len(s) else 1.0
    ax.set_xlim(left, right)
    everywhere = []
    for k, (name, runs) in enumerate(_bands(rows).items()):
        if runs == [(0, len(rows) - 1)]:
            everywhere.append(name)
            continue
        colour = colours[k % len(colours)]
        for j, (a, b) in enumerate(runs):
            x0 = left if a == 0 else edges[a - 1]
            x1 = right if b == len(rows) - 1 else edges[b]
            ax.axvspan(x0, x1, color=colour, alpha=0.13, lw=0, zorder=0)
            if j == 0:
                ax.text(
                    math.sqrt(x0 * x1),
                    math.sqrt(low * high),
                    f"beyond {name}",
                    rotation=90,
                    ha="center",
                    va="center",
                    fontsize=9,
                    color=colour,
                )
    if sweep.fitted_s is not None and left <= sweep.fitted_s <= right:
        units = ", ".join(f"{b} = {u}" for b, u in (sweep.fitted_units or {}).items())
        ax.axvline(sweep.fitted_s, color="#bf8700", ls=":", lw=2, label=f"fit_units: {units}")
    ax.set_xlabel("scale factor s")
    unit_text = ", ".join(f"{u}" for u in dict(sweep.units).values())
    ax.set_ylabel(f"largest deviation of a coordinate\n(original units: {unit_text}; rad)")
    name = file_name(sweep.model) or "model"
    title = f"{name} in {sweep.engine}"
    if sweep.scaling is not None:
        title += f": {unit_change_text(sweep.scaling)}"
    if everywhere:
        title += "\nbeyond at every s: " + ", ".join(everywhere)
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2, fontsize=8.5, frameon=False)
    fig.set_label(sweep_alt_text(sweep))
    return fig
