"""Time one Pi set against bridgman and sympy's nullspace, in one run, and print ratios.

Each tool starts from the variables' dimensions in its own natural input
and ends with a set of integer exponent vectors of dimensionless groups:

* pitheorem: ``System`` from dimension strings, then ``pi_groups()`` (default
  repeaters).  The parse cache is cleared before every call, so each call
  pays for parsing as a single call in a fresh process would.
* bridgman: ``bridgman.pi_groups`` on dicts of integer exponents.
* sympy: ``Matrix(...).nullspace()`` on the integer dimension matrix.

Systems: the white paper's hinged rod, SUPERball (pitheorem's example
file), and a synthetic system of n = 40 variables over k = 7 base dimensions.
Also times ``pi_groups()`` at n = 40 on its own (target: under 50 ms).

Run: python benchmarks/bench_pi_set.py [--quick]
"""

from __future__ import annotations

import argparse

import bridgman
import sympy
from _timing import best_of
from bench_bases import synthetic_system

import pitheorem as pt
from pitheorem import system as system_module
from pitheorem.modelfile import example_path


def cases():
    rod = pt.load_model_file(example_path("hinged_rod")).system
    superball = pt.load_model_file(example_path("superball")).system
    yield "hinged rod", rod
    yield "SUPERball", superball
    yield "n=40, k=7", synthetic_system(40)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repetitions")
    args = parser.parse_args(argv)
    repeats = 20 if args.quick else 100
    print(
        f"{'system':<11} {'n':>3} {'groups':>6} {'pitheorem ms':>13} {'bridgman ms':>12} {'sympy ms':>9} "
        f"{'vs fastest':>10}  (target <= 1.0)"
    )
    for label, system in cases():
        strings = {n: str(d) for n, d in system.dimensions.items()}
        ints = {n: {b: int(p) for b, p in d.exponents.items()} for n, d in system.dimensions.items()}
        matrix = [[ints[n].get(b, 0) for n in system.variables] for b in system.base_dimensions]

        def ours(strings=strings, bases=system.base_dimensions):
            system_module._parse.cache_clear()
            return pt.System(strings, base_dimensions=bases).pi_groups()

        groups = ours()
        assert len(groups) == len(bridgman.pi_groups(ints)) == len(sympy.Matrix(matrix).nullspace())
        t_ours = best_of(ours, repeats)
        t_bridgman = best_of(lambda ints=ints: bridgman.pi_groups(ints), repeats)
        t_sympy = best_of(lambda matrix=matrix: sympy.Matrix(matrix).nullspace(), repeats)
        fastest = min(t_bridgman, t_sympy)
        print(
            f"{label:<11} {len(system.variables):>3} {len(groups):>6} {t_ours * 1e3:>13.3f} {t_bridgman * 1e3:>12.3f} "
            f"{t_sympy * 1e3:>9.3f} {t_ours / fastest:>9.2f}x"
        )
    big = synthetic_system(40)
    t_default = best_of(
        lambda: pt.System(big.dimensions, base_dimensions=big.base_dimensions).pi_groups(), max(3, repeats // 10)
    )
    print(
        f"\npi_groups() with no arguments at n=40, k=7 (System built from Dimensions): "
        f"{t_default * 1e3:.2f} ms (target < 50 ms)"
    )
    print(f"best of {repeats} calls each; 'vs fastest' = pitheorem time / min(bridgman, sympy)")


if __name__ == "__main__":
    main()
