"""pitheorem.engines.packages: the one list of engine packages and how a missing one is reported."""

from __future__ import annotations

import subprocess
import sys

import pytest

import pitheorem as pt
from pitheorem.engines import (
    ENGINES,
    hidden_constants,
    simulate_rod,
)
from pitheorem.engines.packages import PACKAGES, check_engine, engine_module
from pitheorem.engines.paper.rod import EngineUnavailableError
from tests.conftest import REPO


def test_each_engine_names_its_package_in_one_place(monkeypatch):
    # the catalogue's engines are the engines with a package, and every reader of an engine name agrees
    assert tuple(PACKAGES) == ENGINES == ("pybullet", "mujoco", "mjx")
    assert PACKAGES["pybullet"] == "pybullet"
    for call in (
        lambda: check_engine("ode"),
        lambda: engine_module("ode"),
        lambda: hidden_constants("ode"),
        lambda: simulate_rod("ode"),
    ):
        with pytest.raises(pt.InvalidRequestError) as caught:
            call()
        assert str(caught.value) == "unknown engine 'ode'; use 'pybullet', 'mujoco' or 'mjx'"
        assert caught.value.culprit == "ode"
    with pytest.raises(pt.InvalidRequestError, match="unknown engine 3"):
        check_engine(3)
    # the old spelling is read as the one name, and every reader answers with the one name
    assert check_engine("bullet") == "pybullet"
    assert hidden_constants("bullet") == hidden_constants("pybullet")
    assert all(c.engine == "pybullet" for c in hidden_constants("bullet"))
    # a missing package is named in the error, as the one list has it
    monkeypatch.setitem(sys.modules, "pybullet", None)  # import pybullet now raises ImportError
    with pytest.raises(EngineUnavailableError) as caught:
        engine_module("pybullet")
    assert (caught.value.engine, caught.value.package, caught.value.culprit) == ("pybullet", "pybullet", "pybullet")
    assert (
        str(caught.value) == "engine 'pybullet' needs the Python package 'pybullet': pip install \"pitheorem[engines]\""
    )


def test_bullet_prints_no_banner():
    pytest.importorskip("pybullet", reason="pybullet is not installed (pip install 'pitheorem[engines]')")
    code = "from pitheorem.engines import simulate_rod; simulate_rod('pybullet', t_final=0.01)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=REPO)
    assert out.stdout == ""
    assert out.stderr == ""


def test_quiet_stdout_silences_both_descriptors_and_restores_them(capfd):
    import os

    from pitheorem.engines.packages import quiet_stdout

    print("before", flush=True)
    with quiet_stdout():
        os.write(1, b"C library banner on stdout\n")
        os.write(2, b"C library warning on stderr\n")
    os.write(1, b"after\n")
    os.write(2, b"after on stderr\n")
    out, err = capfd.readouterr()
    assert out == "before\nafter\n"
    assert err == "after on stderr\n"


def test_quiet_stdout_stands_aside_where_descriptors_cannot_be_copied_or_c_cannot_flush(monkeypatch):
    import ctypes
    import os

    from pitheorem.engines.packages import quiet_stdout

    def refuse(*args):
        raise OSError("no descriptors here")

    with monkeypatch.context() as patch:
        patch.setattr(os, "dup", refuse)
        with quiet_stdout():  # nothing silenced, nothing raised
            ran = True
    assert ran
    with monkeypatch.context() as patch:
        patch.setattr(ctypes, "CDLL", refuse)
        with quiet_stdout():
            ran_again = True
    assert ran_again


def test_quiet_stdout_silences_pythons_streams_too_where_they_are_not_the_descriptors():
    """A notebook's or pytest's sys.stdout is no file descriptor: what Python prints there is silenced too
    (mujoco.mjx prints a note on a missing warp on import)."""
    import contextlib
    import io

    from pitheorem.engines.packages import quiet_stdout

    seen = io.StringIO()
    with contextlib.redirect_stdout(seen), contextlib.redirect_stderr(seen):
        with quiet_stdout():
            print("not shown")
            print("nor this", file=sys.stderr)
        print("shown")
    assert seen.getvalue() == "shown\n"


def test_quiet_stdout_closes_the_copy_it_made_when_the_second_cannot_be_made(monkeypatch):
    import os

    from pitheorem.engines.packages import quiet_stdout

    made = []
    real_dup = os.dup

    def dup_once(fd):
        if made:
            raise OSError("out of descriptors")
        made.append(real_dup(fd))
        return made[-1]

    with monkeypatch.context() as patch:
        patch.setattr(os, "dup", dup_once)
        with quiet_stdout():
            ran = True
    assert ran
    assert len(made) == 1
    with pytest.raises(OSError, match=r"\[Errno 9\]"):  # EBADF: the copy of stdout was closed, not leaked
        os.fstat(made[0])


def test_an_engine_not_imported_yet_is_imported_quietly_package_by_package(monkeypatch, capfd):
    """engine_module imports each of the engine's packages in turn and returns the last (mjx: mujoco.mjx)."""
    from pitheorem.engines.registry import registered

    if not registered("mjx").installed():
        pytest.skip("mujoco-mjx is not installed (pip install 'pitheorem[mjx]')")
    import mujoco

    # as if never imported (where it was, the module and mujoco's attribute are put back after the test)
    monkeypatch.delitem(sys.modules, "mujoco.mjx", raising=False)
    monkeypatch.delattr(mujoco, "mjx", raising=False)
    module = engine_module("mjx")
    assert module.__name__ == "mujoco.mjx"
    assert sys.modules["mujoco.mjx"] is module
    assert callable(module.put_model)
    out, err = capfd.readouterr()
    assert (out, err) == ("", "")  # mujoco.mjx's note on a missing warp is not shown
    assert engine_module("mjx") is module  # imported now: the same module, nothing imported again
