"""The Cause record: the six kinds, validation, a deterministic order."""

import dataclasses

import pytest

from pitheorem.engines import CAUSE_KINDS, Cause
from pitheorem.engines.verdicts.causes import sorted_causes
from pitheorem.errors import InvalidRequestError, PiTheoremError


def test_the_seven_kinds_of_the_design():
    assert set(CAUSE_KINDS) == {"precision", "solver", "contact", "threshold", "setting", "unscaled", "unknown"}


def test_a_cause_says_whether_its_counter_run_restores_the_run():
    assert Cause("solver", "x", "y").restores is None  # no run tests it (an audit's cause)
    assert Cause("contact", "a / b", "z", restores=True).to_dict() == {
        "kind": "contact",
        "element": "a / b",
        "detail": "z",
        "restores": True,
    }


@pytest.mark.parametrize("kind", ["", "Contact", "contacts", None])
def test_an_unknown_kind_is_refused_by_name(kind):
    with pytest.raises(InvalidRequestError, match="unknown cause kind") as info:
        Cause(kind, "x", "y")
    assert isinstance(info.value, PiTheoremError)
    assert repr(kind) in str(info.value)


def test_element_and_detail_must_be_text():
    with pytest.raises(InvalidRequestError, match="element"):
        Cause("solver", 3, "y")
    with pytest.raises(InvalidRequestError, match="detail"):
        Cause("solver", "x", None)


def test_a_cause_is_immutable_and_hashable():
    c = Cause("threshold", "mjMINVAL", "below")
    with pytest.raises(dataclasses.FrozenInstanceError):
        c.kind = "solver"
    assert {c, Cause("threshold", "mjMINVAL", "below")} == {c}


def test_sorted_causes_orders_by_kind_then_element_and_drops_repeats():
    given = [
        Cause("contact", "b", ""),
        Cause("precision", "z", ""),
        Cause("unscaled", "y", ""),
        Cause("contact", "a", ""),
        Cause("contact", "b", ""),
    ]
    got = sorted_causes(given)
    assert [(c.kind, c.element) for c in got] == [
        ("unscaled", "y"),
        ("precision", "z"),
        ("contact", "a"),
        ("contact", "b"),
    ]
    assert sorted_causes(reversed(given)) == got
