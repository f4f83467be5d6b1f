"""Read line data, titles, labels and axis limits from MATLAB ``.fig`` files.

A ``.fig`` file (MATLAB R2007-R2014, "hgS_070000" format) is a MAT-file, version 5, holding the
saved handle-graphics tree under the key ``hgS_070000``.  Every node is a struct with fields
``type``, ``handle``, ``properties``, ``children`` and ``special``.  This reader walks
``children`` recursively and collects

* the ``XData``/``YData`` of every ``graph2d.lineseries`` (or plain ``line``) node, and
* for each ``axes`` node its ``XLim``/``YLim`` and its title and axis labels.  The labels are
  ``text`` children; which is which is given by the axes' ``special`` field, the 1-based indices
  of the title, x label, y label and z label among the children (``[2 3 4 0]`` in the paper's
  files: line first, then title, x label, y label; 0 means none).

Only :func:`scipy.io.loadmat` is needed.  Usage, as a script::

    python matlab_ports/figdata.py FILE.fig            # summary
    python matlab_ports/figdata.py --sample 1000 OUT.json FILE.fig ...   # sampled reference
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import NamedTuple

import numpy as np

__all__ = ["FigContents", "provenance", "read_fig_lines", "sample_reference"]

LINE_TYPES = ("graph2d.lineseries", "line")


class FigContents(NamedTuple):
    """What :func:`read_fig_lines` returns: the lines, labels and limits of a figure.

    The labels and limits are those of the first axes that has a title or labels.

    Examples
    --------
    >>> import numpy as np
    >>> c = FigContents([(np.array([0.0, 1.0]), np.array([2.0, 3.0]))], "T", "x", "y", (0.0, 1.0), (2.0, 3.0))
    >>> c.title, len(c.lines)
    ('T', 1)
    """

    lines: list  # [(xdata, ydata), ...] as float64 arrays, in tree order
    title: str | None
    xlabel: str | None
    ylabel: str | None
    xlim: tuple | None
    ylim: tuple | None


def _as_list(x):
    """Children of a node as a list (``loadmat(squeeze_me=True)`` unwraps single children)."""
    if x is None:
        return []
    if isinstance(x, np.ndarray):
        return list(x.ravel())
    return [x]


def _text(node):
    s = getattr(node.properties, "String", None)
    if isinstance(s, np.ndarray):  # multi-line strings are cell arrays
        return "\n".join(str(v) for v in s.ravel())
    return None if s is None else str(s)


def _walk(node, out):
    kind = str(node.type)
    props = node.properties
    children = _as_list(getattr(node, "children", None))
    if kind in LINE_TYPES:
        x = np.atleast_1d(np.asarray(props.XData, dtype=float))
        y = np.atleast_1d(np.asarray(props.YData, dtype=float))
        out["lines"].append((x, y))
    elif kind == "axes" and out["title"] is None:
        special = [int(i) for i in np.atleast_1d(getattr(node, "special", []))]
        labels = {}
        for key, idx in zip(("title", "xlabel", "ylabel"), special, strict=False):
            if 0 < idx <= len(children) and str(children[idx - 1].type) == "text":
                labels[key] = _text(children[idx - 1])
        if labels:
            out.update(labels)
            out["xlim"] = tuple(float(v) for v in np.atleast_1d(props.XLim))
            out["ylim"] = tuple(float(v) for v in np.atleast_1d(props.YLim))
    for child in children:
        _walk(child, out)


def read_fig_lines(path):
    """Line data, title, axis labels and axis limits of a MATLAB ``.fig`` file.

    Parameters
    ----------
    path : str or os.PathLike
        The ``.fig`` file.

    Returns
    -------
    FigContents
        ``(lines, title, xlabel, ylabel, xlim, ylim)``; ``lines`` is a list of
        ``(xdata, ydata)`` float64 arrays; the other fields come from the first axes that has a
        title or label (``None`` if there is none).

    Examples
    --------
    A tiny ``.fig``-like file written with scipy (a real one comes from MATLAB's ``savefig``):

    >>> import tempfile, os, scipy.io
    >>> text = lambda s: {"type": "text", "handle": 3.0, "properties": {"String": s},
    ...                   "children": np.zeros((0, 1)), "special": np.zeros((0, 1))}
    >>> line = {"type": "graph2d.lineseries", "handle": 2.0, "children": np.zeros((0, 1)),
    ...         "properties": {"XData": [0.0, 1.0], "YData": [2.0, 3.0]}, "special": np.zeros((0, 1))}
    >>> axes = {"type": "axes", "handle": 1.0, "special": [2.0, 3.0, 4.0, 0.0],
    ...         "properties": {"XLim": [0.0, 10.0], "YLim": [0.5, 1.5]},
    ...         "children": np.array([line, text("T"), text("x"), text("y")], dtype=object)}
    >>> fig = {"type": "figure", "handle": 0.0, "properties": {}, "children": axes,
    ...        "special": np.zeros((0, 1))}
    >>> path = os.path.join(tempfile.mkdtemp(), "tiny.fig")
    >>> scipy.io.savemat(path, {"hgS_070000": fig})
    >>> contents = read_fig_lines(path)
    >>> contents.title, contents.xlabel, contents.ylabel, contents.xlim, contents.ylim
    ('T', 'x', 'y', (0.0, 10.0), (0.5, 1.5))
    >>> [(x.tolist(), y.tolist()) for x, y in contents.lines]
    [([0.0, 1.0], [2.0, 3.0])]
    """
    from scipy.io import loadmat

    mat = loadmat(path, squeeze_me=True, struct_as_record=False)
    out = {"lines": [], "title": None, "xlabel": None, "ylabel": None, "xlim": None, "ylim": None}
    for root in _as_list(mat["hgS_070000"]):
        _walk(root, out)
    return FigContents(**out)


def sample_reference(paths, step=1000):
    """Every ``step``-th point of each file's first line, as exact ``repr`` strings.

    This produced ``tests/data/matlab_fig_samples.json``; ``float(s)`` restores each value
    exactly (``repr`` of a float round-trips).

    Parameters
    ----------
    paths : iterable of path-like
        ``.fig`` files.
    step : int
        Sampling stride; indices ``0, step, 2*step, ...`` (the last point is included when the
        length minus one is a multiple of ``step``).

    Returns
    -------
    dict
        ``{file name: {"indices", "x", "y", "n_points", "title", "xlabel", "ylabel", "xlim",
        "ylim"}}``.

    Examples
    --------
    A ``.fig``-like file of one line of five points, written with scipy (see
    :func:`read_fig_lines`), sampled every second point:

    >>> import tempfile, os, scipy.io
    >>> none = np.zeros((0, 1))
    >>> line = {"type": "line", "handle": 2.0, "children": none, "special": none,
    ...         "properties": {"XData": [0.0, 0.1, 0.2, 0.3, 0.4], "YData": [1.0, 0.5, 0.25, 0.125, 0.0625]}}
    >>> title = {"type": "text", "handle": 3.0, "properties": {"String": "decay"}, "children": none,
    ...          "special": none}
    >>> axes = {"type": "axes", "handle": 1.0, "special": [2.0, 0.0, 0.0, 0.0],
    ...         "properties": {"XLim": [0.0, 0.4], "YLim": [0.0, 1.0]},
    ...         "children": np.array([line, title], dtype=object)}
    >>> path = os.path.join(tempfile.mkdtemp(), "decay.fig")
    >>> scipy.io.savemat(path, {"hgS_070000": {"type": "figure", "handle": 0.0, "properties": {},
    ...                                        "children": axes, "special": none}})
    >>> sample = sample_reference([path], step=2)["decay.fig"]
    >>> sample["n_points"], sample["indices"], sample["x"], sample["y"], sample["title"]
    (5, [0, 2, 4], ['0.0', '0.2', '0.4'], ['1.0', '0.25', '0.0625'], 'decay')
    """
    result = {}
    for path in paths:
        c = read_fig_lines(path)
        x, y = c.lines[0]
        idx = list(range(0, len(x), step))
        result[Path(path).name] = {
            "n_points": len(x),
            "indices": idx,
            "x": [repr(float(x[i])) for i in idx],
            "y": [repr(float(y[i])) for i in idx],
            "title": c.title,
            "xlabel": c.xlabel,
            "ylabel": c.ylabel,
            "xlim": list(c.xlim),
            "ylim": list(c.ylim),
        }
    return result


def provenance(paths, step):
    """Where a sampled reference comes from: the JSON's ``"provenance"`` entry.

    Parameters
    ----------
    paths : iterable of path-like
        The ``.fig`` files sampled.
    step : int
        The sampling stride given to :func:`sample_reference`.

    Returns
    -------
    dict
        ``{"source", "extraction", "indices", "format", "command"}``, each a sentence.

    Examples
    --------
    >>> provenance(["figure1.fig", "figure2.fig"], 1000)["command"]
    'python matlab_ports/figdata.py --sample 1000 OUT.json figure1.fig figure2.fig'
    """
    names = " ".join(Path(p).name for p in paths)
    return {
        "source": (
            "MATLAB figure files of the white paper 'Scaling Analysis for Rigid Body Simulations' "
            "(A. P. Sabelhaus, 2014), from NTRTsim src/dev/apsabelhaus/scaling_analysis/ "
            "(January 2015 version), read from shared/reference/ntrt_scaling_analysis/ beside "
            "the repository; the .fig files themselves are not in this repository"
        ),
        "extraction": (
            "matlab_ports.figdata.read_fig_lines: scipy.io.loadmat, key hgS_070000, walk "
            "children, XData/YData of the graph2d.lineseries node (the only line); title and "
            "labels from the axes' text children indexed by its 'special' field; XLim/YLim"
        ),
        "indices": f"0, {step}, 2*{step}, ... of the 0-based point index (every {step}th point)",
        "format": "x and y as repr() strings of IEEE doubles; float() restores them exactly",
        "command": f"python matlab_ports/figdata.py --sample {step} OUT.json {names}",
    }


def main(argv=None):
    """Print a summary of ``.fig`` files, or write a sampled reference JSON (``--sample``)."""
    parser = argparse.ArgumentParser(description="Summarise MATLAB .fig files.")
    parser.add_argument("files", nargs="+", type=Path)
    parser.add_argument("--sample", nargs=2, metavar=("STEP", "OUT_JSON"), default=None)
    args = parser.parse_args(argv)
    if args.sample:
        step, out = int(args.sample[0]), Path(args.sample[1])
        doc = {"provenance": provenance(args.files, step), "files": sample_reference(args.files, step)}
        out.write_text(json.dumps(doc, indent=1) + "\n")
        return
    for path in args.files:
        c = read_fig_lines(path)
        print(f"{path.name}: title={c.title!r} xlabel={c.xlabel!r} ylabel={c.ylabel!r}")
        print(f"  xlim={c.xlim} ylim={c.ylim}")
        for x, y in c.lines:
            print(f"  line: {len(x)} points, x {x[0]}..{x[-1]}, y {y[0]}..{y[-1]}")


if __name__ == "__main__":
    main()
