"""The support-minimal points of an affine family of exponent vectors, in vectorised batches.

:func:`pitheorem.search` reduces a request to a family ``a0 + span(V)``
(``d`` independent directions) and needs its minimal points: the distinct
points that vanish on ``d`` free variables whose direction columns are
independent.  For such a subset ``S``, expanding the ``(d+1) x (d+1)``
determinant of ``M = [V; a0]`` restricted to ``S`` plus one more column
``k`` along that column gives ``det(M[:, S + k]) = w . M[:, k]``, where the
cofactors ``w`` are the exterior product of ``M[:, S]``.  So, with
``w_d = det(V[:, S])``, the point is ``(w . M) / w_d``, zero on ``S``, and
its coordinates along ``V`` are ``w_i / w_d``: integers throughout.

Those integers are computed in float64 for thousands of subsets at once,
after a Hadamard bound in Python integers has proved every one of them
exact; each surviving subset is then confirmed in exact int64 arithmetic
(its point vanishes on ``S`` and keeps every prescribed exponent).  When
the bound fails, :func:`minimal_points` returns None and the caller uses
exact fractions instead.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from .bases import LaplaceTables, PrefixDescent, float_is_exact

__all__ = ["MinimalPoints", "minimal_points"]

# distinct points gathered before duplicates are merged again
_MERGE_EVERY = 1 << 16


class MinimalPoints(Sequence):
    """Minimal points with their coordinates, as exact fractions made on demand.

    Item ``i`` is ``(point, coords)``: tuples of Fraction, as
    :class:`pitheorem.scalesearch.SearchResult` keeps them.  Counting them
    makes none; the first iteration makes them all and keeps them, since
    tables read them once per variable.
    """

    __slots__ = ("_den", "_kept", "_keys", "_made", "_u0", "_weights")

    def __init__(self, keys: np.ndarray, weights: np.ndarray, den: int, u0, kept):
        self._keys = keys  # per point: [w_d, numerators...] in lowest terms, w_d > 0
        self._weights = weights  # per point: cofactors w of one subset giving it
        self._den = den
        self._u0 = tuple(u0)
        self._kept = [list(w) for w in kept]
        self._made: list | None = None

    def __len__(self) -> int:
        return len(self._keys)

    def _item(self, i: int):
        key = self._keys[i].tolist()
        scale = key[0] * self._den
        point = tuple(Fraction(p, scale) for p in key[1:])
        w = self._weights[i].tolist()
        z = [Fraction(x, w[-1]) for x in w[:-1]]
        coords = tuple(
            u + sum((zi * v[j] for zi, v in zip(z, self._kept, strict=True)), Fraction(0))
            for j, u in enumerate(self._u0)
        )
        return point, coords

    def __iter__(self):
        if self._made is None:
            self._made = [self._item(i) for i in range(len(self))]
        return iter(self._made)

    def __getitem__(self, index):
        if self._made is not None:
            return self._made[index]
        if isinstance(index, slice):
            return [self._item(i) for i in range(len(self))[index]]
        return self._item(range(len(self))[index])


def _support_keys(points: np.ndarray) -> np.ndarray:
    """One sortable value per point: its support as packed bits (first variable highest)."""
    packed = np.ascontiguousarray(np.packbits(points != 0, axis=1))
    return packed.view(np.dtype((np.void, packed.shape[1]))).ravel()


def _merge(supports, keys, weights):
    supports, first = np.unique(supports, return_index=True)
    return supports, keys[first], weights[first]


def minimal_points(
    a0_int: Sequence[int], dirs_int: Sequence[Sequence[int]], free: Sequence[int], constrained: Sequence[int]
):
    """Distinct minimal points of ``a0 + span(dirs)``, or None when floats cannot be proved exact.

    Parameters
    ----------
    a0_int, dirs_int : integer vectors
        The particular point and the directions, all times one common denominator.
    free : sequence of int
        Positions of the variables that may be held at zero.
    constrained : sequence of int
        Positions where every point must equal ``a0`` (prescribed and fixed).

    Returns
    -------
    tuple of (keys, weights) arrays, sorted fewest-changed-variables first, or None
        ``keys[i] = [w_d, p_1, ..., p_n]``: point ``i`` is ``p / (w_d * den)``.

    Examples
    --------
    >>> from pitheorem.family import minimal_points
    >>> keys, weights = minimal_points([1, 1, 0], [[0, 1, -1]], [1, 2], [0])
    >>> keys.tolist()
    [[1, 1, 1, 0], [1, 1, 0, 1]]
    """
    d = len(dirs_int)
    rows = [list(v) for v in dirs_int] + [list(a0_int)]
    if not float_is_exact(rows, d + 1):
        return None
    m_all = np.array(rows, dtype=float)
    tables = LaplaceTables.get(d + 1)
    free = np.asarray(free, dtype=np.int64)
    constrained = np.asarray(constrained, dtype=np.int64)
    a0_constrained = np.array([a0_int[j] for j in constrained], dtype=np.int64)
    parts, held, limit = [], 0, _MERGE_EVERY
    for subsets, minors in PrefixDescent(m_all[:, free], np.ones((1, 1)), 0).prefixes(d, 0):
        independent = minors[:, 0] != 0  # the minor without the a0 row is det(V[:, S])
        subsets, minors = subsets[independent], minors[independent]
        if not len(subsets):
            continue
        w = tables.last_column_weights(minors)
        points = (w @ m_all).astype(np.int64)  # exact integers, by the bound
        w = w.astype(np.int64)
        w_d = w[:, -1]
        # exact confirmation in integers: zero on S, the prescribed exponents kept
        on_s = np.take_along_axis(points, free[subsets], axis=1)
        kept = points[:, constrained] == w_d[:, None] * a0_constrained[None, :]
        if on_s.any() or not kept.all():
            return None
        sign = np.where(w_d < 0, -1, 1)[:, None]
        keys = np.hstack([w_d[:, None], points]) * sign
        keys //= np.gcd.reduce(keys, axis=1)[:, None]
        # two minimal points never share a support (the line through them would hold a point
        # of smaller support), so the support is the key for removing repeats
        part = _merge(_support_keys(points), keys, w)
        parts.append(part)
        held += len(part[0])
        if held > limit:  # merge repeats across chunks; the limit doubles, so merging costs O(total)
            parts = [_merge(*(np.concatenate(p) for p in zip(*parts, strict=True)))]
            held = len(parts[0][0])
            limit = max(limit, 2 * held)
    if not parts:
        return np.zeros((0, len(a0_int) + 1), dtype=np.int64), np.zeros((0, d + 1), dtype=np.int64)
    supports, keys, weights = (np.concatenate(p) for p in zip(*parts, strict=True))
    # confirm that repeated supports are repeated points, then keep one of each
    order = np.argsort(supports, kind="stable")
    supports, keys, weights = supports[order], keys[order], weights[order]
    repeat = supports[1:] == supports[:-1]
    if (keys[1:][repeat] != keys[:-1][repeat]).any():
        return None  # cannot happen (see above); exact code decides if it ever does
    unique = np.concatenate([[True], ~repeat])
    keys, weights, supports = keys[unique], weights[unique], supports[unique]
    # fewest changed variables first, then by their positions (lexicographically, as sorted lists):
    # among equal counts, the support holding the earliest differing variable, the larger packed value
    count = (keys[:, 1:] != 0).sum(axis=1)
    order = np.lexsort([np.arange(len(keys))[::-1], count])  # supports ascend, so reversed = descending
    return keys[order], weights[order]
