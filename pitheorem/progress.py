"""Progress on stderr for the command line's long commands: a bar of named stages, or of counted runs.

A command that may run for more than a couple of seconds (``apply`` and
``convert`` on a large file, ``check``, ``verify``, ``sweep``) shows where
it is on stderr while it works, with tqdm, and leaves nothing behind when
it is done.  It is quiet unless stderr is a terminal, in JSON mode, and
where tqdm is not installed (:func:`wanted`), so that a pipe, a log file
or a script reading the JSON never sees it.

The bar appears only after :data:`DELAY` seconds: a command that finishes
sooner shows nothing.  While a stage runs, its elapsed time keeps ticking
(a stage such as compiling a large model reports nothing itself).
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Sequence

__all__ = ["DELAY", "TICK", "StageBar", "counting_bar", "say", "wanted"]

#: seconds a bar waits before it appears (a quick command shows nothing)
DELAY = 0.5

#: seconds between two redraws of a stage bar while a stage runs (its elapsed time)
TICK = 0.5


def wanted(fmt: str = "text") -> bool:
    """Whether the command line shows progress: stderr is a terminal and the output is not JSON.

    Parameters
    ----------
    fmt : str
        The output format asked for (``--format``).

    Returns
    -------
    bool

    Examples
    --------
    >>> from pitheorem.progress import wanted
    >>> wanted("json")
    False
    """
    if fmt == "json":
        return False
    isatty = getattr(sys.stderr, "isatty", None)
    try:
        return bool(isatty and isatty())
    except ValueError:  # a closed stream
        return False


def say(text: str) -> None:
    """Print one line on stderr, above any bar that is showing (tqdm's ``write``), never through it.

    Examples
    --------
    >>> import contextlib, io
    >>> from pitheorem.progress import say
    >>> err = io.StringIO()
    >>> with contextlib.redirect_stderr(err):
    ...     say("pitheorem: note: hello")
    >>> err.getvalue()
    'pitheorem: note: hello\\n'
    """
    tqdm = sys.modules.get("tqdm")  # no bar can be showing where tqdm was never imported
    if tqdm is not None and hasattr(tqdm, "tqdm"):
        tqdm.tqdm.write(text, file=sys.stderr)
    else:
        print(text, file=sys.stderr)


def _tqdm():
    """tqdm's class, or None where it is not installed (the bars are then quiet)."""
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return tqdm


def counting_bar(total: int, what: str, unit: str):
    """tqdm's bar of `total` counted steps on stderr (quiet for its first :data:`DELAY` seconds), or None.

    None where tqdm is not installed.  The caller updates and closes it.

    Examples
    --------
    >>> from pitheorem.progress import counting_bar
    >>> bar = counting_bar(3, "sweep", "run")
    >>> bar.total, bar.desc
    (3, 'sweep')
    >>> bar.close()
    """
    tqdm = _tqdm()
    if tqdm is None:
        return None
    return tqdm(total=total, desc=what, unit=unit, file=sys.stderr, leave=False, delay=DELAY)


class StageBar:
    """A bar of a command's named stages on stderr, or nothing at all.

    Use it as a context manager and call :meth:`stage` as each stage
    begins; once :data:`DELAY` seconds have passed, the bar shows the
    running stage's name, how many stages are done and the time so far,
    redrawn every :data:`TICK` seconds, and it is erased when the block ends.

    Parameters
    ----------
    what : str
        What the bar stands for (the command's name).
    stages : sequence of str
        Every stage, in order; :meth:`stage` names one of them.
    show : bool
        False makes the bar do nothing (:func:`wanted`).

    Examples
    --------
    >>> from pitheorem.progress import StageBar
    >>> with StageBar("apply", ("loading", "writing"), show=False) as bar:
    ...     bar.stage("loading")
    ...     bar.stage("writing")
    >>> bar.done
    ('loading', 'writing')
    """

    def __init__(self, what: str, stages: Sequence[str], *, show: bool) -> None:
        self.what = what
        self.stages = tuple(stages)
        self.show = show
        self._done: list[str] = []
        self._tqdm = None
        self._bar = None
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._ticker: threading.Thread | None = None
        self._start = 0.0

    @property
    def done(self) -> tuple[str, ...]:
        """The stages begun so far, in order."""
        return tuple(self._done)

    def __enter__(self) -> StageBar:
        self._tqdm = _tqdm() if self.show else None
        self._start = time.monotonic()
        if self._tqdm is not None:
            self._ticker = threading.Thread(target=self._tick, name="pitheorem-progress", daemon=True)
            self._ticker.start()
        return self

    def _redraw(self) -> None:
        """Draw the bar as it stands, once :data:`DELAY` seconds have passed (the first time, make it)."""
        if self._tqdm is None or not self._done or time.monotonic() - self._start < DELAY:
            return
        with self._lock:
            name = self._done[-1]
            if self._bar is None:
                self._bar = self._tqdm(
                    total=len(self.stages),
                    desc=f"{self.what}: {name}",
                    unit="stage",
                    file=sys.stderr,
                    leave=False,
                    bar_format="{desc} |{bar}| {n}/{total} stages, {elapsed}",
                )
                self._bar.start_t -= time.monotonic() - self._start  # the time since the command began
            self._bar.n = self.stages.index(name)
            self._bar.set_description_str(f"{self.what}: {name}", refresh=False)
            self._bar.refresh()

    def _tick(self) -> None:
        while not self._stop.wait(TICK):
            self._redraw()

    def stage(self, name: str) -> None:
        """Begin the stage `name` (one of :attr:`stages`): the stages before it count as done."""
        if name not in self.stages:
            raise ValueError(f"unknown stage {name!r}; the stages are {', '.join(self.stages)}")
        self._done.append(name)
        self._redraw()

    def __exit__(self, *exc) -> None:
        self._stop.set()
        if self._ticker is not None:
            self._ticker.join()
        with self._lock:
            if self._bar is not None:
                self._bar.close()
                self._bar = None
