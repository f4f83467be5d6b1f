"""Matplotlib figures.  Functions return a Figure; none calls ``plt.show``."""

from __future__ import annotations

from fractions import Fraction

from .display import power_text

__all__ = ["plot_search"]


def plot_search(result, ax=None):
    """Chart of a search result: variables down, minimal solutions across.

    Each cell is coloured by the exponent of ``s`` (blue shrinks, red
    grows, white unchanged) and labelled with it.

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
    >>> fig.axes[0].get_xlabel()
    'minimal scaling'
    """
    import matplotlib.pyplot as plt
    import numpy as np

    names = result.system.variables
    points = [s.powers for s in result.iter_scalings()]
    data = np.array([[float(p[i]) for p in points] for i in range(len(names))]).reshape(len(names), len(points))
    if ax is None:
        fig, ax = plt.subplots(figsize=(1.2 + 0.9 * max(len(points), 1), 0.9 + 0.42 * len(names)), layout="constrained")
    else:
        fig = ax.figure
    limit = max(1.0, float(np.abs(data).max()) if data.size else 1.0)
    ax.imshow(data if data.size else np.zeros((len(names), 1)), cmap="RdBu_r", vmin=-limit, vmax=limit, aspect="auto")
    for i in range(len(names)):
        for j in range(len(points)):
            p = Fraction(points[j][i])
            dark = abs(float(p)) > 0.6 * limit
            ax.text(j, i, power_text(p), ha="center", va="center", fontsize=10, color="white" if dark else "black")
    roles = ["scale" if n in result.scale else "fixed" if n in result.fixed else "" for n in names]
    ax.set_yticks(range(len(names)), [f"{n} ({r})" if r else n for n, r in zip(names, roles, strict=True)])
    ax.set_xticks(range(len(points)), [f"#{k + 1}" for k in range(len(points))])
    ax.set_xlabel("minimal scaling")
    request = ", ".join(f"{n} by {power_text(p)}" for n, p in result.scale.items())
    if result.feasible:
        title = f"{request}: {len(points)} minimal scaling(s)"
    else:
        title = f"{request}: impossible, {result.certificate.expr} would change"
    ax.set_title(title, fontsize=10)
    return fig
