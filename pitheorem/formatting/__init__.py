"""Display and export: every value as text, LaTeX, HTML or JSON, from one home.

``format(x, spec)`` (and ``f"{x:spec}"``) renders any value pitheorem shows
a user in one of :data:`FORMATS`; ``str(x)`` is ``format(x, "text")``, and
the notebook hooks (``_repr_latex_``, ``_repr_html_``) and the command
line's ``--format`` go through the same renderers.  The value types wear
one of three mixins of this module and write no text themselves:

* :class:`TextDisplay`: ``__str__`` and ``__format__``;
* :class:`MathDisplay`: also ``_repr_latex_``, ``$\\displaystyle ...$``
  (a dimension, a Pi group, a scaling);
* :class:`TableDisplay`: also ``_repr_html_``, an HTML table whose math is
  written ``$...$`` (a search result, a unit fit).  A math object has no
  ``_repr_html_``: Jupyter and myst-nb would show it instead of its LaTeX.

The formats, one module each:

``"text"`` (:mod:`pitheorem.formatting.text`)
    Plain text, as ``print`` shows it: aligned columns, ``s^2``.
``"latex"`` (:mod:`pitheorem.formatting.latex`)
    LaTeX source to paste into a document: math-mode for a math object
    (``\\Pi_{g} = \\frac{g l m}{k_{\\theta}}``; put it between ``$``), text
    mode with a ``tabular`` for a table or a report.
``"html"`` (:mod:`pitheorem.formatting.html`)
    An HTML fragment; math between ``$`` for MathJax.
``"json"`` (:mod:`pitheorem.formatting.json`)
    A JSON document for programs: keys in a fixed order, integers as
    integers, exact rationals as strings such as ``"1/2"``.

The pieces the formats share (powers of ``s``, exact numbers, how a search
note is phrased, aligned columns) live in :mod:`pitheorem.formatting.pieces`.

Extending it: a new output format is one new module beside these, with a
``RENDERERS`` dict, and its name in :data:`FORMATS`; a new value type is
one renderer in each format module's ``RENDERERS``, keyed by the type's
qualified name (``"pitheorem.scaling.Scaling"``), and one of the mixins
on the type.  ``tests/test_formatting.py`` renders every value type in
every format and fails for a type that builds its own text.

A format module is imported on first use, and none imports a value type's
module: renderers are looked up by the names along the value's class
hierarchy, so ``import pitheorem`` loads nothing here but this file.
"""

from __future__ import annotations

from importlib import import_module

from ..errors import InvalidRequestError

__all__ = ["FORMATS", "MathDisplay", "TableDisplay", "TextDisplay", "render"]

#: the format specs: ``format(x, spec)`` with one of these ("" means "text")
FORMATS = ("text", "latex", "html", "json")


def render(value, spec: str = "text") -> str:
    """Render a value in one of the formats.

    Parameters
    ----------
    value : object
        A value pitheorem displays (a :class:`~pitheorem.Dimension`, a
        :class:`~pitheorem.SearchResult`, a report, ...).
    spec : str
        One of :data:`FORMATS`; ``""`` means ``"text"``.

    Returns
    -------
    str

    Raises
    ------
    InvalidRequestError
        For a spec that is no format, naming it and the formats.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting import render
    >>> dim = pt.Dimension.parse("L T^-2")
    >>> render(dim), render(dim, "latex")
    ('L T^-2', '\\\\mathsf{L}\\\\,\\\\mathsf{T}^{-2}')
    >>> try:
    ...     render(dim, "yaml")
    ... except pt.InvalidRequestError as err:
    ...     print(err)
    unknown format 'yaml'; the formats are text, latex, html, json ('' is text)
    """
    name = spec or "text"
    if name not in FORMATS:
        raise InvalidRequestError(
            f"unknown format {spec!r}; the formats are {', '.join(FORMATS)} ('' is text)", culprit=spec
        )
    renderers = import_module(f"{__name__}.{name}").RENDERERS
    for cls in type(value).__mro__:
        renderer = renderers.get(f"{cls.__module__}.{cls.__qualname__}")
        if renderer is not None:
            return renderer(value)
    raise InvalidRequestError(f"no {name} display for a {type(value).__name__}", culprit=type(value).__name__)


class TextDisplay:
    """Mixin of a displayed value: ``str`` and ``format`` through :func:`render`.

    Examples
    --------
    >>> import pitheorem as pt
    >>> note = pt.SearchNote("outside_equations", ("m",))
    >>> str(note) == format(note, "") == format(note, "text")
    True
    >>> format(note, "json").splitlines()[1]
    '  "kind": "outside_equations",'
    """

    __slots__ = ()

    def __str__(self) -> str:
        return render(self, "text")

    def __format__(self, spec: str) -> str:
        return render(self, spec)


class MathDisplay(TextDisplay):
    r"""Mixin of a math object: Jupyter shows it as ``$\displaystyle ...$``, its LaTeX.

    Examples
    --------
    >>> import pitheorem as pt
    >>> pt.Dimension.parse("M L")._repr_latex_()
    '$\\displaystyle \\mathsf{M}\\,\\mathsf{L}$'
    """

    __slots__ = ()

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {render(self, 'latex')}$"


class TableDisplay(TextDisplay):
    """Mixin of a table: Jupyter shows its HTML, with math between ``$``.

    Examples
    --------
    >>> import pitheorem as pt
    >>> res = pt.search(pt.System({"l": "L", "g": "L T^-2", "t": "T"}), scale={"g": 1})
    >>> res._repr_html_().count("<table")
    1
    """

    __slots__ = ()

    def _repr_html_(self) -> str:
        return render(self, "html")
