"""The command line on engine model files: ``params``, and ``groups``/``bases``/``search``/``apply`` on MJCF and URDF.

:mod:`pitheorem.cli` dispatches here by file kind (:func:`pitheorem.modelfile.model_kind`):
an engine model becomes a :class:`~pitheorem.modelfile.ModelFile` of its
system and its one-number values (:func:`engine_model_file`), so the TOML
commands work on it unchanged, and ``apply`` writes the scaled file the
engine loads (:func:`apply_engine`).  Like the TOML commands, ``params``
and ``apply`` return an answer (:mod:`pitheorem.answers`) that the command
line prints in the format asked for.
"""

from __future__ import annotations

import contextlib
import re
from collections.abc import Callable, Iterator
from fractions import Fraction
from pathlib import Path

from ..answers import EngineApplyAnswer, EngineVerifyAnswer, ParamsAnswer, SweepAnswer
from ..errors import InvalidRequestError
from ..modelfile import ModelFile
from .enginemodel import EngineModel, EngineModelError, UnscalableParameterError
from .loading import load, runner_module, scene_options
from .protocols import EngineNotes, RefusesScalings
from .registry import file_format, registered
from .verdicts.causes import Cause
from .verdicts.probes import kept_input_dimensions

__all__ = [
    "CHECK_STAGES",
    "CONVERT_STAGES",
    "VERIFY_STAGES",
    "apply_engine",
    "automatic_scene",
    "check_engine_model",
    "convert_engine",
    "engine_model_file",
    "params_answer",
    "parse_s_values",
    "parse_scene",
    "parse_units",
    "scene_help",
    "scene_text",
    "search_refusals",
    "sweep_engine",
    "verify_engine",
]


_TRUTH = {"true": True, "yes": True, "1": True, "false": False, "no": False, "0": False}

#: what each kind of scene option takes, as the help shows it
_SCENE_VALUES = {"flag": "true|false", "number": "X", "point": "X,Y,Z"}


def scene_help() -> str:
    """The command line's help for ``--scene``: every runner's scene options with what each takes.

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.engines.cli import scene_help
    >>> print(scene_help())
    in pybullet: any of fixed_base=true|false ground=true|false split_impulse=true|false g=X damping=X base_position=X,Y,Z (X a number)
    """
    by_engine: dict[str, list[str]] = {}
    for name, (engine, kind, _default, _read) in scene_options().items():
        by_engine.setdefault(engine, []).append(f"{name}={_SCENE_VALUES[kind]}")
    return "; ".join(f"in {engine}: any of {' '.join(names)}" for engine, names in by_engine.items()) + " (X a number)"


def parse_scene(items: list[str] | None) -> dict:
    """The ``--scene NAME=VALUE`` items of the command line as options of :func:`pitheorem.engines.load`.

    Parameters
    ----------
    items : list of str or None
        Names of :func:`pitheorem.engines.loading.scene_options`: ``fixed_base``,
        ``ground`` and ``split_impulse`` take true/false; ``g`` and
        ``damping`` a number; ``base_position`` three numbers separated by
        commas.

    Returns
    -------
    dict

    Raises
    ------
    InvalidRequestError
        For an unknown name, a repeated name or a value of the wrong kind.

    Examples
    --------
    >>> from pitheorem.engines.cli import parse_scene
    >>> parse_scene(["ground=true", "damping=0", "base_position=0,0,1"])
    {'ground': True, 'damping': 0.0, 'base_position': (0.0, 0.0, 1.0)}
    """
    options = {}
    for item in items or ():
        name, sep, text = item.partition("=")
        name, text = name.strip(), text.strip()
        known = scene_options()
        if not sep or name not in known:
            raise InvalidRequestError(f"--scene {item!r}: write NAME=VALUE with NAME one of {', '.join(known)}")
        if name in options:
            raise InvalidRequestError(f"--scene sets {name!r} twice")
        _engine, kind, _default, read = known[name]
        if kind == "flag":
            if text.lower() not in _TRUTH:
                raise InvalidRequestError(f"--scene {item!r}: {name} is true or false")
            value = _TRUTH[text.lower()]
        else:
            parts = [part.strip() for part in text.split(",")]
            if len(parts) != (3 if kind == "point" else 1):
                raise InvalidRequestError(
                    f"--scene {item!r}: {name} takes "
                    + ("three numbers such as 0,0,1" if kind == "point" else "one number")
                )
            value = parts if kind == "point" else parts[0]
        try:
            options[name] = read(name, value)
        except InvalidRequestError as err:
            raise InvalidRequestError(f"--scene {item!r}: {err}", culprit=err.culprit) from None
    return options


def engine_model_file(path: str, **options) -> tuple[ModelFile, EngineModel]:
    """The engine model and a :class:`~pitheorem.modelfile.ModelFile` of its system and scalar values.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import engine_model_file
    >>> mf, model = engine_model_file(str(engines.example_path("pendulum.xml")))
    >>> mf.roles["t"], mf.values["g"]
    ('time', 9.81)
    """
    model = load(path, **options)
    system = model.system()
    values = {p.name: p.value[0] for p in model.parameters if not p.mixed and len(p.value) == 1}
    roles = {n: "time" if n == "t" else "parameter" for n in system.variables}
    name = Path(path).name
    return ModelFile(
        name=name, description=f"{model.engine} model {name}", system=system, values=values, roles=roles, path=str(path)
    ), model


@contextlib.contextmanager
def engine_warnings(paths, engine: str | None = None) -> Iterator[list[tuple[str, list[str]]]]:
    """The warnings the engines give while the block runs on the files `paths`, collected, not printed.

    Yields a list of ``(engine name, the list its warnings' texts are appended to)``, one per hook.
    Each file runs in `engine`, or in the engine its format runs in by default; that engine's runner
    module (or the one it builds on: MJX's and MuJoCo Warp's, MuJoCo's) collects its warnings where it
    has the hook ``warnings_collected`` (MuJoCo: they would go to the console and to
    ``MUJOCO_LOG.TXT`` in the working folder, once per run), each hook once however many files use it.
    Nothing is collected for an engine without the hook, one not installed, or a file of no engine's
    format.

    Parameters
    ----------
    paths : str or sequence of str
        The model file, or the files (``pitheorem sweep`` takes several).
    engine : str, optional
        The engine every file runs in (the command line's ``--engine``).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import engine_warnings
    >>> path = str(engines.example_path("pendulum.xml"))
    >>> with engine_warnings([path, path]) as collected:
    ...     _ = engines.load(path).with_values(timestep=1e9).run(3)
    >>> [(name, heard[0][:30]) for name, heard in collected]
    [('mujoco', 'Nan, Inf or huge value in QPOS')]
    """
    hooks: dict = {}  # hook -> the engine named for it, in the order first met
    for path in [paths] if isinstance(paths, str) else paths:
        fmt = file_format(path)
        line = registered(engine) if engine else registered(fmt.engine) if fmt is not None else None
        if line is None or not line.installed():
            continue
        for name in filter(None, (line.name, line.base)):
            hook = getattr(runner_module(name), "warnings_collected", None)
            if hook is not None:
                hooks.setdefault(hook, line.name)
                break
    collected: list[tuple[str, list[str]]] = []
    with contextlib.ExitStack() as stack:
        for hook, name in hooks.items():
            heard: list[str] = []
            stack.enter_context(hook(heard))
            collected.append((name, heard))
        yield collected


def search_refusals(model: EngineModel, scalings) -> str | None:
    """One line saying which of a search's scalings the file's own numbers refuse, and why; None if none.

    A number that mixes dimensions (a free joint's damping acts on lengths
    and on angles) follows a scaling only where the scaling moves all of its
    dimensions alike; a search of the system knows nothing of that, so it may
    list scalings that ``apply`` then refuses.  The line names the first such
    number and the listed scalings (``#1``, ...) it refuses.  What a scene
    option removes (PyBullet's link damping) is not counted: ``apply`` and
    ``verify`` choose that scene themselves.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import search_refusals
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "puck.xml"
    >>> _ = path.write_text('<mujoco><worldbody><body><joint name="root" type="free" damping="0.1"/>'
    ...                     '<geom size="0.1"/></body></worldbody></mujoco>')
    >>> puck = engines.load(path)
    >>> res = pt.search(puck.system(), scale={"g": 1})
    >>> print(search_refusals(puck, res.scalings))  # doctest: +NORMALIZE_WHITESPACE
    apply refuses every scaling listed: the one number joint 'root' damping acts with dimensions
    M T^-1 (lin) | M L^2 T^-1 (rot), so the scaling needs s^-2 as lin, s^0 as rot; set it to 0
    or hold the base units it mixes fixed
    >>> pendulum = engines.load(engines.example_path("pendulum.xml"))  # no number mixes dimensions
    >>> search_refusals(pendulum, pt.search(pendulum.system(), scale={"g": 1}).scalings) is None
    True
    """
    mixed = model.by_dimension()[1]
    refused: list[tuple[int, str]] = []
    for k, scaling in enumerate(scalings, 1):
        for p in mixed:
            try:
                p.factor(scaling, 2)
            except UnscalableParameterError as err:
                refused.append((k, err.reason))
                break
    if not refused:
        return None
    if len(refused) == len(scalings):
        which = "every scaling listed"
    else:
        runs: list[list[int]] = []  # consecutive solutions as one range: #4 to #26
        for k, _ in refused:
            if runs and runs[-1][-1] == k - 1:
                runs[-1].append(k)
            else:
                runs.append([k])
        ranges = ", ".join(f"#{r[0]}" if len(r) == 1 else f"#{r[0]} to #{r[-1]}" for r in runs)
        which = f"{ranges} ({len(refused)} of {len(scalings)})"
    return f"apply refuses {which}: {refused[0][1]}"


def automatic_scene(model: EngineModel, scaling, s, scene: dict | None = None) -> dict:
    """The scene options the command line adds so that the engine's default scene follows `scaling`.

    PyBullet's default scene has link damping (one number acting as a rate
    and per length, which no scaling that changes lengths can follow) and
    split impulse (whose threshold, a length, cannot be set from Python).
    When the scaling is refused for them and the user set neither, the
    command line loads the model in the runner's remedy scene instead, in
    both runs, and says so in one line (:func:`scene_text`).

    Parameters
    ----------
    model : EngineModel
        The model as loaded with the user's scene.
    scaling : Scaling
    s : Fraction
    scene : dict, optional
        The scene options the user gave (:func:`parse_scene`); none of them
        is overridden.

    Returns
    -------
    dict
        The options to add (empty when the scaling is accepted, when the
        runner refuses nothing, or when the user set every remedy option).

    Examples
    --------
    >>> import os, pybullet_data
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import automatic_scene
    >>> model = engines.load(os.path.join(pybullet_data.getDataPath(), "cartpole.urdf"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[1]
    >>> automatic_scene(model, sc, 4)
    {'damping': 0.0, 'split_impulse': False}
    >>> automatic_scene(model, sc, 4, {"damping": 0.0, "split_impulse": False})
    {}
    """
    if not isinstance(model.runner, RefusesScalings):
        return {}
    try:
        model.scaled(scaling, s)
    except UnscalableParameterError:
        return {k: v for k, v in model.runner.remedy_scene.items() if k not in (scene or {})}
    return {}


def scene_refusal(model: EngineModel, scaling, s) -> str | None:
    """One short line when the model's scene refuses `scaling` and a scene option removes it, else None.

    Examples
    --------
    >>> import os, pybullet_data
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import scene_refusal
    >>> model = engines.load(os.path.join(pybullet_data.getDataPath(), "cartpole.urdf"), damping=0.1)
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[1]
    >>> print(scene_refusal(model, sc, 4))
    the scene refuses this scaling (4 numbers, the first 'link_slideBar_linearDamping'); give --scene damping=0 split_impulse=false
    """
    if not isinstance(model.runner, RefusesScalings):
        return None
    try:
        model.scaled(scaling, s)
    except UnscalableParameterError as err:
        many = re.match(r"(\d+) numbers cannot follow", err.reason)
        many = f"{many.group(1)} numbers, the first " if many else ""
        return (
            f"the scene refuses this scaling ({many}{err.name!r}); give --scene {scene_text(model.runner.remedy_scene)}"
        )
    return None


def scene_text(options: dict) -> str:
    """Scene options as ``--scene`` writes them: ``damping=0 split_impulse=false``.

    Examples
    --------
    >>> from pitheorem.engines.cli import scene_text
    >>> scene_text({"damping": 0.0, "split_impulse": False, "base_position": (0.0, 0.0, 1.5)})
    'damping=0 split_impulse=false base_position=0,0,1.5'
    """

    def one(value) -> str:
        if isinstance(value, bool):
            return "true" if value else "false"
        if isinstance(value, (tuple, list)):
            return ",".join(one(v) for v in value)
        return f"{value:g}" if float(value) == int(value) else repr(float(value))

    return " ".join(f"{name}={one(value)}" for name, value in options.items())


def params_answer(path: str, *, name: str | None = None, **options) -> ParamsAnswer:
    """The parameter table of an engine model file (``pitheorem params FILE``).

    Parameters
    ----------
    path : str
        The file.
    name : str, optional
        The file as the command line named it (``example:pendulum.xml``);
        default: `path`.
    **options
        Scene options of a URDF file (:func:`parse_scene`).

    Returns
    -------
    ParamsAnswer

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import params_answer
    >>> answer = params_answer(str(engines.example_path("pendulum.xml")))
    >>> format(answer, "json").splitlines()[2]
    '  "engine": "mujoco",'
    """
    return ParamsAnswer(str(path) if name is None else name, load(path, **options))


def apply_engine(
    model: EngineModel,
    scaling,
    s,
    output: str | None,
    scene=None,
    *,
    keep_inputs=False,
    copy_assets=False,
    stage: Callable[[str], None] | None = None,
) -> EngineApplyAnswer:
    """Scale an engine model file and write it (``pitheorem apply FILE ... --output OUT``).

    Parameters
    ----------
    model : EngineModel
        The model loaded from the MJCF or URDF file (:func:`engine_model_file`
        gives it with the system the scaling was searched on).
    scaling : Scaling
        A scaling of its system (:func:`engine_model_file`).
    s : Fraction
        The scale factor.
    output : str or None
        Where to write the scaled file (PyBullet's settings are written
        beside it); None writes nothing.
    scene : dict, optional
        The scene options the URDF file was loaded with (:func:`parse_scene`);
        without ``damping``, a refusal of PyBullet's mixed damping names
        ``--scene damping=0``.
    keep_inputs : bool
        Keep every control input's value (``--keep-inputs``; see
        :meth:`~pitheorem.engines.EngineModel.scaled`).
    copy_assets : bool
        Copy the mesh and texture files beside the written file
        (``--copy-assets``; see :meth:`~pitheorem.engines.EngineModel.save`).
    stage : callable, optional
        ``stage(name)``, called as ``"scaling"`` and ``"writing"`` begin
        (the command line's progress bar, :class:`pitheorem.progress.StageBar`).

    Returns
    -------
    EngineApplyAnswer
        The parameters the scaling changes, and the files written.

    Examples
    --------
    >>> import os, tempfile
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import apply_engine, engine_model_file
    >>> path = str(engines.example_path("pendulum.xml"))
    >>> mf, model = engine_model_file(path)
    >>> sc = pt.search(mf.system, scale={"g": 1}).scalings[0]
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     answer = apply_engine(model, sc, 10, os.path.join(tmp, "p10.xml"))
    >>> str(answer).splitlines()[-1].startswith("wrote")
    True
    """
    stage = stage if stage is not None else (lambda name: None)
    stage("scaling")
    try:
        scaled = model.scaled(scaling, s, keep_inputs=keep_inputs)
    except UnscalableParameterError as err:
        option, flags = (
            model.runner.command_line_remedy(err.name) if isinstance(model.runner, RefusesScalings) else ("", "")
        )
        if option and option not in (scene or {}):
            raise InvalidRequestError(f"{err}; on the command line: {flags}") from None
        raise
    # with kept inputs: each number an input passes through, measured with the input taken out
    kept = kept_input_dimensions(model) if keep_inputs else {}
    exponents = (
        (p, scaling.exponent_of(p.dimension / kept[p.name] if p.name in kept else p.dimension))
        for p in model.parameters
        if not p.mixed and any(v != 0 for v in p.value)
    )
    changed_parameters = [(p, e) for p, e in exponents if e != 0]
    changed = tuple((p.name, e) for p, e in changed_parameters)
    details = tuple((p.dimension_text, p.value, scaled.parameter(p.name).value) for p, _ in changed_parameters)
    written, beside = None, ()
    if output:
        stage("writing")
        out = Path(output)
        if out.exists() and out.resolve() == Path(model.path).resolve():
            raise InvalidRequestError(f"--output {output!r} is the input file; choose another name")
        scaled.save(out, copy_assets=copy_assets)
        written = str(out)
        beside = scaled.runner.written_beside(out)
    return EngineApplyAnswer(
        Path(model.path).name, s, scaling, changed, len(model.parameters), written, beside, details
    )


#: the stages of a verification as the command line's progress bar names them: the copies made,
#: the first batch of runs, the controls and the scale-free proof, the causes
#: (:data:`pitheorem.engines.verdicts.verify.STAGES` of them)
VERIFY_STAGES = ("making copies", "running", "proving", "diagnosing")


def verify_engine(
    model: EngineModel,
    scaling,
    s,
    duration: float,
    inputs: str = "smooth",
    progress: bool = False,
    *,
    stage: Callable[[str], None] | None = None,
) -> EngineVerifyAnswer:
    """The command line's ``verify``: the model and its scaled copy run, and the verdict.

    Parameters
    ----------
    model : EngineModel
    scaling : Scaling
    s : Fraction
    duration : float
    inputs : {"smooth", "zero"}
        :func:`pitheorem.engines.smooth_controls`, or no input.
    progress : bool
        Show a progress bar of the verification's stages on stderr (tqdm).
    stage : callable, optional
        ``stage(name)``, called as each of :data:`VERIFY_STAGES` begins
        (a bar the caller shows, :class:`pitheorem.progress.StageBar`); with
        it, `progress` is not needed.

    Returns
    -------
    EngineVerifyAnswer
        Printed in any format; ``answer.report.similar`` is the verdict.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import verify_engine
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> answer = verify_engine(model, sc, 4, 0.5)
    >>> print(answer); answer.report.similar
    exact: the scaled copy, mapped back, equals the original bit for bit at every step (s = 4, 250 steps)
    strength: an error of 0.0001 in gravity or the masses is caught; the twins stay together to the end (t = 0.5)
    True
    """
    from ..progress import StageBar
    from .verdicts.binary import exact_in_binary
    from .verdicts.verify import smooth_controls, verify

    controls = smooth_controls(model) if inputs == "smooth" and len(model.inputs()[0]) else None
    with StageBar("verify", VERIFY_STAGES, show=progress and stage is None) as bar:
        begin = stage if stage is not None else bar.stage

        def advance(done, total):
            if done < len(VERIFY_STAGES):
                begin(VERIFY_STAGES[done])

        begin(VERIFY_STAGES[0])
        rep = verify(model, scaling, s, duration=duration, controls=controls, progress=advance)
    notes = model.runner.engine_notes() if isinstance(model.runner, EngineNotes) else ()
    return EngineVerifyAnswer(
        model.path, model.engine, Fraction(s), duration, inputs, exact_in_binary(model, scaling, s), rep, notes
    )


def parse_units(items: list[str] | None, option: str) -> dict[str, str]:
    """``--units L=mm M=g`` (or ``--from``) as a mapping of base dimension to unit name.

    Parameters
    ----------
    items : list of str or None
        ``BASE=UNIT`` items, BASE one of M, L, T.
    option : str
        The option's name, for the message (``"--units"``).

    Returns
    -------
    dict of str to str

    Raises
    ------
    InvalidRequestError
        For an item that is not ``BASE=UNIT``, or a base given twice.

    Examples
    --------
    >>> from pitheorem.engines.cli import parse_units
    >>> parse_units(["L=mm", "M=g"], "--units")
    {'L': 'mm', 'M': 'g'}
    """
    out = {}
    for item in items or ():
        base, sep, unit = (part.strip() for part in item.partition("="))
        if not sep or base not in ("M", "L", "T") or not unit:
            raise InvalidRequestError(
                f"{option} {item!r}: write BASE=UNIT with BASE one of M, L, T (L=mm, M=g)", culprit=item
            )
        if base in out:
            raise InvalidRequestError(f"{option} sets {base} twice", culprit=item)
        out[base] = unit
    return out


#: the stages of ``convert`` as its progress bar names them (:func:`convert_engine`)
CONVERT_STAGES = ("loading", "converting", "writing", "checking")


def convert_engine(
    path: str,
    *,
    from_units=None,
    units=None,
    fit: str | None = None,
    output: str | None = None,
    fmt: str = "text",
    keep_inputs: bool = False,
    copy_assets: bool = False,
    stage: Callable[[str], None] | None = None,
) -> str:
    """The command line's ``convert``: the same model in other units, written with ``--output``.

    Parameters
    ----------
    path : str
        An MJCF file.
    from_units : mapping of str to str, optional
        The units the file is written in (``--from``).
    units : mapping of str to str, optional
        The new units (``--units``).
    fit : str, optional
        An engine: choose the units with :func:`pitheorem.fit_units` for it
        (``--fit mujoco``); `units` may then be left out.
    output : str, optional
        Where to write the converted file.
    fmt : {"text", "json"}
    keep_inputs : bool
        Keep every control input's value (``--keep-inputs``).
    copy_assets : bool
        Copy the mesh and texture files beside the written file (``--copy-assets``).
    stage : callable, optional
        ``stage(name)``, called as each of :data:`CONVERT_STAGES` begins
        (the command line's progress bar, :class:`pitheorem.progress.StageBar`).

    Returns
    -------
    str

    Raises
    ------
    InvalidRequestError
        Without `units` or `fit`, with both, or with `output` the input file.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import convert_engine
    >>> print(convert_engine(str(engines.example_path("pendulum.xml")), units={"L": "mm"}).splitlines()[0])
    pendulum.xml: M=kg L=m T=s -> M=kg L=mm T=s (factors M 1, L 1000, T 1)
    """
    import json

    from .units import conversion, read_units

    if bool(units) == bool(fit):
        raise InvalidRequestError("convert needs --units BASE=UNIT ... or --fit ENGINE (one of the two)")
    stage = stage if stage is not None else (lambda name: None)
    stage("loading")
    model = load(path, units=from_units or None)
    fitted = None
    stage("converting")
    if fit:
        from .fitting import engine_fit, fitted_units

        fitted = engine_fit(model, engine=fit)
        units = fitted_units(model, fitted)
    new = read_units({**model.units, **units})
    factors = _factors_text(model.units, new)
    try:
        converted = model.converted(**new, keep_inputs=keep_inputs)
    except EngineModelError:
        if fitted is None:
            raise
        # the file's format holds one set of units (a URDF file is in SI): the fit's cannot be written
        text = (
            f"{Path(path).name}: no units keep every number clear of {fit}'s thresholds\n"
            f"its format holds only {_units_text(model.units)}; {_units_text(new)} would clear them; "
            "a similarity scaling (pitheorem apply) changes its numbers instead"
        )
        if fmt == "json":
            return json.dumps({"file": path, "fit": fit, "feasible": False, "written": None, "reason": text}, indent=2)
        return text
    unchanged = all(f == "1" for f in factors.values())
    written = None
    if output and not (fit and unchanged):  # a fit that changes nothing writes no copy of the file
        out = Path(output)
        if out.exists() and out.resolve() == Path(path).resolve():
            raise InvalidRequestError(f"--output {output!r} is the input file; choose another name")
        stage("writing")
        converted.save(out, copy_assets=copy_assets)
        written = str(out)
    steps = len(conversion(model.system(), model.units, new))
    from .thresholds import check_summary

    stage("checking")
    crossings = tuple(f"{c.element}: {c.detail}" for c in check_summary(converted, fit or None)[0])
    if fmt == "json":
        return json.dumps(
            {
                "file": path,
                "from": model.units,
                "to": new,
                "factors": factors,
                "scalings": steps,
                "fit": fit,
                "feasible": None if fitted is None else fitted.feasible,
                "written": written,
                "thresholds": list(crossings),
            },
            indent=2,
        )
    name = Path(path).name
    if fit and unchanged:
        lines = [f"{name}: its units ({_units_text(model.units)}) are those --fit {fit} chooses; nothing to convert"]
    else:
        lines = [
            f"{name}: {_units_text(model.units)} -> {_units_text(new)} (factors "
            + ", ".join(f"{b} {f}" for b, f in factors.items())
            + ")"
        ]
    if fitted is not None and not fitted.feasible:
        lines.append(f"no units keep every number clear of {fit}'s thresholds; these are the closest")
    lines.extend(f"  {c}" for c in crossings)
    if written:
        lines.append(f"wrote {written}")
    elif not (fit and unchanged):
        lines.append("nothing written (give --output OUT)")
    return "\n".join(lines)


def _units_text(units) -> str:
    return " ".join(f"{b}={u}" for b, u in units.items())


def _factors_text(old, new) -> dict[str, str]:
    from ..exact import short_text
    from .units import unit_size

    return {b: short_text(unit_size(b, old[b]) / unit_size(b, new[b])) for b in old}


#: the stages of ``check`` as its progress bar names them (:func:`check_engine_model`)
CHECK_STAGES = ("loading", "checking", "loading in the other engine")


def check_engine_model(
    path: str,
    *,
    from_units=None,
    engine: str | None = None,
    fmt: str = "text",
    stage: Callable[[str], None] | None = None,
) -> tuple[str, bool]:
    """The command line's ``check``: the thresholds a model sits beyond or near, and whether it is clean.

    Parameters
    ----------
    path : str
        An MJCF or URDF file.
    from_units : mapping of str to str, optional
        The units the file is written in.
    engine : str, optional
        Hold the numbers against this engine's thresholds (default: the
        model's own engine).
    fmt : {"text", "json"}
    stage : callable, optional
        ``stage(name)``, called as each of :data:`CHECK_STAGES` begins
        (the command line's progress bar, :class:`pitheorem.progress.StageBar`).

    Returns
    -------
    (str, bool)

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import check_engine_model
    >>> text, clean = check_engine_model(str(engines.example_path("pendulum.xml")))
    >>> print(text); clean
    pendulum.xml: clear of every catalogued threshold of mujoco
    True
    """
    import json

    from .packages import check_engine
    from .thresholds import check_summary

    stage = stage if stage is not None else (lambda name: None)
    stage("loading")
    model = load(path, units=from_units or None)
    engine = model.engine if engine is None else check_engine(engine)
    stage("checking")
    causes, units_help = check_summary(model, engine)
    refused = None
    if engine != model.engine:  # another engine that compiles the file its own way (MJX) may refuse it: said first
        stage("loading in the other engine")
        try:
            load(path, units=from_units or None, engine=engine)
        except EngineModelError as err:
            refused = str(err).strip().splitlines()[0].removeprefix(f"{path}: ")
            causes = (Cause("threshold", "file", f"{engine} refuses the file: {refused}"), *causes)
    if fmt == "json":
        return json.dumps(
            {"file": path, "engine": engine, "units": model.units, "causes": [c.to_dict() for c in causes]}, indent=2
        ), not causes
    name = Path(path).name
    notes = model.runner.engine_notes() if isinstance(model.runner, EngineNotes) else ()
    if not causes:
        return "\n".join(
            [f"{name}: clear of every catalogued threshold of {engine}", *(f"note: {n}" for n in notes)]
        ), True
    count = sum(int(c.element.split(" ", 1)[0]) for c in causes if c.element.split(" ", 1)[0].isdigit())
    lines = [f"{name}: {count} number(s) at, beyond or near {len(causes)} threshold(s) of {engine}"]
    if refused is not None:
        lines[0] = f"{name}: {engine} refuses the file ({refused})"
        causes = causes[1:]
        if causes:
            lines.append(f"and {count} number(s) at, beyond or near {len(causes)} threshold(s) of {engine}:")
    lines.extend(f"  {c.element}: {c.detail}" for c in causes)
    if units_help:
        lines.append(f"units clear of them: pitheorem convert {name} --fit {engine} --output OUT")
    lines.extend(f"note: {n}" for n in notes)
    return "\n".join(lines), False


def parse_s_values(items: list[str]) -> tuple:
    """The scale factors of ``--s``: numbers, and ranges ``A:B:N`` of N factors evenly spaced in log s.

    Parameters
    ----------
    items : list of str
        Each a scale factor (``4``, ``1/4``, ``1e-3``) or ``A:B:N``: from
        A to B inclusive, N factors, evenly spaced on a log scale; a
        factor that is an integral power of ten is exact (``1e3`` is 1000).

    Returns
    -------
    tuple of Fraction or float

    Raises
    ------
    InvalidRequestError
        For a range with a bound that is no positive number or a count below 2.

    Examples
    --------
    >>> from pitheorem.engines.cli import parse_s_values
    >>> [str(s) for s in parse_s_values(["1e-3:1e3:7"])]
    ['1/1000', '1/100', '1/10', '1', '10', '100', '1000']
    >>> [float(s) for s in parse_s_values(["1:100:3", "4"])]
    [1.0, 10.0, 100.0, 4.0]
    """
    import math

    from ..exact import read_count, read_positive

    out = []
    for item in items:
        if ":" not in item:
            out.append(read_positive(item, "--s"))
            continue
        parts = item.split(":")
        if len(parts) != 3:
            raise InvalidRequestError(f"--s {item!r}: a range is A:B:N (from A to B, N factors)", culprit=item)
        a, b = (read_positive(p, "--s") for p in parts[:2])
        count = parts[2].strip()
        n = read_count(int(count) if count.isdigit() else count, "the count of an --s range", least=2, most=10_000)
        low, high = math.log10(a), math.log10(b)
        for k in range(n):
            e = low + (high - low) * k / (n - 1)
            exact = round(e)
            out.append(Fraction(10) ** exact if abs(e - exact) < 1e-12 else 10.0**e)
    return tuple(out)


def sweep_engine(
    models: list,
    scalings: list,
    s: tuple,
    duration: float,
    *,
    names: list[str],
    inputs: str = "smooth",
    client=None,
    plot: str | None = None,
    progress: bool = False,
) -> SweepAnswer:
    """The command line's ``sweep``: each model verified at every ``s``, and the figures written.

    Parameters
    ----------
    models : list of EngineModel
    scalings : list of Scaling
        One per model.
    s : tuple
        The scale factors (:func:`parse_s_values`).
    duration : float
    names : list of str
        Each file's name as given.
    inputs : {"smooth", "zero"}
    client : dask.distributed.Client, optional
    plot : str, optional
        A PNG path; with several files each figure gets the file's stem
        before the suffix (``sweep_hopper.png``).
    progress : bool
        Show a progress bar on stderr (tqdm).

    Returns
    -------
    SweepAnswer

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.cli import sweep_engine
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> answer = sweep_engine([model], [sc], (1, 4), 0.2, names=["pendulum.xml"])
    >>> answer.sweeps[0].verdicts
    ('exact', 'exact')
    """
    from ..progress import counting_bar
    from .verdicts.sweep import sweep
    from .verdicts.verify import smooth_controls

    bar = counting_bar(len(models) * len(s), "sweep", "run") if progress else None
    sweeps, plots = [], []
    try:
        for model, scaling in zip(models, scalings, strict=True):
            step = [0]

            def advance(done, total, step=step):
                if bar is not None:
                    bar.update(done - step[0])
                step[0] = done

            controls = smooth_controls(model) if inputs == "smooth" and len(model.inputs()[0]) else None
            sweeps.append(sweep(model, scaling, s, duration, controls, client=client, progress=advance))
    finally:
        if bar is not None:
            bar.close()
    if plot:
        for name, sw in zip(names, sweeps, strict=True):
            out = Path(plot) if len(sweeps) == 1 else Path(plot).with_stem(f"{Path(plot).stem}_{Path(name).stem}")
            plots.append(str(_save_figure(sw, out)))
    return SweepAnswer(tuple(names), tuple(sweeps), tuple(plots))


def _save_figure(sw, path: Path) -> Path:
    """The sweep's figure as a PNG, its alt text in the file's Description."""
    import matplotlib.pyplot as plt

    fig = sw.plot()
    try:
        fig.savefig(path, dpi=150, metadata={"Description": fig.get_label()})
    finally:
        plt.close(fig)
    return path
