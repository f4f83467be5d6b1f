"""Exhaustive search for similarity scalings: :func:`search` and :class:`SearchResult`.

Every similarity scaling is a change of base units ``u`` (see
:mod:`pitheorem.scaling`), with exponents ``a = D^T u``.  A request
prescribes some exponents (``g -> s g``: ``a_g = 1``) and holds others at
zero, which is a linear system ``C u = b``:

* it has no solution exactly when some row combination ``y`` gives
  ``y^T C = 0`` but ``y^T b != 0``; then the product of the constrained
  variables with exponents ``y`` is dimensionless and the request would
  multiply it by ``s^(y.b)``: the certificate of impossibility;
* otherwise its solutions form an affine space ``a0 + span(V)`` of exponent
  vectors.  A solution is *support-minimal* (no other solution changes a
  strict subset of its variables) exactly when holding every variable it
  leaves unchanged fixes it uniquely, so the minimal solutions are the
  distinct points obtained by holding ``dim V`` further variables with
  independent directions at zero.  Enumerating those subsets reuses the
  exact basis enumerator of :mod:`pitheorem.bases`.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field, fields
from fractions import Fraction
from math import comb, gcd, lcm
from types import MappingProxyType
from typing import ClassVar

from .errors import InvalidRequestError
from .exact import read_exponent
from .formatting import TableDisplay, TextDisplay
from .formatting.pieces import request_text
from .groups import PiGroup
from .immutable import immutable
from .linalg import nullspace, rank, solve
from .scaling import Scaling
from .system import System

__all__ = ["SearchNote", "SearchResult", "search"]


def _dot(x, y) -> Fraction:
    return sum((a * b for a, b in zip(x, y, strict=True)), Fraction(0))


@immutable
@dataclass(frozen=True, slots=True)
class SearchNote(TextDisplay):
    """An assumption a search made, as data that each front end phrases.

    ``str(note)`` is the phrasing of the Python front end (the result's
    text and HTML); the command line phrases the same note with its own
    options (both through ``pitheorem.formatting.pieces.note_text``).

    Attributes
    ----------
    kind : {"time_fixed", "outside_equations"}
        ``"time_fixed"``: no `fixed` was given, so the variables of
        dimension T were held fixed.  ``"outside_equations"``: a search
        ``within=`` equations held the variables that do not appear in them.
    variables : tuple of str
        The variables the note is about, in system order.

    Examples
    --------
    >>> import pitheorem as pt
    >>> res = pt.search(pt.System({"l": "L", "g": "L T^-2", "t": "T"}), scale={"g": 1})
    >>> res.notes
    (SearchNote(kind='time_fixed', variables=('t',)),)
    >>> print(res.notes[0])
    Time variable t is held fixed by default; pass fixed=() to let time change
    """

    #: every kind of note a search makes
    KINDS: ClassVar[tuple[str, ...]] = ("time_fixed", "outside_equations")

    kind: str
    variables: tuple[str, ...]

    def __post_init__(self):
        if self.kind not in self.KINDS:
            raise InvalidRequestError(f"unknown note kind {self.kind!r}; the kinds are {', '.join(self.KINDS)}")
        if isinstance(self.variables, str) or not all(isinstance(n, str) for n in self.variables):
            raise InvalidRequestError(f"a note's variables are a sequence of names, got {self.variables!r}")
        object.__setattr__(self, "variables", tuple(self.variables))  # a list read from JSON becomes a tuple


class _Once:
    """The minimal solutions of one request: enumerated on first use, then kept.

    The only state a :class:`SearchResult` changes after it is made, and
    none of it is visible except as speed.
    """

    __slots__ = ("_args", "_value")

    def __init__(self, *args):
        self._args = args
        self._value = None

    def __call__(self):
        if self._args is not None:
            self._value = _minimal_points(*self._args)
            self._args = None
        return self._value


@immutable
@dataclass(frozen=True, slots=True)
class SearchResult(TableDisplay):
    """The answer of :func:`search`: every minimal scaling, or a proof of none.

    A frozen value, made whole by :func:`search`: its attributes cannot be
    assigned.  The minimal scalings are enumerated once, on first use of
    :attr:`scalings`, :attr:`n_scalings`, :meth:`table` or the text display;
    ``repr`` and the attributes below never enumerate.

    Attributes
    ----------
    system : System
    scale : mapping of str to Fraction
        The prescribed exponents (read-only).
    fixed : tuple of str
        Variables held unchanged (including those outside `allow`).
    notes : tuple of SearchNote
        Assumptions made, e.g. that time was held fixed by default.
    feasible : bool
    certificate : PiGroup or None
        When infeasible: a dimensionless product of prescribed and fixed
        variables that the request would change.
    certificate_power : Fraction
        When infeasible: the power of ``s`` by which the request would
        multiply the certificate (0 when feasible).
    particular : Scaling or None
        When feasible: one solution, not necessarily minimal.
    directions : tuple of Scaling
        When feasible: independent scalings that keep every prescribed and
        fixed exponent; every solution is ``particular`` plus a
        combination of them.

    Examples
    --------
    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "t": "T"})
    >>> res = pt.search(rod, scale={"g": 1}, fixed=("t", "m", "k_theta"))
    >>> res.feasible, str(res.certificate)
    (False, 'Pi = g**2*m*t**2/k_theta')
    >>> res
    <SearchResult g by s with t, m, k_theta fixed: infeasible, certificate g**2*m*t**2/k_theta>
    """

    system: System
    scale: Mapping[str, Fraction] = field(hash=False)
    fixed: tuple[str, ...]
    notes: tuple[SearchNote, ...]
    feasible: bool
    certificate: PiGroup | None = None
    certificate_power: Fraction = Fraction(0)
    particular: Scaling | None = None
    directions: tuple[Scaling, ...] = ()
    # the scalings are changes of units (else symmetries of equations: Scaling.unit_change_vector is None)
    _is_units: bool = field(default=True, repr=False, compare=False)
    _minimal: _Once = field(default=None, repr=False, compare=False)

    def __reduce__(self):
        # a read-only mapping does not pickle: send the prescribed exponents as a plain dict
        state = {f.name: getattr(self, f.name) for f in fields(self)}
        state["scale"] = dict(self.scale)
        return (_unpickle_result, (state,))

    # -- minimal solutions ------------------------------------------------
    def _enumerate(self):
        """``(point, coords)`` of each minimal solution, enumerated on first call."""
        return self._minimal() if self._minimal is not None else []

    @property
    def n_scalings(self) -> int:
        """Number of support-minimal scalings (computed exactly, not built).

        Examples
        --------
        >>> import pitheorem as pt
        >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "t": "T"})
        >>> pt.search(rod, scale={"g": 1}).n_scalings
        2
        """
        return len(self._enumerate())

    @property
    def max_n_scalings(self) -> int:
        """Upper bound C(#free, dim) on :attr:`n_scalings`, known without enumerating.

        Examples
        --------
        >>> import pitheorem as pt
        >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "t": "T"})
        >>> pt.search(rod, scale={"g": 1}).max_n_scalings
        3
        """
        if not self.feasible:
            return 0
        n_free = len(self.system.variables) - len(self.scale) - len(self.fixed)
        return comb(n_free, len(self.directions))

    def iter_scalings(self) -> Iterator[Scaling]:
        """Yield the minimal scalings in order (see :attr:`scalings`).

        Examples
        --------
        >>> import pitheorem as pt
        >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "t": "T"})
        >>> print(next(pt.search(rod, scale={"g": 1}).iter_scalings()))
        m -> m/s^2, l -> s l, g -> s g
        """
        for point, coords in self._enumerate():
            yield Scaling(self.system, point, coords if self._is_units else None)

    @property
    def scalings(self) -> list[Scaling]:
        """Every support-minimal scaling, fewest changed variables first.

        Ties are broken by the positions of the changed variables, then by
        the size of the exponents.  A new list on each call.

        Examples
        --------
        >>> import pitheorem as pt
        >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "t": "T"})
        >>> [str(sc) for sc in pt.search(rod, scale={"g": 1}).scalings]
        ['m -> m/s^2, l -> s l, g -> s g', 'l -> s l, g -> s g, k_theta -> s^2 k_theta']
        """
        return list(self.iter_scalings())

    @property
    def roles(self) -> dict[str, str]:
        """Each variable's role in the request: ``"scale"``, ``"fixed"`` or ``"free"``.

        In system order; ``"fixed"`` includes the variables held by default
        (time) and those outside `allow`.

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})
        >>> pt.search(s, scale={"g": 1}).roles
        {'m': 'free', 'l': 'free', 'g': 'scale', 't': 'fixed'}
        """
        return {
            n: "scale" if n in self.scale else "fixed" if n in self.fixed else "free" for n in self.system.variables
        }

    # -- display (pitheorem.formatting renders it: text, LaTeX, HTML, JSON) --
    def explanation(self) -> str:
        """One sentence saying what was found, or why nothing can be.

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"theta_r": "1", "l": "L"})
        >>> print(pt.search(s, scale={"theta_r": 1}).explanation())
        Impossible: theta_r is dimensionless and built only from prescribed and fixed variables, but the request would multiply it by s, so no change of units (and hence no similarity scaling) can do it.
        """
        from .formatting.text import explanation

        return explanation(self)

    def table(self) -> str:
        """Plain-text table: variables down, minimal solutions across.

        The last rows, ``[M]``, ``[L]``, ... with the role ``base``, give the
        change of base units behind each scaling (`Scaling.unit_change`):
        the power of ``s`` by which every reading in that unit is multiplied.

        Examples
        --------
        >>> import pitheorem as pt
        >>> s = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"})
        >>> print(pt.search(s, scale={"g": 1}).table())
        variable  role   #1
        m         free   -
        l         free   s
        g         scale  s
        t         fixed  -
        [M]       base   -
        [L]       base   s
        [T]       base   -
        """
        from .formatting.text import search_table

        return search_table(self)

    def __repr__(self) -> str:
        # cheap: the request and the size of the answer, never the enumeration
        if not self.feasible:
            answer = f"infeasible, certificate {self.certificate.expr}"
        elif self.directions:
            answer = (
                f"feasible, a family of dimension {len(self.directions)}, "
                f"at most {self.max_n_scalings} minimal solution(s)"
            )
        else:
            answer = "feasible, unique"
        return f"<SearchResult {request_text(self)}: {answer}>"

    def plot(self, ax=None):
        """Chart of the table, one colour per exponent.

        See :func:`pitheorem.plotting.plot_search`.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw into these axes (default: a new figure).

        Returns
        -------
        matplotlib.figure.Figure

        Examples
        --------
        Draw into axes of your own figure:

        >>> import matplotlib.pyplot as plt
        >>> import pitheorem as pt
        >>> fig, (left, right) = plt.subplots(1, 2)
        >>> res = pt.search(pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T"}), scale={"g": 1})
        >>> res.plot(ax=right) is fig, right.get_xlabel()
        (True, 'minimal scaling')
        """
        from .plotting import plot_search

        return plot_search(self, ax=ax)


def _unpickle_result(state: dict) -> SearchResult:
    return SearchResult(**{**state, "scale": MappingProxyType(state["scale"])})


# -- solving a request ---------------------------------------------------------------------


def _scaling(system: System, generators, is_units: bool, coords) -> Scaling:
    # variables with the same column of the generators (the same dimension, for changes of units) take the
    # same exponent: each column is summed once (a robot file's thousands of numbers have a few dozen)
    exponents: dict[tuple, Fraction] = {}
    vector = []
    for i in range(len(system.variables)):
        column = tuple(g[i] for g in generators)
        if column not in exponents:
            exponents[column] = _dot(coords, column)
        vector.append(exponents[column])
    return Scaling(system, tuple(vector), tuple(coords) if is_units else None)


def _solve(
    system: System, scale: dict[str, Fraction], fixed: tuple[str, ...], notes: tuple[SearchNote, ...], generators=None
) -> SearchResult:
    """The whole answer of a request, as one frozen :class:`SearchResult`."""
    # allowed exponent vectors are combinations of these rows: the rows of
    # the dimension matrix (changes of units), or a symmetry basis
    is_units = generators is None
    gens = system.rows() if generators is None else [list(g) for g in generators]
    names = list(scale) + list(fixed)
    rhs = [scale[n] for n in scale] + [Fraction(0)] * len(fixed)
    rows = [[g[system.index(n)] for g in gens] for n in names]
    request = {
        "system": system,
        "scale": MappingProxyType(dict(scale)),
        "fixed": tuple(fixed),
        "notes": tuple(notes),
        "_is_units": is_units,
    }
    w0 = solve(rows, rhs) if gens else ([] if not any(rhs) else None)
    if w0 is None:
        certificate, power = _certificate(system, scale, names, rows, rhs)
        return SearchResult(**request, feasible=False, certificate=certificate, certificate_power=power)
    # directions that keep every constraint: coordinates in null(C), kept
    # only while their exponent vectors stay independent
    null_w = nullspace(rows, len(gens)) if rows else nullspace([], len(gens))
    kept, images = [], []
    for w in null_w:
        image = list(_scaling(system, gens, is_units, w).vector)
        if rank([*images, image]) > len(images):
            kept.append(w)
            images.append(image)
    particular = _scaling(system, gens, is_units, w0)
    directions = tuple(_scaling(system, gens, is_units, w) for w in kept)
    constrained = set(scale) | set(fixed)
    free = [i for i, n in enumerate(system.variables) if n not in constrained]
    minimal = _Once(particular.vector, [d.vector for d in directions], free, w0, kept)
    return SearchResult(**request, feasible=True, particular=particular, directions=directions, _minimal=minimal)


def _certificate(system: System, scale, names, rows, rhs) -> tuple[PiGroup, Fraction]:
    """y with y^T C = 0 and y.b != 0: a dimensionless product the request changes, and its power of s."""
    transposed = [list(col) for col in zip(*rows, strict=True)] if rows and rows[0] else []
    candidates = nullspace(transposed, len(names)) if transposed else nullspace([], len(names))
    changing = [y for y in candidates if _dot(y, rhs) != 0]
    best = min(changing, key=lambda y: (sum(1 for x in y if x), [i for i, x in enumerate(y) if x]))
    scaled = [n for n, y in zip(names, best, strict=True) if y and n in scale]
    group = PiGroup.from_exponents(
        dict(zip(names, best, strict=True)),
        variable=scaled[0] if scaled else None,
        order=[n for n in system.variables if n in names],
    )
    group = PiGroup(group.exponents, None)
    return group, _dot([group.exponents.get(n, 0) for n in names], rhs)


def _minimal_points(a0, dirs, free, u0, kept):
    """``(point, coords)`` of every minimal solution of ``a0 + span(dirs)``, in the order of `scalings`.

    `free` are the positions that may be held at zero; `u0` and `kept` are
    the coordinates of `a0` and of the directions over the generators.
    """
    a0, dirs = list(a0), [list(v) for v in dirs]
    if not dirs:
        return [(tuple(a0), tuple(u0))]
    # one common denominator makes the particular point and the directions integers
    den = lcm(*(x.denominator for x in a0), *(x.denominator for v in dirs for x in v))
    a0_int = [int(x * den) for x in a0]
    dirs_int = [[int(x * den) for x in v] for v in dirs]
    from .family import MinimalPoints, minimal_points  # numpy loads only when a family is enumerated

    batched = minimal_points(a0_int, dirs_int, free, [i for i in range(len(a0)) if i not in set(free)])
    if batched is not None:
        return MinimalPoints(*batched, den, u0, kept)
    found = _exact_points(a0_int, dirs_int, den, free, u0, kept)

    def order(point):
        support = [i for i, p in enumerate(point) if p]
        return (len(support), support, [abs(p) for p in point], point)

    return [(p, found[p]) for p in sorted(found, key=order)]


def _exact_points(a0_int, dirs_int, den, free, u0, kept) -> dict[tuple[Fraction, ...], tuple[Fraction, ...]]:
    """Minimal points by one exact solve per subset: for families too large for exact floats."""
    from .bases import independent_subsets

    rows = [[v[i] for i in free] for v in dirs_int]
    seen: dict[tuple[int, ...], tuple[int, ...]] = {}
    for subset in independent_subsets(rows, range(len(free)), [], len(dirs_int)):
        zero = [free[k] for k in subset]
        z = solve([[v[i] for v in dirs_int] for i in zero], [-a0_int[i] for i in zero])
        z_den = lcm(*(x.denominator for x in z))
        z_num = [int(x * z_den) for x in z]
        point = [a * z_den + sum(c * v[i] for c, v in zip(z_num, dirs_int, strict=True)) for i, a in enumerate(a0_int)]
        g = gcd(den * z_den, *point)
        key = (den * z_den // g, *(p // g for p in point))
        if key not in seen:
            seen[key] = tuple(z)
    found = {}
    for (scale_den, *point), z in seen.items():
        exact = tuple(Fraction(p, scale_den) for p in point)
        found[exact] = tuple(u + _dot(z, [w[j] for w in kept]) for j, u in enumerate(u0))
    return found


def search(
    system: System,
    scale: Mapping[str, object],
    fixed: Iterable[str] | None = None,
    *,
    allow: Iterable[str] | None = None,
    within=None,
) -> SearchResult:
    """Find every minimal similarity scaling meeting a request, or prove none exists.

    Parameters
    ----------
    system : System
    scale : mapping of str to number
        Prescribed exponents of the scale factor ``s``: ``{"g": 1}`` means
        ``g -> s g``, ``{"l": -1}`` means ``l -> l / s``.
    fixed : iterable of str, optional
        Variables that must not change.  Default: every variable whose
        dimension is exactly time (T), so the scaled model runs in the same
        time; pass ``fixed=()`` to let time change.
    allow : iterable of str, optional
        If given, only these variables (besides `scale`) may change; all
        others are held fixed.
    within : SymmetryReport, optional
        Search the scaling symmetries of particular equations (from
        :func:`pitheorem.scaling_symmetries`) instead of the changes of
        units.  Variables that do not appear in the equations are held
        fixed.  Solutions beyond changes of units have
        ``is_unit_change`` false (and no ``unit_change``).

    Returns
    -------
    SearchResult

    Raises
    ------
    InvalidRequestError, UnknownVariableError, DuplicateVariableError
        For an empty request, unknown names, non-numeric or zero exponents,
        or a variable both scaled and fixed.

    Examples
    --------
    The white paper's hinged rod, with the force and torque it leaves
    implicit: gravity can be scaled without touching time, in three
    minimal ways.

    >>> import pitheorem as pt
    >>> rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2",
    ...                  "c_theta": "M L^2 T^-1", "t": "T", "F": "M L T^-2", "tau": "M L^2 T^-2"})
    >>> res = pt.search(rod, scale={"g": 1})
    >>> print(res)
    Scaling g by s with t fixed: 3 minimal solutions of a 1-parameter family.
    Time variable t is held fixed by default; pass fixed=() to let time change
    <BLANKLINE>
    variable  role   #1     #2   #3
    m         free   1/s^2  1/s  -
    l         free   s      s    s
    g         scale  s      s    s
    k_theta   free   -      s    s^2
    c_theta   free   -      s    s^2
    t         fixed  -      -    -
    F         free   1/s    -    s
    tau       free   -      s    s^2
    [M]       base   1/s^2  1/s  -
    [L]       base   s      s    s
    [T]       base   -      -    -

    Holding the paper's repeaters m and k_theta as well makes it impossible,
    and the certificate says why:

    >>> print(pt.search(rod, scale={"g": 1}, fixed=("t", "m", "k_theta")).certificate)
    Pi = g**2*m*t**2/k_theta
    """
    if not isinstance(system, System):
        raise InvalidRequestError(f"search needs a System, got {type(system).__name__}")
    if not isinstance(scale, Mapping):
        raise InvalidRequestError(f"scale must be a mapping such as {{'g': 1}}, got {scale!r}")
    if not scale:
        raise InvalidRequestError("empty request: scale must prescribe at least one variable, e.g. scale={'g': 1}")
    scaled = system.check_names(tuple(scale), "scale")
    exponents = {n: read_exponent(scale[n], f"exponent of {n!r}") for n in scaled}
    for n, p in exponents.items():
        if p == 0:
            raise InvalidRequestError(f"scale gives {n!r} exponent 0: to keep {n!r} unchanged, put it in fixed")
    notes = []
    if fixed is None:
        held = tuple(n for n in system.time_variables if n not in exponents)
        if held:
            notes.append(SearchNote("time_fixed", held))
    else:
        held = system.check_names(fixed, "fixed")
    both = [n for n in held if n in exponents]
    if both:
        raise InvalidRequestError(f"variable {both[0]!r} is both scaled and fixed; a variable can be only one")
    if allow is not None:
        allowed = system.check_names(allow, "allow")
        clash = [n for n in allowed if n in held]
        if clash:
            raise InvalidRequestError(f"variable {clash[0]!r} is both fixed and allowed to change")
        extra = tuple(n for n in system.variables if n not in allowed and n not in exponents and n not in held)
        held = held + extra
    generators = None
    if within is not None:
        generators, outside = _symmetry_generators(system, within, exponents)
        extra = tuple(n for n in outside if n not in held)
        if extra:
            notes.append(SearchNote("outside_equations", extra))
            held = held + extra
    return _solve(system, exponents, held, tuple(notes), generators)


def _symmetry_generators(system: System, within, exponents):
    from .equations import SymmetryReport  # sympy's equation machinery loads only for within=

    if not isinstance(within, SymmetryReport):
        raise InvalidRequestError(f"within must be a SymmetryReport from scaling_symmetries, got {within!r}")
    variables, basis = within.variables, within.basis
    for n in variables:
        system.index(n, "within (the equations' symbols)")
    for n in exponents:
        if n not in variables:
            raise InvalidRequestError(
                f"{n!r} does not appear in the equations, so their symmetries say nothing about scaling it"
            )
    generators = [[Fraction(vec.get(n, 0)) for n in system.variables] for vec in basis]
    outside = tuple(n for n in system.variables if n not in variables)
    return generators, outside
