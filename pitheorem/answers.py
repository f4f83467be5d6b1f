"""The command line's answers: what each subcommand found about one model file, as values.

``pitheorem groups``, ``bases``, ``search``, ``apply``, ``params``, ``verify`` and ``sweep``
compute one of these and print ``format(answer, FORMAT)``: its text, LaTeX,
HTML or JSON comes from :mod:`pitheorem.formatting`, like every other
display.  Each answer joins what one output shows: the model file's name
with its Pi groups and their values, a search with the model's name, and
so on.  They hold results and never compute.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from fractions import Fraction
from typing import NamedTuple

from .formatting import TextDisplay

__all__ = [
    "ApplyAnswer",
    "BasesAnswer",
    "EngineApplyAnswer",
    "EngineVerifyAnswer",
    "GroupsAnswer",
    "ParamsAnswer",
    "SearchAnswer",
    "SweepAnswer",
]


class GroupsAnswer(NamedTuple):
    """``pitheorem groups``: a model's Pi groups, with their values where the file gives them.

    Parameters
    ----------
    model : str
        The model's name.
    system : System
    groups : PiSet
    values : tuple
        Each group's value (Fraction or float), None when a variable has no
        value, or a phrase such as ``"undefined (density = 0)"`` when a
        zero value meets a negative exponent.
    passed_over : tuple of str, optional
        The variables whose value is 0, which the default repeaters avoid
        (empty when the repeaters were given).
    settings_avoided : bool, optional
        Whether the default repeaters also avoid the engine's settings
        (an engine model's, :meth:`~pitheorem.engines.EngineModel.default_repeating`).

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.answers import GroupsAnswer
    >>> s = pt.System({"l": "L", "h": "L"})
    >>> print(GroupsAnswer("pair", s, s.pi_groups(repeating=("l",)), (None,)))
    pair: 2 variables, rank 1, 1 dimensionless groups
    repeating variables: l
    <BLANKLINE>
    group  expression  value
    Pi_h   h/l
    """

    model: str
    system: object
    groups: object
    values: tuple
    passed_over: tuple[str, ...] = ()
    settings_avoided: bool = False

    __str__ = TextDisplay.__str__
    __format__ = TextDisplay.__format__


class BasesAnswer(NamedTuple):
    """``pitheorem bases``: the valid repeating sets of a model, or only their number.

    Parameters
    ----------
    model : str
    rank : int
    exclude, require : tuple of str
        The conditions asked for.
    n_bases : int
    bases : sequence of tuple of str, or None
        The sets; None when only the count was asked for.

    Examples
    --------
    >>> from pitheorem.answers import BasesAnswer
    >>> print(BasesAnswer("pair", 1, (), (), 2, [("l",), ("h",)]))
    pair: 2 valid repeating sets of 1 variables
    1  l
    2  h
    """

    model: str
    rank: int
    exclude: tuple[str, ...]
    require: tuple[str, ...]
    n_bases: int
    bases: Sequence[tuple[str, ...]] | None

    __str__ = TextDisplay.__str__
    __format__ = TextDisplay.__format__


class SearchAnswer(NamedTuple):
    """``pitheorem search``: a search on a model; its notes in the command line's terms.

    Parameters
    ----------
    model : str
    result : SearchResult

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.answers import SearchAnswer
    >>> res = pt.search(pt.System({"l": "L", "g": "L T^-2", "t": "T"}), scale={"g": 1})
    >>> print(format(SearchAnswer("drop", res), "text").splitlines()[1])
    Time variable t is held fixed by default; give --fixed with no names to let time change
    """

    model: str
    result: object

    __str__ = TextDisplay.__str__
    __format__ = TextDisplay.__format__


class ApplyAnswer(NamedTuple):
    """``pitheorem apply``: a model's values scaled by one minimal scaling.

    Parameters
    ----------
    model : str
    s : Fraction
        The scale factor.
    solution : int
        Which minimal scaling of `result`, from 1.
    result : SearchResult
    scaling : Scaling
        That scaling.
    values, scaled : mapping of str to number
        The file's values and the scaled ones.
    output : str or None
        The file written, if any.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from fractions import Fraction
    >>> from pitheorem.answers import ApplyAnswer
    >>> res = pt.search(pt.System({"l": "L", "t": "T"}), scale={"l": 1}, fixed=())
    >>> sc = res.scalings[0]
    >>> print(ApplyAnswer("rope", Fraction(2), 1, res, sc, {"l": 3}, sc.apply({"l": 3}, 2), None))
    rope, s = 2: the only minimal scaling
      l -> s l
    <BLANKLINE>
    variable  factor  value  scaled value
    l         s       3      6
    """

    model: str
    s: Fraction
    solution: int
    result: object
    scaling: object
    values: Mapping[str, object]
    scaled: Mapping[str, object]
    output: str | None

    __str__ = TextDisplay.__str__
    __format__ = TextDisplay.__format__


class ParamsAnswer(NamedTuple):
    """``pitheorem params``: a model's parameter table, under the file name as given.

    Parameters
    ----------
    model : str
        The file, as the command line named it.
    engine_model : EngineModel or ModelFile
        The engine model of an MJCF or URDF file, or the model of a TOML
        file (its variables are its parameters).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.answers import ParamsAnswer
    >>> answer = ParamsAnswer("pendulum.xml", engines.load(engines.example_path("pendulum.xml")))
    >>> str(answer).splitlines()[0]
    'pendulum.xml: mujoco model, 49 parameters (source: 11 file, 35 default, 3 derived)'
    """

    model: str
    engine_model: object

    __str__ = TextDisplay.__str__
    __format__ = TextDisplay.__format__


class EngineApplyAnswer(NamedTuple):
    """``pitheorem apply`` on an MJCF or URDF file: the parameters a scaling changes, and the files written.

    Parameters
    ----------
    model : str
        The file's name.
    s : Fraction
    scaling : Scaling
    changed : tuple of (str, Fraction)
        Each parameter the scaling changes, with its exponent of ``s``.
    n_parameters : int
        How many parameters the model has.
    output : str or None
        The scaled file written, if any.
    also_written : tuple of str
        Files written beside it (PyBullet's settings).
    details : tuple of (str, tuple, tuple), optional
        For each changed parameter, in the order of `changed`: its
        dimension's text, its values and its scaled values.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from fractions import Fraction
    >>> from pitheorem.answers import EngineApplyAnswer
    >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L", "t": "T"}), {"L": 1})
    >>> print(EngineApplyAnswer("arm.xml", Fraction(2), sc, (("l", Fraction(1)),), 2, None, (),
    ...                         (("L", (0.5,), (1.0,)),)))
    arm.xml, s = 2: units of L by s
    1 of 2 parameters change, by dimension:
      dimension  factor  count  parameters
      L          s       1      l
    <BLANKLINE>
    parameter  factor  value  scaled value
    l          s       0.5    1
    """

    model: str
    s: Fraction
    scaling: object
    changed: tuple[tuple[str, Fraction], ...]
    n_parameters: int
    output: str | None
    also_written: tuple[str, ...] = ()
    details: tuple[tuple[str, tuple, tuple], ...] = ()

    __str__ = TextDisplay.__str__
    __format__ = TextDisplay.__format__


class EngineVerifyAnswer(NamedTuple):
    """``pitheorem verify``: a model file and its scaled copy run in their engine, and the verdict.

    Parameters
    ----------
    model : str
        The file's path.
    engine : str
    s : Fraction
    duration : float
        Simulated time of the original run.
    input : str
        ``"smooth"`` or ``"zero"``.
    exact_expected : bool
        Whether every factor is exact in binary (``s`` a power of four), so
        that the scaled run should equal the original bit for bit.
    report : SimilarityReport
        What :func:`pitheorem.engines.verify` found.
    notes : tuple of str
        The engine's notes on this model (``EngineNotes``): a known bug of
        the installed version that can touch the verdict.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from fractions import Fraction
    >>> from pitheorem import engines
    >>> from pitheorem.answers import EngineVerifyAnswer
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> rep = engines.verify(model, sc, 4, duration=0.5, controls=lambda t: [0.1])
    >>> print(EngineVerifyAnswer("pendulum.xml", "mujoco", Fraction(4), 0.5, "smooth", True, rep))
    exact: the scaled copy, mapped back, equals the original bit for bit at every step (s = 4, 250 steps)
    strength: an error of 0.0001 in gravity or the masses is caught; the twins stay together to the end (t = 0.5)
    """

    model: str
    engine: str
    s: Fraction
    duration: float
    input: str
    exact_expected: bool
    report: object
    #: what the engine's runner says of itself that can touch this verdict (a known bug of its version)
    notes: tuple = ()

    __str__ = TextDisplay.__str__
    __format__ = TextDisplay.__format__


class SweepAnswer(NamedTuple):
    """``pitheorem sweep``: one sweep per model file, and with several files a table of robots by scale.

    Parameters
    ----------
    model : tuple of str
        Each file's name as given on the command line.
    sweeps : tuple of Sweep
        What :func:`pitheorem.engines.sweep` found for each file, in the
        order of the files.
    plots : tuple of str
        The figures written (``--plot``), one per file; empty without.

    Examples
    --------
    >>> from pitheorem.answers import SweepAnswer
    >>> from pitheorem.engines import Sweep, SweepRow
    >>> rows = (SweepRow(1, "exact", 0.0, 1e-12, None, True, None, (), ()),)
    >>> a = SweepAnswer(("a.xml", "b.xml"), (Sweep("a.xml", "mujoco", None, 1.0, rows),
    ...                                      Sweep("b.xml", "mujoco", None, 1.0, rows)), ())
    >>> print(str(a).splitlines()[-3:])
    ['robot  1', 'a.xml  exact', 'b.xml  exact']
    """

    model: tuple
    sweeps: tuple
    plots: tuple

    __str__ = TextDisplay.__str__
    __format__ = TextDisplay.__format__
