"""Time pitheorem.engines on gymnasium's, pybullet_data's and tests/robots' models against the engines' own work.

Two ratios, each against a baseline timed in the same run:

* ``load + system + search`` of every corpus model against MuJoCo's (or PyBullet's) own load of
  the file, with the absolute time of the largest model (the issue's goal: under 1 s);
* ``engines.verify`` of 1 s of simulated time at s = 10 under a smooth input, everything
  included (the scaled copy made and compiled, the original, the scaled run and the three one-ulp
  twins of the yardstick, mapping back), against what one plain run costs a user: compile the
  file and step it once with the same input (goal: within 4x for MJCF, 5x for URDF).  Two plain
  runs are timed for MuJoCo: the user's loop (``mj_step`` from Python, the input set before each
  step), and, stricter, the same steps in MuJoCo's ``rollout`` (the loop in C, which verify itself
  uses).  For PyBullet: one client loading the file and stepping in a Python loop.  Where the
  runs are not similar, verify also finds the causes (an audit and counter-runs, paid only
  then); the ``verdict`` column times the verdict alone (``diagnose=False``).  The verify table
  covers gymnasium's models, four pybullet_data URDFs and the robots of tests/robots (not with
  ``--quick``).

Issue 31's targets (the verdict within 3x a plain run, median over robots with meshes; with
causes within 10x; the three slowest under 20 s) are measured on dm_control's robots (and a
Menagerie checkout's) by ``--verdicts``, which runs ``bench_verdicts.py``.

Run: python benchmarks/bench_engines.py [--quick] [--verdicts [--menagerie DIR]]
"""

from __future__ import annotations

import argparse
import json
import warnings
from pathlib import Path

from _timing import best_of

import pitheorem as pt
from pitheorem import engines

ROBOTS = Path(__file__).resolve().parent.parent / "tests" / "robots"


def corpus():
    import gymnasium
    import pybullet_data

    mjcf = sorted((Path(gymnasium.__file__).parent / "envs" / "mujoco" / "assets").glob("*.xml"))
    data = Path(pybullet_data.getDataPath())
    urdf = [data / n for n in ("cartpole.urdf", "pendulum5.urdf", "sphere2.urdf", "kuka_iiwa/model.urdf")]
    return mjcf, urdf


def robots():
    """tests/robots: its MJCF files, and its URDF files each with its scene (ground or fixed base)."""
    scenes = json.loads((ROBOTS / "scenes.json").read_text())
    mjcf = [(p, {}) for p in sorted(ROBOTS.glob("mjcf/**/*.xml"))]
    urdf = [(p, {**scenes[p.stem], "damping": 0.0, "split_impulse": False}) for p in sorted(ROBOTS.glob("urdf/*.urdf"))]
    return mjcf + urdf


def label(path: Path) -> str:
    """A model's name in the tables: its file name, or its place in tests/robots."""
    return f"robots/{path.relative_to(ROBOTS).as_posix()}" if ROBOTS in path.parents else path.name


def load_scale_save(repeat: int) -> str:
    """Load, scale by 10 and save SUPERball (693 parameters, the largest shipped model) against MuJoCo's compile.

    Measured 2026-11-25 before issue 21's work on this machine: 64.5 ms for the same steps; 19 ms after it (3.3x).
    """
    import tempfile

    import mujoco

    path = engines.example_path("superball.xml")
    with tempfile.TemporaryDirectory() as folder:

        def ours():
            model = engines.load(path)
            model.scaled(pt.Scaling.from_unit_change(model.system(), {"L": 1}), 10).save(Path(folder) / "sb.xml")

        t_ours = best_of(ours, repeat)
    t_engine = best_of(lambda: mujoco.MjModel.from_xml_path(str(path)), repeat)
    return (
        f"superball.xml: load + scale + save {t_ours * 1e3:.1f} ms, MuJoCo's compile {t_engine * 1e3:.2f} ms "
        f"(ratio {t_ours / t_engine:.0f}); 64.5 ms before issue 21's work"
    )


def ratio(time, baseline) -> str:
    return "-" if time == "-" else f"{time / baseline:.2f}"


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
    print(load_scale_save(repeat))
    print(
        f"largest model {largest[1]} ({largest[0]} parameters): load + system + search {largest[2]:.3f} s "
        f"(goal: under 1 s)"
    )
    print()
    print(
        f"{'model':34s} {'verify 1 s':>11s} {'user loop':>10s} {'ratio':>6s} {'rollout':>9s} {'ratio':>6s}"
        f" {'verdict':>7s}  (goal: within 4x, URDF 5x)"
    )
    print("  verdict: where the runs are not similar verify also finds the causes (the audit, counter-runs);")
    print("  this column is the verdict alone (diagnose=False) over the user loop, the ratios beside it are")
    print("  verify's with its causes")
    cases = [(p, {}) for p in (mjcf[:3] if quick else mjcf)]
    cases += [
        (p, {"base_position": (0, 0, 1), "ground": True, "damping": 0.0, "split_impulse": False})
        for p in (urdf[:1] if quick else urdf)
    ]
    cases += [] if quick else robots()
    for path, options in cases:
        model = load_quiet(path, **options)
        sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
        n_steps = round(1.0 / model.timestep())
        controls = engines.smooth_controls(model)
        t_verify = best_of(
            lambda model=model, sc=sc, controls=controls: engines.verify(
                model, sc, 10, duration=1.0, controls=controls
            ),
            repeat,
        )
        diagnosed = engines.verify(model, sc, 10, duration=1.0, controls=controls).similar is False
        verdict = "-"
        if diagnosed:
            t_verdict = best_of(
                lambda model=model, sc=sc, controls=controls: engines.verify(
                    model, sc, 10, duration=1.0, controls=controls, diagnose=False
                ),
                repeat,
            )
            verdict = t_verdict
        if path.suffix == ".urdf":  # PyBullet reads the file in the run itself, stepping from Python
            t_loop = best_of(
                lambda path=path, n=n_steps, controls=controls, options=options: load_quiet(path, **options).run(
                    n, controls
                ),
                repeat,
            )
            print(
                f"{label(path):34s} {t_verify:9.3f} s {t_loop:8.3f} s {t_verify / t_loop:6.2f} {'':9s} {'':6s} "
                f"{ratio(verdict, t_loop):>7s}"
            )
            continue

        def user_loop(path=path, n=n_steps, controls=controls):
            m = mujoco.MjModel.from_xml_path(str(path))
            d = mujoco.MjData(m)
            dt = m.opt.timestep
            for i in range(n):
                d.ctrl[:] = controls(i * dt)
                mujoco.mj_step(m, d)

        def in_rollout(path=path, n=n_steps, controls=controls, model=model):
            mujoco.MjModel.from_xml_path(str(path))
            return model.run(n, controls)

        t_loop, t_rollout = best_of(user_loop, repeat), best_of(in_rollout, repeat)
        print(
            f"{label(path):34s} {t_verify:9.3f} s {t_loop:8.3f} s {t_verify / t_loop:6.2f} "
            f"{t_rollout:7.3f} s {t_verify / t_rollout:6.2f} {ratio(verdict, t_loop):>7s}"
        )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer models, one repetition")
    parser.add_argument("--verdicts", action="store_true", help="issue 31's targets on robots with meshes instead")
    parser.add_argument("--menagerie", type=Path, help="with --verdicts: a MuJoCo Menagerie checkout")
    args = parser.parse_args()
    if args.verdicts:
        import bench_verdicts

        bench_verdicts.main(args.menagerie, [], 1)
    else:
        main(args.quick)
