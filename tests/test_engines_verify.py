"""engines.verify: engine runs of a model and its scaled copy, judged against the one-ulp sensitivity."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import pitheorem as pt

mujoco = pytest.importorskip("mujoco", reason="mujoco is not installed (pip install 'pitheorem[engines]')")

from pitheorem import engines  # noqa: E402

DATA = Path(__file__).resolve().parent / "data" / "engines"


def smooth(n):
    return lambda t: 0.3 * np.sin(2.0 * t + np.arange(n))


@pytest.mark.parametrize("name", ["tendon_actuators.xml", "contact.xml"])
@pytest.mark.parametrize("s", [2, 10])
def test_own_models_are_similar_under_gravity_times_s(name, s):
    model = engines.load(DATA / name)
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    nu = model.runner.mjmodel.nu
    rep = engines.verify(model, sc, s, duration=1.0, controls=smooth(nu) if nu else None)
    assert rep.similar, str(rep)
    assert set(rep.sensitivity) == set(rep.deviation)
    assert rep.original.y.shape == rep.mapped.y.shape == rep.nudged.y.shape


def test_a_scaling_that_leaves_a_parameter_behind_is_caught():
    model = engines.load(DATA / "tendon_actuators.xml")
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    good = model.scaled(sc, 10)
    # the same copy with the slide joint's stiffness left at its original value
    stiffness = model.parameter("joint_slide_stiffness").value[0]
    broken = good.with_values(joint_slide_stiffness=stiffness)
    rep = engines.verify(model, sc, 10, duration=1.0, scaled=broken)
    assert not rep.similar
    assert rep.max_deviation > 1e3 * max(rep.sensitivity.values())


def test_controls_are_converted_by_input_dimension():
    model = engines.load(DATA / "tendon_actuators.xml")
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    nu = model.runner.mjmodel.nu
    rep = engines.verify(model, sc, 10, duration=0.5, controls=lambda t: np.full(nu, 0.2))
    assert rep.similar
    # by hand: inputs of dimension M L T^-2, 1, L T^-1, T^-1, 1, M L T^-2 at lengths times 10
    by_hand = np.array([10, 1, 10, 1, 1, 10.0])
    _names, dims = model.runner.coordinate_dimensions()
    back = np.array([10.0 ** sc.exponent_of(d) for d in dims])
    scaled = model.scaled(sc, 10).runner
    n = 250
    original = model.runner.run(n, lambda t: np.full(nu, 0.2))
    converted = scaled.run(n, lambda t: np.full(nu, 0.2) * by_hand) / back
    unconverted = scaled.run(n, lambda t: np.full(nu, 0.2)) / back
    assert np.abs(converted - original).max() < 1e-12
    assert np.abs(unconverted - original).max() > 1e-3
    with pytest.raises(pt.InvalidRequestError, match="6 inputs"):
        engines.verify(model, sc, 10, duration=0.01, controls=lambda t: [0.0])


def test_controls_are_called_at_original_times():
    model = engines.load(DATA / "tendon_actuators.xml")
    sc = pt.Scaling.from_unit_change(model.system(), {"T": 1})
    seen = []

    def controls(t):
        seen.append(t)
        return np.zeros(6)

    engines.verify(model, sc, 4, duration=0.01, controls=controls)
    # once per step, at the start of each step of the original run: the nudged and the scaled run
    # get the same inputs (the scaled run's step i starts at 4 i dt, which is i dt in original time)
    dt = model.runner.timestep()
    assert seen == [i * dt for i in range(10)]


def test_scaled_time_step_is_checked_and_duration_validated():
    model = engines.load(DATA / "contact.xml")
    sc = pt.Scaling.from_unit_change(model.system(), {"T": 1})
    other = model.scaled(pt.Scaling.from_unit_change(model.system(), {"L": 1}), 2)
    with pytest.raises(pt.InvalidRequestError, match="time step"):
        engines.verify(model, sc, 2, duration=0.1, scaled=other)
    for bad in (0, -1, math.nan, "x"):
        with pytest.raises(pt.InvalidRequestError):
            engines.verify(model, sc, 2, duration=bad)
    rep = engines.verify(model, sc, 2, duration=0.2)
    assert rep.similar
    assert rep.method == "mujoco"


# -- closed-loop controllers ----------------------------------------------------------------------


def test_a_policy_that_returns_the_controls_runs_exactly_as_the_controls():
    model = engines.load(DATA / "tendon_actuators.xml")
    nu = model.runner.mjmodel.nu
    dt = model.runner.timestep()
    rows = np.array([smooth(nu)(i * dt) for i in range(200)])
    step = iter(range(200))
    open_loop = model.runner.run(200, rows)
    closed_loop = model.runner.run(200, policy=lambda m, d: rows[next(step)])
    # MuJoCo's rollout (open loop, in C) and the Python loop of a policy take the very same steps
    assert np.array_equal(open_loop, closed_loop)
    assert np.array_equal(open_loop, model.runner.run(200, smooth(nu)))  # called at t = i dt
    assert np.abs(open_loop - model.runner.run(200)).max() > 1e-6  # the inputs act


def test_controller_is_built_once_per_run_from_that_runs_model():
    model = engines.load(DATA / "tendon_actuators.xml")
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    seen = []

    def controller(run_model):
        seen.append(run_model.parameter("g").value[0])
        return lambda m, d: np.zeros(m.nu)

    rep = engines.verify(model, sc, 10, duration=0.05, controller=controller, ensemble=2)
    assert rep.similar
    g = model.parameter("g").value[0]
    # the original, the scaled copy, two twins, then each group's first negative control: the copy with gravity
    # off by 1e-4 and with its masses doubled, both caught, so that gravity's larger errors need no run
    ten = pytest.approx(10 * g, rel=1e-15)
    assert seen == [g, ten, g, g, pytest.approx(10 * g * (1 + 1e-4), rel=1e-15), ten]
    assert [(c.group, c.error, c.caught) for c in rep.controls] == [("g", 1e-4, True), ("masses", 1.0, True)]


def test_controller_misuse_is_named():
    model = engines.load(DATA / "tendon_actuators.xml")
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    nu = model.runner.mjmodel.nu
    with pytest.raises(pt.InvalidRequestError, match="not both"):
        engines.verify(model, sc, 2, duration=0.01, controls=smooth(nu), controller=lambda m: None)
    with pytest.raises(pt.InvalidRequestError, match="must be callable"):
        engines.verify(model, sc, 2, duration=0.01, controller=3.0)
    with pytest.raises(pt.InvalidRequestError, match="callable policy"):
        engines.verify(model, sc, 2, duration=0.01, controller=lambda run_model: "no policy")
    with pytest.raises(pt.InvalidRequestError, match=f"{nu} inputs, got 1"):
        engines.verify(model, sc, 2, duration=0.01, controller=lambda run_model: lambda m, d: [0.0])
    with pytest.raises(pt.InvalidRequestError, match=f"the controller's policy must give {nu} numbers, got 'x'"):
        engines.verify(model, sc, 2, duration=0.01, controller=lambda run_model: lambda m, d: "x")


def test_runs_in_one_batch_equal_the_runs_one_by_one():
    model = engines.load(DATA / "contact.xml")  # contacts, the solver's default tolerance: warm starts matter
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    scaled = model.scaled(sc, 10).runner
    b = model.runner
    n, nu = 300, b.mjmodel.nu
    rows = np.array([smooth(nu)(0.01 * i) for i in range(n)]) if nu else None
    jobs = [(b, rows, False, None), (b, rows, True, None), (scaled, rows, False, None), (b, rows, False, None)]
    one_by_one = [backend.run(n, controls, nudge) for backend, controls, nudge, _ in jobs]
    for _ in range(2):  # more runs than threads: a thread's second run must not inherit the first's state
        batch = b.run_many(n, jobs)
        assert all(np.array_equal(a, c) for a, c in zip(one_by_one, batch, strict=True))
    assert np.abs(one_by_one[0] - one_by_one[2] / 10).max() > 0  # different models: not a vacuous equality
    # the datas kept from those batches fit this model's sizes only: a batch of another model gets its own
    other = engines.load(engines.example_path("pendulum.xml")).runner
    assert np.array_equal(b.run_many(5, [(other, None, False, None)])[0], other.run(5))


def test_smooth_controls_and_controls_refuse_what_they_cannot_use():
    model = engines.load(engines.example_path("pendulum.xml"))
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    with pytest.raises(pt.InvalidRequestError, match="smooth_controls needs an EngineModel, got int"):
        engines.smooth_controls(3)
    with pytest.raises(pt.PiTheoremError, match="amplitude"):
        engines.smooth_controls(model, amplitude=-1)
    with pytest.raises(pt.PiTheoremError, match="period"):
        engines.smooth_controls(model, period=0)
    with pytest.raises(pt.InvalidRequestError, match="controls must be a callable t -> inputs, got list"):
        engines.verify(model, sc, 2, duration=0.1, controls=[0.1])
    # what the callable gives: numbers, as many as the inputs, finite (an API fuzz's "x" raised numpy's ValueError)
    with pytest.raises(pt.InvalidRequestError, match=r"controls\(t\) at t = 0 must give 1 numbers, got 'x'"):
        engines.verify(model, sc, 2, duration=0.1, controls=lambda t: "x")
    with pytest.raises(pt.InvalidRequestError, match="must give 1 inputs, got 2"):
        engines.verify(model, sc, 2, duration=0.1, controls=lambda t: [0.1, 0.2])
    with pytest.raises(pt.InvalidRequestError, match=r"at t = 0.002 gave \[nan\]: every input must be finite"):
        engines.verify(model, sc, 2, duration=0.1, controls=lambda t: [0.1 if t == 0 else float("nan")])
    u = engines.smooth_controls(model, amplitude=0.5, period=2.0)
    assert float(u(0.5)[0]) == pytest.approx(0.5 * np.sin(np.pi / 2))  # the sine at a quarter period


def test_a_batch_run_inherits_nothing_from_the_run_before_it_on_its_thread(tmp_path):
    """Rollout sets only the physics state between runs: inputs and active constraints must not carry over."""
    chain = tmp_path / "chain.xml"
    chain.write_text(
        '<mujoco><worldbody><body name="a" pos="0 0 1"><joint name="ja" axis="0 1 0"/>'
        '<geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>'
        '<body name="b" pos="0.3 0 0"><joint name="jb" axis="0 1 0"/>'
        '<geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/></body></body></worldbody>'
        '<equality><joint joint1="ja" joint2="jb"/></equality>'
        '<actuator><motor joint="ja" gear="1"/></actuator></mujoco>'
    )
    b = engines.load(chain).runner
    free = b.variant(inactive_equalities=(0,))
    u = np.full((80, 1), 0.5)
    # more jobs than threads: each thread runs a constrained and a free run, driven and undriven, in turn
    jobs = [
        (b, u, False, None),
        (free, None, False, None),
        (free, u, False, None),
        (b, None, False, None),
        (b, u, False, None),
    ]
    together = b.run_many(80, jobs)
    one_by_one = [backend.run(80, controls) for backend, controls, _, _ in jobs]
    assert all(np.array_equal(x, y) for x, y in zip(one_by_one, together, strict=True))
    assert not np.array_equal(one_by_one[0], one_by_one[2])  # the constraint matters: not a vacuous equality
    assert not np.array_equal(one_by_one[1], one_by_one[2])  # and so does the input


def test_a_batch_run_takes_its_own_models_mocap_pose_not_the_run_before_its(tmp_path):
    """A mocap body's pose is an input a reset takes from the model: a scaled copy's differs from the original's."""
    path = tmp_path / "platform.xml"
    path.write_text(
        '<mujoco><worldbody><body name="platform" mocap="true" pos="0 0 0.5"><geom type="box" size="1 1 0.05"/>'
        '</body><body name="ball" pos="0 0 1"><freejoint/><geom type="sphere" size="0.05" mass="1"/></body>'
        "</worldbody></mujoco>"
    )
    model = engines.load(path)
    twice = model.scaled(pt.Scaling.from_unit_change(model.system(), {"L": 1}), 2).runner
    b = model.runner
    jobs = [(twice, None, False, None), (b, None, False, None), (twice, None, False, None), (b, None, False, None)]
    together = b.run_many(300, jobs)
    one_by_one = [backend.run(300) for backend, *_ in jobs]
    assert all(np.array_equal(x, y) for x, y in zip(one_by_one, together, strict=True))
    # not vacuous: each ball lands on its own model's platform, the copy's at twice the height
    assert 0.55 < one_by_one[1][-1, 2] < 0.65
    assert 1.1 < one_by_one[0][-1, 2] < 1.3


#: a stiff hinge under an explicit spring at a long time step: Euler's oscillation grows tenfold a step until
#: MuJoCo finds the acceleration huge and resets the run (stiffness 400); at stiffness 100 it is stable
SPRING_ARM = (
    '<mujoco><option timestep="0.01"/><worldbody><body name="arm" pos="0 0 1">'
    '<joint name="hinge" axis="0 1 0" stiffness="{k}" springref="0.5"/>'
    '<geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02" mass="0.1"/></body></worldbody>'
    '<actuator><motor joint="hinge"/></actuator></mujoco>'
)


def _reset_row(path, n_steps):
    """By hand in plain MuJoCo: the row (1 + the step) at which MuJoCo warns of a bad acceleration and resets."""
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    for i in range(n_steps):
        mujoco.mj_step(m, d)
        if d.warning[mujoco.mjtWarning.mjWARN_BADQACC].number:
            return i + 1
    return None


def test_a_run_mujoco_resets_is_compared_only_before_it_and_is_inconclusive(tmp_path):
    path = tmp_path / "unstable.xml"
    path.write_text(SPRING_ARM.format(k=400))
    model = engines.load(path)
    k = _reset_row(path, 40)
    assert k is not None
    for rows in (model.runner.run(40), model.runner.run(40, policy=lambda m, d: np.zeros(1))):
        assert np.isfinite(rows[:k]).all()  # open loop (rollout) and closed loop alike
        assert np.isnan(rows[k:]).all()  # what MuJoCo ran after its reset is no run of this model
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    rep = engines.verify(model, sc, 4, duration=0.4)
    assert rep.exact  # the copy breaks down at the same step, bit for bit: that alone proves nothing
    assert rep.verdict == "inconclusive"
    assert rep.engine_reset == (pytest.approx(0.01 * k), "original")
    assert len(rep.original) == k  # compared before it
    assert "gave up on the original's run" in str(rep)
    assert json.loads(format(rep, "json"))["engine_reset"] == [pytest.approx(0.01 * k), "original"]
    assert rep.causes == ()  # no cause is looked for in a run that is not one


def test_a_copy_that_breaks_down_where_the_original_does_not_is_not_similar(tmp_path):
    path = tmp_path / "stable.xml"
    path.write_text(SPRING_ARM.format(k=100))
    model = engines.load(path)
    assert _reset_row(path, 40) is None
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    good = model.scaled(sc, 4)
    wrong = good.with_values(joint_hinge_stiffness=4 * good.parameter("joint_hinge_stiffness").value[0])
    rep = engines.verify(model, sc, 4, duration=0.4, scaled=wrong, diagnose=False)
    assert rep.verdict == "not similar"
    assert rep.engine_reset is not None
    assert rep.engine_reset[1] == "copy"
    assert "gave up on the copy's run" in str(rep)
    assert engines.verify(model, sc, 4, duration=0.4, diagnose=False).engine_reset is None


def test_what_verify_cannot_compare_is_refused_by_name():
    model = engines.load(DATA / "hanging.xml")
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1})
    with pytest.raises(pt.InvalidRequestError, match=r"verify needs an EngineModel .*, got str"):
        engines.verify(str(DATA / "hanging.xml"), sc, 2, duration=0.01)
    for scaled in ("copy.xml", model.runner):
        with pytest.raises(pt.InvalidRequestError, match="scaled must be an EngineModel of the same engine"):
            engines.verify(model, sc, 2, duration=0.01, scaled=scaled)
    # the same engine and time step, other coordinates (a ball and a box against one hinge)
    other = engines.load(DATA / "contact.xml")
    assert other.runner.timestep() == model.runner.timestep()
    with pytest.raises(pt.InvalidRequestError, match="other coordinates than the original"):
        engines.verify(model, sc, 2, duration=0.01, scaled=other)
    assert engines.verify(model, sc, 2, duration=0.01).passed  # its own scaled copy: no refusal
    # ensemble and seed: whole numbers, at least 1 and at least 0
    for what, bad, wanted in (
        ("ensemble", 0, "from 1 to 100"),
        ("ensemble", 2.0, "from 1 to 100"),
        ("ensemble", True, "from 1 to 100"),
        ("seed", -1, "of at least 0"),
        ("seed", "1", "of at least 0"),
    ):
        with pytest.raises(pt.InvalidRequestError) as caught:
            engines.verify(model, sc, 2, duration=0.01, **{what: bad})
        assert str(caught.value) == f"{what} must be a whole number {wanted}, got {bad!r}"
    assert engines.verify(model, sc, 2, duration=0.01, ensemble=np.int64(1), seed=0).passed


def test_a_model_or_copy_mujoco_refuses_is_verified_into_mujocos_refusal(tmp_path):
    """MuJoCo refuses masses below its threshold: verify raises that refusal, for the original or the copy."""

    def body(size):
        path = tmp_path / f"ball_{size}.xml"
        path.write_text(
            f'<mujoco><worldbody><body><freejoint/><geom size="{size}" density="1000"/></body></worldbody></mujoco>'
        )
        return engines.load(path)

    speck, ball = body("1e-6"), body("0.01")
    assert speck.runner.refusal is not None
    sc = pt.Scaling.from_unit_change(speck.system(), {"M": 1})
    s = 2**60  # a heavier mass unit: the copy's mass clears MuJoCo's threshold, the original's does not
    assert speck.scaled(sc, s).runner.run(3).shape == (4, 13)
    with pytest.raises(engines.EngineModelError, match="mass and inertia of moving bodies") as caught:
        engines.verify(speck, sc, s, duration=0.01)
    assert "MuJoCo does not run it" in str(caught.value)
    # a copy of another backend type (given by hand): the original runs, then the copy raises its refusal
    with pytest.raises(engines.EngineModelError, match="mass and inertia of moving bodies") as caught:
        engines.verify(ball, sc, 1, duration=0.01, scaled=speck)
    assert caught.value.path == speck.runner.path


def test_a_baseline_run_once_gives_the_same_reports_as_verify_alone():
    from pitheorem.engines.verdicts.verify import baseline

    model = engines.load(DATA / "tendon_actuators.xml")
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    u = smooth(model.runner.mjmodel.nu)
    base = baseline(model, 0.2, u)
    for s in (4, 10, 0.1):
        alone = engines.verify(model, sc, s, duration=0.2, controls=u)
        shared = engines.verify(model, sc, s, duration=0.2, controls=u, baseline=base)
        assert np.array_equal(alone.original.y, shared.original.y)
        assert np.array_equal(alone.mapped.y, shared.mapped.y)
        assert dict(alone.sensitivity) == dict(shared.sensitivity)
        assert (alone.verdict, alone.horizon, alone.detection_limit) == (
            shared.verdict,
            shared.horizon,
            shared.detection_limit,
        )
    assert not base.run.flags.writeable  # shared by every verification: nobody changes it


def test_a_baseline_of_other_runs_is_refused_by_name():
    from pitheorem.engines.verdicts.verify import baseline

    model = engines.load(DATA / "tendon_actuators.xml")
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    u = smooth(model.runner.mjmodel.nu)
    base = baseline(model, 0.1, u, ensemble=2)
    for wrong in (
        {"duration": 0.2, "controls": u, "ensemble": 2},  # another duration
        {"duration": 0.1, "controls": None, "ensemble": 2},  # other inputs
        {"duration": 0.1, "controls": lambda t: 2 * u(t), "ensemble": 2},
        {"duration": 0.1, "controls": u, "ensemble": 3},  # other twins
        {"duration": 0.1, "controls": u, "ensemble": 2, "seed": 1},
    ):
        with pytest.raises(pt.InvalidRequestError, match="baseline was run for another"):
            engines.verify(model, sc, 4, baseline=base, **wrong)
    with pytest.raises(pt.InvalidRequestError, match="closed-loop controller"):
        engines.verify(model, sc, 4, duration=0.1, ensemble=2, baseline=base, controller=lambda m: lambda *a: 0)
    with pytest.raises(pt.InvalidRequestError, match="must come from baseline"):
        engines.verify(model, sc, 4, duration=0.1, baseline="runs")


def test_progress_is_told_each_stage_in_order():
    from pitheorem.engines.verdicts.verify import STAGES

    model = engines.load(DATA / "tendon_actuators.xml")
    sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    seen = []
    engines.verify(model, sc, 4, duration=0.05, progress=lambda done, total: seen.append((done, total)))
    assert seen == [(k, STAGES) for k in range(1, STAGES + 1)]


# -- a copy that keeps its inputs: its causes held against the kept copy ----------------------------

#: three unnamed actuators (as many files leave them): a cause names each by its number
UNNAMED_ACTUATORS = """<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <body pos="0 0 1"><joint name="hinge" type="hinge" axis="0 1 0" damping="0.05"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.03" mass="1"/></body>
    <body pos="1 0 1"><joint name="slide" type="slide" axis="1 0 0" damping="0.1"/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.5"/></body>
    <body pos="2 0 1"><joint name="slide2" type="slide" axis="0 0 1" damping="0.2"/>
      <geom type="sphere" size="0.05" mass="0.3"/></body>
  </worldbody>
  <actuator>
    <motor joint="hinge" gear="2" ctrlrange="-1 1"/>
    <position joint="slide" kp="50" kv="2" ctrlrange="-0.1 0.1"/>
    <general joint="slide2" gainprm="3" ctrlrange="-1 1"/>
  </actuator>
</mujoco>
"""


def _three_inputs(t):
    return [0.5 * math.sin(5 * t), 0.05 * math.cos(3 * t), 0.7 * math.sin(2 * t)]


@pytest.mark.parametrize("s", [4, 10])
@pytest.mark.parametrize("actuator", [1, 2])
def test_a_kept_inputs_copy_with_one_gain_left_unscaled_is_caught_and_its_cause_names_that_actuator(
    tmp_path, s, actuator
):
    path = tmp_path / "unnamed.xml"
    path.write_text(UNNAMED_ACTUATORS)
    model = engines.load(path)
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1, "M": 3})
    kept = model.scaled(sc, s, keep_inputs=True)
    gain = [p.name for p in model.parameters if p.path.startswith("actuator") and p.name.endswith("gainprm_gain")]
    assert len(gain) == 3
    name = gain[actuator]
    assert kept.parameter(name).value != model.parameter(name).value  # the kept copy carries the factor there
    wrong = kept.with_values(**{name: model.parameter(name).value[0]})  # that gain left as the original's
    rep = engines.verify(model, sc, s=s, duration=0.3, controls=_three_inputs, keep_inputs=True, scaled=wrong)
    assert not rep.similar
    assert rep.causes, rep
    # one cause, on that actuator alone: the others keep their inputs as they should
    assert [c.kind for c in rep.causes] == ["unscaled"], [str(c) for c in rep.causes]
    assert rep.causes[0].detail.startswith(f"actuator #{actuator}:"), str(rep.causes[0])
    others = {f"actuator #{k}" for k in range(3) if k != actuator}
    assert not any(o in str(c) for c in rep.causes for o in others)


@pytest.mark.parametrize("s", [4, 10])
def test_a_right_kept_inputs_copy_diagnoses_no_cause(tmp_path, s):
    path = tmp_path / "unnamed.xml"
    path.write_text(UNNAMED_ACTUATORS)
    model = engines.load(path)
    sc = pt.Scaling.from_unit_change(model.system(), {"L": 1, "M": 3})
    kept = model.scaled(sc, s, keep_inputs=True)
    rep = engines.verify(model, sc, s=s, duration=0.3, controls=_three_inputs, keep_inputs=True, scaled=kept)
    assert rep.similar
    assert rep.exact == (s == 4)
    assert rep.causes == ()
    # the audit the diagnosis starts from, run on the right copy: nothing held wrong
    held = engines.audit(model, sc, s, scaled=kept, keep_inputs=True)
    assert [c for c in held.causes if c.kind != "solver"] == []
    # held against a copy whose inputs were scaled instead, the same right copy is wrong at every actuator
    default = engines.audit(model, sc, s, scaled=kept)
    named = " ".join(str(c) for c in default.causes)
    assert all(f"actuator #{k}" in named for k in range(3)), named


def test_a_number_whose_probe_overflows_takes_no_power_and_stops_nothing(tmp_path):
    """A margin of -1e308 (found by a fuzz of the test models) is -inf in the probe by 4: no power of s, so the
    probe check names nothing for it, and a verification of the file ends in a verdict, not an OverflowError."""
    from pitheorem.engines.verdicts.probes import dimension_causes

    path = tmp_path / "huge_margin.xml"
    path.write_text((DATA / "cart_and_far_ball.xml").read_text().replace('margin="0.01"', 'margin="-1e308"'))
    model = engines.load(path)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    probe = model.scaled(sc, 4).runner.stored_numbers()
    assert not np.isfinite(probe["geom_margin"]).all()  # the premise: the probe overflows
    assert dimension_causes(model, sc, model.runner.stored_numbers(), probe) == []
    assert engines.verify(model, sc, 4, duration=0.02).verdict in ("exact", "similar", "not similar", "inconclusive")


def test_a_time_step_too_short_for_the_duration_is_refused_by_name():
    """A time step of 1e-320 (found by a fuzz of the test models) makes a run of 0.02 s 2e318 steps: refused by
    name, with both numbers, by verify and baseline alike, not an OverflowError.  So are more twins, steps or
    sweep workers than pitheorem makes (an API fuzz's ensemble of 2**70 filled 12 GB of memory making twins)."""
    from pitheorem.engines.verdicts.verify import baseline

    model = engines.load(engines.example_path("pendulum.xml")).with_values(timestep=1e-320)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    for run in (lambda: engines.verify(model, sc, 4, duration=0.02), lambda: baseline(model, 0.02)):
        with pytest.raises(pt.InvalidRequestError, match=r"time step 1e-320 s is more than 1e\+07 steps"):
            run()
    from pitheorem.engines.enginemodel import MAX_STEPS
    from pitheorem.engines.verdicts.sweep import MAX_WORKERS
    from pitheorem.engines.verdicts.verify import MAX_TWINS

    fine = engines.load(engines.example_path("pendulum.xml"))
    with pytest.raises(pt.InvalidRequestError, match=f"ensemble must be a whole number from 1 to {MAX_TWINS}"):
        engines.verify(fine, sc, 4, duration=0.02, ensemble=2**70)
    with pytest.raises(pt.InvalidRequestError, match=f"n_steps must be a whole number from 0 to {MAX_STEPS}"):
        fine.run(MAX_STEPS + 1)
    with pytest.raises(pt.InvalidRequestError, match=f"workers must be a whole number from 1 to {MAX_WORKERS}"):
        engines.sweep(fine, sc, [4], duration=0.02, workers=MAX_WORKERS + 1)
    # a time step of 0 or below (MuJoCo compiles both: a run that never advances) is refused too
    for dt in (0.0, -0.0, -0.002):
        still = model.with_values(timestep=dt)
        with pytest.raises(pt.InvalidRequestError, match="a run needs a positive one"):
            engines.verify(still, sc, 4, duration=0.02)
