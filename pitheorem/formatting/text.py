"""Plain text: what ``str(x)`` and ``print(x)`` show, and the command line's default output.

One renderer per value type, filed in :data:`RENDERERS` under the type's
qualified name.  Powers of ``s`` read ``s^2``, ``1/s``, ``s^(1/2)``
(:func:`~pitheorem.formatting.pieces.power_text`); tables are aligned
columns (:func:`~pitheorem.formatting.pieces.align`).
"""

from __future__ import annotations

import textwrap

import sympy

from .pieces import (
    COMMAND_LINE_TIME_REMEDY,
    PYTHON_TIME_REMEDY,
    SWEEP_HEADER,
    align,
    changed_by_kind,
    changed_rows,
    default_text,
    names_text,
    note_text,
    parameter_rows,
    parameters_head,
    power_text,
    range_cells,
    registry,
    request_text,
    search_cells,
    solutions_text,
    strength_lines,
    sweep_cells,
    sweep_fit_text,
    sweep_grid,
    sweep_head,
    unit_change_text,
    unit_fit_rows,
    value_text,
    values_text,
    which_scaling,
)

__all__ = ["RENDERERS", "explanation", "parameter_table", "search_table", "symmetry_head", "unit_fit_head"]

#: renderer of each value type, by qualified type name
RENDERERS: dict = {}
_renders = registry(RENDERERS)


# -- dimensions, groups, scalings ------------------------------------------------------------


@_renders("pitheorem.dimensions.Dimension")
def _dimension(dim) -> str:
    parts = []
    for b, p in dim.exponents.items():
        power = str(p.numerator) if p.denominator == 1 else f"({p})"
        parts.append(b if p == 1 else f"{b}^{power}")
    return " ".join(parts) or "1"


@_renders("pitheorem.groups.PiGroup")
def _pi_group(group) -> str:
    return f"{group.name} = {sympy.sstr(group.expr)}"


@_renders("pitheorem.groups.PiSet")
def _pi_set(groups) -> str:
    return "\n".join(map(_pi_group, groups)) or "(no dimensionless groups)"


@_renders("pitheorem.scaling.Scaling")
def _scaling(sc) -> str:
    parts = []
    for n, p in sc.exponents.items():
        if p:
            f = power_text(p)
            parts.append(f"{n} -> {n}/{f[2:]}" if f.startswith("1/") else f"{n} -> {f} {n}")
    return ", ".join(parts) or "identity (nothing changes)"


# -- search ----------------------------------------------------------------------------------


@_renders("pitheorem.scalesearch.SearchNote")
def _note(note) -> str:
    return note_text(note)


def explanation(result) -> str:
    """One sentence saying what a search found, or why nothing can be.

    Parameters
    ----------
    result : SearchResult

    Returns
    -------
    str

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.text import explanation
    >>> explanation(pt.search(pt.System({"l": "L", "t": "T"}), scale={"l": 1}))
    'Scaling l by s with t fixed: 1 minimal solution (unique).'
    """
    if result.feasible:
        d = len(result.directions)
        extra = f" of a {d}-parameter family" if d else " (unique)"
        return f"Scaling {request_text(result)}: {solutions_text(result.n_scalings)}{extra}."
    return (
        f"Impossible: {result.certificate.expr} is dimensionless and built only from prescribed and fixed "
        f"variables, but the request would multiply it by {power_text(result.certificate_power)}, so no change "
        "of units (and hence no similarity scaling) can do it."
    )


def search_table(result) -> str:
    """A search's minimal scalings as aligned columns: variables down, scalings across.

    Parameters
    ----------
    result : SearchResult

    Returns
    -------
    str

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.text import search_table
    >>> print(search_table(pt.search(pt.System({"l": "L", "t": "T"}), scale={"l": 1})))
    variable  role   #1
    l         scale  s
    t         fixed  -
    [L]       base   s
    [T]       base   -
    """
    variables, base_units = search_cells(result, power_text)
    rows = [["variable", "role", *(f"#{k}" for k in range(1, result.n_scalings + 1))]]
    rows += [[n, role, *cells] for n, role, cells in variables]
    rows += [[f"[{b}]", "base", *(cell or "n/a" for cell in cells)] for b, cells in base_units]
    table = align(rows)
    if any(cell is None for _, cells in base_units for cell in cells):
        table += "\n(n/a: that scaling is a symmetry of the equations, not a change of units)"
    return table


#: a search with more variables than this opens its table with a summary of each scaling
SUMMARY_OVER = 20


def _search_summary(result) -> list[str]:
    """For a large model: each minimal scaling's change of units and how many variables it changes."""
    if len(result.system) <= SUMMARY_OVER:
        return []
    lines = ["", f"summary (the table below has a row for each of the {len(result.system)} variables):"]
    for k, sc in enumerate(result.scalings, 1):
        changed = [n for n, p in sc.exponents.items() if p]
        lines.append(f"  #{k}: {unit_change_text(sc)}; changes {len(changed)} of {len(result.system)} variables")
    return lines


@_renders("pitheorem.scalesearch.SearchResult")
def _search_result(result, *, time_remedy: str = PYTHON_TIME_REMEDY) -> str:
    """A search's explanation, its notes in a front end's terms, then its table or certificate."""
    lines = [explanation(result), *(note_text(note, time_remedy=time_remedy) for note in result.notes)]
    if result.feasible:
        lines += _search_summary(result)
        lines += ["", search_table(result)]
    else:
        lines.append(
            f"certificate: {_pi_group(result.certificate)} (the request multiplies it by "
            f"{power_text(result.certificate_power)})"
        )
    return "\n".join(lines)


# -- equations -------------------------------------------------------------------------------


@_renders("pitheorem.equations.DimensionReport")
def _dimension_report(report) -> str:
    if report.consistent:
        return f"consistent: dimension {_dimension(report.dimension)}"
    lines = [f"inconsistent: {len(report.offending)} offending term(s)"]
    lines += [
        f"  {sympy.sstr(term)} has dimension {_dimension(got)}, expected {_dimension(want)}"
        for term, got, want in report.offending
    ]
    lines += [f"  tie: {tie}" for tie in report.ties]
    return "\n".join(lines)


def _vector(vec) -> str:
    return ", ".join(f"{n}: {p}" for n, p in vec.items() if p) or "0"


def symmetry_head(report) -> list[str]:
    """The lines that sum up a symmetry report (the text, LaTeX and HTML displays open with them).

    Parameters
    ----------
    report : SymmetryReport

    Returns
    -------
    list of str

    Examples
    --------
    >>> import sympy, pitheorem as pt
    >>> from pitheorem.formatting.text import symmetry_head
    >>> t = sympy.Symbol("t"); x = sympy.Function("x")(t)
    >>> symmetry_head(pt.scaling_symmetries([sympy.Eq(x.diff(t, 2), 0)], pt.System({"x": "L", "t": "T"})))[-1]
    'no symmetries beyond changes of units'
    """
    return [
        f"symmetry subspace of dimension {report.n_symmetries} over {', '.join(report.variables)}",
        f"changes of units: dimension {len(report.within_units)}"
        + ("" if report.contains_units else " (NOT all symmetries: the equations are inconsistent)"),
        "symmetries beyond changes of units:" if report.beyond_units else "no symmetries beyond changes of units",
    ]


@_renders("pitheorem.equations.SymmetryReport")
def _symmetry_report(report) -> str:
    return "\n".join([*symmetry_head(report), *(f"  {_vector(v)}" for v in report.beyond_units)])


# -- simulations -----------------------------------------------------------------------------


def _verdict(report) -> tuple[str, str]:
    """``PASSED``/``FAILED``, and whether the exponents are a change of units."""
    return (
        "FAILED" if not report.passed else "INCONCLUSIVE" if report.inconclusive else "PASSED",
        "similarity scaling" if report.is_similarity else "NOT a similarity scaling",
    )


@_renders("pitheorem.simulation.SimilarityReport")
def _similarity_report(report) -> str:
    verdict, kind = _verdict(report)
    per = ", ".join(f"{n}: {d:.3g}" for n, d in report.deviation.items())
    if report.sensitivity is not None:
        worst = max(report.sensitivity.values(), default=0.0)
        judged = f"yardstick: {report.baseline_factor:g}x each state's one-ulp sensitivity (the largest {worst:.3g})"
    else:
        judged = f"tol {report.tol:g}"
    exact = report.exact and report.sensitivity is not None
    head = ("bit for bit, " if report.inconclusive else "EXACT (bit for bit), ") if exact else ""
    lines = [
        f"{head}{verdict}: max deviation {report.max_deviation:.3g} ({judged}) at s={report.s:g}, "
        f"{kind}, method {report.method}; per state {per}"
    ]
    if report.excited is False:
        lines.append("the original run moved nothing beyond its own rounding: this verdict proves nothing")
    lines.extend(strength_lines(report))
    lines.extend(f"cause: {cause}" for cause in report.causes)
    return "\n".join(lines)


@_renders("pitheorem.engines.paper.rod.EngineSimilarityReport")
def _engine_similarity_report(report) -> str:
    verdict, kind = _verdict(report)
    ode = "" if report.ode_report is None else f"; pure ODE: {report.ode_report.max_deviation:.3g}"
    own = "" if report.engine_vs_ode is None else f"; engine vs exact ODE: {report.engine_vs_ode:.3g}"
    return (
        f"{report.engine}: {verdict}, max deviation {report.max_deviation:.3g} (tol {report.tol:g}) at "
        f"s={report.s:g}, {kind}, dt {report.dt:.6g} -> {report.dt_scaled:.6g}{ode}{own}"
    )


# -- unit fits -------------------------------------------------------------------------------


@_renders("pitheorem.unitfit.RangeBound")
def _range_bound(bound) -> str:
    return f"{bound.name} {'>=' if bound.side == 'low' else '<='} {bound.bound}"


def unit_fit_head(fit) -> str:
    """The line that sums up a unit fit (the text, LaTeX and HTML displays open with it).

    Parameters
    ----------
    fit : UnitFit

    Returns
    -------
    str

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem.formatting.text import unit_fit_head
    >>> unit_fit_head(pt.fit_units(pt.System({"l": "L"}), {"l": 500}, ranges={"l": (1, 2)}, nice=2))
    'unit fit (factors rounded to powers of 2): every value in range'
    """
    kind = f"factors rounded to powers of {fit.nice}" if fit.nice else "continuous fit"
    head = (
        "every value in range"
        if fit.feasible
        else (f"NOT every value fits: worst violation {fit.worst_violation:.3g} decades")
    )
    return f"unit fit ({kind}): {head}"


@_renders("pitheorem.unitfit.UnitFit")
def _unit_fit(fit) -> str:
    lines = [unit_fit_head(fit)]
    for b, f in fit.factors.items():
        u = fit.unit_change[b]
        power = f"{fit.nice}^{u}" if fit.nice else f"10^{float(u):.6g}"
        lines.append(f"  {b}: readings x {float(f):.6g} ({power}), new unit = {1 / float(f):.6g} old units")
    for n, old, new, bounds, ok in unit_fit_rows(fit):
        line = f"  {n:>8s} {old:12.6g} -> {new:12.6g}"
        if bounds is not None:
            where, mark = range_cells(bounds, ok)
            line += f"   in {where}  {mark}"
        lines.append(line)
    if fit.conflict:
        lines.append("  conflicting bounds: " + "; ".join(map(_range_bound, fit.conflict)))
    return "\n".join(lines)


# -- engines ---------------------------------------------------------------------------------


@_renders("pitheorem.engines.verdicts.causes.Cause")
def _cause(cause) -> str:
    return f"{cause.kind}: {cause.element}: {cause.detail}"


@_renders("pitheorem.engines.verdicts.audit.Audit")
def _audit(audit) -> str:
    head = f"audit at s = {audit.s:g}: {audit.compared} stored numbers compared, "
    if not audit.causes:
        return head + "every one the original times its factor"
    return head + f"{len(audit.causes)} cause(s):\n" + "\n".join(f"  {c}" for c in audit.causes)


@_renders("pitheorem.engines.constants.HiddenConstant")
def _hidden_constant(constant) -> str:
    return f"{constant.name} [{_dimension(constant.dimension)}] ({default_text(constant.default)})"


@_renders("pitheorem.engines.rules.RuleVerdict")
def _rule_verdict(verdict) -> str:
    lines = [f"{verdict.rule.name}:"]
    if verdict.unit_change is None:
        lines.append(f"  NOT a change of units: it changes {_pi_group(verdict.certificate)}")
        return "\n".join(lines)
    units = ", ".join(f"{b} by X^{u}" for b, u in verdict.unit_change.items() if u) or "nothing"
    lines.append(f"  a change of units: readings of {units}")
    for name, dim, p in verdict.missing:
        lines.append(f"  not named: {name} [{_dimension(dim)}] must scale by X^{p}")
    if verdict.unchanged:
        lines.append(f"  not named, rightly unchanged: {', '.join(verdict.unchanged)}")
    for c in verdict.broken:
        lines.append(
            f"  hidden constant left out: {_hidden_constant(c)}"
            f" must scale by X^{verdict.scaling.exponent_of(c.dimension)}"
        )
    return "\n".join(lines)


@_renders("pitheorem.engines.verdicts.sweep.SweepRow")
def _sweep_row(row) -> str:
    s, verdict, deviation, yardstick, crossed = sweep_cells(row)
    line = f"s = {s}: {verdict}"
    if row.max_deviation is not None:
        line += f", deviation {deviation}, yardstick {yardstick}"
    if crossed:
        line += f", beyond {crossed}"
    return line


#: the width the lines of a sweep's prose are wrapped at (its table is as wide as its columns)
SWEEP_WIDTH = 88


@_renders("pitheorem.engines.verdicts.sweep.Sweep")
def _sweep(sweep) -> str:
    lines = [
        textwrap.fill(sweep_head(sweep), SWEEP_WIDTH, subsequent_indent="  "),
        align([list(SWEEP_HEADER)] + [sweep_cells(r) for r in sweep.rows]),
    ]
    # each cause once, with the factors it was found at (a cause of every factor is not said at each)
    grouped: dict[str, list[str]] = {}
    for r in sweep.rows:
        for c in r.causes:
            factors = grouped.setdefault(f"{c.kind}: {c.element}", [])
            if value_text(r.s) not in factors:
                factors.append(value_text(r.s))
    if grouped:
        lines.append("causes:")
        for cause, factors in grouped.items():
            line = f"  {cause} (s = {', '.join(factors)})"
            lines.append(textwrap.fill(line, SWEEP_WIDTH, subsequent_indent="    "))
    fit = sweep_fit_text(sweep)
    if fit:
        lines.append(textwrap.fill(fit, SWEEP_WIDTH, subsequent_indent="  "))
    return "\n".join(lines)


def parameter_table(model) -> str:
    """An engine model's parameters as aligned columns: name, dimension, value, source, path.

    Parameters
    ----------
    model : EngineModel

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.formatting.text import parameter_table
    >>> parameter_table(engines.load(engines.example_path("pendulum.xml"))).splitlines()[0].split()
    ['name', 'dimension', 'value', 'source', 'path']
    """
    rows = [("name", "dimension", "value", "source", "path")]
    rows += [
        (name, text, values_text(value), source, path) for name, _, text, value, source, path in parameter_rows(model)
    ]
    return align(rows)


def _parameters(name: str, model) -> str:
    return f"{parameters_head(name, model)}\n{parameter_table(model)}"


@_renders("pitheorem.engines.enginemodel.EngineModel")
def _engine_model(model) -> str:
    return _parameters(model.path or "(unsaved)", model)


# -- the command line's answers --------------------------------------------------------------


@_renders("pitheorem.answers.GroupsAnswer")
def _groups_answer(answer) -> str:
    system, groups = answer.system, answer.groups
    lines = [
        f"{answer.model}: {len(system)} variables, rank {system.rank}, {system.n_groups} dimensionless groups",
        f"repeating variables: {', '.join(groups.repeating) or '(none)'}",
    ]
    if answer.passed_over:
        lines.append(
            "(the first valid set without "
            + ("the engine's settings, " if answer.settings_avoided else "")
            + "time variables, variables lacking one value, and the "
            f"variables whose value is 0: {names_text(answer.passed_over)})"
        )
    if len(groups):
        rows = [["group", "expression", "value"]]
        rows += [[g.name, sympy.sstr(g.expr), value_text(v)] for g, v in zip(groups, answer.values, strict=True)]
        lines += ["", align(rows)]
    return "\n".join(lines)


@_renders("pitheorem.answers.BasesAnswer")
def _bases_answer(answer) -> str:
    if answer.bases is None:
        return str(answer.n_bases)
    conditions = []
    if answer.exclude:
        conditions.append(f"without {', '.join(answer.exclude)}")
    if answer.require:
        conditions.append(f"with {', '.join(answer.require)}")
    condition = f" ({'; '.join(conditions)})" if conditions else ""
    width = len(str(len(answer.bases)))
    lines = [f"{answer.model}: {answer.n_bases} valid repeating sets of {answer.rank} variables{condition}"]
    if len(answer.bases) < answer.n_bases:
        lines.append(f"the first {len(answer.bases)} (--all lists every one, --count only their number):")
    lines += [f"{k:>{width}}  {' '.join(b)}" for k, b in enumerate(answer.bases, 1)]
    return "\n".join(lines)


@_renders("pitheorem.answers.SearchAnswer")
def _search_answer(answer) -> str:
    return _search_result(answer.result, time_remedy=COMMAND_LINE_TIME_REMEDY)


@_renders("pitheorem.answers.ApplyAnswer")
def _apply_answer(answer) -> str:
    exponents = answer.scaling.exponents
    lines = [
        f"{answer.model}, s = {answer.s}: {which_scaling(answer.result, answer.solution)}",
        f"  {_scaling(answer.scaling)}",
    ]
    lines += [note_text(note, time_remedy=COMMAND_LINE_TIME_REMEDY) for note in answer.result.notes]
    rows = [["variable", "factor", "value", "scaled value"]]
    rows += [
        [n, power_text(exponents[n]), value_text(v), value_text(answer.scaled[n])] for n, v in answer.values.items()
    ]
    lines += ["", align(rows)]
    if answer.output:
        lines += ["", f"wrote {answer.output}"]
    return "\n".join(lines)


@_renders("pitheorem.answers.ParamsAnswer")
def _params_answer(answer) -> str:
    return _parameters(answer.model, answer.engine_model)


@_renders("pitheorem.answers.EngineApplyAnswer")
def _engine_apply_answer(answer) -> str:
    lines = [
        f"{answer.model}, s = {answer.s}: {unit_change_text(answer.scaling)}",
        f"{len(answer.changed)} of {answer.n_parameters} parameters change"
        + (", by dimension:" if answer.changed else ""),
    ]
    if answer.changed:
        changed = changed_rows(answer)
        rows = [["dimension", "factor", "count", "parameters"]]
        rows += [
            [dim, power_text(p), str(len(names)), ", ".join(names[:2]) + (", ..." if len(names) > 2 else "")]
            for dim, p, names in changed_by_kind((name, p, dim) for name, p, dim, _, _ in changed)
        ]
        lines.append("\n".join("  " + line for line in align(rows).splitlines()))
        rows = [["parameter", "factor", "value", "scaled value"]]
        rows += [[name, power_text(p), values_text(old), values_text(new)] for name, p, _, old, new in changed]
        lines += ["", align(rows)]
    if answer.output:
        also = f" (and {', '.join(answer.also_written)})" if answer.also_written else ""
        lines += ["", f"wrote {answer.output}{also}"]
    return "\n".join(lines)


@_renders("pitheorem.answers.EngineVerifyAnswer")
def _engine_verify_answer(answer) -> str:
    rep, s = answer.report, answer.s
    steps = len(rep.original) - 1
    if rep.exact and (rep.inconclusive or rep.engine_reset is not None):  # within 120 characters: the rest below
        why = "as do copies made wrong on purpose"
        if rep.engine_reset is not None:  # inconclusive however the controls went: the run itself broke down
            why = "up to where the engine gave up on the run"
        head = "inconclusive" if rep.inconclusive else "exact"
        lines = [f"{head}: the copy matches bit for bit (s = {s}, {steps} steps), {why}"]
    elif rep.exact:
        lines = [
            f"exact: the scaled copy, mapped back, equals the original bit for bit at every step (s = {s}, {steps} steps)"
        ]
    else:
        verdict = {"similar": "similar", "inconclusive": "inconclusive", "not similar": "NOT similar"}[rep.verdict]
        worst = max(rep.sensitivity.values(), default=0.0)
        lines = [
            f"{verdict}: deviation {rep.max_deviation:.3g} (original units) against {rep.baseline_factor:g}x the "
            f"spread {worst:.3g} of {rep.ensemble} one-ulp twins; s = {s}, {steps} steps"
        ]
        if rep.first_divergence is not None:
            t, name = rep.first_divergence
            lines.append(f"first difference at t = {t:.6g}, in {name}")
    if not rep.excited:
        lines.append(
            "the original run moved nothing beyond its own rounding: this verdict proves nothing "
            "(use --input smooth or another initial pose)"
        )
    lines.extend(strength_lines(rep))
    lines.extend(f"note: {note}" for note in answer.notes)
    if rep.causes:
        lines.append("causes:")
        lines.extend(f"  {c}" for c in rep.causes)
    elif not rep.similar or (not rep.exact and answer.exact_expected):
        lines.append("no cause found by the audit and the counter-runs (solver, contacts)")
    return "\n".join(lines)


@_renders("pitheorem.answers.SweepAnswer")
def _sweep_answer(answer) -> str:
    parts = [_sweep(sw) for sw in answer.sweeps]
    if answer.plots:
        parts.append("\n".join(f"wrote {path}" for path in answer.plots))
    if len(answer.sweeps) > 1:
        parts.append("verdicts of every file by scale factor s:\n" + align(sweep_grid(answer)))
    return "\n\n".join(parts)
