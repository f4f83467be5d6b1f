"""``python -m pitheorem``: the command line of :mod:`pitheorem.cli`."""

from __future__ import annotations

__all__: list[str] = []

if __name__ == "__main__":
    import sys

    from .cli import main

    sys.exit(main())
