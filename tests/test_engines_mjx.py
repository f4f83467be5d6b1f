"""pitheorem.engines.runners.mjx: MJCF files loaded, scaled, saved and verified in MJX (float32 by default).

Runs only where MJX is installed (``pip install "pitheorem[mjx]"``).  The runs are kept short (the
pendulum and a small planar hopper, 0.2 s each): on the CPU most of the time is JAX compiling the
batch runner, once per model's sizes (``benchmarks/mjx_corpus.py`` runs the rest of gymnasium's files).
"""

from __future__ import annotations

import importlib.util
import re
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt

pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")
# found, not imported: importing MJX (JAX, and Warp's kernel definitions) takes seconds, twice as long under
# coverage, and the xdist worker that collects this file but runs none of it would pay for it
for _module in ("jax", "mujoco.mjx"):
    if importlib.util.find_spec(_module) is None:
        pytest.skip(f"{_module} is not installed (pip install 'pitheorem[mjx]')", allow_module_level=True)

from pitheorem import engines  # noqa: E402
from pitheorem.engines.runners import mjx as mjx_backend  # noqa: E402

pytestmark = pytest.mark.usefixtures("mjx_untraced")

PENDULUM = engines.example_path("pendulum.xml")
#: every verification of a model runs this long: the same number of steps and batch, so that JAX compiles
#: the batch runner once per model, not once per test
DURATION = 0.2
gymnasium = sys.modules.get("gymnasium") or pytest.importorskip("gymnasium")
ASSETS = Path(gymnasium.__file__).resolve().parent / "envs" / "mujoco" / "assets"
MARGINS = Path(__file__).parent / "data" / "engines" / "margins_on_floor.xml"


def time_free(model):
    return pt.search(model.system(), scale={"g": 1}, fixed=("timestep",)).scalings[0]


@pytest.fixture(scope="module")
def pendulum():
    return engines.load(PENDULUM, engine="mjx")


def test_an_mjcf_file_loads_scales_and_saves_in_mjx(pendulum, tmp_path):
    assert pendulum.engine == "mjx"
    assert pendulum.runner.precision == "float32"
    assert pendulum.settings() == {"precision": "float32"}
    stored = pendulum.runner.stored_numbers()
    assert {a.dtype for a in stored.values()} == {np.dtype(np.float32)}
    assert stored["opt.timestep"][0] == np.float32(0.002)
    # the table is MuJoCo's reading of the file
    assert pendulum.parameters == engines.load(PENDULUM).parameters
    scaled = pendulum.scaled(time_free(pendulum), 4)
    assert scaled.engine == "mjx"
    assert type(scaled.runner) is mjx_backend.MjxRunner
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
    import jax

    before = jax.config.jax_enable_x64
    model = engines.load(PENDULUM, engine="mjx", precision="float64")
    assert {a.dtype for a in model.runner.stored_numbers().values()} == {np.dtype(np.float64)}
    rows = model.runner.run(10, controls=lambda t: [0.1])
    assert rows.shape == (11, 2)
    assert jax.config.jax_enable_x64 == before
    with pytest.raises(pt.InvalidRequestError, match="precision must be 'float32' or 'float64'"):
        engines.load(PENDULUM, engine="mjx", precision="float16")


# the shipped pendulum, and a small planar hopper with gymnasium's hopper's ingredients (capsules landing on a
# plane, margins on its geoms: the copy's static body_margin differs), which XLA compiles in a third of the
# hopper's time; gymnasium's hopper and the rest of its files run in benchmarks/mjx_corpus.py
@pytest.mark.parametrize("path", [PENDULUM, MARGINS], ids=lambda p: Path(p).name)
def test_s4_reproduces_the_original_bit_for_bit_in_float32(path):
    model = engines.load(path, engine="mjx")
    if model.parameter("tolerance").value[0]:
        model = model.with_values(tolerance=0)  # the solver's stopping rule is not scale-free (as in MuJoCo)
    sc = time_free(model)
    rep = engines.verify(model, sc, s=4, duration=DURATION, controls=engines.smooth_controls(model))
    assert rep.exact, rep.max_deviation
    assert rep.excited
    assert rep.causes == ()


def test_the_small_hopper_lands_and_its_copy_has_other_static_margins():
    # what makes it a test of contacts and of the batch's static arrays: C MuJoCo finds contacts within the
    # verification's duration, and the copy's body_margin (static in MJX) is not the original's
    import mujoco

    model = engines.load(MARGINS, engine="mjx")
    m = mujoco.MjModel.from_xml_path(str(MARGINS))
    d = mujoco.MjData(m)
    contacts = []
    for _ in range(round(DURATION / m.opt.timestep)):
        mujoco.mj_step(m, d)
        contacts.append(d.ncon)
    assert contacts[0] == 0  # it starts in the air
    assert max(contacts) > 0  # and lands
    copy = model.scaled(time_free(model), 4)
    assert not np.array_equal(copy.runner.device_model().body_margin, model.runner.device_model().body_margin)


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
    import jax

    runner = mjx_backend._runner(jax, "float32")
    batches = []

    def counting(models, qpos, qvel, rows):
        batches.append(qpos.shape[0])
        return runner(models, qpos, qvel, rows)

    monkeypatch.setitem(mjx_backend._RUNNERS, "float32", counting)
    engines.verify(pendulum, time_free(pendulum), s=4, duration=DURATION, ensemble=3, diagnose=False)
    # original, scaled copy, three twins and each group's first negative control: one call (gravity's larger
    # errors, where 1e-4 passes unnoticed, a second)
    from pitheorem.engines.verdicts.strength import control_factors

    assert batches[0] == 5 + len({g for g, _e, _f in control_factors(pendulum)})
    assert len(batches) <= 2


def test_twins_move_every_number_by_one_float32_ulp(pendulum):
    before, after = pendulum.runner.stored_numbers(), pendulum.runner.twin(7).stored_numbers()
    moved = 0
    for field, value in before.items():
        ulp = np.abs(after[field].astype(float) - value.astype(float))
        nonzero = value != 0
        if field == "opt.timestep":
            assert np.array_equal(after[field], value)
            continue
        assert np.array_equal(
            ulp[nonzero], np.abs(np.spacing(value[nonzero], dtype=np.float32).astype(float))
        ) or np.all(ulp[nonzero] <= np.abs(np.spacing(value[nonzero])).astype(float) * 2)
        assert np.all(after[field][~nonzero] == 0)
        moved += int(nonzero.sum())
    assert moved > 20


UNSUPPORTED = {
    "pgs": (
        '<mujoco><option solver="PGS"/><worldbody><body><joint type="hinge"/><geom size="0.1" mass="1"/>'
        "</body></worldbody></mujoco>",
        "option solver",
        "MJX does not support the PGS solver",
    ),
    "box_cylinder": (
        '<mujoco><worldbody><geom type="cylinder" size="0.1 0.1"/><body pos="0 0 1"><freejoint/>'
        '<geom type="box" size="0.1 0.1 0.1"/></body></worldbody></mujoco>',
        "geom pair",
        "collisions not implemented",
    ),
    # MJX's own wording after "MJX does not support": the culprit is the element it names, or "model"
    "implicit": (
        '<mujoco><option integrator="implicit"/><worldbody><body><joint type="hinge"/>'
        '<geom size="0.1" mass="1"/></body></worldbody></mujoco>',
        "option",
        "mjINT_IMPLICIT",
    ),
    "contact_sensor": (
        '<mujoco><worldbody><body name="b"><joint type="hinge"/><geom size="0.1" mass="1"/>'
        '</body></worldbody><sensor><contact body1="b"/></sensor></mujoco>',
        "sensor",
        "Contact sensor with body matching",
    ),
    "fluid_implicitfast": (
        '<mujoco><option integrator="implicitfast" density="1.2"/><worldbody><body>'
        '<joint type="hinge"/><geom size="0.1" mass="1"/></body></worldbody></mujoco>',
        "model",
        "fluid drag",
    ),
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
    stored = pendulum.runner.stored_numbers()
    assert 0.9 * sum(a.size for a in stored.values()) < audit.compared <= sum(a.size for a in stored.values())
    assert [c.kind for c in audit.causes] == ["solver"]  # the file's tolerance: no scale-free stopping rule
    assert engines.check(pendulum) == engines.check(engines.load(PENDULUM))


def test_a_closed_loop_controller_is_refused(pendulum):
    with pytest.raises(pt.InvalidRequestError, match="MJX runs open loop here"):
        pendulum.runner.run(3, policy=lambda *state: [0.0])


def test_mjx_segment_regularizer_is_measured_as_catalogued():
    import jax

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


# -- MJX's own thresholds, measured (pitheorem.engines.thresholds: the [thresholds.mjx] tables) ----------


def test_capsule_regularizer_passes_float32s_resolution_below_its_threshold():
    import jax

    # MJX's closest point on a capsule's segment, in float32, against the point without the 1e-6 (numpy, float64
    # from the same float32 inputs): off by about 1e-6 / (2 h^2) of h, above float32's rounding below h = 2
    from mujoco.mjx._src import math as mjx_math

    (t,) = engines.thresholds.thresholds("mjx", names=["mjx_segment_regularizer_float32"])
    ulp = 2.0**-23
    assert t.value == pytest.approx((1e-6 / (2 * ulp)) ** 0.5, rel=0.05)  # where 1e-6 / (2 h^2) is one ulp
    closest = jax.jit(mjx_math.closest_segment_point)
    rng = np.random.default_rng(0)

    def worst(h):
        a, b = np.array([0, 0, -h], np.float32), np.array([0, 0, h], np.float32)
        out = 0.0
        for _ in range(100):
            p = np.array([rng.uniform(0.5, 2) * h, 0, rng.uniform(-h, h)], np.float32)
            ab, ap = b.astype(float) - a, p.astype(float) - a
            exact = a[2] + np.clip(ap @ ab / (ab @ ab), 0, 1) * ab[2]
            out = max(out, abs(float(closest(a, b, p)[2]) - exact) / h)
        return out

    for h in (0.01, 0.1, 1.0):  # below: the regularizer's shift, far above float32's rounding
        assert worst(h) > 2.5 * ulp
        assert worst(h) == pytest.approx(1e-6 / (2 * h * h), rel=0.6)
    for h in (3.0, 5.0):  # above: float32's rounding alone
        assert worst(h) <= 2 * ulp


def test_mjx_takes_cylinders_shorter_than_2_mm_as_lying_on_a_plane():
    from types import SimpleNamespace

    import jax
    from mujoco.mjx._src.collision_primitive import plane_cylinder

    (t,) = engines.thresholds.thresholds("mjx", names=["mjx_cylinder_plane_parallel"])

    def contacts(h):  # a cylinder of radius 0.01 standing on the plane z = 0
        m = SimpleNamespace(geom_size=np.array([[0, 0, 0], [0.01, h, 0]], np.float32))
        d = SimpleNamespace(
            geom_xpos=np.array([[0, 0, 0], [0, 0, h]], np.float32), geom_xmat=np.array([np.eye(3)] * 2, np.float32)
        )
        dist, _, _ = plane_cylinder(m, d, None, jax.numpy.array([[0, 1]]))
        return np.asarray(dist, float)

    assert np.allclose(contacts(1.1 * t.value), 0, atol=1e-7)  # three points on the lower disk
    for h in (0.9 * t.value, 0.1 * t.value):  # one point on the upper disk, 2 h from the plane
        assert sorted(contacts(h)) == pytest.approx([0, 0, 2 * h], abs=1e-9)


def test_numbers_beyond_float32s_range_are_flushed_or_infinite_and_checked(tmp_path):
    import jax

    (low, high) = engines.thresholds.thresholds("mjx", names=["mjx_float32_min_normal", "mjx_float32_max"])
    assert low.value == float(np.finfo(np.float32).tiny)
    assert high.value == float(np.finfo(np.float32).max)
    product = jax.jit(lambda x, y: x * y)
    assert float(product(np.float32(1e-40), np.float32(1))) == 0  # XLA flushes subnormal results to 0
    assert float(product(np.float32(2e-38), np.float32(0.5))) == 0
    assert float(product(np.float32(2e38), np.float32(2))) == np.inf
    path = tmp_path / "extreme.xml"
    path.write_text(
        '<mujoco><worldbody><body><joint name="a" type="hinge" damping="1e-40"/><geom size="0.1"/>'
        '</body><body pos="1 0 0"><joint name="b" type="hinge" damping="1e39"/><geom size="0.1"/>'
        "</body></worldbody></mujoco>"
    )
    with pytest.warns(RuntimeWarning, match="overflow encountered in cast"):  # JAX, putting 1e39 in float32
        model = engines.load(path, engine="mjx")
    damping = model.runner.stored_numbers()["dof_damping"]
    assert 0 < abs(damping[0]) < np.finfo(np.float32).tiny
    assert damping[1] == np.inf
    said = {c.element: c.detail for c in engines.check(model)}
    assert "below mjx_float32_min_normal" in said["joint_a_damping"]
    assert "above mjx_float32_max" in said["joint_b_damping"]
    # in float64, and in MuJoCo, float32's range is no threshold: nor in an audit
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    with warnings.catch_warnings():  # the scaled copy's 1e39 overflows float32 again
        warnings.simplefilter("ignore", RuntimeWarning)
        assert "mjx_float32_max" in " ".join(c.detail for c in engines.audit(model, lengths, 4).causes)
    for other in (engines.load(path, engine="mjx", precision="float64"), engines.load(path)):
        assert not any("float32" in c.detail for c in engines.check(other))
        assert not any("mjx_float32" in c.detail for c in engines.audit(other, lengths, 4).causes)


def test_a_shrunk_hopper_is_flagged_for_mjx_and_fitted_units_clear_it(tmp_path):
    from pitheorem.engines.cli import check_engine_model
    from pitheorem.engines.fitting import fitted_units

    model = engines.load(ASSETS / "hopper.xml", engine="mjx")
    lengths = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    shrunk = model.scaled(lengths, 1 / 16)
    in_mjx = {c.element: c.detail for c in engines.check(shrunk)}
    in_mujoco = {c.element: c.detail for c in engines.check(shrunk, "mujoco")}
    own = {e for e, d in in_mjx.items() if "mjx_" in d}
    # the four capsules that meet another capsule (torso, thigh, leg, foot): MJX's regularizer, not MuJoCo's
    assert own == {f"geom_{g}_geom_half_length" for g in ("torso", "thigh", "leg", "foot")}
    assert set(in_mujoco) == set(in_mjx) - own
    foot = in_mjx["geom_foot_geom_half_length"]
    need = float(re.search(r"dimension L by (\S+) clears it", foot).group(1))
    assert need == pytest.approx(2 * 2.0 / (0.195 / 16), rel=1e-3)  # a factor 2 clear of h = 2 (said in 3 digits)
    # the command line says the same
    saved = shrunk.save(tmp_path / "hopper_16.xml")
    text, clean = check_engine_model(str(saved), engine="mjx")
    assert not clean
    assert "mjx_segment_regularizer_float32" in text
    assert check_engine_model(str(saved))[1] is False  # MuJoCo: the rolling friction below mjMINMU
    # fit_units(engine="mjx") chooses units clear of every threshold of MJX and of float32's comfortable range
    fit = pt.fit_units(shrunk, engine="mjx")
    assert fit.feasible
    units = fitted_units(shrunk, fit)
    fitted = shrunk.converted(**units)
    assert engines.check(fitted) == ()
    assert engines.check(fitted, "mujoco") == ()
    # shrunk ten times, the capsules need lengths by 1026 (h = 20), and float32's comfortable range (1e-6 to
    # 1e6) bounds the densities (M L^-3) from below and the armatures (M L^2) from above: with factors that are
    # powers of ten only lengths by 1e4 and masses by exactly 1 fit, and rounding puts the foot just outside;
    # powers of two fit
    tenth = model.scaled(lengths, 0.1)
    assert {c.element for c in engines.check(tenth) if "mjx_" in c.detail} == own
    stuck = pt.fit_units(tenth, engine="mjx")
    assert not stuck.feasible
    assert {b.name for b in stuck.conflict} == {
        "geom_foot_geom_density",
        "joint_foot_joint_armature",
        "geom_foot_geom_half_length",
    }
    fit = pt.fit_units(tenth, engine="mjx", nice=2)
    assert fit.feasible
    assert fit.factors["L"] == 2048
    fitted = tenth.converted(**fitted_units(tenth, fit))
    assert engines.check(fitted) == ()
    assert engines.check(fitted, "mujoco") == ()
    # the original hopper is clear of MuJoCo's thresholds, not of MJX's: in millimetres it is
    original = engines.load(ASSETS / "hopper.xml")
    assert engines.check(original) == ()
    assert {c.element for c in engines.check(original, "mjx")} == own
    assert fitted_units(original, pt.fit_units(original, engine="mjx"))["L"] == "mm"


def test_mjx_floors_the_fluid_models_masses_and_moments_at_1e_12(tmp_path):
    import jax

    # a free body moving in a fluid: MJX's fluid forces (qfrc_passive, nothing else acts) against MuJoCo's
    # (qfrc_fluid, which floors the moments at 1e-15 and not the mass)
    import mujoco
    from mujoco import mjx

    floors = engines.thresholds.thresholds("mjx", names=["mjx_fluid_moments_floor", "mjx_fluid_mass_floor"])
    assert [t.value for t in floors] == [1e-12, 1e-12]
    forward = jax.jit(mjx.forward)

    def text(mass, moment):
        return (
            '<mujoco><option viscosity="1" density="1" gravity="0 0 0"/><worldbody><body name="speck">'
            f'<freejoint/><inertial pos="0 0 0" mass="{mass}" diaginertia="{moment} {moment} {moment}"/>'
            '<geom size="0.001" contype="0" conaffinity="0" mass="0"/></body></worldbody></mujoco>'
        )

    def ratio(mass, moment):  # MJX's force and torque over MuJoCo's
        m = mujoco.MjModel.from_xml_string(text(mass, moment))
        d = mujoco.MjData(m)
        d.qvel[:] = [1, 0, 0, 0, 0, 1]
        mujoco.mj_forward(m, d)
        dx = forward(mjx.put_model(m), mjx.put_data(m, d))
        return np.asarray(dx.qfrc_passive, float)[[0, 5]] / d.qfrc_fluid[[0, 5]]

    assert ratio(1e-9, 1e-12) == pytest.approx([1, 1], rel=1e-6)  # at the floor: the same forces
    assert ratio(1e-9, 1e-14) == pytest.approx([10, 1000], rel=0.01)  # a box 10 times larger
    assert ratio(1e-12, 1e-11) == pytest.approx([1, 1], rel=1e-6)
    assert ratio(1e-13, 1e-11) == pytest.approx([0.194, 0.0072], rel=0.01)
    # check names them in MJX (float32 and float64 alike) and not in MuJoCo; without a fluid, nothing
    path = tmp_path / "speck.xml"
    path.write_text(text(1e-13, 1e-14))
    for model in (engines.load(path, engine="mjx"), engines.load(path, engine="mjx", precision="float64")):
        said = {c.element: c.detail for c in engines.check(model)}
        assert "below mjx_fluid_mass_floor" in said["body_speck_mass_in_fluid"]
        assert "below mjx_fluid_moments_floor" in said["body_speck_fluid_box_moments"]
    assert not any("mjx_" in c.detail for c in engines.check(engines.load(path)))
    path.write_text(text(1e-13, 1e-14).replace('viscosity="1" density="1" ', ""))
    assert not any("fluid" in c.element for c in engines.check(engines.load(path, engine="mjx")))


WORM = """<mujoco model="worm">
  <option timestep="0.0001"/>
  <default><geom type="capsule" size="0.00004" density="1050" friction="0.8 5e-6 1e-7" condim="6"/>
    <joint type="hinge" axis="0 0 1" stiffness="2e-10" damping="1e-12"/></default>
  <worldbody>
    <geom name="floor" type="plane" size="0.01 0.01 0.001"/>
    <body name="s0" pos="0 0 0.00004"><freejoint/><geom fromto="0 0 0 0.0002 0 0"/>
      <body name="s1" pos="0.0002 0 0"><joint name="bend1"/><geom fromto="0 0 0 0.0002 0 0"/>
        <body name="s2" pos="0.0002 0 0"><joint name="bend2"/><geom fromto="0 0 0 0.0002 0 0"/></body>
      </body>
    </body>
  </worldbody>
  <actuator><motor joint="bend1" ctrlrange="-2e-11 2e-11"/><motor joint="bend2" ctrlrange="-2e-11 2e-11"/>
  </actuator>
</mujoco>
"""


def test_a_worm_fitted_for_mjx_is_clear_of_its_thresholds_and_runs(tmp_path):
    from pitheorem.engines.fitting import fitted_units

    path = tmp_path / "worm.xml"
    path.write_text(WORM)
    worm = engines.load(path)  # MuJoCo refuses it (inertias below mjMINVAL): a table to repair
    # in millimetres MuJoCo takes it; MJX's capsules (half-length 0.1 mm) do not: the first and last segments
    # meet (the others are parent and child)
    in_mm = worm.converted(L="mm")
    assert engines.check(in_mm) == ()
    assert {c.element for c in engines.check(in_mm, "mjx")} == {"geom1_half_length", "geom3_half_length"}
    fit = pt.fit_units(worm, engine="mjx")
    assert fit.feasible
    units = fitted_units(worm, fit)
    assert units["L"] == "um"
    saved = worm.converted(**units).save(tmp_path / "worm_mjx.xml")
    in_mjx = engines.load(saved, engine="mjx")
    assert engines.check(in_mjx) == ()
    assert engines.check(in_mjx, "mujoco") == ()
    high = in_mjx.inputs()[2]
    rows = in_mjx.run(200, controls=lambda t: high * np.sin(60e-3 * t - np.arange(2)))
    assert np.isfinite(rows).all()
    assert np.abs(rows[-1] - rows[0]).max() > 0  # it moved


FILTERED = """<mujoco><worldbody><geom name="ground" type="plane" size="1 1 0.1"/>
  <body name="a"><freejoint/><geom name="a" type="capsule" size="0.1 0.2"/>
    <body name="b" pos="0 0 1"><joint/><geom name="b" type="capsule" size="0.1 0.2"/>
      <geom name="b2" type="sphere" size="0.1" contype="2" conaffinity="2"/>
      <body name="c" pos="0 0 1"><joint/><geom name="c" type="capsule" size="0.1 0.2"/></body></body></body>
  <body name="d" pos="2 0 0"><freejoint/><geom name="d" type="sphere" size="0.1" contype="0" conaffinity="0"/>
  </body></worldbody>
  <contact><exclude body1="c" body2="a"/><pair geom1="d" geom2="a"/></contact></mujoco>"""


@pytest.mark.parametrize("name", ["hopper.xml", "walker2d.xml", "ant.xml", "humanoid.xml", "reacher.xml", "filtered"])
def test_the_pairs_thresholds_reads_are_mjxs_own(name):
    import mujoco
    from mujoco.mjx._src.collision_driver import geom_pairs

    from pitheorem.engines.runners.mjx import _FILTERPARENT, _collision_pairs

    assert mujoco.mjtDisableBit.mjDSBL_FILTERPARENT == _FILTERPARENT
    m = (
        mujoco.MjModel.from_xml_string(FILTERED)
        if name == "filtered"
        else mujoco.MjModel.from_xml_path(str(ASSETS / name))
    )
    theirs = {tuple(sorted((int(a), int(b)))) for a, b, _ in geom_pairs(m)}
    plane = int(mujoco.mjtGeom.mjGEOM_PLANE)
    ours = {(a, b) for a, b in _collision_pairs(m) if not m.geom_type[a] == m.geom_type[b] == plane}
    assert ours == theirs
    # with the parent filter off, a body's geoms meet its parent's too
    m.opt.disableflags |= _FILTERPARENT
    assert {tuple(sorted((int(a), int(b)))) for a, b, _ in geom_pairs(m)} == {
        (a, b) for a, b in _collision_pairs(m) if not m.geom_type[a] == m.geom_type[b] == plane
    }


@pytest.mark.parametrize("name", ["hopper.xml", "ant.xml"])
def test_a_scaled_copy_is_one_program_with_its_original(name):
    import jax

    # a copy whose static arrays differ from its original's runs in a call of its own, a program XLA compiles
    # apart, which may round differently: the hopper's copy then parted from its original after one step
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        model = engines.load(ASSETS / name, engine="mjx")
    copy = model.scaled(time_free(model), 4)
    assert not np.array_equal(copy.runner.device_model().body_margin, model.runner.device_model().body_margin)
    aligned = mjx_backend._aligned(copy.runner, model.runner)
    structure = jax.tree_util.tree_structure
    assert structure(aligned) == structure(model.runner.device_model())
    # the arrays MJX traces are the copy's own
    assert np.array_equal(aligned.geom_size, copy.runner.device_model().geom_size)
    assert not np.array_equal(aligned.geom_size, model.runner.device_model().geom_size)


def test_the_static_arrays_taken_from_the_original_are_never_read_by_mjx():
    # what _UNREAD_STATIC claims, read from the installed MJX's source: the field is named only where the
    # model's type declares it (and, for a heightfield's radii, where the heightfield collision reads it)
    import mujoco.mjx

    sources = [p for p in Path(mujoco.mjx.__file__).parent.rglob("*.py") if not p.name.endswith("_test.py")]
    for _owner, field, geom_type in mjx_backend._UNREAD_STATIC:
        readers = sorted(p.name for p in sources if field in p.read_text(encoding="utf-8"))
        allowed = {"types.py", "io.py"} | ({"collision_driver.py"} if geom_type else set())
        assert set(readers) <= allowed, (field, readers)


def test_a_file_mujoco_refuses_is_refused_with_mujocos_reason(tmp_path):
    speck = tmp_path / "speck.xml"  # a mass below MuJoCo's threshold: its compiler refuses the file
    speck.write_text(
        '<mujoco><worldbody><body><freejoint/><geom size="1e-6" density="1000"/></body></worldbody></mujoco>'
    )
    with pytest.raises(engines.EngineModelError, match="mass and inertia of moving bodies") as caught:
        engines.load(speck, engine="mjx")
    assert str(caught.value) == str(engines.load(speck).runner.refusal)  # as MuJoCo's loader has it


def test_a_scaled_copy_shares_the_batch_unless_a_heightfield_reads_its_bounds(pendulum, tmp_path):
    # the pendulum's copy runs with the original's geom_rbound_hfield (never read without a heightfield)
    copy = pendulum.scaled(time_free(pendulum), 4).runner
    mine, theirs = (
        copy.device_model()._impl.geom_rbound_hfield,
        pendulum.runner.device_model()._impl.geom_rbound_hfield,
    )
    assert not np.array_equal(mine, theirs)
    aligned = mjx_backend._aligned(copy, pendulum.runner)
    assert np.array_equal(aligned._impl.geom_rbound_hfield, theirs)
    assert np.array_equal(aligned.opt.gravity, copy.device_model().opt.gravity)  # the rest is the copy's own
    # with a heightfield the bounds size its collision patch: the copy keeps its own
    terrain = tmp_path / "terrain.xml"
    terrain.write_text(
        '<mujoco><asset><hfield name="h" nrow="3" ncol="3" size="1 1 0.1 0.1" '
        'elevation="0 0 0 0 1 0 0 0 0"/></asset><worldbody><geom type="hfield" hfield="h"/>'
        '<body pos="0 0 1"><freejoint/><geom type="sphere" size="0.1"/></body></worldbody></mujoco>'
    )
    ground = engines.load(terrain, engine="mjx")
    scaled_ground = ground.scaled(time_free(ground), 4).runner
    assert mjx_backend._aligned(scaled_ground, ground.runner) is scaled_ground.device_model()
    # and a model of other sizes is not aligned with the pendulum
    assert mjx_backend._aligned(ground.runner, pendulum.runner) is ground.runner.device_model()


def test_a_batch_starts_from_given_states_nudged_by_one_float32_ulp(pendulum):
    b = pendulum.runner
    # seven runs of DURATION: the batch and length of the pendulum's verifications above (the original, its
    # copy, three twins and two negative controls), one program that XLA compiles once
    n = round(DURATION / b.timestep())
    given = np.array([0.5, -0.25])  # a first row: qpos, qvel (the pendulum has no activation)
    inputs = np.full((n, 1), 0.1)
    runs = b.run_many(
        n,
        [
            (b, None, False, None),
            (b, None, True, given),
            (b, None, False, given),
            (b, inputs, False, None),
            (b, lambda t: [0.1], False, None),
            (b, None, True, None),
            (b, inputs, False, given),
        ],
    )
    swinging = runs[2]
    k = n // 2
    state = swinging[k]
    assert state[0] != 0
    assert state[1] != 0  # swinging: a state no rest pose has
    from_state = b.run_many(n, [(b, None, False, state)] * 7)
    assert all(np.array_equal(run, from_state[0]) for run in from_state)
    # a run from the state at step k goes on as the run it was taken from
    np.testing.assert_allclose(from_state[0][: n - k + 1], swinging[k:], rtol=1e-5, atol=1e-6)
    # a nudge moves each start coordinate up by the float32 ulp of 1 below magnitude 1 (as MuJoCo's nudge does
    # in float64), and the run parts from the unnudged
    eps = 2.0**-23
    assert runs[2][0].tolist() == [0.5, -0.25]
    assert runs[1][0].tolist() == [0.5 + eps, -0.25 + eps]
    assert not np.array_equal(runs[1], runs[2])
    # at rest, a coordinate at exactly zero moves to the ulp of 1, not to NaN; from 1 and up, to the next float32
    qpos, qvel = mjx_backend._initial(b, True, None, np.float32)
    assert qvel.tolist() == [eps]
    assert runs[5][0].tolist() == [*qpos.tolist(), eps]  # the batch starts a nudged run at rest there
    assert not np.array_equal(runs[6], runs[2])  # from the same state, the inputs act
    assert mjx_backend._nudged(np.array([2.0, -1.0]), np.float32).tolist() == [2.0 + 2 * eps, -1.0 + eps / 2]
    # inputs as rows and as a function of time give the same run, and the inputs act
    assert np.array_equal(runs[3], runs[4])
    assert not np.array_equal(runs[3], runs[0])


def test_a_variant_changes_the_solver_tolerance_only(pendulum):
    variant = pendulum.runner.variant(tolerance=1e-3)
    assert variant.solver_settings() == {"tolerance": 1e-3}
    assert pendulum.runner.solver_settings() == {"tolerance": pendulum.parameter("tolerance").value[0]}
    assert float(variant.device_model().opt.tolerance) == pytest.approx(1e-3)
    assert variant.precision == pendulum.runner.precision


def test_a_start_with_activations_is_refused_by_name(tmp_path):
    path = tmp_path / "filtered.xml"
    path.write_text(
        '<mujoco><worldbody><body><joint name="j" type="hinge"/><geom size="0.1" mass="1"/></body>'
        '</worldbody><actuator><general joint="j" dyntype="filter" dynprm="0.1"/></actuator></mujoco>'
    )
    model = engines.load(path, engine="mjx")
    assert model.coordinates()[0] == ["qpos[j]", "qvel[j]", "act[0]"]
    with pytest.raises(pt.InvalidRequestError, match="MJX runs start with every activation at zero"):
        model.run(2, initial=[0.1, 0.0, 0.5])


def test_a_urdf_in_mjx_is_mujocos_urdf_model_with_its_settings_file(tmp_path):
    path = engines.example_path("hinged_rod.urdf")
    in_mjx, in_mujoco = engines.load(path, engine="mjx"), engines.load(path, engine="mujoco")
    assert [(p.name, p.value) for p in in_mjx.parameters] == [(p.name, p.value) for p in in_mujoco.parameters]
    sc = pt.Scaling.from_unit_change(in_mjx.system(), {"L": 1, "T": -1})
    out = in_mjx.scaled(sc, 4).save(tmp_path / "rod.urdf")
    assert (tmp_path / "rod.urdf.mujoco.json").is_file()
    assert engines.load(out, engine="mjx").timestep() == in_mjx.timestep() / 4
    with pytest.raises(pt.InvalidRequestError, match="precision"):
        engines.load(path, engine="mjx", precision="float16")


def test_an_mjx_copy_keeps_its_inputs_as_mujocos_does():
    path = Path(__file__).resolve().parent / "data" / "engines" / "actuated.xml"
    model = engines.load(path, engine="mjx")
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1, "M": 3})
    kept = model.scaled(sc, 4, keep_inputs=True)
    in_mujoco = engines.load(path).scaled(sc, 4, keep_inputs=True)
    np.testing.assert_array_equal(kept.inputs()[1], model.inputs()[1])
    np.testing.assert_array_equal(kept.inputs()[2], model.inputs()[2])
    assert [repr(p.value) for p in kept.parameters] == [repr(p.value) for p in in_mujoco.parameters]  # NaN: unset


# -- MJX from the command line and in a sweep (here rather than beside the other commands' tests, so that one
# xdist worker imports MJX, and the pendulum's verifications share one compiled program: DURATION, 7 runs) ----


def test_check_says_first_that_another_engine_refuses_the_file(tmp_path, capsys):
    from pitheorem.cli import main

    path = tmp_path / "pgs.xml"
    path.write_text(
        '<mujoco><option solver="PGS"/><worldbody><body><joint type="hinge"/>'
        '<geom size=".1" mass="1"/></body></worldbody></mujoco>'
    )
    assert main(["check", str(path)]) == 0  # MuJoCo runs it
    capsys.readouterr()
    assert main(["check", str(path), "--engine", "mjx"]) == 1
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("pgs.xml: mjx refuses the file (option solver: MJX does not support the PGS solver")


def test_verify_on_the_command_line_runs_in_mjx(capsys):
    import json

    import mujoco.mjx  # noqa: F401  (its note on a missing warp, if any, printed before the command)

    from pitheorem.cli import main

    capsys.readouterr()
    argv = ["verify", str(PENDULUM), "--scale", "g=1", "--s", "4", "--engine", "mjx", "--duration", str(DURATION)]
    assert main([*argv, "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)  # nothing but the answer: not MJX's note on a missing warp
    assert (doc["engine"], doc["exact"]) == ("mjx", True)


def test_mjx_sweeps_run_in_this_process_and_match_verify(monkeypatch):
    from pitheorem.engines.verdicts.strength import control_factors
    from tests.conftest import expected_verdict, recorded_batches

    def push(t):
        return [0.1 * np.sin(7.0 * t)]

    model = engines.load(PENDULUM)
    sc = time_free(model)
    mjx_class = type(engines.load(PENDULUM, engine="mjx").runner)
    batches = recorded_batches(monkeypatch, mjx_class)
    sw = engines.sweep(model, sc, s=(4, 10), duration=DURATION, controls=push, engine="mjx", fit=False)
    monkeypatch.undo()
    calls = [len(jobs) for jobs in batches]
    assert sw.engine == "mjx"
    # the original and its three twins once, then both copies with their first controls in one vectorised call
    assert calls[:2] == [4, 2 * (1 + len({g for g, _e, _f in control_factors(model)}))]
    mjx = engines.load(PENDULUM, engine="mjx")
    for row in sw.rows:
        rep = engines.verify(mjx, sc, row.s, duration=DURATION, controls=push)
        assert (row.verdict, row.max_deviation) == (expected_verdict(rep), rep.max_deviation)
    assert np.isfinite([r.yardstick for r in sw.rows]).all()


def test_a_variant_switches_contacts_equalities_and_limits_off_as_mujocos_does():
    """MJX keeps no contact list for a pair's counter-run, but it switches contacts off, equality constraints
    inactive and limits off as MuJoCo's runner does (the diagnosis's counter-runs: tested through MuJoCo Warp,
    whose runs compile faster); the runner's own model is untouched."""
    import mujoco

    from pitheorem.engines.protocols import SolverDiagnosis, SwitchesConstraints

    path = Path(__file__).resolve().parent / "data" / "engines" / "weld_and_egg.xml"
    runner = engines.load(path, engine="mjx").runner
    assert isinstance(runner, SwitchesConstraints)
    assert not isinstance(runner, SolverDiagnosis)
    assert runner.equality_names() == engines.load(path).runner.equality_names() == ["equality #0"]
    assert runner.equality_kinds() == ["weld"]
    variant = runner.variant(contacts=False, inactive_equalities=(0,))
    contact = int(mujoco.mjtDisableBit.mjDSBL_CONTACT)
    assert int(variant.device_model().opt.disableflags) & contact
    assert np.asarray(variant.device_model().eq_active0).tolist() == [False]
    assert not int(runner.device_model().opt.disableflags) & contact
    assert np.asarray(runner.device_model().eq_active0).tolist() == [True]
