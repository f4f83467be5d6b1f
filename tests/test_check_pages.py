"""Tests of docs/check_pages.py, the CI check of what readers see, on small hand-written pages.

Not a module of pitheorem: the docs tooling (``docs/check_pages.py``).
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

_spec = importlib.util.spec_from_file_location(
    "check_pages", Path(__file__).resolve().parent.parent / "docs" / "check_pages.py"
)
check_pages = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(check_pages)

PNG_A = b"\x89PNG first figure"
PNG_B = b"\x89PNG second figure"


def _cell(*images: str, text: str = "") -> str:
    imgs = "".join(f'<img alt="" src="_images/{name}" />' for name in images)
    pre = f'<div class="output"><pre>{text}</pre></div>' if text else ""
    return (
        '<div class="cell docutils container"><div class="cell_input"><pre>x</pre></div>'
        f'<div class="cell_output docutils container">{imgs}{pre}</div></div>'
    )


@pytest.fixture
def site(tmp_path):
    (tmp_path / "_images").mkdir()
    (tmp_path / "_images" / "a.png").write_bytes(PNG_A)
    (tmp_path / "_images" / "b.png").write_bytes(PNG_B)
    (tmp_path / "_images" / "a_copy.png").write_bytes(PNG_A)
    return tmp_path


def _problems(site, body: str) -> list[str]:
    page = site / "page.html"
    page.write_text(f"<html><body>{body}</body></html>", encoding="utf-8")
    return check_pages.check_page(page, site)


def test_two_figures_in_one_cell_pass(site):
    assert _problems(site, _cell("a.png", "b.png")) == []


def test_same_figure_twice_in_one_cell_fails(site):
    found = _problems(site, _cell("a.png", "a.png"))
    assert len(found) == 1
    assert "same figure twice" in found[0]


def test_same_figure_under_two_names_in_one_cell_fails(site):
    # identical bytes are the same figure, whatever the file is called
    assert any("same figure twice" in p for p in _problems(site, _cell("a.png", "a_copy.png")))


def test_same_figure_in_two_cells_passes(site):
    # two cells may show the same picture on purpose; only a repeat within one cell is an accident
    assert _problems(site, _cell("a.png") + _cell("a.png")) == []


def test_line_at_the_limit_passes_and_one_longer_fails(site):
    limit = check_pages.MAX_LINE
    assert _problems(site, _cell(text="x" * limit + "\nshort")) == []
    found = _problems(site, _cell(text="short\n" + "y" * (limit + 1)))
    assert len(found) == 1
    assert f"{limit + 1} characters" in found[0]


def test_long_line_in_a_code_block_outside_cells_fails(site):
    body = f'<div class="highlight"><pre>{"z" * (check_pages.MAX_LINE + 5)}</pre></div>'
    assert len(_problems(site, body)) == 1


def test_entities_count_as_one_character(site):
    # a line of MAX_LINE characters written with HTML entities is still MAX_LINE characters
    assert _problems(site, _cell(text="&lt;" * check_pages.MAX_LINE)) == []


def test_main_reports_and_fails(site, capsys):
    (site / "page.html").write_text(_cell("b.png", "b.png"), encoding="utf-8")
    assert check_pages.main([str(site)]) == 1
    assert "same figure twice" in capsys.readouterr().out


@pytest.mark.parametrize(
    "path",
    [
        "/root/.cache/x.xml",
        "/usr/lib/python3/dist-packages/x.xml",
        "/opt/venv/lib/python3.12/site-packages/gymnasium/envs/mujoco/assets/ant.xml",
        "/work/checkout/pitheorem/examples/pendulum.xml",
        "/tmp/tmpab12cd/fly_mm.xml",
    ],
)
def test_a_machine_path_anywhere_on_a_page_fails(site, path):
    # in a cell's output, in prose and in a code block alike
    for body in (_cell(text=f"wrote {path}"), f"<p>see {path}</p>", f"<pre>open({path!r})</pre>"):
        found = _problems(site, body)
        assert len(found) == 1, body
        assert "machine's path" in found[0]


def test_a_file_named_by_its_name_or_example_name_passes(site):
    assert _problems(site, _cell(text="wrote fly_mm.xml\nexample:pendulum.xml: mujoco model")) == []


@pytest.mark.parametrize(
    "output",
    [
        "{'M': '0', 'L': '1', 'T': '0'}",
        "unit change: {'M': Fraction(0, 1), 'L': Fraction(1, 1)}",
        "Fraction(1, 2)",
        "[Fraction(-1, 2), Fraction(1, 3)]",
        "exponent = Fraction(3, 4)",
        "System({'m': 'M', 'l': 'L'})",
    ],
)
def test_a_raw_dict_or_fraction_repr_in_a_cell_output_fails(site, output):
    found = _problems(site, _cell(text=output))
    assert len(found) == 1
    assert "raw repr" in found[0]


@pytest.mark.parametrize(
    "output",
    [
        "M: s^0  L: s^1  T: s^0",
        '{"m": "-2", "l": "1"}',  # JSON, which a page may show on purpose
        "pass an exact exponent such as Fraction(1, 3) or '1/3'",  # advice, not a repr
        "m = 2 (Fraction), l = 3.0 (float)",
    ],
)
def test_readable_output_passes(site, output):
    assert _problems(site, _cell(text=output)) == []


def test_a_raw_repr_outside_cell_outputs_passes(site):
    # a code block may write a dict literal: only what executed cells print is checked
    assert _problems(site, "<div class=\"highlight\"><pre>units = {'L': 'mm'}</pre></div>") == []


def test_main_fails_on_a_page_with_a_machine_path(site, capsys):
    (site / "page.html").write_text(f"<html><body>{_cell(text='/tmp/x/fly.xml')}</body></html>", encoding="utf-8")
    assert check_pages.main([str(site), "--no-browser"]) == 1
    assert "machine's path" in capsys.readouterr().out


def test_docstring_examples_are_exempt_from_the_line_limit(site):
    # docstring examples wrap in the page (custom.css), so a long line there is no problem
    long = "w" * (check_pages.MAX_LINE + 10)
    body = f'<div class="doctest highlight-default"><div class="highlight"><pre>{long}</pre></div></div>'
    assert _problems(site, body) == []
    # but a code block after it is checked again
    assert len(_problems(site, body + f'<div class="highlight"><pre>{long}</pre></div>')) == 1


def _equation(number: int) -> str:
    return f'<div class="eq"><span class="eqno">({number})<a class="headerlink" href="#e">#</a></span>x</div>'


def test_equation_numbers_must_start_at_one_on_each_page(site):
    assert _problems(site, _equation(1) + _equation(2)) == []
    found = _problems(site, _equation(14) + _equation(15))  # numbered across the site
    assert len(found) == 1
    assert "(14), (15)" in found[0]
    assert len(_problems(site, _equation(1) + _equation(3))) == 1


# -- the layout at a phone's width, in a headless browser -------------------------------------

SITE_CSS = Path(__file__).resolve().parent.parent / "docs" / "_static" / "custom.css"
#: the script that sets a display equation wider than its column smaller until it fits
FIT_MATH = SITE_CSS.with_name("fit-math.js")
needs_browser = pytest.mark.skipif(check_pages.browser() is None, reason="no headless Chromium on the path")

#: an aligned text table with a line wider than a phone, a display equation and a table wider than one
WIDE_BLOCK = (
    '<div class="cell_output"><div class="highlight"><pre>'
    + "name      dimension  value  scaled value   source  path of the attribute in the file\n"
    + "g         L T^-2     9.81   98.1           file    option/@gravity\n</pre></div></div>"
)
WIDE_EQUATION = (
    '<div class="math"><mjx-container display="true" style="display: block">'
    '<span style="display: inline-block; width: 56em">x = 1</span></mjx-container></div>'
)
#: an equation a third wider than a phone's column (MathJax sizes everything in em): it fits when set smaller
SOMEWHAT_WIDE_EQUATION = WIDE_EQUATION.replace("56em", "28em").replace("x = 1", "y = 2")
WIDE_TABLE = (
    '<table class="docutils"><tr><td><span style="display: inline-block; width: 900px">a</span></td></tr></table>'
)


def _laid_out(site, style: str, body: str = WIDE_BLOCK + WIDE_EQUATION + WIDE_TABLE, script: str = "") -> list[str]:
    page = site / "page.html"
    page.write_text(
        f"<html><head><style>{style}</style><script>{script}</script></head><body><article>"
        f"{body}</article></body></html>",
        encoding="utf-8",
    )
    return check_pages.layout_problems([page], site, check_pages.browser())


@needs_browser
def test_layout_check_finds_a_wrapped_block_a_clipped_equation_and_a_clipped_table(site):
    # what the site did below 960 px before: code wrapped, and nothing scrolled
    found = _laid_out(
        site,
        "pre { white-space: pre-wrap; font-size: 12px; } mjx-container, div.math, table "
        "{ overflow: hidden; } article { width: 360px; }",
    )
    assert len(found) == 4, found
    assert "page.html: at 390 px, an aligned block wraps (2 lines shown on " in found[0]
    assert "a display equation is clipped: x = 1" in found[1]
    assert "the page is wider than the screen" in found[2]  # the table that runs past the column
    assert "a table is clipped" in found[3]


@needs_browser
def test_the_site_css_keeps_aligned_columns_and_scrolls_wide_tables(site):
    assert (
        _laid_out(site, SITE_CSS.read_text(encoding="utf-8") + " article { width: 360px; }", WIDE_BLOCK + WIDE_TABLE)
        == []
    )


@needs_browser
def test_an_equation_wider_than_its_column_fails_even_when_it_scrolls(site):
    css = SITE_CSS.read_text(encoding="utf-8") + " article { width: 360px; }"
    found = _laid_out(site, css, SOMEWHAT_WIDE_EQUATION)
    assert len(found) == 1, found
    assert "a display equation is wider than its column (" in found[0]
    assert "in 360): y = 2" in found[0]


@needs_browser
def test_the_site_script_sets_a_wide_equation_smaller_until_it_fits_and_leaves_the_widest_to_be_broken(site):
    css = SITE_CSS.read_text(encoding="utf-8") + " article { width: 360px; }"
    script = FIT_MATH.read_text(encoding="utf-8")
    assert _laid_out(site, css, SOMEWHAT_WIDE_EQUATION, script) == []
    # twice as wide: more than the script shrinks, so the check asks for the equation to be broken into lines
    found = _laid_out(site, css, SOMEWHAT_WIDE_EQUATION + WIDE_EQUATION, script)
    assert len(found) == 1, found
    assert found[0].endswith(": x = 1")
    assert "a display equation is wider than its column" in found[0]


@needs_browser
def test_a_page_wider_than_the_screen_fails(site):
    found = _laid_out(site, "body { margin: 0; } article { width: 700px; }", "<p>a paragraph</p>")
    assert found == ["page.html: at 390 px, the page is wider than the screen (700 px)"]
