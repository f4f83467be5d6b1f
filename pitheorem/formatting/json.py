"""JSON documents: what ``format(x, "json")`` and ``--format json`` give.

Meant for programs: keys come in a fixed order (a system's variables in
its own order), integers are JSON integers, every exact rational (an
exponent of ``s``, a unit change, a rational value) is a string such as
``"1/2"`` or ``"-2"`` that :class:`fractions.Fraction` reads back, floats
are JSON numbers, and a search note is ``{"kind", "variables", "text"}``:
the data of a :class:`~pitheorem.SearchNote` and its sentence.

Each value type has a data function, filed in :data:`DATA` (a document is
the data of its parts); :data:`RENDERERS` dumps it with an indent of two.
"""

from __future__ import annotations

import json

import sympy

from . import render
from .pieces import (
    COMMAND_LINE_TIME_REMEDY,
    PYTHON_TIME_REMEDY,
    changed_rows,
    json_number,
    note_text,
    parameter_rows,
    rational_text,
    registry,
)
from .text import explanation

__all__ = ["DATA", "RENDERERS", "dumps"]

#: data function of each value type, by qualified type name: the value as dicts, lists, str and numbers
DATA: dict = {}
_data = registry(DATA)


def dumps(data) -> str:
    """The JSON text of some data, as every JSON output of pitheorem writes it.

    Parameters
    ----------
    data : dict or list

    Returns
    -------
    str

    Examples
    --------
    >>> from pitheorem.formatting.json import dumps
    >>> print(dumps({"g": "1/2"}))
    {
      "g": "1/2"
    }
    """
    return json.dumps(data, indent=2, ensure_ascii=False)


def _rationals(mapping) -> dict:
    return {k: rational_text(v) for k, v in mapping.items()}


def _numbers(mapping) -> dict:
    return {k: json_number(v) for k, v in mapping.items()}


# -- dimensions, groups, scalings ------------------------------------------------------------


@_data("pitheorem.dimensions.Dimension")
def _dimension(dim) -> dict:
    return {"dimension": render(dim, "text"), "exponents": _rationals(dim.exponents)}


@_data("pitheorem.groups.PiGroup")
def _pi_group(group) -> dict:
    return {
        "name": group.name,
        "variable": group.variable,
        "expression": sympy.sstr(group.expr),
        "latex": group.latex,
        "exponents": group.exponents,
    }


@_data("pitheorem.groups.PiSet")
def _pi_set(groups) -> dict:
    return {
        "variables": list(groups.variables),
        "repeating": list(groups.repeating),
        "groups": [_pi_group(g) for g in groups],
    }


@_data("pitheorem.scaling.Scaling")
def _scaling(sc) -> dict:
    return {
        "changed": list(sc.changed),
        "exponents": _rationals(sc.exponents),
        "unit_change": _rationals(sc.unit_change) if sc.is_unit_change else None,
    }


# -- search ----------------------------------------------------------------------------------


def _note(note, time_remedy: str = PYTHON_TIME_REMEDY) -> dict:
    # the data of the note (SearchNote(kind, variables) rebuilds it) and its sentence
    return {"kind": note.kind, "variables": list(note.variables), "text": note_text(note, time_remedy=time_remedy)}


_data("pitheorem.scalesearch.SearchNote")(_note)


def _certificate(result):
    cert = result.certificate
    if cert is None:
        return None
    return {
        "expression": sympy.sstr(cert.expr),
        "latex": cert.latex,
        "exponents": cert.exponents,
        "power": rational_text(result.certificate_power),
    }


def _search_result(result, time_remedy: str = PYTHON_TIME_REMEDY) -> dict:
    return {
        "scale": _rationals(result.scale),
        "fixed": list(result.fixed),
        "feasible": result.feasible,
        "count": result.n_scalings if result.feasible else 0,
        "scalings": [_scaling(sc) for sc in result.scalings],
        "certificate": _certificate(result),
        "explanation": explanation(result),
        "notes": [_note(note, time_remedy) for note in result.notes],
    }


_data("pitheorem.scalesearch.SearchResult")(_search_result)


# -- equations -------------------------------------------------------------------------------


@_data("pitheorem.equations.DimensionReport")
def _dimension_report(report) -> dict:
    return {
        "consistent": report.consistent,
        "dimension": render(report.dimension, "text"),
        "offending": [
            {"term": sympy.sstr(term), "dimension": render(got, "text"), "expected": render(want, "text")}
            for term, got, want in report.offending
        ],
        "ties": list(report.ties),
    }


@_data("pitheorem.equations.SymmetryReport")
def _symmetry_report(report) -> dict:
    return {
        "variables": list(report.variables),
        "n_symmetries": report.n_symmetries,
        "basis": [_rationals(v) for v in report.basis],
        "within_units": [_rationals(v) for v in report.within_units],
        "beyond_units": [_rationals(v) for v in report.beyond_units],
        "contains_units": report.contains_units,
    }


# -- simulations -----------------------------------------------------------------------------


@_data("pitheorem.simulation.SimilarityReport")
def _similarity_report(report) -> dict:
    return {
        "passed": report.passed,
        "max_deviation": report.max_deviation,
        "tol": report.tol,
        "s": json_number(report.s),
        "is_similarity": report.is_similarity,
        "method": report.method,
        "scaled_dt": report.scaled_dt,
        "deviation": dict(report.deviation),
        "sensitivity": None if report.sensitivity is None else dict(report.sensitivity),
        "baseline_factor": report.baseline_factor,
        "exponents": _rationals(report.exponents),
        "exact": report.exact,
        "excited": report.excited,
        "ensemble": report.ensemble,
        "first_divergence": None if report.first_divergence is None else list(report.first_divergence),
        "causes": [_cause(c) for c in report.causes],
        "verdict": report.verdict,
        "horizon": report.horizon,
        "detection_limit": report.detection_limit,
        "inconclusive": report.inconclusive,
        "controls": [{"group": c.group, "error": c.error, "caught": c.caught} for c in report.controls],
        "scale_free": _scale_free(report.scale_free),
        "engine_reset": None if report.engine_reset is None else list(report.engine_reset),
    }


def _scale_free(free) -> dict | None:
    """The scale-free proof beside a verdict, or None."""
    if free is None:
        return None
    return {
        "settings": dict(free.settings),
        "exact": free.exact,
        "first_divergence": None if free.first_divergence is None else list(free.first_divergence),
    }


@_data("pitheorem.engines.paper.rod.EngineSimilarityReport")
def _engine_similarity_report(report) -> dict:
    ode = None if report.ode_report is None else report.ode_report.max_deviation
    return {
        "engine": report.engine,
        **_similarity_report(report),
        "dt": report.dt,
        "dt_scaled": report.dt_scaled,
        "engine_vs_ode": report.engine_vs_ode,
        "ode_max_deviation": ode,
    }


# -- sweeps ----------------------------------------------------------------------------------


@_data("pitheorem.engines.verdicts.sweep.SweepRow")
def _sweep_row(row) -> dict:
    return {
        "s": json_number(row.s),
        "verdict": row.verdict,
        "max_deviation": row.max_deviation,
        "yardstick": row.yardstick,
        "horizon": row.horizon,
        "excited": row.excited,
        "first_divergence": None if row.first_divergence is None else list(row.first_divergence),
        "causes": [_cause(c) for c in row.causes],
        "thresholds": list(row.thresholds),
    }


@_data("pitheorem.engines.verdicts.sweep.Sweep")
def _sweep(sweep) -> dict:
    return {
        "file": sweep.model,
        "engine": sweep.engine,
        "scaling": None if sweep.scaling is None else _scaling(sweep.scaling),
        "duration": sweep.duration,
        "baseline_factor": sweep.baseline_factor,
        "units": dict(sweep.units),
        "fitted_units": None if sweep.fitted_units is None else dict(sweep.fitted_units),
        "fitted_s": sweep.fitted_s,
        "rows": [_sweep_row(r) for r in sweep.rows],
    }


# -- unit fits -------------------------------------------------------------------------------


@_data("pitheorem.unitfit.RangeBound")
def _range_bound(bound) -> dict:
    return {"name": bound.name, "side": bound.side, "bound": json_number(bound.bound)}


@_data("pitheorem.unitfit.UnitFit")
def _unit_fit(fit) -> dict:
    return {
        "feasible": fit.feasible,
        "s": json_number(fit.s),
        "nice": fit.nice,
        "unit_change": _rationals(fit.unit_change),
        "factors": _numbers(fit.factors),
        "values": _numbers(fit.values),
        "scaled": _numbers(fit.scaled),
        "ranges": [{"name": n, "low": json_number(lo), "high": json_number(hi)} for n, lo, hi in fit.ranges],
        "satisfied": list(fit.satisfied),
        "violated": list(fit.violated),
        "worst_violation": fit.worst_violation,
        "conflict": [_range_bound(b) for b in fit.conflict],
        "fixed": list(fit.fixed),
        "fixed_units": list(fit.fixed_units),
        "exact": fit.exact,
    }


# -- engines ---------------------------------------------------------------------------------


@_data("pitheorem.engines.verdicts.causes.Cause")
def _cause(cause) -> dict:
    return {"kind": cause.kind, "element": cause.element, "detail": cause.detail, "restores": cause.restores}


@_data("pitheorem.engines.verdicts.audit.Audit")
def _audit(audit) -> dict:
    return {"s": audit.s, "compared": audit.compared, "causes": [_cause(c) for c in audit.causes]}


@_data("pitheorem.engines.constants.HiddenConstant")
def _hidden_constant(constant) -> dict:
    return {
        "engine": constant.engine,
        "name": constant.name,
        "dimension": render(constant.dimension, "text"),
        "default": constant.default,
        "where": constant.where,
        "source": constant.source,
        "note": constant.note,
    }


@_data("pitheorem.engines.rules.RuleVerdict")
def _rule_verdict(verdict) -> dict:
    def exponent(dimension):
        return rational_text(verdict.scaling.exponent_of(dimension))

    return {
        "rule": verdict.rule.name,
        "engine": verdict.rule.engine,
        "is_unit_change": verdict.is_unit_change,
        "complete": verdict.complete,
        "unit_change": None if verdict.unit_change is None else _rationals(verdict.unit_change),
        "certificate": None if verdict.certificate is None else _pi_group(verdict.certificate),
        "missing": [
            {"name": n, "dimension": render(d, "text"), "exponent": rational_text(p)} for n, d, p in verdict.missing
        ],
        "unchanged": list(verdict.unchanged),
        "broken": [
            {"name": c.name, "dimension": render(c.dimension, "text"), "exponent": exponent(c.dimension)}
            for c in verdict.broken
        ],
    }


def _parameters(name: str, model) -> dict:
    if not hasattr(model, "parameters"):  # a TOML model file: each variable with its role and description
        return {
            "model": name,
            "engine": None,
            "parameters": [
                {
                    "name": n,
                    "path": "",
                    "value": [json_number(v) for v in value],
                    "dimension": text,
                    "source": role,
                    "description": description,
                }
                for n, _, text, value, role, description in parameter_rows(model)
            ],
        }
    return {
        "model": name,
        "engine": model.engine,
        "parameters": [
            {
                "name": p.name,
                "path": p.path,
                "value": list(p.value),
                "dimension": p.dimension_text,
                "source": p.source,
                "settable": p.settable,
                "note": p.note,
            }
            for p in model.parameters
        ],
    }


@_data("pitheorem.engines.enginemodel.EngineModel")
def _engine_model(model) -> dict:
    return _parameters(model.path, model)


# -- the command line's answers --------------------------------------------------------------


@_data("pitheorem.answers.GroupsAnswer")
def _groups_answer(answer) -> dict:
    return {
        "model": answer.model,
        "variables": list(answer.system.variables),
        "rank": answer.system.rank,
        "repeating": list(answer.groups.repeating),
        "groups": [
            {**_pi_group(g), "value": json_number(v)} for g, v in zip(answer.groups, answer.values, strict=True)
        ],
    }


@_data("pitheorem.answers.BasesAnswer")
def _bases_answer(answer) -> dict:
    doc = {
        "model": answer.model,
        "rank": answer.rank,
        "exclude": list(answer.exclude),
        "require": list(answer.require),
        "count": answer.n_bases,
    }
    if answer.bases is not None:
        doc["bases"] = [list(b) for b in answer.bases]
    return doc


@_data("pitheorem.answers.SearchAnswer")
def _search_answer(answer) -> dict:
    return {"model": answer.model, **_search_result(answer.result, COMMAND_LINE_TIME_REMEDY)}


@_data("pitheorem.answers.ApplyAnswer")
def _apply_answer(answer) -> dict:
    return {
        "model": answer.model,
        "s": rational_text(answer.s),
        "solution": answer.solution,
        "count": answer.result.n_scalings,
        "scaling": _scaling(answer.scaling),
        "values": _numbers(answer.values),
        "scaled": _numbers(answer.scaled),
        "output": answer.output,
        "notes": [_note(note, COMMAND_LINE_TIME_REMEDY) for note in answer.result.notes],
    }


@_data("pitheorem.answers.ParamsAnswer")
def _params_answer(answer) -> dict:
    return _parameters(answer.model, answer.engine_model)


@_data("pitheorem.answers.EngineApplyAnswer")
def _engine_apply_answer(answer) -> dict:
    return {
        "model": answer.model,
        "s": rational_text(answer.s),
        "scaling": _scaling(answer.scaling),
        "parameters": answer.n_parameters,
        "changed": [
            {
                "name": name,
                "exponent": rational_text(p),
                "dimension": dim,
                "value": list(old),
                "scaled_value": list(new),
            }
            for name, p, dim, old, new in changed_rows(answer)
        ],
        "output": answer.output,
        "also_written": list(answer.also_written),
    }


@_data("pitheorem.answers.EngineVerifyAnswer")
def _engine_verify_answer(answer) -> dict:
    rep = answer.report
    return {
        "file": answer.model,
        "engine": answer.engine,
        "s": json_number(answer.s),
        "duration": answer.duration,
        "input": answer.input,
        "exact_expected": answer.exact_expected,
        "exact": rep.exact,
        "similar": rep.similar,
        "verdict": rep.verdict,
        "horizon": rep.horizon,
        "detection_limit": rep.detection_limit,
        "excited": rep.excited,
        "max_deviation": rep.max_deviation,
        "first_divergence": None if rep.first_divergence is None else list(rep.first_divergence),
        "causes": [_cause(c) for c in rep.causes],
        "scale_free": _scale_free(rep.scale_free),
        "engine_reset": None if rep.engine_reset is None else list(rep.engine_reset),
        "notes": list(answer.notes),
        "report": _similarity_report(rep),
    }


@_data("pitheorem.answers.SweepAnswer")
def _sweep_answer(answer) -> dict:
    return {
        "files": list(answer.model),
        "plots": list(answer.plots),
        "sweeps": [_sweep(sw) for sw in answer.sweeps],
    }


#: renderer of each value type, by qualified type name: its data, dumped
RENDERERS: dict = {name: (lambda value, data=data: dumps(data(value))) for name, data in DATA.items()}
