"""The MATLAB ports in matlab_ports/ reproduce the original programs and the paper's figures.

The hinged-rod port is compared with the MATLAB figure files of the white paper: in full (all
100001 points) when ``../shared/reference/ntrt_scaling_analysis/*.fig`` sits beside the
repository, and always against the every-1000th-point sample kept in
``tests/data/matlab_fig_samples.json`` (see its ``provenance`` entry).

Not a module of pitheorem: the ``matlab_ports`` namespace, ports of the white paper's
MATLAB programs, checked against those programs' figures.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import matplotlib.colors
import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[1]
if str(REPO) not in sys.path:  # matlab_ports/ lives at the repository root, outside the package
    sys.path.insert(0, str(REPO))

from matlab_ports import (  # noqa: E402
    figdata,
    rod_hinge_dynamics,
    scaling_counterexample,
    scaling_counterexample_nonlinear,
    scaling_counterexample_projectile,
)

FIG_DIR = Path(__file__).resolve().parents[2] / "shared" / "reference" / "ntrt_scaling_analysis"
SAMPLES = Path(__file__).resolve().parent / "data" / "matlab_fig_samples.json"
FIG_FILES = {
    "figure1": "original_angular.fig",
    "figure2": "grav_only_angular.fig",
    "figure3": "l_g_angular.fig",
    "figure4": "l_g_c_angular.fig",
    "figure5": "l_g_c_t_angular.fig",
}
NONLINEAR = scaling_counterexample_nonlinear
have_figs = all((FIG_DIR / name).is_file() for name in FIG_FILES.values())


@pytest.fixture(scope="module")
def figure_data():
    return NONLINEAR.simulate_figures()


@pytest.fixture(scope="module")
def samples():
    return json.loads(SAMPLES.read_text())


# --- (a) the five curves against the MATLAB data ---------------------------------------------


@pytest.mark.parametrize("name", sorted(FIG_FILES))
def test_curves_match_sampled_reference(figure_data, samples, name):
    ref = samples["files"][FIG_FILES[name]]
    idx = np.array(ref["indices"])
    t, theta = figure_data[name]
    assert len(t) == len(theta) == ref["n_points"] == 100001
    # bit for bit: the samples are repr() strings of the MATLAB doubles, so float() restores them
    np.testing.assert_array_equal(t[idx], [float(v) for v in ref["x"]])
    np.testing.assert_array_equal(theta[idx], [float(v) for v in ref["y"]])


def test_sampled_reference_has_provenance(samples):
    assert {"source", "extraction", "indices", "format", "command"} <= set(samples["provenance"])
    assert set(samples["files"]) == set(FIG_FILES.values())
    for ref in samples["files"].values():
        assert ref["indices"] == list(range(0, 100001, 1000))


@pytest.mark.skipif(not have_figs, reason=f"MATLAB reference .fig files not found in {FIG_DIR}")
@pytest.mark.parametrize("name", sorted(FIG_FILES))
def test_curves_match_full_fig_data(figure_data, name):
    contents = figdata.read_fig_lines(FIG_DIR / FIG_FILES[name])
    assert len(contents.lines) == 1
    x_ref, y_ref = contents.lines[0]
    t, theta = figure_data[name]
    assert t.shape == theta.shape == x_ref.shape == y_ref.shape == (100001,)
    np.testing.assert_array_equal(t, x_ref)  # bit for bit, all 100001 points
    np.testing.assert_array_equal(theta, y_ref)
    # generated figure reproduces the .fig's title, labels and axis limits
    ax = NONLINEAR.plot_figures({name: figure_data[name]})[name].axes[0]
    assert (ax.get_title(), ax.get_xlabel(), ax.get_ylabel()) == (
        contents.title,
        contents.xlabel,
        contents.ylabel,
    )
    assert ax.get_xlim() == contents.xlim
    assert ax.get_ylim() == contents.ylim


def test_figure5_time_axis_runs_to_20(figure_data):
    t5, theta5 = figure_data["figure5"]
    _, theta4 = figure_data["figure4"]
    assert t5[0] == 0.0
    assert t5[-1] == 20.0
    np.testing.assert_array_equal(t5, 2 * figure_data["figure1"][0])
    np.testing.assert_array_equal(theta5, theta4)  # same parameters, simulated again


def test_figure5_reproduces_figure1(figure_data):
    """The paper's point: with g, l, c and t scaled the original response comes back
    (up to the Euler discretisation, which now takes steps of 2*dt in original time)."""
    _, theta1 = figure_data["figure1"]
    _, theta5 = figure_data["figure5"]
    np.testing.assert_allclose(theta5[:50001], theta1[::2], rtol=0, atol=1e-3)
    assert np.max(np.abs(figure_data["figure4"][1] - theta1)) > 0.1
    assert np.max(np.abs(figure_data["figure3"][1] - theta1)) > 0.1


def test_fast_mode_truncates():
    data = NONLINEAR.simulate_figures(n_points=50)
    assert all(len(t) == len(theta) == 50 for t, theta in data.values())


# --- (b) titles, labels, axis limits -----------------------------------------------------------

# transcribed from the paper's Figures 1-5, not imported from the ports: the oracle must not be the code under test
TITLES = {
    "figure1": "Original, unscaled simulation",
    "figure2": "With only gravity scaled",
    "figure3": "Gravity and length scale changed",
    "figure4": "Gravity, length, and angular damping constant scale changed",
    "figure5": "Gravity, length, angular damping constant, and time scale changed",
}


@pytest.mark.parametrize("name", sorted(TITLES))
def test_nonlinear_figure_labels(name):
    figs = NONLINEAR.plot_figures(NONLINEAR.simulate_figures(n_points=100))
    assert sorted(figs) == sorted(TITLES)
    ax = figs[name].axes[0]
    assert ax.get_title() == TITLES[name]
    assert ax.get_xlabel() == "time, sec"
    radial = "Radial position of rod, radians"
    assert ax.get_ylabel() == (radial if name == "figure1" else "Angular position of rod, radians")
    assert ax.get_xlim() == (0.0, 10.0)  # also figure5 (quirk of the original)
    assert ax.get_ylim() == (0.5, 1.5)


@pytest.mark.parametrize("name", sorted(FIG_FILES))
def test_sampled_reference_labels_match_spec(samples, name):
    ref = samples["files"][FIG_FILES[name]]
    assert ref["title"] == TITLES[name]
    assert ref["xlabel"] == "time, sec"
    assert ref["xlim"] == [0.0, 10.0]
    assert ref["ylim"] == [0.5, 1.5]


def test_linear_and_projectile_axis_labels_are_matlabs():
    """The labels that the MATLAB programs set (example_code/scaling_counterexample.m and
    backup/scaling_counterexample_backup.m), written out here from those files."""
    lin = scaling_counterexample.plot_runs(scaling_counterexample.simulate())
    for fig in lin.values():
        ax = fig.axes[0]
        assert (ax.get_xlabel(), ax.get_ylabel()) == ("time, sec", "Vertical height of particle, meters")
    proj = scaling_counterexample_projectile.plot_runs(scaling_counterexample_projectile.simulate())
    plain = ("Horizontal length, meters", "Vertical length, meters")
    scaled = (
        "Horizontal length, units of meters * scaling const",
        "Vertical length, units of meters * scaling const",
    )
    got = {name: (f.axes[0].get_xlabel(), f.axes[0].get_ylabel()) for name, f in proj.items()}
    assert got == {"original": plain, "gravity": plain, "gravity_length": scaled}


def test_projectile_port_names_its_matlab_file():
    doc = scaling_counterexample_projectile.__doc__
    assert "backup/scaling_counterexample_backup.m" in doc
    assert "scaling_counterexample_projectile.m" not in doc  # no such MATLAB file exists


def test_linear_and_projectile_titles():
    lin = scaling_counterexample.plot_runs(scaling_counterexample.simulate())
    assert [f.axes[0].get_title() for f in lin.values()] == [
        "Original, unscaled simulation",
        "With only gravity scaled",
        "With both gravity and initial length constants scaled",
    ]
    red = lin["original"].axes[0].get_lines()[1]
    assert matplotlib.colors.to_hex(red.get_color()) == "#ff0000"  # y_dot in red
    proj = scaling_counterexample_projectile.plot_runs(scaling_counterexample_projectile.simulate())
    assert [f.axes[0].get_title() for f in proj.values()] == [
        "Original, unscaled simulation",
        "With only gravity scaled",
        "With both gravity and length scaled, post-hoc",
    ]


# --- the dynamics functions ------------------------------------------------------------------


def test_rod_dynamics_restoring_spring():
    """The code's sign (not the paper's Eq. 1): the spring pulls theta back to theta_r."""
    f = rod_hinge_dynamics.rod_hinge_dynamics
    above = f([1.0, 0.0], m=1.0, x_r=0.0, l=1.0, g=0.0, k=2.0, c=0.0, theta_r=0.5)
    below = f([0.0, 0.0], m=1.0, x_r=0.0, l=1.0, g=0.0, k=2.0, c=0.0, theta_r=0.5)
    assert above[1] < 0 < below[1]
    # 3/(m l^2) * (m g l/2 cos(theta) - c theta_dot - k theta + k theta_r)
    got = f([0.3, 0.7], 1.5, 1.0, 2.0, 9.81, 100.0, 10.0, np.pi / 3)
    want = 3 / (1.5 * 4.0) * (1.5 * 9.81 * 2.0 / 2 * np.cos(0.3) - 7.0 - 30.0 + 100.0 * np.pi / 3)
    np.testing.assert_allclose(got, [0.7, want], rtol=1e-14)


def test_rod_dynamics_longitudinal_variants():
    y, m, x_r, L, g, k, c = [0.4, 0.9], 1.5, 1.0, 2.0, 9.81, 100.0, 10.0
    s, co = np.sin(0.4), np.cos(0.4)
    base = (m * g * L / 2) * co + k * L**2 * s * co - k * x_r * L * s
    a = rod_hinge_dynamics.rod_hinge_dynamics_longitudinal(y, m, x_r, L, g, k, c, 0.0)
    b = rod_hinge_dynamics.rod_hinge_dynamics_longitudinal_rotational_damper(y, m, x_r, L, g, k, c, 0.0)
    np.testing.assert_allclose(a, [0.9, 3 / (m * L**3) * (base - c * L * 0.9 * s**2)], rtol=1e-13)
    np.testing.assert_allclose(b, [0.9, 3 / (m * L**3) * (base - c * 0.9)], rtol=1e-13)


# --- (c) linear port: superposition ----------------------------------------------------------


def test_linear_superposition():
    runs = scaling_counterexample.simulate()
    t, x1 = runs["original"]
    _, x2 = runs["gravity"]
    _, x3 = runs["gravity_length"]
    assert len(t) == 401
    assert (t[0], t[-1]) == (0.0, 4.0)
    assert x1.shape == x2.shape == x3.shape == (2, 401)
    np.testing.assert_allclose(x3, x1, rtol=0, atol=1e-12)  # scaled and divided back: the same
    assert np.max(np.abs(x2 - x1)) > 0.5  # gravity alone: different
    assert (x1[0, 0], x1[1, 0]) == (1.0, 0.0)


def _matlab_linear_loop(m, y0, y_rest, g, k, c, n=401, dt=0.01):
    """The MATLAB loop y(:, i) = (A * y(:, i-1) + C) * dt + y(:, i-1), written out row by row
    with plain floats, independently of the port."""
    A = [[0.0, 1.0], [-k / m, -c / m]]
    C = [0.0, -g + k * y_rest / m]
    rows = [(float(y0), 0.0)]
    for _ in range(1, n):
        y = rows[-1]
        rows.append(tuple((A[j][0] * y[0] + A[j][1] * y[1] + C[j]) * dt + y[j] for j in range(2)))
    return np.array(rows).T


@pytest.mark.parametrize("g_factor", [1.0, 10.0])
def test_linear_port_is_the_matlab_update_bit_for_bit(g_factor):
    p = dict(scaling_counterexample.PARAMS, g=g_factor * scaling_counterexample.PARAMS["g"])
    t = np.zeros(401)
    np.testing.assert_array_equal(scaling_counterexample.euler(p, t), _matlab_linear_loop(**p))


def test_linear_third_run_is_scaled_by_the_matlab_factor():
    runs = scaling_counterexample.simulate()
    p = dict(scaling_counterexample.PARAMS)
    factor = (10 * p["g"]) / p["g"]  # length_scaling_factor = g_scaled/g
    want = _matlab_linear_loop(**dict(p, g=10 * p["g"], y0=factor * p["y0"], y_rest=factor * p["y_rest"]))
    np.testing.assert_array_equal(runs["gravity_length"][1], want / factor)


def test_linear_settles_at_static_equilibrium():
    _, x = scaling_counterexample.simulate()["original"]
    p = scaling_counterexample.PARAMS
    assert x[0, -1] == pytest.approx(p["y_rest"] - p["m"] * p["g"] / p["k"], abs=1e-4)


# --- (d) projectile: tf and the sin quirk ----------------------------------------------------


def test_projectile_flight_time_and_x_quirk():
    P = scaling_counterexample_projectile
    runs = P.simulate()
    v0, g, angle = P.PARAMS["v0"], P.PARAMS["g"], P.PARAMS["angle"]
    t, x, y = runs["original"]
    assert len(t) == 100
    assert t[-1] == 2 * v0 * np.sin(angle) / g == P.flight_time(v0, g, angle)
    np.testing.assert_array_equal(x, v0 * np.sin(angle) * t)  # quirk: sin, not cos
    assert np.max(np.abs(x - v0 * np.cos(angle) * t)) > 10  # what cos would have given: ~0
    assert y[0] == 0.0
    assert abs(y[-1]) < 1e-12
    tg, _, _ = runs["gravity"]
    assert tg[-1] == pytest.approx(t[-1] / 10, rel=1e-15)
    _, x3, y3 = runs["gravity_length"]
    np.testing.assert_allclose(x3, x, rtol=1e-14)
    np.testing.assert_allclose(y3, y, rtol=0, atol=1e-12)


# --- figdata reader -------------------------------------------------------------------------


@pytest.mark.skipif(not have_figs, reason=f"MATLAB reference .fig files not found in {FIG_DIR}")
def test_figdata_reads_figure5_labels():
    contents = figdata.read_fig_lines(FIG_DIR / FIG_FILES["figure5"])
    assert contents.title == TITLES["figure5"]
    assert contents.ylabel == "Angular position of rod, radians"
    assert contents.xlim == (0.0, 10.0)  # the original axis, though the data run to 20
    assert contents.lines[0][0][-1] == 20.0


# --- (e) scripts run on their own ------------------------------------------------------------


@pytest.mark.parametrize(
    ("module", "pngs"),
    [
        ("scaling_counterexample_nonlinear", [f"figure{i}.png" for i in range(1, 6)]),
        ("scaling_counterexample", [f"linear_{k}.png" for k in ("original", "gravity", "gravity_length")]),
        (
            "scaling_counterexample_projectile",
            [f"projectile_{k}.png" for k in ("original", "gravity", "gravity_length")],
        ),
    ],
)
def test_script_writes_pngs(tmp_path, module, pngs):
    outdir = tmp_path / "out"
    proc = subprocess.run(
        [sys.executable, str(REPO / "matlab_ports" / f"{module}.py"), "--outdir", str(outdir)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in outdir.iterdir()) == sorted(pngs)
    for name in pngs:
        assert (outdir / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# --- the fast scalar loop is the MATLAB vector update, bit for bit ----------------------------


def test_scalar_loop_equals_vector_update():
    """simulate() works on floats; MATLAB's y(:,i) = y(:,i-1) + f(y(:,i-1))*dt on 2-vectors
    (rod_hinge_dynamics) gives the same bits."""
    p = NONLINEAR.PARAMS
    n = 3000
    fast = NONLINEAR.simulate(p, np.zeros(n))
    y = np.empty((2, n))
    y[:, 0] = (NONLINEAR.THETA_0, 0.0)
    args = (p["m"], p["x_r"], p["l"], p["g"], p["k"], p["c"], p["theta_r"])
    for i in range(1, n):
        y[:, i] = y[:, i - 1] + rod_hinge_dynamics.rod_hinge_dynamics(y[:, i - 1], *args) * NONLINEAR.DT
    np.testing.assert_array_equal(fast, y)
