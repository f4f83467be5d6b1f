"""Survey the robot corpus of tests/robots with pitheorem.engines: load, search, verify at s = 4 and s = 10.

Not a test (it asserts nothing): a table for the lead of issue 22, written to ``tests/robots/SURVEY.md``.
Run from the repository root::

    .venv/bin/python tests/robots/survey.py                 # the committed corpus, writes SURVEY.md
    .venv/bin/python tests/robots/survey.py --print         # the same table on stdout, SURVEY.md untouched
    .venv/bin/python tests/robots/survey.py --diagnose      # counter-runs for each file not exact at s = 4
    .venv/bin/python tests/robots/survey.py --fetched /tmp/robots/menagerie/unitree_go1/scene.xml ...

For each file (and URDF scene): ``engines.load`` (timed), the number of parameters,
``pt.search(model.system(), scale={"g": 1})``, then ``engines.verify(model, scalings[0], s, duration=1.0,
controls=smooth)`` at s = 4 and s = 10, where ``smooth`` is a small sinusoid per input: for an MJCF actuator
with a control range, the middle of the range (or 0 when 0 lies inside it) plus 0.2 of the distance to the
nearer bound times sin(3 t + i); without a range, 0.1 sin(3 t + i); for a URDF joint, 0.05 of its effort
limit times sin(3 t + i).  Every exception is recorded with its type and message, never raised.
"""

from __future__ import annotations

import argparse
import sys
import time
import traceback
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import pitheorem as pt
from pitheorem import engines

HERE = Path(__file__).resolve().parent
DURATION = 1.0
SCALES = (4, 10)

#: the committed corpus: (file relative to tests/robots, URDF scene options); one row each
CORPUS = (
    ("mjcf/quadruped.xml", {}),
    ("mjcf/humanoid.xml", {}),
    ("mjcf/walker.xml", {}),
    ("mjcf/hand.xml", {}),
    ("mjcf/arm.xml", {}),
    ("mjcf/drone.xml", {}),
    ("mjcf/attach/scene.xml", {}),
    ("mjcf/attach/gripper/gripper.xml", {}),
    ("mjcf/bin.xml", {}),
    ("mjcf/spinner.xml", {}),
    ("urdf/quadruped.urdf", {"ground": True, "base_position": (0, 0, 0.5)}),
    ("urdf/quadruped.urdf", {"ground": True, "base_position": (0, 0, 0.5), "damping": 0.0, "split_impulse": False}),
    ("urdf/gripper.urdf", {"fixed_base": True, "base_position": (0, 0, 0.5)}),
    ("urdf/gripper.urdf", {"fixed_base": True, "base_position": (0, 0, 0.5), "damping": 0.0, "split_impulse": False}),
    ("urdf/arm.urdf", {"fixed_base": True}),
    ("urdf/arm.urdf", {"fixed_base": True, "damping": 0.0, "split_impulse": False}),
    ("urdf/wheeled.urdf", {"ground": True, "base_position": (0, 0, 0.081)}),
    ("urdf/wheeled.urdf", {"ground": True, "base_position": (0, 0, 0.081), "damping": 0.0, "split_impulse": False}),
)


@dataclass
class Verdict:
    """One verify call: its verdict or the exception it raised."""

    similar: bool | None = None
    max_deviation: float | None = None
    sensitivity: float | None = None
    worst: str = ""
    seconds: float = 0.0
    error: str = ""


@dataclass
class Row:
    """One file (and URDF scene) of the survey."""

    name: str
    options: dict
    provenance: str = "written for pitheorem"
    load_seconds: float | None = None
    parameters: int | None = None
    search_seconds: float | None = None
    warnings: list[str] = field(default_factory=list)
    moved: float | None = None
    verdicts: dict[int, Verdict] = field(default_factory=dict)
    error: str = ""
    reload_error: str = ""


def smooth_controls(model):
    """The small sinusoidal input of the module docstring, for `model`'s inputs; None for a model without any."""
    if model.engine == "pybullet":
        efforts = []
        for _j, jname, _jtype in model.runner._info["joints"]:
            name = f"{engines.parameters.identifier(f'joint_{jname}')}_effort"
            try:
                efforts.append(model.parameter(name).value[0])
            except pt.PiTheoremError:
                efforts.append(1.0)  # no effort limit: a torque of 0.05
        amplitude = 0.05 * np.array(efforts)
        centre = np.zeros_like(amplitude)
    else:
        m = model.runner.mjmodel
        if not m.nu:
            return None
        lo, hi = m.actuator_ctrlrange[:, 0], m.actuator_ctrlrange[:, 1]
        limited = m.actuator_ctrllimited.astype(bool) & (hi > lo)
        centre = np.where(limited & ~((lo < 0) & (hi > 0)), (lo + hi) / 2, 0.0)
        amplitude = np.where(limited, 0.2 * np.minimum(hi - centre, centre - lo), 0.1)
    if not amplitude.size:
        return None
    phase = np.arange(amplitude.size)
    return lambda t: centre + amplitude * np.sin(3.0 * t + phase)


def message(err: BaseException) -> str:
    """An exception as one table cell: its type and its first line."""
    text = str(err).strip().splitlines()[0] if str(err).strip() else ""
    return f"{type(err).__name__}: {text}"


def verdict(model, scaling, s, controls, scaled=None) -> Verdict:
    out = Verdict()
    start = time.perf_counter()
    try:
        rep = engines.verify(model, scaling, s=s, duration=DURATION, controls=controls, scaled=scaled)
    except Exception as err:  # a survey records every failure
        out.error = message(err)
    else:
        out.similar = bool(rep.similar)
        out.max_deviation = float(rep.max_deviation)
        out.sensitivity = max(rep.sensitivity.values()) if rep.sensitivity else None
        out.worst = max(rep.deviation, key=rep.deviation.get) if rep.deviation else ""
    out.seconds = time.perf_counter() - start
    return out


def survey(path: Path, options: dict, name: str, provenance: str = "written for pitheorem") -> Row:
    row = Row(name, options, provenance)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            start = time.perf_counter()
            model = engines.load(path, **options)
            row.load_seconds = time.perf_counter() - start
        row.warnings = sorted({str(w.message).splitlines()[0] for w in caught})
        row.parameters = len(model.parameters)
        start = time.perf_counter()
        scaling = pt.search(model.system(), scale={"g": 1}).scalings[0]
        row.search_seconds = time.perf_counter() - start
    except Exception as err:
        row.error = message(err)
        traceback.print_exc(file=sys.stderr)
        return row
    controls = smooth_controls(model)
    try:
        n = max(1, round(DURATION / model.runner.timestep()))
        u = None if controls is None else np.array([controls(i * model.runner.timestep()) for i in range(n)])
        run = model.runner.run(n, u)
        row.moved = float(np.max(np.abs(run - run[0])))
    except Exception as err:
        row.moved = None
        print(f"{name}: plain run failed: {message(err)}", file=sys.stderr)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for s in SCALES:
            row.verdicts[s] = verdict(model, scaling, s, controls)
        try:  # the scaled copy saved and loaded again, as a user would share it
            import tempfile

            with tempfile.TemporaryDirectory() as tmp:
                suffix = ".urdf" if model.engine == "pybullet" else ".xml"
                try:
                    engines.load(model.scaled(scaling, 4).save(Path(tmp) / f"scaled{suffix}"))
                except Exception as err:
                    row.reload_error = message(err).replace(str(Path(tmp)), "<tmp>")
        except Exception as err:
            row.reload_error = message(err)
    return row


def cell(x, fmt="{:.3g}") -> str:
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    return fmt.format(x)


def options_text(options: dict) -> str:
    if not options:
        return ""
    return ", ".join(f"{k}={v}" for k, v in options.items())


def table(rows: list[Row]) -> str:
    head = (
        "| file | scene | load s | params | search s | moved | s=4 exact | s=4 similar | s=4 max dev | "
        "s=4 sens | s=10 similar | s=10 max dev | s=10 sens | s=10 worst coordinate | saved s=4 reloads |"
    )
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    errors = []
    for r in rows:
        v4, v10 = r.verdicts.get(4, Verdict()), r.verdicts.get(10, Verdict())
        exact = None if v4.max_deviation is None else v4.max_deviation == 0.0
        name = r.name + ("" if r.provenance == "written for pitheorem" else f" ({r.provenance})")
        reload = "-" if r.error else ("yes" if not r.reload_error else "**no**")
        cells = [
            name,
            options_text(r.options),
            cell(r.load_seconds, "{:.3f}"),
            cell(r.parameters, "{}"),
            cell(r.search_seconds, "{:.3f}"),
            cell(r.moved),
            cell(exact),
            cell(v4.similar),
            cell(v4.max_deviation),
            cell(v4.sensitivity),
            cell(v10.similar),
            cell(v10.max_deviation),
            cell(v10.sensitivity),
            v10.worst or "-",
            reload,
        ]
        if r.error:
            cells[5:14] = ["error"] * 9
        lines.append("| " + " | ".join(cells) + " |")
        for label, text in (
            ("load/search", r.error),
            ("verify s=4", v4.error),
            ("verify s=10", v10.error),
            ("save+reload", r.reload_error),
        ):
            if text:
                errors.append(f"- `{name}` [{options_text(r.options) or 'as is'}] {label}: {text}")
        for w in r.warnings:
            errors.append(f"- `{name}` [{options_text(r.options) or 'as is'}] load warning: {w}")
    return "\n".join(lines) + ("\n\nExceptions and warnings:\n\n" + "\n".join(errors) if errors else "") + "\n"


# -- counter-runs: what makes a file exact at s = 4 ---------------------------------------------------


def mjcf_variant(path: Path, change) -> engines.EngineModel:
    """The MJCF model at `path` with `change(spec)` applied before it is compiled (nothing written to disk)."""
    import mujoco

    from pitheorem.engines.fileformats.mjcf import MjcfDocument
    from pitheorem.engines.runners.mujoco import MujocoRunner

    spec = mujoco.MjSpec.from_file(str(path))
    change(spec)
    return engines.EngineModel(
        MujocoRunner(MjcfDocument(spec, str(path), path.resolve().parent, warn=False)), "mujoco", str(path)
    )


def no_contacts(spec):
    import mujoco

    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT


def zero_tolerance(spec):
    spec.option.tolerance = 0.0


def explicit_springlengths(spec):
    """Each tendon rest length left to MuJoCo's sentinel (-1: from the initial pose) written as its value."""
    m = spec.compile()
    for i, tendon in enumerate(spec.tendons):
        if np.all(np.asarray(tendon.springlength) == -1):
            tendon.springlength = np.array(m.tendon_lengthspring[i], dtype=float)


def mesh_twin_deviation(path: Path) -> float | None:
    """How far the original drifts from itself when every mesh is made one float32 ulp larger (None: no mesh).

    MuJoCo keeps mesh vertices in float32, so a scaled copy's vertices are rounded to about 6e-8 of
    their size; this twin shows what a rounding of that size does to the run, with no scaling at all.
    """
    model = mjcf_variant(path, lambda spec: None)
    if not model.runner.mjmodel.nmesh:
        return None

    def larger(spec):
        for mesh in spec.meshes:
            mesh.scale = np.asarray(mesh.scale, dtype=float) * (1 + 2.0**-23)

    twin = mjcf_variant(path, larger)
    controls = smooth_controls(model)
    dt = model.runner.timestep()
    n = max(1, round(DURATION / dt))
    u = None if controls is None else np.array([controls(i * dt) for i in range(n)])
    return float(np.max(np.abs(model.runner.run(n, u) - twin.runner.run(n, u))))


def no_equalities(spec):
    for eq in spec.equalities:
        eq.active = False


def diagnose(path: Path, name: str, s_values=(4, 10)) -> list[str]:
    """Counter-runs at s = 4 and 10: each remedy alone and all together, for an MJCF file."""
    variants = {
        "as is": lambda spec: None,
        "tolerance 0": zero_tolerance,
        "contacts off": no_contacts,
        "springlength explicit": explicit_springlengths,
        "springlength explicit + equalities off": lambda spec: (explicit_springlengths(spec), no_equalities(spec)),
        "tolerance 0 + springlength explicit": lambda spec: (zero_tolerance(spec), explicit_springlengths(spec)),
        "tolerance 0 + contacts off + springlength explicit": lambda spec: (
            zero_tolerance(spec),
            no_contacts(spec),
            explicit_springlengths(spec),
        ),
    }
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        twin = mesh_twin_deviation(path)
        if twin is not None:
            out.append(
                f"- `{name}` twin with every mesh scale times 1 + 2^-23 (one float32 ulp), not scaled: "
                f"deviation {twin:.3g} from the original"
            )
        for label, change in variants.items():
            try:
                model = mjcf_variant(path, change)
                scaling = pt.search(model.system(), scale={"g": 1}).scalings[0]
                controls = smooth_controls(model)
                parts = []
                for s in s_values:
                    v = verdict(model, scaling, s, controls)
                    parts.append(
                        f"s={s}: "
                        + (
                            v.error
                            or f"max dev {v.max_deviation:.3g} (sens {cell(v.sensitivity)}, "
                            f"similar {cell(v.similar)}, worst {v.worst})"
                        )
                    )
                out.append(f"- `{name}` {label}: " + "; ".join(parts))
            except Exception as err:
                out.append(f"- `{name}` {label}: {message(err)}")
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--print", action="store_true", help="print the table instead of writing SURVEY.md")
    parser.add_argument("--diagnose", action="store_true", help="counter-runs for the MJCF files")
    parser.add_argument("--only", nargs="*", default=None, help="only these corpus files (relative names)")
    parser.add_argument("--fetched", nargs="*", default=(), help="files fetched from elsewhere (not committed)")
    parser.add_argument(
        "--scene", action="append", default=[], help="URDF scene options for the fetched files, e.g. ground=True"
    )
    args = parser.parse_args(argv)
    corpus = [(n, o) for n, o in CORPUS if args.only is None or n in args.only]
    if args.diagnose:
        for n, _ in corpus:
            if n.endswith(".xml"):
                print("\n".join(diagnose(HERE / n, n)), flush=True)
        for f in args.fetched:
            if f.endswith(".xml"):
                print("\n".join(diagnose(Path(f), f)), flush=True)
        return 0
    rows = []
    for n, options in corpus:
        rows.append(survey(HERE / n, options, n))
        print(f"{n}: done", file=sys.stderr, flush=True)
    scene = {}
    for item in args.scene:
        key, _, value = item.partition("=")
        scene[key] = {"True": True, "False": False}.get(value, value)
        if key == "base_position":
            scene[key] = tuple(float(v) for v in value.split(","))
    for f in args.fetched:
        options = scene if f.endswith(".urdf") else {}
        rows.append(survey(Path(f), options, f, "fetched, not committed"))
        print(f"{f}: done", file=sys.stderr, flush=True)
    text = table(rows)
    if args.print or args.fetched or args.only is not None:
        print(text)
    else:
        target = HERE / "SURVEY.md"
        old = target.read_text() if target.is_file() else ""
        marker = "<!-- survey table -->"
        if marker in old:  # keep the findings written around the table
            before, _, rest = old.partition(marker)
            _, _, after = rest.partition(marker)
            target.write_text(f"{before}{marker}\n{text}{marker}{after}")
        else:
            target.write_text(f"# Survey of the robot corpus\n\n{marker}\n{text}{marker}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
