"""HTML fragments: what ``format(x, "html")`` and a notebook's ``_repr_html_`` give.

Tables are ``<table>`` elements; their math (names, powers of ``s``,
dimensions, Pi groups) is LaTeX between ``$``, which Jupyter and the docs'
MathJax typeset.  Every other piece of text is escaped.  A math object (a
dimension, a Pi group, a scaling, a range bound) renders as its LaTeX
between ``$`` in a ``<span>``, though its notebook display is its LaTeX.
"""

from __future__ import annotations

from html import escape

import sympy

from . import render
from .pieces import (
    COMMAND_LINE_TIME_REMEDY,
    PYTHON_TIME_REMEDY,
    SWEEP_HEADER,
    UNCHANGED,
    base_latex,
    changed_rows,
    default_text,
    deviation_rows,
    group_name_latex,
    latex_name,
    note_text,
    parameter_rows,
    parameters_head,
    power_latex,
    range_cells,
    rational_latex,
    registry,
    search_cells,
    sweep_cells,
    sweep_fit_text,
    sweep_grid,
    sweep_head,
    unit_fit_rows,
    value_text,
    values_text,
)
from .text import explanation, symmetry_head, unit_fit_head

__all__ = ["RENDERERS"]

#: renderer of each value type, by qualified type name
RENDERERS: dict = {}
_renders = registry(RENDERERS)

_CELL = 'style="padding: 0.15em 0.9em; text-align: center"'


def _math(latex: str) -> str:
    return f"${escape(latex, quote=False)}$"


def _power_cell(exponent) -> str:
    """A power of s in a table cell; an unchanged entry shows the same mark as in plain text."""
    return _math(power_latex(exponent)) if exponent else UNCHANGED


def _code(text: str) -> str:
    return f"<code>{escape(text)}</code>"


def _p(inner: str) -> str:
    return f"<p>{inner}</p>"


def _row(cells, attributes: str = "") -> str:
    """One row: the first cell a row heading, the others data (each already HTML)."""
    first, *rest = cells
    return f"<tr{attributes}><th {_CELL}>{first}</th>" + "".join(f"<td {_CELL}>{cell}</td>" for cell in rest) + "</tr>"


def _table(header, rows, below=()) -> str:
    """A table: a header row, rows, and `below` (the change of base units) under a rule."""
    lines = [f"<tr>{''.join(f'<th {_CELL}>{cell}</th>' for cell in header)}</tr>", *map(_row, rows)]
    lines += [
        _row(cells, ' class="base-unit"' + (' style="border-top: 1px solid #999"' if k == 0 else ""))
        for k, cells in enumerate(below)
    ]
    return f'<table style="border-collapse: collapse">{"".join(lines)}</table>'


def _latex(value) -> str:
    return _math(render(value, "latex"))


def _span_of_latex(value) -> str:
    return f"<span>{_latex(value)}</span>"


# -- dimensions, groups, scalings ------------------------------------------------------------

for _name in (
    "pitheorem.dimensions.Dimension",
    "pitheorem.groups.PiGroup",
    "pitheorem.scaling.Scaling",
    "pitheorem.unitfit.RangeBound",
):
    _renders(_name)(_span_of_latex)


def _group_name(group) -> str:
    return _math(group_name_latex(group))


@_renders("pitheorem.groups.PiSet")
def _pi_set(groups) -> str:
    if not len(groups):
        return _span_of_latex(groups)
    return _table(["group", "expression"], [[_group_name(g), _math(g.latex)] for g in groups])


# -- search ----------------------------------------------------------------------------------


def _note(note, time_remedy: str = PYTHON_TIME_REMEDY) -> str:
    remedy = escape(time_remedy).replace("fixed=()", _code("fixed=()")).replace("--fixed", _code("--fixed"))
    return _p(note_text(note, time_remedy=remedy, code=_code))


_renders("pitheorem.scalesearch.SearchNote")(_note)


def _search_result(result, time_remedy: str = PYTHON_TIME_REMEDY) -> str:
    notes = "".join(_note(note, time_remedy) for note in result.notes)
    head = _p(escape(explanation(result))) + notes
    if not result.feasible:
        cert = result.certificate
        return head + _p(
            f"certificate: {_latex(cert)} (the request multiplies it by {_math(power_latex(result.certificate_power))})"
        )
    variables, base_units = search_cells(result, _power_cell)
    rows = [[_math(latex_name(n)), f"<em>{role}</em>", *cells] for n, role, cells in variables]
    below = [
        [_math(rf"[\mathrm{{{b}}}]"), "<em>base unit</em>", *(cell or "n/a" for cell in cells)]
        for b, cells in base_units
    ]
    header = ["variable", "role", *(f"#{k}" for k in range(1, result.n_scalings + 1))]
    return head + _table(header, rows, below)


_renders("pitheorem.scalesearch.SearchResult")(_search_result)


# -- equations -------------------------------------------------------------------------------


@_renders("pitheorem.equations.DimensionReport")
def _dimension_report(report) -> str:
    if report.consistent:
        return _p(f"consistent: dimension {_latex(report.dimension)}")
    rows = [[_math(sympy.latex(term)), _latex(got), _latex(want)] for term, got, want in report.offending]
    ties = "".join(_p(f"tie: {escape(tie)}") for tie in report.ties)
    return (
        _p(f"inconsistent: {len(report.offending)} offending term(s)")
        + _table(["term", "dimension", "expected"], rows)
        + ties
    )


@_renders("pitheorem.equations.SymmetryReport")
def _symmetry_report(report) -> str:
    head = "".join(_p(escape(line)) for line in symmetry_head(report))
    if not report.beyond_units:
        return head
    rows = [
        [f"#{k}", *(_math(rational_latex(vec.get(n, 0))) for n in report.variables)]
        for k, vec in enumerate(report.beyond_units, 1)
    ]
    return head + _table(["symmetry", *(_math(latex_name(n)) for n in report.variables)], rows)


# -- simulations -----------------------------------------------------------------------------


@_renders("pitheorem.simulation.SimilarityReport")
def _similarity_report(report) -> str:
    header, rows = deviation_rows(report, lambda n: _math(latex_name(n)))
    return _p(escape(render(report, "text"))) + _table(header, rows)


# -- unit fits -------------------------------------------------------------------------------


@_renders("pitheorem.unitfit.UnitFit")
def _unit_fit(fit) -> str:
    units = [[_math(base_latex(b)), f"{float(f):.6g}", f"{1 / float(f):.6g}"] for b, f in fit.factors.items()]
    rows = [
        [_math(latex_name(n)), f"{old:.6g}", f"{new:.6g}", *range_cells(bounds, ok, "<strong>OUT OF RANGE</strong>")]
        for n, old, new, bounds, ok in unit_fit_rows(fit)
    ]
    conflict = _p("conflicting bounds: " + "; ".join(map(_latex, fit.conflict))) if fit.conflict else ""
    return (
        _p(escape(unit_fit_head(fit)))
        + _table(["base", "readings times", "new unit (old units)"], units)
        + _table(["variable", "value", "new value", "range", ""], rows)
        + conflict
    )


# -- engines ---------------------------------------------------------------------------------


@_renders("pitheorem.engines.verdicts.causes.Cause")
def _cause(cause) -> str:
    return f"<span><strong>{escape(cause.kind)}</strong>: {_code(cause.element)}: {escape(cause.detail)}</span>"


@_renders("pitheorem.engines.verdicts.audit.Audit")
def _audit(audit) -> str:
    first = render(audit, "text").splitlines()[0]
    items = "".join(f"<li>{render(c, 'html')}</li>" for c in audit.causes)
    return _p(escape(first)) + (f"<ul>{items}</ul>" if items else "")


@_renders("pitheorem.engines.constants.HiddenConstant")
def _hidden_constant(constant) -> str:
    return f"<span>{_code(constant.name)} [{_latex(constant.dimension)}] ({default_text(constant.default)})</span>"


@_renders("pitheorem.engines.rules.RuleVerdict")
def _rule_verdict(verdict) -> str:
    first, *rest = render(verdict, "text").splitlines()
    return (
        _p(f"<strong>{escape(first)}</strong>")
        + "<ul>"
        + "".join(f"<li>{escape(line.strip())}</li>" for line in rest)
        + "</ul>"
    )


@_renders("pitheorem.engines.verdicts.sweep.SweepRow")
def _sweep_row(row) -> str:
    return f"<span>{escape(render(row, 'text'))}</span>"


@_renders("pitheorem.engines.verdicts.sweep.Sweep")
def _sweep(sweep) -> str:
    rows = [[escape(cell) for cell in sweep_cells(r)] for r in sweep.rows]
    header = [_math("s"), *SWEEP_HEADER[1:]]
    out = _p(escape(sweep_head(sweep))) + _table(header, rows)
    caused = [r for r in sweep.rows if r.causes]
    if caused:
        items = "".join(
            f"<li>s = {escape(value_text(r.s))}: " + "; ".join(render(c, "html") for c in r.causes) + "</li>"
            for r in caused
        )
        out += f"<ul>{items}</ul>"
    fit = sweep_fit_text(sweep)
    return out + (_p(escape(fit)) if fit else "")


def _parameters(name: str, model) -> str:
    rows = [
        [
            _code(name),
            _latex(dimension) if dimension is not None else escape(text),
            escape(values_text(value)),
            escape(source),
            escape(path),
        ]
        for name, dimension, text, value, source, path in parameter_rows(model)
    ]
    return _p(escape(parameters_head(name, model))) + _table(["name", "dimension", "value", "source", "path"], rows)


@_renders("pitheorem.engines.enginemodel.EngineModel")
def _engine_model(model) -> str:
    return _parameters(model.path or "(unsaved)", model)


# -- the command line's answers --------------------------------------------------------------


@_renders("pitheorem.answers.GroupsAnswer")
def _groups_answer(answer) -> str:
    groups = answer.groups
    head = _p(escape(render(answer, "text").splitlines()[0])) + _p(
        "repeating variables: " + (", ".join(_math(latex_name(n)) for n in groups.repeating) or "(none)")
    )
    if not len(groups):
        return head
    rows = [[_group_name(g), _math(g.latex), escape(value_text(v))] for g, v in zip(groups, answer.values, strict=True)]
    return head + _table(["group", "expression", "value"], rows)


@_renders("pitheorem.answers.BasesAnswer")
def _bases_answer(answer) -> str:
    if answer.bases is None:
        return _p(str(answer.n_bases))
    head = _p(escape(render(answer, "text").splitlines()[0]))
    rows = [[str(k), _math(", ".join(map(latex_name, b)))] for k, b in enumerate(answer.bases, 1)]
    return head + _table(["#", "repeating variables"], rows)


@_renders("pitheorem.answers.SearchAnswer")
def _search_answer(answer) -> str:
    return _search_result(answer.result, COMMAND_LINE_TIME_REMEDY)


@_renders("pitheorem.answers.ApplyAnswer")
def _apply_answer(answer) -> str:
    exponents = answer.scaling.exponents
    head = (
        _p(escape(render(answer, "text").splitlines()[0]))
        + _p(_latex(answer.scaling))
        + "".join(_note(n, COMMAND_LINE_TIME_REMEDY) for n in answer.result.notes)
    )
    rows = [
        [_math(latex_name(n)), _power_cell(exponents[n]), escape(value_text(v)), escape(value_text(answer.scaled[n]))]
        for n, v in answer.values.items()
    ]
    wrote = _p(f"wrote {_code(answer.output)}") if answer.output else ""
    return head + _table(["variable", "factor", "value", "scaled value"], rows) + wrote


@_renders("pitheorem.answers.ParamsAnswer")
def _params_answer(answer) -> str:
    return _parameters(answer.model, answer.engine_model)


@_renders("pitheorem.answers.EngineApplyAnswer")
def _engine_apply_answer(answer) -> str:
    head = _p(escape(render(answer, "text").splitlines()[0]))
    head += _p(escape(f"{len(answer.changed)} of {answer.n_parameters} parameters change"))
    rows = [
        [_code(name), _power_cell(p), escape(values_text(old)), escape(values_text(new))]
        for name, p, _, old, new in changed_rows(answer)
    ]
    wrote = _p(f"wrote {_code(answer.output)}") if answer.output else ""
    return head + _table(["parameter", "factor", "value", "scaled value"], rows) + wrote


@_renders("pitheorem.answers.EngineVerifyAnswer")
def _engine_verify_answer(answer) -> str:
    lines = [line for line in render(answer, "text").splitlines() if not line.startswith(("causes:", "  "))]
    items = "".join(f"<li>{render(c, 'html')}</li>" for c in answer.report.causes)
    return "".join(_p(escape(line)) for line in lines) + (f"<ul>{items}</ul>" if items else "")


@_renders("pitheorem.answers.SweepAnswer")
def _sweep_answer(answer) -> str:
    out = "".join(_sweep(sw) for sw in answer.sweeps)
    out += "".join(_p(f"wrote {_code(path)}") for path in answer.plots)
    if len(answer.sweeps) > 1:
        header, *rows = sweep_grid(answer)
        out += _table([escape(cell) for cell in header], [[escape(cell) for cell in row] for row in rows])
    return out
