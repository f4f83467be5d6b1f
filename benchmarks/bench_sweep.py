"""Time engines.sweep of a gymnasium model at 13 scale factors against the same verifies one after another.

The baseline is what a user does without the sweep: ``engines.verify`` at each ``s`` in turn,
everything included (copies compiled, runs, yardstick, causes where the copy is not similar).
The sweep does the same verifications, spread over the machine's cores (a process pool of
forked workers); the ratio is the sweep's time over the baseline's, both timed in this run,
the best of ``--repeats`` tries each (the goal: at most 0.65 on 2 cores).  ``--dask`` also
times the sweep on a ``LocalCluster`` of one worker process per core, and checks that its
rows are those of the local sweep.

Where the gain comes from: the original's run and its three twins' do not depend on ``s``, so
the sweep runs them once (``pitheorem.engines.verdicts.verify.baseline``) and each ``s`` runs
only its copy and the first negative control, where verify alone runs all six every time; the
pool then spreads over the cores what a verify does between its batches (compiling the copy,
mapping back, comparing, the audit and counter-runs of a copy that is not similar).

Run: python benchmarks/bench_sweep.py [--model hopper.xml] [--duration 1] [--repeats 2] [--dask]
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np
from _timing import best_of, timed

import pitheorem as pt
from pitheorem import engines


def cpu_seconds(fn) -> float:
    """Processor seconds one call of `fn` takes, in this process and its worker processes."""
    import resource

    def used():
        mine, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
        return mine.ru_utime + mine.ru_stime + children.ru_utime + children.ru_stime

    start = used()
    fn()
    return used() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--model", default="hopper.xml", help="a file of gymnasium's MuJoCo assets")
    parser.add_argument("--duration", type=float, default=1.0, help="simulated seconds per run (default 1)")
    parser.add_argument("--repeats", type=int, default=2, help="best of this many tries (default 2)")
    parser.add_argument("--dask", action="store_true", help="also time a LocalCluster")
    args = parser.parse_args()

    import gymnasium

    path = Path(gymnasium.__file__).parent / "envs" / "mujoco" / "assets" / args.model
    model = engines.load(path)
    scaling = pt.search(model.system(), scale={"g": 1}).scalings[0]
    controls = engines.smooth_controls(model)
    s = tuple(float(v) for v in np.logspace(-3, 3, 13))

    def one_after_another():
        return [engines.verify(model, scaling, v, duration=args.duration, controls=controls) for v in s]

    def swept():
        return engines.sweep(model, scaling, s=s, duration=args.duration, controls=controls, fit=False)

    reports = one_after_another()  # warm: MuJoCo's first compile, imports
    sweep = swept()
    assert [r.verdict for r in reports] == list(sweep.verdicts), "the sweep's verdicts are not verify's"
    baseline = best_of(one_after_another, args.repeats)
    parallel = best_of(swept, args.repeats)
    load = os.getloadavg()[0]
    print(f"{args.model}: 13 scale factors from 1e-3 to 1e3, {args.duration:g} s each, {os.cpu_count()} cores")
    print(f"  verdicts: {', '.join(sweep.verdicts)}")
    print(f"  verify one after another  {baseline:8.2f} s   (processor time {cpu_seconds(one_after_another):.2f} s)")
    print(f"  engines.sweep (processes) {parallel:8.2f} s   ratio {parallel / baseline:.2f} (goal <= 0.65)")
    print(f"  (load average {load:.1f} on {os.cpu_count()} cores: other work on the machine shrinks any gain)")
    if args.dask:
        from distributed import Client, LocalCluster

        with (
            LocalCluster(n_workers=os.cpu_count(), threads_per_worker=1, dashboard_address=None) as cluster,
            Client(cluster) as client,
        ):

            def on_dask():
                return engines.sweep(
                    model, scaling, s=s, duration=args.duration, controls=controls, fit=False, client=client
                )

            remote, _ = timed(on_dask)  # warm: each worker reads the model once
            cluster_time = best_of(on_dask, args.repeats)
        same = "the same rows" if remote == sweep else "OTHER ROWS"
        print(f"  engines.sweep (LocalCluster) {cluster_time:5.2f} s   ratio {cluster_time / baseline:.2f}, {same}")


if __name__ == "__main__":
    main()
