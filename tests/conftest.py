"""Shared fixtures: the white paper's systems, and a matplotlib guard."""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

REPO = Path(__file__).resolve().parents[1]
REFERENCE = REPO.parent / "shared" / "reference"
if str(REPO) not in sys.path:  # lets tests import matlab_ports/ and benchmarks/
    sys.path.insert(0, str(REPO))

import pitheorem as pt  # noqa: E402

#: the paper's hinged rod (Section 2.1) with force and torque, as name -> formula
ROD = {name: str(dim) for name, dim in pt.models.rod_system().dimensions.items()}

#: the NTRT SUPERball CONFIG list of Section 4, plus m and l, and the Corde moduli
SUPERBALL = {name: str(dim) for name, dim in pt.models.superball_parameters().dimensions.items()}


@pytest.fixture
def rod() -> pt.System:
    return pt.System(ROD)


@pytest.fixture
def superball() -> pt.System:
    return pt.System(SUPERBALL)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")
