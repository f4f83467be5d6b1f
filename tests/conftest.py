"""Shared fixtures and oracles: the white paper's systems, broken model files, a matplotlib guard, and
independent oracles (sympy's exact rank and solutions, loops over every subset) that several test files
check pitheorem against."""

from __future__ import annotations

import functools
import os
import subprocess
import sys
from collections import Counter
from fractions import Fraction
from itertools import combinations
from math import gcd, lcm
from pathlib import Path

import matplotlib
import pytest
import sympy
from hypothesis import settings
from hypothesis import strategies as st
from sympy import QQ
from sympy.polys.matrices import DomainMatrix

import pitheorem as pt

matplotlib.use("Agg")

# CI (CI=true, as .ci/run is run there) draws hypothesis's examples from a fixed seed, so that a red
# build is the code's doing and reproduces; locally each run explores new examples (a failure found so
# is kept as an @example beside its property)
settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")


REPO = Path(__file__).resolve().parents[1]


REFERENCE = REPO.parent / "shared" / "reference"


if str(REPO) not in sys.path:  # lets tests import matlab_ports/ and benchmarks/
    sys.path.insert(0, str(REPO))

# JAX's compiled programs (MJX's batch runner: seconds to tens of seconds of XLA on the CPU) are kept in the
# environment's build folder, as Warp's kernels are (tests/test_engines_warp.py): the other xdist worker and
# the next run of the suite load a program instead of compiling it again.  A loaded program is the one
# compiled (JAX keys it by the program, its shapes, the flags and the versions), so runs are unchanged.
os.environ.setdefault("JAX_COMPILATION_CACHE_DIR", str(Path(sys.prefix) / "jax-cache"))
# XLA's backend without LLVM's optimisation passes: a cold compile of MJX's step takes a third less CPU, and
# a run of the tests' few steps no longer.  The properties tested (a copy bit for bit at s = 4, within the
# float32 yardstick at s = 10) hold for any deterministic program: both runs are the same compiled program.
os.environ.setdefault("XLA_FLAGS", "--xla_backend_optimization_level=0")


def untraced(function):
    """`function`, called with Python's trace function off and then put back as it was.

    Coverage measures pitheorem through that trace function, which Python calls at every call of every
    function, pitheorem's or not.  An engine stepped from Python (MJWarp launches a few hundred kernels a
    step, each through several calls of Warp's launch code) ran 2.5 times slower traced, for lines coverage
    does not measure.  Wrapped around such a step, nothing of pitheorem runs untraced.
    """

    @functools.wraps(function)
    def call(*args, **kwargs):
        tracer = sys.gettrace()
        sys.settrace(None)
        try:
            return function(*args, **kwargs)
        finally:
            sys.settrace(tracer)

    return call


@pytest.fixture(scope="module")
def mjx_untraced():
    """MJX's step, data and model making without coverage's tracing (:func:`untraced`): JAX traces MJX's
    Python once per program, which coverage made twice as slow; pitheorem's own lines are still measured."""
    mjx = pytest.importorskip("mujoco.mjx", reason="mujoco-mjx is not installed (pip install 'pitheorem[mjx]')")
    with pytest.MonkeyPatch.context() as patch:
        for name in ("step", "make_data", "put_model"):
            patch.setattr(mjx, name, untraced(getattr(mjx, name)))
        yield


#: the test files that take longest, longest first, sent to xdist's workers before the others: each worker
#: takes the next file when it is nearly done with its last, so that sending the long ones first leaves the
#: short ones to even out the end.  Seconds of CPU under ``make coverage`` on a fresh clone (2026-11-28): MJX
#: 47, Warp 38 (both mostly compiling with empty caches: JAX tracing and XLA compiling MJX's step, Warp its
#: kernels), the command line 29, the verdicts' causes 25, the corpus 18, SUPERball 11, the fuzz 8.  By its own
#: rule (the files with the most tests first) xdist sent the engines' files last, and the suite waited at its
#: end for the Warp file's compile.
FIRST = (
    "tests/test_engines_mjx.py",
    "tests/test_engines_warp.py",
    "tests/test_engines_cli.py",
    "tests/test_engines_diagnose.py",
    "tests/test_engines_corpus.py",
    "tests/test_engines_superball.py",
    "tests/test_fuzz.py",
)


def pytest_configure(config):
    if getattr(config.option, "dist", "no") in ("loadfile", "loadscope"):
        config.option.loadscopereorder = False  # the workers' order below, not xdist's by the number of tests


def pytest_collection_modifyitems(config, items):
    """On an xdist worker: the files of :data:`FIRST`, then the others by their number of tests (xdist's rule)."""
    if not hasattr(config, "workerinput"):
        return
    files = {id(item): item.nodeid.split("::")[0] for item in items}
    counts = Counter(files.values())
    items.sort(key=lambda item: (FIRST.index(f) if (f := files[id(item)]) in FIRST else len(FIRST), -counts[f]))


#: the paper's hinged rod (Section 2.1) with force and torque, as name -> formula
ROD = {name: str(dim) for name, dim in pt.models.rod_system().dimensions.items()}


#: the NTRT SUPERball CONFIG list of Section 4, plus m and l, and the Corde moduli
SUPERBALL = {name: str(dim) for name, dim in pt.models.superball_parameters().dimensions.items()}


#: the paper's hinged rod as a model (its equations, defaults and initial state)
HINGED_ROD = pt.models.hinged_rod()


#: the paper's Figure 5 scaling: g by s, l by 1/s with m and k_theta held, hence c_theta by 1/s and t by 1/s
FIG5 = pt.search(HINGED_ROD.system, scale={"g": 1, "l": -1}, fixed=("m", "k_theta")).scalings[0]


#: every minimal scaling of g by s that leaves time alone
TIME_FREE = pt.search(HINGED_ROD.system, scale={"g": 1}).scalings


#: Formulas the parser refuses, each with the culprit its message must name: Dimension.parse
#: (test_dimensions) and System (test_system) are checked on them.
BAD_FORMULAS = [
    # (formula, culprit that must appear in the message)
    ("M L^^2", "'^'"),
    ("M L^", "the end of the formula"),
    ("M L^x", "'x'"),
    ("kg", "'kg'"),
    ("M $ L", "'$'"),
    ("M L^(1/0)", "division by zero"),
    ("M (L", "')'"),
    ("M L)", "')'"),
    ("2 M", "'2'"),
    ("M / ", "formula ends too early"),
    ("* M", "'*'"),
    ("M L^(1/2", "')'"),
    ("m", "'m'"),
    ("M,L", "','"),
    ("L^2.5.1", "'.1'"),
    ("Length", "'Length'"),
]

#: Broken model files, each with what its one-line message must say: the reader
#: (test_modelfile) and the command line (test_cli) are checked on every one.
BROKEN_MODEL_FILES = {
    "bad_toml": ('[variables]\nm = { dimension = "M"\n', ["line 2", "invalid TOML"]),
    "bad_toml_value": ("[variables]\nm = = 1\n", ["line 2", "invalid TOML"]),
    "not_utf8": ("\udcff[variables]\n", ["not UTF-8"]),
    "missing_variables": ('name = "x"\n', ["no [variables]"]),
    "variables_not_table": ("variables = 3\n", ["variables", "must be a table", "3"]),
    "empty_variables": ("[variables]\n", ["[variables]", "empty"]),
    "unknown_top_key": ('nmae = "x"\n[variables]\nl = { dimension = "L" }\n', ["'nmae'", "did you mean 'name'"]),
    "unknown_key": ('[variables]\nl = { dimension = "L", vaule = 2 }\n', ["variable 'l'", "'vaule'", "'value'"]),
    "unknown_key_dim": ('[variables]\nl = { dim = "L" }\n', ["variable 'l'", "'dim'"]),
    "both": ('[variables]\nl = { dimension = "L", unit = "m" }\n', ["variable 'l'", "both dimension and unit"]),
    "neither": ("[variables]\nl = { value = 2 }\n", ["variable 'l'", "neither dimension nor unit"]),
    "unknown_dimension": ('[variables]\nq = { dimension = "Q" }\n', ["variable 'q'", "'Q'"]),
    "bad_dimension_syntax": ('[variables]\nm = { dimension = "M L^^2" }\n', ["variable 'm'", "'M L^^2'", "position 4"]),
    "dimension_not_string": ("[variables]\nq = { dimension = 1 }\n", ["variable 'q'", "string"]),
    "outside_base_dimensions": (
        'base_dimensions = ["M", "L"]\n[variables]\nt = { dimension = "T" }\n',
        ["variable 't'", "unknown base dimension 'T'", "M, L"],
    ),
    "bad_base_dimensions": (
        'base_dimensions = "MLT"\n[variables]\nm = { dimension = "M" }\n',
        ["base_dimensions", "'MLT'"],
    ),
    "bad_unit": ('[variables]\nq = { unit = "furlongz" }\n', ["variable 'q'", "furlongz"]),
    "duplicate": (
        '[variables]\nm = { dimension = "M" }\nm = { dimension = "L" }\n',
        ["line 3", "variable 'm'", "twice"],
    ),
    "duplicate_table": (
        '[variables.m]\ndimension = "M"\n[variables.m]\ndimension = "L"\n',
        ["line 3", "variable 'm'", "twice"],
    ),
    "duplicate_key_in_entry": ('[variables]\nm = { dimension = "M", dimension = "L" }\n', ["line 2"]),
    "bad_role": ('[variables]\nt = { dimension = "T", role = "clock" }\n', ["variable 't'", "'clock'", "time"]),
    "time_not_T": (
        '[variables]\nl = { dimension = "L", role = "time" }\n',
        ["variable 'l'", "dimension L", "dimension T"],
    ),
    "two_times": (
        '[variables]\nt = { dimension = "T", role = "time" }\ntau = { dimension = "T", role = "time" }\n',
        ["variable 'tau'", "'t'", "at most one"],
    ),
    "value_not_number": ('[variables]\nm = { dimension = "M", value = "heavy" }\n', ["variable 'm'", "'heavy'"]),
    "value_bool": ('[variables]\nm = { dimension = "M", value = true }\n', ["variable 'm'", "true"]),
    "value_list": ('[variables]\nm = { dimension = "M", value = [1, 2] }\n', ["variable 'm'", "number"]),
    "value_zero_denominator": ('[variables]\nm = { dimension = "M", value = "1/0" }\n', ["variable 'm'", "'1/0'"]),
    "value_nan": ('[variables]\nm = { dimension = "M", value = nan }\n', ["variable 'm'", "finite", "nan"]),
    "entry_not_table": ('[variables]\nm = "M"\n', ["variable 'm'", "must be a table"]),
    "bad_name": ('[variables]\nk-theta = { dimension = "M" }\n', ["variable 'k-theta'", "valid name", "k_theta"]),
    "name_not_string": ('name = 3\n[variables]\nm = { dimension = "M" }\n', ["name must be a string"]),
    "bad_description": ('[variables]\nm = { dimension = "M", description = 3 }\n', ["variable 'm'", "description"]),
}


def broken_model_file(folder: Path, case: str) -> tuple[Path, list[str]]:
    """Write the broken model file `case` of :data:`BROKEN_MODEL_FILES` into `folder`; its path and fragments."""
    text, fragments = BROKEN_MODEL_FILES[case]
    path = folder / f"{case}.toml"
    path.write_bytes(text.encode("utf-8", errors="surrogateescape"))  # not_utf8 holds a stray byte
    return path, fragments


@pytest.fixture
def rod() -> pt.System:
    return pt.System(ROD)


@pytest.fixture
def superball() -> pt.System:
    return pt.System(SUPERBALL)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


#: the base dimensions of random systems, in order
BASES = ("M", "L", "T", "Theta")


PRIMES = (2, 3, 5, 7, 11, 13, 17, 19, 23, 29)


#: exponents that are fractions with small denominators
rational_exponent = st.fractions(min_value=-2, max_value=2, max_denominator=3)


def columns_of(system: pt.System) -> list[list[Fraction]]:
    return [[system.dimension(v).exponent_of(b) for b in system.base_dimensions] for v in system.variables]


def qq_matrix(rows) -> DomainMatrix:
    """Rows of Fractions or ints as sympy's exact matrix over the rationals.

    The oracles work in sympy's DomainMatrix (the exact engine under sympy.Matrix, without its
    conversions: a third of the time, and fewer Python calls for coverage to trace), never in
    pitheorem's own arithmetic.
    """
    rows = [[QQ(f.numerator, f.denominator) for f in map(Fraction, row)] for row in rows]
    return DomainMatrix(rows, (len(rows), len(rows[0]) if rows else 0), QQ)


def sympy_rank(cols) -> int:
    return qq_matrix(cols).rank() if cols else 0


def oracle_bases(system: pt.System, exclude=(), require=()) -> list[tuple[str, ...]]:
    cols = columns_of(system)
    r = sympy_rank(cols)
    found = []
    for subset in combinations(range(len(cols)), r):
        names = tuple(system.variables[j] for j in subset)
        if set(names) & set(exclude) or not set(require) <= set(names):
            continue
        if sympy_rank([cols[j] for j in subset]) == r:
            found.append(names)
    return found


def oracle_groups(system: pt.System, repeating) -> list[tuple[tuple[str, int], ...]]:
    """Each non-repeating variable over the repeaters, solved by sympy, as primitive integers."""
    cols = columns_of(system)
    rep = [system.variables.index(n) for n in repeating]
    d_r = sympy.Matrix([[sympy.Rational(str(cols[j][i])) for j in rep] for i in range(len(system.base_dimensions))])
    out = []
    for j, name in enumerate(system.variables):
        if j in rep:
            continue
        target = sympy.Matrix([sympy.Rational(str(x)) for x in cols[j]])
        x = d_r.solve(target) if rep else sympy.Matrix([])
        exps = {n: Fraction(0) for n in system.variables}
        exps[name] = Fraction(1)
        for k, n in enumerate(repeating):
            exps[n] -= Fraction(int(x[k].p), int(x[k].q))
        den = lcm(*(e.denominator for e in exps.values()))
        ints = {n: int(e * den) for n, e in exps.items()}
        g = gcd(*ints.values())
        out.append(tuple((n, ints[n] // g) for n in system.variables if ints[n]))
    return out


def oracle_search(system: pt.System, scale: dict, fixed) -> list[tuple[Fraction, ...]]:
    """Support-minimal solutions by trying every set of free variables held at zero, with sympy."""
    d_t = qq_matrix(columns_of(system))  # a = D^T u
    free = [n for n in system.variables if n not in scale and n not in fixed]
    points = set()
    for size in range(len(free) + 1):
        for zero in combinations(free, size):
            held = {
                **{n: Fraction(p) for n, p in scale.items()},
                **dict.fromkeys([*fixed, *zero], Fraction(0)),
            }
            point = _unique_image(d_t, [system.variables.index(n) for n in held], list(held.values()))
            if point is not None:
                points.add(point)
    supports = {p: frozenset(i for i, x in enumerate(p) if x) for p in points}
    minimal = [p for p in points if not any(supports[q] < supports[p] for q in points)]
    keys = [(len(supports[p]), sorted(supports[p])) for p in minimal]
    assert len({repr(key) for key in keys}) == len(keys), "two minimal points with one support"
    return sorted(minimal, key=lambda p: (len(supports[p]), sorted(supports[p])))


def _unique_image(d_t: DomainMatrix, rows: list[int], values: list[Fraction]) -> tuple[Fraction, ...] | None:
    """a = D^T u where u solves the rows of D^T given (row i of u's image equal to its value), if that a is
    one point: None where the rows contradict each other or leave a free direction that moves a."""
    m = d_t.shape[1]
    held = d_t.extract(rows, range(m))
    reduced, pivots = held.hstack(qq_matrix([[v] for v in values])).rref()
    if m in pivots:  # a row 0 = nonzero: no solution
        return None
    if len(pivots) < m and not (d_t * held.nullspace().transpose()).is_zero_matrix:
        return None  # a free direction of u that moves a: the held rows do not pin a point
    u = [QQ(0)] * m  # the free unknowns at zero
    for i, j in enumerate(pivots):
        u[j] = reduced[i, m].element
    a = d_t * DomainMatrix([[x] for x in u], (m, 1), QQ)
    return tuple(Fraction(int(a[i, 0].element.numerator), int(a[i, 0].element.denominator)) for i in range(a.shape[0]))


@st.composite
def systems(draw, exponent=None, max_vars=8, max_bases=4):
    """A random system of up to `max_vars` variables over the first 1 to `max_bases` of BASES."""
    exponent = st.integers(-3, 3) if exponent is None else exponent
    k = draw(st.integers(1, max_bases))
    n = draw(st.integers(1, max_vars))
    columns = draw(st.lists(st.lists(exponent, min_size=k, max_size=k), min_size=n, max_size=n))
    return pt.System({f"x{j}": pt.Dimension(zip(BASES[:k], col, strict=True)) for j, col in enumerate(columns)})


def dimension_of_group(system: pt.System, group: pt.PiGroup) -> dict[str, Fraction]:
    """The nonzero base exponents of a group's product, multiplied out here with Fractions.

    Not with Dimension's own algebra: that is code under test, and a group's exponents times its
    variables' may pass the exponent limits that every Dimension is held to (issue 33).
    """
    total: dict[str, Fraction] = {}
    for name, power in group.exponents.items():
        for base, p in system.dimension(name).exponents.items():
            total[base] = total.get(base, Fraction(0)) + p * power
    return {base: p for base, p in total.items() if p != 0}


def loaded_after(code: str, watch=("numpy", "scipy", "matplotlib")) -> set[str]:
    """Which of the modules `watch` (numpy, scipy and matplotlib) a fresh interpreter has loaded after running `code`."""
    probe = code + f"\nimport sys\nprint('loaded:', *(m for m in {tuple(watch)!r} if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    return set(out.stdout.strip().splitlines()[-1].split()[1:])


def plain_mujoco_runs_equal(model, copy, scaling, s, n_steps: int, change=None, controls=None) -> bool:
    """An oracle that does not use pitheorem's runs: by hand in plain MuJoCo.

    The compiled models of `model` and of its scaled `copy` are copied, each changed alike by
    ``change(mjmodel)`` (a counter-run's change: a flag off, a geom out of collision, an equality
    inactive), stepped `n_steps` times from rest with ``mj_step``, and the copy's positions and
    velocities, divided by ``s`` to the power of each one's dimension under `scaling`, are held to the
    original's bit for bit.  `controls`, a function of the step's start time, gives the original's
    inputs; the copy's are those times ``s`` to the power of each input's dimension.
    """
    import numpy as np

    dims = model.runner.coordinate_dimensions()[1]
    factors = np.array([float(s) ** float(scaling.exponent_of(d)) for d in dims])
    inputs = np.array([float(s) ** float(scaling.exponent_of(d)) for d in model.inputs()[0]])
    ran = plain_mujoco_run(model.runner.mjmodel, n_steps, controls, 1.0, change=change)
    copied = plain_mujoco_run(copy.runner.mjmodel, n_steps, controls, inputs, change=change)
    return bool(np.array_equal(ran, copied / factors[: ran.shape[1]]))


def plain_mujoco_run(compiled, n_steps: int, controls=None, times=1.0, *, change=None, right=None, fields=()):
    """Positions and velocities after each of `n_steps` steps of ``mj_step``, from rest, in plain MuJoCo.

    A copy of the compiled model `compiled` is run: its `fields` first set to those of `right` (an
    EngineModel: a copy's numbers set right), then changed by ``change(m)``; ``controls(t)`` (of the
    step's start time) times `times` gives the inputs.
    """
    import copy as copy_module

    import mujoco
    import numpy as np

    m = copy_module.copy(compiled)
    for field in fields:
        getattr(m, field)[:] = getattr(right.runner.mjmodel, field)
    if change is not None:
        change(m)
    d = mujoco.MjData(m)
    rows = []
    for i in range(n_steps):
        if controls is not None:
            d.ctrl[:] = np.asarray(controls(i * m.opt.timestep)) * times
        mujoco.mj_step(m, d)
        rows.append(np.concatenate([d.qpos, d.qvel]))
    return np.array(rows)


def expected_verdict(rep) -> str:
    """The verdict read off a report's fields (passed, inconclusive, exact), as verify's report defines it."""
    if not rep.passed:
        return "not similar"
    if rep.inconclusive:
        return "inconclusive"
    return "exact" if rep.exact else "similar"


def recorded_batches(monkeypatch, runner_class) -> list:
    """Patch ``runner_class.run_many`` to record each batch's jobs (a list per call) before running it.

    Returns the record, which fills as the test runs; ``monkeypatch.undo()`` restores the method.
    """
    batches: list = []
    run_many = runner_class.run_many

    def recording(self, n_steps, jobs):
        batches.append(list(jobs))
        return run_many(self, n_steps, jobs)

    monkeypatch.setattr(runner_class, "run_many", recording)
    return batches
