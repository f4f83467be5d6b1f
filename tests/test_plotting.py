"""pitheorem.plotting: the search chart and the similarity figure, read back from their matplotlib artists.

The oracles are the numbers the figures show, compared with what the search
and the report hold (each cell's label is the power of s of its scaling).
"""

from __future__ import annotations

from fractions import Fraction

import matplotlib.pyplot as plt
import numpy as np
import pytest

import pitheorem as pt
from pitheorem.plotting import plot_search, plot_similarity


@pytest.fixture(scope="module")
def hinged():
    return pt.models.hinged_rod()


def test_search_chart_shows_every_minimal_scaling(rod):
    res = pt.search(rod, scale={"g": 1})
    fig = res.plot()
    ax = fig.axes[0]
    assert [t.get_text() for t in ax.get_xticklabels()] == ["#1", "#2", "#3"]
    # one row a variable, labelled with its role unless free; one cell a power of s
    assert [t.get_text() for t in ax.get_yticklabels()] == [
        n if role == "free" else f"{n} ({role})" for n, role in res.roles.items()
    ]
    labels = [t.get_text() for t in ax.get_yticklabels()]
    assert (labels[rod.index("g")], labels[rod.index("t")], labels[rod.index("m")]) == ("g (scale)", "t (fixed)", "m")
    cells = {(round(text.get_position()[1]), round(text.get_position()[0])): text.get_text() for text in ax.texts}
    assert len(cells) == len(rod.variables) * 3
    assert cells[(0, 0)] == "$s^{-2}$"  # m in the first scaling, in mathtext
    for j, scaling in enumerate(res.scalings):
        shown = [cells[(i, j)] for i in range(len(rod.variables))]
        assert shown == [
            "-" if p == 0 else f"${pt.formatting.pieces.power_latex(Fraction(p))}$" for p in scaling.vector
        ]
    assert ax.get_title() == "g by s: 3 minimal scalings"
    # a colour bar says what the colours mean
    bar = fig.axes[1]
    assert bar.get_ylabel() == "exponent of $s$"
    assert [t.get_text() for t in bar.get_yticklabels()] == ["-2 shrinks", "0 same", "2 grows"]
    infeasible = pt.search(rod, scale={"g": 1}, fixed=("t", "m", "k_theta"))
    assert "impossible" in infeasible.plot().axes[0].get_title()
    assert len(infeasible.plot().axes[0].texts) == 0


def test_plot_search_draws_into_given_axes(rod):
    res = pt.search(rod, scale={"g": 1, "l": -1}, fixed=("m", "k_theta"))
    fig, (left, right) = plt.subplots(1, 2)
    assert plot_search(res, ax=right) is fig
    assert len(left.images) == 0
    assert len(right.images) == 1
    # the colours are the exponents themselves, clipped at +-1 at least
    image = np.asarray(right.images[0].get_array())
    assert image[:, 0].tolist() == [float(p) for p in res.scalings[0].vector]
    assert right.images[0].get_clim() == (-1.0, 1.0)
    assert right.get_xlabel() == "minimal scaling"


def test_report_plot(hinged):
    rep = pt.verify_similarity(hinged, {"g": 1}, s=2, t_final=1.0, check=False)  # the paper's Figure 2
    fig = rep.plot()
    top, bottom = fig.axes
    labels = [line.get_label() for line in top.get_lines()]
    assert labels == [
        "theta (original)",
        "theta (scaled, mapped back)",
        "omega (original)",
        "omega (scaled, mapped back)",
    ]
    assert top.get_legend() is not None
    assert bottom.get_legend() is not None
    diff_labels = [line.get_label() for line in bottom.get_lines()]
    assert "|theta difference|" in diff_labels
    assert "|omega difference|" in diff_labels
    assert bottom.get_xlabel() == "t, original units"
    assert "NOT similar" in top.get_title()
    np.testing.assert_array_equal(top.get_lines()[0].get_ydata(), rep.original["theta"])
    np.testing.assert_array_equal(top.get_lines()[1].get_ydata(), rep.mapped["theta"])
    one = rep.plot(states=["omega"]).axes[0]
    assert [line.get_label() for line in one.get_lines()] == ["omega (original)", "omega (scaled, mapped back)"]
    with pytest.raises(pt.UnknownVariableError, match="'phi'"):
        rep.plot(states=["phi"])


def test_report_plot_names_a_unit_on_every_axis(hinged):
    sc = pt.search(hinged.system, scale={"g": 1}).scalings[0]
    rep = pt.verify_similarity(hinged, sc, s=2, t_final=0.5)
    top, bottom = rep.plot().axes
    # without units given, each axis shows the dimension of what it plots
    assert top.get_ylabel() == "theta [1], omega [T^-1]"
    assert bottom.get_xlabel() == "t [T]"
    assert bottom.get_ylabel() == "|difference|: theta [1], omega [T^-1]"
    top, bottom = rep.plot(units={"theta": "rad", "omega": "rad/s", "t": "s"}).axes
    assert top.get_ylabel() == "theta [rad], omega [rad/s]"
    assert bottom.get_xlabel() == "t [s]"


def test_plot_similarity_is_the_reports_plot(hinged):
    sc = pt.search(hinged.system, scale={"g": 1}).scalings[0]
    rep = pt.verify_similarity(hinged, sc, s=2, t_final=0.5)
    fig = plot_similarity(rep, states=["theta"], units={"t": "s"})
    top, bottom = fig.axes
    assert [line.get_label() for line in top.get_lines()] == ["theta (original)", "theta (scaled, mapped back)"]
    # the difference line is |mapped - original|, computed here by hand, and the tolerance a dotted line
    difference, tol = bottom.get_lines()
    np.testing.assert_array_equal(difference.get_ydata(), np.abs(rep.mapped["theta"] - rep.original["theta"]))
    assert list(tol.get_ydata()) == [rep.tol, rep.tol]
    assert top.get_title() == f"s = 2: similar (max deviation {rep.max_deviation:.2g})"
    assert (top.get_ylabel(), bottom.get_xlabel()) == ("theta [1]", "t [s]")
    # judged against its one-ulp baseline, a report has no tolerance to draw (no "tol = nan")
    judged = pt.verify_similarity(hinged, sc, s=2, t_final=0.5, baseline=True)
    assert [line.get_label() for line in plot_similarity(judged, states=["theta"]).axes[1].get_lines()] == [
        "|theta difference|"
    ]
