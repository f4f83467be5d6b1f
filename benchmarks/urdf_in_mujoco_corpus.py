"""URDF in MuJoCo on pybullet_data's URDF files: which compile, and which verify bit for bit at s = 4.

Run with the engines installed (``pip install "pitheorem[engines]"``, which brings pybullet_data)::

    python benchmarks/urdf_in_mujoco_corpus.py [--duration 1.0] [--all] [NAME ...]
    python benchmarks/urdf_in_mujoco_corpus.py --gepetto DIR [--json FILE] [NAME ...]

For every URDF file of pybullet_data (the thousand generated ones under ``random_urdfs`` only with
``--all``; NAMEs select files by their path relative to pybullet_data), or with ``--gepetto DIR``
every robot of Gepetto's example-robot-data that ``docs/corpus_verdicts.py`` runs in PyBullet
(``GEPETTO_URDFS``; DIR a checkout or a bare git directory, read as that script reads it, with
the same meaning; a checkout of another folder name is linked as ``example-robot-data``, which its
``package://`` paths name; NAMEs select robots by their file name): load it with
``engine="mujoco"``, or the reason it is refused (by the URDF format or by MuJoCo); search a scaling
with gravity scaled by s and time fixed; verify the scaled copy at s = 4 for ``--duration`` seconds
under :func:`pitheorem.engines.smooth_controls` (a motor per movable joint).  At a power of four every
factor is exact in binary, so a faithful copy reproduces the original run bit for bit.

Prints one row per file: ``exact``, ``similar`` (within the twins' yardstick but not bit for bit),
``inconclusive`` (the run cannot show an error of some group), ``not`` (not similar) or ``refused``,
whether the run moved (``moved``) or the robot is welded to the world with no joint (``welded``),
and, where not exact, the causes the verdict names (``+``: its counter-run restores the run), the
scale-free proof (``rep.scale_free``: the solver's settings of no pure dimension, then MuJoCo's native
convex collision, made scale-free in both runs, then the solver's iterations capped alike in both) and
what plain MuJoCo shows (``by hand``): both compiled models stepped side by side with ``mj_step``
under the same input, and at the first step whose state is not exactly the original's times its
factor, whether the contacts MuJoCo found (depth, point, frame) are the original's times their
factors (if not, the collision code is not scale-free: which geom types), and how many constraint
rows have their softness R at MuJoCo's floor ``mjMINVAL`` = 1e-15 (a contact between bodies that
cannot move along it: MuJoCo's approximate inverse weight is 0 there, and the floor is a number no
scaling moves).  Where rows sit at that floor, the file is verified again under the same length and time
units with the mass unit kept (``mass unit kept``): R is an inverse mass, so the floor is the copy's true
R there, and the run shows whether the floor was the only cause.  Then a summary.

mujoco 4.0.0, pybullet_data's 95 files (``--duration 1.0``): MuJoCo compiles 71 and refuses 24; 58 are
exact (13 that move), 8 similar, 3 inconclusive (the PR2 gripper, ``minitaur_single_motor`` and
``diff_ring``: no gravity control leaves the original by ten times what the copy, parted at the softness
floor, does), 2 not similar (R2-D2 and ``minitaur_rainbow_dash_v1``).  Of the 13, 9
are exact by the scale-free proof: 8 with native convex collision off (the Panda, two Laikagos, five
minitaurs), and ``minitaur_rainbow_dash_v1`` with the tolerance at 0, native convex collision off and
the solver's iterations capped at 2 a step (MuJoCo's line search ends an island's iterations where its
direction falls under mjMINVAL, which the copy meets at other iterations; see
docs/howto/urdf_in_mujoco.md).  The other 4 have contacts at the softness floor (R2-D2, the PR2 gripper,
``minitaur_single_motor`` and ``differential/diff_ring``; the proof, capped at 1 iteration, still parts
them at the first step): with the mass unit kept, R2-D2 and the PR2 gripper are exact as written, the
other two exact with native convex collision off.  The whole run: 44 s.

With ``--gepetto``, each robot's ``package://example-robot-data/...`` meshes are found as
``engines.load(..., engine="mujoco")`` finds them (the scheme dropped, the rest looked for in the
folders above the URDF: the robots are written below a folder named ``example-robot-data``).  A robot
whose meshes the snapshot lacks (Git LFS, size limits) is reported ``not run`` with them named.  A
robot of more than ``LARGE_BODIES`` links runs ``LARGE_DURATION`` simulated seconds, as in
``docs/corpus_verdicts.py`` (the row says ``duration``).  ``--json FILE`` writes the rows, the
counts, the date, the commit and the versions (``docs/howto/urdf_in_mujoco_fetched.json``, which
the docs page reads).
"""

from __future__ import annotations

import argparse
import datetime
import importlib.util
import json
import platform
import shutil
import subprocess
import tempfile
import time
import warnings
import xml.etree.ElementTree as ET
from collections import Counter
from pathlib import Path

import mujoco
import numpy as np
import pybullet_data

import pitheorem as pt
from pitheorem import engines

DATA = Path(pybullet_data.getDataPath())
HERE = Path(__file__).resolve().parent


def corpus_verdicts():
    """``docs/corpus_verdicts.py``, imported: its example-robot-data list, reader and durations."""
    spec = importlib.util.spec_from_file_location("corpus_verdicts", HERE.parent / "docs" / "corpus_verdicts.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _files(everything: bool) -> list[str]:
    names = sorted(p.relative_to(DATA).as_posix() for p in DATA.rglob("*.urdf"))
    return [n for n in names if everything or not n.startswith("random_urdfs/")]


def _factor(dimension, change, s: float) -> float:
    return s ** float(sum(dimension.exponent_of(b) * change[b] for b in "MLT"))


def by_hand(model, copy, change, s: float, duration: float) -> str:
    """Plain MuJoCo: step both compiled models side by side and say where and why they part."""
    m, c = model.runner.mjmodel, copy.runner.mjmodel
    _names, dims = model.runner.coordinate_dimensions()
    fq = np.array([_factor(d, change, s) for d in dims[: m.nq]])
    fv = np.array([_factor(d, change, s) for d in dims[m.nq :]])
    fu = np.array([_factor(d, change, s) for d in model.inputs()[0]])
    length = _factor(pt.Dimension.parse("L"), change, s)
    u = engines.smooth_controls(model)
    d, e = mujoco.MjData(m), mujoco.MjData(c)
    for i in range(round(duration / m.opt.timestep)):
        before = mujoco.MjData(m), mujoco.MjData(c)
        for source, target in zip((d, e), before, strict=True):
            target.qpos[:], target.qvel[:], target.qacc_warmstart[:] = source.qpos, source.qvel, source.qacc_warmstart
        d.ctrl[:] = u(i * m.opt.timestep)
        e.ctrl[:] = d.ctrl * fu
        mujoco.mj_step(m, d)
        mujoco.mj_step(c, e)
        if np.array_equal(d.qpos * fq, e.qpos) and np.array_equal(d.qvel * fv, e.qvel):
            continue
        d0, e0 = before  # the step's start, equal in both: what MuJoCo computed from it
        d0.ctrl[:], e0.ctrl[:] = d.ctrl, e.ctrl
        d0.time, e0.time = i * m.opt.timestep, i * c.opt.timestep
        mujoco.mj_forward(m, d0)
        mujoco.mj_forward(c, e0)
        moved = set()
        for x, y in zip(d0.contact[: d0.ncon], e0.contact[: e0.ncon], strict=False):
            if not (
                x.dist * length == y.dist
                and np.array_equal(np.asarray(x.pos) * length, y.pos)
                and np.array_equal(x.frame, y.frame)
            ):
                moved.add("-".join(sorted(mujoco.mjtGeom(int(m.geom_type[g])).name[7:].lower() for g in x.geom)))
        geometry = f"contacts off in {', '.join(sorted(moved))}" if moved else "contacts scaled"
        if d0.ncon != e0.ncon:
            geometry = f"{d0.ncon} contacts, {e0.ncon} in the copy"
        floor = int(np.sum(d0.efc_R[: d0.nefc] <= 2 * mujoco.mjMINVAL))
        return f"by hand: parts at step {i + 1}; {geometry}; R at floor in {floor} of {d0.nefc} rows"
    return "by hand: exact"


def judge(path: Path, label: str, duration: float, hide: str | None = None) -> dict:
    """The verdict on one file (exact, similar, inconclusive, not, refused) and what stands behind it.

    `label` stands for the file's path in a refusal's message, and `hide` (a folder) is dropped from it.
    """
    row: dict = {"name": label, "duration": duration}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            model = engines.load(path, engine="mujoco")
        except pt.PiTheoremError as err:
            text = str(err).replace(str(path), label)
            if hide:
                text = text.replace(hide.rstrip("/") + "/", "")
            return {**row, "verdict": "refused", "reason": " ".join(text.split())[:300]}
        sc = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
        rep = engines.verify(model, sc, 4, duration=duration, controls=engines.smooth_controls(model))
    welded = model.runner.mjmodel.njnt == 0
    row["motion"] = "welded" if welded else "moved" if rep.excited else "still"
    if rep.exact:
        return {**row, "verdict": "exact"}
    row["verdict"] = {"not similar": "not"}.get(rep.verdict, rep.verdict)  # similar, inconclusive or not
    row["causes"] = [{"kind": c.kind, "element": c.element, "restores": bool(c.restores)} for c in rep.causes]
    change = {b: sc.unit_change[b] for b in "MLT"}
    free = rep.scale_free
    row["scale_free"] = "no scale-free proof" if free is None else free.text()
    row["by_hand"] = by_hand(model, model.scaled(sc, 4), change, 4, duration)
    floored = "R at floor in" in row["by_hand"] and "R at floor in 0 " not in row["by_hand"]  # rows at mjMINVAL
    if floored and change["M"] != 0:
        row["mass_kept"] = mass_kept(model, change, duration)
    return row


def detail(row: dict) -> str:
    """What stands behind a verdict, on one line."""
    if row["verdict"] == "refused":
        return row["reason"]
    if row["verdict"] == "not run":
        return row["reason"]
    if row["verdict"] == "exact":
        return row["motion"]
    causes = "; ".join(f"{c['kind']}{'+' if c['restores'] else ''} {c['element']}" for c in row["causes"])
    kept = f"; mass unit kept: {row['mass_kept']}" if "mass_kept" in row else ""
    return f"{row['motion']}; {causes or 'no cause named'}; {row['scale_free']}; {row['by_hand']}{kept}"


def mass_kept(model, change, duration: float) -> str:
    """The same lengths and time, the mass unit kept: the run that shows the softness floor is the only cause.

    A contact's softness R is an inverse mass; where MuJoCo holds it at its floor mjMINVAL in both runs, the
    floor is the copy's true R only when the mass unit is kept.  Verified as the file is written, and with
    its scale-free proof.
    """
    sc = pt.Scaling.from_unit_change(model.system(), {**change, "M": 0})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rep = engines.verify(model, sc, 4, duration=duration, controls=engines.smooth_controls(model))
    if rep.exact:
        return "exact"
    free = rep.scale_free
    return "not exact" if free is None else free.text().replace("scale-free: ", "")


def gepetto(source: Path, folder: Path) -> tuple[list[tuple[Path, str, str | None]], str | None]:
    """example-robot-data's robots, as ``docs/corpus_verdicts.py`` reads them: ``(path, name, why not run)``."""
    if (source / "robots").is_dir() and source.resolve().name != "example-robot-data":
        # a checkout of another name: package://example-robot-data/... is found from a folder of that name
        (folder / "example-robot-data").symlink_to(source.resolve(), target_is_directory=True)
        source = folder / "example-robot-data"
    items, commit = corpus_verdicts().gepetto_entries(source, folder)
    if commit is None and (source / ".git").exists():  # a git checkout: its commit
        git = ["git", "-C", str(source), "rev-parse", "HEAD"]
        done = subprocess.run(git, capture_output=True, text=True, check=False)
        commit = done.stdout.strip() or None
    return [(Path(i["path"]), i["name"], i.get("skip")) for i in items], commit


def links(path: Path) -> int:
    """The links of a URDF: the count ``docs/corpus_verdicts.py`` weighs a robot's duration by."""
    return len(ET.parse(path).getroot().findall("link"))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=1.0)
    parser.add_argument("--all", action="store_true", help="also the generated files under random_urdfs")
    parser.add_argument("--gepetto", type=Path, help="example-robot-data: a checkout or a bare git directory")
    parser.add_argument("--json", type=Path, help="write the rows, counts and versions to this file")
    parser.add_argument("names", nargs="*")
    args = parser.parse_args()
    folder = Path(tempfile.mkdtemp(prefix="pitheorem-urdf-mujoco-"))
    verdicts = corpus_verdicts()  # a robot of more than LARGE_BODIES links runs LARGE_DURATION seconds
    commit = None
    if args.gepetto is not None:
        robots, commit = gepetto(args.gepetto, folder)
        robots = [r for r in robots if not args.names or r[1] in args.names]
    else:
        robots = [(DATA / name, name, None) for name in (args.names or _files(args.all))]
    counts: Counter = Counter()
    moved: Counter = Counter()
    start = time.perf_counter()
    proved = 0  # not exact as written, but bit for bit with the settings of no pure dimension made scale-free
    kept = 0  # not exact, but bit for bit (as written or by that proof) with the mass unit kept
    rows = []
    for path, name, skip in robots:
        if skip is not None:
            row = {"name": name, "verdict": "not run", "reason": skip}
        else:
            large = args.gepetto is not None and links(path) > verdicts.LARGE_BODIES
            row = judge(path, name, verdicts.LARGE_DURATION if large else args.duration, hide=str(folder))
        rows.append(row)
        counts[row["verdict"]] += 1
        moved[row["verdict"]] += row.get("motion") == "moved"
        proved += "the copy is bit for bit the original" in row.get("scale_free", "")
        kept += row.get("mass_kept") == "exact" or "the copy is bit for bit the original" in row.get("mass_kept", "")
        shorter = f" [{row['duration']} s]" if row.get("duration", args.duration) != args.duration else ""
        print(f"{name:48s} {row['verdict']:8s} {detail(row)}{shorter}", flush=True)
    summary = (
        f"{len(robots)} files: "
        + ", ".join(
            f"{counts[v]} {v} ({moved[v]} moved)" for v in ("exact", "similar", "inconclusive", "not") if counts[v]
        )
        + f", {counts['refused']} refused"
        + (f", {counts['not run']} not run" if counts["not run"] else "")
        + f"; {proved} of the others exact by the scale-free proof"
        + f", {kept} with the mass unit kept (softness at MuJoCo's floor)"
    )
    print(f"\n{summary} | {time.perf_counter() - start:.0f} s")
    shutil.rmtree(folder, ignore_errors=True)
    if args.json is not None:
        data = record(rows, summary, args, commit, verdicts)
        args.json.write_text(json.dumps(data, indent=1) + "\n")


def record(rows: list[dict], summary: str, args, corpus_commit: str | None, verdicts) -> dict:
    """The JSON a docs page reads: the rows, the counts, the date, the commit and the versions."""
    commit = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=HERE, check=False
    ).stdout.strip()
    return {
        "generated": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d"),
        "versions": {
            "pitheorem": pt.__version__,
            "commit": commit or None,
            "mujoco": mujoco.__version__,
            "example-robot-data": corpus_commit,
            "python": platform.python_version(),
        },
        "settings": {
            "scale": "g",
            "fixed": ["t"],
            "s": 4,
            "controls": "engines.smooth_controls(model)",
            "duration": args.duration,
            "large_duration": verdicts.LARGE_DURATION,
            "large_bodies": verdicts.LARGE_BODIES,
        },
        "summary": summary,
        "robots": rows,
    }


if __name__ == "__main__":
    main()
