"""Time the generated right-hand sides against hand-written ones, in one run, and print ratios.

A :class:`pitheorem.Model` generates its numeric right-hand side from its sympy equations. The
baseline is the same physics written out by hand in plain Python floats (as the package did
before issue 14), integrated the same way: scipy's ``solve_ivp`` (DOP853, the tolerances of
:func:`pitheorem.simulate`) and a fixed-step Euler loop, interleaved, best of several runs.

Target (issue 14): the generated right-hand side within 1.2 times the hand-written one.

Run: python benchmarks/bench_simulation.py [--quick]
"""

from __future__ import annotations

import argparse
import math

import numpy as np
from _timing import best_of
from scipy.integrate import solve_ivp

import pitheorem as pt

TARGET = 1.2


def rod_by_hand(t, y, p):
    """The hinged rod of the paper's Eq. 1 (restoring spring), written out."""
    angle, rate = float(y[0]), float(y[1])
    inertia = p["m"] * p["l"] * p["l"] / 3.0
    gravity = 0.5 * p["m"] * p["g"] * p["l"] * math.cos(angle)
    return np.array([rate, (gravity - p["c_theta"] * rate - p["k_theta"] * (angle - p["theta_r"])) / inertia])


def spring_by_hand(t, y, p):
    """The hinged rod held by a longitudinal spring and damper, written out."""
    angle, rate = float(y[0]), float(y[1])
    length = p["l"] * math.sqrt(5.0 + 4.0 * math.sin(angle))
    lever = 2.0 * p["l"] * p["l"] * math.cos(angle) / length
    pull = p["k"] * (length - p["x_r"]) + p["c"] * lever * rate
    inertia = p["m"] * p["l"] * p["l"] / 3.0
    return np.array([rate, (0.5 * p["m"] * p["g"] * p["l"] * math.cos(angle) - pull * lever) / inertia])


def adaptive(rhs, p, y0, t_final):
    solve_ivp(lambda t, y: rhs(t, y, p), (0.0, t_final), y0, method="DOP853", rtol=1e-10, atol=1e-12)


def euler(rhs, p, y0, n_steps, dt=1e-3):
    y = np.array(y0, dtype=float)
    for i in range(n_steps):
        y = y + rhs(i * dt, y, p) * dt


def main(quick: bool = False):
    repeat, t_final, n_steps = (3, 5.0, 2000) if quick else (7, 20.0, 20000)
    cases = [(pt.models.hinged_rod(), rod_by_hand), (pt.models.hinged_rod_longitudinal(), spring_by_hand)]
    print(
        f"{'model':26s} {'integrator':11s} {'generated':>10s} {'by hand':>10s} {'ratio':>7s}  (goal: within {TARGET}x)"
    )
    worst = 0.0
    for model, by_hand in cases:
        p, y0 = model.resolve_params(), model.resolve_initial()
        np.testing.assert_allclose(model.rhs(0.0, y0, p), by_hand(0.0, y0, p), rtol=1e-12)
        runs = {
            "solve_ivp": lambda rhs, p=p, y0=y0: adaptive(rhs, p, y0, t_final),
            "euler": lambda rhs, p=p, y0=y0: euler(rhs, p, y0, n_steps),
        }
        for name, run in runs.items():
            ours = best_of(lambda run=run, rhs=model.rhs: run(rhs), repeat)
            base = best_of(lambda run=run, rhs=by_hand: run(rhs), repeat)
            worst = max(worst, ours / base)
            print(f"{model.name:26s} {name:11s} {ours * 1e3:8.1f} ms {base * 1e3:8.1f} ms {ours / base:7.2f}")
    print(f"worst ratio {worst:.2f} ({'within' if worst <= TARGET else 'ABOVE'} the goal of {TARGET}x)")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer and shorter runs")
    main(parser.parse_args().quick)
