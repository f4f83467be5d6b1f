"""pitheorem.answers: what each subcommand found, as values that hold results and never compute.

Each answer is a NamedTuple: it keeps what it is given, as given, cannot be
changed, and prints through the formatting home (its text is
``formatting.render(answer, "text")``; every format of every answer is in
test_formatting).  What the command line puts into them is in test_cli.
"""

from __future__ import annotations

import inspect
import pickle

import pytest

import pitheorem as pt
from pitheorem import answers
from pitheorem.formatting import TextDisplay, render

ANSWERS = [getattr(answers, name) for name in answers.__all__]


def test_every_answer_is_a_named_tuple_with_the_text_display():
    assert [cls.__name__ for cls in ANSWERS] == [
        "ApplyAnswer",
        "BasesAnswer",
        "EngineApplyAnswer",
        "EngineVerifyAnswer",
        "GroupsAnswer",
        "ParamsAnswer",
        "SearchAnswer",
        "SweepAnswer",
    ]
    for cls in ANSWERS:
        assert issubclass(cls, tuple)
        assert cls.__str__ is TextDisplay.__str__
        assert cls.__format__ is TextDisplay.__format__
        assert list(inspect.signature(cls).parameters) == list(cls._fields)


@pytest.mark.parametrize("cls", ANSWERS, ids=lambda cls: cls.__name__)
def test_an_answer_keeps_what_it_is_given_and_cannot_be_changed(cls):
    given = [object() for _ in cls._fields]  # stand-ins: an answer never looks inside its fields
    answer = cls(*given)
    assert all(getattr(answer, name) is value for name, value in zip(cls._fields, given, strict=True))
    with pytest.raises(AttributeError):
        setattr(answer, cls._fields[0], "other")
    with pytest.raises(AttributeError):
        answer.anything = 1
    changed = answer._replace(model="other")
    assert (changed.model, answer.model) == ("other", given[0])


def test_optional_fields_default_to_nothing():
    # an engine apply names no other file and no values by default; groups pass over no variable
    assert answers.EngineApplyAnswer._field_defaults == {"also_written": (), "details": ()}
    assert answers.GroupsAnswer._field_defaults == {"passed_over": (), "settings_avoided": False}
    assert answers.EngineVerifyAnswer._field_defaults == {"notes": ()}  # the engine's notes: none by default
    others = (answers.EngineApplyAnswer, answers.GroupsAnswer, answers.EngineVerifyAnswer)
    assert all(not cls._field_defaults for cls in ANSWERS if cls not in others)


def test_answers_print_their_rendered_text_and_pickle():
    system = pt.System({"l": "L", "h": "L", "g": "L T^-2", "t": "T"})
    groups = system.pi_groups(repeating=("l", "t"))
    found = [
        answers.GroupsAnswer("pair", system, groups, (None, None)),
        answers.BasesAnswer("pair", 2, ("h",), (), 3, system.bases(exclude=("h",))),
        answers.BasesAnswer("pair", 2, (), (), 6, None),
        answers.SearchAnswer("pair", pt.search(system, scale={"g": 1})),
    ]
    for answer in found:
        assert str(answer) == format(answer, "") == render(answer, "text")
        assert f"{answer:json}" == render(answer, "json")
        again = pickle.loads(pickle.dumps(answer))
        assert type(again) is type(answer)
        assert str(again) == str(answer)
    # the count alone (``pitheorem bases --count``): the number and nothing else, for scripts
    assert str(found[2]) == "6"
    assert str(found[1]).startswith("pair: 3 valid repeating sets of 2 variables (without h)\n1  ")
