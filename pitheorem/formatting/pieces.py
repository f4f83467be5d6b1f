r"""The pieces every format shares, each written once.

* powers of the scale factor ``s``: :func:`power_text` (``s^2``, ``1/s``)
  and :func:`power_latex` (``s^{2}``, ``s^{-1}``);
* exact numbers: :func:`rational_text` for an exponent, :func:`json_number`
  and :func:`value_text` for a value (a float, or an exact Fraction);
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
    "PYTHON_TIME_REMEDY",
    "align",
    "base_latex",
    "deviation_rows",
    "group_name_latex",
    "json_number",
    "latex_escape",
    "latex_name",
    "note_text",
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
    "unit_fit_rows",
    "value_text",
    "which_scaling",
]

#: how the Python front end says to let time change, closing a "time_fixed" note
PYTHON_TIME_REMEDY = "pass fixed=() to let time change"
#: how the command line says it
COMMAND_LINE_TIME_REMEDY = "give --fixed with no names to let time change"


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
    """Plain-text power of s: ``-`` for unchanged, ``s``, ``s^2``, ``1/s``, ``s^(1/2)``.

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
        return "-"
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


# -- LaTeX -----------------------------------------------------------------------------------

_LATEX_SPECIAL = {"\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "_": r"\_", "^": r"\^{}", "#": r"\#",
                  "$": r"\$", "%": r"\%", "&": r"\&", "~": r"\textasciitilde{}"}


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
    return scale_text(result) + (f" with {', '.join(result.fixed)} fixed" if result.fixed else "")


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
    'time variables t, dt are held fixed by default; pass fixed=() to let time change'
    >>> note_text(note, time_remedy=COMMAND_LINE_TIME_REMEDY)
    'time variables t, dt are held fixed by default; give --fixed with no names to let time change'
    >>> note_text(SearchNote("outside_equations", ("m",)))
    'variable m does not appear in the equations and is held fixed'
    """
    names = ", ".join(code(n) for n in note.variables)
    one = len(note.variables) == 1
    if note.kind == "time_fixed":
        subject = f"time variable {names} is" if one else f"time variables {names} are"
        return f"{subject} held fixed by default; {time_remedy}"
    if note.kind == "outside_equations":
        verb = "does not appear in the equations and is" if one else "do not appear in the equations and are"
        return f"{'variable' if one else 'variables'} {names} {verb} held fixed"
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
    rows = [[name(n), f"{d:.3g}", *([f"{sensitivity[n]:.3g}"] if sensitivity is not None else [])]
            for n, d in report.deviation.items()]
    return header, rows


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
    return [(n, float(fit.values[n]), float(fit.scaled[n]), ranged.get(n), (n in fit.satisfied) if n in ranged else None)
            for n in fit.system.variables if n in fit.values]


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
    return [f"[{bounds[0]:g}, {bounds[1]:g}]", "ok" if ok else out_of_range]


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
    'pendulum.xml: mujoco model, 49 parameters'
    """
    return f"{name}: {model.engine} model, {len(model.parameters)} parameters"


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
