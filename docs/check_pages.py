"""Check what readers see in the built documentation: figures present, no tracebacks.

Usage::

    python docs/check_pages.py [BUILD_DIR]

BUILD_DIR defaults to ``docs/_build/html`` next to this file. The script reads every
``*.html`` page below it and reports

* a page whose text says ``Traceback`` (an executed cell that failed, or an intended error
  shown with its traceback: the docs print such errors' messages instead);
* a page listed in :data:`MIN_FIGURES` with fewer images than it should show (a figure
  that silently failed to render);
* an ``<img>`` whose local file is missing from the build;
* a page with math (``class="math``) that does not load the bundled MathJax;
* a figure shown twice in the output of one cell (a cell that ends with a call returning a
  Figure that pyplot has already shown: assign the result, ``fig = report.plot()``);
* equation numbers that do not run (1), (2), ... down the page (each page numbers its own
  equations; ``docs/conf.py`` arranges it);
* a line of a code or output block (``<pre>``) longer than :data:`MAX_LINE`
  characters. ``_static/custom.css`` sets the size of the code font so that
  :data:`MAX_LINE` characters fill the text column of a 1280 px wide window; a longer line
  would run past the column there. (Narrow screens wrap code blocks instead, also in
  ``custom.css``.) Such a line is fixed where it is made: a shorter code line, or output
  wrapped or shortened by the code that prints it. The examples of docstrings
  (``div.doctest``, on the API reference pages) are exempt: they follow the code's line
  length, and ``custom.css`` wraps them at every width;
* a machine's path anywhere in a page's text (:data:`MACHINE_PATHS`: ``/root/``,
  ``/usr/``, ``site-packages``, ``/work/``, ``/tmp/``): the build machine's installation
  or temporary folders mean nothing to a reader; show a file by its name;
* a raw Python repr in the output of an executed cell (:data:`RAW_REPRS`): a dict
  printed as ``{'m': ...}`` or a ``Fraction(1, 2)`` inside a container or on its own.
  Print such values readably (a line per item, a table, ``str()`` of each number).

Then, where a headless Chromium is installed (``chromium``, ``chromium-browser`` or
``google-chrome`` on the path; ``--no-browser`` skips it), every page is laid out at
:data:`PHONE_WIDTH` px, a phone's width, and measured (:func:`layout_problems`):

* an aligned code or output block that wraps (it shows more lines than its text has): the
  columns of a table printed as text would turn to mush; it must scroll sideways instead;
* a display equation wider than its column, even one that scrolls inside it: an equation
  must be read whole. ``_static/fit-math.js`` sets a wide one smaller until it fits (down
  to 62 % of its size); one that needs more is broken into lines in its source
  (``aligned`` or ``gathered``), or, for a cell's output, printed in parts;
* a table wider than its column that neither fits nor scrolls inside it (its end is
  clipped or runs past the column);
* a page wider than the screen (anything that makes the whole page scroll sideways).

Exit status: 0 when every check passes, 1 when one fails (each finding printed as
``page: what``), 2 when the build folder is missing or holds no HTML. Only the standard
library is used (and the browser, when there is one).
"""

from __future__ import annotations

import hashlib
import json
import re
import shutil
import subprocess
import sys
import tempfile
from html.parser import HTMLParser
from pathlib import Path

__all__ = [
    "MACHINE_PATHS",
    "MAX_LINE",
    "MIN_FIGURES",
    "PHONE_WIDTH",
    "RAW_REPRS",
    "PageScan",
    "browser",
    "check_page",
    "layout_problems",
    "main",
]

#: the window width, in px, at which pages are laid out and measured (a phone's)
PHONE_WIDTH = 390

#: JavaScript run on each laid-out page: the aligned blocks that wrap, and the display
#: equations and tables that overflow their column without scrolling inside it
_PROBE = r"""
function probe(d, w) {
  const found = [];
  const scrolls = el => ['auto', 'scroll'].includes(w.getComputedStyle(el).overflowX);
  const clipped = el => {
    // the first box from el outwards that is narrower than its content must scroll
    for (let box = el; box && box !== d.body; box = box.parentElement) {
      if (box.scrollWidth > box.clientWidth + 1) return !scrolls(box);
      if (box.tagName === 'ARTICLE' || box.tagName === 'MAIN') break;
    }
    const column = d.querySelector('article') || d.body;
    return el.getBoundingClientRect().right > column.getBoundingClientRect().right + 1;
  };
  for (const pre of d.querySelectorAll('div.highlight pre, div.cell_output pre')) {
    if (pre.closest('div.doctest')) continue;  // docstring examples wrap on purpose
    const st = w.getComputedStyle(pre);
    const lineHeight = parseFloat(st.lineHeight) || 1.2 * parseFloat(st.fontSize);
    const text = pre.textContent.replace(/\n$/, '');
    const lines = text.split('\n').length;
    const shown = (pre.clientHeight - parseFloat(st.paddingTop) - parseFloat(st.paddingBottom)) / lineHeight;
    if (shown > lines + 0.6) {
      const longest = text.split('\n').reduce((a, b) => (b.length > a.length ? b : a), '');
      found.push(`an aligned block wraps (${lines} lines shown on ${Math.round(shown)}): ${longest.slice(0, 50)}`);
    }
  }
  for (const eq of d.querySelectorAll('mjx-container[display="true"]')) {
    if (clipped(eq)) found.push(`a display equation is clipped: ${eq.textContent.slice(0, 40)}`);
    else if (eq.scrollWidth > eq.clientWidth + 1) {
      found.push(`a display equation is wider than its column (${eq.scrollWidth} px in ${eq.clientWidth}): `
        + eq.textContent.slice(0, 40));
    }
  }
  if (d.documentElement.scrollWidth > w.innerWidth + 1) {
    found.push(`the page is wider than the screen (${d.documentElement.scrollWidth} px)`);
  }
  for (const table of d.querySelectorAll('article table')) {
    if (clipped(table)) found.push(`a table is clipped (${table.scrollWidth} px wide)`);
  }
  return found;
}
const pages = PAGES, results = {};
const frame = document.getElementById('page');
async function run() {
  for (const page of pages) {
    await new Promise(done => { frame.onload = done; frame.src = page; });
    const w = frame.contentWindow;
    if (w.MathJax && w.MathJax.startup && w.MathJax.startup.promise) {
      await w.MathJax.startup.promise;
    }
    await new Promise(done => setTimeout(done, 50));
    results[page] = probe(frame.contentDocument, w);
  }
  document.getElementById('out').textContent = JSON.stringify(results);
}
run();
"""

#: longest line, in characters, that a code or output block may hold (see the module docstring)
MAX_LINE = 88

#: a machine's path in a page's text: the build machine's home, system, package or work folders
MACHINE_PATHS = re.compile(r"/root/|/usr/|site-packages|/work/|/tmp/")

#: a raw repr in a cell's output: a dict literal with a quoted key (Python's quotes: JSON's
#: double quotes pass), or a Fraction's repr inside a
#: container (after a bracket, a comma, a colon or an equals sign) or at the start of a line. A
#: message that advises "such as Fraction(1, 3)" is prose and passes.
RAW_REPRS = re.compile(r"\{'[^'\n]*': |(?:^|[\[{(,:=]\s*)Fraction\(-?\d+, \d+\)", re.MULTILINE)

#: pages whose executed cells draw figures, and how many each shows at least
MIN_FIGURES = {
    "tutorials/00_getting_started.html": 1,
    "tutorials/02_reproducing_the_white_paper.html": 2,
    "tutorials/03_settling_the_papers_conjecture.html": 2,
    "tutorials/05_linear_systems.html": 2,
    "tutorials/06_similarity_in_physics_engines.html": 1,
    "tutorials/07_scaling_your_own_mujoco_model.html": 1,
    "tutorials/10_where_similarity_holds.html": 4,
    "explanation/errata.html": 1,
    "howto/compare_scaled_simulation.html": 1,
}


class PageScan(HTMLParser):
    """Collects images, scripts, math markers, code blocks and visible text of a page.

    ``outputs`` holds the image sources of each executed cell's output (``div.cell_output``),
    one list per cell; ``blocks`` the text of each ``<pre>`` block outside docstring examples.
    """

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.images: list[str] = []
        self.scripts: list[str] = []
        self.has_math = False
        self.text: list[str] = []
        self.outputs: list[list[str]] = []
        self.output_text: list[str] = []  # the text of every cell output, one string a cell
        self.blocks: list[str] = []
        self._div_depth = 0
        self._output_depth: int | None = None  # div depth of the open cell output, if any
        self._pre: list[str] | None = None
        self._doctest_depth: int | None = None  # div depth of the open docstring example
        self.equation_numbers: list[str] = []
        self._eqno: list[str] | None = None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        classes = (attrs.get("class") or "").split()
        if tag == "div":
            self._div_depth += 1
            if "cell_output" in classes and self._output_depth is None:
                self._output_depth = self._div_depth
                self.outputs.append([])
                self.output_text.append("")
            if "doctest" in classes and self._doctest_depth is None:
                self._doctest_depth = self._div_depth
        if tag == "img" and attrs.get("src"):
            self.images.append(attrs["src"])
            if self._output_depth is not None:
                self.outputs[-1].append(attrs["src"])
        if tag == "script" and attrs.get("src"):
            self.scripts.append(attrs["src"])
        if tag == "pre":
            self._pre = []
        if tag == "span" and "eqno" in classes:
            self._eqno = []
        if tag == "a" and self._eqno is not None:  # the number ends where its link begins
            self.equation_numbers.append("".join(self._eqno).strip())
            self._eqno = None
        if "math" in classes:
            self.has_math = True

    def handle_endtag(self, tag):
        if tag == "div":
            if self._output_depth == self._div_depth:
                self._output_depth = None
            if self._doctest_depth == self._div_depth:
                self._doctest_depth = None
            self._div_depth -= 1
        if tag == "pre" and self._pre is not None:
            if self._doctest_depth is None:  # docstring examples wrap (see the module docstring)
                self.blocks.append("".join(self._pre))
            self._pre = None

    def handle_data(self, data):
        self.text.append(data)
        if self._output_depth is not None:
            self.output_text[-1] += data
        if self._pre is not None:
            self._pre.append(data)
        if self._eqno is not None:
            self._eqno.append(data)


def _image_key(src: str, page: Path) -> str:
    """What identifies a figure: the bytes of its file when it is in the build, else its source."""
    path = page.parent / src
    if not src.startswith(("data:", "http:", "https:", "//")) and path.is_file():
        return hashlib.sha256(path.read_bytes()).hexdigest()
    return src


def check_page(page: Path, root: Path) -> list[str]:
    """Return the problems found on one built page (empty when it is fine)."""
    scan = PageScan()
    scan.feed(page.read_text(encoding="utf-8"))
    rel = page.relative_to(root).as_posix()
    problems = []
    text = "".join(scan.text)
    if "Traceback" in text:
        problems.append("shows a Traceback")
    for found in dict.fromkeys(m.group(0) for m in MACHINE_PATHS.finditer(text)):
        at = text.find(found)
        problems.append(f"shows a machine's path ({found}): {text[max(0, at - 40) : at + 40]!r}")
    for output in scan.output_text:
        lines = (output[output.rfind("\n", 0, m.start()) + 1 :].split("\n", 1)[0] for m in RAW_REPRS.finditer(output))
        problems.extend(f"a cell's output shows a raw repr: {line[:70]!r}" for line in dict.fromkeys(lines))
    want = MIN_FIGURES.get(rel, 0)
    if len(scan.images) < want:
        problems.append(f"shows {len(scan.images)} image(s), expected at least {want}")
    for src in scan.images:
        if not src.startswith(("data:", "http:", "https:", "//")) and not (page.parent / src).is_file():
            problems.append(f"image {src} is missing from the build")
    expected = [f"({k})" for k in range(1, len(scan.equation_numbers) + 1)]
    if scan.equation_numbers != expected:
        problems.append(f"equation numbers {', '.join(scan.equation_numbers)} do not run (1), (2), ...")
    for srcs in scan.outputs:
        keys = [_image_key(src, page) for src in srcs]
        if len(set(keys)) < len(keys):
            problems.append(f"a cell output shows the same figure twice ({srcs[0]})")
    for block in scan.blocks:
        longest = max(block.splitlines() or [""], key=len)
        if len(longest) > MAX_LINE:
            problems.append(
                f"a code or output line has {len(longest)} characters (at most {MAX_LINE}): {longest[:60]!r}..."
            )
    if scan.has_math and not any("mathjax" in s.lower() and not s.startswith(("http", "//")) for s in scan.scripts):
        problems.append("has math but does not load the bundled MathJax")
    return [f"{rel}: {p}" for p in problems]


def browser() -> str | None:
    """The headless browser the layout checks use: Chromium or Chrome on the path, else None."""
    return next(filter(None, map(shutil.which, ("chromium", "chromium-browser", "google-chrome"))), None)


def layout_problems(pages: list[Path], root: Path, program: str, width: int = PHONE_WIDTH) -> list[str]:
    """Lay out pages in a headless browser `width` px wide; return what wraps or is clipped.

    The pages load one after the other in a frame of a page written for the purpose, which
    measures each (after MathJax has typeset it) and writes the findings into itself; the
    browser prints that page's final DOM (``--dump-dom``), where they are read.
    """
    if not pages:
        return []
    with tempfile.TemporaryDirectory() as tmp:
        runner = Path(tmp) / "layout.html"
        script = _PROBE.replace("PAGES", json.dumps([p.resolve().as_uri() for p in pages]))
        runner.write_text(
            f'<html><body style="margin:0"><iframe id="page" style="width:{width}px;height:1200px;border:0">'
            f'</iframe><pre id="out"></pre><script>{script}</script></body></html>',
            encoding="utf-8",
        )
        dom = subprocess.run(
            [
                program,
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--allow-file-access-from-files",
                f"--window-size={width + 20},1300",
                f"--virtual-time-budget={60000 * len(pages)}",
                "--dump-dom",
                runner.as_uri(),
            ],
            capture_output=True,
            text=True,
            timeout=60 + 10 * len(pages),
            check=False,
        ).stdout
    start, end = dom.find('<pre id="out">'), dom.find("</pre>", dom.find('<pre id="out">'))
    text = dom[start + len('<pre id="out">') : end] if start >= 0 else ""
    if not text.strip():
        return [f"layout check at {width} px: the browser measured nothing ({program})"]
    found = json.loads(text.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", '"').replace("&amp;", "&"))
    by_uri = {p.resolve().as_uri(): p for p in pages}
    return [
        f"{by_uri[uri].relative_to(root).as_posix()}: at {width} px, {what}"
        for uri, whats in found.items()
        for what in whats
    ]


def main(argv: list[str] | None = None) -> int:
    """Check every page; print findings; return the exit status."""
    args = sys.argv[1:] if argv is None else argv
    use_browser = "--no-browser" not in args
    args = [a for a in args if a != "--no-browser"]
    root = Path(args[0]) if args else Path(__file__).parent / "_build" / "html"
    pages = sorted(root.rglob("*.html")) if root.is_dir() else []
    if not pages:
        print(f"check_pages: no HTML pages in {root}; build the docs first (make docs)")
        return 2
    missing = [p for p in MIN_FIGURES if not (root / p).is_file()]
    problems = [f"{p}: page is missing from the build" for p in missing]
    for page in pages:
        problems += check_page(page, root)
    program = browser() if use_browser else None
    if program is not None:  # the generated API stubs are left out: docstring examples wrap on purpose
        problems += layout_problems([p for p in pages if "generated" not in p.parts], root, program)
    else:
        print(f"check_pages: layout checks at {PHONE_WIDTH} px skipped (no headless Chromium on the path)")
    for line in problems:
        print(line)
    print(f"check_pages: {'FAILED' if problems else 'ok'}: {len(pages)} pages checked, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
