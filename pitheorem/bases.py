"""Every valid repeating-variable set ("basis") of a dimension matrix.

A basis is a set of ``r = rank(D)`` variables whose columns of the
dimension matrix ``D`` are linearly independent.  There can be millions of
candidate subsets, so they are tested in vectorised batches:

1. ``D`` is reduced to ``r`` independent integer rows (same column
   dependencies, smaller matrices).
2. Each candidate ``r x r`` submatrix is triangularised by fraction-free
   Gaussian elimination modulo the prime ``p = 2^31 - 1``.  A nonzero
   determinant mod ``p`` proves the integer determinant nonzero: those
   subsets are bases, exactly.
3. A zero determinant mod ``p`` proves the subset dependent when the
   Hadamard bound on ``|det|`` is below ``p`` (the usual case for dimension
   matrices); otherwise the subset is re-checked with exact fractions.

So the numerics only decide what is cheap to decide; every answer is exact.
Subsets are visited in lexicographic order of variable positions, which
makes the output order deterministic.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from fractions import Fraction
from math import lcm, prod, sqrt

import numpy as np

from .linalg import rank

__all__ = ["count_independent_subsets", "independent_subsets"]

_PRIME = 2_147_483_647  # 2^31 - 1: products of two residues fit in int64
_CHUNK = 1 << 17


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
        self.columns = np.array(self.int_rows, dtype=np.int64).reshape(len(self.int_rows), -1)
        # a zero column (a dimensionless variable) can never be in a basis
        self.candidates = np.array(
            [j for j in candidates if self.columns[:, j].any()], dtype=np.int64
        )
        self.required = np.array(sorted(required), dtype=np.int64)
        norms = sorted((sqrt(float((self.columns[:, j] ** 2).sum())) for j in range(self.columns.shape[1])), reverse=True)
        # Hadamard: |det| <= product of column norms; below p, "0 mod p" means 0
        self.mod_p_decides_zero = prod(norms[:size]) < _PRIME / 2
        self.mod = self.columns % _PRIME

    def chunks(self) -> Iterator[tuple[np.ndarray, np.ndarray]]:
        """Yield (subsets as sorted index rows, independence mask) in lex order."""
        if self.size == 0:
            yield np.zeros((1, 0), dtype=np.int64), np.ones(1, dtype=bool)
            return
        free = self.size - len(self.required)
        cand = self.candidates
        pick = lex_combinations(len(cand), free)
        for start in range(0, len(pick), _CHUNK):
            chosen = cand[pick[start : start + _CHUNK]]
            subsets = np.hstack([chosen, np.broadcast_to(self.required, (len(chosen), len(self.required)))])
            subsets.sort(axis=1)
            mask = _full_rank_mod_p(self.mod, subsets)
            if not self.mod_p_decides_zero:
                for i in np.flatnonzero(~mask):
                    sub = [[row[j] for j in subsets[i]] for row in self.int_rows]
                    mask[i] = rank(sub) == self.size
            yield subsets, mask


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
