"""Where a pybullet_data robot's runs part in MuJoCo, each cause removed in turn, by hand in plain MuJoCo.

Run with the engines installed::

    python benchmarks/urdf_in_mujoco_partings.py [NAME] [--mass M] [--length L] [--time T] [--steps N]

NAME (default ``quadruped/minitaur_rainbow_dash_v1.urdf``: a path below pybullet_data, or the path of
any URDF file, such as one of example-robot-data's written out by ``urdf_in_mujoco_corpus.py --gepetto``) is loaded with ``engine="mujoco"`` and scaled
at s = 4 under the change of units given (default: lengths by s, the mass unit and time kept, so that no
contact's softness at MuJoCo's floor mjMINVAL plays a part).  Both compiled models are stepped side by
side with ``mj_step`` under :func:`pitheorem.engines.smooth_controls` (the copy's inputs times their
factors), each time with the same options changed in both: as written; native convex collision off;
then also the line search's ``ls_tolerance`` at 0; then ``tolerance`` at 0 (every iteration run); then
that with ``iterations`` capped in both runs, at the most the original takes in a step as written (native
convex collision off; the most of any island), that halved, down to 1 (the scale-free proof's last ways,
``pitheorem.engines.verdicts.scalefree.capped_ways``).  Prints the first step whose state is not the
original's times its factors, and, where that is step 1 with ``tolerance`` 0, the first count of solver
iterations at which that step is no longer bit for bit, and each island's iterations in that step.

``minitaur_rainbow_dash_v1`` (mujoco 4.0.0, 1500 steps): steps 10, 41, 123 and 1; step 1 is bit for bit
with up to 6 iterations, not with 7; its islands (one per leg) stop after 100, 100, 3 and 6 iterations in
the original, 100 in each in the copy: the line search stops an island where the norm of its direction
falls under mjMINVAL (``mujoco_minval_search``), and the copy's slides accelerate 4 times as much.  Capped
at 5 (the most as written), 2 and 1 iteration: steps 3, 896 and none.  With ``--length 0 --mass 1`` bit
for bit in every way.  With ``--mass -2`` (the issue's scaling, masses by 1/16) the same steps, the same
islands' iterations, the same caps.
"""

from __future__ import annotations

import argparse
import copy as copy_module
import warnings
from pathlib import Path

import mujoco
import numpy as np
from urdf_in_mujoco_corpus import DATA, _factor

import pitheorem as pt
from pitheorem import engines

#: the options changed in both runs, each row adding to the one before
WAYS = (
    ("as written", {}),
    ("native convex collision off", {"nativeccd": True}),
    ("and ls_tolerance 0", {"nativeccd": True, "ls_tolerance": 0.0}),
    ("and tolerance 0", {"nativeccd": True, "ls_tolerance": 0.0, "tolerance": 0.0}),
)


def changed(compiled, options: dict, iterations: int | None = None):
    """A copy of a compiled model with the options of one way (and a count of iterations) set."""
    m = copy_module.copy(compiled)
    if options.get("nativeccd"):
        m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_NATIVECCD
    for name in ("ls_tolerance", "tolerance"):
        if name in options:
            setattr(m.opt, name, options[name])
    if iterations is not None:
        m.opt.iterations = iterations
    return m


def parting(m, c, u, fq, fv, fu, n_steps: int) -> int | None:
    """The first step whose state in the copy is not the original's times its factors (None: none)."""
    d, e = mujoco.MjData(m), mujoco.MjData(c)
    for i in range(n_steps):
        d.ctrl[:] = u(i * m.opt.timestep)
        e.ctrl[:] = d.ctrl * fu
        mujoco.mj_step(m, d)
        mujoco.mj_step(c, e)
        if not (np.array_equal(d.qpos * fq, e.qpos) and np.array_equal(d.qvel * fv, e.qvel)):
            return i + 1
    return None


def urdf_path(name: str) -> Path:
    """A NAME below pybullet_data, or a file's own path."""
    return DATA / name if (DATA / name).is_file() else Path(name)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("name", nargs="?", default="quadruped/minitaur_rainbow_dash_v1.urdf")
    parser.add_argument("--mass", type=int, default=0)
    parser.add_argument("--length", type=int, default=1)
    parser.add_argument("--time", type=int, default=0)
    parser.add_argument("--steps", type=int, default=500)
    args = parser.parse_args()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = engines.load(urdf_path(args.name), engine="mujoco")
    change = {"M": args.mass, "L": args.length, "T": args.time}
    scaling = pt.Scaling.from_unit_change(model.system(), change)
    original, scaled = model.runner.mjmodel, model.scaled(scaling, 4).runner.mjmodel
    dims = model.runner.coordinate_dimensions()[1]
    fq = np.array([_factor(d, change, 4) for d in dims[: original.nq]])
    fv = np.array([_factor(d, change, 4) for d in dims[original.nq :]])
    fu = np.array([_factor(d, change, 4) for d in model.inputs()[0]])
    u = engines.smooth_controls(model)
    print(f"{args.name}, units changed by {change}, s = 4, {args.steps} steps")
    for label, options in WAYS:
        step = parting(changed(original, options), changed(scaled, options), u, fq, fv, fu, args.steps)
        print(f"  {label:30s} {'bit for bit' if step is None else f'part at step {step}'}")
        if step == 1 and "tolerance" in options:
            first = next(
                k
                for k in range(1, original.opt.iterations + 1)
                if parting(changed(original, options, k), changed(scaled, options, k), u, fq, fv, fu, 1) == 1
            )
            print(f"  {'':30s} step 1 bit for bit with up to {first - 1} solver iterations, not with {first}")
            islands = []
            for compiled in (original, scaled):
                m = changed(compiled, options)
                d = mujoco.MjData(m)
                d.ctrl[:] = u(0) * (1 if compiled is original else fu)
                mujoco.mj_step(m, d)
                islands.append([int(n) for n in d.solver_niter[: max(1, d.nisland)]])
            print(f"  {'':30s} each island's iterations at step 1: {islands[0]}, in the copy {islands[1]}")
    capped = dict(WAYS[-1][1])
    most = most_iterations(changed(original, {"nativeccd": True}), u, args.steps)
    caps = [most]
    while caps[-1] > 1:
        caps.append(caps[-1] // 2)
    for cap in caps:
        step = parting(changed(original, capped, cap), changed(scaled, capped, cap), u, fq, fv, fu, args.steps)
        label = f"and iterations {cap}" + (" (the most)" if cap == most else "")
        print(f"  {label:30s} {'bit for bit' if step is None else f'part at step {step}'}")


def most_iterations(m, u, n_steps: int) -> int:
    """The most solver iterations any island takes in a step of a run as written."""
    d = mujoco.MjData(m)
    most = 0
    for i in range(n_steps):
        d.ctrl[:] = u(i * m.opt.timestep)
        mujoco.mj_step(m, d)
        most = max(most, int(np.max(d.solver_niter[: max(1, d.nisland)])))
    return most


if __name__ == "__main__":
    main()
