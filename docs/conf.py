"""Sphinx configuration for the pitheorem documentation site.

Built by ``make docs`` as ``python -m sphinx -n -W --keep-going -b html docs docs/_build/html``.

Two rules shape this file:

* **Nothing is fetched, at build time or when a reader opens a page.** There is no
  intersphinx, MathJax is served from ``_static/mathjax`` (copied from the PyPI package
  ``sphinx-mathjax-offline``), and the theme has no analytics, launch or repository
  buttons. ``docs/check_offline.py`` checks the built HTML for any remote script,
  stylesheet, font or image.
* **No warnings.** The build runs nitpicky (``-n``) with warnings as errors (``-W``).
  Without intersphinx, references into other projects (numpy, sympy, ...) cannot resolve,
  so they are listed in ``nitpick_ignore_regex`` below; references into pitheorem must
  resolve.
"""

from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent

# Document the checkout, even when the docs are built from an environment in which the
# package is not installed. ``make docs`` installs it editable, so this changes nothing
# there. The notebook kernels are separate processes: they get the same path through
# PYTHONPATH, which they inherit from this process.
sys.path.insert(0, str(ROOT))
os.environ["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)

from pybtex.plugin import register_plugin  # noqa: E402
from pybtex.richtext import Text  # noqa: E402
from pybtex.style.formatting.plain import Style as PlainStyle  # noqa: E402
from pybtex.style.labels import BaseLabelStyle  # noqa: E402

import pitheorem  # noqa: E402  (after the path set-up above)

# -- Project information --------------------------------------------------------------

project = "pitheorem"
author = "the pitheorem developers"
copyright = "2026, the pitheorem developers"
version = pitheorem.__version__
release = pitheorem.__version__

# -- General configuration ------------------------------------------------------------

extensions = [
    "myst_nb",  # MyST markdown and notebooks; it loads myst_parser itself
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "sphinx.ext.mathjax",
    "sphinxcontrib.bibtex",
    "sphinx_proof",
]

# Files Sphinx reads. ``.md`` files with a jupytext/kernelspec header are notebooks and
# are executed; other ``.md`` files are plain MyST pages.
source_suffix = {
    ".rst": "restructuredtext",
    ".md": "myst-nb",
    ".ipynb": "myst-nb",
}

# Tutorials live in the top-level ``tutorials/`` folder, so that they can be opened in
# Jupyter (through jupytext) without the docs. They enter the docs tree through the
# symbolic link ``docs/tutorials -> ../tutorials``, which is committed to git (git stores
# symlinks as such). We chose the link over copying the folder in this file because a
# copy makes two versions of every tutorial, and Sphinx's error messages and the "source"
# download then point at the copy instead of the file a developer edits. Sphinx walks
# into symlinked folders, and myst-nb executes the notebooks with ``docs/tutorials`` as
# their working folder. If the link is missing (an export that flattened it, say), stop
# with a message rather than building a site without tutorials.
if not (DOCS / "tutorials" / "index.md").is_file():
    raise RuntimeError(
        "docs/tutorials must be a symbolic link to ../tutorials (re-create it with: ln -s ../tutorials docs/tutorials)"
    )

# Notebooks are never sources here: the tutorials are MyST markdown. A stray ``.ipynb`` beside
# one (``jupytext --to ipynb tutorials/*.md`` writes them there) would otherwise make Sphinx
# fail with "multiple files found for the document"; ``make notebooks`` writes its executed
# notebooks to _build/notebooks instead.
exclude_patterns = [
    "_build",
    "jupyter_execute",
    "**.ipynb_checkpoints",
    "**.ipynb",
    "Thumbs.db",
    ".DS_Store",
    "README.md",
    "tutorials/README.md",
]
templates_path = ["_templates"]

# A single backquoted name is a cross-reference to a Python object, as in numpydoc
# docstrings (`System.rank`).
default_role = "py:obj"
nitpicky = True
# No intersphinx (it would download objects.inv), so names from other projects cannot be
# linked. Ignore exactly those; every pitheorem name must resolve.
_external = (
    r"(sympy|numpy|np|scipy|matplotlib|mpl|pint|fractions|collections|collections\.abc"
    r"|typing|numbers|pathlib|os|io|types|enum|dataclasses|abc|argparse|re)"
)
nitpick_ignore_regex = [
    (r"py:.*", _external + r"\..*"),
    # bare names that type hints and numpydoc "Parameters" produce for them
    (
        r"py:.*",
        r"(Fraction|Rational|Matrix|Expr|Symbol|Basic|Mapping|MutableMapping|Sequence"
        r"|Iterable|Iterator|Collection|Callable|Hashable|Any|Self|Path|Figure|Axes"
        r"|ndarray|array_like|ArrayLike|NDArray|Quantity|Unit|UnitRegistry"
        r"|optional|default)",
    ),
    # numpydoc's convention writes parameter names in single backquotes (`scale`), which
    # the default role turns into object references. A bare lowercase name that does not
    # resolve is such a parameter name; qualified or capitalised names (`System.rank`,
    # `PiGroup`) and explicit roles (:func:`...`) are still checked.
    (r"py:obj", r"[a-z_][a-z0-9_]*"),
]

# Numbered figures, tables and equations; `{eq}` references show "(1)".
numfig = True
math_numfig = True
math_eqref_format = "({number})"

# -- MyST and myst-nb -----------------------------------------------------------------

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3

nb_execution_mode = "cache"  # a fresh clone (CI) executes every notebook once
nb_execution_raise_on_error = True  # a failing cell fails the build
nb_execution_show_tb = True
nb_execution_timeout = 120  # seconds per cell
nb_merge_streams = True
# myst-nb would add require.js and the widget manager from a CDN to pages with
# ipywidgets output; there must be none.
nb_ipywidgets_js = {}

# -- API reference (autodoc, autosummary, numpydoc) -----------------------------------

autosummary_generate = True  # writes reference/generated/*.rst (git-ignored)
autosummary_ignore_module_all = False  # the package's __all__ is the public API
autosummary_imported_members = True
autodoc_default_options = {"member-order": "bysource"}
autodoc_typehints = "none"  # numpydoc "Parameters" give the types, once
autoclass_content = "class"

numpydoc_show_class_members = False  # the class template lists members with autodoc
numpydoc_class_members_toctree = False
numpydoc_attributes_as_param_list = True
numpydoc_xref_param_type = False

# -- Bibliography ---------------------------------------------------------------------

bibtex_bibfiles = ["references.bib"]
bibtex_reference_style = "author_year"  # in the text: [Buckingham, 1914]


# In the bibliography, label each entry the way the text cites it ("Buckingham 1914")
# instead of with the number that pybtex's plain style gives.
class _AuthorYearLabels(BaseLabelStyle):
    def format_labels(self, sorted_entries):
        for entry in sorted_entries:
            people = entry.persons.get("author") or entry.persons.get("editor") or []
            names = [" ".join(p.prelast_names + p.last_names) for p in people]
            names = [Text.from_latex(n).render_as("text") for n in names]
            if len(names) > 2:
                who = f"{names[0]} et al."
            elif len(names) == 2:
                who = f"{names[0]} and {names[1]}"
            else:
                who = names[0] if names else entry.key
            yield f"{who} {entry.fields.get('year', '')}".strip()


class _AuthorYearStyle(PlainStyle):
    default_label_style = "pitheorem-author-year"


register_plugin("pybtex.style.labels", "pitheorem-author-year", _AuthorYearLabels)
register_plugin("pybtex.style.formatting", "pitheorem", _AuthorYearStyle)
bibtex_default_style = "pitheorem"

# -- sphinx-proof ---------------------------------------------------------------------

proof_minimal_theme = False

# -- Math, served offline -------------------------------------------------------------
# sphinx-mathjax-offline ships MathJax 3 (with its web fonts) as package data, in a
# folder named "sphinx-mathjax-offline" (a name with dashes: it cannot be imported with
# an import statement, but importlib finds it). We do not load it as a Sphinx extension:
# its hook copies the files only after a build without errors. Instead its
# ``static`` folder is added to html_static_path, so Sphinx copies ``mathjax/`` into
# ``_build/html/_static/mathjax`` like any other static file, on every build.
_mathjax_spec = importlib.util.find_spec("sphinx-mathjax-offline")
if _mathjax_spec is None or not _mathjax_spec.submodule_search_locations:
    raise RuntimeError(
        "The docs serve MathJax from the PyPI package 'sphinx-mathjax-offline'. "
        "Install the docs requirements: pip install -e '.[docs]'"
    )
_MATHJAX_STATIC = Path(next(iter(_mathjax_spec.submodule_search_locations))) / "static"
if not (_MATHJAX_STATIC / "mathjax" / "tex-chtml.js").is_file():
    raise RuntimeError(f"MathJax not found in {_MATHJAX_STATIC}")

# Relative to _static: the page loads _static/mathjax/tex-chtml.js, and MathJax then
# finds its extensions and its fonts (output/chtml/fonts/woff-v2) beside it.
mathjax_path = "mathjax/tex-chtml.js"
mathjax3_config = {
    # Sphinx numbers equations itself (math_numfig). pitheorem's HTML displays (a search
    # result's table, in a notebook cell's output) write their math between $ signs, as
    # Jupyter reads it; MathJax reads $ only in those outputs (myst_mathjax_classes below),
    # and never in code or in the <pre> of printed text.
    "tex": {"tags": "none", "inlineMath": [["$", "$"], ["\\(", "\\)"]]},
    "options": {"enableMenu": True},
}
# the classes MathJax typesets: myst's own (math, and the page's math roles) plus the HTML
# output of notebook cells ("text_html"), whose math pitheorem writes between $ signs
myst_mathjax_classes = "tex2jax_process|mathjax_process|math|output_area|text_html"

# -- HTML output ----------------------------------------------------------------------

html_theme = "sphinx_book_theme"
html_title = "pitheorem"
html_static_path = ["_static", str(_MATHJAX_STATIC)]
html_css_files = ["custom.css"]
# a display equation wider than its column is set smaller until it fits (a phone's column)
html_js_files = [("fit-math.js", {"defer": "defer"})]
html_last_updated_fmt = None
html_show_sourcelink = False
html_copy_source = True  # the download button offers the page's .md source
html_theme_options = {
    # Nothing that talks to a server: no repository, issue, edit or launch buttons, no
    # analytics, no icon links to external sites, no version switcher.
    "use_repository_button": False,
    "use_issues_button": False,
    "use_edit_page_button": False,
    "use_source_button": False,
    "use_download_button": True,
    "use_fullscreen_button": True,
    "launch_buttons": {},
    "icon_links": [],
    # The sidebar has the search field; without this the theme adds a second one in a
    # header bar above the page.
    "navbar_persistent": [],
    "show_toc_level": 2,
    "home_page_in_toc": True,
    "show_navbar_depth": 1,
    "navigation_with_keys": False,
}

# -- Numbers per page, and a proof index by title ---------------------------------------
# Sphinx numbers equations and captioned figures with one counter for the whole site
# unless the toctree is numbered, so a page's first equation could be "(14)". These pages
# are read one at a time (a tutorial, a proof), so each page numbers its own from 1:
# after Sphinx has assigned the numbers, renumber them within every page, in page order.


def _number_per_page(app, env):
    for numbers in env.toc_fignumbers.values():
        for by_id in numbers.values():
            for i, key in enumerate(sorted(by_id, key=by_id.get), start=1):
                by_id[key] = (i,)
    return []


# sphinx-proof's index (prf-prf.html) lists each statement by its label ("thm-row-space").
# Keep each statement's title beside its label when a page is read, and list the index by
# title, grouped by kind, with the page it is on.


def _keep_proof_titles(app, doctree):
    before, _, after = app.config.proof_title_format.partition("%t")
    proofs = getattr(app.env, "proof_list", {})
    for node in doctree.findall(lambda n: hasattr(n, "get") and n.get("realtype") and n.get("label")):
        title = node.get("title", "")
        if before and title.startswith(before):
            title = title[len(before) :]
        if after and title.endswith(after):
            title = title[: -len(after)]
        if node["label"] in proofs:
            proofs[node["label"]]["title"] = title.strip()


def _titled_proof_index():
    from collections import defaultdict

    from sphinx_proof.domain import ProofIndex

    class TitledProofIndex(ProofIndex):
        def generate(self, docnames=None):
            env = self.domain.env
            groups = defaultdict(list)
            for label, entry in getattr(env, "proof_list", {}).items():
                kind = entry["realtype"].capitalize()
                title = entry.get("title") or label
                page = env.titles[entry["docname"]].astext() if entry["docname"] in env.titles else ""
                groups[kind].append((title.replace("$", ""), 0, entry["docname"], label, page, "", ""))
            return sorted((kind, sorted(items)) for kind, items in groups.items()), True

    return TitledProofIndex


def setup(app):
    app.connect("env-get-updated", _number_per_page, priority=900)  # after Sphinx's numbering (500)
    app.connect("doctree-read", _keep_proof_titles)
    from sphinx_proof.domain import ProofDomain

    ProofDomain.indices = [_titled_proof_index()]
