"""Immutable value types: the one decorator, :func:`immutable`, that every public value type wears.

A value type (a :class:`~pitheorem.System`, a :class:`~pitheorem.Scaling`,
a search result, ...) is made whole by its constructor and never changes
afterwards.  Frozen dataclasses mostly enforce that themselves, but not
uniformly: under Python 3.11 a frozen dataclass with ``slots=True``
answers the assignment of a name that is no field (``sc.foo = 1``) with an
unrelated ``TypeError`` about ``super()``, and classes with plain
``__slots__`` refuse nothing at all.  :func:`immutable` replaces
``__setattr__`` and ``__delattr__`` by one method that raises
:class:`dataclasses.FrozenInstanceError` (an ``AttributeError``) naming the
attribute and the type, for every class it decorates.

A constructor, ``__post_init__`` or a lazy cache writes its own attributes
with ``object.__setattr__``, which the decorator leaves alone.
"""

from __future__ import annotations

from dataclasses import FrozenInstanceError

__all__ = ["immutable"]


def _refuse(self, name: str, *value) -> None:
    raise FrozenInstanceError(
        f"cannot assign or delete {name!r}: a {type(self).__name__} is immutable (build a new one instead)"
    )


def immutable(cls: type) -> type:
    """Make every attribute assignment and deletion on instances of `cls` raise.

    Parameters
    ----------
    cls : type
        The class to protect; its own code must write attributes with
        ``object.__setattr__``.

    Returns
    -------
    type
        The same class.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> from pitheorem.immutable import immutable
    >>> @immutable
    ... @dataclass(frozen=True, slots=True)
    ... class Point:
    ...     x: int
    >>> p = Point(1)
    >>> try:
    ...     p.y = 2
    ... except AttributeError as err:
    ...     print(err)
    cannot assign or delete 'y': a Point is immutable (build a new one instead)
    """
    cls.__setattr__ = _refuse
    cls.__delattr__ = _refuse
    return cls
