"""Time ``engines.load`` of a large MJCF file against MuJoCo's own compile of it, at three sizes.

The file is generated here: ``n`` repeated bodies, each a free box with a hinged capsule, a site and
a motor (about 570 bytes and 52 numbers of the parameter table per body), so that every size has
the same mix of elements.  Both are timed in the same run, each the best of a few calls:

* MuJoCo: ``mujoco.MjModel.from_xml_path`` (its parser and compiler);
* pitheorem: ``engines.load``, which checks the file's numbers, has MuJoCo parse and compile it
  (the same work again), and walks every element to list its dimensional numbers.

The times are the process's CPU time (``time.process_time``), not the wall clock: on a machine
shared with other work the wall clock of the same compile varied by x2, the CPU time much less.

Issue 33's goal: ``engines.load`` within 1.5 times MuJoCo's compile at every size, and growing
linearly with the file.  MuJoCo's own compile grows faster than the file (about x4.5 for x2 bodies
here), so the columns ``ours`` (load minus MuJoCo's compile) and ``ours per body`` show the part
that is pitheorem's, which should stay flat per body.

Measured on 2026-11-27 (2 shared cores, CPU time), before and after issue 33's work, in one run:

======  ======  =================  ===============  =================  ===============
bodies  MuJoCo  load before        ours per body    load after         ours per body
======  ======  =================  ===============  =================  ===============
   500  0.20 s  0.59 s (ratio 2.9)  0.78 ms         0.40 s (ratio 2.0)  0.40 ms
 1,000  0.78 s  1.73 s (ratio 2.2)  0.95 ms         1.19 s (ratio 1.5)  0.39 ms
 2,000  3.4 s   5.87 s (ratio 1.7)  1.24 ms         4.29 s (ratio 1.2)  0.42 ms
======  ======  =================  ===============  =================  ===============

Before, pitheorem's own part grew faster than the file (MuJoCo's listing of a spec's geoms is
quadratic, and Python's garbage collector scanned the growing table again and again); after, it
is 0.4 ms per body at every size.  The goal of 1.5 is met from 1,000 bodies on; below that the
walk's 0.4 ms per body (about 7 microseconds per number of the table) weighs more than MuJoCo's
compile, whose cost per body grows with the file.

Run: python benchmarks/bench_load.py [--quick] [--sizes 500 1000 2000]
"""

from __future__ import annotations

import argparse
import tempfile
import time
import warnings
from pathlib import Path

from pitheorem import engines

SIZES = (500, 1000, 2000)
QUICK = (100, 200, 400)


def repeated_bodies(n: int) -> str:
    """An MJCF model of `n` free bodies, each with a hinged child, a site and a motor on the hinge."""
    bodies, motors = [], []
    for i in range(n):
        bodies.append(
            f'<body name="b{i}" pos="{(i % 50) * 0.5} {(i // 50) * 0.5} 1"><freejoint name="f{i}"/>'
            f'<geom name="g{i}" type="box" size="0.1 0.1 0.05" mass="1" friction="1 0.005 0.0001"/>'
            f'<body name="c{i}" pos="0 0 0.1">'
            f'<joint name="h{i}" type="hinge" axis="0 1 0" damping="0.1" stiffness="2" range="-1 1" armature="0.01"/>'
            f'<geom name="k{i}" type="capsule" fromto="0 0 0 0.2 0 0" size="0.02" density="1000"/>'
            f'<site name="s{i}" pos="0.2 0 0" size="0.01"/></body></body>'
        )
        motors.append(f'<motor name="a{i}" joint="h{i}" gear="10" ctrlrange="-1 1" ctrllimited="true"/>')
    return (
        '<mujoco model="repeated"><option timestep="0.002" gravity="0 0 -9.81"/><worldbody>'
        '<geom name="floor" type="plane" size="50 50 0.1"/>\n'
        + "\n".join(bodies)
        + "\n</worldbody><actuator>\n"
        + "\n".join(motors)
        + "\n</actuator></mujoco>\n"
    )


def best_cpu(fn, repeats: int) -> float:
    """Least CPU time of `repeats` calls of `fn`, in seconds."""
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        fn()
        best = min(best, time.process_time() - start)
    return best


def main(sizes, repeat: int) -> None:
    import mujoco

    print(
        f"{'bodies':>6s} {'file':>8s} {'params':>7s} {'MuJoCo':>8s} {'load':>8s} {'ratio':>6s} "
        f"{'ours':>7s} {'ours per body':>14s}  (goal: ratio within 1.5)"
    )
    with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        engines.load(engines.example_path("pendulum.xml"))  # imports and caches, outside the timings
        for n in sizes:
            path = Path(folder) / f"repeated_{n}.xml"
            path.write_text(repeated_bodies(n), encoding="utf-8")
            t_engine = best_cpu(lambda path=path: mujoco.MjModel.from_xml_path(str(path)), repeat)
            t_load = best_cpu(lambda path=path: engines.load(path), repeat)
            params = len(engines.load(path).parameters)
            ours = t_load - t_engine
            print(
                f"{n:6d} {path.stat().st_size / 1e6:6.2f}MB {params:7d} {t_engine:7.3f}s {t_load:7.3f}s "
                f"{t_load / t_engine:6.2f} {ours:6.3f}s {ours / n * 1e3:11.3f} ms"
            )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help=f"sizes {QUICK}, one call each")
    parser.add_argument("--sizes", type=int, nargs=3, help=f"three numbers of bodies (default {SIZES})")
    args = parser.parse_args()
    main(args.sizes or (QUICK if args.quick else SIZES), 1 if args.quick else 3)
