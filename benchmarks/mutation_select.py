"""The MJCF walker's mutants chosen by the rule of ``MUTATION.md`` (issue 33), as mutmut names them.

A mutant is chosen when it mutates one of the ``_Walker`` methods in ``METHODS`` and the line of the
original that it changes holds one of ``TOKENS`` (a dimension, an entry's slice, a joint's coordinate
or force, an actuator's length, force, control or activation).  The chosen names are sorted, and
every ``--every``-th is printed, from the ``--first``-th (counting from 1).

Run it in the folder where mutmut has generated its mutants (``mutants/`` beside ``pyproject.toml``,
with ``only_mutate`` naming ``pitheorem/engines/fileformats/mjcf.py``)::

    python benchmarks/mutation_select.py --every 20 --first 6 > names.txt
    nice -n 19 mutmut run --max-children 1 $(cat names.txt)

The second sample of ``MUTATION.md`` is ``--every 20 --first 6`` (79 of 1,571 names); the first was
``--every 40 --first 1`` on the walker as it was then (commit 7f79ed3).
"""

from __future__ import annotations

import argparse
import ast
import difflib
import json
import re
from pathlib import Path

METHODS = (
    "actuator actuator_target add_solimp add_solref body compiler control_dimension equality friction geom "
    "joint muscle option sensor sensor_dimension spring_and_drive tendon"
).split()
TOKENS = (
    "dim(",
    "_L",
    "_M",
    "_T",
    "_ONE",
    "_FORCE",
    "_TORQUE",
    ".q",
    ".force",
    ".per(",
    "slice(",
    "length",
    "force",
    "ctrl",
    "act_dim",
    "rate",
)
MODULE = "pitheorem.engines.fileformats.mjcf"


def _functions(source: str) -> dict[str, list[str]]:
    """The lines of every function and method of mutmut's mutated file, by its (mangled) name."""
    lines, out = source.splitlines(), {}
    for top in ast.parse(source).body:
        for node in [top, *(top.body if isinstance(top, ast.ClassDef) else [])]:
            if isinstance(node, ast.FunctionDef):
                out[node.name] = lines[node.lineno - 1 : node.end_lineno]
    return out


def chosen(mutants: Path) -> list[str]:
    """Every mutant name of the rule, sorted."""
    path = mutants / "pitheorem" / "engines" / "fileformats" / "mjcf.py"
    functions = _functions(path.read_text())
    keys = json.loads(Path(f"{path}.meta").read_text())["exit_code_by_key"]
    out = []
    for key in keys:
        short = key.rsplit(".", 1)[1]
        match = re.fullmatch(r"xǁ_Walkerǁ(\w+)__mutmut_\d+", short)
        if not match or match.group(1) not in METHODS:
            continue
        original = functions[f"xǁ_Walkerǁ{match.group(1)}__mutmut_orig"][1:]
        changed = [
            line[1:]
            for line in difflib.unified_diff(original, functions[short][1:], lineterm="", n=0)
            if line.startswith("-") and not line.startswith("---")
        ]
        if any(token in line for line in changed for token in TOKENS):
            out.append(key)
    return sorted(out)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mutants", type=Path, default=Path("mutants"), help="mutmut's folder of mutants")
    parser.add_argument("--every", type=int, default=1, help="print every n-th name")
    parser.add_argument("--first", type=int, default=1, help="the first name printed, counting from 1")
    args = parser.parse_args(argv)
    names = chosen(args.mutants)
    print("\n".join(names[args.first - 1 :: args.every]))


if __name__ == "__main__":
    main()
