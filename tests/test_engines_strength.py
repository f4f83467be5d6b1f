"""pitheorem.engines.verdicts.strength: the twins' horizon, negative controls and what a run can see."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem.engines.verdicts.strength import (
    CONTROL_ERRORS,
    COPY_MARGIN,
    HORIZON_FRACTION,
    caught,
    control_factors,
    horizon,
)
from pitheorem.formatting.pieces import float_text, strength_lines

mujoco = pytest.importorskip("mujoco")

from pitheorem import engines  # noqa: E402


@settings(max_examples=60, deadline=None)
@given(st.integers(2, 40), st.integers(0, 39), st.floats(0.02, 10.0))
def test_the_horizon_is_the_last_time_before_a_twin_parts_by_the_fraction(n, k, jump):
    """A twin equal to a ramp until step k, then off by `jump` of the ramp's range: the horizon ends at k - 1."""
    k = min(k, n - 1)
    t = np.linspace(0.0, 1.0, n)
    run = np.column_stack([t * 3.0, np.zeros(n)])  # a still coordinate beside: it has no spread to count
    twin = run.copy()
    twin[k:, 0] += jump * 3.0
    assert jump > HORIZON_FRACTION
    assert horizon(t, run, [twin]) == t[max(k - 1, 0)]
    assert horizon(t, run, [run.copy()]) == t[-1]  # twins that never part: the whole run
    below = run.copy()
    below[:, 0] += HORIZON_FRACTION * 3.0 * 0.5  # within the fraction throughout
    assert horizon(t, run, [below]) == t[-1]


def test_a_still_coordinate_jittering_by_rounding_does_not_end_the_horizon():
    t = np.arange(4.0)
    run = np.array([[0.0, 0.0], [1.0, 1e-15], [2.0, 0.0], [3.0, 1e-15]])
    twin = run.copy()
    twin[:, 1] = [0.0, 0.0, 1e-15, 0.0]  # off by 100% of its own range of 1e-15, 3e-16 of the largest
    assert horizon(t, run, [twin]) == 3.0
    twin[3, 1] = 3 * HORIZON_FRACTION * 1e-3 * 3.0  # past the fraction of STILL of the largest range
    assert horizon(t, run, [twin]) == 2.0


def test_a_twin_that_goes_nan_parts_at_once():
    t = np.arange(3.0)
    run = np.array([[0.0], [1.0], [2.0]])
    assert horizon(t, run, [np.array([[0.0], [np.nan], [2.0]])]) == 0.0


def test_caught_by_any_bit_or_beyond_the_yardstick_where_the_copy_is_bit_for_bit():
    a = np.array([[1.0, 2.0], [3.0, 4.0]])
    limits = np.array([0.1, 0.1])
    assert not caught(a, a.copy(), limits, bits=True, copy=a)
    assert caught(a, np.nextafter(a, 9.0), limits, bits=True, copy=a)
    assert not caught(a, a + 0.05, limits, bits=False, copy=a)
    assert caught(a, a + 0.2, limits, bits=False, copy=a)
    assert caught(a, np.full_like(a, np.nan), limits, bits=False, copy=a)
    assert caught(a, np.full_like(a, np.nan), limits, bits=True, copy=a)


_runs = st.integers(1, 6).flatmap(
    lambda n: st.integers(1, 4).flatmap(
        lambda k: st.lists(
            st.lists(st.floats(-1e3, 1e3, allow_nan=False, allow_subnormal=False), min_size=k, max_size=k),
            min_size=n,
            max_size=n,
        )
    )
)


@settings(max_examples=200, deadline=None)
@given(
    _runs,
    st.data(),
    st.booleans(),
)
def test_caught_against_the_copy_is_a_property_of_deviations_beyond_the_copys_own(rows, data, bits):
    """A control identical to the copy, or to the original, is never caught; one moved far enough always is."""
    original = np.array(rows)
    n, k = original.shape
    noise = st.floats(-1.0, 1.0, allow_nan=False, allow_subnormal=False)
    copy = original + np.array(data.draw(st.lists(st.lists(noise, min_size=k, max_size=k), min_size=n, max_size=n)))
    limits = np.array(data.draw(st.lists(st.floats(0.0, 1.0), min_size=k, max_size=k)))
    assert not caught(original, copy.copy(), limits, bits=bits, copy=copy)  # what the copy itself does
    assert not caught(original, original.copy(), limits, bits=bits, copy=copy)  # no error at all
    # a control that leaves the original along a direction, in one coordinate at least, scaled up by far enough
    j = data.draw(st.integers(0, k - 1))
    direction = np.array(data.draw(st.lists(st.lists(noise, min_size=k, max_size=k), min_size=n, max_size=n)))
    i = data.draw(st.integers(0, n - 1))
    direction[i, j] = data.draw(st.sampled_from([-1.0, 1.0])) * data.draw(st.floats(1e-3, 1.0))
    floor = np.max(np.abs(copy - original), axis=0)
    far = 4.0 * (COPY_MARGIN * floor[j] + limits[j] + 1.0) / abs(direction[i, j])
    assert caught(original, original + far * direction, limits, bits=bits, copy=copy)
    # where the copy is bit for bit, the rule is the old one: any bit, or beyond the yardstick
    control = original + direction
    old = not np.array_equal(original, control) if bits else bool(np.any(np.abs(control - original) > limits))
    assert caught(original, control, limits, bits=bits, copy=original) is old


def test_a_control_is_caught_only_beyond_the_copys_own_deviation_in_that_coordinate():
    a = np.array([[0.0, 0.0], [1.0, 1.0]])
    limits = np.array([1e-6, 1e-6])
    off = 2.0**-10  # exact in binary, as are the sums below

    def late(x, y):  # the runs as the original, but at the second sample
        return a + np.array([[0.0, 0.0], [x, y]])

    copy = late(off, 0.0)  # the engine parted the copy in the first coordinate only
    assert not caught(a, late(COPY_MARGIN * off, 0.0), limits, bits=True, copy=copy)
    assert caught(a, late(2 * COPY_MARGIN * off, 0.0), limits, bits=True, copy=copy)
    # a bit off where the copy is bit for bit is caught (the rule's own bound), beside a coordinate it is not
    assert caught(a, late(off, 1e-15), limits, bits=True, copy=copy)
    assert not caught(a, late(off, 1e-15), limits, bits=False, copy=copy)  # within the yardstick
    # a copy that went NaN in a coordinate hides a control's NaN there, not elsewhere
    broken = late(np.nan, 0.0)
    assert not caught(a, broken, limits, bits=True, copy=broken)
    assert caught(a, late(np.nan, 1.0), limits, bits=True, copy=broken)


# A capsule hinged at its centre, 1 mm into a box welded to the world: neither body moves along the contact, so
# MuJoCo raises the contact's softness R to its floor mjMINVAL in the original and in a copy whose mass unit
# changed alike, where the copy's true R is another: the runs part by rounding.  Gravity cannot turn it.
_STUCK = (
    '<mujoco><option timestep="0.002"/><worldbody><geom type="box" size="0.5 0.5 0.05" pos="0 0 -0.05"/>'
    '<body pos="0 0 0.019"><joint name="spin" type="hinge" axis="0 1 0"/>'
    '<geom type="capsule" fromto="-0.2 0 0 0.2 0 0" size="0.02" mass="1"/></body></worldbody></mujoco>'
)


def test_a_control_that_differs_from_the_original_only_as_the_right_copy_does_is_not_caught(tmp_path):
    """The issue's false "caught": a copy the engine parts from the original by rounding, on a run gravity cannot
    move.  Every control differs from the original in some bit too, as the copy does; none is an error seen."""
    path = tmp_path / "stuck.xml"
    path.write_text(_STUCK)
    model = engines.load(path)
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    assert sc.unit_change["M"] != 0  # the mass unit changes: R at the floor is not the copy's true R
    copy = model.scaled(sc, 4)
    # by hand in plain MuJoCo: gravity doubled runs the original's very bits; the copy (time and angles kept, so
    # its coordinates are the original's units) parts from it
    a, b, c = model.runner.mjmodel, model.multiplied(g=2).runner.mjmodel, copy.runner.mjmodel
    da, db, dc = mujoco.MjData(a), mujoco.MjData(b), mujoco.MjData(c)
    same_under_2g, same_copy = [], []
    for _ in range(150):
        for m, d in ((a, da), (b, db), (c, dc)):
            mujoco.mj_step(m, d)
        same_under_2g.append(np.array_equal(da.qpos, db.qpos) and np.array_equal(da.qvel, db.qvel))
        same_copy.append(np.array_equal(da.qpos, dc.qpos) and np.array_equal(da.qvel, dc.qvel))
    assert all(same_under_2g)
    assert not all(same_copy)
    assert da.efc_R[: da.nefc].tolist() == dc.efc_R[: dc.nefc].tolist() == [2 * mujoco.mjMINVAL] * da.nefc
    rep = engines.verify(model, sc, 4, duration=0.3)
    assert rep.passed
    assert not rep.exact
    assert rep.verdict == "inconclusive"
    assert rep.detection_limit is None
    assert rep.unseen == ("g",)
    assert [(c.group, c.error, c.caught, c.hidden) for c in rep.controls] == [
        ("g", e, False, True) for e in CONTROL_ERRORS
    ]
    lines = strength_lines(rep)
    assert COPY_MARGIN == 10  # the words state the margin
    assert (
        "INCONCLUSIVE: not even gravity doubled moves this run 10 times further from the original than the copy "
        "itself (rounding the engine parts the runs by, or chaos), so it cannot tell an error in that from the "
        "copy's own deviation"
    ) in lines
    assert not any("is caught" in line for line in lines)
    assert not any("gravity cannot act" in line for line in lines)  # the run cannot tell, whatever gravity does
    # the twins part at once (it moves only by rounding): the words say the comparison says little
    assert rep.horizon < 0.3
    assert any("past it the comparison says little" in line for line in lines)


def test_a_wrong_copys_own_deviation_hides_its_controls_and_the_report_stays_not_similar():
    """Gravity left unscaled on a driven pendulum: not similar.  Its controls, made from that copy, stand no further
    from the original than it does; the report says not similar, with no word that would weaken it."""
    model = engines.load(engines.example_path("causes/hanging.xml"))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    wrong = model.scaled(sc, 10).multiplied(g=0.1)  # gravity as it was
    rep = engines.verify(model, sc, 10, duration=0.5, scaled=wrong, controls=engines.smooth_controls(model))
    assert rep.verdict == "not similar"
    assert all(c.hidden and not c.caught for c in rep.controls)
    lines = strength_lines(rep)
    assert not any("INCONCLUSIVE" in line or "than the copy itself" in line for line in lines)
    assert str(rep).splitlines()[0].startswith("FAILED")


def test_where_the_copy_parts_by_rounding_a_control_that_moves_the_robot_is_still_caught(tmp_path):
    """The stuck capsule beside a hopper: the copy is not bit for bit (the capsule's rounding), yet gravity times
    1.0001 moves the hopper far beyond what the copy deviates: caught at the smallest error, as before."""
    hopper = engines.example_path("causes/walker_on_floor.xml").read_text()
    stuck = (
        '<geom type="box" size="0.3 0.3 0.05" pos="3 0 0.05"/><body pos="3 0 0.119">'
        '<joint name="spin" type="hinge" axis="0 1 0"/>'
        '<geom type="capsule" fromto="-0.2 0 0 0.2 0 0" size="0.02" mass="1"/></body>'
    )
    path = tmp_path / "hopper_and_stuck.xml"
    path.write_text(hopper.replace("<worldbody>", "<worldbody>" + stuck, 1))
    model = engines.load(path)
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    rep = engines.verify(model, sc, 4, duration=1.0, controls=engines.smooth_controls(model), diagnose=False)
    assert not rep.exact
    assert rep.first_divergence[1] == "qvel[spin]"
    assert rep.verdict == "similar"
    assert rep.detection_limit == CONTROL_ERRORS[0]
    assert [(c.group, c.caught) for c in rep.controls] == [("g", True), ("masses", True)]


def test_the_controls_are_gravity_at_each_error_and_the_masses_doubled():
    model = engines.load(engines.example_path("pendulum.xml"))
    controls = control_factors(model)
    assert [(g, e) for g, e, _ in controls] == [*(("g", e) for e in CONTROL_ERRORS), ("masses", 1.0)]
    assert all(f == {"g": 1.0 + e} for g, e, f in controls if g == "g")
    masses = controls[-1][2]
    # every mass and density the file states, none the compiler derived (a body's mass from its geoms)
    expected = {
        p.name
        for p in model.parameters
        if str(p.dimension) in ("M", "M L^-3") and p.source != "derived" and any(v != 0 for v in p.value)
    }
    assert set(masses) == expected
    assert masses
    assert set(masses.values()) == {2.0}


def test_a_model_without_gravity_has_only_the_mass_control():
    model = engines.load(engines.example_path("pendulum.xml")).with_values(g=0)
    assert [g for g, _e, _f in control_factors(model)] == ["masses"]


def test_a_copy_with_gravity_left_wrong_is_never_similar_where_the_run_cannot_show_it():
    """The issue's false positive: a run gravity cannot act on passes a wrong copy; the controls say so."""
    model = engines.load(engines.example_path("causes/hanging.xml"))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    wrong = model.scaled(sc, 10).multiplied(g=0.1)  # gravity as it was
    rep = engines.verify(model, sc, 10, duration=0.3, scaled=wrong)
    assert rep.passed  # within the yardstick
    assert rep.inconclusive
    assert not rep.similar
    assert rep.verdict == "inconclusive"
    assert rep.detection_limit is None
    # the first control passed unnoticed, so every other one was run too, and none was caught
    assert [(c.group, c.error, c.caught) for c in rep.controls] == [
        *(("g", e, False) for e in CONTROL_ERRORS),
        ("masses", 1.0, False),
    ]
    # independent of verify: MuJoCo's own runs of the hanging pendulum under 9.81 and 19.62 are the same bits
    m = model.runner.mjmodel
    d1, d2 = mujoco.MjData(m), mujoco.MjData(m)
    m2 = model.multiplied(g=2).runner.mjmodel
    for _ in range(100):
        mujoco.mj_step(m, d1)
        mujoco.mj_step(m2, d2)
    assert np.array_equal(d1.qpos, d2.qpos)


def test_a_moving_run_catches_a_small_gravity_error_and_says_its_limit():
    model = engines.load(engines.example_path("pendulum.xml"))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    u = engines.smooth_controls(model)
    rep = engines.verify(model, sc, 10, duration=0.5, controls=u)
    assert rep.verdict == "similar"
    assert rep.detection_limit == CONTROL_ERRORS[0]
    assert [(c.group, c.error, c.caught) for c in rep.controls] == [
        ("g", CONTROL_ERRORS[0], True),
        ("masses", 1.0, True),
    ]
    assert rep.horizon == pytest.approx(0.5)
    proof = engines.verify(model, sc, 4, duration=0.5, controls=u)
    assert proof.verdict == "exact"
    assert proof.detection_limit == CONTROL_ERRORS[0]  # at a power of four any bit counts
    off = engines.verify(model, sc, 10, duration=0.5, controls=u, strength=False)
    assert off.controls == ()
    assert off.horizon is None
    assert off.detection_limit is None
    assert off.similar


def test_a_gravity_control_made_in_the_compiled_model_runs_as_one_compiled_from_the_file():
    """The control copy that skips compiling (gravity changed in the compiled model) steps the very same bits."""
    model = engines.load(engines.example_path("pendulum.xml"))
    in_place = model.runner.with_gravity_times(1.5)
    compiled = model.multiplied(g=1.5).runner
    assert np.array_equal(in_place.mjmodel.opt.gravity, compiled.mjmodel.opt.gravity)
    assert np.array_equal(model.runner.mjmodel.opt.gravity, [0.0, 0.0, -9.81])  # the original is left alone
    a, b = mujoco.MjData(in_place.mjmodel), mujoco.MjData(compiled.mjmodel)
    a.qpos[:] = b.qpos[:] = 0.3
    for _ in range(200):
        mujoco.mj_step(in_place.mjmodel, a)
        mujoco.mj_step(compiled.mjmodel, b)
    assert np.array_equal(a.qpos, b.qpos)
    assert a.qpos[0] != 0.3


def _slider(path, option: str = ""):
    """A box on a horizontal slide joint pushed by a motor, written to `path` (`option`: more of <option>)."""
    path.write_text(
        f'<mujoco><option timestep="0.002" {option}/><worldbody><body><joint name="x" type="slide" '
        'axis="1 0 0" damping="0.2"/><geom type="box" size="0.1 0.1 0.1" mass="1"/></body></worldbody>'
        '<actuator><motor joint="x" gear="1"/></actuator></mujoco>'
    )
    return path


def test_a_copy_with_gravity_left_wrong_on_a_planar_model_is_inconclusive_not_similar(tmp_path):
    """A slider moving in the horizontal plane: gravity cannot act on it, so a copy with gravity left unscaled
    moves exactly like a right one.  Its masses are seen (a motor pushes them), gravity is not: inconclusive."""
    model = engines.load(_slider(tmp_path / "planar.xml"))
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    u = engines.smooth_controls(model)
    wrong = model.scaled(sc, 10).multiplied(g=0.1)  # gravity as it was
    rep = engines.verify(model, sc, 10, duration=0.5, controls=u, scaled=wrong)
    assert rep.passed  # the motion is the right one
    assert rep.verdict == "inconclusive"
    assert [(c.group, c.caught) for c in rep.controls] == [("g", False)] * 3 + [("masses", True)]
    assert rep.detection_limit == 1.0  # the masses doubled are seen
    text = str(rep)
    assert "INCONCLUSIVE: not even gravity doubled changes this run" in text
    assert "a gravity error cannot be seen" in text
    right = engines.verify(model, sc, 10, duration=0.5, controls=u)
    assert right.verdict == "inconclusive"  # a right copy cannot prove its gravity either


def test_a_masses_control_made_in_the_compiled_model_matches_its_definition(tmp_path):
    """Every body's mass and inertia doubled, the derived constants computed again: as MuJoCo compiles a file
    whose masses and inertias are doubled (the oracle: MuJoCo's own compile of that file)."""
    text = (
        '<mujoco><worldbody><body pos="0 0 1"><joint type="hinge" axis="0 1 0"/>'
        '<inertial pos="0 0 -0.5" mass="{m}" diaginertia="{i} {i} {i}"/>'
        '<geom type="sphere" size="0.1" contype="0" conaffinity="0"/></body></worldbody></mujoco>'
    )
    path = tmp_path / "p.xml"
    path.write_text(text.format(m=1.5, i=0.02))
    doubled = engines.load(path).runner.with_masses_times(2.0).mjmodel
    two = mujoco.MjModel.from_xml_string(text.format(m=3.0, i=0.04))
    for field in ("body_mass", "body_inertia", "body_subtreemass", "dof_invweight0", "body_invweight0"):
        assert np.array_equal(getattr(doubled, field), getattr(two, field)), field
    assert engines.load(path).runner.mjmodel.body_mass[1] == 1.5  # the original is left alone


def test_the_masses_are_a_control_only_where_something_else_carries_mass(tmp_path):
    """A body that only falls moves alike whatever it weighs: every mass doubled is then a change of the unit of
    mass, no error.  A damping, or a motor's force, puts mass into a dimensionless group: then it is one."""
    from pitheorem.dimensions import Dimension

    def model(joint):
        path = tmp_path / f"m{len(joint)}.xml"
        path.write_text(
            f'<mujoco><worldbody><body pos="0 0 1"><joint type="hinge" axis="0 1 0"{joint}/>'
            '<geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02" mass="0.4"/></body></worldbody></mujoco>'
        )
        return engines.load(path)

    def groups(m, inputs=()):
        return [g for g, _e, _f in control_factors(m, inputs)]

    falling = model("")
    assert groups(falling) == ["g", "g", "g"]
    assert groups(falling, [Dimension.parse("M L^2 T^-2")]) == ["g", "g", "g", "masses"]  # a torque acts
    assert groups(model(' damping="0.1"')) == ["g", "g", "g", "masses"]
    sc = pt.search(falling.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    rep = engines.verify(falling, sc, 10, duration=0.5)
    assert rep.verdict == "similar"  # gravity is seen, and the masses form no group
    assert [c.group for c in rep.controls] == ["g"]


def test_a_model_without_gravity_is_said_to_catch_errors_in_its_masses_only(tmp_path):
    """No gravity in the file: no gravity control runs, and the strength line names only the masses."""
    model = engines.load(_slider(tmp_path / "free.xml", 'gravity="0 0 0"'))
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    rep = engines.verify(model, sc, 10, duration=0.5, controls=engines.smooth_controls(model))
    assert {c.group for c in rep.controls} == {"masses"}
    line = next(line for line in str(rep).splitlines() if line.startswith("strength:"))
    assert f"an error of {float_text(rep.detection_limit)} in the masses is caught" in line
    assert "gravity" not in line
    worst = max(rep.sensitivity.values())
    assert f"(yardstick: 10x each state's one-ulp sensitivity (the largest {worst:.3g}))" in str(rep).splitlines()[0]
