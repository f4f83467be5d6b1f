"""Every valid repeating-variable set ("basis") of a dimension matrix.

A basis is a set of ``r = rank(D)`` variables whose columns of the
dimension matrix ``D`` are linearly independent.  There can be millions of
candidate subsets, so they are tested in vectorised batches, exactly:

* Usually (small integer exponents, the normal case for dimension
  matrices) the subsets are grown column by column in lexicographic order,
  carrying for each prefix its exterior product: the vector of all its
  maximal minors.  Extending a prefix by one column is a Laplace expansion,
  a prefix whose minors all vanish is dependent and pruned with everything
  that extends it, and the last column of every subset is handled by one
  matrix product (the determinant is linear in that column).  All values
  are integers bounded by the Hadamard bound, which is checked to be below
  2^53 first, so float64 arithmetic on them is exact.
* Otherwise each candidate ``r x r`` submatrix is triangularised by
  fraction-free elimination modulo the prime ``p = 2^31 - 1``: a nonzero
  result proves independence; a zero one proves dependence when the
  Hadamard bound is below ``p``, and is re-checked with exact fractions
  when it is not.

Subsets are visited in lexicographic order of column positions, which
makes the output order deterministic.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from fractions import Fraction
from itertools import combinations
from math import lcm, prod
from typing import ClassVar

import numpy as np

from .linalg import rank

__all__ = ["count_independent_subsets", "independent_subsets"]

_PRIME = 2_147_483_647  # 2^31 - 1: products of two residues fit in int64
_CHUNK = 1 << 17
_EXACT_FLOAT = 2**53  # floats hold every integer below this exactly


def _integer_rows(rows: Sequence[Sequence[Fraction]]) -> list[list[int]]:
    out = []
    for row in rows:
        den = lcm(*(Fraction(x).denominator for x in row))
        out.append([int(Fraction(x) * den) for x in row])
    return out


def lex_combinations(m: int, k: int) -> np.ndarray:
    """All k-subsets of ``range(m)`` as rows, in lexicographic order.

    Examples
    --------
    >>> from pitheorem.bases import lex_combinations
    >>> lex_combinations(4, 2).tolist()
    [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]
    """
    if k == 0:
        return np.zeros((1, 0), dtype=np.int64)
    if k > m:
        return np.zeros((0, k), dtype=np.int64)
    combos = np.arange(m - k + 1, dtype=np.int64)[:, None]
    for depth in range(1, k):
        last = combos[:, -1]
        # next element runs from last+1 up to m-k+depth (room for the rest)
        counts = (m - k + depth) - last
        total = int(counts.sum())
        offsets = np.repeat(np.cumsum(counts) - counts, counts)
        new = np.arange(total, dtype=np.int64) - offsets + np.repeat(last + 1, counts)
        combos = np.hstack([np.repeat(combos, counts, axis=0), new[:, None]])
    return combos


def _full_rank_mod_p(columns: np.ndarray, combos: np.ndarray) -> np.ndarray:
    """Boolean mask: is det of each selected square submatrix nonzero mod p."""
    r = columns.shape[0]
    m = np.ascontiguousarray(np.transpose(columns[:, combos], (1, 0, 2)))  # (N, r, r)
    n = m.shape[0]
    ok = np.ones(n, dtype=bool)
    rows = np.arange(n)
    for c in range(r):
        nonzero = m[:, c:, c] != 0
        ok &= nonzero.any(axis=1)
        pivot = nonzero.argmax(axis=1) + c
        swap = pivot != c
        if swap.any():
            idx, piv = rows[swap], pivot[swap]
            top = m[idx, c].copy()
            m[idx, c] = m[idx, piv]
            m[idx, piv] = top
        if c + 1 < r:
            p = m[:, c, c][:, None, None]
            f = m[:, c + 1 :, c][:, :, None]
            m[:, c + 1 :, :] = (m[:, c + 1 :, :] * p - f * m[:, c, :][:, None, :]) % _PRIME
    return ok


class _Enumerator:
    """Shared set-up for iterating and counting independent subsets."""

    def __init__(self, rows, candidates: Sequence[int], required: Sequence[int], size: int):
        self.size = size
        if size == 0:  # every variable dimensionless: the empty set is the one basis
            return
        self.int_rows = _integer_rows(rows)
        # Issue 12: every bound below is computed in Python integers.  Entries
        # may exceed int64 (lcm scaling of large denominators), and int64
        # arithmetic wraps silently; such matrices keep object dtype and take
        # the mod-p path with exact re-checks.
        n_rows, n_cols = len(self.int_rows), (len(self.int_rows[0]) if self.int_rows else 0)
        biggest = max((abs(x) for row in self.int_rows for x in row), default=0)
        self.columns = np.array(self.int_rows, dtype=np.int64 if biggest < 2**62 else object).reshape(n_rows, n_cols)
        # a zero column (a dimensionless variable) can never be in a basis
        self.candidates = np.array(
            [j for j in candidates if any(row[j] for row in self.int_rows)], dtype=np.int64
        )
        self.required = np.array(sorted(required), dtype=np.int64)
        squared_norms = sorted((sum(row[j] ** 2 for row in self.int_rows) for j in range(n_cols)), reverse=True)
        hadamard_squared = prod(squared_norms[:size])  # |det| <= product of column norms (Hadamard)
        # below p, "0 mod p" means 0
        self.mod_p_decides_zero = 4 * hadamard_squared < _PRIME**2
        self.mod = (self.columns % _PRIME).astype(np.int64)
        # every minor and every partial Laplace sum stays below size * biggest * Hadamard
        self.float_is_exact = (size * biggest) ** 2 * hadamard_squared < _EXACT_FLOAT**2

    def chunks(self) -> Iterator[tuple[np.ndarray, np.ndarray]]:
        """Yield (subsets as sorted index rows, independence mask) in lex order."""
        if self.size == 0:
            yield np.zeros((1, 0), dtype=np.int64), np.ones(1, dtype=bool)
            return
        if self.float_is_exact:
            yield from self._wedge_chunks()
        else:
            yield from self._mod_p_chunks()

    def _finish(self, chosen: np.ndarray) -> np.ndarray:
        """Candidate positions -> sorted column indices, with the required columns."""
        subsets = np.hstack([self.candidates[chosen], np.broadcast_to(self.required, (len(chosen), len(self.required)))])
        subsets.sort(axis=1)
        return subsets

    def _mod_p_chunks(self):
        pick = lex_combinations(len(self.candidates), self.size - len(self.required))
        for start in range(0, len(pick), _CHUNK):
            subsets = self._finish(pick[start : start + _CHUNK])
            mask = _full_rank_mod_p(self.mod, subsets)
            if not self.mod_p_decides_zero:
                for i in np.flatnonzero(~mask):
                    sub = [[row[j] for j in subsets[i]] for row in self.int_rows]
                    mask[i] = rank(sub) == self.size
            yield subsets, mask

    def _wedge_chunks(self):
        r = self.size
        a = self.columns[:, self.candidates].astype(float)  # (r, m)
        m = a.shape[1]
        tables = _LaplaceTables.get(r)
        # exterior product of the required columns: the state every prefix starts from
        wedge = np.ones((1, 1))
        for j, col in enumerate(self.required):
            wedge = tables.extend(wedge, np.zeros(1, dtype=np.int64), self.columns[:, [col]].T.astype(float), j)
        start = len(self.required)
        if start == r:
            yield self._finish(np.zeros((1, 0), dtype=np.int64)), np.ones(1, dtype=bool)
            return
        prefixes = np.zeros((1, 0), dtype=np.int64)
        for j in range(start, r - 1):
            last = prefixes[:, -1] if prefixes.shape[1] else np.full(len(prefixes), -1)
            counts = np.maximum(m - (r - j - 1) - (last + 1), 0)
            parents = np.repeat(np.arange(len(prefixes)), counts)
            offsets = np.repeat(np.cumsum(counts) - counts, counts)
            new_col = np.arange(len(parents)) - offsets + np.repeat(last + 1, counts)
            wedge = tables.extend(wedge, parents, a[:, new_col].T, j)
            alive = wedge.any(axis=1)  # a prefix with all minors zero is dependent: prune it
            prefixes = np.hstack([prefixes[parents], new_col[:, None]])[alive]
            wedge = wedge[alive]
        signed = tables.last_column_weights(wedge)  # det(prefix + c) = signed @ a[:, c]
        last = prefixes[:, -1] if prefixes.shape[1] else np.full(len(prefixes), -1)
        step = max(1, _CHUNK // max(m, 1))
        for lo in range(0, len(prefixes), step):
            dets = signed[lo : lo + step] @ a
            later = np.arange(m)[None, :] > last[lo : lo + step, None]
            rows, cols = np.nonzero(later)
            chosen = np.hstack([prefixes[lo + rows], cols[:, None]])
            yield self._finish(chosen), dets[rows, cols] != 0


class _LaplaceTables:
    """Index tables for exterior products of columns with ``r`` entries.

    Level ``j`` holds, for a prefix of ``j`` columns, its minors on every
    ``j``-subset of the ``r`` rows (in lexicographic order of row subsets).
    """

    _cache: ClassVar[dict[int, _LaplaceTables]] = {}

    def __init__(self, r: int):
        self.r = r
        self.levels = [list(combinations(range(r), j)) for j in range(r + 1)]
        self.position = [{rows: k for k, rows in enumerate(level)} for level in self.levels]

    @classmethod
    def get(cls, r: int) -> _LaplaceTables:
        if r not in cls._cache:
            cls._cache[r] = cls(r)
        return cls._cache[r]

    def extend(self, wedge: np.ndarray, parents: np.ndarray, cols: np.ndarray, j: int) -> np.ndarray:
        """Minors of (prefix + new column) by Laplace expansion along the new column.

        ``wedge`` has one row per prefix of length ``j``; ``cols`` one row
        (the new column's entries) per extended prefix.
        """
        base = wedge[parents]
        out = np.zeros((len(parents), len(self.levels[j + 1])))
        for k, rows in enumerate(self.levels[j + 1]):
            for q, i in enumerate(rows):
                minor = base[:, self.position[j][rows[:q] + rows[q + 1 :]]]
                if (q + j) % 2:
                    out[:, k] -= cols[:, i] * minor
                else:
                    out[:, k] += cols[:, i] * minor
        return out

    def last_column_weights(self, wedge: np.ndarray) -> np.ndarray:
        """Signed cofactors: det(prefix + c) = weights @ c for a prefix of r-1 columns."""
        r = self.r
        everything = tuple(range(r))
        order = [self.position[r - 1][everything[:i] + everything[i + 1 :]] for i in range(r)]
        signs = np.array([(-1.0) ** (i + r - 1) for i in range(r)])
        return wedge[:, order] * signs


def independent_subsets(rows, candidates, required, size) -> Iterator[tuple[int, ...]]:
    """Yield every independent column subset of the given size, in lex order.

    Parameters
    ----------
    rows : sequence of sequences of Fraction
        A matrix with full row rank ``size``.
    candidates : sequence of int
        Columns that may be chosen.
    required : sequence of int
        Columns every subset must contain (disjoint from `candidates`).
    size : int
        Number of columns per subset (the rank).

    Examples
    --------
    >>> from pitheorem.bases import independent_subsets
    >>> list(independent_subsets([[1, 0, 1], [0, 1, 1]], [0, 1, 2], [], 2))
    [(0, 1), (0, 2), (1, 2)]
    """
    for subsets, mask in _Enumerator(rows, candidates, required, size).chunks():
        yield from map(tuple, subsets[mask].tolist())


def count_independent_subsets(rows, candidates, required, size) -> int:
    """Count independent column subsets without building them.

    Examples
    --------
    >>> from pitheorem.bases import count_independent_subsets
    >>> count_independent_subsets([[1, 2, 0]], [0, 1, 2], [], 1)
    2
    """
    return sum(int(mask.sum()) for _, mask in _Enumerator(rows, candidates, required, size).chunks())
