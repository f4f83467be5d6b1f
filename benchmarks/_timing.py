"""How the benchmark scripts time things: the best of several calls, one call, and a sampled loop.

Each ``bench_*.py`` script times pitheorem and its baselines with these, so every ratio it prints
compares times taken the same way.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from itertools import islice

__all__ = ["best_of", "sampled_seconds", "timed"]


def best_of(fn: Callable[[], object], repeats: int) -> float:
    """Fastest of `repeats` calls of `fn`, in seconds (the least disturbed by other load)."""
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best


def timed(fn: Callable[[], object]) -> tuple[object, float]:
    """The value of one call of `fn`, and the seconds it took."""
    start = time.perf_counter()
    value = fn()
    return value, time.perf_counter() - start


def sampled_seconds(
    work: Callable[[object], object], items: Iterable, total: int, sample: int | None
) -> tuple[float, bool]:
    """Seconds `work` takes over all `total` items, timed on the first `sample` of them and scaled up.

    Returns the seconds and whether they were extrapolated (a table marks those with "~").
    ``sample=None``, or a sample of at least `total`, times every item.
    """
    if sample is not None and total > sample:
        items = islice(items, sample)
    else:
        sample = total
    start = time.perf_counter()
    for item in items:
        work(item)
    return (time.perf_counter() - start) * total / sample, sample < total
