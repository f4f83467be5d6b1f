"""Every command of the command line on a corpus of model files: exit codes, first lines, repeats.

Run it as a script for the whole corpus (every shipped example, every gymnasium MuJoCo model, every
pybullet_data URDF that PyBullet loads, the thousand generated files of ``random_urdfs`` left out)::

    .venv/bin/python tests/robots/cli_corpus.py [--only SUBSTRING] [--urdf-limit N]

Each command runs with the least its request needs (:data:`REQUESTS`; ``convert`` fits units for a
URDF and changes them for an MJCF file).  It prints one line per file and command that breaks a rule,
then a count of files, and per command its exit codes, its longest first line and how many runs
repeated a line; its exit status is the number of files with a problem (capped at 100).  ``tests/test_engines_cli.py`` runs the same rules
(:func:`problems`) on a sample that fits the test suite's time.

The rules (issue 32, "Done when"): every command exits 0, or 1 where its help documents 1 (``search``
and ``apply`` when no scaling exists, ``verify`` when the copy is not similar, ``sweep`` when some copy
is not similar or refused, ``check`` when a number
is beyond or near a threshold, ``convert --fit`` when no units clear every threshold); the first line
of what it prints is under 120 characters; and no line comes twice, on stdout or on stderr.
"""

from __future__ import annotations

import contextlib
import io
import sys
from collections import Counter
from pathlib import Path

#: the request each command is given: the least it needs
REQUESTS = {
    "params": [],
    "groups": [],
    "bases": [],
    "search": ["--scale", "g=1"],
    "apply": ["--scale", "g=1", "--s", "4"],
    "verify": ["--scale", "g=1", "--s", "4", "--duration", "0.2"],
    "sweep": ["--scale", "g=1", "--s", "0.25", "4", "--duration", "0.2"],
    "check": [],
}
#: the commands whose help documents exit code 1
MAY_EXIT_1 = {"search", "apply", "verify", "sweep", "check", "convert"}


def commands(path: str) -> list[list[str]]:
    """Each command line to run on `path` (a file or ``example:NAME``)."""
    name = path.lower()
    if name.endswith(".toml") or not name.endswith((".xml", ".urdf")):
        verbs = ("params", "groups", "bases", "search", "apply")  # TOML: the engine commands refuse it by design
        return [[verb, path, *REQUESTS[verb]] for verb in verbs]
    lines = [[verb, path, *request] for verb, request in REQUESTS.items()]
    # a URDF file is in SI by its specification: convert fits units for it, an MJCF file changes them too
    lines.append(
        ["convert", path, "--fit", "pybullet"] if name.endswith(".urdf") else ["convert", path, "--units", "L=mm"]
    )
    return lines


def run(argv: list[str]) -> tuple[int, str, str]:
    """`argv` run through :func:`pitheorem.cli.main`: exit code, stdout, stderr."""
    import warnings

    from pitheorem.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
        warnings.resetwarnings()  # each command as a fresh process shows its warnings: once each
        code = main(argv)
    return code, out.getvalue(), err.getvalue()


def problems(argv: list[str], seen: dict | None = None) -> list[str]:
    """What `argv` breaks of the rules (an empty list when none).

    `seen`, if given, gathers per command what was measured: its exit codes, its longest first line
    and how many runs repeated a line (the script's summary).
    """
    code, out, err = run(argv)
    if seen is not None:
        first = (out.strip().splitlines() or err.strip().splitlines() or [""])[0]
        row = seen.setdefault(argv[0], {"exit": {}, "longest first line": 0, "runs repeating a line": 0})
        row["exit"][code] = row["exit"].get(code, 0) + 1
        row["longest first line"] = max(row["longest first line"], len(first))
        row["runs repeating a line"] += any(
            len(lines) != len(set(lines))
            for lines in ([x for x in text.splitlines() if x.strip()] for text in (out, err))
        )
    found = []
    if code not in ((0, 1) if argv[0] in MAY_EXIT_1 else (0,)):
        found.append(f"exit {code}: {(err.strip().splitlines() or [''])[0][:200]}")
    first = (out.strip().splitlines() or err.strip().splitlines() or [""])[0]
    if len(first) >= 120:
        found.append(f"first line of {len(first)} characters: {first[:100]}...")
    for stream, text in (("stdout", out), ("stderr", err)):
        lines = [line for line in text.splitlines() if line.strip()]
        repeated = sorted({line for line in lines if lines.count(line) > 1})
        if repeated:
            found.append(f"{stream} repeats {len(repeated)} line(s), the first: {repeated[0][:120]}")
    return found


def corpus(urdf_limit: int | None = None) -> list[str]:
    """Every shipped example, gymnasium MuJoCo model and pybullet_data URDF that PyBullet loads."""
    from pitheorem.modelfile import examples

    files = [f"example:{name}" for name in examples()]
    with contextlib.suppress(ImportError):
        import gymnasium

        files += sorted(str(p) for p in (Path(gymnasium.__file__).parent / "envs" / "mujoco" / "assets").glob("*.xml"))
    with contextlib.suppress(ImportError):
        import pybullet_data

        data = Path(pybullet_data.getDataPath())
        # the thousand generated files of random_urdfs are left out: one generator, one kind of file
        urdfs = sorted(p for p in data.rglob("*.urdf") if "random_urdfs" not in p.relative_to(data).parts)
        files += [str(p) for p in urdfs if pybullet_loads(p)][:urdf_limit]
    return files


def pybullet_loads(path: Path) -> bool:
    """Whether PyBullet itself loads `path` (in DIRECT mode, with its own defaults)."""
    import pybullet

    client = pybullet.connect(pybullet.DIRECT)
    try:
        with open_fd_silenced():
            pybullet.loadURDF(str(path), physicsClientId=client)
    except pybullet.error:
        return False
    finally:
        pybullet.disconnect(client)
    return True


@contextlib.contextmanager
def open_fd_silenced():
    """PyBullet's C++ messages on file descriptors 1 and 2, dropped."""
    import os

    saved = [os.dup(1), os.dup(2)]
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(null, 1)
        os.dup2(null, 2)
        yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (*saved, null):
            os.close(fd)


def main(argv: list[str] | None = None) -> int:
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", help="only files whose path contains this")
    parser.add_argument("--urdf-limit", type=int, help="at most this many pybullet_data URDF files")
    args = parser.parse_args(argv)
    files = [f for f in corpus(args.urdf_limit) if args.only is None or args.only in f]
    bad, seen = 0, {}
    for path in files:
        found = [f"{line[0]}: {p}" for line in commands(path) for p in problems(line, seen)]
        bad += bool(found)
        for text in found:
            print(f"{path}: {text}", flush=True)
    kinds = Counter("example" if f.startswith("example:") else "urdf" if f.endswith(".urdf") else "mjcf" for f in files)
    print(
        f"{len(files)} files ({kinds['example']} shipped examples, {kinds['mjcf']} gymnasium MJCF, "
        f"{kinds['urdf']} pybullet_data URDF), {bad} with a problem"
    )
    for verb, row in seen.items():
        codes = ", ".join(f"exit {code}: {n}" for code, n in sorted(row["exit"].items()))
        print(
            f"  {verb:8} {codes}; longest first line {row['longest first line']}; "
            f"runs repeating a line {row['runs repeating a line']}"
        )
    return min(bad, 100)


if __name__ == "__main__":
    sys.exit(main())
