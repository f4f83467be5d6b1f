"""The fast paths of issue 13 give the exact answers, in the same order, as independent oracles.

The oracles use sympy's exact matrices and plain loops over every subset:
nothing from pitheorem's linear algebra, basis enumeration or search.
"""

from __future__ import annotations

import subprocess
import sys
import types
from collections.abc import Sequence
from fractions import Fraction
from itertools import combinations
from math import gcd, lcm
from unittest import mock

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem import bases as bases_module
from pitheorem import family as family_module
from pitheorem.basis_sequence import BasisSequence

BASES = ("M", "L", "T", "Theta")
PRIMES = (2, 3, 5, 7, 11, 13, 17, 19, 23, 29)


# -- oracles -------------------------------------------------------------------------------
def columns_of(system: pt.System) -> list[list[Fraction]]:
    return [[system.dimension(v).exponent_of(b) for b in system.base_dimensions] for v in system.variables]


def sympy_rank(cols) -> int:
    return sympy.Matrix([[sympy.Rational(x.numerator, x.denominator) for x in c] for c in cols]).rank() if cols else 0


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
    cols = columns_of(system)
    d_t = sympy.Matrix([[sympy.Rational(str(x)) for x in c] for c in cols])  # a = D^T u
    free = [n for n in system.variables if n not in scale and n not in fixed]
    points = set()
    for size in range(len(free) + 1):
        for zero in combinations(free, size):
            held = {**{n: sympy.Rational(str(Fraction(p))) for n, p in scale.items()},
                    **dict.fromkeys([*fixed, *zero], sympy.Integer(0))}
            rows = sympy.Matrix([d_t.row(system.variables.index(n)) for n in held])
            rhs = sympy.Matrix(list(held.values()))
            try:
                sol, _ = rows.gauss_jordan_solve(rhs)
            except ValueError:
                continue
            a = d_t * sol
            if any(x.free_symbols for x in a):
                continue
            points.add(tuple(Fraction(int(x.p), int(x.q)) for x in a))
    supports = {p: frozenset(i for i, x in enumerate(p) if x) for p in points}
    minimal = [p for p in points if not any(supports[q] < supports[p] for q in points)]
    keys = [(len(supports[p]), sorted(supports[p])) for p in minimal]
    assert len({repr(key) for key in keys}) == len(keys), "two minimal points with one support"
    return sorted(minimal, key=lambda p: (len(supports[p]), sorted(supports[p])))


# -- strategies ----------------------------------------------------------------------------
@st.composite
def systems(draw, exponent=None, max_vars=8, max_bases=4):
    exponent = st.integers(-3, 3) if exponent is None else exponent
    k = draw(st.integers(1, max_bases))
    n = draw(st.integers(1, max_vars))
    columns = draw(st.lists(st.lists(exponent, min_size=k, max_size=k), min_size=n, max_size=n))
    return pt.System({f"x{j}": pt.Dimension(zip(BASES[:k], col, strict=True)) for j, col in enumerate(columns)})


huge = st.integers(-(2**70), 2**70)
reciprocal_primes = st.sampled_from([Fraction(s, p) for p in PRIMES for s in (1, -1)] + [Fraction(0)])


# -- bases: answers and order --------------------------------------------------------------
@settings(max_examples=150, deadline=None)
@given(systems(), st.data())
def test_bases_equal_brute_force_in_order(system, data):
    exclude = tuple(data.draw(st.lists(st.sampled_from(system.variables), unique=True, max_size=2)))
    require = tuple(n for n in data.draw(st.lists(st.sampled_from(system.variables), unique=True, max_size=2))
                    if n not in exclude)
    try:
        got = system.bases(exclude=exclude, require=require)
    except (pt.DependentRepeatingSetError, pt.RepeatingCountError):
        assert sympy_rank([columns_of(system)[system.index(n)] for n in require]) < len(require)
        return
    expected = oracle_bases(system, exclude, require)
    assert got == expected
    assert list(got) == expected
    assert list(system.iter_bases(exclude=exclude, require=require)) == expected
    assert system.count_bases(exclude=exclude, require=require) == len(expected)


@pytest.mark.parametrize(("exponent", "max_vars"), [
    (huge, 6),  # entries far beyond 2^53 and int64: the float path must step aside, residues and exact rank decide
    (reciprocal_primes, 7),
], ids=["huge", "reciprocal_primes"])
@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_bases_exact_with_extreme_exponents(exponent, max_vars, data):
    system = data.draw(systems(exponent=exponent, max_vars=max_vars, max_bases=3))
    expected = oracle_bases(system)
    assert system.bases() == expected
    assert system.count_bases() == len(expected)


@settings(max_examples=40, deadline=None)
@given(systems(max_vars=9), st.integers(1, 5))
def test_small_chunks_keep_answers_and_order(system, chunk):
    # the depth-first descent in chunks of `chunk` rows visits subsets in the same order
    with mock.patch.object(bases_module, "_CHUNK", chunk):
        assert system.bases() == oracle_bases(system)
        assert system.count_bases() == len(oracle_bases(system))


@settings(max_examples=40, deadline=None)
@given(systems(max_vars=8))
def test_residue_path_equals_float_path(system):
    expected = oracle_bases(system)
    with mock.patch.object(bases_module, "float_is_exact", return_value=False):
        assert system.bases() == expected
        assert system.count_bases() == len(expected)


def test_hadamard_bound_is_computed_in_python_integers():
    big = [[2**62, 1], [1, 2**62]]
    assert bases_module.hadamard_squared(big, 2) == (2**124 + 1) ** 2
    assert not bases_module.float_is_exact(big, 2)
    assert bases_module.float_is_exact([[3, 0], [0, 4]], 2)
    assert all(sympy.isprime(p) and p < 2**31 for p in bases_module._PRIMES)


# -- issue 12's reproducers ------------------------------------------------------------------
def test_determinant_two_to_the_64_is_not_zero():
    # Exponents near 2^59 are over the exponent limit, so System refuses them by name; the
    # enumeration itself is checked on this very matrix in tests/test_edges.py.
    a, b, c = (2**27 + 1) * 2**32, (2**27 + 2) * 2**32, 2**59
    assert sympy.Matrix([[a, c], [b, a]]).det() == 2**64  # the oracle: exact, and nonzero
    rows = [[a, c], [b, a]]
    assert bases_module.count_independent_subsets(rows, [0, 1], [], 2) == 1
    with pytest.raises(pt.errors.LimitError, match="exceeds the limit"):
        pt.System({"a": {"L": a, "T": b}, "b": {"L": c, "T": a}})


@pytest.mark.parametrize("g", [Fraction(1, 3), Fraction(1, 10**9), Fraction(1, 10**12)])
def test_search_with_large_denominators_on_the_rod(g):
    rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "c_theta": "M L^2 T^-1",
                     "t": "T"})
    result = pt.search(rod, scale={"g": g}, fixed=())
    expected = oracle_search(rod, {"g": g}, ())
    assert result.n_scalings == len(expected)
    assert [s.vector for s in result.scalings] == expected


def test_denominator_over_the_limit_is_named():
    rod = pt.System({"l": "L", "g": "L T^-2", "t": "T"})
    with pytest.raises(pt.errors.LimitError, match="denominator"):
        pt.search(rod, scale={"g": Fraction(1, 10**20)}, fixed=())


def test_search_one_third_on_length_and_time():
    system = pt.System({"l": "L", "t": "T"})
    result = pt.search(system, scale={"l": Fraction(1, 3)}, fixed=())
    assert result.n_scalings == len(oracle_search(system, {"l": Fraction(1, 3)}, ())) == 1


def test_reciprocal_prime_exponents():
    variables = {f"x{p}": {"L": Fraction(1, p), "T": Fraction(1, q)} for p, q in zip(PRIMES, (*PRIMES[1:], 2), strict=True)}
    system = pt.System({**variables, "m": "M"})
    assert system.bases() == oracle_bases(system)
    assert system.count_bases() == len(oracle_bases(system))
    small = pt.System({n: variables[n] for n in ("x2", "x3", "x23", "x29")} | {"t": "T"})
    result = pt.search(small, scale={"x23": 1}, fixed=())
    assert [s.vector for s in result.scalings] == oracle_search(small, {"x23": 1}, ())


# -- BasisSequence -------------------------------------------------------------------------
def test_basis_sequence_behaves_like_the_list_it_stands_for():
    system = pt.System({"l": "L", "t": "T", "v": "L/T", "x": "L", "a": "L T^-2"})
    bases = system.bases()
    expected = oracle_bases(system)
    assert isinstance(bases, BasisSequence)
    assert isinstance(bases, Sequence)
    assert len(bases) == len(expected)
    assert [bases[i] for i in range(-len(expected), len(expected))] == expected + expected
    for s in (slice(1, 4), slice(None, None, -1), slice(0, 9, 3), slice(5, 2)):
        assert bases[s] == expected[s]
        assert list(bases[s]) == expected[s]
    with pytest.raises(IndexError):
        bases[len(expected)]
    assert bases.indices.tolist() == [[system.index(n) for n in b] for b in expected]
    with pytest.raises(ValueError, match="read-only"):
        bases.indices[0, 0] = 3  # read-only
    with pytest.raises(TypeError):
        bases[0] = ("l", "t")  # type: ignore[index]
    assert bases == expected
    assert expected == bases
    assert not (bases != expected)
    assert bases != expected[:-1]
    assert bases != expected[::-1]
    assert expected[2] in bases
    assert ("l", "x") not in bases
    assert repr(bases) == repr(expected)
    assert bases.index(expected[3]) == 3


def test_default_repeaters_need_time_when_the_rest_do_not_span():
    system = pt.System({"t": "T", "m": "M", "l": "L", "x": "L"})
    assert system.default_repeating() == ("t", "m", "l")  # the first basis: every basis holds t
    assert system.pi_groups().repeating == ("t", "m", "l")


def test_rank_zero_system_has_the_empty_basis():
    system = pt.System({"a": "1", "b": "1"})
    assert system.bases() == [()]
    assert list(system.bases()) == [()]
    assert system.count_bases() == 1
    assert system.bases().indices.shape == (1, 0)


# -- one elimination for a Pi set --------------------------------------------------------------
@settings(max_examples=100, deadline=None)
@given(systems(exponent=st.sampled_from([-2, -1, 0, 0, 1, 2, Fraction(1, 2)]), max_vars=7), st.booleans(),
       st.integers(0, 7))
def test_pi_groups_equal_sympy_solutions(system, with_time, at):
    if with_time:  # a variable of dimension time, anywhere in the order
        items = [(n, system.dimension(n)) for n in system.variables]
        items.insert(min(at, len(items)), ("t", pt.Dimension({"T": 1})))
        system = pt.System(items)
    every = oracle_bases(system)
    timelike = {n for n in system.variables if system.dimension(n) == pt.Dimension({"T": 1})}
    avoiding = [b for b in every if not timelike & set(b)]
    default = (avoiding or every)[0]
    assert system.default_repeating() == default
    groups = system.pi_groups()
    assert groups.repeating == default
    assert [tuple(g.exponents.items()) for g in groups] == oracle_groups(system, default)
    for basis in every[:3]:
        assert [tuple(g.exponents.items()) for g in system.pi_groups(repeating=basis[::-1])] == oracle_groups(
            system, basis[::-1])


# -- search in batches ---------------------------------------------------------------------
@settings(max_examples=50, deadline=None)
@given(systems(exponent=st.sampled_from([-2, -1, 0, 0, 1, 2, Fraction(1, 2)]), max_vars=6, max_bases=3),
       st.data())
def test_search_equals_brute_force_in_order(system, data):
    name = data.draw(st.sampled_from(system.variables))
    power = data.draw(st.sampled_from([1, -1, 2, Fraction(1, 3), Fraction(-3, 2)]))
    others = [n for n in system.variables if n != name]
    fixed = tuple(data.draw(st.lists(st.sampled_from(others), unique=True, max_size=2))) if others else ()
    result = pt.search(system, scale={name: power}, fixed=fixed)
    if not result.feasible:
        return
    expected = oracle_search(system, {name: power}, fixed)
    assert [s.vector for s in result.scalings] == expected
    # the exact fallback agrees, coordinates included
    with mock.patch.object(family_module, "minimal_points", return_value=None):
        exact = pt.search(system, scale={name: power}, fixed=fixed)
        assert list(exact._enumerate()) == list(result._enumerate())
    with mock.patch.object(family_module, "_MERGE_EVERY", 1), mock.patch.object(bases_module, "_CHUNK", 2):
        assert list(pt.search(system, scale={name: power}, fixed=fixed)._enumerate()) == list(result._enumerate())


def test_batched_search_takes_the_vectorised_path_and_scalings_are_units():
    system = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k": "M T^-2", "t": "T", "v": "L/T"})
    result = pt.search(system, scale={"g": 1}, fixed=())
    assert isinstance(result._enumerate(), family_module.MinimalPoints)
    for scaling in result.scalings:
        exps = scaling.vector
        unit = scaling.unit_change
        for j, n in enumerate(system.variables):
            assert exps[j] == sum(system.dimension(n).exponent_of(b) * unit[b] for b in system.base_dimensions)


# -- start-up ------------------------------------------------------------------------------
def loaded_after(code: str) -> set[str]:
    probe = code + "\nimport sys\nprint('loaded:', *(m for m in ('numpy', 'scipy', 'matplotlib') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    return set(out.stdout.strip().splitlines()[-1].split()[1:])


def test_import_loads_neither_numpy_scipy_nor_matplotlib():
    assert loaded_after("import pitheorem") == set()


def test_cli_groups_and_search_load_neither_scipy_nor_matplotlib(tmp_path):
    run = ("import sys\nfrom pitheorem.cli import main\nsys.argv = ['pitheorem', *{args!r}]\n"
           "try:\n    main()\nexcept SystemExit:\n    pass")
    assert loaded_after(run.format(args=["groups", "example:hinged_rod"])) == set()
    assert "scipy" not in loaded_after(run.format(args=["search", "example:hinged_rod", "--scale", "g=1"]))
    assert "matplotlib" not in loaded_after(run.format(args=["bases", "example:hinged_rod"]))


def test_lazy_names_resolve_to_the_functions_not_the_modules():
    import pitheorem.scalesearch as scalesearch
    import pitheorem.simulation as simulation

    assert scalesearch.__name__ == "pitheorem.scalesearch"  # the module is the module
    assert pt.search is scalesearch.search
    assert pt.search.__name__ == "search"
    assert pt.simulate.__name__ == "simulate"
    assert callable(pt.simulate)
    # the module's name differs from its functions': importing it gives the module
    assert isinstance(simulation, types.ModuleType)
    assert simulation.simulate is pt.simulate
    assert simulation.verify_similarity is pt.verify_similarity
    for name in pt.__all__:
        assert getattr(pt, name) is not None
        assert name in dir(pt)
    with pytest.raises(AttributeError):
        pt.no_such_name  # noqa: B018


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["M", "L", "T", "Theta", "I", "N", "J", "A", "Q", "kg"]),
                          st.integers(-120, 120)), min_size=1, max_size=4), st.booleans())
def test_quick_formula_reader_agrees_with_the_parser(factors, spaced):
    text = (" " if spaced else "  ").join(f"{b}^{p}" if p != 1 else b for b, p in factors)
    try:
        expected = pt.Dimension.parse(text)
    except pt.PiTheoremError as err:
        with pytest.raises(type(err)):
            pt.System({"x": text})
        return
    assert pt.System({"x": text}).dimension("x") == expected


def test_int_and_fraction_columns_share_integer_rows():
    from pitheorem.linalg import integer_rows

    assert integer_rows([[Fraction(1, 2), 3, True], [np.int64(2), Fraction(4), 0]]) == [[1, 6, 2], [2, 4, 0]]


def test_basis_sequence_pretty_prints_as_its_list():
    seen = []

    class Printer:  # the one method of IPython's pretty printer that _repr_pretty_ calls
        def pretty(self, obj):
            seen.append(obj)

    sets = pt.models.rod_system().bases(exclude=("t",))
    sets[:3]._repr_pretty_(Printer(), cycle=False)
    assert seen == [[("m", "l", "g"), ("m", "l", "k_theta"), ("m", "l", "c_theta")]]
    assert isinstance(seen[0], list)


@pytest.mark.parametrize("m", range(7))
@pytest.mark.parametrize("k", range(8))
def test_lex_combinations_are_itertools_combinations(m, k):
    got = bases_module.lex_combinations(m, k)
    expected = [list(c) for c in combinations(range(m), k)]
    assert got.shape == (len(expected), k)
    assert got.tolist() == expected


def test_basis_sequences_compare_by_content():
    one = pt.System({"l": "L", "t": "T", "x": "L"}).bases()  # (l, t), (t, x)
    same = pt.System({"l": "L", "t": "T", "x": "L"}).bases()
    other = pt.System({"l": "L", "t": "T", "v": "L/T"}).bases()  # (l, t), (l, v), (t, v)
    shifted = pt.System({"a": "L", "b": "T", "c": "T"}).bases()  # (a, b), (a, c): same length as one
    assert len(one) == len(shifted) == 2
    assert one == same
    assert not (one != same)
    assert one != other
    assert one != shifted
    assert one != one[:1]
    assert (one == 5) is False  # not a sequence: no comparison, no error
    assert one != None  # noqa: E711 (the comparison itself is under test)


def test_basis_sequence_iterates_past_its_batch_of_4096():
    names = [f"x{j}" for j in range(32)]
    combos = list(combinations(range(32), 3))  # 4960 rows, one block
    sequence = BasisSequence(names, [np.array(combos)])
    assert list(sequence) == [tuple(names[i] for i in c) for c in combos]
    # a system whose every 3 columns are independent (Vandermonde): the bases are all 3-subsets
    system = pt.System({n: {"M": 1, "L": j, "T": j * j} for j, n in enumerate(names)})
    bases = system.bases()
    bases.indices  # noqa: B018 (joins the chunks into one block)
    assert list(bases) == [tuple(names[i] for i in c) for c in combos]


def test_empty_basis_sequence_keeps_the_index_type():
    # 300 variables: positions up to 299 need 16 bits, even when no basis is left
    system = pt.System({f"x{j}": "L" for j in range(300)})
    assert system.bases().indices.dtype == np.uint16
    none_left = system.bases(exclude=system.variables)
    assert len(none_left) == 0
    assert none_left.indices.dtype == np.uint16
    assert none_left.indices.shape == (0, 1)
    assert system.bases()[5:2].indices.dtype == np.uint16


def test_minimal_points_can_be_indexed_before_they_are_iterated():
    # a0 = (1, 1, 0), one direction (0, 1, -1), free positions 1 and 2: the minimal points are
    # a0 (zero at 2, coordinate 0) and a0 - direction (zero at 1, coordinate -1), by hand
    keys, weights = family_module.minimal_points([1, 1, 0], [[0, 1, -1]], [1, 2], [0])
    expected = [((1, 1, 0), (0,)), ((1, 0, 1), (-1,))]
    assert family_module.MinimalPoints(keys, weights, 1, (0,), [[1]])[1] == expected[1]
    assert family_module.MinimalPoints(keys, weights, 1, (0,), [[1]])[-2] == expected[0]
    assert family_module.MinimalPoints(keys, weights, 1, (0,), [[1]])[0:2] == expected
    points = family_module.MinimalPoints(keys, weights, 1, (0,), [[1]])
    assert list(points) == expected
    assert points[1] == expected[1]


def test_minimal_points_of_directions_dependent_on_the_free_variables():
    # both directions vanish off position 1: no two free positions carry an independent minor,
    # so there is no minimal point; the arrays keep their documented widths (n + 1 and d + 1)
    keys, weights = family_module.minimal_points([1, 1, 0, 0], [[0, 1, 0, 0], [0, 2, 0, 0]], [1, 2, 3], [0])
    assert keys.shape == (0, 5)
    assert weights.shape == (0, 3)


def test_joined_and_empty_index_arrays_are_read_only():
    names = ["a", "b", "c"]
    joined = BasisSequence(names, [np.array([[0, 1]]), np.array([[0, 2], [1, 2]])])
    empty = BasisSequence(names, [], width=2)
    for sequence in (joined, empty):
        with pytest.raises(ValueError, match="read-only"):
            sequence.indices[:] = 0
    assert joined.indices.tolist() == [[0, 1], [0, 2], [1, 2]]
    assert list(joined) == [("a", "b"), ("a", "c"), ("b", "c")]
