"""Time pitheorem.search against a brute-force baseline, in one run, and print ratios.

The baseline finds the minimal scalings the obvious way: for every subset
of the free variables, hold it at zero as well, solve exactly, keep the
unique solutions, then discard those whose support contains another's.
That is 2^(free) exact solves, so for larger systems it is timed on a
sample of subsets and scaled up to the full count (marked "~").

Request: scale one variable by s, hold four others fixed (seeded random
choices), on synthetic systems of n variables over k = 7 base dimensions.

A second part times the worst case of issue 13: one variable scaled,
``fixed=()``, k = 7, so a family of dimension 6, at n = 22 (target: under
1 s), against the exact algorithm it replaced (one exact-fraction solve per
independent subset, still pitheorem's fallback), run in the same process;
every minimal scaling and its coordinates must agree exactly.

Run: python benchmarks/bench_search.py [--quick]
"""

from __future__ import annotations

import argparse
import random
from fractions import Fraction
from itertools import combinations
from unittest import mock

from _timing import sampled_seconds, timed
from bench_bases import synthetic_system

import pitheorem as pt
from pitheorem.linalg import nullspace, solve


def request(system: pt.System, seed: int = 1):
    rng = random.Random(seed)
    names = list(system.variables)
    rng.shuffle(names)
    return {names[0]: 1}, tuple(names[1:5])


def brute_force_seconds(system, scale, fixed, sample: int | None):
    bases = system.base_dimensions
    col = {n: [system.dimension(n).exponent_of(b) for b in bases] for n in system.variables}
    free = [n for n in system.variables if n not in scale and n not in fixed]
    subsets = (z for k in range(len(free) + 1) for z in combinations(free, k))

    def solve_holding(zero):
        held = [*scale, *fixed, *zero]
        rows = [col[n] for n in held]
        if solve(rows, [scale.get(n, Fraction(0)) for n in held]) is not None:
            nullspace(rows, len(bases))

    return sampled_seconds(solve_holding, subsets, 2 ** len(free), sample)


def search_and_count(system, scale, fixed):
    """The search and its count of minimal scalings (the count runs the enumeration: it is timed too)."""
    result = pt.search(system, scale=scale, fixed=fixed)
    return result, result.n_scalings


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller systems only")
    args = parser.parse_args(argv)
    sizes = (10, 14, 20) if args.quick else (10, 14, 20, 30, 40, 50, 60)
    print(f"{'n':>3} {'minimal':>8} {'pitheorem s':>12} {'brute s':>14} {'speed-up':>12}")
    for n in sizes:
        system = synthetic_system(n, seed=n)
        scale, fixed = request(system)
        (_result, count), ours = timed(
            lambda system=system, scale=scale, fixed=fixed: search_and_count(system, scale, fixed)
        )
        brute, estimated = brute_force_seconds(system, scale, fixed, sample=2_000)
        mark = "~" if estimated else " "
        print(f"{n:>3} {count:>8} {ours:>12.4f} {mark}{brute:>13.3g} {brute / ours:>11.3g}x")
    print(
        "\nspeed-up = brute-force time / pitheorem time; ~ = extrapolated from 2,000 subsets."
        "  Target: n = 40 under 0.5 s."
    )
    worst_case(16 if args.quick else 22)


def worst_case(n: int) -> None:
    system = synthetic_system(n, seed=n)
    scale = {system.variables[0]: 1}
    (result, count), ours = timed(lambda: search_and_count(system, scale, ()))
    with mock.patch("pitheorem.family.minimal_points", return_value=None):  # the exact per-subset path
        (exact, exact_count), baseline = timed(lambda: search_and_count(system, scale, ()))
    same = count == exact_count and list(result._enumerate()) == list(exact._enumerate())
    assert same, "batched and exact minimal scalings differ"
    print(f"\nWorst case, n = {n}, k = 7, one variable scaled, fixed=(), family dimension {len(result.directions)}:")
    print(
        f"  {count} minimal scalings: pitheorem {ours:.3f} s (target < 1 s); exact per-subset solves "
        f"{baseline:.2f} s; speed-up {baseline / ours:.0f}x; every scaling and its coordinates identical: {same}"
    )


if __name__ == "__main__":
    main()
