"""Time engines.verify on robots nobody here wrote against one plain run of each, and print the ratios.

The baseline, timed in the same run for each robot, is what one plain run costs a user:
compile the file with MuJoCo and step it for 1 s of simulated time from Python, setting the
same smooth input before each step.  Against it, for gravity times s with time fixed:

* the verdict alone (``diagnose=False``) at s = 4 and s = 10: the original, the scaled
  copy (made and compiled), the twins of the yardstick and the first negative control in one
  batch, and the other controls where that one passes unnoticed;
* the verdict with its causes (``diagnose=True``): the audit and the counter-runs where the
  runs are not exact at s = 4 or not similar at s = 10.

Issue 31's targets: the median verdict within 3x a plain run, with causes within 10x, and
the three slowest robots under 20 s each.  The corpus is dm_control's model files (suite and
locomotion, with meshes; ``pip install dm-control``), gymnasium's, robosuite's twelve robots
(arms, a humanoid, quadrupeds, mobile manipulators, each with its meshes) and four of
gymnasium-robotics' (Fetch, the Shadow hand, Adroit), each when installed
(``pip install --no-deps robosuite gymnasium-robotics``: only their files are read), and
every ``*/scene.xml`` of a MuJoCo Menagerie checkout given with ``--menagerie DIR``.
Times are the best of ``--repeat`` (default 1).

Run: python benchmarks/bench_verdicts.py [--menagerie DIR] [--only NAME ...] [--repeat N]
"""

from __future__ import annotations

import argparse
import importlib.util
import statistics
import warnings
from pathlib import Path

from _timing import best_of

import pitheorem as pt
from pitheorem import engines

#: dm_control's files that are whole robots (the others are included pieces or arenas)
DM_SUITE = (
    "acrobot cartpole cheetah dog finger fish hopper humanoid humanoid_CMU manipulator pendulum "
    "point_mass quadruped reacher swimmer walker"
).split()
DM_LOCOMOTION = ("walkers/assets/rodent.xml", "walkers/assets/fruitfly_v2/fruitfly.xml")


def corpus(menagerie: Path | None) -> list[Path]:
    out = []
    try:
        import dm_control
    except ImportError:
        print("dm_control is not installed: its models are left out (pip install dm-control)")
    else:
        root = Path(dm_control.__file__).parent
        out += [root / "suite" / f"{name}.xml" for name in DM_SUITE]
        out += [root / "locomotion" / rel for rel in DM_LOCOMOTION]
    try:
        import gymnasium
    except ImportError:
        print("gymnasium is not installed: its models are left out")
    else:
        out += sorted((Path(gymnasium.__file__).parent / "envs" / "mujoco" / "assets").glob("*.xml"))
    # robosuite's robot files and gymnasium-robotics' (real arms, hands and mobile manipulators with meshes):
    # the corpus page's, found without importing the packages (pip install --no-deps is enough)
    out += [path for _corpus, _name, path in _corpus_page().packaged_robots()]
    if menagerie is not None:
        out += sorted(Path(menagerie).glob("*/scene.xml"))
    return [p for p in out if p.exists()]


def _corpus_page():
    """docs/corpus_verdicts.py, the corpus page's script, whose lists of robots this benchmark shares."""
    path = Path(__file__).resolve().parents[1] / "docs" / "corpus_verdicts.py"
    spec = importlib.util.spec_from_file_location("corpus_verdicts", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def plain_run(path: Path, controls, n_steps: int) -> None:
    """What a user pays for one run: compile, then step from Python with the input set before each step."""
    import mujoco

    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    dt = m.opt.timestep
    for i in range(n_steps):
        d.ctrl[:] = controls(i * dt)
        mujoco.mj_step(m, d)


def main(menagerie: Path | None, only: list[str], repeat: int) -> None:
    warnings.simplefilter("ignore")
    files = [p for p in corpus(menagerie) if not only or any(o in str(p) for o in only)]
    print(
        f"{'robot':28s} {'plain':>8s} {'v s=4':>6s} {'v s=10':>6s} {'c s=4':>6s} {'c s=10':>6s} {'slowest':>8s}  verdicts"
    )
    verdict_ratios, cause_ratios, slowest, meshed = [], [], [], []
    for path in files:
        name = path.parent.name if path.name in ("scene.xml", "robot.xml") else path.stem
        try:
            model = engines.load(path)
            sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
        except pt.PiTheoremError as err:
            print(f"{name:28s} refused: {str(err).splitlines()[0][:80]}")
            continue
        controls = engines.smooth_controls(model)
        n_steps = round(1.0 / model.runner.timestep())
        base = best_of(lambda p=path, u=controls, n=n_steps: plain_run(p, u, n), repeat)
        cells, verdicts, worst = [], [], 0.0
        for diagnose in (False, True):
            for s in (4, 10):
                reports = []

                def one(s=s, diagnose=diagnose, reports=reports, model=model, sc=sc, controls=controls):
                    reports.append(engines.verify(model, sc, s, duration=1.0, controls=controls, diagnose=diagnose))

                took = best_of(one, repeat)
                worst = max(worst, took)
                (cause_ratios if diagnose else verdict_ratios).append(took / base)
                cells.append(f"{took / base:6.1f}")
                if diagnose:
                    verdicts.append(f"{reports[-1].verdict}({len(reports[-1].causes)})")
        slowest.append((worst, name))
        if model.runner.mjmodel.nmesh:  # the corpus: robots with meshes
            meshed.append((verdict_ratios[-2:], cause_ratios[-2:]))
        print(f"{name:28s} {base:7.3f}s {' '.join(cells)} {worst:7.2f}s  {' '.join(verdicts)}")
    if not verdict_ratios:
        return
    print()
    print(f"median verdict / plain run, every robot:       {statistics.median(verdict_ratios):.2f}x")
    print(f"median with causes / plain run, every robot:   {statistics.median(cause_ratios):.2f}x")
    if meshed:
        v = statistics.median(r for rows, _ in meshed for r in rows)
        c = statistics.median(r for _, rows in meshed for r in rows)
        print(f"robots with meshes ({len(meshed)}): median verdict {v:.2f}x (target: at most 3x), with causes {c:.2f}x")
        print("  (target: at most 10x); a plain run of a few milliseconds (gymnasium's small models) is mostly")
        print("  the fixed cost of a verification, not its runs")
    top = ", ".join(f"{n} {t:.1f} s" for t, n in sorted(slowest, reverse=True)[:3])
    print(f"three slowest verifications: {top} (target: under 20 s each)")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--menagerie", type=Path, help="a MuJoCo Menagerie checkout: every */scene.xml")
    parser.add_argument("--only", nargs="*", default=[], help="robots whose path contains one of these")
    parser.add_argument("--repeat", type=int, default=1, help="best of this many runs (default 1)")
    args = parser.parse_args()
    main(args.menagerie, args.only, args.repeat)
