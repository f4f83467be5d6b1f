"""Time pitheorem.engines on gymnasium's MuJoCo models and pybullet_data URDFs, against the engines' own work.

Two ratios, each against a baseline timed in the same run:

* ``load + system + search`` of every corpus model against MuJoCo's (or PyBullet's) own load of
  the file, with the absolute time of the largest model (the issue's goal: under 1 s);
* ``engines.verify`` of 1 s of simulated time (original run, scaled run, one-ulp baseline run,
  scaling and mapping back) against the original run alone (goal: within 4x).  The original run
  is the fastest way the package knows to run a model once: for MuJoCo its own ``rollout`` (the
  stepping loop in C), for PyBullet one client stepping in a Python loop.

Run: python benchmarks/bench_engines.py [--quick]
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np
from _timing import best_of

import pitheorem as pt
from pitheorem import engines


def corpus():
    import gymnasium
    import pybullet_data

    mjcf = sorted((Path(gymnasium.__file__).parent / "envs" / "mujoco" / "assets").glob("*.xml"))
    data = Path(pybullet_data.getDataPath())
    urdf = [data / n for n in ("cartpole.urdf", "pendulum5.urdf", "sphere2.urdf", "kuka_iiwa/model.urdf")]
    return mjcf, urdf


def load_quiet(path, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        return engines.load(path, **options)


def main(quick: bool = False):
    import mujoco

    mjcf, urdf = corpus()
    repeat = 1 if quick else 3
    print(f"{'model':34s} {'params':>6s} {'load+system+search':>19s} {'engine load':>12s} {'ratio':>7s}")
    largest = (0, None, 0.0)
    for path in mjcf:
        def ours(path=path):
            model = load_quiet(path)
            pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings  # noqa: B018

        t_ours = best_of(ours, repeat)
        t_engine = best_of(lambda path=path: mujoco.MjModel.from_xml_path(str(path)), repeat)
        n = len(load_quiet(path).parameters)
        largest = max(largest, (n, path.name, t_ours))
        print(f"{path.name:34s} {n:6d} {t_ours:17.3f} s {t_engine:10.4f} s {t_ours / t_engine:7.1f}")
    print(f"largest model {largest[1]} ({largest[0]} parameters): load + system + search {largest[2]:.3f} s "
          f"(goal: under 1 s)")
    print()
    print(f"{'model':34s} {'verify 1 s':>11s} {'original run':>13s} {'ratio':>7s}  (goal: within 4x)")
    cases = [(p, {}) for p in (mjcf[:3] if quick else mjcf)]
    cases += [(p, {"base_position": (0, 0, 1), "ground": True, "damping": 0.0, "split_impulse": False})
              for p in (urdf[:1] if quick else urdf)]
    for path, options in cases:
        model = load_quiet(path, **options)
        if model.engine == "mujoco":
            model = model.with_values(tolerance=0)
        sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
        scaled = model.scaled(sc, 10)
        n_steps = round(1.0 / model.backend.timestep())
        nu = len(model.backend.control_dimensions())

        def controls(t, nu=nu):
            return 0.3 * np.sin(2 * t + np.arange(nu))

        t_verify = best_of(lambda model=model, sc=sc, scaled=scaled, controls=controls: engines.verify(
            model, sc, 10, duration=1.0, controls=controls, scaled=scaled), repeat)
        t_run = best_of(lambda model=model, n=n_steps, controls=controls: model.backend.run(n, controls), repeat)
        print(f"{path.name:34s} {t_verify:9.3f} s {t_run:11.3f} s {t_verify / t_run:7.2f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer models, one repetition")
    main(parser.parse_args().quick)
