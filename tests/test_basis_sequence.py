"""pitheorem.basis_sequence: the read-only sequence of repeating sets that ``System.bases`` returns.

It must behave like the list of tuples it stands for (indexing, slicing,
equality, membership, printing), against lists built by brute force.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import combinations, pairwise

import numpy as np
import pytest

import pitheorem as pt
from pitheorem.basis_sequence import BasisSequence
from tests.conftest import oracle_bases


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


def test_basis_sequence_pretty_prints_as_its_list():
    seen = []

    class Printer:  # the one method of IPython's pretty printer that _repr_pretty_ calls
        def pretty(self, obj):
            seen.append(obj)

    sets = pt.models.rod_system().bases(exclude=("t",))
    sets[:3]._repr_pretty_(Printer(), cycle=False)
    assert seen == [[("m", "l", "g"), ("m", "l", "k_theta"), ("m", "l", "c_theta")]]
    assert isinstance(seen[0], list)


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


def test_joined_and_empty_index_arrays_are_read_only():
    names = ["a", "b", "c"]
    joined = BasisSequence(names, [np.array([[0, 1]]), np.array([[0, 2], [1, 2]])])
    empty = BasisSequence(names, [], width=2)
    for sequence in (joined, empty):
        with pytest.raises(ValueError, match="read-only"):
            sequence.indices[:] = 0
    assert joined.indices.tolist() == [[0, 1], [0, 2], [1, 2]]
    assert list(joined) == [("a", "b"), ("a", "c"), ("b", "c")]


def test_bases_are_indexed_by_integers_only():
    with pytest.raises(TypeError, match=r"indexed by integers or slices, not str$"):
        pt.System({"l": "L", "t": "T"}).bases()["l"]


@pytest.mark.parametrize(("n", "dtype"), [(256, np.uint8), (257, np.uint16)])
def test_the_index_type_is_the_smallest_that_holds_the_last_position(n, dtype):
    # positions 0 .. n - 1: 255 is the largest a byte holds, 256 needs two
    names = [f"x{j}" for j in range(n)]
    bases = pt.System(dict.fromkeys(names, "L")).bases()
    assert bases.indices.dtype == dtype
    assert bases[-1] == (names[-1],)
    assert list(bases) == [(name,) for name in names]


def test_blocks_are_read_in_place_without_a_copy():
    chunk = np.array([[0, 1], [0, 2]], dtype=np.uint8)
    sequence = BasisSequence(["a", "b", "c"], [chunk])
    assert np.shares_memory(sequence.indices, chunk)


def test_items_are_found_across_blocks_before_they_are_joined():
    names = ["a", "b", "c", "d"]
    rows = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]
    for sizes in ([1, 5], [2, 1, 3], [3, 3], [1, 1, 1, 1, 1, 1]):
        cuts = np.cumsum([0, *sizes])
        chunks = [np.array(rows[a:b]) for a, b in pairwise(cuts)]
        expected = [(names[i], names[j]) for i, j in rows]
        assert [BasisSequence(names, chunks)[i] for i in range(-6, 6)] == expected + expected


def test_empty_slices_and_sequences_keep_the_width():
    bases = pt.System({"l": "L", "t": "T", "x": "L"}).bases()
    assert bases[5:2].indices.shape == (0, 2)
    assert bases[5:2] == []
    rank_zero = pt.System({"x": "1", "y": "1"}).bases()
    assert rank_zero == [()]
    assert rank_zero[1:].indices.shape == (0, 0)
    assert BasisSequence(["a"], []).indices.shape == (0, 0)


def test_rank_zero_blocks_each_hold_empty_sets():
    sequence = BasisSequence(["a", "b"], [np.zeros((1, 0), dtype=int), np.zeros((2, 0), dtype=int)])
    assert list(sequence) == [(), (), ()]
    assert len(sequence) == 3


def test_sequences_over_different_names_differ_even_with_the_same_positions():
    one = pt.System({"l": "L", "t": "T"}).bases()
    other = pt.System({"a": "L", "b": "T"}).bases()
    assert one.indices.tolist() == other.indices.tolist() == [[0, 1]]
    assert one != other
    assert not (one == other)
