"""pitheorem.engines.mjx: MJCF files loaded, scaled, saved and verified in MJX (float32 by default).

Runs only where MJX is installed (``pip install "pitheorem[mjx]"``).  The models are kept tiny (the
pendulum and gymnasium's two-link reacher, 0.2 s each): on the CPU most of the time is JAX compiling the
batch runner, once per model's sizes (``benchmarks/mjx_corpus.py`` runs the rest of gymnasium's files).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")
jax = pytest.importorskip("jax", reason="jax is not installed (pip install 'pitheorem[mjx]')")
pytest.importorskip("mujoco.mjx", reason="mujoco-mjx is not installed (pip install 'pitheorem[mjx]')")

from pitheorem import engines  # noqa: E402
from pitheorem.engines import mjx as mjx_backend  # noqa: E402

PENDULUM = engines.example_path("pendulum.xml")
#: every verification of a model runs this long: the same number of steps and batch, so that JAX compiles
#: the batch runner once per model, not once per test
DURATION = 0.2
gymnasium = sys.modules.get("gymnasium") or pytest.importorskip("gymnasium")
ASSETS = Path(gymnasium.__file__).resolve().parent / "envs" / "mujoco" / "assets"


def time_free(model):
    return pt.search(model.system(), scale={"g": 1}, fixed=("timestep",)).scalings[0]


@pytest.fixture(scope="module")
def pendulum():
    return engines.load(PENDULUM, engine="mjx")


def test_an_mjcf_file_loads_scales_and_saves_in_mjx(pendulum, tmp_path):
    assert pendulum.engine == "mjx"
    assert pendulum._backend.precision == "float32"
    assert pendulum.settings() == {"precision": "float32"}
    stored = pendulum._backend.stored_numbers()
    assert {a.dtype for a in stored.values()} == {np.dtype(np.float32)}
    assert stored["opt.timestep"][0] == np.float32(0.002)
    # the table is MuJoCo's reading of the file
    assert pendulum.parameters == engines.load(PENDULUM).parameters
    scaled = pendulum.scaled(time_free(pendulum), 4)
    assert scaled.engine == "mjx"
    assert type(scaled._backend) is mjx_backend.MjxBackend
    out = scaled.save(tmp_path / "pendulum_4.xml")
    back = engines.load(out, engine="mjx")
    assert back.parameter("g").value == scaled.parameter("g").value == (9.81 * 4,)
    # units: declared at load, recorded in a saved file and read back in MJX as in MuJoCo
    cm = engines.load(PENDULUM, engine="mjx", units={"L": "cm"})
    assert cm.engine == "mjx"
    assert cm.units == {"M": "kg", "L": "cm", "T": "s"}
    mm = cm.converted(L="mm")
    assert mm.engine == "mjx"
    saved = mm.save(tmp_path / "pendulum_mm.xml")
    assert engines.load(saved, engine="mjx").units == engines.load(saved).units == {"M": "kg", "L": "mm", "T": "s"}


def test_float64_on_request_and_jax_left_as_it_was():
    before = jax.config.jax_enable_x64
    model = engines.load(PENDULUM, engine="mjx", precision="float64")
    assert {a.dtype for a in model._backend.stored_numbers().values()} == {np.dtype(np.float64)}
    rows = model._backend.run(10, controls=lambda t: [0.1])
    assert rows.shape == (11, 2)
    assert jax.config.jax_enable_x64 == before
    with pytest.raises(pt.InvalidRequestError, match="precision must be 'float32' or 'float64'"):
        engines.load(PENDULUM, engine="mjx", precision="float16")


# the shipped pendulum, gymnasium's two-link arm and its hopper (margins on its geoms: the copy's static
# body_margin differs); the rest of gymnasium's files run in benchmarks/mjx_corpus.py
@pytest.mark.parametrize("path", [PENDULUM, ASSETS / "reacher.xml", ASSETS / "hopper.xml"],
                         ids=lambda p: Path(p).name)
def test_s4_reproduces_the_original_bit_for_bit_in_float32(path):
    with warnings.catch_warnings():  # gymnasium's custom numerics (frame_skip) have no known dimension
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        model = engines.load(path, engine="mjx")
    if model.parameter("tolerance").value[0]:
        model = model.with_values(tolerance=0)  # the solver's stopping rule is not scale-free (as in MuJoCo)
    sc = time_free(model)
    rep = engines.verify(model, sc, s=4, duration=DURATION, controls=engines.smooth_controls(model))
    assert rep.exact, rep.max_deviation
    assert rep.excited
    assert rep.causes == ()


def test_s10_is_judged_against_the_float32_yardstick(pendulum):
    rep = engines.verify(pendulum, time_free(pendulum), s=10, duration=DURATION, controls=lambda t: [0.1])
    assert rep.similar
    assert not rep.exact  # float32 rounds the numbers times 10, which no proof expects at s = 10
    assert rep.causes == ()  # similar, as in MuJoCo: nothing to look for
    assert 0 < rep.max_deviation < 1e-5
    # the audit names the rounding: MJX keeps the numbers in float32
    audit = engines.audit(pendulum, time_free(pendulum), s=10)
    assert "precision" in {c.kind for c in audit.causes}
    assert all("float32" in c.detail for c in audit.causes if c.kind == "precision")


def test_the_runs_of_a_verification_are_one_vmapped_call(pendulum, monkeypatch):
    runner = mjx_backend._runner(jax, "float32")
    batches = []

    def counting(models, qpos, qvel, rows):
        batches.append(qpos.shape[0])
        return runner(models, qpos, qvel, rows)

    monkeypatch.setitem(mjx_backend._RUNNERS, "float32", counting)
    engines.verify(pendulum, time_free(pendulum), s=4, duration=DURATION, ensemble=3, diagnose=False)
    assert batches == [5]  # original, scaled copy and three twins


def test_twins_move_every_number_by_one_float32_ulp(pendulum):
    before, after = pendulum._backend.stored_numbers(), pendulum._backend.twin(7).stored_numbers()
    moved = 0
    for field, value in before.items():
        ulp = np.abs(after[field].astype(float) - value.astype(float))
        nonzero = value != 0
        if field == "opt.timestep":
            assert np.array_equal(after[field], value)
            continue
        assert np.array_equal(ulp[nonzero], np.abs(np.spacing(value[nonzero], dtype=np.float32).astype(float))
                              ) or np.all(ulp[nonzero] <= np.abs(np.spacing(value[nonzero])).astype(float) * 2)
        assert np.all(after[field][~nonzero] == 0)
        moved += int(nonzero.sum())
    assert moved > 20


UNSUPPORTED = {
    "pgs": ('<mujoco><option solver="PGS"/><worldbody><body><joint type="hinge"/><geom size="0.1" mass="1"/>'
            "</body></worldbody></mujoco>", "option solver", "MJX does not support the PGS solver"),
    "box_cylinder": ('<mujoco><worldbody><geom type="cylinder" size="0.1 0.1"/><body pos="0 0 1"><freejoint/>'
                     '<geom type="box" size="0.1 0.1 0.1"/></body></worldbody></mujoco>', "geom pair",
                     "collisions not implemented"),
}


@pytest.mark.parametrize("case", sorted(UNSUPPORTED))
def test_what_mjx_does_not_support_is_refused_by_name(case, tmp_path):
    text, element, reason = UNSUPPORTED[case]
    path = tmp_path / f"{case}.xml"
    path.write_text(text)
    with pytest.raises(engines.EngineModelError) as caught:
        engines.load(path, engine="mjx")
    assert caught.value.element == element
    assert reason in str(caught.value)
    assert "run the file in 'mujoco'" in str(caught.value)
    assert engines.load(path).engine == "mujoco"  # MuJoCo runs it


def test_audit_and_check_read_mjxs_own_float32_numbers(pendulum):
    sc = time_free(pendulum)
    audit = engines.audit(pendulum, sc, s=4)
    stored = pendulum._backend.stored_numbers()
    assert 0.9 * sum(a.size for a in stored.values()) < audit.compared <= sum(a.size for a in stored.values())
    assert [c.kind for c in audit.causes] == ["solver"]  # the file's tolerance: no scale-free stopping rule
    assert engines.check(pendulum) == engines.check(engines.load(PENDULUM))


def test_a_closed_loop_controller_is_refused(pendulum):
    with pytest.raises(pt.InvalidRequestError, match="MJX runs open loop here"):
        pendulum._backend.run(3, policy=lambda *state: [0.0])


def test_mjx_segment_regularizer_is_measured_as_catalogued():
    # MJX's closest point on a segment adds 1e-6 to the squared length: the point of a segment of length l
    # is off by 1e-6 / l^2 relative, a constant of dimension L^2 (catalogued as mjx_segment_regularizer)
    from mujoco.mjx._src import math as mjx_math

    constant = engines.hidden_constants("mjx", names=["mjx_segment_regularizer"])[0]
    assert str(constant.dimension) == "L^2"
    with jax.enable_x64(True):
        for length, expected in ((1.0, 1.0e-6), (0.1, 1.0e-4)):
            a, b = np.zeros(3), np.array([length, 0.0, 0.0])
            point = np.array([length / 2, 1.0, 0.0])
            closest = float(mjx_math.closest_segment_point(a, b, point)[0])
            off = abs(closest - length / 2) / (length / 2)
            assert off == pytest.approx(expected, rel=1e-3)
            assert off == pytest.approx(constant.default / length**2, rel=1e-3)


@pytest.mark.parametrize("name", ["hopper.xml", "ant.xml"])
def test_a_scaled_copy_is_one_program_with_its_original(name):
    # a copy whose static arrays differ from its original's runs in a call of its own, a program XLA compiles
    # apart, which may round differently: the hopper's copy then parted from its original after one step
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        model = engines.load(ASSETS / name, engine="mjx")
    copy = model.scaled(time_free(model), 4)
    assert not np.array_equal(copy._backend._device.body_margin, model._backend._device.body_margin)
    aligned = mjx_backend._aligned(copy._backend, model._backend)
    structure = jax.tree_util.tree_structure
    assert structure(aligned) == structure(model._backend._device)
    # the arrays MJX traces are the copy's own
    assert np.array_equal(aligned.geom_size, copy._backend._device.geom_size)
    assert not np.array_equal(aligned.geom_size, model._backend._device.geom_size)


def test_the_static_arrays_taken_from_the_original_are_never_read_by_mjx():
    # what _UNREAD_STATIC claims, read from the installed MJX's source: the field is named only where the
    # model's type declares it (and, for a heightfield's radii, where the heightfield collision reads it)
    import mujoco.mjx

    sources = [p for p in Path(mujoco.mjx.__file__).parent.rglob("*.py") if not p.name.endswith("_test.py")]
    for _owner, field, geom_type in mjx_backend._UNREAD_STATIC:
        readers = sorted(p.name for p in sources if field in p.read_text(encoding="utf-8"))
        allowed = {"types.py", "io.py"} | ({"collision_driver.py"} if geom_type else set())
        assert set(readers) <= allowed, (field, readers)
