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
* a page with math (``class="math``) that does not load the bundled MathJax.

Exit status: 0 when every check passes, 1 when one fails (each finding printed as
``page: what``), 2 when the build folder is missing or holds no HTML. Only the standard
library is used.
"""

from __future__ import annotations

import sys
from html.parser import HTMLParser
from pathlib import Path

__all__ = ["MIN_FIGURES", "PageScan", "check_page", "main"]

#: pages whose executed cells draw figures, and how many each shows at least
MIN_FIGURES = {
    "tutorials/00_getting_started.html": 1,
    "tutorials/02_reproducing_the_white_paper.html": 3,
    "tutorials/03_settling_the_papers_conjecture.html": 3,
    "tutorials/05_linear_systems.html": 2,
    "tutorials/06_similarity_in_physics_engines.html": 1,
    "tutorials/07_scaling_your_own_mujoco_model.html": 1,
    "explanation/errata.html": 1,
    "howto/compare_scaled_simulation.html": 2,
}


class PageScan(HTMLParser):
    """Collects image sources, script sources, math markers and visible text of a page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.images: list[str] = []
        self.scripts: list[str] = []
        self.has_math = False
        self.text: list[str] = []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "img" and attrs.get("src"):
            self.images.append(attrs["src"])
        if tag == "script" and attrs.get("src"):
            self.scripts.append(attrs["src"])
        if "math" in (attrs.get("class") or "").split():
            self.has_math = True

    def handle_data(self, data):
        self.text.append(data)


def check_page(page: Path, root: Path) -> list[str]:
    """Return the problems found on one built page (empty when it is fine)."""
    scan = PageScan()
    scan.feed(page.read_text(encoding="utf-8"))
    rel = page.relative_to(root).as_posix()
    problems = []
    if "Traceback" in "".join(scan.text):
        problems.append("shows a Traceback")
    want = MIN_FIGURES.get(rel, 0)
    if len(scan.images) < want:
        problems.append(f"shows {len(scan.images)} image(s), expected at least {want}")
    for src in scan.images:
        if not src.startswith(("data:", "http:", "https:", "//")) and not (page.parent / src).is_file():
            problems.append(f"image {src} is missing from the build")
    if scan.has_math and not any("mathjax" in s.lower() and not s.startswith(("http", "//")) for s in scan.scripts):
        problems.append("has math but does not load the bundled MathJax")
    return [f"{rel}: {p}" for p in problems]


def main(argv: list[str] | None = None) -> int:
    """Check every page; print findings; return the exit status."""
    args = sys.argv[1:] if argv is None else argv
    root = Path(args[0]) if args else Path(__file__).parent / "_build" / "html"
    pages = sorted(root.rglob("*.html")) if root.is_dir() else []
    if not pages:
        print(f"check_pages: no HTML pages in {root}; build the docs first (make docs)")
        return 2
    missing = [p for p in MIN_FIGURES if not (root / p).is_file()]
    problems = [f"{p}: page is missing from the build" for p in missing]
    for page in pages:
        problems += check_page(page, root)
    for line in problems:
        print(line)
    print(f"check_pages: {'FAILED' if problems else 'ok'}: {len(pages)} pages checked, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
