"""MJX on gymnasium's MuJoCo models: which load, and verify at s = 4 (bit for bit?) and s = 10.

Run with an environment that has MJX (``pip install "pitheorem[mjx]"``)::

    python benchmarks/mjx_corpus.py [--duration 0.2]

For each of gymnasium's 14 MJCF files: load it in MJX (float32), or the reason MJX refuses it; search with
gravity scaled and time fixed; verify the scaled copy at s = 4 (which must reproduce the original bit for bit)
and at s = 10 (judged against the one-ulp yardstick), with a smooth open-loop input and the solver's
tolerance at 0 in both runs (it is no scale-free stopping rule).  Prints one line per model and the seconds
each took (JIT compilation on the CPU included).
"""

from __future__ import annotations

import argparse
import time
import warnings
from pathlib import Path

import gymnasium

import pitheorem as pt
from pitheorem import engines

ASSETS = Path(gymnasium.__file__).resolve().parent / "envs" / "mujoco" / "assets"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=0.2)
    parser.add_argument("models", nargs="*", default=sorted(p.name for p in ASSETS.glob("*.xml")))
    args = parser.parse_args()
    for name in args.models:
        start = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", engines.UnscalableModelWarning)
            try:
                model = engines.load(ASSETS / name, engine="mjx")
            except pt.PiTheoremError as err:
                print(f"{name:28s} refused: {err}")
                continue
        if model.parameter("tolerance").value[0] != 0:
            model = model.with_values(tolerance=0)
        sc = pt.search(model.system(), scale={"g": 1}, fixed=("timestep",)).scalings[0]
        u = engines.smooth_controls(model)
        four = engines.verify(model, sc, s=4, duration=args.duration, controls=u, diagnose=False)
        ten = engines.verify(model, sc, s=10, duration=args.duration, controls=u, diagnose=False)
        print(
            f"{name:28s} s=4 exact {four.exact!s:5} excited {four.excited!s:5} | s=10 similar {ten.similar!s:5} "
            f"max deviation {ten.max_deviation:.3g} | {time.perf_counter() - start:.1f} s",
            flush=True,
        )


if __name__ == "__main__":
    main()
