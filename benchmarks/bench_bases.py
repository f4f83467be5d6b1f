"""Time System.bases() against two baselines, in one run, and print ratios.

Baselines:
* plain: exact rational rank of every r-subset (what a textbook loop does);
  for large systems it is timed on a random sample of subsets and scaled up
  to the full count (marked "~").
* numpy-det: a vectorised float determinant (np.linalg.det on batches) of
  every r-subset, counting |det| > 1e-9.  Fast, but not exact: it is the
  speed to match, not a correct answer.

Synthetic systems: n variables over k = 7 base dimensions with small random
integer exponents (seeded, so every run sees the same systems).

A second table times listing every basis at n = 30, k = 7:
``len(list(system.bases()))`` against the numpy-det count (target: within
1.0 times), and the peak memory traced while ``bases()`` runs against the
bytes of the index array it returns (target: within 1.2 times); and the
peak memory of ``count_bases()`` against that of listing.

Run: python benchmarks/bench_bases.py [--quick]
"""

from __future__ import annotations

import argparse
import gc
import random
import tracemalloc
from itertools import combinations
from math import comb

import numpy as np
from _timing import sampled_seconds, timed

import pitheorem as pt
from pitheorem.bases import lex_combinations
from pitheorem.linalg import rank

BASES = ("M", "L", "T", "Theta", "I", "N", "J")


def synthetic_system(n: int, k: int = 7, seed: int = 0) -> pt.System:
    rng = random.Random(seed)
    variables = {}
    for j in range(n):
        exponents = {b: rng.choice((-2, -1, 0, 0, 0, 1, 1, 2)) for b in BASES[:k]}
        variables[f"x{j}"] = pt.Dimension(exponents)
    return pt.System(variables, base_dimensions=BASES[:k])  # N is an opt-in base


def matrix_of(system: pt.System) -> np.ndarray:
    return np.array(system.matrix.tolist(), dtype=float)


def numpy_det_count(system: pt.System, chunk: int = 1 << 17) -> int:
    d = matrix_of(system)
    r = system.rank
    count = 0
    combos = lex_combinations(d.shape[1], r)
    for start in range(0, len(combos), chunk):
        sub = np.transpose(d[:, combos[start : start + chunk]], (1, 0, 2))
        if d.shape[0] != r:  # rank-deficient rows: use the Gram determinant
            sub = sub.transpose(0, 2, 1) @ sub
        count += int((np.abs(np.linalg.det(sub)) > 1e-9).sum())
    return count


def plain_seconds(system: pt.System, sample: int | None) -> tuple[float, bool]:
    columns = [[system.dimension(v).exponent_of(b) for b in system.base_dimensions] for v in system.variables]
    subsets = combinations(range(len(columns)), system.rank)
    return sampled_seconds(
        lambda subset: rank([columns[j] for j in subset]), subsets, comb(len(columns), system.rank), sample
    )


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller systems only")
    args = parser.parse_args(argv)
    sizes = (10, 16, 20) if args.quick else (10, 16, 20, 25, 30, 35, 40)
    warm_up = synthetic_system(8)  # one-off costs (module imports, index tables) are not per-size work
    warm_up.count_bases()
    numpy_det_count(warm_up)
    print(
        f"{'n':>3} {'subsets':>10} {'bases':>10} {'pitheorem s':>12} {'numpy-det s':>12} "
        f"{'plain s':>10} {'vs numpy':>9} {'vs plain':>9}"
    )
    for n in sizes:
        system = synthetic_system(n)
        count, ours = timed(system.count_bases)
        det_count, det = timed(lambda s=system: numpy_det_count(s))
        plain, estimated = plain_seconds(system, sample=20_000)
        assert det_count == count, "the float determinant disagrees with the exact count"
        mark = "~" if estimated else " "
        print(
            f"{n:>3} {comb(n, system.rank):>10} {count:>10} {ours:>12.3f} {det:>12.3f} "
            f"{mark}{plain:>9.2f} {ours / det:>8.2f}x {plain / ours:>8.1f}x"
        )
    print(
        "\n'vs numpy' = pitheorem time / numpy-det time (target <= 2);"
        " 'vs plain' = plain time / pitheorem time (target >= 1); ~ = extrapolated from 20,000 subsets"
    )
    listing(25 if args.quick else 30)
    largest = synthetic_system(sizes[-1])
    count, peak = peak_bytes(largest.count_bases)
    print(f"  peak memory of count_bases() at n = {sizes[-1]}: {peak / 2**20:.2f} MiB for {count} bases")


def peak_bytes(fn):
    """Peak memory traced (Python objects and numpy buffers) while fn runs, and its value."""
    gc.collect()
    tracemalloc.start()
    try:
        value = fn()
        return value, tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def listing(n: int) -> None:
    system = synthetic_system(n)
    print(f"\nListing every basis, n = {n}, k = 7")
    length, ours = timed(lambda: len(list(system.bases())))
    det_count, det = timed(lambda: numpy_det_count(system))
    assert length == det_count, "the float determinant disagrees with the exact list"
    print(
        f"  len(list(system.bases())) = {length}: {ours:.3f} s; numpy-det count {det:.3f} s; "
        f"ratio {ours / det:.2f}x (target <= 1.0)"
    )
    bases, peak = peak_bytes(system.bases)
    held = bases.indices.nbytes
    as_int64 = len(bases) * system.rank * 8
    print(
        f"  peak memory of bases(): {peak / 2**20:.1f} MiB; its index array ({bases.indices.dtype}) "
        f"{held / 2**20:.1f} MiB; ratio {peak / held:.2f}x (target <= 1.2); "
        f"the same array in int64 {as_int64 / 2**20:.1f} MiB"
    )
    del bases
    count, count_peak = peak_bytes(system.count_bases)
    print(f"  peak memory of count_bases(): {count_peak / 2**20:.2f} MiB for {count} bases (no prefix table kept)")


if __name__ == "__main__":
    main()
