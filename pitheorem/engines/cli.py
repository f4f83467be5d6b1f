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

from fractions import Fraction
from pathlib import Path

from ..answers import EngineApplyAnswer, EngineVerifyAnswer, ParamsAnswer
from ..errors import InvalidRequestError
from ..modelfile import ModelFile
from .model import EngineModel, UnscalableParameterError, load
from .urdf import SCENE_OPTIONS, scene_option

__all__ = ["apply_engine", "engine_model_file", "params_answer", "parse_scene", "scene_help", "verify_engine"]


_TRUTH = {"true": True, "yes": True, "1": True, "false": False, "no": False, "0": False}

#: what each kind of scene option takes, as the help shows it
_SCENE_VALUES = {"flag": "true|false", "number": "X", "point": "X,Y,Z"}


def scene_help() -> str:
    """The command line's help for ``--scene``: every name of ``SCENE_OPTIONS`` with what it takes.

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.engines.cli import scene_help
    >>> print(scene_help())
    URDF files: PyBullet's scene and settings, any of fixed_base=true|false ground=true|false split_impulse=true|false g=X damping=X base_position=X,Y,Z (X a number)
    """
    options = " ".join(f"{name}={_SCENE_VALUES[kind]}" for name, (kind, _default) in SCENE_OPTIONS.items())
    return f"URDF files: PyBullet's scene and settings, any of {options} (X a number)"


def parse_scene(items: list[str] | None) -> dict:
    """The ``--scene NAME=VALUE`` items of the command line as options of :func:`pitheorem.engines.load`.

    Parameters
    ----------
    items : list of str or None
        Names of ``pitheorem.engines.urdf.SCENE_OPTIONS``: ``fixed_base``,
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
        if not sep or name not in SCENE_OPTIONS:
            raise InvalidRequestError(f"--scene {item!r}: write NAME=VALUE with NAME one of {', '.join(SCENE_OPTIONS)}")
        if name in options:
            raise InvalidRequestError(f"--scene sets {name!r} twice")
        kind = SCENE_OPTIONS[name][0]
        if kind == "flag":
            if text.lower() not in _TRUTH:
                raise InvalidRequestError(f"--scene {item!r}: {name} is true or false")
            value = _TRUTH[text.lower()]
        else:
            parts = [part.strip() for part in text.split(",")]
            if len(parts) != (3 if kind == "point" else 1):
                raise InvalidRequestError(f"--scene {item!r}: {name} takes "
                                          + ("three numbers such as 0,0,1" if kind == "point" else "one number"))
            value = parts if kind == "point" else parts[0]
        try:
            options[name] = scene_option(name, value)
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
    return ModelFile(name=name, description=f"{model.engine} model {name}", system=system, values=values,
                     roles=roles, path=str(path)), model


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


def apply_engine(model: EngineModel, scaling, s, output: str | None, scene=None) -> EngineApplyAnswer:
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
    try:
        scaled = model.scaled(scaling, s)
    except UnscalableParameterError as err:
        if model.engine == "pybullet" and err.name.endswith("Damping") and "damping" not in (scene or {}):
            raise InvalidRequestError(f"{err}; on the command line: --scene damping=0") from None
        raise
    exponents = ((p, scaling.exponent_of(p.dimension)) for p in model.parameters
                 if not p.mixed and any(v != 0 for v in p.value))
    changed_parameters = [(p, e) for p, e in exponents if e != 0]
    changed = tuple((p.name, e) for p, e in changed_parameters)
    details = tuple((p.dimension_text, p.value, scaled.parameter(p.name).value) for p, _ in changed_parameters)
    written, beside = None, ()
    if output:
        out = Path(output)
        if out.exists() and out.resolve() == Path(model.path).resolve():
            raise InvalidRequestError(f"--output {output!r} is the input file; choose another name")
        scaled.save(out)
        written = str(out)
        beside = (f"{out}.settings.json", f"{out}.settings.py") if model.engine == "pybullet" else ()
    return EngineApplyAnswer(Path(model.path).name, s, scaling, changed, len(model.parameters), written, beside,
                             details)



def verify_engine(model: EngineModel, scaling, s, duration: float, inputs: str = "smooth") -> EngineVerifyAnswer:
    """The command line's ``verify``: the model and its scaled copy run, and the verdict.

    Parameters
    ----------
    model : EngineModel
    scaling : Scaling
    s : Fraction
    duration : float
    inputs : {"smooth", "zero"}
        :func:`pitheorem.engines.smooth_controls`, or no input.

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
    True
    """
    from .verify import exact_in_binary, smooth_controls, verify

    controls = smooth_controls(model) if inputs == "smooth" and len(model.backend.control_dimensions()) else None
    rep = verify(model, scaling, s, duration=duration, controls=controls)
    return EngineVerifyAnswer(model.path, model.engine, Fraction(s), duration, inputs,
                              exact_in_binary(model, scaling, s), rep)
