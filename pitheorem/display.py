"""Shared text and LaTeX rendering: powers of the scale factor ``s``, and search notes.

A search's notes (:class:`pitheorem.scalesearch.SearchNote`) are data; this
module phrases them, and each front end says in its own terms how to lift
an assumption (Python: ``fixed=()``; the command line: ``--fixed``).
"""

from __future__ import annotations

from fractions import Fraction

from .errors import InvalidRequestError

__all__ = ["PYTHON_TIME_REMEDY", "note_text", "power_latex", "power_text"]

#: how the Python front end says to let time change (the command line says it with --fixed)
PYTHON_TIME_REMEDY = "pass fixed=() to let time change"


def power_text(exponent) -> str:
    """Plain-text power of s: ``-`` for unchanged, ``s``, ``s^2``, ``1/s``, ``s^(1/2)``.

    Examples
    --------
    >>> from pitheorem.display import power_text
    >>> [power_text(p) for p in (0, 1, 2, -1, -3, 0.5)]
    ['-', 's', 's^2', '1/s', '1/s^3', 's^(1/2)']
    """
    p = Fraction(exponent).limit_denominator() if isinstance(exponent, float) else Fraction(exponent)
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
    r"""LaTeX power of s: ``1`` for unchanged, ``s^{2}``, ``s^{-1/2}`` ...

    Examples
    --------
    >>> from pitheorem.display import power_latex
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
        Marks up each variable name (default: plain text; the HTML display
        wraps them in ``<code>``).

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.display import note_text
    >>> from pitheorem.scalesearch import SearchNote
    >>> note = SearchNote("time_fixed", ("t", "dt"))
    >>> note_text(note)
    'time variables t, dt are held fixed by default; pass fixed=() to let time change'
    >>> note_text(note, time_remedy="give --fixed with no names to let time change")
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
