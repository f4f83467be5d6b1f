"""The ``pitheorem`` command line: params, groups, bases, search and apply on a model file.

Every subcommand reads a TOML model file (format: :mod:`pitheorem.modelfile`),
an MJCF (MuJoCo) or a URDF (PyBullet) file, or a shipped example
``example:NAME``, NAME one of ``hinged_rod``, ``superball`` (TOML),
``hinged_rod.xml``, ``pendulum.xml``, ``superball.xml`` (MJCF) and
``hinged_rod.urdf`` (URDF, with its settings file): the names
:func:`pitheorem.modelfile.examples` lists::

    pitheorem params FILE
    pitheorem groups FILE [--repeating m l k_theta]
    pitheorem bases  FILE [--exclude t] [--require m] [--count | --all]
    pitheorem search FILE --scale g=1 [l=-1 ...] [--fixed [t m ...]] [--allow ...] [--no-default-fixed]
    pitheorem apply  FILE --scale g=1 [--fixed ...] --s 2 [--solution K] [--output OUT]
    pitheorem verify FILE --scale g=1 --s 4 [--duration 1]          (MJCF and URDF)
    pitheorem check  FILE [--from L=cm M=g] [--engine mujoco]        (MJCF and URDF)
    pitheorem convert FILE [--from L=cm M=g] --units L=mm | --fit mujoco [--output OUT]
    pitheorem sweep  FILE [FILE ...] --scale g=1 --s 1e-3:1e3:13 [--plot sweep.png] [--dask ADDRESS]

``groups`` without ``--repeating`` takes the first valid set of repeating
variables without time variables; if one of them has the value 0 (which
would leave groups undefined), the first set without time variables,
without zero values and without variables lacking one value, and it says
which variables are 0; a group that is undefined for the file's values (a zero
to a negative power) says so in its row.  ``bases`` lists the first
:data:`BASES_SHOWN` sets, and every one with ``--all``.

Every subcommand takes ``--format text|latex|html|json`` (default ``text``:
aligned plain text).  A subcommand computes its answer (a value of
:mod:`pitheorem.answers`) and prints it in that format; every display is
rendered by :mod:`pitheorem.formatting`, whose :mod:`~pitheorem.formatting.json`
module says what the JSON holds: keys in a fixed order (the file's variable
order), Pi-group exponents as integers, every exact rational (scaling
exponents, unit changes, rational values) as a string such as ``"1/2"`` or
``"-2"``, each of a search's notes as ``{"kind", "variables", "text"}``.

``--scale`` takes exponents of the scale factor ``s``, never factors:
``g=1`` means g -> s g, ``l=-1`` means l -> l / s, and ``g=1/6`` means
g -> s^(1/6) g (not "multiply g by 1/6"); ``apply`` picks ``s`` itself with
``--s``.  Exponents and ``--s`` are read exactly (``0.1`` is 1/10), under the
rule of :mod:`pitheorem.exact`.
Without ``--fixed``, a search holds every variable of dimension T fixed (so
the scaled model runs in the same time); ``--fixed`` with no names, or
``--no-default-fixed``, lets time change too.

A command that may take more than a moment (``apply`` or ``convert`` on a
large file, ``check``, ``verify``, ``sweep``) shows a progress bar of its
stages on stderr while it works, and erases it when done
(:mod:`pitheorem.progress`); only when stderr is a terminal, never with
``--format json``.

Exit codes
----------
0
    Success; for ``search``, at least one scaling exists.
1
    The request is valid but no similarity scaling meets it: ``search``
    prints the certificate of impossibility, ``apply`` writes nothing.
    (Like ``grep``, which exits 1 when nothing matches.)  ``verify``: the
    copy is not similar, or the verdict is inconclusive (the run cannot
    show an error: negative controls pass unnoticed); ``check``: a number is beyond or near one of the
    engine's thresholds; ``convert --fit``: no units clear every
    threshold (the closest are used).
2
    Bad input: an unreadable or malformed model file, an unknown variable,
    a bad exponent, a contradictory request, or a usage error.  The
    message on stderr is one line, ``pitheorem: error: ...``, naming the
    culprit.
"""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import re
import sys
import warnings
from collections.abc import Sequence
from fractions import Fraction
from itertools import islice
from pathlib import Path

from . import __version__
from .errors import CommandLineError, InvalidRequestError, LimitError, PiTheoremError
from .formatting import FORMATS, render
from .modelfile import EXAMPLES, ModelFile, example_path, examples, load_model_file, model_kind, write_model_file
from .progress import StageBar, say, wanted

# The answers, the search and the exact readers load when a command needs them (start-up time)

__all__ = ["BASES_SHOWN", "EXIT_ERROR", "EXIT_INFEASIBLE", "EXIT_OK", "build_parser", "main"]

#: exit code of a successful run
EXIT_OK = 0
#: exit code when no similarity scaling meets a valid request
EXIT_INFEASIBLE = 1
#: exit code of bad input (and of argparse's usage errors)
EXIT_ERROR = 2

_CommandError = CommandLineError  # the short name used throughout this module

#: how many repeating sets ``pitheorem bases`` lists without ``--all``
BASES_SHOWN = 50

#: how the help and the error for a bad ``example:`` name list the shipped examples
_EXAMPLES_TEXT = "example:NAME, NAME one of " + ", ".join(examples())
#: the shipped examples verify, check and convert read: the MJCF and URDF files
_ENGINE_EXAMPLES_TEXT = "example:NAME, NAME one of " + ", ".join(n for n in examples() if Path(n).suffix)

_SCALE_HELP = (
    "NAME=EXP: EXP is the exponent of the scale factor s, not a factor: NAME -> s^EXP NAME "
    "(g=1: g -> s g; l=-1/2: l -> s^(-1/2) l; g=1/6: g -> s^(1/6) g)"
)


# -- helpers ---------------------------------------------------------------------------------


def _as_named(text) -> str:
    """Text as the user wrote its files: a shipped example's installed path becomes ``example:NAME``.

    The engines read a shipped example by its path inside the installed
    package; the command line shows it by the name the user gave.
    """
    text = str(text).replace(str(EXAMPLES) + os.sep, "example:")
    for name in examples():
        if not Path(name).suffix:  # a TOML model file is named without its suffix
            text = text.replace(f"example:{name}.toml", f"example:{name}")
    return text


def _engine_path(path: str) -> str | None:
    """FILE as the engines read it when it is an MJCF or URDF model (a shipped one by its path), else None.

    TOML and JSON files, shipped or not, never load the engines package.
    """
    if path.startswith("example:"):
        name = path.removeprefix("example:")
        if name not in examples():
            raise _CommandError(
                f"{path}: no such example; the shipped examples are {', '.join(examples())}", culprit=path
            )
        shipped = example_path(name)
        return str(shipped) if model_kind(shipped) != "toml" else None
    return path if model_kind(path) != "toml" else None


def _load(path: str, scene: list[str] | None = None) -> ModelFile:
    return _load_with_engine(path, scene)[0]


def _load_with_engine(
    path: str, scene: list[str] | None = None, engine: str | None = None, added: dict | None = None
) -> tuple[ModelFile, object]:
    """The model file and, for MJCF or URDF, the engine's model it was read from (else None).

    `added` holds scene options the command line chose itself (:func:`_scaled_scene`).
    """
    engine_path = _engine_path(path)
    if engine_path is not None:  # MJCF or URDF: its system and scalar values, through the engine
        from .engines.cli import engine_model_file, parse_scene

        options = {} if engine is None else {"engine": engine}  # the file's own engine unless one is named
        return engine_model_file(engine_path, **parse_scene(scene), **(added or {}), **options)
    if scene:
        raise _CommandError(f"--scene sets up URDF models; {path} is no URDF file")
    try:
        return load_model_file(path), None
    except IsADirectoryError:
        raise _CommandError(f"cannot read model file {path!r}: it is a directory") from None
    except OSError as err:
        raise _CommandError(f"cannot read model file {path!r}: {err.strerror or err}") from None


def _parse_scale(entries: Sequence[str]) -> dict[str, Fraction]:
    from .exact import read_exponent

    scale: dict[str, Fraction] = {}
    for entry in entries:
        name, sep, text = entry.partition("=")
        name, text = name.strip(), text.strip()
        if not sep or not name or not text:
            raise _CommandError(
                f"--scale entry {entry!r} must look like NAME=EXP, where EXP is the exponent "
                "of the scale factor s (g=1 means g -> s g), e.g. g=1 or l=-1/2",
                culprit=entry,
            )
        if name in scale:
            raise _CommandError(f"--scale names {name!r} twice; give each variable one exponent", culprit=name)
        try:
            scale[name] = read_exponent(text, f"the exponent of s for {name!r} in --scale")
        except PiTheoremError as err:
            if "s" in text.lower() or "*" in text or "x" in text.lower():
                # g=s^2, g=2s, g=*6, g=x6: a factor or formula where a plain exponent belongs
                raise _CommandError(
                    f"--scale {entry!r}: EXP must be a plain number, the exponent of the scale factor s "
                    f"({name}={text} is not one); {name}=2 means {name} -> s^2 {name}, and {name}=1/6 means "
                    f"{name} -> s^(1/6) {name}, not a factor 1/6; apply takes s itself with --s",
                    culprit=entry,
                ) from None
            raise _CommandError(
                f"--scale {entry!r}: {err}; EXP is the exponent of the scale factor s "
                f"({name}=1 means {name} -> s {name})",
                culprit=entry,
            ) from None
    return scale


#: exact scaled values with more digits than this are refused (Python prints at most 4300)
_MAX_DIGITS = 4000


def _scaled_values(sc, values: dict, s: Fraction) -> dict:
    """The values scaled by :meth:`Scaling.apply` with an exact `s`, fit to be written.

    Float values are scaled exactly and rounded once (98.1, not
    98.10000000000001); an exact value stays exact when its scaled value is
    rational, and becomes the nearest float when not.
    """
    from .exact import short_text

    try:
        scaled = sc.apply(values, s)
    except LimitError as err:  # a float value rounded beyond floating point: said in the command line's terms
        raise _out_of_float_range(err.what, err.culprit) from None
    out = {}
    for n, new in scaled.items():
        if isinstance(new, Fraction):
            if max(new.numerator.bit_length(), new.denominator.bit_length()) > _MAX_DIGITS * 3.32:
                raise _CommandError(
                    f"the scaled value of {n!r} is {short_text(new)}, with more than {_MAX_DIGITS} "
                    "digits; choose a smaller --s",
                    culprit=n,
                )
        elif not isinstance(new, float):  # an irrational exact number
            new = float(new) if abs(new) < 1e308 else math.inf
        if isinstance(new, float) and (not math.isfinite(new) or (new == 0 and values[n] != 0)):
            raise _out_of_float_range(f"the scaled value of {n!r}", n)
        out[n] = new
    return out


def _out_of_float_range(what: str, culprit) -> CommandLineError:
    return _CommandError(
        f"{what} is beyond the range of floating point (about 1e-308 to 1e308); choose an --s nearer to 1",
        culprit=culprit,
    )


def _run_search(model: ModelFile, args):
    from .scalesearch import search

    scale = _parse_scale(args.scale)
    if args.fixed is not None:
        fixed = tuple(args.fixed)
    elif args.no_default_fixed:
        fixed = ()
    else:
        fixed = None
    return search(model.system, scale, fixed, allow=args.allow)


# -- the commands: each computes its answer and prints it in the format asked for ------------


def _print(answer, args) -> None:
    print(_text(answer, args))


def _text(answer, args) -> str:
    """The answer as the command prints it (rendered while a progress bar still shows: a large table takes time)."""
    return _as_named(render(answer, args.format))


def _stages(args, stages) -> StageBar:
    """The command's bar of named stages on stderr: shown only on a terminal, never in JSON mode."""
    return StageBar(args.command, stages, show=wanted(args.format))


def _zero_valued(model: ModelFile) -> tuple[str, ...]:
    """The variables whose value in the file is 0, in file order."""
    return tuple(n for n, v in model.values.items() if v == 0)


def _default_repeating(model: ModelFile) -> tuple[str, ...]:
    """The repeaters of ``groups`` without ``--repeating``: the system's default, unless one of them is 0.

    A repeater whose value is 0 leaves every group it divides undefined.
    Then the first valid set (in ``bases`` order) is taken that avoids time
    variables, zero values and variables without one value (so that every
    group gets a value), or failing that the first without time variables
    and zero values, or the first without zero values; if every set needs
    a zero, the system's default after all.
    """
    system = model.system
    default = system.default_repeating()
    zero = set(_zero_valued(model))
    if not zero & set(default):
        return default
    time = set(system.time_variables)
    valueless = set(system.variables) - set(model.values)
    for avoid in (zero | time | valueless, zero | time, zero):
        first = next(system.iter_bases(exclude=[n for n in system.variables if n in avoid]), None)
        if first is not None:
            return first
    return default


def _group_value(group, values):
    """A group's value from the file's values: None without every value, a phrase when it is undefined."""
    if not all(n in values for n in group.exponents):
        return None
    try:
        return group.evaluate(values)
    except InvalidRequestError:  # a zero to a negative power, or a value beyond floating point
        zero = [n for n, p in group.exponents.items() if p < 0 and values[n] == 0]
        if not zero:
            raise
        return f"undefined ({zero[0]} = 0)"


def _cmd_groups(args) -> int:
    from .answers import GroupsAnswer

    engine = args.repeating is None and _engine_path(args.file) is not None
    with _stages(args, ("loading", "computing")) as bar:
        bar.stage("loading")
        if engine:  # the robot's numbers, never a solver's setting
            model, engine_model = _load_with_engine(args.file, args.scene)
            repeating = engine_model.default_repeating()
        else:
            model = _load(args.file, args.scene)
            repeating = args.repeating if args.repeating is not None else _default_repeating(model)
        bar.stage("computing")
        groups = model.system.pi_groups(repeating=repeating)
        values = tuple(_group_value(g, model.values) for g in groups)
        passed_over = () if args.repeating is not None else _zero_valued(model)
        text = _text(GroupsAnswer(model.name, model.system, groups, values, passed_over, engine), args)
    print(text)
    return EXIT_OK


def _cmd_bases(args) -> int:
    from .answers import BasesAnswer

    if args.count and args.all:
        raise _CommandError("--count prints only the number of sets and --all lists every one; give one of them")
    with _stages(args, ("loading", "counting")) as bar:
        bar.stage("loading")
        model = _load(args.file, args.scene)
        system = model.system
        bar.stage("counting")
        if args.all:
            bases = system.bases(exclude=args.exclude, require=args.require)
            count = len(bases)
        else:  # the count, and the first sets only: a large model has millions
            count = system.count_bases(exclude=args.exclude, require=args.require)
            bases = (
                None
                if args.count
                else tuple(islice(system.iter_bases(exclude=args.exclude, require=args.require), BASES_SHOWN))
            )
        text = _text(BasesAnswer(model.name, system.rank, tuple(args.exclude), tuple(args.require), count, bases), args)
    print(text)
    return EXIT_OK


def _cmd_search(args) -> int:
    from .answers import SearchAnswer

    with _stages(args, ("loading", "searching")) as bar:
        bar.stage("loading")
        model, engine_model = _load_with_engine(args.file, args.scene)
        bar.stage("searching")
        result = _run_search(model, args)
        text = _text(SearchAnswer(model.name, result), args)
    print(text)
    if engine_model is not None and result.feasible:  # scalings the file's mixed numbers cannot follow
        from .engines.cli import search_refusals

        refusal = search_refusals(engine_model, result.scalings)
        if refusal is not None:
            say(f"pitheorem: note: {refusal}")
    return EXIT_OK if result.feasible else EXIT_INFEASIBLE


def _chosen_scaling(result, k: int):
    """The K-th minimal scaling of a feasible search (``--solution K``)."""
    count = result.n_scalings
    if not 1 <= k <= count:
        raise _CommandError(
            f"--solution {k} is out of range: the request has {count} minimal "
            f"{'scaling' if count == 1 else 'scalings'}; choose " + ("1" if count == 1 else f"1 to {count}")
        )
    return result.scalings[k - 1]


def _scaled_scene(args, model, engine_model, result, s, engine=None, file=None, named=False):
    """The model, its engine model, search result and scaling, in a scene the scaling can follow.

    When the engine's default scene refuses the chosen scaling (PyBullet's link
    damping and split impulse) and the user set none of the remedy's options,
    the file is loaded once more in the remedy scene, used by both runs, and
    one line on stderr says which scene and how to choose another.  `file`
    is the model file (default ``args.file``); `named` puts its name in that
    line (``sweep`` of several files says it once per file).
    """
    from .engines.cli import automatic_scene, parse_scene, scene_refusal, scene_text

    file = args.file if file is None else file
    sc = _chosen_scaling(result, args.solution)
    added = automatic_scene(engine_model, sc, s, parse_scene(args.scene))
    if not added:
        return model, engine_model, result, sc
    chosen = _load_with_engine(file, args.scene, engine, added)
    chosen_result = _run_search(chosen[0], args)
    chosen_sc = _chosen_scaling(chosen_result, args.solution)
    if automatic_scene(chosen[1], chosen_sc, s):  # the user's own options still refuse it: one short line
        raise _CommandError(f"{Path(file).name}: {scene_refusal(engine_model, sc, s)}")
    runs = f"every run of {Path(file).name}" if named else "both runs"
    say(f"pitheorem: note: scene {scene_text(added)} in {runs} (the default refuses this scaling; --scene sets it)")
    return (*chosen, chosen_result, chosen_sc)


def _say_scaling(result, k: int) -> None:
    """One line on stderr: which of several minimal scalings apply or verify uses, and how to pick another."""
    if result.n_scalings > 1:
        say(
            f"pitheorem: note: minimal scaling #{k} of {result.n_scalings}; --solution K picks another "
            "(pitheorem search lists them)"
        )


def _cmd_apply(args) -> int:
    with _stages(args, ("loading", "searching", "scaling", "writing")) as bar:
        answer = _apply(args, bar)
        if answer is None:  # no scaling meets the request: said on stderr, nothing written
            return EXIT_INFEASIBLE
        text = _text(answer[0], args)
    print(text)
    if answer[1] is not None:  # an engine file: which of the minimal scalings was used
        _say_scaling(answer[1], args.solution)
    return EXIT_OK


def _apply(args, bar: StageBar):
    """``apply``'s answer and, for an engine file, its search result; None when no scaling meets the request."""
    from .answers import ApplyAnswer
    from .exact import read_positive

    bar.stage("loading")
    model, engine_model = _load_with_engine(args.file, args.scene)
    for flag, given in (("--keep-inputs", args.keep_inputs), ("--copy-assets", args.copy_assets)):
        if given and engine_model is None:
            raise _CommandError(f"{flag} is for MJCF and URDF model files; {args.file} has no actuators or assets")
    s = read_positive(args.s, "--s")
    if engine_model is None and not model.values:
        raise _CommandError(
            f"{args.file}: no variable has a value, so there is nothing to scale; "
            'give values in the model file, e.g. m = { dimension = "M", value = 1.5 }'
        )
    bar.stage("searching")
    result = _run_search(model, args)
    if not result.feasible:
        say(f"pitheorem: {result.explanation()} Nothing written.")
        return None
    sc = _chosen_scaling(result, args.solution)
    if engine_model is not None:  # write the scaled file the engine loads
        from .engines.cli import apply_engine, parse_scene

        model, engine_model, result, sc = _scaled_scene(args, model, engine_model, result, s)
        answer = apply_engine(
            engine_model,
            sc,
            s,
            args.output,
            scene=parse_scene(args.scene),
            keep_inputs=args.keep_inputs,
            copy_assets=args.copy_assets,
            stage=bar.stage,
        )
        return answer, result
    bar.stage("scaling")
    scaled_model = model.with_values(_scaled_values(sc, model.values, s), name=f"{model.name}, scaled with s = {s}")
    output = None
    if args.output:
        bar.stage("writing")
        out = Path(args.output)
        if model.path and out.exists() and out.resolve() == Path(model.path).resolve():
            raise _CommandError(f"--output {args.output!r} is the input file; choose another name")
        try:
            write_model_file(scaled_model, out)
        except OSError as err:
            raise _CommandError(f"cannot write {args.output!r}: {err.strerror or err}") from None
        output = str(out)
    return ApplyAnswer(model.name, s, args.solution, result, sc, model.values, scaled_model.values, output), None


def _add_engine_file_flags(p, copy: str) -> None:
    """``--keep-inputs`` and ``--copy-assets``, the options of a written MJCF or URDF copy."""
    p.add_argument(
        "--keep-inputs",
        action="store_true",
        help=f"keep every actuator input's value (MJCF): the factors go on the gains, so a policy trained on "
        f"the original's inputs drives the {copy} copy as it is; default: inputs are scaled by their dimension",
    )
    p.add_argument(
        "--copy-assets",
        action="store_true",
        help="copy the mesh and texture files into OUT's folder (OUT_STEM_assets/); default: name the originals "
        "relative to OUT",
    )


def _cmd_verify(args) -> int:
    if _engine_path(args.file) is None:
        raise _CommandError(f"{args.file}: verify runs MJCF (.xml) or URDF (.urdf) model files in their engine")
    from .engines.cli import VERIFY_STAGES, verify_engine
    from .exact import read_positive

    with _stages(args, ("loading", "searching", *VERIFY_STAGES)) as bar:
        bar.stage("loading")
        model, engine_model = _load_with_engine(args.file, args.scene, args.engine)
        s = read_positive(args.s, "--s")
        duration = read_positive(args.duration, "--duration")
        bar.stage("searching")
        result = _run_search(model, args)
        if not result.feasible:
            say(f"pitheorem: {result.explanation()} Nothing verified.")
            return EXIT_ERROR
        model, engine_model, result, sc = _scaled_scene(args, model, engine_model, result, s, args.engine)
        answer = verify_engine(engine_model, sc, s, float(duration), args.input, stage=bar.stage)
        text = _text(answer, args)
    print(text)
    _say_scaling(result, args.solution)
    return EXIT_OK if answer.report.similar else EXIT_INFEASIBLE


def _cmd_sweep(args) -> int:
    from .exact import read_positive

    paths = [_engine_path(f) for f in args.file]
    if None in paths:
        culprit = args.file[paths.index(None)]
        raise _CommandError(f"{culprit}: sweep runs MJCF (.xml) or URDF (.urdf) model files in their engine")
    from .engines.cli import parse_s_values, sweep_engine

    s = parse_s_values(args.s)
    duration = read_positive(args.duration, "--duration")
    models, scalings = [], []
    with _stages(args, ("loading", "searching")) as bar:  # then a bar of the runs
        for name in args.file:
            bar.stage("loading")
            model, engine_model = _load_with_engine(name, args.scene, args.engine)
            bar.stage("searching")
            result = _run_search(model, args)
            if not result.feasible:
                say(f"pitheorem: {name}: {result.explanation()} Nothing swept.")
                return EXIT_ERROR
            # the scene a scaling needs, as verify chooses it: judged at the first factor that changes anything
            moved = next((v for v in s if v != 1), s[0])
            model, engine_model, result, sc = _scaled_scene(
                args, model, engine_model, result, moved, args.engine, file=name, named=True
            )
            models.append(engine_model)
            scalings.append(sc)
    client = _dask_client(args.dask) if args.dask else None
    show = wanted(args.format)
    answer = sweep_engine(
        models,
        scalings,
        s,
        float(duration),
        names=args.file,
        inputs=args.input,
        client=client,
        plot=args.plot,
        progress=show,
    )
    _print(answer, args)
    failed = any(v in ("not similar", "refused") for sw in answer.sweeps for v in sw.verdicts)
    return EXIT_INFEASIBLE if failed else EXIT_OK


def _dask_client(address: str):
    """A Dask client of the scheduler at `address`, or a one-line error naming the extra."""
    try:
        from distributed import Client
    except ImportError:
        raise _CommandError('--dask needs Dask: pip install "pitheorem[cluster]"') from None
    try:
        return Client(address, timeout=30)
    except (OSError, TimeoutError) as err:
        raise _CommandError(f"--dask {address!r}: cannot reach the scheduler ({err})", culprit=address) from None


def _engine_file(args, command: str) -> str:
    """The MJCF or URDF file of ``check`` and ``convert`` (a shipped one by its path), or a one-line error."""
    path = _engine_path(args.file)
    if path is None:
        raise _CommandError(f"{args.file}: {command} reads MJCF (.xml) or URDF (.urdf) model files")
    return path  # --format is text or json: the parser of both commands allows no other


def _cmd_check(args) -> int:
    path = _engine_file(args, "check")
    from .engines.cli import CHECK_STAGES, check_engine_model, parse_units

    from_units = parse_units(args.from_units, "--from")
    with _stages(args, CHECK_STAGES) as bar:
        text, clean = check_engine_model(
            path, from_units=from_units, engine=args.engine, fmt=args.format, stage=bar.stage
        )
    print(_as_named(text))
    return EXIT_OK if clean else EXIT_INFEASIBLE


def _cmd_convert(args) -> int:
    path = _engine_file(args, "convert")
    from .engines.cli import CONVERT_STAGES, convert_engine, parse_units

    from_units, units = parse_units(args.from_units, "--from"), parse_units(args.units, "--units")
    with _stages(args, CONVERT_STAGES) as bar:
        text = convert_engine(
            path,
            from_units=from_units,
            units=units,
            fit=args.fit,
            output=args.output,
            fmt=args.format,
            keep_inputs=args.keep_inputs,
            copy_assets=args.copy_assets,
            stage=bar.stage,
        )
    print(_as_named(text))
    return EXIT_INFEASIBLE if "no units keep every number clear" in text or '"feasible": false' in text else EXIT_OK


def _cmd_params(args) -> int:
    engine_path = _engine_path(args.file)
    if engine_path is None:  # a TOML or JSON model file: its variables, dimensions and values
        from .answers import ParamsAnswer

        _print(ParamsAnswer(args.file, _load(args.file, args.scene)), args)
        return EXIT_OK
    from .engines.cli import params_answer, parse_scene

    # the file by its name (a shipped one as example:NAME): the first line stays short whatever its folder
    named = _as_named(args.file)
    name = named if named.startswith("example:") else Path(args.file).name
    with _stages(args, ("loading", "printing")) as bar:
        bar.stage("loading")
        answer = params_answer(engine_path, **parse_scene(args.scene), name=name)
        bar.stage("printing")
        text = _text(answer, args)
    print(text)
    return EXIT_OK


# -- parser and entry point ------------------------------------------------------------------


#: the warnings this command has shown: each is shown once, whichever call raised it and however often
_SHOWN: set[str] = set()


def _one_line_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A warning as the command line shows it: ``pitheorem: warning: ...``, never Python's source line; once."""
    text = f"pitheorem: warning: {_as_named(message)}"
    if text in _SHOWN:
        return
    _SHOWN.add(text)
    if file is None or file is sys.stderr:
        say(text)  # above a progress bar that is showing
    else:
        print(text, file=file)


@contextlib.contextmanager
def _engine_warnings(args):
    """The engines' warnings during an MJCF or URDF command, each kind in one line after it.

    MuJoCo prints a warning on the console and appends it to ``MUJOCO_LOG.TXT`` in the working
    folder, once per run: a verdict's twins, controls and counter-runs repeat one breakdown a dozen
    times, and the user's folder gets a file.  While a command runs they are collected instead
    (:func:`pitheorem.engines.cli.engine_warnings`, for every file of a ``sweep``), and after it each
    kind (its text with the numbers left out) is one line: the first text, and how many times the
    engine gave one of its kind.
    """
    files = getattr(args, "file", None) or []
    try:
        paths = [p for p in map(_engine_path, [files] if isinstance(files, str) else files) if p is not None]
    except PiTheoremError:  # a bad FILE is the command's to report
        paths = []
    if not paths:
        yield
        return
    from .engines.cli import engine_warnings

    with contextlib.ExitStack() as stack:
        try:
            collected = stack.enter_context(engine_warnings(paths, getattr(args, "engine", None)))
        except (PiTheoremError, OSError):  # an unknown engine or an unreadable file: the command reports it
            collected = []
        try:
            yield
        finally:
            for engine, heard in collected:
                kinds: dict[str, list] = {}
                for text in heard:
                    kinds.setdefault(re.sub(r"[-+]?\d+(\.\d+)?", "#", text), []).append(text.strip())
                for texts in kinds.values():
                    times = f" ({len(texts)} times in the runs)" if len(texts) > 1 else ""
                    say(f"pitheorem: warning: {engine}: {texts[0]}{times}")


class _Help(argparse.HelpFormatter):
    """Argparse's help, with ``--scene``'s options listed from the engines' own list.

    The list (:func:`pitheorem.engines.loading.scene_options`) is read only when
    help is shown: building the parser must not import the engines.
    """

    def _get_help_string(self, action):  # the hook argparse's own ArgumentDefaultsHelpFormatter overrides
        if action.dest == "scene":
            from .engines.cli import scene_help

            return scene_help()
        return super()._get_help_string(action)


class _Parser(argparse.ArgumentParser):
    """Argparse's parser, whose usage errors are one line, as every other error of the command.

    Its subcommands' parsers are of the same class (``add_subparsers`` makes them so).
    """

    def error(self, message: str):
        self.exit(EXIT_ERROR, f"pitheorem: error: {message} (see '{self.prog} --help')\n")


def build_parser() -> argparse.ArgumentParser:
    """The argparse parser of the ``pitheorem`` command.

    Returns
    -------
    argparse.ArgumentParser

    Examples
    --------
    >>> from pitheorem.cli import build_parser
    >>> args = build_parser().parse_args(["search", "rod.toml", "--scale", "g=1", "--fixed"])
    >>> args.command, args.scale, args.fixed
    ('search', ['g=1'], [])
    """
    parser = _Parser(
        prog="pitheorem",
        description="Exact dimensional analysis and similarity-scaling search on a model file: "
        "TOML, MJCF (MuJoCo) or URDF (PyBullet).",
        epilog="Exit codes: 0 success; 1 no similarity scaling meets the request (search, apply), the copy "
        "is not similar (verify), a number sits at, beyond or near a threshold (check), no units clear every "
        f"threshold (convert --fit); 2 bad input. FILE may be a shipped example, {_EXAMPLES_TEXT}.",
        allow_abbrev=False,
        formatter_class=_Help,
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    common = argparse.ArgumentParser(add_help=False, allow_abbrev=False)
    common.add_argument(
        "file", metavar="FILE", help=f"TOML, MJCF (.xml) or URDF (.urdf) model file, or {_EXAMPLES_TEXT}"
    )
    common.add_argument("--format", choices=FORMATS, default="text", help="output format (default: text)")
    common.add_argument("--scene", nargs="+", metavar="NAME=VALUE", help="URDF files: PyBullet's scene")
    # verify runs only engine files: its FILE names only the shipped MJCF and URDF examples
    engine_common = argparse.ArgumentParser(add_help=False, allow_abbrev=False)
    engine_common.add_argument(
        "file", metavar="FILE", help=f"MJCF (.xml) or URDF (.urdf) model file, or {_ENGINE_EXAMPLES_TEXT}"
    )
    engine_common.add_argument("--format", choices=FORMATS, default="text", help="output format (default: text)")
    engine_common.add_argument("--scene", nargs="+", metavar="NAME=VALUE", help="URDF files: PyBullet's scene")

    request = argparse.ArgumentParser(add_help=False, allow_abbrev=False)
    request.add_argument("--scale", nargs="+", required=True, metavar="NAME=EXP", help=_SCALE_HELP)
    request.add_argument(
        "--fixed",
        nargs="*",
        metavar="NAME",
        help="variables held unchanged (default: those of dimension T; no names: none)",
    )
    request.add_argument("--allow", nargs="*", metavar="NAME", help="only these variables (besides --scale) may change")
    request.add_argument(
        "--no-default-fixed",
        action="store_true",
        help="do not hold time fixed by default (same as --fixed with no names)",
    )

    options = {"allow_abbrev": False, "formatter_class": _Help}
    p = sub.add_parser(
        "params",
        parents=[common],
        **options,
        help="every variable or engine parameter, with its dimension and value",
        description="List every variable of a TOML model file, or every dimensional number of "
        "an MJCF (MuJoCo) or URDF (PyBullet) model, with its dimension and value.",
    )
    p.set_defaults(run=_cmd_params)

    p = sub.add_parser(
        "groups",
        parents=[common],
        **options,
        help="Pi groups of the model",
        description="Print the dimensionless (Pi) groups of the model.",
    )
    p.add_argument(
        "--repeating",
        nargs="+",
        metavar="NAME",
        help="repeating variables (default: the first valid set without time variables; if "
        "that holds a variable whose value is 0, the first without those either)",
    )
    p.set_defaults(run=_cmd_groups)

    p = sub.add_parser(
        "bases",
        parents=[common],
        **options,
        help=f"the number of valid repeating sets, and the first {BASES_SHOWN}",
        description="List every valid set of repeating variables, with their count.",
    )
    p.add_argument("--exclude", nargs="*", default=[], metavar="NAME", help="never use these as repeaters")
    p.add_argument("--require", nargs="*", default=[], metavar="NAME", help="every set must contain these")
    p.add_argument("--count", action="store_true", help="print only the number of sets")
    p.add_argument(
        "--all", action="store_true", help=f"list every set (default: the number of sets and the first {BASES_SHOWN})"
    )
    p.set_defaults(run=_cmd_bases)

    p = sub.add_parser(
        "search",
        parents=[common, request],
        **options,
        help="every minimal similarity scaling, or a proof that none exists",
        description="Find every minimal similarity scaling meeting the request, "
        "or print a certificate that none exists (exit code 1).",
    )
    p.set_defaults(run=_cmd_search)

    p = sub.add_parser(
        "apply",
        parents=[common, request],
        **options,
        help="scale the model's values by a minimal scaling (and write them with --output)",
        description="Scale the values of the model file by a minimal similarity scaling; "
        "--output writes the scaled file.",
    )
    p.add_argument(
        "--s",
        required=True,
        metavar="S",
        help="the scale factor s itself, e.g. 2 or 1/2 (each variable is multiplied by s^EXP)",
    )
    p.add_argument("--solution", type=int, default=1, metavar="K", help="use the K-th minimal scaling (default 1)")
    p.add_argument(
        "--output",
        metavar="OUT",
        help="write the scaled model file: .toml or .json for a TOML model, the same kind for MJCF/URDF",
    )
    _add_engine_file_flags(p, "scaled")
    p.set_defaults(run=_cmd_apply)

    p = sub.add_parser(
        "verify",
        parents=[engine_common, request],
        **options,
        help="run an MJCF or URDF model and its scaled copy: similar or not, and why",
        description="Run the model and its scaled copy in their engine and compare them in original "
        "units: exact at s a power of four, similar within the model's own rounding, or not, with "
        "the causes found. Exit codes: 0 similar, 1 not similar, 2 bad input.",
    )
    p.add_argument("--s", required=True, metavar="S", help="the scale factor, e.g. 4 (a power of four: exact) or 10")
    p.add_argument("--duration", default="1", metavar="T", help="simulated time of the original run (default 1)")
    p.add_argument(
        "--input",
        choices=("smooth", "zero"),
        default="smooth",
        help="actuator inputs: a smooth sine per actuator (default), or none",
    )
    p.add_argument("--solution", type=int, default=1, metavar="K", help="use the K-th minimal scaling (default 1)")
    p.add_argument(
        "--engine", metavar="ENGINE", help="run the file in this engine instead of its own (an MJCF file in mjx, say)"
    )
    p.set_defaults(run=_cmd_verify)

    p = sub.add_parser(
        "sweep",
        parents=[request],
        **options,
        help="verify MJCF or URDF models at many scale factors: where similarity holds",
        description="Verify each model at every scale factor (as verify does at one), in parallel on "
        "this machine's cores or on a Dask cluster (--dask); a table per file, and with several "
        "files a table of verdicts by scale. Exit codes: 0 every copy exact or similar (or "
        "inconclusive), 1 some copy not similar or refused, 2 bad input.",
    )
    p.add_argument(
        "file", nargs="+", metavar="FILE", help=f"MJCF (.xml) or URDF (.urdf) model files, or {_EXAMPLES_TEXT}"
    )
    p.add_argument("--format", choices=FORMATS, default="text", help="output format (default: text)")
    p.add_argument("--scene", nargs="+", metavar="NAME=VALUE", help="URDF files: PyBullet's scene")
    p.add_argument(
        "--s",
        nargs="+",
        required=True,
        metavar="S",
        help="scale factors: numbers (4, 1/4) and ranges A:B:N, N factors from A to B evenly spaced in log s",
    )
    p.add_argument("--duration", default="1", metavar="T", help="simulated time of each original run (default 1)")
    p.add_argument(
        "--input",
        choices=("smooth", "zero"),
        default="smooth",
        help="actuator inputs: a smooth sine per actuator (default), or none",
    )
    p.add_argument("--solution", type=int, default=1, metavar="K", help="use the K-th minimal scaling (default 1)")
    p.add_argument("--engine", metavar="ENGINE", help="run the files in this engine instead of their own")
    p.add_argument("--plot", metavar="PNG", help="write the figure (with several files, one per file: PNG_stem.png)")
    p.add_argument("--dask", metavar="ADDRESS", help="run on the Dask cluster of this scheduler (tcp://host:8786)")
    p.set_defaults(run=_cmd_sweep)

    units = argparse.ArgumentParser(add_help=False, allow_abbrev=False)
    units.add_argument(
        "file", metavar="FILE", help=f"MJCF (.xml) or URDF (.urdf) model file, or {_ENGINE_EXAMPLES_TEXT}"
    )
    units.add_argument("--format", choices=("text", "json"), default="text", help="output format (default: text)")
    units.add_argument(
        "--from",
        dest="from_units",
        nargs="+",
        metavar="BASE=UNIT",
        help="the units the file is written in, e.g. L=cm M=g (default: SI, or those the file records)",
    )

    p = sub.add_parser(
        "check",
        parents=[units],
        **options,
        help="the engine thresholds an MJCF or URDF model sits beyond or near",
        description="Hold every number of the model against the catalogued thresholds of its engine "
        "(MuJoCo: mjMINVAL, mjMINMU, mjMAXVAL; PyBullet: its minimum object sizes), each with a unit "
        "change that clears it. Exit codes: 0 clean, 1 some number at, beyond or near a threshold, "
        "2 bad input.",
    )
    p.add_argument(
        "--engine",
        metavar="ENGINE",
        help="hold the numbers against this engine's thresholds (default: the file's engine)",
    )
    p.set_defaults(run=_cmd_check)

    p = sub.add_parser(
        "convert",
        parents=[units],
        **options,
        help="the same MJCF model in other units (--units L=mm, or --fit ENGINE)",
        description="Write the same model in other units: every number by its dimension (gravity, "
        "densities, stiffness, damping, gains, time constants, the time step and keyframes), the "
        "units recorded in the file. --fit ENGINE chooses units clear of that engine's thresholds. "
        "A fit that keeps the file's own units writes nothing and says so. "
        "Exit codes: 0 converted (or nothing to convert), 1 no units clear every threshold (the closest are "
        "used), 2 bad input.",
    )
    p.add_argument("--units", nargs="+", metavar="BASE=UNIT", help="the new units, e.g. L=mm M=g T=ms")
    p.add_argument("--fit", metavar="ENGINE", help="choose units clear of this engine's thresholds (mujoco, ...)")
    p.add_argument("--output", metavar="OUT", help="write the converted file")
    _add_engine_file_flags(p, "converted")
    p.set_defaults(run=_cmd_convert)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``pitheorem`` command; return its exit code.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments after the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 on success, 1 when no similarity scaling meets the request, 2 on
        bad input (after printing one line ``pitheorem: error: ...`` to
        stderr).

    Examples
    --------
    >>> from pitheorem.cli import main
    >>> main(["groups", "example:hinged_rod", "--repeating", "m", "l", "k_theta"])
    hinged rod: 9 variables, rank 3, 6 dimensionless groups
    repeating variables: m, l, k_theta
    <BLANKLINE>
    group       expression                   value
    Pi_theta_r  theta_r                      1.0472
    Pi_g        g*l*m/k_theta                0.2943
    Pi_c_theta  c_theta**2/(k_theta*l**2*m)  0.166667
    Pi_t        k_theta*t**2/(l**2*m)
    Pi_F        F*l/k_theta
    Pi_tau      tau/k_theta
    0
    >>> main(["search", "example:hinged_rod", "--scale", "g=1", "--fixed", "t", "m", "k_theta"])
    Impossible: g**2*m*t**2/k_theta is dimensionless and built only from prescribed and fixed variables, but the request would multiply it by s^2, so no change of units (and hence no similarity scaling) can do it.
    certificate: Pi = g**2*m*t**2/k_theta (the request multiplies it by s^2)
    1
    """
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version, and argparse's usage errors
        return exc.code if isinstance(exc.code, int) else EXIT_ERROR
    try:
        _SHOWN.clear()
        with warnings.catch_warnings(), _engine_warnings(args):  # both restore the displays on return
            warnings.showwarning = _one_line_warning
            return args.run(args)
    except PiTheoremError as err:
        message = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
        print(f"pitheorem: error: {_as_named(message)}", file=sys.stderr)
        return EXIT_ERROR
    except BrokenPipeError:  # e.g. `pitheorem bases FILE | head`: the reader has gone, stay quiet
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_OK
    except OSError as err:
        print(f"pitheorem: error: {_as_named(repr(err.filename))}: {err.strerror or err}", file=sys.stderr)
        return EXIT_ERROR
    except (ValueError, TypeError, ArithmeticError, RecursionError, MemoryError) as err:
        # last resort: a bad input that slipped past validation must still give one line and
        # exit code 2, never a traceback and never 1 (which means "no scaling exists")
        message = str(err).strip().splitlines()[0] if str(err).strip() else ""
        print(
            f"pitheorem: error: {type(err).__name__}: {_as_named(message)} (please report this input)", file=sys.stderr
        )
        return EXIT_ERROR
