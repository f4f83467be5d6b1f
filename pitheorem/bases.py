"""Every valid repeating-variable set ("basis") of a dimension matrix.

A basis is a set of ``r = rank(D)`` variables whose columns of the
dimension matrix ``D`` are linearly independent.  There can be millions of
candidate subsets, so they are tested in vectorised batches, exactly:

* Usually (small integer exponents, the normal case for dimension
  matrices) the subsets are grown column by column in lexicographic order,
  depth first, a bounded chunk of prefixes at a time, carrying for each
  prefix its exterior product: the vector of all its maximal minors.
  Extending a prefix by one column is a Laplace expansion, a prefix whose
  minors all vanish is dependent and pruned with everything that extends
  it, and the last column of every subset is handled by one matrix product
  (the determinant is linear in that column).  Every value is an integer
  below a Hadamard bound computed first in Python integers; when that bound
  is below 2^53, float64 arithmetic on them is exact.
* Otherwise each candidate ``r x r`` submatrix is triangularised by
  fraction-free elimination modulo primes near 2^31: a nonzero result
  proves independence.  A determinant that vanishes modulo primes whose
  product exceeds twice the Hadamard bound is zero (Chinese remainder
  theorem); when eight primes are not enough, exact fractions decide.

Subsets are visited in lexicographic order of column positions, which
makes the output order deterministic.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from itertools import combinations
from math import comb, isqrt, prod
from typing import ClassVar

import numpy as np

from .linalg import integer_rows, rank

__all__ = [
    "LaplaceTables",
    "PrefixDescent",
    "count_independent_subsets",
    "float_is_exact",
    "independent_subsets",
    "lex_combinations",
]

# primes below 2^31: a product of two residues fits in int64
_PRIMES = (2147483647, 2147483629, 2147483587, 2147483579, 2147483563, 2147483549, 2147483543, 2147483497)
# rows per numpy batch: small enough that the working arrays of every level of the
# depth-first descent together stay a few megabytes
_CHUNK = 2048
_EXACT_FLOAT = 2**53


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


def _lex_combination_chunks(m: int, k: int, limit: int = 1 << 16) -> Iterator[np.ndarray]:
    """The rows of ``lex_combinations(m, k)`` in order, a bounded batch at a time."""
    if comb(m, k) <= limit:
        yield lex_combinations(m, k)
        return
    for first in range(m - k + 1):
        for rest in _lex_combination_chunks(m - first - 1, k - 1, limit):
            yield np.hstack([np.full((len(rest), 1), first, dtype=np.int64), rest + (first + 1)])


def hadamard_squared(int_rows: Sequence[Sequence[int]], k: int) -> int:
    """Square of a bound on every k x k minor: the k largest squared column norms, multiplied.

    Python integers throughout, so it cannot overflow.

    Examples
    --------
    >>> from pitheorem.bases import hadamard_squared
    >>> hadamard_squared([[3, 0, 1], [4, 1, 0]], 2)
    25
    """
    norms = sorted((sum(x * x for x in col) for col in zip(*int_rows, strict=True)), reverse=True)
    return prod(norms[:k])


def float_is_exact(int_rows: Sequence[Sequence[int]], k: int) -> bool:
    """Are Laplace expansions of minors of up to k columns exact in float64?

    Every minor of j <= k columns is at most the Hadamard bound ``H``, each
    product of an entry and a minor at most ``max|entry| * H``, and each sum
    of k such products at most ``k max|entry| H``; below 2^53 every one of
    these integers is a float64 exactly, whatever the order of summation.

    Examples
    --------
    >>> from pitheorem.bases import float_is_exact
    >>> float_is_exact([[1, 2], [3, 4]], 2), float_is_exact([[2**40, 0], [0, 2**40]], 2)
    (True, False)
    """
    biggest = max((abs(x) for row in int_rows for x in row), default=0)
    return (k * biggest) ** 2 * hadamard_squared(int_rows, k) < _EXACT_FLOAT**2


def _full_rank_mod_p(columns: np.ndarray, combos: np.ndarray, prime: int) -> np.ndarray:
    """Boolean mask: is det of each selected square submatrix nonzero mod `prime`.

    `columns` holds residues in ``[0, prime)``.
    """
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
            m[:, c + 1 :, :] = (m[:, c + 1 :, :] * p - f * m[:, c, :][:, None, :]) % prime
    return ok


class LaplaceTables:
    """Index tables for exterior products of columns with ``r`` entries.

    Level ``j`` holds, for a prefix of ``j`` columns, its minors on every
    ``j``-subset of the ``r`` rows (in lexicographic order of row subsets).
    Extending to level ``j + 1`` expands each new minor along the new
    column: ``sum_q (-1)^(q + j) c[rows[q]] * minor(rows without rows[q])``.
    Shared by the basis enumeration here and the minimal points of
    :mod:`pitheorem.family`; build one with :meth:`get`, which keeps one
    per ``r``.

    Examples
    --------
    >>> import numpy as np
    >>> from pitheorem.bases import LaplaceTables
    >>> tables = LaplaceTables.get(2)
    >>> first = tables.extend(np.ones((1, 1)), np.array([[1.0, 2.0]]), 0)   # the column (1, 2)
    >>> tables.extend(first, np.array([[3.0, 4.0]]), 1).tolist()          # det [[1, 3], [2, 4]]
    [[-2.0]]
    """

    _cache: ClassVar[dict[int, LaplaceTables]] = {}

    def __init__(self, r: int):
        self.r = r
        levels = [list(combinations(range(r), j)) for j in range(r + 1)]
        position = [{rows: k for k, rows in enumerate(level)} for level in levels]
        self.width = [len(level) for level in levels]
        # per level j -> j+1: entry rows (K, j+1), minor positions (K, j+1), signs (K, j+1)
        self.steps = []
        for j in range(r):
            new = levels[j + 1]
            entry = np.array([list(rows) for rows in new], dtype=np.int64).reshape(len(new), j + 1)
            minor = np.array(
                [[position[j][rows[:q] + rows[q + 1 :]] for q in range(j + 1)] for rows in new], dtype=np.int64
            ).reshape(len(new), j + 1)
            sign = np.array([[(-1.0) ** (q + j) for q in range(j + 1)]] * len(new)).reshape(len(new), j + 1)
            self.steps.append((entry, minor, sign))
        everything = tuple(range(r))
        self.last_order = np.array(
            [position[r - 1][everything[:i] + everything[i + 1 :]] for i in range(r)] if r else [], dtype=np.int64
        )
        self.last_signs = np.array([(-1.0) ** (i + r - 1) for i in range(r)])

    @classmethod
    def get(cls, r: int) -> LaplaceTables:
        if r not in cls._cache:
            cls._cache[r] = cls(r)
        return cls._cache[r]

    def extend(self, wedge: np.ndarray, cols: np.ndarray, j: int) -> np.ndarray:
        """Minors of (prefix + new column), one row per prefix, from its level-j minors.

        ``wedge`` (P, width[j]) and ``cols`` (P, r): the new column of each prefix.
        """
        entry, minor, sign = self.steps[j]
        # one term of the expansion at a time: (P, K) temporaries instead of one (P, K, j + 1)
        out = cols[:, entry[:, 0]] * wedge[:, minor[:, 0]] * sign[:, 0]
        for q in range(1, j + 1):
            out += cols[:, entry[:, q]] * wedge[:, minor[:, q]] * sign[:, q]
        return out

    def last_column_weights(self, wedge: np.ndarray) -> np.ndarray:
        """Signed cofactors: det(prefix + c) = weights @ c for a prefix of r-1 columns."""
        return wedge[:, self.last_order] * self.last_signs


class PrefixDescent:
    """Depth-first, chunked growth of column prefixes in lexicographic order, with exterior products.

    ``columns`` is a float array (rows x m) of exact integers; ``start``
    the exterior product of columns every prefix begins with (``n0`` of them).
    Shared by the basis enumeration here and the minimal points of
    :mod:`pitheorem.family`.

    Examples
    --------
    >>> import numpy as np
    >>> from pitheorem.bases import PrefixDescent
    >>> columns = np.array([[1.0, 2.0, 0.0], [0.0, 0.0, 1.0]])   # columns 0 and 1 are parallel
    >>> [p.tolist() for p, _ in PrefixDescent(columns, np.ones((1, 1)), 0).prefixes(2, 0)]
    [[[0, 2], [1, 2]]]
    """

    def __init__(self, columns: np.ndarray, start: np.ndarray, n0: int):
        self.a = columns
        self.at = np.ascontiguousarray(columns.T)
        self.m = columns.shape[1]
        self.tables = LaplaceTables.get(columns.shape[0])
        self.start = start
        self.n0 = n0

    def prefixes(self, depth: int, room: int) -> Iterator[tuple[np.ndarray, np.ndarray]]:
        """Yield (prefixes (P, depth - n0) of column positions, their minors) in lex order.

        Only prefixes whose minors do not all vanish (independent ones) are
        yielded, and only those leaving at least `room` later columns.
        """
        empty = np.zeros((1, 0), dtype=np.int64)
        yield from self._descend(empty, self.start, self.n0, depth, room)

    def _descend(self, prefixes, wedge, j, depth, room):
        if j == depth:
            yield prefixes, wedge
            return
        m = self.m
        last = prefixes[:, -1] if prefixes.shape[1] else np.full(len(prefixes), -1, dtype=np.int64)
        # the next column runs from last + 1 to m - 1 - (columns still to come after it)
        counts = np.maximum(m - (depth + room - j - 1) - (last + 1), 0)
        limit = max(1, _CHUNK // max(m, 1))
        for lo in range(0, len(prefixes), limit):
            c = counts[lo : lo + limit]
            parents = np.repeat(np.arange(lo, lo + len(c)), c)
            if not len(parents):
                continue
            offsets = np.repeat(np.cumsum(c) - c, c)
            new_col = np.arange(len(parents)) - offsets + np.repeat(last[lo : lo + limit] + 1, c)
            child = self.tables.extend(wedge[parents], self.at[new_col], j)
            alive = child.any(axis=1)  # all minors zero: dependent, and so is every extension
            child_prefixes = np.hstack([prefixes[parents], new_col[:, None]])[alive]
            yield from self._descend(child_prefixes, child[alive], j + 1, depth, room)


class _Enumerator:
    """Independent column subsets of one matrix, in lexicographic order, in chunks."""

    def __init__(self, rows, candidates: Sequence[int], required: Sequence[int], size: int):
        self.size = size
        if size == 0:  # every variable dimensionless: the empty set is the one basis
            return
        self.int_rows = integer_rows(rows)
        n_cols = len(self.int_rows[0])
        nonzero = [any(row[j] for row in self.int_rows) for j in range(n_cols)]
        # a zero column (a dimensionless variable) can never be in a basis
        self.candidates = np.array([j for j in candidates if nonzero[j]], dtype=np.int64)
        self.required = np.array(sorted(required), dtype=np.int64)
        self.fast = float_is_exact(self.int_rows, size)
        self.dtype = np.min_scalar_type(max(n_cols - 1, 0))

    def chunks(self) -> Iterator[np.ndarray]:
        """Yield arrays of independent subsets (sorted column indices per row) in lex order."""
        if self.size == 0:
            yield np.zeros((1, 0), dtype=np.int64)
            return
        if len(self.candidates) < self.size - len(self.required):
            return
        if len(self.required) == self.size:
            if rank([[row[j] for j in self.required] for row in self.int_rows]) == self.size:
                yield self.required[None, :]
            return
        yield from (self._wedge_chunks() if self.fast else self._mod_p_chunks())

    def count(self) -> int:
        if self.size == 0:
            return 1
        if len(self.candidates) < self.size - len(self.required) or len(self.required) == self.size:
            return sum(len(c) for c in self.chunks())
        if not self.fast:
            return sum(len(c) for c in self._mod_p_chunks())
        return sum(int(np.count_nonzero(mask)) for _, mask in self._last_column())

    def _finish(self, chosen: np.ndarray) -> np.ndarray:
        """Candidate positions -> sorted column indices, with the required columns.

        In the smallest integer type that holds every column index: listing
        millions of bases then takes a few bytes each.
        """
        subsets = self.candidates.astype(self.dtype)[chosen]
        if len(self.required):
            required = np.broadcast_to(self.required.astype(self.dtype), (len(chosen), len(self.required)))
            subsets = np.hstack([subsets, required])
            subsets.sort(axis=1)
        return subsets

    # -- exact in float64 -----------------------------------------------------------------
    def _last_column(self):
        """Yield (prefixes of r-1 candidate positions, mask (P, m): is prefix + column c independent)."""
        r = self.size
        float_rows = np.array(self.int_rows, dtype=float)
        a = float_rows[:, self.candidates]
        tables = LaplaceTables.get(r)
        # exterior product of the required columns: the state every prefix starts from
        wedge = np.ones((1, 1))
        for j, col in enumerate(self.required):
            wedge = tables.extend(wedge, float_rows[:, [col]].T, j)
        if not wedge.any():
            return
        start = len(self.required)
        m = a.shape[1]
        for prefixes, minors in PrefixDescent(a, wedge, start).prefixes(r - 1, 1):
            dets = tables.last_column_weights(minors) @ a  # det(prefix + c) for every candidate c
            last = prefixes[:, -1] if prefixes.shape[1] else np.full(len(prefixes), -1)
            mask = (dets != 0) & (np.arange(m)[None, :] > last[:, None])
            yield prefixes, mask

    def _wedge_chunks(self):
        for prefixes, mask in self._last_column():
            rows, cols = np.nonzero(mask)
            if len(rows):
                chosen = np.empty((len(rows), prefixes.shape[1] + 1), dtype=self.dtype)
                chosen[:, :-1] = prefixes[rows]
                chosen[:, -1] = cols
                yield self._finish(chosen)

    # -- exact by residues --------------------------------------------------------------
    def _mod_p_chunks(self):
        r = self.size
        # residues are taken of Python integers, so no entry is too large for them
        residues = [np.array([[x % p for x in row] for row in self.int_rows], dtype=np.int64) for p in _PRIMES]
        bound = 2 * (isqrt(hadamard_squared(self.int_rows, r)) + 1)
        # how many primes it takes for "zero modulo each" to prove zero (None: not enough of them)
        enough = next((k for k in range(1, len(_PRIMES) + 1) if prod(_PRIMES[:k]) > bound), None)
        for pick in _lex_combination_chunks(len(self.candidates), r - len(self.required)):
            subsets = self._finish(pick)
            undecided = np.arange(len(subsets))
            independent = np.zeros(len(subsets), dtype=bool)
            for k, (prime, mod) in enumerate(zip(_PRIMES, residues, strict=True)):
                if enough is not None and k == enough:
                    break
                ok = _full_rank_mod_p(mod, subsets[undecided], prime)
                independent[undecided[ok]] = True
                undecided = undecided[~ok]
                if not len(undecided):
                    break
            if enough is None:
                for i in undecided:
                    sub = [[row[j] for j in subsets[i]] for row in self.int_rows]
                    independent[i] = rank(sub) == r
            yield subsets[independent]


def independent_chunks(rows, candidates, required, size) -> Iterator[np.ndarray]:
    """Independent column subsets as arrays of sorted indices, chunk by chunk, in lex order.

    Same arguments as :func:`independent_subsets`.

    Examples
    --------
    >>> from pitheorem.bases import independent_chunks
    >>> [c.tolist() for c in independent_chunks([[1, 0, 1], [0, 1, 1]], [0, 1, 2], [], 2)]
    [[[0, 1], [0, 2], [1, 2]]]
    """
    return _Enumerator(rows, candidates, required, size).chunks()


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
    for chunk in independent_chunks(rows, candidates, required, size):
        yield from map(tuple, chunk.tolist())


def count_independent_subsets(rows, candidates, required, size) -> int:
    """Count independent column subsets without building them.

    Examples
    --------
    >>> from pitheorem.bases import count_independent_subsets
    >>> count_independent_subsets([[1, 2, 0]], [0, 1, 2], [], 1)
    2
    """
    return _Enumerator(rows, candidates, required, size).count()
