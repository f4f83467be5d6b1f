"""Mutation testing of pitheorem's core modules and file readers: does the test suite notice a planted bug?

Run from the repository root (NOT part of ``make test``; it rewrites source files
one at a time and restores them)::

    nice .venv/bin/python benchmarks/mutation.py [--per-module 20] [--seed 12] [--module dimensions ...] \
        [--equivalent benchmarks/mutation_equivalent.txt]
    nice .venv/bin/python benchmarks/mutation.py --site groups:34 --tests tests/test_groups.py::test_x

Each mutant changes one place in one module, the way a slip of the keyboard
would:

=================  =========================================================
``compare``        ``<`` <-> ``<=``, ``>`` <-> ``>=``, ``==`` <-> ``!=``,
                   ``in`` <-> ``not in``, ``is`` <-> ``is not``
``arith``          ``+`` <-> ``-``, ``*`` -> ``/``, ``/`` -> ``*``, ``//`` -> ``/``,
                   ``%`` -> ``//``, ``**`` -> ``*``
``bool``           ``and`` <-> ``or``; ``not x`` -> ``x``; ``-x`` -> ``x``
``constant``       an integer ``n`` -> ``n + 1``; ``True`` <-> ``False``
``minmax``         ``min(...)`` <-> ``max(...)``
``drop-check``     ``if cond: raise ...`` -> ``if False: raise ...``
=================  =========================================================

The mutant set is bounded and reproducible: every site of these kinds in a
module is listed in source order, and ``--per-module`` of them are drawn
with a fixed seed.  Each mutant runs only the tests that exercise its module
(``TARGETS`` below, plus the module's own doctests), stopping at the first
failure; a run that exceeds ``--timeout`` seconds counts as killed (the
mutant made the code hang).  The report lists killed and surviving mutants;
a survivor is either a missing test or an equivalent mutant (one that
cannot change behaviour), which only a reader can tell apart.

Each mutant is named by its module, line and site number (its position
among the module's sites).  ``--site MODULE:INDEX`` runs just those
mutants, and ``--tests`` runs given tests instead of ``TARGETS``: together
they check that a new test kills a survivor.  ``--equivalent FILE`` reads
the survivors a reader has judged equivalent (``LABEL -- reason`` a line,
``benchmarks/mutation_equivalent.txt``) and also prints the score over the
non-equivalent mutants.  Site numbers hold only while the module's source
is unchanged.
"""

from __future__ import annotations

import argparse
import ast
import random
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "pitheorem"

#: the tests that exercise each module (fast: no simulations but the readers' loads, no docs; ``-m "not slow"``)
TARGETS = {
    "exact": [
        "tests/test_exact.py",
        "tests/test_cli.py",
        "tests/test_errors.py",
        "tests/test_system.py",
        "tests/test_dimensions.py",
    ],
    "dimensions": ["tests/test_dimensions.py", "tests/test_system.py", "tests/test_errors.py"],
    "system": ["tests/test_system.py", "tests/test_errors.py", "tests/test_groups.py", "tests/test_dimensions.py"],
    "groups": ["tests/test_groups.py", "tests/test_system.py", "tests/test_errors.py"],
    "linalg": [
        "tests/test_linalg.py",
        "tests/test_groups.py",
        "tests/test_scalesearch.py",
        "tests/test_bases.py",
        "tests/test_properties.py",
        "tests/test_equations.py",
    ],
    "bases": ["tests/test_bases.py", "tests/test_groups.py", "tests/test_properties.py", "tests/test_system.py"],
    "family": ["tests/test_family.py", "tests/test_scalesearch.py"],
    "basis_sequence": ["tests/test_basis_sequence.py", "tests/test_bases.py", "tests/test_groups.py"],
    "scalesearch": ["tests/test_scalesearch.py", "tests/test_equations.py", "tests/test_system.py"],
    "scaling": ["tests/test_scaling.py", "tests/test_scalesearch.py", "tests/test_errors.py"],
    "equations": ["tests/test_equations.py"],
    "model": ["tests/test_model.py", "tests/test_models.py", "tests/test_errors.py"],
    "models": ["tests/test_models.py", "tests/test_model.py", "tests/test_equations.py"],
    "simulation": ["tests/test_simulation.py", "tests/test_models.py", "tests/test_plotting.py"],
    # the readers of model files (their tests load URDF files in PyBullet and MuJoCo: seconds a mutant)
    "engines/fileformats/numbers": ["tests/test_engines_numbers.py", "tests/test_engines_urdf.py"],
    "engines/fileformats/urdf": ["tests/test_engines_urdf.py", "tests/test_engines_numbers.py"],
    **{
        f"formatting/{name}": ["tests/test_formatting.py", "tests/test_cli.py", "tests/test_scalesearch.py"]
        for name in ("__init__", "pieces", "text", "latex", "html", "json")
    },
}

_COMPARE_SWAP = {
    ast.Lt: ast.LtE,
    ast.LtE: ast.Lt,
    ast.Gt: ast.GtE,
    ast.GtE: ast.Gt,
    ast.Eq: ast.NotEq,
    ast.NotEq: ast.Eq,
    ast.In: ast.NotIn,
    ast.NotIn: ast.In,
    ast.Is: ast.IsNot,
    ast.IsNot: ast.Is,
}
_ARITH_SWAP = {
    ast.Add: ast.Sub,
    ast.Sub: ast.Add,
    ast.Mult: ast.Div,
    ast.Div: ast.Mult,
    ast.FloorDiv: ast.Div,
    ast.Mod: ast.FloorDiv,
    ast.Pow: ast.Mult,
}


@dataclass(frozen=True)
class Mutant:
    module: str
    index: int  # position among the module's sites, in source order
    line: int
    kind: str
    description: str


class _Mutator(ast.NodeTransformer):
    """Lists mutation sites (target=None) or applies the one numbered `target`."""

    def __init__(self, target: int | None = None):
        self.target = target
        self.sites: list[tuple[int, str, str]] = []

    def _site(self, node, kind: str, description: str) -> bool:
        """Record a site; True when it is the one to mutate."""
        self.sites.append((getattr(node, "lineno", 0), kind, description))
        return len(self.sites) - 1 == self.target

    def _skip_docstring(self, node):
        body = getattr(node, "body", None)
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            rest = [self.visit(n) for n in body[1:]]
            node.body = [body[0], *[n for n in rest if n is not None]]
            for field in ("decorator_list", "args", "bases", "keywords"):
                if hasattr(node, field):
                    value = getattr(node, field)
                    setattr(
                        node, field, [self.visit(v) for v in value] if isinstance(value, list) else self.visit(value)
                    )
            return node
        return self.generic_visit(node)

    visit_Module = visit_FunctionDef = visit_ClassDef = _skip_docstring

    def visit_AnnAssign(self, node):  # annotations are not behaviour
        if node.value is not None:
            node.value = self.visit(node.value)
        return node

    def visit_arg(self, node):
        return node

    def visit_Compare(self, node):
        self.generic_visit(node)
        for i, op in enumerate(node.ops):
            new = _COMPARE_SWAP.get(type(op))
            if new and self._site(node, "compare", f"{type(op).__name__} -> {new.__name__}"):
                node.ops[i] = new()
        return node

    def visit_BinOp(self, node):
        self.generic_visit(node)
        new = _ARITH_SWAP.get(type(node.op))
        if new and self._site(node, "arith", f"{type(node.op).__name__} -> {new.__name__}"):
            node.op = new()
        return node

    def visit_BoolOp(self, node):
        self.generic_visit(node)
        new = ast.Or if isinstance(node.op, ast.And) else ast.And
        if self._site(node, "bool", f"{type(node.op).__name__} -> {new.__name__}"):
            node.op = new()
        return node

    def visit_UnaryOp(self, node):
        self.generic_visit(node)
        if isinstance(node.op, ast.Not | ast.USub) and self._site(node, "bool", f"drop {type(node.op).__name__}"):
            return node.operand
        return node

    def visit_Constant(self, node):
        if isinstance(node.value, bool):
            if self._site(node, "constant", f"{node.value} -> {not node.value}"):
                return ast.copy_location(ast.Constant(not node.value), node)
        elif isinstance(node.value, int) and self._site(node, "constant", f"{node.value} -> {node.value + 1}"):
            return ast.copy_location(ast.Constant(node.value + 1), node)
        return node

    def visit_Call(self, node):
        self.generic_visit(node)
        if isinstance(node.func, ast.Name) and node.func.id in ("min", "max"):
            other = "max" if node.func.id == "min" else "min"
            if self._site(node, "minmax", f"{node.func.id} -> {other}"):
                node.func = ast.copy_location(ast.Name(other, ast.Load()), node.func)
        return node

    def visit_If(self, node):
        self.generic_visit(node)
        if (
            len(node.body) == 1
            and isinstance(node.body[0], ast.Raise)
            and self._site(node, "drop-check", "if ...: raise -> if False")
        ):
            node.test = ast.copy_location(ast.Constant(False), node.test)
        return node


def list_mutants(module: str) -> list[Mutant]:
    tree = ast.parse((PACKAGE / f"{module}.py").read_text())
    finder = _Mutator()
    finder.visit(tree)
    return [Mutant(module, i, line, kind, desc) for i, (line, kind, desc) in enumerate(finder.sites)]


def mutated_source(mutant: Mutant) -> str:
    tree = ast.parse((PACKAGE / f"{mutant.module}.py").read_text())
    _Mutator(mutant.index).visit(tree)
    return ast.unparse(ast.fix_missing_locations(tree))


def label(mutant: Mutant) -> str:
    """How a mutant is named in the report and in an ``--equivalent`` file."""
    return f"{mutant.module}.py:{mutant.line} site {mutant.index} [{mutant.kind}] {mutant.description}"


def read_equivalent(path: Path | None) -> dict[str, str]:
    """Known-equivalent mutants: one ``label -- reason`` a line; ``#`` starts a comment line."""
    if path is None:
        return {}
    known = {}
    for line in path.read_text().splitlines():
        if line.strip() and not line.lstrip().startswith("#"):
            key, _, reason = line.partition(" -- ")
            known[key.strip()] = reason.strip()
    return known


def run_tests(module: str, timeout: float, tests: list[str] | None = None) -> str:
    """'killed', 'survived' or 'timeout' for the module's current source."""
    cmd = [
        sys.executable,
        "-m",
        "pytest",
        "-x",
        "-q",
        "-p",
        "no:cacheprovider",
        "-p",
        "no:randomly",
        "--hypothesis-seed=0",
        "-m",
        "not slow",
        *(tests or [str(PACKAGE / f"{module}.py"), *TARGETS[module]]),
    ]
    try:
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=timeout, check=False)
    except subprocess.TimeoutExpired:
        return "timeout"
    return "survived" if proc.returncode == 0 else "killed"


def chosen_mutants(args) -> list[Mutant]:
    """The ``--site`` mutants, or ``--per-module`` drawn from each module with the seed."""
    if args.site:
        picked = []
        for spec in args.site:
            module, _, index = spec.partition(":")
            picked.append(list_mutants(module)[int(index)])
        return picked
    picked = []
    for module in args.module:
        every = list_mutants(module)
        picked += sorted(
            random.Random(f"{args.seed}:{module}").sample(every, min(args.per_module, len(every))),
            key=lambda m: m.index,
        )
        print(f"-- {module}: {min(args.per_module, len(every))} of {len(every)} sites", flush=True)
    return picked


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--per-module", type=int, default=20, help="mutants drawn per module (default 20)")
    parser.add_argument("--seed", type=int, default=12, help="seed of the draw (default 12)")
    parser.add_argument("--module", nargs="*", default=sorted(TARGETS), choices=sorted(TARGETS))
    parser.add_argument(
        "--site",
        nargs="*",
        default=(),
        metavar="MODULE:INDEX",
        help="run only these mutants (the site numbers the report prints)",
    )
    parser.add_argument(
        "--tests",
        nargs="*",
        default=None,
        help="run these tests instead of the module's TARGETS (to check that a new test kills)",
    )
    parser.add_argument(
        "--equivalent",
        type=Path,
        default=None,
        help="file of known-equivalent mutants ('LABEL -- reason' a line); the score leaves them out",
    )
    parser.add_argument("--timeout", type=float, default=120.0, help="seconds per mutant run (default 120)")
    args = parser.parse_args(argv)
    known = read_equivalent(args.equivalent)

    chosen = chosen_mutants(args)
    for module in dict.fromkeys(m.module for m in chosen):  # the unmutated code must pass its own selection
        if run_tests(module, args.timeout, args.tests) != "survived":
            print(f"the tests of {module} fail before any mutation; fix them first", file=sys.stderr)
            return 2
    results: list[tuple[Mutant, str]] = []
    start = time.perf_counter()
    for mutant in chosen:
        path = PACKAGE / f"{mutant.module}.py"
        original = path.read_text()
        try:
            path.write_text(mutated_source(mutant))
            outcome = run_tests(mutant.module, args.timeout, args.tests)
        finally:
            path.write_text(original)
        results.append((mutant, outcome))
        print(f"{outcome:8s} {label(mutant)}", flush=True)
    killed = sum(1 for _, o in results if o != "survived")
    survivors = [m for m, o in results if o == "survived"]
    equivalent = [m for m in survivors if label(m) in known]
    scored = len(results) - len(equivalent)
    print(
        f"\n{killed} of {len(results)} mutants killed ({100 * killed / max(len(results), 1):.1f}%) "
        f"in {time.perf_counter() - start:.0f} s"
    )
    if known:
        print(
            f"{len(equivalent)} survivors are known equivalent; {killed} of {scored} non-equivalent mutants "
            f"killed ({100 * killed / max(scored, 1):.1f}%)"
        )
    if survivors:
        print("survivors (missing tests, or equivalent mutants):")
        for m in survivors:
            reason = known.get(label(m))
            print(f"  {label(m)}" + (f"  [equivalent: {reason}]" if reason else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
