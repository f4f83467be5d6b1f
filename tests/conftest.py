"""Shared fixtures: the white paper's systems, broken model files, and a matplotlib guard."""

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


#: Broken model files, each with what its one-line message must say: the reader
#: (test_modelfile) and the command line (test_cli) are checked on every one.
BROKEN_MODEL_FILES = {
    "bad_toml": ('[variables]\nm = { dimension = "M"\n', ["line 2", "invalid TOML"]),
    "bad_toml_value": ("[variables]\nm = = 1\n", ["line 2", "invalid TOML"]),
    "not_utf8": ("\udcff[variables]\n", ["not UTF-8"]),
    "missing_variables": ('name = "x"\n', ["no [variables]"]),
    "variables_not_table": ("variables = 3\n", ["variables", "must be a table", "3"]),
    "empty_variables": ("[variables]\n", ["[variables]", "empty"]),
    "unknown_top_key": ('nmae = "x"\n[variables]\nl = { dimension = "L" }\n', ["'nmae'", "did you mean 'name'"]),
    "unknown_key": ('[variables]\nl = { dimension = "L", vaule = 2 }\n', ["variable 'l'", "'vaule'", "'value'"]),
    "unknown_key_dim": ('[variables]\nl = { dim = "L" }\n', ["variable 'l'", "'dim'"]),
    "both": ('[variables]\nl = { dimension = "L", unit = "m" }\n', ["variable 'l'", "both dimension and unit"]),
    "neither": ('[variables]\nl = { value = 2 }\n', ["variable 'l'", "neither dimension nor unit"]),
    "unknown_dimension": ('[variables]\nq = { dimension = "Q" }\n', ["variable 'q'", "'Q'"]),
    "bad_dimension_syntax": ('[variables]\nm = { dimension = "M L^^2" }\n',
                             ["variable 'm'", "'M L^^2'", "position 4"]),
    "dimension_not_string": ("[variables]\nq = { dimension = 1 }\n", ["variable 'q'", "string"]),
    "outside_base_dimensions": ('base_dimensions = ["M", "L"]\n[variables]\nt = { dimension = "T" }\n',
                                ["variable 't'", "unknown base dimension 'T'", "M, L"]),
    "bad_base_dimensions": ('base_dimensions = "MLT"\n[variables]\nm = { dimension = "M" }\n',
                            ["base_dimensions", "'MLT'"]),
    "bad_unit": ('[variables]\nq = { unit = "furlongz" }\n', ["variable 'q'", "furlongz"]),
    "duplicate": ('[variables]\nm = { dimension = "M" }\nm = { dimension = "L" }\n',
                  ["line 3", "variable 'm'", "twice"]),
    "duplicate_table": ('[variables.m]\ndimension = "M"\n[variables.m]\ndimension = "L"\n',
                        ["line 3", "variable 'm'", "twice"]),
    "duplicate_key_in_entry": ('[variables]\nm = { dimension = "M", dimension = "L" }\n', ["line 2"]),
    "bad_role": ('[variables]\nt = { dimension = "T", role = "clock" }\n', ["variable 't'", "'clock'", "time"]),
    "time_not_T": ('[variables]\nl = { dimension = "L", role = "time" }\n',
                   ["variable 'l'", "dimension L", "dimension T"]),
    "two_times": ('[variables]\nt = { dimension = "T", role = "time" }\ntau = { dimension = "T", role = "time" }\n',
                  ["variable 'tau'", "'t'", "at most one"]),
    "value_not_number": ('[variables]\nm = { dimension = "M", value = "heavy" }\n', ["variable 'm'", "'heavy'"]),
    "value_bool": ('[variables]\nm = { dimension = "M", value = true }\n', ["variable 'm'", "true"]),
    "value_list": ('[variables]\nm = { dimension = "M", value = [1, 2] }\n', ["variable 'm'", "number"]),
    "value_zero_denominator": ('[variables]\nm = { dimension = "M", value = "1/0" }\n', ["variable 'm'", "'1/0'"]),
    "value_nan": ('[variables]\nm = { dimension = "M", value = nan }\n', ["variable 'm'", "finite", "nan"]),
    "entry_not_table": ('[variables]\nm = "M"\n', ["variable 'm'", "must be a table"]),
    "bad_name": ('[variables]\nk-theta = { dimension = "M" }\n', ["variable 'k-theta'", "valid name", "k_theta"]),
    "name_not_string": ('name = 3\n[variables]\nm = { dimension = "M" }\n', ["name must be a string"]),
    "bad_description": ('[variables]\nm = { dimension = "M", description = 3 }\n', ["variable 'm'", "description"]),
}


def broken_model_file(folder: Path, case: str) -> tuple[Path, list[str]]:
    """Write the broken model file `case` of :data:`BROKEN_MODEL_FILES` into `folder`; its path and fragments."""
    text, fragments = BROKEN_MODEL_FILES[case]
    path = folder / f"{case}.toml"
    path.write_bytes(text.encode("utf-8", errors="surrogateescape"))  # not_utf8 holds a stray byte
    return path, fragments


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
