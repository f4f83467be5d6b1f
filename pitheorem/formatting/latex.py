r"""LaTeX source: what ``format(x, "latex")``, ``_repr_latex_`` and ``--format latex`` give.

A math object (a dimension, a Pi group or set, a scaling, a range bound)
renders as math-mode LaTeX, ready to put between ``$`` (its
``_repr_latex_`` is ``$\displaystyle ...$`` of it); a table or a report
renders as text-mode LaTeX, a ``tabular`` whose math cells are between
``$``.  Names are written as sympy writes their symbols (``k_theta`` as
``k_{\theta}``), powers of ``s`` as ``s^{2}``.
"""

from __future__ import annotations

from fractions import Fraction

import sympy

from . import render
from .pieces import (
    PYTHON_TIME_REMEDY,
    SWEEP_HEADER,
    UNCHANGED,
    base_latex,
    changed_rows,
    default_text,
    deviation_rows,
    group_name_latex,
    latex_escape,
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
    which_scaling,
)
from .text import explanation, symmetry_head, unit_fit_head

__all__ = ["RENDERERS"]

#: renderer of each value type, by qualified type name
RENDERERS: dict = {}
_renders = registry(RENDERERS)


def _tabular(columns: str, rows, header=None, rule_before=None) -> str:
    r"""A ``tabular``: cells joined by ``&``, a ``\hline`` under the header and before row `rule_before`."""
    lines = [rf"\begin{{tabular}}{{{columns}}}"]
    if header is not None:
        lines.append(" & ".join(header) + r" \\ \hline")
    for k, row in enumerate(rows):
        if k == rule_before:
            lines.append(r"\hline")
        lines.append(" & ".join(row) + r" \\")
    lines.append(r"\end{tabular}")
    return "\n".join(lines)


def _math(latex: str) -> str:
    return f"${latex}$"


def _power_cell(exponent) -> str:
    """A power of s in a table cell; an unchanged entry shows the same mark as in plain text."""
    return _math(power_latex(exponent)) if exponent else UNCHANGED


def _number(value) -> str:
    """A value in a table cell: a non-integral Fraction as a fraction, anything else as its text."""
    if isinstance(value, Fraction) and value.denominator != 1:
        return _math(rational_latex(value))
    return value_text(value)


def _lines(lines) -> str:
    """Plain-text lines as LaTeX text, a line break between them."""
    return " \\\\\n".join(latex_escape(line.strip()) for line in lines)


# -- dimensions, groups, scalings ------------------------------------------------------------


@_renders("pitheorem.dimensions.Dimension")
def _dimension(dim) -> str:
    return r"\,".join(base_latex(b) if p == 1 else f"{base_latex(b)}^{{{p}}}" for b, p in dim.exponents.items()) or "1"


@_renders("pitheorem.groups.PiGroup")
def _pi_group(group) -> str:
    return f"{group_name_latex(group)} = {group.latex}"


@_renders("pitheorem.groups.PiSet")
def _pi_set(groups) -> str:
    if not len(groups):
        return r"\text{(no dimensionless groups)}"
    body = r" \\ ".join(f"{group_name_latex(g)} &= {g.latex}" for g in groups)
    return rf"\begin{{aligned}} {body} \end{{aligned}}"


#: how many variables one line of a scaling's LaTeX shows (a longer scaling takes several lines)
SCALING_ROW = 5


@_renders("pitheorem.scaling.Scaling")
def _scaling(sc) -> str:
    parts = [rf"{latex_name(n)} \to {power_latex(p)}\,{latex_name(n)}" for n, p in sc.exponents.items() if p]
    if len(parts) <= SCALING_ROW:
        return r",\quad ".join(parts) or r"\text{identity (nothing changes)}"
    # a long scaling on several centred lines, so that it fits a page's column
    rows = [r",\quad ".join(parts[k : k + SCALING_ROW]) for k in range(0, len(parts), SCALING_ROW)]
    return r"\begin{gathered} " + r", \\ ".join(rows) + r" \end{gathered}"


# -- search ----------------------------------------------------------------------------------


@_renders("pitheorem.scalesearch.SearchNote")
def _note(note) -> str:
    return note_text(
        note, time_remedy=latex_escape(PYTHON_TIME_REMEDY), code=lambda name: rf"\texttt{{{latex_escape(name)}}}"
    )


@_renders("pitheorem.scalesearch.SearchResult")
def _search_result(result) -> str:
    if not result.feasible:
        cert = result.certificate.latex
        return (
            f"% {explanation(result)}\n"
            rf"\[ {cert} \;\to\; {power_latex(result.certificate_power)}\,{cert} \]"
        )
    variables, base_units = search_cells(result, _power_cell)
    rows = [[_math(latex_name(n)), role, *cells] for n, role, cells in variables]
    rows += [[rf"$[\mathrm{{{b}}}]$", "base unit", *(cell or "n/a" for cell in cells)] for b, cells in base_units]
    n = result.n_scalings
    return _tabular(
        f"ll{'c' * n}", rows, ["variable", "role", *(rf"\#{k}" for k in range(1, n + 1))], rule_before=len(variables)
    )


# -- equations -------------------------------------------------------------------------------


@_renders("pitheorem.equations.DimensionReport")
def _dimension_report(report) -> str:
    if report.consistent:
        return f"consistent: dimension {_math(_dimension(report.dimension))}"
    head = f"inconsistent: {len(report.offending)} offending term(s)"
    rows = [
        [_math(sympy.latex(term)), _math(_dimension(got)), _math(_dimension(want))]
        for term, got, want in report.offending
    ]
    ties = "".join(f"\n\ntie: {latex_escape(tie)}" for tie in report.ties)
    return f"{head}\n\n{_tabular('lll', rows, ['term', 'dimension', 'expected'])}{ties}"


@_renders("pitheorem.equations.SymmetryReport")
def _symmetry_report(report) -> str:
    head = _lines(symmetry_head(report))
    if not report.beyond_units:
        return head
    rows = [[_math(rational_latex(vec.get(n, 0))) for n in report.variables] for vec in report.beyond_units]
    header = [_math(latex_name(n)) for n in report.variables]
    return f"{head}\n\n{_tabular('c' * len(report.variables), rows, header)}"


# -- simulations -----------------------------------------------------------------------------


@_renders("pitheorem.simulation.SimilarityReport")
def _similarity_report(report) -> str:
    header, rows = deviation_rows(report, lambda n: _math(latex_name(n)))
    return f"{_lines([render(report, 'text')])}\n\n{_tabular('l' + 'r' * (len(header) - 1), rows, header)}"


# -- unit fits -------------------------------------------------------------------------------


@_renders("pitheorem.unitfit.RangeBound")
def _range_bound(bound) -> str:
    relation = r"\geq" if bound.side == "low" else r"\leq"
    return f"{latex_name(bound.name)} {relation} {rational_latex(bound.bound)}"


@_renders("pitheorem.unitfit.UnitFit")
def _unit_fit(fit) -> str:
    head = latex_escape(unit_fit_head(fit))
    units = [[_math(base_latex(b)), f"{float(f):.6g}", f"{1 / float(f):.6g}"] for b, f in fit.factors.items()]
    rows = [
        [_math(latex_name(n)), f"{old:.6g}", f"{new:.6g}", *range_cells(bounds, ok)]
        for n, old, new, bounds, ok in unit_fit_rows(fit)
    ]
    parts = [
        head,
        _tabular("lrr", units, ["base", "readings times", "new unit (old units)"]),
        _tabular("lrrll", rows, ["variable", "value", "new value", "range", ""]),
    ]
    if fit.conflict:
        parts.append("conflicting bounds: " + "; ".join(_math(_range_bound(c)) for c in fit.conflict))
    return "\n\n".join(parts)


# -- engines ---------------------------------------------------------------------------------


@_renders("pitheorem.engines.verdicts.causes.Cause")
def _cause(cause) -> str:
    return rf"\textbf{{{cause.kind}}}: \texttt{{{latex_escape(cause.element)}}}: {latex_escape(cause.detail)}"


@_renders("pitheorem.engines.verdicts.audit.Audit")
def _audit(audit) -> str:
    first, *rest = render(audit, "text").splitlines()
    items = "".join(rf"\item {render(c, 'latex')}" + "\n" for c in audit.causes)
    body = "\\begin{itemize}\n" + items + "\\end{itemize}" if rest else ""
    return latex_escape(first) + ("\n" + body if body else "")


@_renders("pitheorem.engines.constants.HiddenConstant")
def _hidden_constant(constant) -> str:
    return (
        rf"\texttt{{{latex_escape(constant.name)}}} [{_math(_dimension(constant.dimension))}] "
        f"({default_text(constant.default)})"
    )


@_renders("pitheorem.engines.rules.RuleVerdict")
def _rule_verdict(verdict) -> str:
    first, *rest = render(verdict, "text").splitlines()
    items = "".join(f"\n\\item {latex_escape(line.strip())}" for line in rest)
    return rf"\textbf{{{latex_escape(first)}}}" + "\n\\begin{itemize}" + items + "\n\\end{itemize}"


@_renders("pitheorem.engines.verdicts.sweep.SweepRow")
def _sweep_row(row) -> str:
    return latex_escape(render(row, "text"))


@_renders("pitheorem.engines.verdicts.sweep.Sweep")
def _sweep(sweep) -> str:
    rows = [[latex_escape(cell) for cell in sweep_cells(r)] for r in sweep.rows]
    parts = [latex_escape(sweep_head(sweep)), _tabular("rlrrl", rows, list(SWEEP_HEADER))]
    caused = [r for r in sweep.rows if r.causes]
    if caused:
        items = "".join(
            rf"\item $s = {_number(r.s)}$: " + "; ".join(render(c, "latex") for c in r.causes) + "\n" for r in caused
        )
        parts.append("\\begin{itemize}\n" + items + "\\end{itemize}")
    fit = sweep_fit_text(sweep)
    if fit:
        parts.append(latex_escape(fit))
    return "\n\n".join(parts)


def _parameter_table(name: str, model) -> str:
    rows = [
        [
            rf"\texttt{{{latex_escape(name)}}}",
            latex_escape(text),
            " ".join(map(_number, value)),
            latex_escape(source),
            latex_escape(path),
        ]
        for name, _, text, value, source, path in parameter_rows(model)
    ]
    head = f"% {parameters_head(name, model)}"
    return f"{head}\n{_tabular('lllll', rows, ['name', 'dimension', 'value', 'source', 'path'])}"


@_renders("pitheorem.engines.enginemodel.EngineModel")
def _engine_model(model) -> str:
    return _parameter_table(model.path or "(unsaved)", model)


# -- the command line's answers --------------------------------------------------------------


@_renders("pitheorem.answers.GroupsAnswer")
def _groups_answer(answer) -> str:
    lines = [f"{group_name_latex(g)} &= {g.latex}" for g in answer.groups]
    return "\\begin{align*}\n" + " \\\\\n".join(lines) + "\n\\end{align*}"


@_renders("pitheorem.answers.BasesAnswer")
def _bases_answer(answer) -> str:
    if answer.bases is None:
        return str(answer.n_bases)
    rows = [[str(k), _math(", ".join(map(latex_name, b)))] for k, b in enumerate(answer.bases, 1)]
    return _tabular("rl", rows)


@_renders("pitheorem.answers.SearchAnswer")
def _search_answer(answer) -> str:
    return _search_result(answer.result)


@_renders("pitheorem.answers.ApplyAnswer")
def _apply_answer(answer) -> str:
    exponents = answer.scaling.exponents
    rows = [
        [_math(latex_name(n)), _power_cell(exponents[n]), _number(v), _number(answer.scaled[n])]
        for n, v in answer.values.items()
    ]
    head = f"% {answer.model}: {which_scaling(answer.result, answer.solution)}, s = {answer.s}"
    return f"{head}\n{_tabular('lcll', rows, ['variable', 'factor', 'value', 'scaled value'])}"


@_renders("pitheorem.answers.ParamsAnswer")
def _params_answer(answer) -> str:
    return _parameter_table(answer.model, answer.engine_model)


@_renders("pitheorem.answers.EngineApplyAnswer")
def _engine_apply_answer(answer) -> str:
    rows = [
        [rf"\texttt{{{latex_escape(name)}}}", _power_cell(p), " ".join(map(_number, old)), " ".join(map(_number, new))]
        for name, p, _, old, new in changed_rows(answer)
    ]
    head = f"% {answer.model}, s = {answer.s}: {len(answer.changed)} of {answer.n_parameters} parameters change" + (
        f"; wrote {answer.output}" if answer.output else ""
    )
    return f"{head}\n{_tabular('lcll', rows, ['parameter', 'factor', 'value', 'scaled value'])}"


@_renders("pitheorem.answers.EngineVerifyAnswer")
def _engine_verify_answer(answer) -> str:
    lines = [line for line in render(answer, "text").splitlines() if not line.startswith(("causes:", "  "))]
    items = "".join(rf"\item {render(c, 'latex')}" + "\n" for c in answer.report.causes)
    head = f"% {answer.model} in {answer.engine}, s = {answer.s}\n" + "\n\n".join(map(latex_escape, lines))
    return head + ("\n\\begin{itemize}\n" + items + "\\end{itemize}" if items else "")


@_renders("pitheorem.answers.SweepAnswer")
def _sweep_answer(answer) -> str:
    parts = [_sweep(sw) for sw in answer.sweeps]
    parts += [latex_escape(f"wrote {path}") for path in answer.plots]
    if len(answer.sweeps) > 1:
        header, *rows = sweep_grid(answer)
        grid = [[latex_escape(cell) for cell in row] for row in rows]
        parts.append(_tabular("l" * len(header), grid, [latex_escape(cell) for cell in header]))
    return "\n\n".join(parts)
