"""engines.sweep: verify at many scale factors, row for row what verify says alone, locally and on Dask."""

from __future__ import annotations

import json
import math
from fractions import Fraction
from pathlib import Path

import pytest

import pitheorem as pt

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

from pitheorem import engines
from pitheorem.cli import main
from pitheorem.engines.cli import parse_s_values
from pitheorem.engines.thresholds import thresholds
from pitheorem.engines.verdicts.strength import control_factors
from tests.conftest import expected_verdict, recorded_batches

PENDULUM = engines.example_path("pendulum.xml")
DURATION = 0.1

#: a rod hanging straight down at rest: gravity cannot move it, so a verdict on it proves nothing
STILL = """<mujoco><option gravity="0 0 -9.81"/><worldbody><body>
<joint name="hinge" type="hinge" axis="0 1 0"/>
<geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.02" mass="1"/>
</body></worldbody></mujoco>"""


def push(t):
    return [0.1 * math.sin(7.0 * t)]


@pytest.fixture(scope="module")
def pendulum():
    model = engines.load(PENDULUM)
    return model, pt.search(model.system(), scale={"g": 1}).scalings[0]


def verify_alone(model, sc, s, controls=push):
    """What verify says at one s, or "refused" where the engine will not build the copy."""
    try:
        rep = engines.verify(model, sc, s, duration=DURATION, controls=controls)
    except engines.EngineModelError:
        return None
    return rep


def test_every_row_is_what_verify_says_alone_at_that_s(pendulum):
    model, sc = pendulum
    s = (Fraction(1, 4), 1e-3, 1, 10.0**0.5, 1e3)
    sw = engines.sweep(model, sc, s=s, duration=DURATION, controls=push, fit=False)
    assert sw.s == tuple(pt.exact.read_scale_factor(v) for v in s)  # the order asked
    for row in sw.rows:
        rep = verify_alone(model, sc, row.s)
        assert row.verdict == expected_verdict(rep) == rep.verdict
        assert row.horizon == rep.horizon
        assert row.max_deviation == rep.max_deviation
        assert row.yardstick == max(rep.sensitivity.values())
        assert row.causes == rep.causes
        assert row.first_divergence == rep.first_divergence
    assert sw.verdicts[0] == sw.verdicts[2] == "exact"  # s = 1/4 and 1: bit for bit


def test_the_process_pool_and_this_process_give_the_same_rows(pendulum):
    model, sc = pendulum
    s = (4, 1e-2, 10, 100)
    parallel = engines.sweep(model, sc, s=s, duration=DURATION, controls=push, fit=False, workers=2)
    serial = engines.sweep(model, sc, s=s, duration=DURATION, controls=push, fit=False, workers=1)
    assert parallel == serial
    seen = []
    engines.sweep(model, sc, s=s, duration=DURATION, controls=push, fit=False, progress=lambda *a: seen.append(a))
    assert [done for done, _ in seen] == [1, 2, 3, 4]
    assert {total for _, total in seen} == {4}


def test_in_this_process_the_copies_of_every_s_run_in_one_call(pendulum, monkeypatch):
    """The first batches of all the verifications go to the engine at once (rollout's threads, MJX's vmap):
    one call for the baseline, one for every copy and its first controls, and the rows are verify's."""
    from pitheorem.engines.runners.mujoco import MujocoRunner

    model, sc = pendulum
    s = (4, 1e-2, 10, 100)
    batches = recorded_batches(monkeypatch, MujocoRunner)
    sw = engines.sweep(model, sc, s=s, duration=DURATION, controls=push, fit=False, workers=1)
    calls = [len(jobs) for jobs in batches]
    first_controls = len({g for g, _e, _f in control_factors(model)})
    assert calls[:2] == [1 + 3, len(s) * (1 + first_controls)]  # the original and 3 twins; then every copy
    monkeypatch.undo()
    for row in sw.rows:
        rep = verify_alone(model, sc, row.s)
        assert (row.verdict, row.max_deviation, row.horizon) == (rep.verdict, rep.max_deviation, rep.horizon)


def test_a_copy_the_compiler_refuses_is_a_row(pendulum, tmp_path):
    model, _ = pendulum
    mass = pt.Scaling.from_unit_change(model.system(), {"M": 1})
    # s = 1e-17 puts the arm's 1 kg below MuJoCo's mjMINVAL (1e-15): verify alone cannot build the copy
    with pytest.raises(engines.EngineModelError, match="mjMINVAL"):
        engines.verify(model, mass, 1e-17, duration=DURATION)
    sw = engines.sweep(model, mass, s=(1e-17, 1), duration=DURATION, controls=push, fit=False)
    refused, fine = sw.rows
    assert refused.verdict == "refused"
    assert refused.max_deviation is None
    assert refused.yardstick is None
    assert "mjMINVAL" in refused.causes[0].detail
    assert refused.causes[0].kind == "threshold"
    assert "mujoco_minval_mass" in refused.thresholds
    assert fine.verdict == "exact"
    assert fine.thresholds == ()


def test_the_thresholds_crossed_are_those_check_finds_beyond_on_the_copy(pendulum):
    model, _ = pendulum
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    s = (1e-4, 1e-2, 0.15, 1, 1e6)  # at 0.15 the rolling friction (1e-4 m) is near mjMINMU, not below it
    sw = engines.sweep(model, lengths, s=s, duration=DURATION, controls=push, fit=False, workers=1)
    assert any("within a factor" in c.detail for c in engines.check(model.scaled(lengths, 0.15)))
    names = [t.name for t in thresholds("mujoco")]
    for row in sw.rows:
        beyond = {
            n for c in engines.check(model.scaled(lengths, row.s)) for n in names if f"is below {n} " in c.detail
        } | {n for c in engines.check(model.scaled(lengths, row.s)) for n in names if f"is above {n} " in c.detail}
        assert set(row.thresholds) == beyond, row
    assert "mujoco_minmu" in sw.rows[0].thresholds
    assert sw.rows[2].thresholds == sw.rows[3].thresholds == ()


def test_a_model_that_does_not_move_is_inconclusive(tmp_path):
    path = tmp_path / "still.xml"
    path.write_text(STILL)
    model = engines.load(path)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    sw = engines.sweep(model, sc, s=(10,), duration=DURATION, workers=1, fit=False)
    rep = engines.verify(model, sc, 10, duration=DURATION)
    assert rep.excited is False
    assert rep.inconclusive
    assert sw.verdicts == ("inconclusive",) == (rep.verdict,)


def test_units_fit_units_would_choose_are_placed_on_the_sweep(pendulum):
    model, _ = pendulum
    # the same pendulum written in km: its friction lengths sit below mjMINMU, and fit_units takes it
    # back to metres, lengths read 1000 times larger: along the length scaling, that is s = 1000
    far = model.converted(L=1000)
    assert far.units["L"] == "1000 m"
    lengths = pt.Scaling.from_unit_change(far.system(), {"L": 1})
    sw = engines.sweep(far, lengths, s=(1,), duration=DURATION, controls=push, workers=1)
    assert sw.fitted_s == pytest.approx(1000, rel=1e-12)
    assert sw.fitted_units == {"M": "kg", "L": "m", "T": "s"}
    mass = pt.Scaling.from_unit_change(far.system(), {"M": 1})  # moves no unit the fit changes: s = 1
    assert engines.sweep(far, mass, s=(1,), duration=DURATION, workers=1).fitted_s == pytest.approx(1.0)


def test_rows_display_in_every_format(pendulum):
    model, sc = pendulum
    sw = engines.sweep(model, sc, s=(1e-3, 4), duration=DURATION, controls=push, workers=1)
    doc = json.loads(format(sw, "json"))
    assert [r["verdict"] for r in doc["rows"]] == list(sw.verdicts)
    assert [r["max_deviation"] for r in doc["rows"]] == [r.max_deviation for r in sw.rows]
    assert doc["rows"][1]["s"] == 4
    assert doc["rows"][0]["thresholds"] == ["mujoco_minmu"]
    text = str(sw)
    assert "mujoco_minmu" in text.splitlines()[2]
    assert text.splitlines()[3].split()[:2] == ["4", "exact"]
    assert r"\begin{tabular}" in format(sw, "latex")
    assert format(sw, "html").count("<tr>") == 3


def test_the_figure_marks_verdicts_bands_and_the_fitted_units(pendulum):
    model, _ = pendulum
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    sw = engines.sweep(model, lengths, s=(1e-4, 1e-2, 1, 100), duration=DURATION, controls=push, workers=1)
    fig = sw.plot()
    ax = fig.axes[0]
    assert (ax.get_xscale(), ax.get_yscale()) == ("log", "log")
    assert "original units: kg, m, s" in ax.get_ylabel()
    assert ax.get_xlabel() == "scale factor s"
    assert [t.get_text() for t in ax.texts] == ["beyond mujoco_minmu"]  # crossed below 1e-2 only
    labels = ax.get_legend_handles_labels()[1]
    assert any(label.startswith("exact") for label in labels)
    assert any(label.startswith("fit_units: ") for label in labels)
    band = ax.patches[0].get_x() if ax.patches else None
    assert band is None or band <= 1e-4
    assert "beyond mujoco_minmu at s = 0.0001 to 0.01" in fig.get_label()


def test_a_copy_the_engine_gave_up_on_is_drawn_at_the_top_of_the_figure():
    """A row whose copy broke down (MuJoCo reset it: an infinite deviation) is marked, not an axis limit."""
    from pitheorem.engines import Sweep, SweepRow

    rows = (
        SweepRow(1, "exact", 0.0, 1e-12, None, True, None, (), ()),
        SweepRow(100, "similar", 1e-9, 1e-10, None, True, None, (), ()),
        SweepRow(1000, "not similar", math.inf, 1e-8, None, True, None, (), ()),
    )
    ax = Sweep("robot.xml", "mujoco", None, 1.0, rows).plot().axes[0]
    _low, high = ax.get_ylim()
    assert math.isfinite(high)
    assert high == pytest.approx(1e-8 * 30)  # the largest finite number, with room above it
    marks = {tuple(xy) for c in ax.collections for xy in c.get_offsets()}
    assert (1000.0, high / 2) in marks  # the broken-down copy, at the top


def test_on_a_dask_cluster_the_rows_are_the_same(pendulum):
    distributed = pytest.importorskip("distributed")
    model, sc = pendulum
    s = (4, 1e-3, 10)
    local = engines.sweep(model, sc, s=s, duration=DURATION, controls=push, fit=False, workers=1)
    with (
        distributed.LocalCluster(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None) as cluster,
        distributed.Client(cluster) as client,
    ):
        remote = engines.sweep(model, sc, s=s, duration=DURATION, controls=push, fit=False, client=client)
    assert remote == local


def test_a_cluster_worker_reads_the_model_from_its_file_as_a_user_would(pendulum, tmp_path):
    # what a worker process elsewhere does: read the model by its recipe (an unsaved copy saved first)
    from pitheorem.engines.verdicts.sweep import _recipe, _remote_outcome

    model, _sc = pendulum
    copy = model.converted(L=100)
    recipe = _recipe(copy)
    assert Path(recipe[0]).is_file()
    assert recipe[2] == tuple(sorted(copy.units.items()))
    lengths = pt.search(copy.system(), scale={"g": 1}).scalings[0]
    here = engines.sweep(copy, lengths, s=(10,), duration=DURATION, controls=push, fit=False, workers=1).rows[0]
    there = _remote_outcome(recipe, lengths, pt.exact.read_scale_factor(10), DURATION, push, {"diagnose": True})
    assert there[:3] == (here.verdict, here.max_deviation, here.yardstick)


def test_bad_requests_name_the_culprit(pendulum):
    model, sc = pendulum
    with pytest.raises(pt.InvalidRequestError, match="EngineModel"):
        engines.sweep("pendulum.xml", sc, s=(1,))
    with pytest.raises(pt.InvalidRequestError, match="s is empty"):
        engines.sweep(model, sc, s=())
    with pytest.raises(pt.InvalidRequestError, match="sequence of scale factors"):
        engines.sweep(model, sc, s="1e-3:1e3:13")
    with pytest.raises(pt.InvalidRequestError, match="workers"):
        engines.sweep(model, sc, s=(1,), workers=0)
    with pytest.raises(pt.InvalidRequestError, match="Client"):
        engines.sweep(model, sc, s=(1,), client="tcp://localhost:8786")
    with pytest.raises(pt.PiTheoremError):
        engines.sweep(model, sc, s=(1, -2))
    with pytest.raises(pt.InvalidRequestError, match="unknown verdict"):
        engines.SweepRow(1, "fine", 0.0, 0.0, None, True, None, (), ())


@pytest.mark.parametrize(
    ("items", "expected"),
    [
        (["1e-3:1e3:13"], [10 ** (-3 + k / 2) for k in range(13)]),
        (["1/4", "4", "1:16:3"], [0.25, 4.0, 1.0, 4.0, 16.0]),
    ],
)
def test_s_ranges_are_evenly_spaced_in_log_s(items, expected):
    got = parse_s_values(items)
    assert [float(v) for v in got] == pytest.approx(expected, rel=1e-12)


def test_decades_of_an_s_range_are_exact():
    got = parse_s_values(["1e-3:1e3:13"])
    assert got[::2] == tuple(Fraction(10) ** k for k in range(-3, 4))
    assert all(type(v) is float for v in got[1::2])


@pytest.mark.parametrize("bad", ["1:2", "1:10:1", "0:10:3", "1:10:x", "-1"])
def test_bad_s_ranges_exit_2(bad, capsys):
    assert main(["sweep", str(PENDULUM), "--scale", "g=1", "--s", bad]) == 2
    assert capsys.readouterr().err.startswith("pitheorem: error:")


def test_the_command_line_sweeps_several_files_into_one_table(tmp_path, capsys):
    other = tmp_path / "still.xml"
    other.write_text(STILL)
    png = tmp_path / "sweep.png"
    code = main(
        ["sweep", str(PENDULUM), str(other), "--scale", "g=1", "--s", "1:4:2", "--duration", "0.1", "--plot", str(png)]
    )
    out = capsys.readouterr().out
    assert code == 0
    grid = out.split("verdicts of every file by scale factor s:\n")[1].splitlines()
    assert grid[0].split() == ["robot", "1", "4"]
    assert grid[1].split() == ["pendulum.xml", "exact", "exact"]
    assert grid[2].split() == ["still.xml", "inconclusive", "inconclusive"]
    for stem in ("pendulum", "still"):
        written = tmp_path / f"sweep_{stem}.png"
        assert written.read_bytes()[:4] == b"\x89PNG"


def test_the_command_line_json_has_the_rows_of_the_python_call(pendulum, capsys):
    model, sc = pendulum
    code = main(["sweep", str(PENDULUM), "--scale", "g=1", "--s", "4", "1e-3", "--duration", "0.1", "--format", "json"])
    doc = json.loads(capsys.readouterr().out)
    sw = engines.sweep(model, sc, s=(4, Fraction(1, 1000)), duration=0.1, controls=engines.smooth_controls(model))
    assert code == 0
    assert [r["verdict"] for r in doc["sweeps"][0]["rows"]] == list(sw.verdicts)
    assert [r["max_deviation"] for r in doc["sweeps"][0]["rows"]] == [r.max_deviation for r in sw.rows]
