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

#: the paper's hinged rod (Section 2.1), with force and torque
ROD = {
    "m": "M",
    "theta_r": "1",
    "l": "L",
    "g": "L T^-2",
    "k_theta": "M L^2 T^-2",
    "c_theta": "M L^2 T^-1",
    "t": "T",
    "F": "M L T^-2",
    "tau": "M L^2 T^-2",
}

#: the NTRT SUPERball CONFIG list of Section 4, plus m and l, and the Corde moduli
SUPERBALL = {
    "m": "M",
    "l": "L",
    "k": "M T^-2",
    "x_r": "L",
    "g": "L T^-2",
    "c": "M T^-1",
    "F": "M L T^-2",
    "t": "T",
    "G": "M L^-1 T^-2",
    "E": "M L^-1 T^-2",
    "v": "L T^-1",
    "rho": "M L^-3",
}


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
