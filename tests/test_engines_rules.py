"""Tests for pitheorem.engines.rules: published rules of thumb as changes of units."""

from __future__ import annotations

from fractions import Fraction

import pytest

import pitheorem as pt
from pitheorem.engines import (
    BULLET_SCALE_THE_WORLD,
    MUJOCO_FRAME_SIMILAR,
    RULES,
    RuleOfThumb,
    RuleQuantity,
    check_rule,
)


def test_bullet_rule_is_the_change_of_length_unit():
    rule = BULLET_SCALE_THE_WORLD
    built = pt.Scaling.from_exponents(rule.system, rule.exponents)
    assert built == pt.Scaling.from_unit_change(rule.system, {"L": 1})
    verdict = check_rule(rule)
    assert verdict.unit_change == {"M": 0, "L": 1, "T": 0}
    assert verdict.scaling == built


def test_mujoco_similar_is_mass_by_volume_and_length():
    rule = MUJOCO_FRAME_SIMILAR
    assert pt.Scaling.from_exponents(rule.system, rule.exponents) == pt.Scaling.from_unit_change(
        rule.system, {"M": 3, "L": 1}
    )
    verdict = check_rule(rule)
    assert verdict.unit_change == {"M": 3, "L": 1, "T": 0}
    # a global option no frame touches: the convex collision tolerance, a length (issue 10); and the
    # lengths written into MuJoCo's code (mjMINVAL as GJK's stopping distance for polytopes and as the
    # distance below which a primitive pair's normal falls back), which nothing can set (issue 31); and the
    # weight of a weld's rotational rows, 1 where torquescale squared (a squared length) belongs
    assert [c.name for c in verdict.broken] == [
        "mujoco_ccd_tolerance",
        "mujoco_ccd_discrete_tolerance",
        "mujoco_minval_normal",
        "mujoco_weld_rotational_weight",
    ]
    assert not verdict.complete


def test_bullet_rule_incomplete_for_the_rod(rod):
    v = check_rule(BULLET_SCALE_THE_WORLD, rod)
    assert [(n, p) for n, _, p in v.missing] == [("c_theta", 2), ("F", 1)]
    assert v.unchanged == ("t",)
    assert not v.complete
    names = [c.name for c in v.broken]
    for hidden in (
        "bullet_collision_margin",
        "bullet_contact_slop",
        "bullet_multibody_sleep_epsilon",
        "bullet_split_impulse_penetration_threshold",
    ):
        assert hidden in names
    # a factor of each shape's bounding radius, not a length: leaving it alone is right (issue 10)
    assert "bullet_contact_breaking_threshold" not in names
    assert "bullet_linear_sleep_threshold" not in names  # the rule names it
    assert "bullet_time_step" not in names  # time is untouched
    assert "angular springs" not in str(v)
    assert "c_theta [M L^2 T^-1] must scale by X^2" in str(v)


def test_bullet_rule_incomplete_for_superball(superball):
    v = check_rule(BULLET_SCALE_THE_WORLD, superball)
    assert dict((n, p) for n, _, p in v.missing) == {"F": 1, "G": -1, "E": -1, "rho": -3}
    assert set(v.unchanged) == {"k", "c", "t"}  # linear springs and dampers keep their values


def test_each_rule_agrees_with_search(rod):
    for rule in RULES:
        v = check_rule(rule, rod)
        p_m = v.unit_change["M"]
        res = pt.search(rod, scale={"l": 1, **({"m": p_m} if p_m else {})}, fixed=("t",) if p_m else ("t", "m"))
        assert res.feasible
        sc = res.scalings[0]
        for name in rod.variables:
            p = rule.exponent_of(rod.dimension(name))
            if p is not None:
                assert sc.exponents[name] == p, (rule.name, name)
        for name, _, p in v.missing:
            assert sc.exponents[name] == p


def test_a_wrong_rule_gets_a_certificate():
    wrong = RuleOfThumb(
        "torques by X",
        "pybullet",
        "made up",
        (
            RuleQuantity("length", "L", 1),
            RuleQuantity("mass", "M", 0),
            RuleQuantity("torque", "M L^2 T^-2", 1),
            RuleQuantity("time", "T", 0),
        ),
    )
    v = check_rule(wrong)
    assert not v.is_unit_change
    assert not v.complete
    assert v.certificate is not None
    assert set(v.certificate.exponents) <= {"length", "mass", "torque", "time"}
    assert "NOT a change of units" in str(v)


def test_rule_quantity_reads_exponents():
    assert RuleQuantity("x", "L", "1/2").exponent == Fraction(1, 2)
    with pytest.raises(pt.InvalidRequestError):
        RuleQuantity("x", "L", "half")


def test_check_rule_rejects_other_objects():
    with pytest.raises(pt.InvalidRequestError, match="RuleOfThumb"):
        check_rule({"length": 1})


def test_mujoco_frame_scale_measured():
    mujoco = pytest.importorskip("mujoco")
    import numpy as np

    def build(scale):
        frame = f'<frame scale="{scale}">' if scale else "<frame>"
        xml = (
            f'<mujoco><compiler angle="radian"/><worldbody>{frame}<body name="b" pos="0 0 1">'
            '<joint name="h" type="hinge" axis="0 1 0" stiffness="3" damping="0.5" springref="0.1"/>'
            '<joint name="s" type="slide" axis="1 0 0" stiffness="7" damping="0.3" frictionloss="0.2"/>'
            '<geom type="capsule" fromto="0 0 0 1 0 0" size="0.05" margin="0.01" '
            'solimp="0.9 0.95 0.001 0.5 2" solref="0.02 1"/></body></frame></worldbody></mujoco>'
        )
        return mujoco.MjModel.from_xml_string(xml)

    try:
        a, b = build(None), build(2)
    except ValueError:
        pytest.skip("this MuJoCo has no frame scale")
    x = 2.0
    u = check_rule(MUJOCO_FRAME_SIMILAR).scaling
    expect = {
        name: x ** float(u.exponent_of(dim))
        for name, dim in [
            ("mass", "M"),
            ("inertia", "M L^2"),
            ("torque", "M L^2 T^-2"),
            ("angular_damping", "M L^2 T^-1"),
            ("linear_stiffness", "M T^-2"),
            ("linear_damping", "M T^-1"),
            ("length", "L"),
            ("time", "T"),
            ("force", "M L T^-2"),
        ]
    }
    assert b.body_mass[1] / a.body_mass[1] == pytest.approx(expect["mass"])
    assert np.allclose(b.body_inertia[1] / a.body_inertia[1], expect["inertia"])
    assert b.jnt_stiffness[0] / a.jnt_stiffness[0] == pytest.approx(expect["torque"])
    assert b.dof_damping[0] / a.dof_damping[0] == pytest.approx(expect["angular_damping"])
    assert b.jnt_stiffness[1] / a.jnt_stiffness[1] == pytest.approx(expect["linear_stiffness"])
    assert b.dof_damping[1] / a.dof_damping[1] == pytest.approx(expect["linear_damping"])
    assert b.dof_frictionloss[1] / a.dof_frictionloss[1] == pytest.approx(expect["force"])
    assert b.geom_margin[0] / a.geom_margin[0] == pytest.approx(expect["length"])
    assert b.geom_solimp[0][2] / a.geom_solimp[0][2] == pytest.approx(expect["length"])
    assert b.geom_solref[0][0] / a.geom_solref[0][0] == pytest.approx(expect["time"])
    assert b.qpos_spring[0] == pytest.approx(a.qpos_spring[0])  # an angle
    assert np.allclose(b.opt.gravity, a.opt.gravity)  # gravity is the user's job
