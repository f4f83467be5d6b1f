"""Tests for pitheorem.progress and the command line's progress bars on stderr.

A terminal is faked by making ``sys.stderr.isatty()`` answer True (capsys's stream stands in for
the terminal), and the bars' delay is set to 0 so that the short runs here draw them.
"""

from __future__ import annotations

import json
import sys
import time

import pytest

from pitheorem import progress
from pitheorem.cli import main
from pitheorem.engines import example_path
from pitheorem.progress import StageBar, say, wanted

PENDULUM = "example:pendulum.xml"


@pytest.fixture
def terminal(monkeypatch, capsys):
    """stderr is a terminal (a fake one: capsys's stream answers isatty() True), and bars show at once.

    capsys puts its stream in place when the test itself begins, so the stream is patched then,
    as :func:`run` is called.
    """
    monkeypatch.setattr(progress, "DELAY", 0.0)

    def as_terminal():
        monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
        return capsys

    return as_terminal


@pytest.fixture
def no_delay(monkeypatch):
    monkeypatch.setattr(progress, "DELAY", 0.0)


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def _bar_lines(err: str, command: str) -> list[str]:
    """The bar's drawings on stderr (tqdm writes each after a carriage return)."""
    return [part.strip() for part in err.split("\r") if part.strip().startswith(f"{command}: ")]


# -- the pieces ------------------------------------------------------------------------------


def test_wanted_only_on_a_terminal_and_never_in_json_mode(monkeypatch, capsys):
    assert not wanted("text")  # capsys's stream is no terminal
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    assert wanted("text")
    assert wanted("latex")
    assert not wanted("json")


def test_a_stage_bar_shows_each_stage_then_erases_itself(no_delay, capsys):
    with StageBar("apply", ("loading", "writing"), show=True) as bar:
        bar.stage("loading")
        bar.stage("writing")
    err = capsys.readouterr().err
    drawn = _bar_lines(err, "apply")
    assert any("apply: loading" in d and "0/2 stages" in d for d in drawn), err
    assert any("apply: writing" in d and "1/2 stages" in d for d in drawn), err
    last = err.rsplit("\r", 2)[-2]  # erased: the last drawing is blanks only
    assert last, repr(err[-80:])
    assert last.strip() == "", repr(err[-80:])
    assert bar.done == ("loading", "writing")


def test_a_stage_bar_keeps_ticking_while_a_stage_runs(no_delay, monkeypatch, capsys):
    monkeypatch.setattr(progress, "TICK", 0.02)
    with StageBar("check", ("loading",), show=True) as bar:
        bar.stage("loading")
        time.sleep(0.3)  # one stage that reports nothing itself: the bar is redrawn meanwhile
    drawn = _bar_lines(capsys.readouterr().err, "check")
    assert len(drawn) >= 3, drawn


def test_a_stage_bar_waits_its_delay_before_it_shows(monkeypatch, capsys):
    monkeypatch.setattr(progress, "DELAY", 30.0)
    with StageBar("apply", ("loading",), show=True) as bar:
        bar.stage("loading")
    assert capsys.readouterr().err == ""


def test_a_hidden_stage_bar_writes_nothing_and_still_checks_its_stages(no_delay, capsys):
    with StageBar("apply", ("loading",), show=False) as bar:
        bar.stage("loading")
        with pytest.raises(ValueError, match="loading"):
            bar.stage("flying")
    assert capsys.readouterr().err == ""


def test_say_prints_above_a_bar_that_shows(no_delay, capsys):
    with StageBar("apply", ("loading",), show=True) as bar:
        bar.stage("loading")
        say("pitheorem: note: hello")
    err = capsys.readouterr().err
    assert "pitheorem: note: hello\n" in err
    assert err.index("apply: loading") < err.index("pitheorem: note")  # the bar came first, then the note


# -- the commands ----------------------------------------------------------------------------

COMMANDS = {
    "apply": (["apply", PENDULUM, "--scale", "g=1", "--s", "4", "--output", "OUT"], ["loading", "writing"]),
    "convert": (["convert", PENDULUM, "--units", "L=mm", "--output", "OUT"], ["loading", "writing", "checking"]),
    "check": (["check", PENDULUM], ["loading", "checking"]),
    "verify": (["verify", PENDULUM, "--scale", "g=1", "--s", "4", "--duration", "0.1"], ["running", "proving"]),
    "params": (["params", PENDULUM], ["loading"]),
    "groups": (["groups", PENDULUM], ["loading", "computing"]),
    "search": (["search", PENDULUM, "--scale", "g=1"], ["loading", "searching"]),
}


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_each_long_command_shows_its_stages_on_a_terminal_and_nothing_elsewhere(command, tmp_path, monkeypatch, capsys):
    argv, stages = COMMANDS[command]
    argv = [str(tmp_path / "out.xml") if a == "OUT" else a for a in argv]
    monkeypatch.setattr(progress, "DELAY", 0.0)
    quiet = run(capsys, *argv)  # stderr is no terminal here
    assert not _bar_lines(quiet[2], command), quiet[2]
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    shown = run(capsys, *argv)
    drawn = _bar_lines(shown[2], command)
    for stage in stages:
        assert any(d.startswith(f"{command}: {stage} ") for d in drawn), (stage, drawn)
    assert shown[:2] == quiet[:2]  # the same exit code and the same answer on stdout


@pytest.mark.parametrize("command", ["apply", "check", "verify", "convert"])
def test_json_mode_is_quiet_on_a_terminal(command, terminal, tmp_path):
    argv, _ = COMMANDS[command]
    argv = [str(tmp_path / "out.xml") if a == "OUT" else a for a in argv]
    _, out, err = run(terminal(), *argv, "--format", "json")
    assert "\r" not in err, err  # at most a note, no bar
    assert not _bar_lines(err, command), err
    json.loads(out)


def test_sweep_counts_its_runs_on_a_terminal(terminal):
    code, _, err = run(terminal(), "sweep", PENDULUM, "--scale", "g=1", "--s", "1", "4", "--duration", "0.1")
    assert code == 0, err
    assert "sweep:" in err  # tqdm's bar of 2 runs
    assert "/2" in err
    _, _, err = run(
        terminal(), "sweep", PENDULUM, "--scale", "g=1", "--s", "1", "4", "--duration", "0.1", "--format", "json"
    )
    assert err == ""


def test_a_note_on_stderr_is_whole_while_a_bar_shows(terminal):
    # apply's note on which minimal scaling it used comes after the bar is erased, on its own line
    code, _, err = run(terminal(), "apply", str(example_path("superball.xml")), "--scale", "g=1", "--s", "4")
    assert code == 0
    notes = [line for line in err.split("\n") if "pitheorem: note:" in line]
    assert notes
    assert all(line.split("\r")[-1].startswith("pitheorem: note:") for line in notes), notes
