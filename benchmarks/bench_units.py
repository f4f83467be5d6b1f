"""Time a change of units and a threshold check on the largest corpus model, against MuJoCo's own load.

The corpus is gymnasium's MuJoCo models and the MJCF files of tests/robots; the largest is the
one with the most parameters.  Timed, each the best of several calls:

* ``model.converted(L="mm", M="g")``: the same model in other units (a scaled copy, compiled);
* ``engines.check(model)``: every number against the engine's thresholds (and with the file's
  load, as ``pitheorem check`` pays it);
* ``pt.fit_units(model)``: units clear of those thresholds (the linear programs of the fit);

each against MuJoCo compiling the file once (``MjModel.from_xml_path``), the baseline a user pays
anyway.  The issue's goal: convert and check under 0.5 s each.

Run: python benchmarks/bench_units.py [--quick]
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

from _timing import best_of

import pitheorem as pt
from pitheorem import engines

ROBOTS = Path(__file__).resolve().parent.parent / "tests" / "robots" / "mjcf"


def corpus() -> list[Path]:
    import gymnasium

    assets = Path(gymnasium.__file__).parent / "envs" / "mujoco" / "assets"
    return sorted(assets.glob("*.xml")) + sorted(ROBOTS.glob("*.xml"))


def load_quiet(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", engines.UnscalableModelWarning)
        return engines.load(path)


def main(quick: bool = False) -> None:
    import mujoco

    repeat = 2 if quick else 5
    sizes = {path: len(load_quiet(path).parameters) for path in corpus()}
    path = max(sizes, key=lambda p: (sizes[p], p.name))
    model = load_quiet(path)
    model.converted(L="mm", M="g")  # MuJoCo's first compile of a spec, and pint's registry, once
    t_engine = best_of(lambda: mujoco.MjModel.from_xml_path(str(path)), repeat)
    t_convert = best_of(lambda: model.converted(L="mm", M="g"), repeat)
    t_check = best_of(lambda: engines.check(model), repeat)
    t_fit = best_of(lambda: pt.fit_units(model), repeat)
    t_load_check = best_of(lambda: engines.check(load_quiet(path)), repeat)
    print(f"largest corpus model: {path.parent.name}/{path.name} ({sizes[path]} parameters)")
    print(f"{'step':28s} {'seconds':>8s} {'x MuJoCo load':>14s}")
    print(f"{'MuJoCo load (baseline)':28s} {t_engine:8.4f} {1.0:14.1f}")
    for name, t in (
        ("converted(L='mm', M='g')", t_convert),
        ("engines.check", t_check),
        ("load + engines.check", t_load_check),
        ("pt.fit_units(model)", t_fit),
    ):
        print(f"{name:28s} {t:8.4f} {t / t_engine:14.1f}")
    ok = t_convert < 0.5 and t_check < 0.5
    print(f"goal (convert and check under 0.5 s each): {'met' if ok else 'NOT met'}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="two repetitions instead of five")
    main(parser.parse_args().quick)
