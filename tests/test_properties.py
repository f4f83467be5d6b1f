"""Property tests over random dimension matrices (hypothesis), across modules.

Cross-cutting: each property ties several modules together on the same random
system, against oracles that use none of them (sympy's exact rank, every
subset tried in turn): the Pi groups of ``System.pi_groups`` (system,
groups, linalg) are dimensionless and number n - rank, the enumeration of
repeating sets (bases, basis_sequence) equals brute force, with exclude and
require, and Pi sets from any two bases are equivalent (groups).  The
properties of one module alone are in that module's test file.
"""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

import pitheorem as pt
from tests.conftest import dimension_of_group, oracle_bases, rational_exponent, sympy_rank, systems


def check_groups(system: pt.System):
    groups = system.pi_groups()
    assert len(groups) == len(system.variables) - system.rank == system.n_groups
    for group in groups:
        assert dimension_of_group(system, group) == {}
        assert group.exponents.get(group.variable, 0) > 0
        assert all(isinstance(p, int) for p in group.exponents.values())
    matrix = groups.exponent_matrix()
    assert not matrix or sympy_rank(matrix) == len(groups)  # independent
    return groups


@settings(max_examples=120, deadline=None)
@given(systems(max_vars=9))
def test_integer_systems_groups(system):
    check_groups(system)


@settings(max_examples=80, deadline=None)
@given(systems(exponent=rational_exponent, max_vars=9))
def test_rational_systems_groups(system):
    check_groups(system)


@settings(max_examples=120, deadline=None)
@given(systems(max_vars=10))
def test_bases_equal_brute_force(system):
    expected = oracle_bases(system)
    assert system.bases() == expected
    assert system.count_bases() == len(expected)


@settings(max_examples=60, deadline=None)
@given(systems(exponent=rational_exponent, max_vars=8))
def test_rational_bases_equal_brute_force(system):
    assert system.bases() == oracle_bases(system)


@settings(max_examples=60, deadline=None)
@given(systems(max_vars=8), st.data())
def test_exclude_and_require_filter_brute_force(system, data):
    names = system.variables
    exclude = data.draw(st.lists(st.sampled_from(names), unique=True, max_size=2))
    everything = oracle_bases(system)
    assert system.bases(exclude=exclude) == [b for b in everything if not set(b) & set(exclude)]
    if everything:
        basis = data.draw(st.sampled_from(everything))
        require = basis[:1]
        assert system.bases(require=require) == [b for b in everything if set(require) <= set(b)]


@settings(max_examples=60, deadline=None)
@given(systems(max_vars=8), st.data())
def test_piset_from_any_two_bases_equivalent(system, data):
    bases = system.bases()
    first = data.draw(st.sampled_from(bases))
    second = data.draw(st.sampled_from(bases))
    assert system.pi_groups(repeating=first).equivalent(system.pi_groups(repeating=second))
