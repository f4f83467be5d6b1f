"""MATLAB semantics that the ports need to reproduce the originals bit for bit."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np

__all__ = ["colon", "write_figures_main"]


def colon(a: float, d: float, b: float) -> np.ndarray:
    """Emulate MATLAB's range ``a:d:b`` (general, non-integer case), element for element.

    MATLAB does not build ``a:d:b`` as ``a + k*d``: it fills the range symmetrically from both
    ends, ``a + k*d`` on the first half and ``c - k*d`` on the second (``c`` the end point snapped
    to ``b``), with the middle element of an even count of intervals set to ``(a + c)/2``.  This
    keeps the end point exact, and it is the only construction tried that reproduces the time data
    of the reference ``.fig`` files exactly: ``np.arange(n)*d``, ``np.linspace`` and cumulative
    sums all differ in the last bits (``np.linspace(0, 10, 100001)`` at 21596 of the 100001
    points, up to 1.8e-15).

    Parameters
    ----------
    a, d, b : float
        Start, step (positive) and end.

    Returns
    -------
    numpy.ndarray
        The range, ``n + 1`` points with ``n = round((b - a)/d)`` (one less when that overshoots
        ``b`` by more than the rounding tolerance).

    Examples
    --------
    >>> t = colon(0.0, 1e-4, 10.0)
    >>> len(t), float(t[-1]), float(t[3])  # front half: 0 + 3*1e-4
    (100001, 10.0, 0.00030000000000000003)
    >>> bool(t[-3] == 10.0 - 2 * 1e-4)  # back half: counted down from the end point
    True
    """
    if d <= 0:
        raise ValueError("only positive steps are supported")
    tol = 2.0 * np.finfo(float).eps * max(abs(a), abs(b))
    n = round((b - a) / d)
    if a + n * d - b > tol:
        n -= 1
    c = a + n * d
    if c - b > -tol:  # snap the end point to b
        c = b
    k = np.arange(n + 1, dtype=float)
    half = math.floor(n / 2)
    v = np.where(np.arange(n + 1) <= half, a + k * d, c - (n - k) * d)
    if n % 2 == 0:
        v[n // 2] = (a + c) / 2
    return v


def write_figures_main(
    description: str, make_figures: Callable[..., Mapping], prefix: str = "", argv=None, *, fast_mode: bool = False
) -> list[Path]:
    """The command line shared by the ports: make the figures and save each as PNG.

    Parameters
    ----------
    description : str
        The ``--help`` text.
    make_figures : callable
        Returns a dict of name to matplotlib Figure; called with the ``--n-points`` value when
        `fast_mode` is set, with no argument otherwise.
    prefix : str
        Put before each name to make the file name, ``<prefix><name>.png``.
    argv : list of str, optional
        Arguments (default ``sys.argv[1:]``): ``--outdir DIR`` (default ``.``), and
        ``--n-points N`` when `fast_mode` is set.
    fast_mode : bool
        Offer ``--n-points`` to truncate the simulations.

    Returns
    -------
    list of pathlib.Path
        The files written, in the order of the figures.

    Examples
    --------
    >>> import tempfile
    >>> from matplotlib.figure import Figure
    >>> with tempfile.TemporaryDirectory() as d:
    ...     [p.name for p in write_figures_main("demo", lambda: {"a": Figure()}, "x_", ["--outdir", d])]
    ['x_a.png']
    """
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--outdir", type=Path, default=Path("."), help="directory for the PNG files")
    if fast_mode:
        parser.add_argument("--n-points", type=int, default=None, help="truncate the simulations")
    args = parser.parse_args(argv)
    args.outdir.mkdir(parents=True, exist_ok=True)
    figures = make_figures(args.n_points) if fast_mode else make_figures()
    written = []
    for name, fig in figures.items():
        path = args.outdir / f"{prefix}{name}.png"
        fig.savefig(path)
        written.append(path)
    return written
