"""Shared text and LaTeX rendering of powers of the scale factor ``s``."""

from __future__ import annotations

from fractions import Fraction

__all__ = ["power_latex", "power_text"]


def power_text(exponent) -> str:
    """Plain-text power of s: ``-`` for unchanged, ``s``, ``s^2``, ``1/s``, ``s^(1/2)``.

    Examples
    --------
    >>> from pitheorem.display import power_text
    >>> [power_text(p) for p in (0, 1, 2, -1, -3, 0.5)]
    ['-', 's', 's^2', '1/s', '1/s^3', 's^(1/2)']
    """
    p = Fraction(exponent).limit_denominator() if isinstance(exponent, float) else Fraction(exponent)
    if p == 0:
        return "-"
    if p == 1:
        return "s"
    if p == -1:
        return "1/s"
    if p.denominator != 1:
        return f"s^({p})"
    return f"s^{p}" if p > 0 else f"1/s^{-p}"


def power_latex(exponent) -> str:
    r"""LaTeX power of s: ``1`` for unchanged, ``s^{2}``, ``s^{-1/2}`` ...

    Examples
    --------
    >>> from pitheorem.display import power_latex
    >>> from fractions import Fraction
    >>> [power_latex(p) for p in (0, 1, -1, Fraction(1, 2))]
    ['1', 's', 's^{-1}', 's^{1/2}']
    """
    p = Fraction(exponent)
    if p == 0:
        return "1"
    if p == 1:
        return "s"
    return f"s^{{{p}}}"
