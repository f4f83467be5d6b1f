"""Time ``engines.load`` of an MJCF file against MuJoCo's own compile of it: generated files of a few sizes, or yours.

The generated file is ``n`` repeated bodies, each a free box with a hinged capsule, a site and a
motor (about 500 bytes and 55 numbers of the parameter table per body), so that every size has
the same mix of elements.  ``--files`` times model files of your own instead (real robots bring
meshes, tendons, sensors and skins).  Both are timed in the same run, each the best of a few calls:

* MuJoCo: ``mujoco.MjModel.from_xml_path`` (its parser and compiler);
* pitheorem: ``engines.load``, which reads the file as text and checks every attribute's numbers
  (parsed once by ElementTree: no NaN, no infinity, no negative inertial mass), has MuJoCo parse
  and compile it (``MjSpec.from_file`` and ``compile``: the work of MuJoCo's column again), and
  walks every element of the spec once.  The walk reads each dimensional attribute through
  MuJoCo's bindings (to tell a number the file sets from one it leaves out, and the file's from
  MuJoCo's default), gives it its name, path, dimension and source, and keeps a slot per number
  with the element's address, from which the table is made and a scaled copy written.  The
  table's ``Parameter`` objects are made when ``model.parameters`` is first asked for (a scaled
  copy that is only run never lists its numbers): outside the ``load`` column, and timed on its
  own in the column ``+table``.

The columns ``+table`` and the second ``ratio`` are what a user who loads a file and then lists
its parameters (``model.parameters``, ``model.system()``, a search) pays.  Issue 33's goal of 1.5
is stated for ``engines.load`` alone (the first ``ratio``), growing linearly with the file.  The
times are the process's CPU time (``time.process_time``), not the wall clock: on a machine shared
with other work the wall clock of the same compile varied by x2, the CPU time much less.  Run the
loop below from a folder that holds no checkout: ``python -c`` puts the current folder first on
the path, ahead of ``PYTHONPATH``, so that from a checkout both arms would time that checkout.

Measured on 2026-11-28 (2 cores, CPU time, best of 3 calls, one process per size and tree), at
commit 1d7ff07 ("before") and after a tendon's joints were read from the compiled model (the
spec's ``tendon.path`` took 70 microseconds a tendon), a skin's model compiled once (the second
compile only normalised its bone weights again), geoms' and joints' numbers read in one plan
each, and a sensor's dimension found in a table made once::

    for n in 100 250 500 1000 2000; do
      for tree in OLD NEW; do
        PYTHONPATH=$tree python -c "import sys; sys.path.insert(0, '$tree/benchmarks'); \
          import bench_load; bench_load.main([$n], 3)" | tail -1
      done
    done

======  =======  ===================  ===================  =================  ============
bodies  MuJoCo   load before          load after           ours per body      +table after
======  =======  ===================  ===================  =================  ============
   100  0.011 s  0.030 s (ratio 2.76)  0.029 s (ratio 2.57)  0.192 -> 0.179 ms  ratio 2.92
   250  0.053 s  0.097 s (ratio 1.83)  0.096 s (ratio 1.85)  0.176 -> 0.177 ms  ratio 2.03
   500  0.19 s   0.286 s (ratio 1.48)  0.274 s (ratio 1.42)  0.186 -> 0.162 ms  ratio 1.52
 1,000  0.79 s   0.968 s (ratio 1.24)  0.957 s (ratio 1.22)  0.184 -> 0.172 ms  ratio 1.27
 2,000  3.3 s    3.74 s (ratio 1.12)   3.75 s (ratio 1.11)   0.197 -> 0.186 ms  ratio 1.13
======  =======  ===================  ===================  =================  ============

Pitheorem's own part is flat per body from 100 to 2,000 bodies (linear in the file), and the goal
of 1.5 holds from 500 bodies on.  The same day, the same way, with ``--files`` on robots that
ship with dm_control, Gymnasium, Gymnasium-Robotics and MuJoCo Warp's tests (load's ratio,
before -> after): dm_control's dog 2.02 -> 1.11 (a skin: compiled twice before) and humanoid
1.08 -> 1.07; MuJoCo Warp's ALOHA scene 1.10 to 1.22 (noise of the machine: no change in its
walk) and ``n_humanoid`` 1.38 -> 1.34; the Shadow hand with 92 touch sensors 2.62 -> 1.77, the
Adroit pen (44 tendons) 3.27 -> 2.13; Gymnasium's ant 2.11 -> 1.80, humanoid 2.77 -> 2.37,
pusher 3.86 -> 3.25.  Of the 89 MJCF files of those four packages that load (each the best of 5
calls), every one that MuJoCo compiles in 25 ms or more loads within 1.4 (24 files), and the 58
over 1.5 all compile in under 11 ms.

Why a small file cannot come within 1.5 of MuJoCo's compile: MuJoCo parses and compiles 100 of
these bodies (5,521 numbers of the table) in 11 ms, 2 microseconds a number, in C.  Loading them
does that same work again (``MjSpec.from_file`` and ``compile``: 11 ms), so a ratio of 1.5 leaves
5.5 ms for the rest, 1 microsecond a number: the file's check (1.5 ms, of which ElementTree's
parse is 1) and the walk.  Reading one attribute through MuJoCo's bindings takes 0.1 to 0.45
microseconds (more on the first touch of a spec's element), keeping its slot 0.3, its name and
source 0.2: the walk's own floor, measured on a loop that does nothing else, is 0.8 to 1.1
microseconds a number, and the walk takes 2.1.  A file MuJoCo compiles in half a millisecond
(Gymnasium's pusher, the pendulum example) leaves a quarter of a millisecond for the check, the
walk and the call's own overhead (finding the format and the engine, opening the file), which
alone take more.  Skipping the walk altogether (measured the same day by loading with the walk
switched off, which no user could do: it leaves no table) brings 100 bodies to 1.04 and the Adroit
pen to 1.10, but leaves the pendulum example and Gymnasium's pusher at 1.65: a walk deferred until
the numbers are first asked for would not reach 1.5 at every size either, and every use of a
loaded model in pitheorem (the table, a scaled or converted copy, a verification) asks for them,
so that it would move the time, not save it.

Earlier measurements (the same generated file): on 2026-11-27, 500 bodies loaded in 2.9 times
MuJoCo's compile before the garbage collector was paused during the walk and the spec's geoms
were listed by a walk of its tree (2.0 after), and 2,000 bodies in 1.7 (1.2 after); "ours" per
body fell from 0.78 to 0.40 ms and stopped growing faster than the file.  On 2026-11-28 the
walker's plumbing (no numpy on tiny arrays, each actuator type and a joint kind's polynomial
terms found once, pint's unit names asked once per process) took it to 0.17 ms a body (500
bodies: 1.46), and the table's first build fell from 2.2 to 0.73 microseconds a number.

Run: python benchmarks/bench_load.py [--quick] [--sizes 100 250 500 1000 2000] [--files robot.xml ...]
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


def first_table(path, repeats: int) -> tuple[float, int]:
    """Least CPU time of the first ``model.parameters`` of a model just loaded from `path`, and its length."""
    best = float("inf")
    for _ in range(repeats):
        model = engines.load(path)
        start = time.process_time()
        table = model.parameters
        best = min(best, time.process_time() - start)
    return best, len(table)


def files(paths, repeat: int) -> None:
    """The same columns for model files of your own (real robots: meshes, tendons, sensors, skins)."""
    import mujoco

    print(f"{'MuJoCo':>8s} {'load':>8s} {'ratio':>6s} {'params':>7s} {'+table':>8s} {'ratio':>6s}  file")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        len(engines.load(engines.example_path("pendulum.xml")).parameters)  # imports and caches, outside the timings
        for path in map(Path, paths):
            t_engine = best_cpu(lambda path=path: mujoco.MjModel.from_xml_path(str(path)), repeat)
            t_load = best_cpu(lambda path=path: engines.load(path), repeat)
            t_table, params = first_table(path, repeat)
            print(
                f"{t_engine:7.4f}s {t_load:7.4f}s {t_load / t_engine:6.2f} {params:7d} "
                f"{t_table:7.4f}s {(t_load + t_table) / t_engine:6.2f}  {path}"
            )


def main(sizes, repeat: int) -> None:
    import mujoco

    print(
        f"{'bodies':>6s} {'file':>8s} {'params':>7s} {'MuJoCo':>8s} {'load':>8s} {'ratio':>6s} "
        f"{'ours':>7s} {'ours per body':>14s} {'+table':>8s} {'ratio':>6s}  (goal: load's ratio within 1.5)"
    )
    with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        len(engines.load(engines.example_path("pendulum.xml")).parameters)  # imports and caches, outside the timings
        for n in sizes:
            path = Path(folder) / f"repeated_{n}.xml"
            path.write_text(repeated_bodies(n), encoding="utf-8")
            t_engine = best_cpu(lambda path=path: mujoco.MjModel.from_xml_path(str(path)), repeat)
            t_load = best_cpu(lambda path=path: engines.load(path), repeat)
            # what a user who loads and then lists or searches the parameters pays more: the table, made on
            # first use (timed alone, each time on a model just loaded)
            t_table, params = first_table(path, repeat)
            ours = t_load - t_engine
            print(
                f"{n:6d} {path.stat().st_size / 1e6:6.2f}MB {params:7d} {t_engine:7.3f}s {t_load:7.3f}s "
                f"{t_load / t_engine:6.2f} {ours:6.3f}s {ours / n * 1e3:11.3f} ms "
                f"{t_table:7.3f}s {(t_load + t_table) / t_engine:6.2f}"
            )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help=f"sizes {QUICK}, one call each")
    parser.add_argument("--sizes", type=int, nargs="+", help=f"numbers of bodies (default {SIZES})")
    parser.add_argument("--files", nargs="+", help="MJCF files of your own to time instead (no generated file)")
    args = parser.parse_args()
    if args.files:
        files(args.files, 1 if args.quick else 3)
    else:
        main(args.sizes or (QUICK if args.quick else SIZES), 1 if args.quick else 3)
