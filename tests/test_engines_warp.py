"""pitheorem.engines.runners.warp: MJCF files loaded, scaled, saved and verified in MuJoCo Warp, on Warp's CPU.

Runs only where MuJoCo Warp is installed (``pip install "pitheorem[warp]"``).  With an empty kernel cache
this file takes 39 s of CPU, 23 s with a full one (measured alone, 2026-11-28, kernels at -O0; 50 s and
21 s at Warp's default -O2): Warp compiles MJWarp's kernels on the CPU for the first model (the hopper),
and a few more for each model of other sizes (seconds each).  Warp keeps them in its kernel cache, which this module points at
``warp-cache`` in the Python environment (``.venv/warp-cache``, which git ignores): a second run loads
them in seconds.  The models are loaded once per module and every verification runs the same duration,
so that each model's kernels compile once; the whole file runs on one xdist worker (``--dist
loadfile``), sent first (``FIRST`` in ``conftest.py``), so that the compile runs beside the other files.
"""

from __future__ import annotations

import importlib.util
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")
warp = pytest.importorskip("warp", reason="warp-lang is not installed (pip install 'pitheorem[warp]')")
# found, not imported: MJWarp's kernel definitions take seconds to import, twice as long under coverage, and
# the xdist worker that collects this file but runs none of it would pay for them (tests import it: mjw())
if importlib.util.find_spec("mujoco_warp") is None:
    pytest.skip("mujoco-warp is not installed (pip install 'pitheorem[warp]')", allow_module_level=True)

# before Warp initialises: the kernels compiled here are kept in the environment's build folder
warp.config.kernel_cache_dir = str(Path(sys.prefix) / "warp-cache")
warp.config.log_level = warp.LOG_WARNING  # not a line per kernel module loaded
# LLVM's -O0 for the kernels (Warp's default on the CPU is -O2): a cold compile takes a fifth less CPU (50 s ->
# 39 s for this file alone), a warm run about as long.  What is tested holds at any level: a copy and its
# original run the same compiled kernels, and float32 against C MuJoCo's float64 is rounding either way.
warp.config.optimization_level = 0

from pitheorem import engines  # noqa: E402
from pitheorem.engines.runners import warp as warp_runner  # noqa: E402
from tests.conftest import untraced  # noqa: E402

PENDULUM = engines.example_path("pendulum.xml")
#: every verification runs this long, so that the kernels compile once per model
DURATION = 0.2
gymnasium = sys.modules.get("gymnasium") or pytest.importorskip("gymnasium")
ASSETS = Path(gymnasium.__file__).resolve().parent / "envs" / "mujoco" / "assets"


def time_free(model):
    return pt.search(model.system(), scale={"g": 1}, fixed=("timestep",)).scalings[0]


def load(path):
    with warnings.catch_warnings():  # gymnasium's custom numerics (frame_skip) have no known dimension
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        model = engines.load(path, engine="warp", device="cpu")
    if model.parameter("tolerance").value[0]:
        model = model.with_values(tolerance=0)  # the solver's stopping rule is not scale-free (as in MuJoCo)
    return model


def mjw():
    """MuJoCo Warp's package, imported on first use."""
    import mujoco_warp

    return mujoco_warp


@pytest.fixture(scope="module", autouse=True)
def _mjwarps_step_untraced():
    """MJWarp's step without coverage's tracing (:func:`tests.conftest.untraced`): this file's runs 2.5 times
    faster under ``make coverage``, every line of pitheorem still measured."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(mjw(), "step", untraced(mjw().step))
        yield


@pytest.fixture(scope="module")
def pendulum():
    return engines.load(PENDULUM, engine="warp", device="cpu")


@pytest.fixture(scope="module")
def hopper():
    return load(ASSETS / "hopper.xml")


def test_an_mjcf_file_loads_scales_and_saves_in_warp(pendulum, tmp_path):
    assert pendulum.engine == "warp"
    assert pendulum.runner.precision == "float32"
    assert pendulum.settings() == {"precision": "float32", "device": "cpu"}
    stored = pendulum.runner.stored_numbers()
    assert {a.dtype for a in stored.values()} == {np.dtype(np.float32)}
    assert stored["opt.timestep"][0] == np.float32(0.002)
    assert stored["body_mass"].shape == pendulum.runner.mjcf.mjmodel.body_mass.shape  # one world, MuJoCo's layout
    assert pendulum.parameters == engines.load(PENDULUM).parameters  # the table is MuJoCo's reading of the file
    scaled = pendulum.scaled(time_free(pendulum), 4)
    assert scaled.engine == "warp"
    assert type(scaled.runner) is warp_runner.WarpRunner
    assert scaled.runner.stored_numbers()["opt.gravity"][2] == np.float32(-9.81 * 4)
    out = scaled.save(tmp_path / "pendulum_4.xml")
    back = engines.load(out, engine="warp", device="cpu")
    assert back.parameter("g").value == scaled.parameter("g").value == (9.81 * 4,)
    cm = engines.load(PENDULUM, engine="warp", device="cpu", units={"L": "cm"})
    mm = cm.converted(L="mm")
    assert (cm.engine, mm.engine) == ("warp", "warp")
    saved = mm.save(tmp_path / "pendulum_mm.xml")
    assert engines.load(saved, engine="warp", device="cpu").units == {"M": "kg", "L": "mm", "T": "s"}


def test_warp_is_listed_with_its_extra_and_precision():
    assert "warp" in engines.backends()
    from pitheorem.engines.registry import registered

    line = registered("warp")
    assert (line.extra, line.base, line.precision, line.formats) == ("warp", "mujoco", "float32", ("mjcf", "urdf"))


# gymnasium's hopper (contacts, margins, a free-floating base), inverted pendulum (a slider and a hinge)
# and double pendulum; the shipped pendulum runs in the tests below
@pytest.mark.parametrize(
    "name", ["hopper.xml", "inverted_pendulum.xml", "inverted_double_pendulum.xml"], ids=lambda n: n
)
def test_s4_reproduces_the_original_bit_for_bit_in_float32(name, hopper):
    model = hopper if name == "hopper.xml" else load(ASSETS / name)
    rep = engines.verify(model, time_free(model), s=4, duration=DURATION, controls=engines.smooth_controls(model))
    assert rep.exact, rep.max_deviation
    assert rep.excited
    assert rep.causes == ()
    assert not rep.inconclusive  # the negative controls, run as worlds beside it, are caught


def test_the_pendulum_is_exact_at_s4_and_judged_against_the_float32_yardstick_at_s10(pendulum):
    sc = time_free(pendulum)
    proof = engines.verify(pendulum, sc, s=4, duration=DURATION, controls=lambda t: [0.1])
    assert proof.exact
    assert proof.excited
    rep = engines.verify(pendulum, sc, s=10, duration=DURATION, controls=lambda t: [0.1])
    assert rep.similar
    assert not rep.exact  # float32 rounds the numbers times 10
    assert rep.causes == ()
    assert 0 < rep.max_deviation < 1e-5
    audit = engines.audit(pendulum, sc, s=10)  # the audit names the rounding: MJWarp keeps float32
    assert "precision" in {c.kind for c in audit.causes}
    assert all("float32" in c.detail for c in audit.causes if c.kind == "precision")


def test_the_hopper_at_s10_is_similar_against_the_float32_yardstick(hopper):
    rep = engines.verify(hopper, time_free(hopper), s=10, duration=DURATION, controls=engines.smooth_controls(hopper))
    assert rep.similar, rep.max_deviation
    assert not rep.exact
    assert rep.causes == ()


def test_the_runs_of_a_verification_are_the_worlds_of_one_call(pendulum, monkeypatch):
    stepped = {}  # each data stepped, kept (make_data is also called for one world, to read its first rows)
    step = mjw().step

    def counting(m, d):
        stepped.setdefault(id(d), d)
        return step(m, d)

    monkeypatch.setattr(mjw(), "step", counting)
    engines.verify(pendulum, time_free(pendulum), s=4, duration=DURATION, ensemble=3, diagnose=False)
    worlds = [d.nworld for d in stepped.values()]
    # the original, its scaled copy, three twins and each group's first negative control (gravity off by 1e-4,
    # the masses doubled where something else carries mass), each world with its own gravity, masses and
    # sizes: one call; gravity's larger errors, where 1e-4 passes unnoticed, a second
    from pitheorem.engines.verdicts.strength import control_factors

    assert worlds[0] == 5 + len({g for g, _e, _f in control_factors(pendulum)})
    assert len(worlds) <= 2


def test_a_world_runs_as_it_runs_alone_and_runs_repeat_bit_for_bit(hopper):
    # Warp's CPU device runs a kernel's threads one after another: a run is deterministic
    u = engines.smooth_controls(hopper)
    n = 50
    alone = hopper.runner.run(n, controls=u)
    again = hopper.runner.run(n, controls=u)
    copy = hopper.scaled(time_free(hopper), 4).runner
    runs = hopper.runner.run_many(n, [(copy, None, False, None), (hopper.runner, u, False, None)])
    assert np.array_equal(alone, again)
    assert np.array_equal(runs[1], alone)
    assert not np.array_equal(runs[0], alone)


def test_warp_agrees_with_c_mujoco_to_float32s_rounding(pendulum, hopper):
    # measured over 100 steps: 1.0e-6 (pendulum), 3.8e-6 (hopper), in the coordinates' own units
    for model, path in ((pendulum, PENDULUM), (hopper, ASSETS / "hopper.xml")):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", engines.UnscalableModelWarning)
            in_mujoco = engines.load(path).with_values(tolerance=model.parameter("tolerance").value[0])
        u = engines.smooth_controls(model)
        worst = np.max(np.abs(model.runner.run(100, controls=u) - in_mujoco.runner.run(100, controls=u)))
        assert 0 < worst < 1e-4, worst  # float32 against float64: never bit for bit, never far


def test_twins_move_every_number_by_one_float32_ulp(pendulum):
    before, after = pendulum.runner.stored_numbers(), pendulum.runner.twin(7).stored_numbers()
    assert before.keys() == after.keys()
    moved = 0
    for field, value in before.items():
        if field == "opt.timestep":
            assert np.array_equal(after[field], value)
            continue
        nonzero = value != 0
        step = np.abs(after[field][nonzero].astype(float) - value[nonzero].astype(float))
        assert np.array_equal(step, np.abs(np.spacing(value[nonzero])).astype(float)) or np.all(
            step <= 2 * np.abs(np.spacing(value[nonzero])).astype(float)
        ), field
        assert np.all(step > 0), field
        assert np.all(after[field][~nonzero] == 0)
        moved += int(nonzero.sum())
    assert moved > 20


def test_a_run_starts_from_a_given_state_nudged_by_one_float32_ulp(pendulum):
    m = pendulum.runner.mjcf.mjmodel
    first = np.array([0.3] + [0.0] * (m.nv + m.na))
    rows = pendulum.runner.run(5, initial=first)
    assert rows[0, 0] == np.float32(0.3)
    nudged = pendulum.runner.run(5, initial=first, nudge=True)
    assert nudged[0, 0] == np.float32(0.3) + np.spacing(np.float32(1))  # below 1: up by the ulp of 1
    assert nudged[0, 1] == np.spacing(np.float32(1))  # a zero velocity nudged by the ulp of 1


UNSUPPORTED = {
    "pgs": (
        '<mujoco><option solver="PGS"/><worldbody><body><joint type="hinge"/><geom size="0.1" mass="1"/>'
        "</body></worldbody></mujoco>",
        "option solver",
        "mjSOL_PGS",
    ),
    "override": (
        '<mujoco><option><flag override="enable"/></option><worldbody><body><joint type="hinge"/>'
        '<geom size="0.1" mass="1"/></body></worldbody></mujoco>',
        "option flag",
        "mjENBL_OVERRIDE",
    ),
}


@pytest.mark.parametrize("case", sorted(UNSUPPORTED))
def test_what_warp_does_not_support_is_refused_by_name(case, tmp_path):
    text, element, reason = UNSUPPORTED[case]
    path = tmp_path / f"{case}.xml"
    path.write_text(text)
    with pytest.raises(engines.EngineModelError) as caught:
        engines.load(path, engine="warp", device="cpu")
    assert caught.value.element == element
    assert reason in str(caught.value)
    assert "MuJoCo Warp does not support" in str(caught.value)
    assert "run the file in 'mujoco'" in str(caught.value)
    assert engines.load(path).engine == "mujoco"  # MuJoCo runs it


def test_a_device_warp_lacks_and_a_closed_loop_are_refused(pendulum):
    with pytest.raises(pt.InvalidRequestError, match="Warp has no device 'tpu'"):
        engines.load(PENDULUM, engine="warp", device="tpu")
    with pytest.raises(pt.InvalidRequestError, match="MuJoCo Warp runs open loop here"):
        pendulum.runner.run(3, policy=lambda *state: [0.0])
    with pytest.raises(pt.InvalidRequestError, match="takes no option 'precision'"):
        engines.load(PENDULUM, engine="warp", precision="float64")


def test_a_file_mujoco_refuses_is_refused_with_mujocos_reason(tmp_path):
    path = tmp_path / "bad.xml"
    path.write_text('<mujoco><worldbody><body><joint type="hinge"/><geom size="-1"/></body></worldbody></mujoco>')
    with pytest.raises(engines.EngineModelError):
        engines.load(path, engine="warp", device="cpu")


def test_audit_and_check_read_warps_own_float32_numbers(pendulum):
    audit = engines.audit(pendulum, time_free(pendulum), s=4)
    stored = pendulum.runner.stored_numbers()
    assert 0.5 * sum(a.size for a in stored.values()) < audit.compared <= sum(a.size for a in stored.values())
    assert engines.check(pendulum) == engines.check(engines.load(PENDULUM))


@warp.kernel
def _product(x: warp.array(dtype=float), y: warp.array(dtype=float), z: warp.array(dtype=float)):
    i = warp.tid()
    z[i] = x[i] * y[i]


def test_numbers_beyond_float32s_range_are_stored_subnormal_or_infinite_and_checked(tmp_path):
    with warp.ScopedDevice("cpu"):
        x = warp.array(np.array([1e-40, 2e-38, 2e38], np.float32), dtype=float)
        y = warp.array(np.array([1, 0.5, 2], np.float32), dtype=float)
        z = warp.zeros(3, dtype=float)
        warp.launch(_product, 3, inputs=[x, y, z])
    product = z.numpy()
    assert product[0] == np.float32(1e-40)  # kept subnormal, not flushed to zero
    assert product[1] == np.float32(1e-38)
    assert np.isinf(product[2])
    text = PENDULUM.read_text()
    for damping, threshold in (("1e-40", "below warp_float32_min_normal"), ("1e39", "above warp_float32_max")):
        path = tmp_path / f"pendulum_{damping}.xml"
        path.write_text(text.replace('damping="0.05"', f'damping="{damping}"'))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # NumPy's overflow in the cast to float32
            model = engines.load(path, engine="warp", device="cpu")
        held = model.runner.stored_numbers()["dof_damping"][0]
        assert (0 < held < np.finfo(np.float32).tiny) if damping == "1e-40" else np.isinf(held)
        said = [c.detail for c in engines.check(model) if c.element.endswith("damping")]
        assert any(threshold in d for d in said), said
        assert not any("warp_" in c.detail for c in engines.check(engines.load(path)))  # MuJoCo's float64


def test_the_catalogue_has_warps_constants_and_thresholds():
    names = [c.name for c in engines.hidden_constants("warp")]
    assert names == ["warp_parallel_segments_regularizer", "warp_box_box_separation_slack"]
    assert all(c.dimension == pt.Dimension.parse("1") for c in engines.hidden_constants("warp"))
    from pitheorem.engines.thresholds import thresholds

    own = [t.name for t in thresholds("warp")][len(thresholds("mujoco")) :]
    assert own == ["warp_float32_min_normal", "warp_float32_max"]


def test_each_world_starts_with_its_own_models_mocap_bodies(tmp_path):
    path = tmp_path / "mocap.xml"
    path.write_text(
        '<mujoco><option gravity="0 0 -9.81"/><worldbody><body name="target" mocap="true" pos="0.3 0 1">'
        '<site name="there"/></body><body name="bob" pos="0 0 1"><joint type="slide" axis="1 0 0"/>'
        '<geom size="0.05" mass="1" contype="0" conaffinity="0"/><site name="here"/></body></worldbody>'
        '<equality><connect site1="here" site2="there"/></equality></mujoco>'
    )
    model = engines.load(path, engine="warp", device="cpu")
    rep = engines.verify(model, time_free(model), s=4, duration=0.05)
    assert rep.exact  # the copy's mocap body is at its own, scaled, place: the bob is pulled alike
    rows = model.runner.run(25)
    assert rows[-1, 0] > 0.01  # the bob moves toward the mocap target at x = 0.3


#: a free box dropped onto a table fixed to the world, off the origin: the table's pose is one of what MJWarp's
#: make_data computes once (geoms fixed to the world are never moved by a step), and a scaled copy's is elsewhere
TABLE = (
    '<mujoco>{asset}<option gravity="0 0 -9.81"/><worldbody>{table}'
    '<body pos="0.1 0 1.101"><freejoint/><geom type="box" size="0.1 0.1 0.1" mass="1"/></body>'
    "</worldbody></mujoco>"
)
#: the table as a box (the original and its copy are two worlds of one call), or a mesh (a scaled mesh's
#: vertices are no per-world array: the copy runs in a call of its own)
TABLES = {
    "box": ("", '<geom type="box" pos="0 0 0.5" size="0.5 0.5 0.5"/>'),
    "mesh": (
        '<asset><mesh name="slab" vertex="-.5 -.5 -.5  .5 -.5 -.5  -.5 .5 -.5  .5 .5 -.5'
        '  -.5 -.5 .5  .5 -.5 .5  -.5 .5 .5  .5 .5 .5"/></asset>',
        '<geom type="mesh" mesh="slab" pos="0 0 0.5"/>',
    ),
}


@pytest.mark.parametrize("table", sorted(TABLES))
def test_each_world_runs_from_its_own_models_fixed_geoms_as_it_runs_alone(table, tmp_path):
    asset, geom = TABLES[table]
    path = tmp_path / "table.xml"
    path.write_text(TABLE.format(asset=asset, table=geom))
    model = load(path)
    original, copy = model.runner, model.scaled(time_free(model), 4).runner
    n = 50
    alone = [original.run(n), copy.run(n)]  # each model the one world of its call: make_data of its own
    assert abs(alone[0][-1, 2] - 1.1) < 0.005  # it rests on the table top (without it, it would fall to 1.05)
    for jobs, runs in (
        ([original, copy], alone),
        ([copy, original], alone[::-1]),
    ):
        batch = original.run_many(n, [(runner, None, False, None) for runner in jobs])
        for world, run in zip(batch, runs, strict=True):
            assert np.array_equal(world, run)
    if table == "mesh":  # as Meta-World's block was (a mesh table: the copy in a call of its own), the verdict
        rep = engines.verify(model, time_free(model), s=4, duration=DURATION, ensemble=1, diagnose=False)
        assert rep.exact, rep.max_deviation


def test_a_twins_world_starts_with_its_fixed_geoms_where_its_moved_numbers_put_them(tmp_path):
    """A twin moves every number by one float32 unit, the fixed table's position too; the table's pose in its
    world (computed once, by make_data, from MuJoCo's model) must be the moved one, or the yardstick's twin
    would run against the original's table."""
    path = tmp_path / "table.xml"
    path.write_text(TABLE.format(asset="", table=TABLES["box"][1]))
    original = load(path).runner
    twins = [original.twin(seed) for seed in (1, 2)]
    with warp.ScopedDevice("cpu"):
        poses = warp_runner._data([original, *twins]).geom_xpos.numpy()
    # the table is the world body's geom 0: its pose is its stored position, as each runner holds it
    for world, runner in enumerate([original, *twins]):
        assert np.array_equal(poses[world, 0], runner.stored_numbers()["geom_pos"][0])
    assert not np.array_equal(poses[1, 0], poses[0, 0])
    # what MJWarp holds otherwise than MuJoCo (the solver's tolerance, raised to a float32 floor) is its own:
    # the MuJoCo model a twin's world starts from keeps MuJoCo's
    assert original.stored_numbers()["opt.tolerance"][0] != np.float32(original.mjcf.mjmodel.opt.tolerance)
    assert all(t._start_mjmodel.opt.tolerance == original.mjcf.mjmodel.opt.tolerance for t in twins)


def test_a_urdf_runs_in_warp_through_mujocos_urdf_reader():
    path = engines.example_path("hinged_rod.urdf")
    model = engines.load(path, engine="warp", device="cpu")
    assert model.engine == "warp"
    assert model.parameters == engines.load(path, engine="mujoco").parameters  # MuJoCo's reading of the URDF
    rep = engines.verify(model, time_free(model), s=4, duration=DURATION)
    assert rep.exact, rep.max_deviation


def test_the_weld_is_named_by_its_counter_run_and_holds_in_plain_mujoco_warp():
    """MuJoCo Warp switches equality constraints off as MuJoCo does, so a counter-run names the weld of a box
    welded to a turned pose (its rotational rows' weight), and it alone restores the run.  By hand in MuJoCo Warp
    itself (``put_model``, ``make_data``, ``step``): with the weld inactive in both compiled models, the copy is
    the original's bits mapped back; as written, it is not."""
    import copy as copy_module

    model = load(Path(__file__).resolve().parent / "data" / "engines" / "welded_turn.xml")
    sc = time_free(model)
    rep = engines.verify(model, sc, 4, duration=DURATION)
    assert [(c.kind, c.element, c.restores) for c in rep.causes] == [("solver", "equality #0", True)]
    assert "with it inactive in both runs they are equal bit for bit" in rep.causes[0].detail
    scaled = model.scaled(sc, 4)
    back = np.array([4.0 ** float(sc.exponent_of(d)) for d in model.runner.coordinate_dimensions()[1]])

    def run(compiled, weld: bool):
        m = copy_module.copy(compiled)
        m.eq_active0[0] = int(weld)
        with warp.ScopedDevice("cpu"):
            device, data = mjw().put_model(m), mjw().make_data(m)
            rows = []
            for _ in range(50):
                mjw().step(device, data)
                rows.append(np.concatenate([data.qpos.numpy()[0], data.qvel.numpy()[0]]).astype(float))
        return np.array(rows)

    for weld, same in ((True, False), (False, True)):
        original = run(model.runner.mjcf.mjmodel, weld)
        assert np.array_equal(original, run(scaled.runner.mjcf.mjmodel, weld) / back) is same
