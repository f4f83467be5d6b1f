"""Check that the built documentation loads nothing from the network.

Usage::

    python docs/check_offline.py [BUILD_DIR]

BUILD_DIR defaults to ``docs/_build/html`` next to this file. The script reads every
``*.html`` file below it and reports each tag that makes a browser fetch something as the
page opens -- ``<script src>``, ``<link href>`` (stylesheets, fonts, preloads), ``<img>``,
``<iframe>``, ``<audio>``/``<video>``/``<source>``, ``<embed>``, ``<object>`` -- whose
address is remote (``http:``, ``https:`` or protocol-relative ``//``). It also reads every
``*.css`` file for remote ``@import`` and ``url(...)``. Plain ``<a href>`` links are not
reported: a reader has to click them.

Exit status: 0 when nothing remote is found, 1 when something is (each finding is printed
as ``file: tag attribute=value``), 2 when the build folder is missing or holds no HTML.
Only the standard library is used.
"""

from __future__ import annotations

import re
import sys
from html.parser import HTMLParser
from pathlib import Path

__all__ = ["find_remote_css", "find_remote_resources", "is_remote", "main"]

# Tag -> attributes through which the browser fetches a resource without a click.
_FETCHING = {
    "script": ("src",),
    "link": ("href",),
    "img": ("src", "srcset"),
    "iframe": ("src",),
    "frame": ("src",),
    "audio": ("src",),
    "video": ("src", "poster"),
    "source": ("src", "srcset"),
    "track": ("src",),
    "embed": ("src",),
    "object": ("data",),
    "input": ("src",),
}
# <link rel=...> values that are only metadata and make no request.
_NON_FETCHING_REL = {
    "canonical",
    "author",
    "license",
    "alternate",
    "help",
    "search",
    "index",
    "next",
    "prev",
    "previous",
    "up",
    "copyright",
    "glossary",
}

_REMOTE = re.compile(r"^\s*(?:[a-z][a-z0-9+.-]*:)?//", re.IGNORECASE)
_CSS_URL = re.compile(r"""(?:@import\s+(?:url\(\s*)?|url\(\s*)(['"]?)([^'")\s;]+)\1""", re.IGNORECASE)


def is_remote(address: str) -> bool:
    """Return True if a browser would fetch ``address`` from another host.

    Parameters
    ----------
    address : str
        A URL as written in an HTML attribute or a CSS ``url()``.

    Returns
    -------
    bool
        True for ``http://...``, ``https://...``, ``//host/...`` and any other
        ``scheme://`` address; False for relative paths and ``data:`` URLs.

    Examples
    --------
    >>> is_remote("https://cdn.example.org/mathjax.js")
    True
    >>> is_remote("//fonts.example.org/a.css")
    True
    >>> is_remote("_static/mathjax/tex-chtml.js")
    False
    >>> is_remote("data:image/png;base64,AAAA")
    False
    """
    return bool(_REMOTE.match(address))


class _ResourceFinder(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.found: list[tuple[str, str, str]] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        names = _FETCHING.get(tag)
        if names is None:
            return
        values = {k.lower(): (v or "") for k, v in attrs}
        if tag == "link":
            rel = set(values.get("rel", "").lower().split())
            if rel and rel <= _NON_FETCHING_REL:
                return
        for name in names:
            value = values.get(name)
            if not value:
                continue
            # srcset holds "url size, url size, ..."
            candidates = (
                [part.strip().split()[0] for part in value.split(",") if part.strip()] if name == "srcset" else [value]
            )
            self.found.extend((tag, name, c) for c in candidates if is_remote(c))

    handle_startendtag = handle_starttag


def find_remote_resources(html: str) -> list[tuple[str, str, str]]:
    """List the remote resources an HTML page loads as it opens.

    Parameters
    ----------
    html : str
        The text of an HTML page.

    Returns
    -------
    list of tuple of (str, str, str)
        ``(tag, attribute, address)`` for each remote resource, in page order.

    Examples
    --------
    >>> find_remote_resources('<script src="https://cdn.example.org/x.js"></script>')
    [('script', 'src', 'https://cdn.example.org/x.js')]
    >>> find_remote_resources('<a href="https://example.org">a link</a>')
    []
    """
    finder = _ResourceFinder()
    finder.feed(html)
    finder.close()
    return finder.found


def find_remote_css(css: str) -> list[str]:
    """List the remote addresses a stylesheet imports or loads.

    Parameters
    ----------
    css : str
        The text of a CSS file.

    Returns
    -------
    list of str
        Every remote address in an ``@import`` or a ``url(...)``.

    Examples
    --------
    >>> find_remote_css("@import url('https://fonts.example.org/css');")
    ['https://fonts.example.org/css']
    >>> find_remote_css("src: url(../webfonts/fa-solid-900.woff2)")
    []
    """
    return [m.group(2) for m in _CSS_URL.finditer(css) if is_remote(m.group(2))]


def main(argv: list[str] | None = None) -> int:
    """Scan a built HTML site; print findings and return the exit status.

    Parameters
    ----------
    argv : list of str, optional
        Command-line arguments after the program name: at most one, the build folder.

    Returns
    -------
    int
        0 if nothing remote is loaded, 1 if something is, 2 on a usage error.
    """
    args = sys.argv[1:] if argv is None else argv
    if len(args) > 1:
        print("usage: python docs/check_offline.py [BUILD_DIR]", file=sys.stderr)
        return 2
    root = Path(args[0]) if args else Path(__file__).resolve().parent / "_build" / "html"
    pages = sorted(root.rglob("*.html")) if root.is_dir() else []
    if not pages:
        print(
            f"check_offline: no HTML files under {root}; build the docs first",
            file=sys.stderr,
        )
        return 2

    problems: list[str] = []
    for page in pages:
        text = page.read_text(encoding="utf-8", errors="replace")
        for tag, attr, address in find_remote_resources(text):
            problems.append(f"{page.relative_to(root)}: <{tag}> {attr}={address}")
        for address in find_remote_css("\n".join(_inline_styles(text))):
            problems.append(f"{page.relative_to(root)}: <style> url {address}")
    sheets = sorted(root.rglob("*.css"))
    for sheet in sheets:
        text = sheet.read_text(encoding="utf-8", errors="replace")
        for address in find_remote_css(text):
            problems.append(f"{sheet.relative_to(root)}: css url {address}")

    for line in problems:
        print(line)
    status = 1 if problems else 0
    verdict = "FAIL" if problems else "ok"
    print(
        f"check_offline: {verdict}: {len(pages)} HTML pages and {len(sheets)} stylesheets "
        f"scanned, {len(problems)} remote resources found",
        file=sys.stderr,
    )
    return status


def _inline_styles(html: str) -> list[str]:
    return re.findall(r"<style[^>]*>(.*?)</style>", html, flags=re.IGNORECASE | re.DOTALL)


if __name__ == "__main__":
    sys.exit(main())
