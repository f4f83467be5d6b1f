"""Write ``docs/howto/corpus_robots.json``: pitheorem's verdicts on robots nobody here wrote.

Usage::

    pip install -e ".[engines]" dm-control gymnasium
    pip install --no-deps robosuite gymnasium-robotics   # optional: more robots with meshes
    python docs/corpus_verdicts.py [--menagerie DIR] [--gepetto DIR] [--only REGEX]
                                   [--jobs N] [--timeout SECONDS] [--out FILE]

The corpus is every robot file that the installed packages and folders hold:

* dm_control's suite models (``dm_control/suite/*.xml``) and its locomotion walkers and
  third-party robots (the dog, the rodent, the fruit fly, the CMU humanoid, the ant, the
  Jaco arm and hand, ...), with their meshes;
* gymnasium's MuJoCo models (``gymnasium/envs/mujoco/assets/*.xml``);
* robosuite's robots (``robosuite/models/assets/robots/*/robot.xml``: arms, a humanoid, a
  quadruped, mobile manipulators, each alone with its meshes) and four of
  gymnasium-robotics' (Fetch, the Shadow hand, Adroit's hand), when installed (their files
  are only read: ``pip install --no-deps robosuite gymnasium-robotics`` is enough);
* the URDFs of Gepetto's ``example-robot-data`` (``--gepetto``: a checkout, or a bare git
  directory from which the robots are read with ``git cat-file``), one URDF per robot,
  run in PyBullet with the base fixed;
* with ``--menagerie DIR``, a local MuJoCo Menagerie checkout: every ``*/scene.xml``.

For each robot, in a process of its own (a crash or a time-out is recorded, not fatal):
load the file (:func:`pitheorem.engines.load`), search gravity times ``s`` with time fixed
(:func:`pitheorem.search`), save the scaled copy and load it again, then
:func:`pitheorem.engines.verify` it with :func:`pitheorem.engines.smooth_controls` as the
input

* at ``s = 4``, the proof: exact (bit for bit) or not, each cause with whether its
  counter-run restores the run (``cause.restores``), and the proof with the engine's
  settings of no pure dimension made scale-free in both runs (``rep.scale_free``);
* at ``s = 10``, the verdict (``rep.verdict``), the horizon of the twins (``rep.horizon``),
  the detection limit of the negative controls (``rep.detection_limit``, ``rep.controls``)
  and the causes;
* a deliberately wrong copy at ``s = 10``: gravity left at the original's value while
  everything else is scaled. It must never be called similar.

Every run lasts :data:`DURATION` of simulated time, or :data:`LARGE_DURATION` for a robot
with more than :data:`LARGE_BODIES` bodies (the JSON states each robot's). URDFs run as in
``docs/howto/corpus_verdicts.md``: PyBullet with no multibody damping, no split impulse
and ``solverResidualThreshold`` 0, here with the base fixed and no ground.

The JSON file records the date, the versions of pitheorem, MuJoCo, PyBullet, dm_control and
gymnasium, and the commit; it is committed, and ``docs/howto/corpus_robots.md`` renders it.
The Sphinx build only reads it: it needs neither dm_control nor the time to run this.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import datetime
import importlib.metadata
import importlib.util
import json
import math
import os
import pathlib
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time
import traceback
import warnings

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "howto" / "corpus_robots.json"
GEPETTO = pathlib.Path("/work/.mirror/Gepetto+example-robot-data/repo")

#: simulated seconds of every run; LARGE_DURATION for robots with more than LARGE_BODIES bodies
DURATION = 1.0
LARGE_DURATION = 0.25
LARGE_BODIES = 60

#: the scale factors: the proof (a power of four) and the verdict
S_PROOF, S_VERDICT = 4, 10

#: the verdicts a report can give (``SimilarityReport.verdict``)
VERDICTS = ("exact", "similar", "inconclusive", "not similar")

#: dm_control's locomotion walkers and third-party robots (paths below the package)
DM_LOCOMOTION = (
    "locomotion/walkers/assets/dog_v2/dog.xml",
    "locomotion/walkers/assets/rodent.xml",
    "locomotion/walkers/assets/fruitfly_v2/fruitfly.xml",
    "locomotion/walkers/assets/humanoid_CMU_V2020.xml",
    "locomotion/walkers/assets/jumping_ball/jumping_ball_with_head.xml",
    "locomotion/soccer/assets/boxhead/boxhead.xml",
    "third_party/ant/ant.xml",
    "third_party/kinova/jaco_arm.xml",
    "third_party/kinova/jaco_hand.xml",
)

#: gymnasium-robotics' files that are whole robots, alone (paths below its ``envs/assets`` folder)
ROBOTICS = ("fetch/reach.xml", "hand/reach.xml", "adroit_hand/adroit_door.xml", "adroit_hand/adroit_relocate.xml")

#: one URDF per robot of example-robot-data (paths below its ``robots`` folder)
GEPETTO_URDFS = (
    "a1_description/urdf/a1.urdf",
    "alex_description/urdf/alex_nub_hands.urdf",
    "allegro_hand_description/urdf/allegro_right_hand.urdf",
    "anymal_c_simple_description/urdf/anymal.urdf",
    "asr_twodof_description/urdf/TwoDofs.urdf",
    "b1_description/urdf/b1.urdf",
    "baxter_description/urdf/baxter.urdf",
    "bluevolta_description/urdf/bluevolta_bravo7_gripper.urdf",
    "bolt_description/robots/bolt.urdf",
    "borinot_description/urdf/borinot_flying_arm_2.urdf",
    "bravo7_description/urdf/bravo7_gripper.urdf",
    "double_pendulum_description/urdf/double_pendulum.urdf",
    "finger_edu_description/robots/finger_edu.urdf",
    "go1_description/urdf/go1.urdf",
    "go2_description/urdf/go2.urdf",
    "hextilt_description/urdf/hextilt_flying_arm_5.urdf",
    "hyq_description/robots/hyq_no_sensors.urdf",
    "icub_description/robots/icub_reduced.urdf",
    "iris_description/robots/iris_simple.urdf",
    "kinova_description/robots/kinova.urdf",
    "laikago_description/urdf/laikago.urdf",
    "panda_description/urdf/panda.urdf",
    "quadruped_description/urdf/quadruped.urdf",
    "romeo_description/urdf/romeo_small.urdf",
    "simple_humanoid_description/urdf/simple_humanoid.urdf",
    "solo_description/robots/solo12.urdf",
    "talos_data/robots/talos_reduced.urdf",
    "tiago_description/robots/tiago.urdf",
    "tiago_pro_description/robots/tiago_pro.urdf",
    "ur_description/urdf/ur5_robot.urdf",
    "z1_description/urdf/z1.urdf",
)

#: PyBullet's scene for the URDFs, and the setting with no pure dimension set to 0
URDF_OPTIONS = {"fixed_base": True, "damping": 0.0, "split_impulse": False}
URDF_VALUES = {"solverResidualThreshold": 0}


def version(package: str) -> str | None:
    try:
        return importlib.metadata.version(package)
    except importlib.metadata.PackageNotFoundError:
        return None


# -- the corpus ------------------------------------------------------------------------------


def mjcf_entries(menagerie: pathlib.Path | None) -> list[dict]:
    """Every MJCF robot of the corpus: ``{"corpus", "name", "path", "engine"}`` each."""
    out = []
    try:
        import dm_control
    except ImportError:
        print("dm_control is not installed: its models are left out", file=sys.stderr)
    else:
        root = pathlib.Path(dm_control.__file__).parent
        for path in sorted((root / "suite").glob("*.xml")):
            out.append(entry("dm_control suite", path.name, path))
        for name in DM_LOCOMOTION:
            if (root / name).is_file():
                parts = name.split("/")
                label = "/".join(parts[-2:]) if parts[-2] != "assets" else parts[-1]
                out.append(entry("dm_control locomotion", label, root / name))
    try:
        import gymnasium
    except ImportError:
        print("gymnasium is not installed: its models are left out", file=sys.stderr)
    else:
        assets = pathlib.Path(gymnasium.__file__).parent / "envs" / "mujoco" / "assets"
        out += [entry("gymnasium", path.name, path) for path in sorted(assets.glob("*.xml"))]
    out += [entry(corpus, name, path) for corpus, name, path in packaged_robots()]
    if menagerie is not None:
        for path in sorted(menagerie.glob("*/scene.xml")):
            out.append(entry("MuJoCo Menagerie", path.parent.name, path))
    return out


def packaged_robots() -> list[tuple[str, str, pathlib.Path]]:
    """robosuite's robot files and gymnasium-robotics' whole robots, where installed: ``(corpus, name, path)``.

    Also read by ``benchmarks/bench_verdicts.py``.  A package not installed is said on stderr.
    """
    out = []
    robosuite = package_dir("robosuite")
    if robosuite is None:
        print("robosuite is not installed: its robots are left out (pip install --no-deps robosuite)", file=sys.stderr)
    else:
        for path in sorted((robosuite / "models" / "assets" / "robots").glob("*/robot.xml")):
            out.append(("robosuite", path.parent.name, path))
    robotics = package_dir("gymnasium_robotics")
    if robotics is None:
        print(
            "gymnasium-robotics is not installed: its robots are left out (pip install --no-deps gymnasium-robotics)",
            file=sys.stderr,
        )
    else:
        out += [("gymnasium-robotics", name, robotics / "envs" / "assets" / name) for name in ROBOTICS]
    return out


def package_dir(name: str) -> pathlib.Path | None:
    """Where an installed package lies, found without importing it (robosuite's import pulls in much else)."""
    spec = importlib.util.find_spec(name)
    if spec is None or not spec.submodule_search_locations:
        return None
    return pathlib.Path(spec.submodule_search_locations[0])


def gepetto_entries(source: pathlib.Path | None, folder: pathlib.Path) -> tuple[list[dict], str | None]:
    """The URDFs of example-robot-data, extracted below `folder` when `source` is a bare git dir."""
    if source is None or not source.exists():
        print("no example-robot-data (--gepetto): its URDFs are left out", file=sys.stderr)
        return [], None
    missing: set[str] = set()
    if (source / "robots").is_dir():  # a checkout
        root, commit = source, None
    else:  # a bare git directory: the robots read with git cat-file
        git = ["git", "--git-dir", str(source)]
        commit = subprocess.run([*git, "rev-parse", "HEAD"], capture_output=True, text=True, check=True).stdout
        commit = commit.strip()
        root = folder / "example-robot-data"  # package://example-robot-data/... resolves from here
        root.mkdir(parents=True, exist_ok=True)
        robots = sorted({"robots/" + name.split("/")[0] for name in GEPETTO_URDFS})
        missing = extract(git, robots, root)
    out = []
    for name in GEPETTO_URDFS:
        path = root / "robots" / name
        item = entry("example-robot-data", name.split("/")[-1], path, engine="pybullet")
        absent = sorted(set(meshes(path)) & missing) if path.is_file() else [f"robots/{name}"]
        if absent and (f"robots/{name}" in missing or path.is_file()):
            item["skip"] = f"absent from the snapshot: {', '.join(a.split('/')[-1] for a in absent)}"
        if path.is_file() or "skip" in item:
            out.append(item)
    return out, commit


def meshes(urdf: pathlib.Path) -> list[str]:
    """The files a URDF of example-robot-data names, as paths inside the repository."""
    import xml.etree.ElementTree as ET

    names = (m.get("filename", "") for m in ET.parse(urdf).getroot().iter("mesh"))
    return [n.removeprefix("package://example-robot-data/") for n in names if n]


def extract(git: list[str], folders: list[str], root: pathlib.Path) -> set[str]:
    """Write the files of `folders` at HEAD below `root`; the paths of those the snapshot lacks."""
    listing = subprocess.run([*git, "ls-tree", "-r", "HEAD", *folders], capture_output=True, text=True, check=True)
    blobs = [line.split(None, 3) for line in listing.stdout.splitlines()]
    blobs = [(sha, name) for _mode, kind, sha, name in blobs if kind == "blob"]
    request = "".join(f"{sha}\n" for sha, _ in blobs).encode()
    answer = subprocess.run([*git, "cat-file", "--batch"], input=request, capture_output=True, check=True).stdout
    missing = set()
    at = 0
    for _sha, name in blobs:
        end = answer.index(b"\n", at)
        header = answer[at:end].split()
        at = end + 1
        if header[-1] == b"missing":
            missing.add(name)
            continue
        n = int(header[2])
        target = root / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(answer[at : at + n])
        at += n + 1
    return missing


def entry(corpus: str, name: str, path: pathlib.Path, engine: str = "mujoco") -> dict:
    return {"corpus": corpus, "name": name, "path": str(path), "engine": engine}


# -- one robot -------------------------------------------------------------------------------


def judge(item: dict) -> dict:
    """The row of one robot: its proof at s = 4, its verdict at s = 10 and the wrong copy's."""
    import pitheorem as pt
    from pitheorem import engines

    start = time.perf_counter()
    path = pathlib.Path(item["path"])
    row = {"corpus": item["corpus"], "name": item["name"], "engine": item["engine"]}
    if "skip" in item:
        return {**row, "error": f"not run: {item['skip']}"}
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="pitheorem-corpus-"))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", engines.UnscalableModelWarning)
        if item["engine"] == "pybullet":
            model = engines.load(path, **URDF_OPTIONS).with_values(**URDF_VALUES)
        else:
            model = engines.load(path)
    row["load_warnings"] = sorted({str(w.message).split(": ", 1)[-1] for w in caught})
    row["parameters"] = len(model.parameters)
    row["inputs"] = len(model.inputs()[0])
    row.update(size(item, model))
    duration = LARGE_DURATION if row.get("bodies", 0) > LARGE_BODIES else DURATION
    row["duration"] = duration
    tick = time.perf_counter()
    scaling = pt.search(model.system(), scale={"g": 1}, fixed=("t",)).scalings[0]
    row["search_seconds"] = round(time.perf_counter() - tick, 3)
    controls = engines.smooth_controls(model)
    suffix = ".urdf" if item["engine"] == "pybullet" else ".xml"
    for key, s in (("proof", S_PROOF), ("verdict", S_VERDICT)):
        saved = model.scaled(scaling, s).save(tmp / f"copy_{s}{suffix}")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", engines.UnscalableModelWarning)
            again = engines.load(saved)  # the saved file, reloaded
        tick = time.perf_counter()
        rep = engines.verify(model, scaling, s, duration=duration, controls=controls, scaled=again)
        row[key] = report_row(rep, s, time.perf_counter() - tick)
    gravity = model.parameter("g").value
    if any(v != 0 for v in gravity):
        # everything scaled but gravity: the copy a user gets who forgets it
        wrong = model.scaled(scaling, S_VERDICT).multiplied(g=1 / S_VERDICT)
        tick = time.perf_counter()
        rep = engines.verify(
            model, scaling, S_VERDICT, duration=duration, controls=controls, scaled=wrong, diagnose=False
        )
        row["wrong_gravity"] = report_row(rep, S_VERDICT, time.perf_counter() - tick)
    else:
        row["wrong_gravity"] = None  # no gravity to leave unscaled
    row["seconds"] = round(time.perf_counter() - start, 2)
    shutil.rmtree(tmp, ignore_errors=True)
    return row


def size(item: dict, model) -> dict:
    """Bodies, degrees of freedom, meshes of a robot (MuJoCo's counts; a URDF's links), gravity switched off."""
    if item["engine"] == "mujoco":
        import mujoco

        m = mujoco.MjModel.from_xml_path(item["path"])
        off = bool(m.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_GRAVITY)
        return {"bodies": int(m.nbody) - 1, "dofs": int(m.nv), "meshes": int(m.nmesh), "gravity_off": off}
    import xml.etree.ElementTree as ET

    root = ET.parse(item["path"]).getroot()
    meshes = {m.get("filename") for m in root.iter("mesh") if m.get("filename")}
    joints = [j for j in root.iter("joint") if j.get("type") not in ("fixed", None)]
    return {"bodies": len(root.findall("link")), "dofs": len(joints), "meshes": len(meshes), "gravity_off": False}


def report_row(rep, s, seconds: float) -> dict:
    """What the page shows of one report."""

    def number(x):
        return None if x is None or not math.isfinite(float(x)) else float(x)

    yardstick = max(rep.sensitivity.values()) if rep.sensitivity else None
    return {
        "s": s,
        "verdict": rep.verdict,
        "exact": bool(rep.exact),
        "excited": bool(rep.excited),
        "max_deviation": number(rep.max_deviation),
        "yardstick": number(yardstick),
        "horizon": number(rep.horizon),
        "detection_limit": number(rep.detection_limit),
        "inconclusive": bool(rep.inconclusive),
        "controls": [{"group": c.group, "error": c.error, "caught": bool(c.caught)} for c in rep.controls],
        "first_divergence": None
        if rep.first_divergence is None
        else [number(rep.first_divergence[0]), str(rep.first_divergence[1])],
        "causes": [
            {"kind": c.kind, "element": c.element, "detail": c.detail, "restores": c.restores} for c in rep.causes
        ],
        "scale_free": None if rep.scale_free is None else scale_free_row(rep.scale_free, number),
        "engine_reset": None if rep.engine_reset is None else [number(rep.engine_reset[0]), rep.engine_reset[1]],
        "seconds": round(seconds, 2),
    }


def scale_free_row(free, number) -> dict:
    """The proof with the engine's settings of no pure dimension made scale-free in both runs."""
    where = free.first_divergence
    return {
        "settings": [[str(name), str(value)] for name, value in free.settings],
        "exact": bool(free.exact),
        "first_divergence": None if where is None else [number(where[0]), str(where[1])],
        "text": free.text(),
    }


# -- the whole corpus ------------------------------------------------------------------------


def run_one(item: dict, timeout: float) -> dict:
    """Judge one robot in a process of its own; a crash or a time-out becomes the row's error."""
    tick = time.perf_counter()
    head = {"corpus": item["corpus"], "name": item["name"], "engine": item["engine"]}
    try:
        done = subprocess.run(
            [sys.executable, __file__, "--one", json.dumps(item)],
            capture_output=True,
            text=True,
            timeout=timeout,
            check=False,
        )
    except subprocess.TimeoutExpired:
        return {**head, "error": f"timed out after {timeout:.0f} s", "seconds": round(time.perf_counter() - tick, 2)}
    lines = done.stdout.strip().splitlines()
    if done.returncode == 0 and lines:
        return json.loads(lines[-1])
    tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
    return {**head, "error": f"exit {done.returncode}: {tail}", "seconds": round(time.perf_counter() - tick, 2)}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--menagerie", type=pathlib.Path, help="a MuJoCo Menagerie checkout: every */scene.xml")
    parser.add_argument(
        "--gepetto",
        type=pathlib.Path,
        default=GEPETTO if GEPETTO.exists() else None,
        help="example-robot-data: a checkout or a bare git directory",
    )
    parser.add_argument("--only", help="judge only the robots whose corpus/name matches this regex")
    parser.add_argument("--jobs", type=int, default=1, help="robots judged at once (default 1)")
    parser.add_argument("--timeout", type=float, default=900.0, help="seconds per robot (default 900)")
    parser.add_argument("--out", type=pathlib.Path, default=OUT)
    parser.add_argument("--one", help=argparse.SUPPRESS)  # internal: judge one robot, print its row
    args = parser.parse_args(argv)
    if args.one:
        try:
            row = judge(json.loads(args.one))
        except Exception as exc:  # the row records any failure, by its message
            traceback.print_exc()
            item = json.loads(args.one)
            row = {**{k: item[k] for k in ("corpus", "name", "engine")}, "error": f"{type(exc).__name__}: {exc}"}
        print(json.dumps(row))
        return 0

    folder = pathlib.Path(tempfile.mkdtemp(prefix="pitheorem-corpus-"))
    items = mjcf_entries(args.menagerie)
    urdfs, gepetto_commit = gepetto_entries(args.gepetto, folder)
    items += urdfs
    if args.only:
        items = [i for i in items if re.search(args.only, f"{i['corpus']}/{i['name']}")]
    start = time.perf_counter()
    rows = [None] * len(items)
    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        futures = {pool.submit(run_one, item, args.timeout): k for k, item in enumerate(items)}
        for future in concurrent.futures.as_completed(futures):
            k = futures[future]
            rows[k] = future.result()
            print(summary(rows[k]), flush=True)
    commit = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=HERE, check=False
    ).stdout.strip()
    import pitheorem

    data = {
        "generated": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d"),
        "versions": {
            "pitheorem": pitheorem.__version__,
            "commit": commit or None,
            "mujoco": version("mujoco"),
            "pybullet": version("pybullet"),
            "dm_control": version("dm-control"),
            "gymnasium": version("gymnasium"),
            "robosuite": version("robosuite"),
            "gymnasium-robotics": version("gymnasium-robotics"),
            "example-robot-data": gepetto_commit,
            "python": platform.python_version(),
        },
        "settings": {
            "scale": "g",
            "fixed": ["t"],
            "s_proof": S_PROOF,
            "s_verdict": S_VERDICT,
            "controls": "engines.smooth_controls(model) (amplitude 0.3, period 0.5 s)",
            "duration": DURATION,
            "large_duration": LARGE_DURATION,
            "large_bodies": LARGE_BODIES,
            "urdf_options": {**URDF_OPTIONS, **URDF_VALUES},
        },
        "machine": {"cpus": os.cpu_count(), "jobs": args.jobs},
        "seconds": round(time.perf_counter() - start, 1),
        "robots": rows,
    }
    shutil.rmtree(folder, ignore_errors=True)
    args.out.write_text(json.dumps(data, indent=1) + "\n")
    print(f"{len(rows)} robots in {data['seconds']:.0f} s: {args.out}")
    return 0


def summary(row: dict) -> str:
    """One line per robot as it is judged."""
    head = f"{row['corpus']}/{row['name']} ({row.get('seconds', '?')} s)"
    if "error" in row:
        return f"{head}: ERROR {row['error']}"
    wrong = row["wrong_gravity"]
    return (
        f"{head}: s=4 {row['proof']['verdict']}, s=10 {row['verdict']['verdict']}, "
        f"wrong g {wrong['verdict'] if wrong else '-'}"
    )


if __name__ == "__main__":
    sys.exit(main())
