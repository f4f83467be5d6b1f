"""The immutable, array-backed list of bases that :meth:`pitheorem.System.bases` returns."""

from __future__ import annotations

from bisect import bisect_right
from collections.abc import Iterable, Iterator, Sequence

import numpy as np

from .immutable import immutable

__all__ = ["BasisSequence"]


@immutable
class BasisSequence(Sequence):
    """Repeating-variable sets held as a compact index array, named on demand.

    A :class:`~collections.abc.Sequence` of tuples of variable names that
    compares equal to the list of those tuples; the names are made only
    when an item is read, so millions of bases cost a few bytes each.

    Parameters
    ----------
    names : sequence of str
        The system's variables; index ``j`` stands for ``names[j]``.
    chunks : iterable of numpy arrays
        Rows of variable indices, in order, in one or more blocks.

    Examples
    --------
    >>> import pitheorem as pt
    >>> bases = pt.System({"l": "L", "t": "T", "v": "L/T", "x": "L"}).bases()
    >>> len(bases), bases[0], bases[-1]
    (5, ('l', 't'), ('v', 'x'))
    >>> bases[1:3]
    [('l', 'v'), ('t', 'v')]
    >>> bases.indices.tolist()
    [[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]]
    >>> bases == [('l', 't'), ('l', 'v'), ('t', 'v'), ('t', 'x'), ('v', 'x')]
    True
    """

    __slots__ = ("_blocks", "_names", "_offsets", "_width")

    def __init__(self, names: Sequence[str], chunks: Iterable[np.ndarray], width: int | None = None):
        names = np.array(list(names), dtype=object)
        dtype = np.min_scalar_type(max(len(names) - 1, 0))
        blocks = []
        for chunk in chunks:
            if len(chunk):
                block = np.asarray(chunk).astype(dtype, copy=False)
                block.flags.writeable = False
                blocks.append(block)
        offsets = [0]
        for block in blocks:
            offsets.append(offsets[-1] + len(block))
        object.__setattr__(self, "_names", names)
        object.__setattr__(self, "_width", blocks[0].shape[1] if blocks else (width or 0))
        self._hold(blocks, offsets)

    def _hold(self, blocks: list[np.ndarray], offsets: list[int]) -> None:
        # the only writes after construction: the same bases, held as one block (see indices)
        object.__setattr__(self, "_blocks", blocks)
        object.__setattr__(self, "_offsets", offsets)

    def __reduce__(self):
        return (BasisSequence, (self._names.tolist(), [self.indices], self._width))

    @property
    def indices(self) -> np.ndarray:
        """The bases as a read-only array of variable positions, one row per basis.

        The smallest unsigned integer type that holds every position is used.
        """
        if len(self._blocks) != 1:
            whole = (
                np.concatenate(self._blocks)
                if self._blocks
                else np.zeros((0, self._width), dtype=np.min_scalar_type(max(len(self._names) - 1, 0)))
            )
            whole.flags.writeable = False
            self._hold([whole], [0, len(whole)])  # one copy, not the blocks and their concatenation
        return self._blocks[0]

    def __len__(self) -> int:
        return self._offsets[-1]

    def __getitem__(self, index):
        if isinstance(index, slice):
            return BasisSequence(self._names, [self.indices[index]], self._width)
        try:
            i = range(len(self))[index]
        except TypeError:
            raise TypeError(f"bases are indexed by integers or slices, not {type(index).__name__}") from None
        block = bisect_right(self._offsets, i) - 1
        return tuple(self._names[self._blocks[block][i - self._offsets[block]]].tolist())

    def __iter__(self) -> Iterator[tuple[str, ...]]:
        for block in self._blocks:
            if not self._width:  # rank 0: the empty set is the one basis
                yield from ((),) * len(block)
                continue
            for lo in range(0, len(block), 4096):
                rows = block[lo : lo + 4096]
                # zip builds each tuple in C: several times faster than tuple() per row
                yield from zip(*(self._names[rows[:, i]].tolist() for i in range(self._width)), strict=True)

    def __eq__(self, other) -> bool:
        if isinstance(other, BasisSequence):
            return (
                len(self) == len(other)
                and list(self._names) == list(other._names)
                and bool(np.array_equal(self.indices, other.indices))
            )
        if isinstance(other, Sequence) and not isinstance(other, str):
            return len(self) == len(other) and all(a == b for a, b in zip(self, other, strict=True))
        return NotImplemented

    __hash__ = None  # equal to lists, which are unhashable

    def __repr__(self) -> str:
        return repr(list(self))

    def _repr_pretty_(self, printer, cycle) -> None:
        """Jupyter and IPython show the sets as a list, wrapped one set per line when long."""
        printer.pretty(list(self))
