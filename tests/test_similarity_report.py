"""The one comparison of every simulator (simulation.similarity_report), its one-ulp baseline, and the message
naming the Pi group a non-similarity changes."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem.simulation import nudged, similarity_report


def runs(dev, base, values=(1.0, 2.0)):
    t = [0.0, 1.0]
    original = pt.Trajectory(t, [[values[0]], [values[1]]], ("x",))
    mapped = pt.Trajectory(t, [[values[0]], [values[1] + dev]], ("x",))
    nudge = pt.Trajectory(t, [[values[0]], [values[1] + base]], ("x",))
    return original, mapped, nudge


def test_verdict_is_ten_times_the_baseline_per_state():
    # a constant signal: no range to fall back on, the baseline alone decides
    for dev, base, similar in ((9e-12, 1e-12, True), (1.1e-11, 1e-12, False), (0.0, 0.0, True), (1e-15, 0.0, False)):
        original, mapped, nudge = runs(dev, base, values=(2.0, 2.0))
        rep = similarity_report(original, mapped, s=2, scaling={}, exponents={}, nudged=nudge)
        assert rep.similar is similar
        assert math.isnan(rep.tol)  # judged against the baseline, not a tolerance
        assert rep.sensitivity["x"] == pytest.approx(base, rel=1e-3)


def test_zero_baseline_falls_back_to_a_billionth_of_the_range():
    # the signal spans 1 (from 1 to 2); the nudge changed nothing
    original, mapped, nudge = runs(0.9e-9, 0.0)
    assert similarity_report(original, mapped, s=2, scaling={}, exponents={}, nudged=nudge).similar
    original, mapped, nudge = runs(1.1e-9, 0.0)
    assert not similarity_report(original, mapped, s=2, scaling={}, exponents={}, nudged=nudge).similar


def test_absolute_tolerance_without_a_baseline():
    original, mapped, _ = runs(1e-7, 0.0)
    assert similarity_report(original, mapped, s=2, scaling={}, exponents={}, tol=1e-6).passed
    assert not similarity_report(original, mapped, s=2, scaling={}, exponents={}, tol=1e-8).passed
    exact = similarity_report(*runs(0.5, 0.0)[:2], s=2, scaling={}, exponents={}, tol=0.5)
    assert (exact.max_deviation, exact.passed) == (0.5, True)  # a deviation of exactly tol passes
    assert exact.scaled_dt is True  # the default: nothing says the step was not scaled
    with pytest.raises(pt.InvalidRequestError, match="tol"):
        similarity_report(original, mapped, s=2, scaling={}, exponents={})
    short = pt.Trajectory([0.0], [[1.0]], ("x",))
    with pytest.raises(pt.InvalidRequestError, match="cannot be compared"):
        similarity_report(original, short, s=2, scaling={}, exponents={}, tol=1.0)


@given(st.floats(min_value=-1e6, max_value=1e6, allow_nan=False))
def test_nudge_moves_by_one_ulp_of_the_value_or_of_one(x):
    moved = float(nudged([x])[0])
    assert moved > x
    if abs(x) >= 1:  # the next double up, exactly (math.nextafter is the independent oracle)
        assert moved == math.nextafter(x, math.inf)
    else:  # the ulp of 1, up to the rounding of the sum x + 2^-52 itself (half an ulp of the sum)
        assert abs((moved - x) - 2.0**-52) <= math.ulp(max(abs(moved), 2.0**-52)) / 2


def test_verify_similarity_with_a_baseline():
    rod = pt.models.hinged_rod()
    sc = pt.search(rod.system, scale={"g": 1, "l": -1}, fixed=("m", "k_theta")).scalings[0]
    rep = pt.verify_similarity(rod, sc, s=10, t_final=2, baseline=True)
    assert rep.similar
    assert rep.sensitivity is not None
    assert rep.nudged.y.shape == rep.original.y.shape
    assert rep.sensitivity["theta"] > 0
    bad = pt.verify_similarity(rod, {"g": 1}, s=10, t_final=2, check=False, baseline=True)
    assert not bad.similar


def test_check_names_the_pi_group_and_prints_plain_exponents():
    rod = pt.models.hinged_rod()
    with pytest.raises(pt.InvalidRequestError) as caught:
        pt.verify_similarity(rod, {"g": 1, "l": "1/2"}, s=2, t_final=0.1)
    message = str(caught.value)
    assert "Fraction" not in message
    assert "(l: 1/2, g: 1)" in message
    assert "Pi group k_theta/(g*l*m) by s^-3/2" in message
