r"""The pieces every format shares, each written once.

* powers of the scale factor ``s``: :func:`power_text` (``s^2``, ``1/s``)
  and :func:`power_latex` (``s^{2}``, ``s^{-1}``);
* exact numbers: :func:`rational_text` for an exponent, :func:`json_number`
  and :func:`value_text` for a value (a float, or an exact Fraction), and
  :func:`values_text` for a parameter's numbers in a table cell;
* a number in a message or a cause: :func:`float_text`, the shortest text
  that reads back as the same number (``0.004``, ``200``, ``1e+10``);
* names and text in LaTeX: :func:`latex_name` (``k_theta`` as
  ``k_{\theta}``) and :func:`latex_escape`;
* how a search's notes and request are phrased: :func:`note_text`,
  :func:`request_text`, and each front end's way to let time change
  (:data:`PYTHON_TIME_REMEDY`, :data:`COMMAND_LINE_TIME_REMEDY`);
* aligned plain-text columns: :func:`align`.

No value type is imported here: a value is read by its attributes.
"""

from __future__ import annotations

from fractions import Fraction

import sympy

from ..errors import InvalidRequestError
from ..exact import read_number

__all__ = [
    "COMMAND_LINE_TIME_REMEDY",
    "NAMES_SHOWN",
    "PYTHON_TIME_REMEDY",
    "SWEEP_HEADER",
    "UNCHANGED",
    "VALUES_SHOWN",
    "align",
    "base_latex",
    "changed_by_kind",
    "changed_rows",
    "default_text",
    "deviation_rows",
    "file_name",
    "float_text",
    "group_name_latex",
    "json_number",
    "latex_escape",
    "latex_name",
    "names_text",
    "note_text",
    "parameter_rows",
    "parameters_head",
    "power_latex",
    "power_text",
    "range_cells",
    "rational_latex",
    "rational_text",
    "registry",
    "request_text",
    "scale_text",
    "search_cells",
    "solutions_text",
    "sweep_cells",
    "sweep_fit_text",
    "sweep_grid",
    "sweep_head",
    "unit_change_text",
    "unit_fit_rows",
    "value_text",
    "values_text",
    "which_scaling",
]

#: how the Python front end says to let time change, closing a "time_fixed" note
PYTHON_TIME_REMEDY = "pass fixed=() to let time change"
#: how the command line says it
COMMAND_LINE_TIME_REMEDY = "give --fixed with no names to let time change"
#: the mark of an unchanged entry (a power s^0) in a table cell, the same in text, LaTeX and HTML
UNCHANGED = "-"
#: how many names a sentence lists before it says how many more there are
NAMES_SHOWN = 6


def registry(renderers: dict):
    """A decorator that files a renderer in `renderers` under the value types it renders.

    Each format module keeps one ``RENDERERS`` dict, keyed by the qualified
    name of each value type (the names of its class hierarchy are looked
    up, so a subclass without a renderer of its own gets its parent's).

    Parameters
    ----------
    renderers : dict
        The format module's ``RENDERERS``.

    Returns
    -------
    callable
        ``renders(*names)``, a decorator.

    Examples
    --------
    >>> from pitheorem.formatting.pieces import registry
    >>> RENDERERS = {}
    >>> renders = registry(RENDERERS)
    >>> @renders("fractions.Fraction")
    ... def fraction(x):
    ...     return f"{x.numerator} over {x.denominator}"
    >>> RENDERERS["fractions.Fraction"](__import__("fractions").Fraction(1, 2))
    '1 over 2'
    """

    def renders(*names: str):
        def register(renderer):
            for name in names:
                renderers[name] = renderer
            return renderer

        return register

    return renders


# -- powers of s -----------------------------------------------------------------------------


def power_text(exponent) -> str:
    """Plain-text power of s: ``-`` (:data:`UNCHANGED`) for unchanged, ``s``, ``s^2``, ``1/s``, ``s^(1/2)``.

    Parameters
    ----------
    exponent : int, Fraction or float
        A float is read by :func:`pitheorem.exact.read_number`'s float rule.

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import power_text
    >>> [power_text(p) for p in (0, 1, 2, -1, -3, 0.5)]
    ['-', 's', 's^2', '1/s', '1/s^3', 's^(1/2)']
    """
    p = read_number(exponent, "a power of s")  # a float by the float rule, as every number pitheorem reads
    if p == 0:
        return UNCHANGED
    if p == 1:
        return "s"
    if p == -1:
        return "1/s"
    if p.denominator != 1:
        return f"s^({p})"
    return f"s^{p}" if p > 0 else f"1/s^{-p}"


def power_latex(exponent) -> str:
    r"""LaTeX power of s: ``1`` for unchanged, ``s``, ``s^{2}``, ``s^{-1/2}`` ...

    Parameters
    ----------
    exponent : int or Fraction

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import power_latex
    >>> from fractions import Fraction
    >>> [power_latex(p) for p in (0, 1, -1, Fraction(1, 2))]
    ['1', 's', 's^{-1}', 's^{1/2}']
    """
    p = Fraction(exponent)
    if p == 0:
        return "1"
    if p == 1:
        return "s"
    return f"s^{{{p}}}"


# -- exact numbers ---------------------------------------------------------------------------


def rational_text(x) -> str:
    """An exact exponent as text: ``"2"``, ``"-1/2"`` (what JSON holds for a rational).

    Parameters
    ----------
    x : int or Fraction

    Returns
    -------
    str

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.formatting.pieces import rational_text
    >>> rational_text(Fraction(-1, 2)), rational_text(Fraction(4, 2))
    ('-1/2', '2')
    """
    return str(Fraction(x))


def rational_latex(x) -> str:
    r"""An exact number as LaTeX math: ``2``, ``\frac{1}{2}``, ``- \frac{3}{4}``.

    Parameters
    ----------
    x : int or Fraction

    Returns
    -------
    str

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.formatting.pieces import rational_latex
    >>> rational_latex(Fraction(-3, 4)), rational_latex(2)
    ('- \\frac{3}{4}', '2')
    """
    x = Fraction(x)
    return sympy.latex(sympy.Rational(x.numerator, x.denominator))


def json_number(value):
    """A value for JSON: a float as it is; a Fraction as an integer, or a string such as ``"1/3"``.

    Parameters
    ----------
    value : float, int, Fraction or None

    Returns
    -------
    float, int, str or None

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.formatting.pieces import json_number
    >>> json_number(Fraction(6, 2)), json_number(Fraction(1, 3)), json_number(0.5)
    (3, '1/3', 0.5)
    """
    if isinstance(value, Fraction):
        return int(value) if value.denominator == 1 else str(value)
    return value


def float_text(value) -> str:
    """A number in a message: the shortest text that reads back as the same number.

    Python's ``repr`` of a float is its shortest round-trip text; a float
    with an integer value drops its ``.0``, and a large one with trailing
    zeros is written in scientific form when that is shorter.  A float32
    (from an engine's arrays) is written as the shortest text that reads
    back as that float32.  Exact numbers (int, Fraction) are written in
    full.  Only the printing is shortened: ``float(float_text(x)) == x``
    for every finite float ``x``.

    Parameters
    ----------
    value : float, numpy floating, int or Fraction

    Returns
    -------
    str

    Examples
    --------
    >>> import numpy as np
    >>> from fractions import Fraction
    >>> from pitheorem.formatting.pieces import float_text
    >>> float_text(0.004), float_text(200.0), float_text(1e10), float_text(199.99999999999994)
    ('0.004', '200', '1e+10', '199.99999999999994')
    >>> float_text(np.float32(0.004)), float_text(np.float64(-2.5e-7)), float_text(Fraction(1, 3))
    ('0.004', '-2.5e-07', '1/3')
    """
    if isinstance(value, (int, Fraction)) and not isinstance(value, bool):
        return str(value)
    dtype = getattr(value, "dtype", None)
    if dtype is not None and dtype.kind == "f" and dtype.itemsize < 8:
        import numpy as np

        # the fewest digits that read back as this float32 (or float16), then written as Python writes them
        value = float(np.format_float_scientific(value, unique=True))
    text = repr(float(value))
    if text.endswith(".0"):
        text = text[:-2]
        if len(text.lstrip("-")) > 6:  # 10000000000 -> 1e+10: the shortest scientific form that reads back
            digits = len(text.lstrip("-").rstrip("0"))
            scientific = f"{float(value):.{max(digits - 1, 0)}e}"
            text = scientific if len(scientific) < len(text) else text
    return text


def value_text(value) -> str:
    """A value in a text table: a float to six digits, an exact number in full, nothing for None.

    Parameters
    ----------
    value : float, Fraction or None

    Returns
    -------
    str

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.formatting.pieces import value_text
    >>> value_text(2 / 3), value_text(Fraction(2, 3)), value_text(None)
    ('0.666667', '2/3', '')
    """
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


#: how many of a parameter's numbers a table cell shows before it says how many there are
VALUES_SHOWN = 6


def values_text(values) -> str:
    """A parameter's numbers in a table cell: all of a short one, the first few and the count of a long one.

    A mesh's or a skin's vertex list holds tens of thousands of numbers; a
    table that printed them all would make every row as wide (JSON keeps
    every number).

    Parameters
    ----------
    values : sequence of float or Fraction

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import values_text
    >>> values_text((0.5, 1.0, 2.0))
    '0.5 1 2'
    >>> values_text([0.25] * 9000)
    '0.25 0.25 0.25 0.25 0.25 0.25 ... (9000 numbers)'
    """
    values = tuple(values)
    if len(values) <= VALUES_SHOWN + 1:  # "... (7 numbers)" would be no shorter than the seventh number
        return " ".join(map(value_text, values))
    return " ".join(map(value_text, values[:VALUES_SHOWN])) + f" ... ({len(values)} numbers)"


# -- LaTeX -----------------------------------------------------------------------------------

_LATEX_SPECIAL = {
    "\\": r"\textbackslash{}",
    "{": r"\{",
    "}": r"\}",
    "_": r"\_",
    "^": r"\^{}",
    "#": r"\#",
    "$": r"\$",
    "%": r"\%",
    "&": r"\&",
    "~": r"\textasciitilde{}",
}


def latex_name(name: str) -> str:
    r"""A variable's name as LaTeX math, as sympy writes its symbol: ``k_theta`` is ``k_{\theta}``.

    Parameters
    ----------
    name : str

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import latex_name
    >>> latex_name("k_theta"), latex_name("g")
    ('k_{\\theta}', 'g')
    """
    return sympy.latex(sympy.Symbol(name))


def base_latex(name: str) -> str:
    r"""A base dimension as LaTeX math: ``\mathsf{L}``, and ``\Theta`` for temperature.

    Parameters
    ----------
    name : str

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import base_latex
    >>> base_latex("L"), base_latex("Theta")
    ('\\mathsf{L}', '\\Theta')
    """
    return r"\Theta" if name == "Theta" else rf"\mathsf{{{name}}}"


def group_name_latex(group) -> str:
    r"""A Pi group's name as LaTeX math: ``\Pi_{g}``, or ``\Pi`` for a group tied to no variable.

    Parameters
    ----------
    group : PiGroup

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem import PiGroup
    >>> from pitheorem.formatting.pieces import group_name_latex
    >>> group_name_latex(PiGroup({"k_theta": 1}, "k_theta")), group_name_latex(PiGroup({"t": 1}))
    ('\\Pi_{k_{\\theta}}', '\\Pi')
    """
    return rf"\Pi_{{{latex_name(group.variable)}}}" if group.variable else r"\Pi"


def latex_escape(text: str) -> str:
    r"""Text for LaTeX's text mode: the special characters escaped.

    Parameters
    ----------
    text : str

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import latex_escape
    >>> print(latex_escape("k_theta: 50% & more"))
    k\_theta: 50\% \& more
    """
    return "".join(_LATEX_SPECIAL.get(c, c) for c in text)


# -- a search's request and notes ------------------------------------------------------------


def request_text(result) -> str:
    """What a search asked, in words: ``g by s, l by 1/s with t fixed``.

    Parameters
    ----------
    result : SearchResult

    Returns
    -------
    str

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.pieces import request_text
    >>> request_text(pt.search(pt.System({"l": "L", "g": "L T^-2", "t": "T"}), scale={"g": 1}))
    'g by s with t fixed'
    """
    # a long list (an engine file's every time constant) keeps the first name: the line stays short, and the
    # note under it names them all
    shown = 1 if len(result.fixed) > 3 else 3
    return scale_text(result) + (f" with {names_text(result.fixed, shown=shown)} fixed" if result.fixed else "")


def scale_text(result) -> str:
    """What a search prescribed, in words: ``g by s, l by 1/s``.

    Parameters
    ----------
    result : SearchResult

    Returns
    -------
    str

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.pieces import scale_text
    >>> scale_text(pt.search(pt.System({"l": "L", "g": "L T^-2"}), scale={"g": 1, "l": "1/2"}))
    'g by s, l by s^(1/2)'
    """
    return ", ".join(f"{n} by {power_text(p)}" for n, p in result.scale.items())


def names_text(names, *, code=str, shown: int = NAMES_SHOWN, in_all: bool = True) -> str:
    """Names for a sentence: all of a few, or the first few and how many more.

    Parameters
    ----------
    names : sequence of str
    code : callable, optional
        Marks up each name (HTML wraps them in ``<code>``; ``repr`` quotes them).
    shown : int, optional
        How many names a long list keeps (default :data:`NAMES_SHOWN`).
    in_all : bool, optional
        Say how many there are in all (default True; False where the sentence
        says it already).

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import names_text
    >>> names_text(["t", "dt"])
    't, dt'
    >>> names_text([f"x{k}" for k in range(10)], shown=3)
    'x0, x1, x2 and 7 more (10 in all)'
    >>> names_text([f"x{k}" for k in range(10)], code=repr, shown=3, in_all=False)
    "'x0', 'x1', 'x2' and 7 more"
    """
    names = list(names)
    if len(names) <= shown + 1:
        return ", ".join(map(code, names))
    more = f"{', '.join(map(code, names[:shown]))} and {len(names) - shown} more"
    return f"{more} ({len(names)} in all)" if in_all else more


def default_text(default: float) -> str:
    """An engine constant's default in words: ``default 0.002``, or ``no documented default`` for NaN.

    Examples
    --------
    >>> from pitheorem.formatting.pieces import default_text
    >>> default_text(0.002), default_text(float("nan"))
    ('default 0.002', 'no documented default')
    """
    return "no documented default" if default != default else f"default {float_text(default)}"  # NaN != NaN


def solutions_text(n: int) -> str:
    """``1 minimal solution``, ``3 minimal solutions``.

    Examples
    --------
    >>> from pitheorem.formatting.pieces import solutions_text
    >>> solutions_text(1), solutions_text(3)
    ('1 minimal solution', '3 minimal solutions')
    """
    return f"{n} minimal solution{'' if n == 1 else 's'}"


def unit_change_text(scaling) -> str:
    """The change of units behind a scaling, in words: ``L by s, M by s^3`` (``T`` unchanged is left out).

    Parameters
    ----------
    scaling : Scaling

    Returns
    -------
    str
        ``"no change of units"`` for the identity, ``"no change of units
        gives it"`` for a symmetry of equations beyond changes of units.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.pieces import unit_change_text
    >>> unit_change_text(pt.Scaling.from_unit_change(pt.System({"l": "L", "m": "M", "t": "T"}), {"L": 1, "M": 3}))
    'units of M by s^3, L by s'
    """
    if not scaling.is_unit_change:
        return "no change of units gives it"
    parts = [f"{b} by {power_text(u)}" for b, u in scaling.unit_change.items() if u]
    return f"units of {', '.join(parts)}" if parts else "no change of units"


def changed_rows(answer):
    """An engine apply's changed parameters: name, exponent, dimension's text, values, scaled values.

    Parameters
    ----------
    answer : EngineApplyAnswer

    Returns
    -------
    list of (str, Fraction, str, tuple, tuple)
        Blank dimension and values where the answer holds none.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from fractions import Fraction
    >>> from pitheorem.answers import EngineApplyAnswer
    >>> from pitheorem.formatting.pieces import changed_rows
    >>> sc = pt.Scaling.from_unit_change(pt.System({"l": "L"}), {"L": 1})
    >>> changed_rows(EngineApplyAnswer("a.xml", Fraction(2), sc, (("l", Fraction(1)),), 1, None, (),
    ...                                (("L", (0.5,), (1.0,)),)))
    [('l', Fraction(1, 1), 'L', (0.5,), (1.0,))]
    """
    details = answer.details or tuple(("", (), ()) for _ in answer.changed)
    return [(name, p, *detail) for (name, p), detail in zip(answer.changed, details, strict=True)]


def changed_by_kind(rows):
    """Changed parameters grouped by dimension: the one-screen summary of an engine model's scaling.

    Parameters
    ----------
    rows : iterable of (str, Fraction, str)
        Each changed parameter's name, its exponent of ``s`` and its
        dimension's text.

    Returns
    -------
    list of (str, Fraction, list of str)
        Each dimension, its exponent and its parameters, in order of first
        appearance.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from pitheorem.formatting.pieces import changed_by_kind
    >>> changed_by_kind([("a", Fraction(1), "L"), ("m", Fraction(3), "M"), ("b", Fraction(1), "L")])
    [('L', Fraction(1, 1), ['a', 'b']), ('M', Fraction(3, 1), ['m'])]
    """
    kinds: dict = {}
    for name, exponent, dimension in rows:
        kinds.setdefault((dimension, exponent), []).append(name)
    return [(dimension, exponent, names) for (dimension, exponent), names in kinds.items()]


def note_text(note, *, time_remedy: str = PYTHON_TIME_REMEDY, code=str) -> str:
    """One sentence for a search note, in a front end's own terms.

    Parameters
    ----------
    note : SearchNote
        The note, with its ``kind`` and ``variables``.
    time_remedy : str, optional
        How this front end lets time change, closing a ``"time_fixed"``
        note (default: the Python call's ``fixed=()``).
    code : callable, optional
        Marks up each variable name (default: plain text; HTML wraps them
        in ``<code>``).

    Returns
    -------
    str

    Raises
    ------
    InvalidRequestError
        For a kind of note this function does not know.

    Examples
    --------
    >>> from pitheorem.formatting.pieces import COMMAND_LINE_TIME_REMEDY, note_text
    >>> from pitheorem.scalesearch import SearchNote
    >>> note = SearchNote("time_fixed", ("t", "dt"))
    >>> note_text(note)
    'Time variables t, dt are held fixed by default; pass fixed=() to let time change'
    >>> note_text(note, time_remedy=COMMAND_LINE_TIME_REMEDY)
    'Time variables t, dt are held fixed by default; give --fixed with no names to let time change'
    >>> note_text(SearchNote("outside_equations", ("m",)))
    'Variable m does not appear in the equations and is held fixed'
    """
    names = names_text(note.variables, code=code)
    one = len(note.variables) == 1
    if note.kind == "time_fixed":
        subject = f"Time variable {names} is" if one else f"Time variables {names} are"
        return f"{subject} held fixed by default; {time_remedy}"
    if note.kind == "outside_equations":
        verb = "does not appear in the equations and is" if one else "do not appear in the equations and are"
        return f"{'Variable' if one else 'Variables'} {names} {verb} held fixed"
    raise InvalidRequestError(f"unknown note kind {note.kind!r}; the kinds are time_fixed, outside_equations")


def search_cells(result, power):
    """The cells of a search's table, each power of ``s`` written by `power`: variables, then base units.

    Parameters
    ----------
    result : SearchResult
    power : callable
        Writes one exponent (:func:`power_text`, :func:`power_latex`, ...).

    Returns
    -------
    rows : list of (str, str, list of str)
        Each variable, its role (:attr:`pitheorem.SearchResult.roles`) and its power
        in each minimal scaling.
    base_rows : list of (str, list)
        Each base dimension and the power of its unit behind each scaling:
        None for a symmetry of equations that no change of units gives.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.pieces import power_text, search_cells
    >>> rows, base = search_cells(pt.search(pt.System({"l": "L", "t": "T"}), scale={"l": 1}), power_text)
    >>> rows, base
    ([('l', 'scale', ['s']), ('t', 'fixed', ['-'])], [('L', ['s']), ('T', ['-'])])
    """
    scalings = result.scalings
    columns = [sc.exponents for sc in scalings]
    rows = [(n, role, [power(c[n]) for c in columns]) for n, role in result.roles.items()]
    changes = [sc.unit_change if sc.is_unit_change else None for sc in scalings]
    base_rows = [(b, [None if u is None else power(u[b]) for u in changes]) for b in result.system.base_dimensions]
    return rows, base_rows


def which_scaling(result, solution: int) -> str:
    """Which of a search's minimal scalings the command line's ``apply`` used, in words.

    Parameters
    ----------
    result : SearchResult
    solution : int
        Its number, from 1.

    Returns
    -------
    str

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.pieces import which_scaling
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k": "M L^2 T^-2", "t": "T"})
    >>> which_scaling(pt.search(rod, scale={"g": 1}), 2)
    'minimal scaling #2 of 2 (choose another with --solution K)'
    """
    if result.n_scalings == 1:
        return "the only minimal scaling"
    return f"minimal scaling #{solution} of {result.n_scalings} (choose another with --solution K)"


# -- the rows of reports ---------------------------------------------------------------------


def deviation_rows(report, name):
    """The header and rows of a similarity report's table: each state, its deviation and sensitivity.

    Parameters
    ----------
    report : SimilarityReport
    name : callable
        Writes a state's name in the format.

    Returns
    -------
    tuple of (list of str, list of list of str)

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.pieces import deviation_rows
    >>> rod = pt.models.hinged_rod()
    >>> sc = pt.search(rod.system, scale={"g": 1}, fixed=()).scalings[0]
    >>> report = pt.verify_similarity(rod, sc, s=2, t_final=0.5)
    >>> header, rows = deviation_rows(report, str)
    >>> header, [row[0] for row in rows]
    (['state', 'max deviation'], ['theta', 'omega'])
    >>> deviation_rows(pt.verify_similarity(rod, sc, s=2, t_final=0.5, baseline=True), str)[0]
    ['state', 'max deviation', 'one-ulp sensitivity']
    """
    sensitivity = report.sensitivity
    header = ["state", "max deviation"] + (["one-ulp sensitivity"] if sensitivity is not None else [])
    rows = [
        [name(n), f"{d:.3g}", *([f"{sensitivity[n]:.3g}"] if sensitivity is not None else [])]
        for n, d in report.deviation.items()
    ]
    return header, rows


def strength_lines(report) -> list[str]:
    """What a report says of its own strength: the scale-free proof, inconclusive, weak, gravity unseen, the horizon.

    Empty for a report without twins, controls or a scale-free run (an
    ODE verdict against a tolerance).

    Parameters
    ----------
    report : SimilarityReport

    Returns
    -------
    list of str

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.formatting.pieces import strength_lines
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    >>> rep = engines.verify(model, sc, s=10, duration=0.5, controls=lambda t: [0.1])
    >>> strength_lines(rep)
    ['strength: an error of 0.0001 in gravity or the masses is caught; the twins stay together to the end (t = 0.5)']
    """
    free = report.scale_free
    reset = getattr(report, "engine_reset", None)
    if report.horizon is None and not report.controls and free is None and reset is None:
        return []
    lines = [] if free is None else [free.text()]
    if reset is not None:
        when, whose = reset
        lines.append(
            f"{'INCONCLUSIVE: ' if whose == 'original' else ''}the engine gave up on the {whose}'s run at "
            f"t = {float_text(when)} (MuJoCo warned of a bad number: it resets a run whose acceleration or "
            "velocity is NaN, infinite or huge, and a batch stops at a control beyond 1e10; MJX and MuJoCo Warp "
            f"go on in NaN){'; the runs are compared before it' if whose == 'original' else ''}"
        )
    # a group is hidden where its controls left the rule's bound but not the right copy's own deviation (the
    # engine parts the copy on its own): that says nothing of whether the group acts, only that this run's noise
    # covers it; the others passed within the bound itself
    hidden = [g for g in report.unseen if any(c.hidden for c in report.controls if c.group == g)]
    unseen = [g for g in report.unseen if g not in hidden]
    words = {"g": "gravity", "masses": "the masses"}
    if hidden and report.passed:
        # only beside a copy within the yardstick: a copy beyond it is not similar, a verdict the controls cannot
        # weaken (they are that wrong copy, wrong once more, so no nearer the original than it is)
        # 10: pitheorem.engines.verdicts.strength.COPY_MARGIN (the engines lie above this layer; a test holds the two)
        what = " or ".join(words.get(g, g) for g in hidden)
        lines.append(
            f"INCONCLUSIVE: not even {what} doubled move{'s' if len(hidden) == 1 else ''} this run 10 times "
            "further from the original than the copy itself (rounding the engine parts the runs by, or chaos), "
            f"so it cannot tell an error in {'that' if len(hidden) == 1 else 'them'} from the copy's own deviation"
        )
    if unseen:
        what = " or ".join(words.get(g, g) for g in unseen)
        lines.append(
            f"INCONCLUSIVE: not even {what} doubled change{'s' if len(unseen) == 1 else ''} this run beyond "
            f"its yardstick, so it cannot show an error in {'that' if len(unseen) == 1 else 'them'}"
        )
    if "g" in unseen:
        # not "gravity cannot act": a yardstick widened by the run's own sensitivity (a contact at the edge, chaos)
        # hides gravity acting in full (robosuite's Sawyer at s = 10: gravity off moves it by 14.6, within it)
        lines.append(
            "either gravity barely acts on this run's motion (compensated, balanced or planar) or the run's own "
            "sensitivity, its yardstick, is wider than gravity's effect: a gravity error cannot be seen"
        )
    parts = []
    if report.detection_limit is not None:
        # the groups whose controls ran: a model without gravity (spot in robosuite) has no gravity control
        ran = " or ".join(words.get(g, g) for g in dict.fromkeys(c.group for c in report.controls))
        parts.append(f"an error of {float_text(report.detection_limit)} in {ran or 'gravity or the masses'} is caught")
    end = float(report.original.t[-1]) if len(report.original) else 0.0
    if report.horizon is not None:
        if report.horizon < end:
            parts.append(
                f"the twins part by 1% of the motion at t = {report.horizon:.6g} of {end:.6g}: "
                "past it the comparison says little"
            )
        else:
            parts.append(f"the twins stay together to the end (t = {end:.6g})")
    if parts:
        lines.append("strength: " + "; ".join(parts))
    if report.passed and report.detection_limit is not None and report.detection_limit > 1e-2:
        lines.append(
            f"weak evidence: an error smaller than {float_text(report.detection_limit)} in a dimensionless "
            "group would pass unnoticed"
        )
    return lines


def unit_fit_rows(fit):
    """Each variable of a unit fit that has a value: its name, value, new value, range and verdict.

    The range is ``(low, high)`` as floats and the verdict ``True`` when
    the new value lies in it; both are ``None`` for a variable without a
    range.

    Parameters
    ----------
    fit : UnitFit

    Returns
    -------
    list of tuple

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.pieces import unit_fit_rows
    >>> fit = pt.fit_units(pt.System({"l": "L", "t": "T"}), {"l": 500, "t": 2}, ranges={"l": (1, 10)})
    >>> [(name, bounds, ok) for name, _, _, bounds, ok in unit_fit_rows(fit)]
    [('l', (1.0, 10.0), True), ('t', None, None)]
    """
    ranged = {n: (float(lo), float(hi)) for n, lo, hi in fit.ranges}
    return [
        (n, float(fit.values[n]), float(fit.scaled[n]), ranged.get(n), (n in fit.satisfied) if n in ranged else None)
        for n in fit.system.variables
        if n in fit.values
    ]


def range_cells(bounds, ok, out_of_range: str = "OUT OF RANGE") -> list[str]:
    """A unit fit's range and verdict as two cells, both empty for a variable without a range.

    Parameters
    ----------
    bounds : tuple of float or None
        ``(low, high)``, as :func:`unit_fit_rows` gives it.
    ok : bool or None
        Whether the new value lies in the range.
    out_of_range : str, optional
        The verdict's words when it does not (HTML makes them bold).

    Returns
    -------
    list of str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import range_cells
    >>> range_cells((1.0, 10.0), True), range_cells((1.0, 10.0), False), range_cells(None, None)
    (['[1, 10]', 'ok'], ['[1, 10]', 'OUT OF RANGE'], ['', ''])
    """
    if bounds is None:
        return ["", ""]
    return [f"[{float_text(bounds[0])}, {float_text(bounds[1])}]", "ok" if ok else out_of_range]


def parameters_head(name: str, model) -> str:
    """The line above an engine model's parameter table.

    Parameters
    ----------
    name : str
        The model's file, or how the command line named it.
    model : EngineModel

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.formatting.pieces import parameters_head
    >>> model = engines.load(engines.example_path("pendulum.xml"))
    >>> parameters_head("pendulum.xml", model)
    'pendulum.xml: mujoco model, 49 parameters (source: 11 file, 35 default, 3 derived)'
    """
    if not hasattr(model, "parameters"):  # a TOML model file: its variables are its parameters
        return f"{name}: model file, {len(model.system)} variables"
    # a summary above a table that may run to hundreds of rows: how many of each source
    sources = [p.source for p in model.parameters]
    order = ("file", "default", "derived", "engine")  # the file's own numbers first
    kinds = [s for s in order if s in sources] + sorted(set(sources) - set(order))
    by_source = ", ".join(f"{sources.count(s)} {s}" for s in kinds)
    return f"{name}: {model.engine} model, {len(model.parameters)} parameters (source: {by_source})"


def parameter_rows(model):
    """The rows of a parameter table: an engine model's parameters, or a model file's variables.

    Parameters
    ----------
    model : EngineModel or ModelFile

    Returns
    -------
    list of (str, Dimension or None, str, tuple, str, str)
        Each parameter's name, dimension (None for a mixed number), the
        dimension's text, its values, its source and its path: for a model
        file's variable, its value (if any), its role and its description.

    Examples
    --------
    >>> from pitheorem.modelfile import example_path, load_model_file
    >>> from pitheorem.formatting.pieces import parameter_rows
    >>> parameter_rows(load_model_file(example_path("hinged_rod")))[0][2:]
    ('M', (1.5,), 'parameter', 'mass of the rod')
    """
    if hasattr(model, "parameters"):
        return [(p.name, p.dimension, p.dimension_text, p.value, p.source, p.path) for p in model.parameters]
    dims = model.system.dimensions
    return [
        (
            n,
            dims[n],
            str(dims[n]),
            (model.values[n],) if n in model.values else (),
            model.roles.get(n, ""),
            model.descriptions.get(n, ""),
        )
        for n in model.system.variables
    ]


# -- plain-text columns ----------------------------------------------------------------------


def align(rows) -> str:
    """Rows of cells as left-aligned columns two spaces apart, without trailing spaces.

    Parameters
    ----------
    rows : sequence of sequence of str
        The first row is usually the header; every row has as many cells.

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import align
    >>> print(align([["name", "value"], ["g", "9.81"], ["k_theta", "100"]]))
    name     value
    g        9.81
    k_theta  100
    """
    widths = [max(len(r[c]) for r in rows) for c in range(len(rows[0]))]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(r, widths, strict=True)).rstrip() for r in rows)


# -- sweeps ----------------------------------------------------------------------------------

#: the columns of a sweep's table
SWEEP_HEADER = ("s", "verdict", "deviation", "yardstick", "thresholds crossed")


def _short(value) -> str:
    """A deviation or yardstick in a cell: three digits, an exact zero as 0, nothing for None."""
    if value is None:
        return ""
    return "0" if value == 0 else f"{value:.3g}"


def file_name(path: str) -> str:
    """The last part of a file's path, as a table or a title shows it ("" for "").

    Parameters
    ----------
    path : str

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.pieces import file_name
    >>> file_name("robots/hopper.xml"), file_name("C:\\\\robots\\\\ant.xml"), file_name("")
    ('hopper.xml', 'ant.xml', '')
    """
    return path.replace("\\", "/").rsplit("/", 1)[-1]


def sweep_head(sweep) -> str:
    """A sweep's first line: the model, its engine, the scaling, the run's length and the number of rows.

    Parameters
    ----------
    sweep : Sweep

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.engines import Sweep
    >>> from pitheorem.formatting.pieces import sweep_head
    >>> sweep_head(Sweep("robots/hopper.xml", "mujoco", None, 0.5, ()))
    'hopper.xml in mujoco: 0 scale factors, 0.5 s each'
    """
    name = file_name(sweep.model) or "(unsaved model)"
    scaling = "" if sweep.scaling is None else f", {unit_change_text(sweep.scaling)}"
    time_unit = dict(sweep.units).get("T", "s")
    return f"{name} in {sweep.engine}{scaling}: {len(sweep.rows)} scale factors, {sweep.duration:g} {time_unit} each"


def sweep_cells(row) -> list[str]:
    """One row of a sweep's table as text cells, in the order of :data:`SWEEP_HEADER`.

    Parameters
    ----------
    row : SweepRow

    Returns
    -------
    list of str

    Examples
    --------
    >>> from pitheorem.engines import SweepRow
    >>> from pitheorem.formatting.pieces import sweep_cells
    >>> sweep_cells(SweepRow(0.001, "similar", 2.5e-9, 1.25e-10, None, True, None, (), ("mujoco_minmu",)))
    ['0.001', 'similar', '2.5e-09', '1.25e-10', 'mujoco_minmu']
    """
    return [
        value_text(row.s),
        row.verdict,
        _short(row.max_deviation),
        _short(row.yardstick),
        ", ".join(row.thresholds),
    ]


def sweep_fit_text(sweep) -> str:
    """What :func:`pitheorem.fit_units` chooses for the sweep's engine, and where the sweep meets it ("" if not asked).

    Parameters
    ----------
    sweep : Sweep

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.engines import Sweep
    >>> from pitheorem.formatting.pieces import sweep_fit_text
    >>> sweep_fit_text(Sweep("", "mujoco", None, 1.0, (), fitted_units={"M": "g", "L": "mm", "T": "s"}, fitted_s=1e-3))
    'fit_units chooses M = g, L = mm, T = s for mujoco: this scaling reaches them at s = 0.001'
    """
    if sweep.fitted_units is None:
        return ""
    units = ", ".join(f"{b} = {u}" for b, u in sweep.fitted_units.items())
    where = (
        "this scaling moves none of their base units"
        if sweep.fitted_s is None
        else f"this scaling reaches them at s = {sweep.fitted_s:.3g}"
    )
    return f"fit_units chooses {units} for {sweep.engine}: {where}"


def sweep_grid(answer) -> list[list[str]]:
    """Several sweeps as one table of robots by scale: a header row of ``s``, then a row of verdicts per file.

    The ``s`` of every sweep in the order of the first file's rows (the command line sweeps every file
    at the same ``s``).

    Parameters
    ----------
    answer : SweepAnswer

    Returns
    -------
    list of list of str

    Examples
    --------
    >>> from pitheorem.answers import SweepAnswer
    >>> from pitheorem.engines import Sweep, SweepRow
    >>> from pitheorem.formatting.pieces import sweep_grid
    >>> rows = (SweepRow(0.5, "similar", 1e-14, 1e-12, None, True, None, (), ()),)
    >>> sweep_grid(SweepAnswer(("a.xml",), (Sweep("a.xml", "mujoco", None, 1.0, rows),), ()))
    [['robot', '0.5'], ['a.xml', 'similar']]
    """
    first = answer.sweeps[0].rows if answer.sweeps else ()
    grid = [["robot", *(value_text(r.s) for r in first)]]
    grid += [
        [file_name(name), *(r.verdict for r in sw.rows)] for name, sw in zip(answer.model, answer.sweeps, strict=True)
    ]
    return grid
