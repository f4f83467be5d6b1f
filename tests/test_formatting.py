"""The formatting home (pitheorem/formatting): every displayed value in every format, from one place.

* every value type a user sees renders in text, LaTeX, HTML and JSON, and each
  output is checked for what its format promises (JSON that reads back the exact
  numbers, LaTeX with balanced braces, well-formed HTML whose math is ``$...$``,
  text without ``Fraction(`` or sympy's internals);
* every public value type that displays itself takes ``__str__``, ``__format__``
  and its notebook hooks from :mod:`pitheorem.formatting`, and no class of the
  package builds its own text (errors aside: their messages live in errors.py);
* the shared pieces (powers of ``s``, roles, notes) against independent oracles.
"""

from __future__ import annotations

import importlib
import inspect
import json
import pkgutil
import re
import subprocess
import sys
from fractions import Fraction
from functools import cache
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem import formatting
from pitheorem.answers import (
    ApplyAnswer,
    BasesAnswer,
    EngineApplyAnswer,
    EngineVerifyAnswer,
    GroupsAnswer,
    ParamsAnswer,
    SearchAnswer,
    SweepAnswer,
)
from pitheorem.formatting import FORMATS, MathDisplay, TableDisplay, TextDisplay
from pitheorem.formatting.pieces import power_latex, power_text

engines = pytest.importorskip("pitheorem.engines")


ROD = pt.models.rod_system()


def _search(**request):
    return pt.search(ROD, **request)


def _projectile():
    proj = pt.models.projectile()
    return proj, pt.scaling_symmetries(proj.equations, proj.system)


def _dimension_reports():
    s = pt.System({"x": "L", "y": "L", "t": "T"})
    x, y, t = sympy.symbols("x y t")
    return {
        "ok": pt.check_dimensions(x + y, s),
        "bad": pt.check_dimensions(x + y + t, s),
        "tie": pt.check_dimensions(x + t, s),
    }


def _similarity(**options):
    smd = pt.models.spring_mass_damper()
    sc = pt.Scaling.from_unit_change(smd.system, {"L": 1, "T": 1})
    return pt.verify_similarity(smd, sc, s=3, t_final=0.2, **options)


@cache
def _engine_model():
    return engines.load(engines.example_path("pendulum.xml"))


def _apply_answer():
    res = _search(scale={"g": 1})
    sc = res.scalings[1]
    values = {"m": Fraction(3, 2), "l": 2.0, "g": 9.81}
    return ApplyAnswer("hinged rod", Fraction(3, 2), 2, res, sc, values, sc.apply(values, Fraction(3, 2)), "out.toml")


def _engine_apply_answer():
    model = _engine_model()
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    kept = [p for p in model.parameters if not p.mixed and sc.exponent_of(p.dimension)]
    changed = tuple((p.name, sc.exponent_of(p.dimension)) for p in kept)
    scaled = model.scaled(sc, 10)
    details = tuple((p.dimension_text, p.value, scaled.parameter(p.name).value) for p in kept)
    return EngineApplyAnswer(
        "pendulum.xml", Fraction(10), sc, changed, len(model.parameters), "p.xml", ("p.xml.settings.json",), details
    )


@cache
def _engine_verify_answer():
    import tempfile

    text = (Path(__file__).parent / "data" / "engines" / "contact.xml").read_text()
    with tempfile.TemporaryDirectory() as folder:  # PGS and its default stopping rule: not exact, causes named
        pgs = Path(folder) / "pgs.xml"
        pgs.write_text(text.replace('tolerance="0"', 'solver="PGS"'))
        model = engines.load(pgs)
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    rep = engines.verify(model, sc, 4, duration=0.4)
    return EngineVerifyAnswer("pgs.xml", "mujoco", Fraction(4), 0.4, "zero", True, rep)


def _sweep():
    model = _engine_model()
    sc = pt.search(model.system(), scale={"g": 1}).scalings[0]
    cause = engines.Cause("threshold", "body_arm_mass", "mujoco refuses the copy: mass & inertia < mjMINVAL")
    rows = (
        engines.SweepRow(1e-20, "refused", None, None, None, None, None, (cause,), ("mujoco_minval_mass",)),
        engines.SweepRow(Fraction(1, 4), "exact", 0.0, 5e-15, None, True, None, (), ()),
        engines.SweepRow(10.0**0.5, "similar", 2.5e-16, 5e-15, 1.5, True, (0.002, "hinge"), (), ()),
    )
    return engines.Sweep(model.path, "mujoco", sc, 0.2, rows, 10.0, model.units, {"M": "g", "L": "mm", "T": "s"}, 1e-3)


SAMPLES = {
    "dimension": lambda: pt.Dimension.parse("M L^2 T^-2"),
    "dimension_rational": lambda: pt.Dimension.parse("Theta L^(1/2) T^-1", base_dimensions=("L", "T", "Theta")),
    "dimensionless": lambda: pt.Dimension.parse("1"),
    "pi_group": lambda: ROD.pi_groups(repeating=("m", "l", "k_theta"))["c_theta"],
    "pi_group_unnamed": lambda: pt.PiGroup({"g": 2, "t": 2, "l": -2}),
    "pi_set": lambda: ROD.pi_groups(repeating=("m", "l", "k_theta")),
    "pi_set_empty": lambda: pt.System({"l": "L"}).pi_groups(),
    "scaling": lambda: _search(scale={"g": 1}).scalings[0],
    "scaling_rational": lambda: _search(scale={"g": Fraction(1, 2)}, fixed=()).scalings[0],
    "scaling_identity": lambda: pt.Scaling.from_unit_change(ROD, {}),
    "scaling_beyond_units": lambda: pt.search(
        _projectile()[0].system, scale={"x": 1}, fixed=("t", "g"), within=_projectile()[1]
    ).scalings[0],
    "note": lambda: _search(scale={"g": 1}).notes[0],
    "note_outside": lambda: pt.SearchNote("outside_equations", ("m", "k_theta")),
    "search": lambda: _search(scale={"g": 1}),
    "search_rational": lambda: _search(scale={"g": Fraction(1, 2), "l": -1}, fixed=("t",)),
    "search_infeasible": lambda: _search(scale={"g": 1}, fixed=("t", "m", "k_theta")),
    "search_within": lambda: pt.search(
        _projectile()[0].system, scale={"x": 1}, fixed=("t", "g"), within=_projectile()[1]
    ),
    "dimension_report": lambda: _dimension_reports()["ok"],
    "dimension_report_bad": lambda: _dimension_reports()["bad"],
    "dimension_report_tie": lambda: _dimension_reports()["tie"],
    "symmetry_report": lambda: _projectile()[1],
    "similarity_report": lambda: _similarity(),
    "similarity_report_baseline": lambda: _similarity(baseline=True),
    "unit_fit": lambda: pt.fit_units(
        pt.System({"l": "L", "m": "M", "t": "T"}), {"l": 500, "m": Fraction(1, 3), "t": 1}, ranges={"l": (0.05, 10)}
    ),
    "unit_fit_nice": lambda: pt.fit_units(
        pt.System({"l": "L", "m": "M"}), {"l": 500, "m": 2}, ranges={"l": (0.05, 10)}, nice=10
    ),
    "unit_fit_conflict": lambda: pt.fit_units(
        pt.System({"l": "L", "a": "L^2"}), {"l": 1, "a": 1000}, ranges={"l": (1, 2), "a": (1, 2)}
    ),
    "range_bound": lambda: pt.RangeBound("k_theta", "low", Fraction(-1, 20)),
    "hidden_constant": lambda: engines.hidden_constants("pybullet", names=["bullet_time_step"])[0],
    "rule_verdict": lambda: engines.check_rule(engines.BULLET_SCALE_THE_WORLD, ROD),
    "rule_verdict_no_units": lambda: engines.check_rule(
        engines.RuleOfThumb(
            "wrong",
            "pybullet",
            "made up",
            (
                engines.RuleQuantity("length", pt.Dimension.parse("L"), Fraction(1)),
                engines.RuleQuantity("time", pt.Dimension.parse("T"), Fraction(0)),
                engines.RuleQuantity("speed", pt.Dimension.parse("L T^-1"), Fraction(0)),
            ),
        )
    ),
    "engine_model": _engine_model,
    "cause": lambda: engines.Cause("contact", "geom 'foot' / geom 'floor'", "starts at step 3 (t = 0.006) & more"),
    "audit": lambda: engines.audit(
        _engine_model(), pt.search(_engine_model().system(), scale={"g": 1}).scalings[0], 10
    ),
    "engine_similarity_report": lambda: engines.verify_engine_similarity(
        "mujoco", pt.search(pt.models.hinged_rod().system, scale={"g": 1}).scalings[0], s=2, t_final=0.02
    ),
    "groups_answer": lambda: GroupsAnswer(
        "hinged rod",
        ROD,
        ROD.pi_groups(repeating=("m", "l", "k_theta")),
        (None, Fraction(1, 3), 0.2943, None, None, None),
    ),
    "bases_answer": lambda: BasesAnswer("hinged rod", 3, ("t",), ("m",), 2, [("m", "l", "g"), ("m", "l", "k_theta")]),
    "bases_answer_count": lambda: BasesAnswer("hinged rod", 3, (), (), 44, None),
    "search_answer": lambda: SearchAnswer("hinged rod", _search(scale={"g": 1})),
    "search_answer_infeasible": lambda: SearchAnswer(
        "hinged rod", _search(scale={"g": 1}, fixed=("t", "m", "k_theta"))
    ),
    "apply_answer": _apply_answer,
    "params_answer": lambda: ParamsAnswer("pendulum.xml", _engine_model()),
    "engine_apply_answer": _engine_apply_answer,
    "engine_verify_answer": _engine_verify_answer,
    "sweep": _sweep,
    "sweep_row": lambda: _sweep().rows[2],
    "sweep_answer": lambda: SweepAnswer(("a_&_b.xml", "c.xml"), (_sweep(), _sweep()), ("s.png",)),
}


@cache
def sample(name):
    return SAMPLES[name]()


def _qualified(cls) -> str:
    return f"{cls.__module__}.{cls.__qualname__}"


def _exact(x):
    """A number of a JSON document as the exact number it stands for (rationals are strings)."""
    assert isinstance(x, int | str), x
    assert not isinstance(x, bool), x
    return Fraction(x)


def _exact_map(doc: dict) -> dict:
    return {k: _exact(v) for k, v in doc.items()}


def _search_numbers(result, doc):
    assert _exact_map(doc["scale"]) == dict(result.scale)
    assert [_exact_map(sc["exponents"]) for sc in doc["scalings"]] == [sc.exponents for sc in result.scalings]
    if result.certificate is not None:
        assert doc["certificate"]["exponents"] == result.certificate.exponents
        assert _exact(doc["certificate"]["power"]) == result.certificate_power


def _value_numbers(values: dict, doc: dict):
    for name, value in values.items():
        read = doc[name]
        assert (read == value and type(read) is float) if isinstance(value, float) else _exact(read) == value


#: type name -> check that a JSON document gives back the value's exact numbers
JSON_NUMBERS = {
    "Dimension": lambda v, doc: _exact_map(doc["exponents"]) == v.exponents,
    "PiGroup": lambda v, doc: (
        doc["exponents"] == v.exponents and all(type(p) is int for p in doc["exponents"].values())
    ),
    "PiSet": lambda v, doc: [g["exponents"] for g in doc["groups"]] == [g.exponents for g in v],
    "Scaling": lambda v, doc: (
        _exact_map(doc["exponents"]) == v.exponents
        and (doc["unit_change"] is None) == (not v.is_unit_change)
        and (not v.is_unit_change or _exact_map(doc["unit_change"]) == v.unit_change)
    ),
    "SearchNote": lambda v, doc: (doc["kind"], tuple(doc["variables"])) == (v.kind, v.variables),
    "SearchResult": lambda v, doc: _search_numbers(v, doc) is None,
    "DimensionReport": lambda v, doc: pt.Dimension.parse(doc["dimension"]) == v.dimension,
    "SymmetryReport": lambda v, doc: [_exact_map(b) for b in doc["basis"]] == [dict(b) for b in v.basis],
    "SimilarityReport": lambda v, doc: (
        _exact_map(doc["exponents"]) == dict(v.exponents) and doc["max_deviation"] == v.max_deviation
    ),
    "EngineSimilarityReport": lambda v, doc: doc["dt"] == v.dt and _exact_map(doc["exponents"]) == dict(v.exponents),
    "UnitFit": lambda v, doc: (
        _exact_map(doc["unit_change"]) == dict(v.unit_change) and _value_numbers(v.values, doc["values"]) is None
    ),
    "RangeBound": lambda v, doc: _exact(doc["bound"]) == v.bound,
    "Cause": lambda v, doc: doc == {"kind": v.kind, "element": v.element, "detail": v.detail, "restores": v.restores},
    "Audit": lambda v, doc: doc["compared"] == v.compared and len(doc["causes"]) == len(v.causes),
    "HiddenConstant": lambda v, doc: pt.Dimension.parse(doc["dimension"]) == v.dimension,
    "RuleVerdict": lambda v, doc: (
        doc["unit_change"] is None if v.unit_change is None else _exact_map(doc["unit_change"]) == v.unit_change
    ),
    "EngineModel": lambda v, doc: [tuple(p["value"]) for p in doc["parameters"]] == [p.value for p in v.parameters],
    "GroupsAnswer": lambda v, doc: (
        [
            g["value"] if g["value"] is None or isinstance(g["value"], float) else _exact(g["value"])
            for g in doc["groups"]
        ]
        == list(v.values)
    ),
    "BasesAnswer": lambda v, doc: doc["count"] == v.n_bases,
    "SearchAnswer": lambda v, doc: _search_numbers(v.result, doc) is None,
    "ApplyAnswer": lambda v, doc: (
        _exact(doc["s"]) == v.s
        and _value_numbers(v.values, doc["values"]) is None
        and _value_numbers(v.scaled, doc["scaled"]) is None
    ),
    "ParamsAnswer": lambda v, doc: len(doc["parameters"]) == len(v.engine_model.parameters),
    "EngineApplyAnswer": lambda v, doc: [_exact(c["exponent"]) for c in doc["changed"]] == [p for _, p in v.changed],
    "Sweep": lambda v, doc: (
        [_exact(r["s"]) if isinstance(r["s"], int | str) else r["s"] for r in doc["rows"]] == list(v.s)
        and [r["max_deviation"] for r in doc["rows"]] == [r.max_deviation for r in v.rows]
        and _exact_map(doc["scaling"]["exponents"]) == v.scaling.exponents
    ),
    "SweepRow": lambda v, doc: doc["s"] == v.s and doc["thresholds"] == list(v.thresholds),
    "SweepAnswer": lambda v, doc: [len(sw["rows"]) for sw in doc["sweeps"]] == [len(sw.rows) for sw in v.sweeps],
    "EngineVerifyAnswer": lambda v, doc: (
        _exact(doc["s"]) == v.s
        and doc["exact"] is v.report.exact
        and doc["max_deviation"] == v.report.max_deviation
        and [c["kind"] for c in doc["causes"]] == [c.kind for c in v.report.causes]
        and doc["report"]["causes"] == doc["causes"]
    ),
}


#: sympy's internals that must never reach a user's text
SYMPY_NOISE = re.compile(r"\b(Symbol|Rational|Integer|Mul|Pow|Add|Float|Function|Derivative)\(")


def balanced_braces(latex: str) -> bool:
    depth = 0
    for c in latex.replace("\\\\", "").replace(r"\{", "").replace(r"\}", ""):
        depth += {"{": 1, "}": -1}.get(c, 0)
        if depth < 0:
            return False
    return depth == 0


class _WellFormed(HTMLParser):
    """Every element closed in order; the text outside the tags collected."""

    VOID = frozenset({"br", "hr", "img", "input", "meta", "wbr", "col"})

    def __init__(self, html: str):
        super().__init__(convert_charrefs=True)
        self.open, self.errors, self.text = [], [], []
        self.feed(html)
        self.close()

    def handle_starttag(self, tag, attrs):
        if tag not in self.VOID:
            self.open.append(tag)

    def handle_endtag(self, tag):
        if not self.open or self.open.pop() != tag:
            self.errors.append(tag)

    def handle_data(self, data):
        self.text.append(data)


def math_of(html: str) -> list[str]:
    """The LaTeX between ``$`` signs in the text of an HTML fragment (raises when it is not well formed)."""
    parsed = _WellFormed(html)
    assert not parsed.errors, parsed.errors
    assert not parsed.open, parsed.open
    text = "".join(parsed.text)
    assert text.count("$") % 2 == 0, text
    return text.split("$")[1::2]


def test_every_renderer_has_a_sample_and_every_format_renders_every_type():
    renderers = {name: importlib.import_module(f"pitheorem.formatting.{name}").RENDERERS for name in FORMATS}
    keys = set().union(*renderers.values())
    assert {_qualified(type(sample(name))) for name in SAMPLES} == keys
    for qualified in keys:  # each key names a real class, one that displays through the home
        module, _, name = qualified.rpartition(".")
        cls = getattr(importlib.import_module(module), name)
        assert cls.__str__ is TextDisplay.__str__, qualified
        assert cls.__format__ is TextDisplay.__format__, qualified
        for fmt, table in renderers.items():  # its own renderer, or its parent's (a report's engine variant)
            assert any(_qualified(k) in table for k in cls.__mro__), (qualified, fmt)


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("name", sorted(SAMPLES))
def test_every_value_renders_in_every_format(name, fmt):
    value = sample(name)
    out = format(value, fmt)
    assert isinstance(out, str)
    assert out.strip()
    assert out == f"{value:{fmt}}" == formatting.render(value, fmt)
    assert "Fraction(" not in out
    assert f"{type(value).__name__}(" not in out  # no repr slipped in
    if fmt == "text":
        assert out == str(value) == format(value, "")
        assert not SYMPY_NOISE.search(out), out
    elif fmt == "latex":
        assert balanced_braces(out), out
        assert not SYMPY_NOISE.search(out), out
    elif fmt == "html":
        math = math_of(out)
        assert all(balanced_braces(m) for m in math), math
        if isinstance(value, MathDisplay | TableDisplay):
            assert math, f"{name}: no $...$ math in its HTML"
        assert "\\(" not in out
    else:
        doc = json.loads(out)
        assert isinstance(doc, dict)
        assert JSON_NUMBERS[type(value).__name__](value, doc) is not False, doc
        assert out == json.dumps(doc, indent=2, ensure_ascii=False)  # one layout, keys in a fixed order


@pytest.mark.parametrize("name", sorted(SAMPLES))
def test_a_bad_spec_names_itself_and_the_formats(name):
    value = sample(name)
    for spec in ("yaml", "LaTeX", ">10"):
        with pytest.raises(pt.InvalidRequestError) as caught:
            format(value, spec)
        assert isinstance(caught.value, ValueError)
        assert repr(spec) in str(caught.value)
        assert all(f in str(caught.value) for f in FORMATS)
        assert caught.value.culprit == spec


@pytest.mark.parametrize("name", sorted(SAMPLES))
def test_notebook_hooks_by_kind(name):
    value = sample(name)
    if isinstance(value, MathDisplay):
        latex = value._repr_latex_()
        assert latex == f"$\\displaystyle {format(value, 'latex')}$"
        assert not hasattr(value, "_repr_html_")  # myst-nb would rank it above the LaTeX
    else:
        assert not hasattr(value, "_repr_latex_")
    if isinstance(value, TableDisplay):
        assert value._repr_html_() == format(value, "html")
        assert (
            "<table" in value._repr_html_()
            or not getattr(value, "feasible", True)
            or isinstance(value, pt.DimensionReport | pt.SymmetryReport)
        )


#: public classes that do not display as values, by kind, with the reason
NOT_DISPLAYED = {
    BaseException: "errors and warnings say what is wrong in their message, which errors.py builds: no display",
}


_HOOKS = ("__str__", "__format__", "_repr_latex_", "_repr_html_")


def _owner(cls, hook):
    return next((k for k in cls.__mro__ if hook in vars(k)), None)


def _public_classes():
    for module in (pt, engines):
        for name in module.__all__:
            value = getattr(module, name)
            if inspect.isclass(value):
                yield f"{module.__name__}.{name}", value


@pytest.mark.parametrize(("name", "cls"), list(_public_classes()), ids=lambda x: x if isinstance(x, str) else "")
def test_every_public_value_type_that_displays_gets_it_from_the_formatting_home(name, cls):
    if any(issubclass(cls, kind) for kind in NOT_DISPLAYED):
        return
    for hook in _HOOKS:
        owner = _owner(cls, hook)
        if owner is None or owner is object:
            continue
        assert owner.__module__ == formatting.__name__, f"{name}.{hook} is built in {owner.__module__}"
    if _owner(cls, "__str__") is not object:
        assert issubclass(cls, TextDisplay)
        assert cls.__format__ is TextDisplay.__format__


def test_no_class_of_the_package_builds_its_own_display():
    import pitheorem

    offenders = []
    for info in pkgutil.walk_packages(pitheorem.__path__, "pitheorem."):
        if info.name.startswith("pitheorem.formatting"):
            continue
        module = importlib.import_module(info.name)
        for cls in vars(module).values():
            if not inspect.isclass(cls) or cls.__module__ != module.__name__ or issubclass(cls, BaseException):
                continue
            for hook in _HOOKS:
                own = vars(cls).get(hook)
                if own is not None and getattr(own, "__module__", None) != formatting.__name__:
                    offenders.append(f"{module.__name__}.{cls.__qualname__}.{hook}")
    assert offenders == []


def test_a_format_loads_on_first_use_and_alone():
    code = (
        "import sys, pitheorem as pt\n"
        "def loaded(): return sorted(m[21:] for m in sys.modules if m.startswith('pitheorem.formatting.'))\n"
        "dim = pt.Dimension.parse('L'); print(loaded()); str(dim); print(loaded())"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.splitlines() == ["[]", "['pieces', 'text']"]


exponents = st.fractions(min_value=-12, max_value=12, max_denominator=6)


def _read_power_text(text: str) -> Fraction:
    if text == "-":
        return Fraction(0)
    sign, body = (-1, text[2:]) if text.startswith("1/") else (1, text)
    if body == "s":
        return Fraction(sign)
    assert body.startswith("s^"), text
    power = body[2:]
    return sign * Fraction(power[1:-1] if power.startswith("(") else power)


def _read_power_latex(latex: str) -> Fraction:
    if latex in ("1", "-"):  # "-" is the unchanged mark of a table cell, as in plain text
        return Fraction(0)
    if latex == "s":
        return Fraction(1)
    match = re.fullmatch(r"s\^\{(-?\d+(?:/\d+)?)\}", latex)
    assert match, latex
    return Fraction(match.group(1))


@given(exponents)
def test_powers_of_s_read_back_as_their_exponent(p):
    assert _read_power_text(power_text(p)) == p
    assert _read_power_latex(power_latex(p)) == p


@pytest.mark.parametrize(
    "request_",
    [
        {"scale": {"g": 1}},
        {"scale": {"g": 1, "l": -1}, "fixed": ("m", "k_theta")},
        {"scale": {"g": 1}, "allow": ("l", "m", "F")},
    ],
)
def test_roles_in_every_table_follow_the_request(request_):
    res = pt.search(ROD, **request_)
    scale, fixed = set(request_["scale"]), set(res.fixed)
    oracle = {n: "scale" if n in scale else "fixed" if n in fixed else "free" for n in ROD.variables}
    assert res.roles == oracle
    text_rows = [line.split()[:2] for line in res.table().splitlines()[1 : len(ROD.variables) + 1]]
    assert dict(text_rows) == oracle
    latex_rows = [line.split(" & ")[:2] for line in format(res, "latex").splitlines()[2 : len(ROD.variables) + 2]]
    assert [role for _, role in latex_rows] == list(oracle.values())
    assert re.findall(r"<em>(\w+)</em>", format(res, "html"))[: len(ROD.variables)] == list(oracle.values())


def test_every_table_cell_is_the_power_of_its_scaling():
    res = pt.search(ROD, scale={"l": Fraction(1, 2)}, fixed=("t", "m"))
    (sc,) = res.scalings
    assert sc.exponents["k_theta"] == 1
    assert sc.exponents["F"] == Fraction(1, 2)
    latex = format(res, "latex").splitlines()[2 : len(ROD.variables) + 2]
    assert [_read_power_latex(row.split(" & ")[2].removesuffix(r" \\").strip("$")) for row in latex] == list(sc.vector)
    cells = re.findall(r"<td[^>]*>([^<]*)</td>", format(res, "html"))
    html_powers = [_read_power_latex(c.strip("$")) for c in cells if c.startswith(("$s", "-"))]
    assert html_powers[: len(ROD.variables)] == list(sc.vector)
    doc = json.loads(format(res, "json"))
    assert _exact_map(doc["scalings"][0]["unit_change"]) == sc.unit_change


def test_group_and_set_display(rod):
    pi_g = rod.pi_groups(repeating=("m", "l", "k_theta"))["g"]
    assert str(pi_g) == "Pi_g = g*l*m/k_theta"
    assert pi_g._repr_latex_().startswith("$\\displaystyle \\Pi_{g} =")
    text = rod.pi_groups(repeating=("m", "l", "k_theta"))._repr_latex_()
    assert text.count("&=") == 6
    assert "aligned" in text
    assert format(pt.PiGroup({"t": 1}), "latex") == r"\Pi = t"


def test_dimension_latex_names_theta():
    assert pt.Dimension.parse("Theta").latex == r"\Theta"
    assert format(pt.Dimension.parse("M L^2 T^-2"), "latex") == r"\mathsf{M}\,\mathsf{L}^{2}\,\mathsf{T}^{-2}"
    assert format(pt.Dimension.parse("L^(1/2)"), "latex") == r"\mathsf{L}^{1/2}"


def test_scaling_latex_writes_powers_of_s():
    sc = pt.search(ROD, scale={"g": 1}).scalings[0]  # m -> m/s^2, l -> s l, g -> s g, F -> F/s
    assert format(sc, "latex") == r"m \to s^{-2}\,m,\quad l \to s\,l,\quad g \to s\,g,\quad F \to s^{-1}\,F"
    assert sc._repr_latex_().startswith("$\\displaystyle m \\to s^{-2}")


def test_search_html_table_and_notes(rod):
    res = pt.search(rod, scale={"g": 1})
    html = res._repr_html_()
    assert html.count("<tr>") == len(rod.variables) + 1
    assert "pass <code>fixed=()</code> to let time change" in html
    infeasible = pt.search(rod, scale={"g": 1}, fixed=("t", "m", "k_theta"))
    assert "<table" not in infeasible._repr_html_()
    assert r"$\Pi = \frac{g^{2} m t^{2}}{k_{\theta}}$" in infeasible._repr_html_()


def test_search_text_of_an_impossible_request_ends_with_its_certificate(rod):
    res = pt.search(rod, scale={"g": 1}, fixed=("t", "m", "k_theta"))
    assert str(res).splitlines()[-1] == "certificate: Pi = g**2*m*t**2/k_theta (the request multiplies it by s^2)"


def test_reports_print():
    s = pt.System({"x": "L", "y": "L", "t": "T"})
    x, y = sympy.symbols("x y")
    assert str(pt.check_dimensions(x + y, s)) == "consistent: dimension L"
    proj = pt.models.projectile()
    text = str(pt.scaling_symmetries(proj.equations, proj.system))
    assert "beyond changes of units" in text
    assert "x: 1, vx: 1" in text
    assert str(pt.RangeBound("x", "high", Fraction(3))) == "x <= 3"
    assert format(pt.RangeBound("x", "low", Fraction(1, 20)), "latex") == r"x \geq \frac{1}{20}"


def test_search_notes_are_phrased_by_each_front_end():
    note = pt.SearchNote("time_fixed", ("t",))
    assert format(note, "latex").endswith(r"\texttt{t} is held fixed by default; pass fixed=() to let time change")
    assert json.loads(format(note, "json"))["text"] == str(note)
    answer = SearchAnswer("rod", pt.search(ROD, scale={"g": 1}))
    assert json.loads(format(answer, "json"))["notes"][0]["text"].endswith(
        "give --fixed with no names to let time change"
    )
    assert "give <code>--fixed</code> with no names" in format(answer, "html")


def _plain(html: str) -> str:
    """HTML without its inline styles, easier to read in a test."""
    return re.sub(r' style="[^"]*"', "", html)


def test_align_a_lone_header():
    from pitheorem.formatting.pieces import align

    assert align([["name", "value"]]) == "name  value"
    assert align([["a", "bb"], ["ccc", ""]]) == "a    bb\nccc"


def test_dimension_text_writes_every_power():
    dim = pt.Dimension.parse("M L^2 T^-2 Theta^(1/2) I^(-1/3)")
    assert str(dim) == "M L^2 T^-2 Theta^(1/2) I^(-1/3)"
    assert format(dim, "latex") == r"\mathsf{M}\,\mathsf{L}^{2}\,\mathsf{T}^{-2}\,\Theta^{1/2}\,\mathsf{I}^{-1/3}"
    assert json.loads(format(dim, "json")) == {
        "dimension": str(dim),
        "exponents": {"M": "1", "L": "2", "T": "-2", "Theta": "1/2", "I": "-1/3"},
    }


def test_search_of_a_family_in_latex_and_html():
    res = pt.search(pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"}), scale={"g": 1}, fixed=())
    assert format(res, "latex") == "\n".join(
        [
            r"\begin{tabular}{llcc}",
            r"variable & role & \#1 & \#2 \\ \hline",
            r"$m$ & free & - & - \\",
            r"$l$ & free & $s$ & - \\",
            r"$g$ & scale & $s$ & $s$ \\",
            r"$t$ & free & - & $s^{-1/2}$ \\",
            r"\hline",
            r"$[\mathrm{M}]$ & base unit & - & - \\",
            r"$[\mathrm{L}]$ & base unit & $s$ & - \\",
            r"$[\mathrm{T}]$ & base unit & - & $s^{-1/2}$ \\",
            r"\end{tabular}",
        ]
    )
    html = _plain(format(res, "html"))
    assert html.startswith(
        "<p>Scaling g by s: 2 minimal solutions of a 2-parameter family.</p><table>"
        "<tr><th>variable</th><th>role</th><th>#1</th><th>#2</th></tr>"
        "<tr><th>$m$</th><td><em>free</em></td><td>-</td><td>-</td></tr>"
    )
    assert html.endswith(
        '<tr class="base-unit"><th>$[\\mathrm{T}]$</th><td><em>base unit</em></td>'
        "<td>-</td><td>$s^{-1/2}$</td></tr></table>"
    )


def test_unit_fit_in_text_latex_and_html():
    fit = pt.fit_units(pt.System({"l": "L", "m": "M", "t": "T"}), {"l": 500, "t": 2}, ranges={"l": (1, 10)}, nice=10)
    assert str(fit) == "\n".join(
        [
            "unit fit (factors rounded to powers of 10): every value in range",
            "  M: readings x 1 (10^0), new unit = 1 old units",
            "  L: readings x 0.01 (10^-2), new unit = 100 old units",
            "  T: readings x 1 (10^0), new unit = 1 old units",
            "         l          500 ->            5   in [1, 10]  ok",
            "         t            2 ->            2",
        ]
    )
    latex = format(fit, "latex")
    assert r"$\mathsf{L}$ & 0.01 & 100 \\" in latex
    assert r"$l$ & 500 & 5 & [1, 10] & ok \\" in latex
    assert r"$t$ & 2 & 2 &  &  \\" in latex
    html = _plain(format(fit, "html"))
    assert "<tr><th>$\\mathsf{L}$</th><td>0.01</td><td>100</td></tr>" in html
    assert "<tr><th>$l$</th><td>500</td><td>5</td><td>[1, 10]</td><td>ok</td></tr>" in html
    assert "$m$" not in html  # no value given: not listed


def test_symmetries_and_a_tie_in_latex_and_html():
    proj = pt.models.projectile()
    sym = pt.scaling_symmetries(proj.equations, proj.system)
    assert format(sym, "latex").endswith(
        "\n".join(
            [
                "symmetries beyond changes of units:",
                "",
                r"\begin{tabular}{cccccc}",
                r"$g$ & $t$ & $x$ & $y$ & $vx$ & $vy$ \\ \hline",
                r"$0$ & $0$ & $1$ & $0$ & $1$ & $0$ \\",
                r"\end{tabular}",
            ]
        )
    )
    assert _plain(format(sym, "html")).endswith(
        "<tr><th>#1</th><td>$0$</td><td>$0$</td><td>$1$</td><td>$0$</td><td>$1$</td><td>$0$</td></tr></table>"
    )
    x, t = sympy.symbols("x t")
    tie = pt.check_dimensions(x + t, pt.System({"x": "L", "t": "T"}))
    assert format(tie, "latex") == "\n".join(
        [
            "inconsistent: 2 offending term(s)",
            "",
            r"\begin{tabular}{lll}",
            r"term & dimension & expected \\ \hline",
            r"$t$ & $\mathsf{T}$ & $\mathsf{L}$ \\",
            r"$x$ & $\mathsf{L}$ & $\mathsf{T}$ \\",
            r"\end{tabular}",
            "",
            "tie: in t + x, T and L have 1 term(s) each: no majority says which is wrong, so all are listed",
        ]
    )


def test_rule_verdict_text():
    verdict = engines.check_rule(
        engines.BULLET_SCALE_THE_WORLD,
        pt.System({"m": "M", "c": "M L^2 T^-1", "t": "T"}),
        hidden=["bullet_contact_slop"],
    )
    assert str(verdict) == "\n".join(
        [
            "Bullet wiki: Scaling The World:",
            "  a change of units: readings of L by X^1",
            "  not named: c [M L^2 T^-1] must scale by X^2",
            "  not named, rightly unchanged: t",
            "  hidden constant left out: bullet_contact_slop [L] (default 1e-05) must scale by X^1",
        ]
    )
    assert format(verdict, "latex").splitlines()[:3] == [
        r"\textbf{Bullet wiki: Scaling The World:}",
        r"\begin{itemize}",
        r"\item a change of units: readings of L by X\^{}1",
    ]
    nothing = engines.check_rule(
        engines.RuleOfThumb("still", "pybullet", "", (engines.RuleQuantity("length", "L", 0),))
    )
    assert str(nothing).splitlines()[1] == "  a change of units: readings of nothing"


def test_similarity_reports_add_the_sensitivity_column_when_measured():
    plain, judged = sample("similarity_report"), sample("similarity_report_baseline")
    assert r"\begin{tabular}{lr}" in format(plain, "latex")
    assert r"\begin{tabular}{lrr}" in format(judged, "latex")
    assert "one-ulp sensitivity" in format(judged, "html")
    assert "one-ulp sensitivity" not in format(plain, "html")
    assert json.loads(format(judged, "json"))["sensitivity"] == dict(judged.sensitivity)
    assert json.loads(format(plain, "json"))["sensitivity"] is None


def test_engine_model_names_its_file_or_says_it_is_unsaved():
    model = _engine_model()
    sources = [p.source for p in model.parameters]
    counts = ", ".join(f"{sources.count(s)} {s}" for s in ("file", "default", "derived", "engine") if s in sources)
    head = f"{model.path}: mujoco model, {len(model.parameters)} parameters (source: {counts})"
    assert str(model).splitlines()[0] == head
    assert set(sources) <= {"file", "default", "derived", "engine"}  # so the counts above cover every parameter
    assert format(model, "latex").splitlines()[0] == f"% {head}"
    copy = model.with_values(tolerance=0)
    assert str(copy).startswith("(unsaved): mujoco model")
    assert format(copy, "latex").startswith("% (unsaved): mujoco model")


def test_answers_of_the_command_line():
    bases = sample("bases_answer")
    assert (
        str(bases) == "hinged rod: 2 valid repeating sets of 3 variables (without t; with m)\n1  m l g\n2  m l k_theta"
    )
    assert format(bases, "latex") == "\n".join(
        [r"\begin{tabular}{rl}", r"1 & $m, l, g$ \\", r"2 & $m, l, k_{\theta}$ \\", r"\end{tabular}"]
    )
    assert _plain(format(bases, "html")).endswith(
        "<tr><th>1</th><td>$m, l, g$</td></tr><tr><th>2</th><td>$m, l, k_{\\theta}$</td></tr></table>"
    )
    assert _plain(format(bases, "html")).startswith(f"<p>{str(bases).splitlines()[0]}</p>")
    applied = sample("engine_apply_answer")
    assert len(applied.changed) > 8
    lines = str(applied).splitlines()
    assert lines[1] == f"{len(applied.changed)} of {applied.n_parameters} parameters change, by dimension:"
    # the summary: one row per dimension, whose counts add up to every changed parameter
    summary = lines[3 : lines.index("")]
    count_at = lines[2].index("count")  # the summary's columns are aligned under its header
    assert sum(int(line[count_at:].split()[0]) for line in summary) == len(applied.changed)
    table = lines[lines.index("") + 2 : -2]  # then every changed parameter with its factor, value and scaled value
    assert [row.split()[:2] for row in table] == [[name, power_text(p)] for name, p in applied.changed]
    g_row = next(row.split() for row in table if row.split()[0] == "g")
    assert g_row[2:] == ["9.81", "98.1"]
    assert lines[-2:] == ["", "wrote p.xml (and p.xml.settings.json)"]
    changed = json.loads(format(applied, "json"))["changed"]
    assert len(changed) == len(applied.changed)  # all of them
    assert next(c for c in changed if c["name"] == "g")["value"] == [9.81]


def test_json_counts_no_scaling_for_an_impossible_request_and_keeps_unicode():
    assert json.loads(format(sample("search_infeasible"), "json"))["count"] == 0
    group = pt.System({"θ": "1", "l": "L"}).pi_groups()[0]
    assert '"name": "Pi_θ"' in format(group, "json")


def test_scaling_text_divides_by_negative_powers():
    assert str(sample("scaling")) == "m -> m/s^2, l -> s l, g -> s g, F -> F/s"
    assert str(sample("scaling_rational")).startswith("m -> m/s, l -> s^(1/2) l")


def test_report_texts_name_what_was_measured():
    judged = sample("similarity_report_baseline")
    assert f"(the largest {max(judged.sensitivity.values()):.3g})" in str(judged)
    engine = sample("engine_similarity_report")
    assert f"; pure ODE: {engine.ode_report.max_deviation:.3g}" in str(engine)
    assert str(engine).endswith(f"; engine vs exact ODE: {engine.engine_vs_ode:.3g}")
    assert json.loads(format(engine, "json"))["ode_max_deviation"] == engine.ode_report.max_deviation


def test_answers_in_latex_and_html():
    applied = sample("apply_answer")  # m -> m/s, with s = 3/2: 3/2 becomes 1
    assert r"$m$ & $s^{-1}$ & $\frac{3}{2}$ & 1 \\" in format(applied, "latex").splitlines()
    groups = _plain(format(sample("groups_answer"), "html"))
    assert r"<p>repeating variables: $m$, $l$, $k_{\theta}$</p><table>" in groups
    assert "<tr><th>$\\Pi_{g}$</th><td>$\\frac{g l m}{k_{\\theta}}$</td><td>1/3</td></tr>" in groups
    model = _engine_model()
    assert _plain(format(model, "html")).startswith(f"<p>{model.path}: mujoco model, ")
    html = format(sample("search"), "html")
    rows = html.split("<tr")
    assert [i for i, row in enumerate(rows) if "border-top" in row] == [len(ROD.variables) + 2]  # the first base row


def test_search_table_heads_the_minimal_scalings(rod):
    table = pt.search(rod, scale={"g": 1}).table().splitlines()
    assert table[0].split() == ["variable", "role", "#1", "#2", "#3"]
    assert table[1].split() == ["m", "free", "1/s^2", "1/s", "-"]


@pytest.mark.parametrize(
    ("model", "request_"),
    [("rod", {"scale": {"g": 1}}), ("superball", {"scale": {"l": 1}, "fixed": ("t", "m")})],
)
def test_table_base_unit_rows_explain_every_column(rod, model, request_):
    system = rod if model == "rod" else pt.models.superball_parameters()
    res = pt.search(system, **request_)
    rows = [line.split() for line in res.table().splitlines()[1:]]
    base = {r[0][1:-1]: [_read_power_text(c) for c in r[2:]] for r in rows if r[1] == "base"}
    variables = {r[0]: [_read_power_text(c) for c in r[2:]] for r in rows if r[1] != "base"}
    assert sorted(base) == sorted(system.base_dimensions)
    assert list(variables) == list(system.variables)
    # each variable's power is its dimension applied to the column's change of base units
    for name, powers in variables.items():
        dim = system.dimension(name)
        for k, power in enumerate(powers):
            assert power == sum(dim.exponent_of(b) * base[b][k] for b in base)
    html = res._repr_html_()
    assert html.count('<tr class="base-unit"') == len(system.base_dimensions)


def test_table_of_symmetries_beyond_units_says_they_have_no_unit_change():
    proj = pt.models.projectile()
    sym = pt.scaling_symmetries(proj.equations, proj.system)
    res = pt.search(proj.system, scale={"x": 1}, fixed=("t", "g"), within=sym)
    rows = [line.split() for line in res.table().splitlines()]
    base = [r for r in rows if r[1] == "base"]
    assert [r[0] for r in base] == [f"[{b}]" for b in proj.system.base_dimensions]
    assert all(r[2:] == ["n/a"] for r in base)
    assert "n/a: that scaling is a symmetry of the equations, not a change of units" in res.table()
    assert res._repr_html_().count(">n/a</td>") == len(proj.system.base_dimensions)


def test_html_without_symmetries_beyond_units_or_groups_has_no_table():
    smd = pt.models.spring_mass_damper()
    sym = pt.scaling_symmetries(smd.equations, smd.system)
    assert sym.beyond_units == ()
    html = _plain(format(sym, "html"))
    assert "<table" not in html
    assert html.endswith("<p>no symmetries beyond changes of units</p>")
    lone = pt.System({"l": "L"})
    answer = GroupsAnswer("a rod's length", lone, lone.pi_groups(), ())
    html = _plain(format(answer, "html"))
    assert "<table" not in html
    assert html.endswith("<p>repeating variables: $l$</p>")


# -- numbers in messages ---------------------------------------------------------------------


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_float_text_reads_back_as_the_same_float_and_is_never_longer_than_repr(x):
    from pitheorem.formatting.pieces import float_text

    text = float_text(x)
    assert float(text) == x  # only the printing is shortened, never the value
    assert len(text) <= len(repr(x))
    assert not text.endswith(".0")


@given(st.floats(width=32, allow_nan=False, allow_infinity=False))
def test_float_text_of_a_float32_reads_back_as_that_float32(x):
    from pitheorem.formatting.pieces import float_text

    value = np.float32(x)
    assert np.float32(float_text(value)) == value
    assert len(float_text(value)) <= len(repr(float(value)))


def test_float_text_writes_the_shortest_decimal_not_seventeen_digits():
    from pitheorem.formatting.pieces import float_text

    assert f"{0.004:.17g}" == "0.0040000000000000001"  # what the causes printed before
    assert float_text(0.004) == "0.004"
    assert float_text(200.0) == "200"
    assert float_text(199.99999999999994) == "199.99999999999994"  # another number: never rounded to 200
    assert float_text(1e10) == "1e+10"
    assert float_text(123456789.0) == "123456789"
    assert float_text(-0.0) == "-0"
    assert float_text(Fraction(-3, 4)) == "-3/4"
    assert float_text(np.float32(1e-5)) == "1e-05"
