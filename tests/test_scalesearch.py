"""pitheorem.scalesearch (pt.search): the white paper's cases, properties against brute force, bad requests."""

from __future__ import annotations

import pickle
from fractions import Fraction
from itertools import product
from types import SimpleNamespace
from unittest import mock

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import pitheorem as pt
from pitheorem import bases as bases_module
from pitheorem import family as family_module
from pitheorem.exact import (
    MAX_DENOMINATOR,
)
from tests.conftest import PRIMES, dimension_of_group, oracle_search, systems


def exps(scaling: pt.Scaling) -> dict[str, Fraction]:
    return {n: Fraction(p) for n, p in zip(scaling.system.variables, scaling.vector, strict=True) if p}


def test_rod_gravity_time_free_has_exactly_three_minimal_solutions(rod):
    res = pt.search(rod, scale={"g": 1})
    assert res.feasible
    assert res.fixed == ("t",)
    assert res.notes == (pt.SearchNote("time_fixed", ("t",)),)
    assert "fixed by default" in str(res.notes[0])
    assert [exps(s) for s in res.scalings] == [
        {"m": -2, "l": 1, "g": 1, "F": -1},
        {"m": -1, "l": 1, "g": 1, "k_theta": 1, "c_theta": 1, "tau": 1},
        {"l": 1, "g": 1, "k_theta": 2, "c_theta": 2, "F": 1, "tau": 2},
    ]
    assert res.n_scalings == 3
    assert len(res.directions) == 1


def test_rod_gravity_with_paper_repeaters_fixed_is_impossible(rod):
    res = pt.search(rod, scale={"g": 1}, fixed=("t", "m", "k_theta"))
    assert not res.feasible
    assert res.scalings == []
    assert res.n_scalings == 0
    assert res.certificate.is_power_of(pt.PiGroup((("g", 2), ("t", 2), ("m", 1), ("k_theta", -1))))
    assert res.certificate_power != 0
    assert "g**2*m*t**2/k_theta" in res.explanation()


def test_paper_final_scaling_runs_s_times_faster(rod):
    res = pt.search(rod, scale={"g": 1, "l": -1}, fixed=("m", "k_theta"))
    assert res.notes == ()  # an explicit fixed replaces the default
    (only,) = res.scalings
    assert exps(only) == {"l": -1, "g": 1, "c_theta": -1, "t": -1, "F": 1}
    assert only.unit_change == {"M": 0, "L": -1, "T": -1}


def test_dimensionless_variable_cannot_be_scaled(rod):
    res = pt.search(rod, scale={"theta_r": 1})
    assert not res.feasible
    assert res.certificate.exponents == {"theta_r": 1}


def test_superball_length_scaling_is_unique(superball):
    res = pt.search(superball, scale={"l": 1}, fixed=("t", "m"))
    (only,) = res.scalings
    assert exps(only) == {"l": 1, "g": 1, "x_r": 1, "F": 1, "v": 1, "rho": -3, "G": -1, "E": -1}


def test_allow_restricts_changes(rod):
    res = pt.search(rod, scale={"g": 1}, allow=("l", "m", "F"))
    assert [exps(s) for s in res.scalings] == [{"m": -2, "l": 1, "g": 1, "F": -1}]
    assert set(res.fixed) >= {"t", "k_theta", "c_theta", "tau", "theta_r"}


@st.composite
def requests(draw):
    system = draw(systems(max_vars=8))
    names = system.variables
    target = draw(st.sampled_from(names))
    power = draw(st.sampled_from([Fraction(1), Fraction(-1), Fraction(2), Fraction(1, 2)]))
    others = [n for n in names if n != target]
    fixed = draw(st.lists(st.sampled_from(others), unique=True, max_size=3)) if others else []
    return system, {target: power}, tuple(fixed)


@settings(max_examples=150, deadline=None)
@given(requests())
def test_minimal_scalings_equal_brute_force(request):
    system, scale, fixed = request
    res = pt.search(system, scale=scale, fixed=fixed)
    got = {s.vector for s in res.scalings}
    assert len(got) == len(res.scalings)
    # the sympy oracle needs a base dimension; with none, no variable can change
    assert got == (set(oracle_search(system, scale, fixed)) if system.base_dimensions else set())
    assert res.feasible == bool(got) or not system.base_dimensions


@settings(max_examples=150, deadline=None)
@given(requests())
def test_scalings_keep_groups_and_respect_request(request):
    system, scale, fixed = request
    res = pt.search(system, scale=scale, fixed=fixed)
    groups = system.pi_groups()
    for sc in res.scalings:
        for group in groups:
            assert sum(sc.vector[system.index(n)] * p for n, p in group.exponents.items()) == 0
        for n, p in scale.items():
            assert sc.vector[system.index(n)] == p
        for n in fixed:
            assert sc.vector[system.index(n)] == 0
        # a = D^T u
        for n, p in zip(system.variables, sc.vector, strict=True):
            assert sc.exponent_of(system.dimension(n)) == p


@settings(max_examples=150, deadline=None)
@given(requests())
def test_certificates_prove_impossibility(request):
    system, scale, fixed = request
    res = pt.search(system, scale=scale, fixed=fixed)
    assume(not res.feasible)
    cert = res.certificate
    assert dimension_of_group(system, cert) == {}
    assert set(cert.exponents) <= set(scale) | set(fixed)
    change = sum(scale.get(n, 0) * p for n, p in cert.exponents.items())
    assert change != 0
    assert change == res.certificate_power


BAD = [
    ({"scale": {}}, pt.InvalidRequestError, "empty request"),
    ({"scale": {"gravity": 1}}, pt.UnknownVariableError, "'gravity'"),
    ({"scale": {"g": 1}, "fixed": ("g",)}, pt.InvalidRequestError, "'g' is both scaled and fixed"),
    ({"scale": {"g": "fast"}}, pt.InvalidRequestError, "'fast'"),
    ({"scale": {"g": None}}, pt.InvalidRequestError, "None"),
    ({"scale": {"g": True}}, pt.InvalidRequestError, "True"),
    ({"scale": {"g": float("nan")}}, pt.InvalidRequestError, "nan"),
    ({"scale": {"g": 0}}, pt.InvalidRequestError, "put it in fixed"),
    ({"scale": {"g": 1}, "fixed": ("time",)}, pt.UnknownVariableError, "'time'"),
    ({"scale": {"g": 1}, "fixed": ("t", "t")}, pt.DuplicateVariableError, "'t'"),
    ({"scale": {"g": 1}, "fixed": ("t",), "allow": ("t",)}, pt.InvalidRequestError, "'t'"),
    ({"scale": {"g": 1}, "allow": ("nope",)}, pt.UnknownVariableError, "'nope'"),
    ({"scale": [("g", 1)]}, pt.InvalidRequestError, "mapping"),
]


@pytest.mark.parametrize(("kwargs", "kind", "culprit"), BAD)
def test_bad_requests(rod, kwargs, kind, culprit):
    with pytest.raises(kind) as info:
        pt.search(rod, **kwargs)
    assert culprit in str(info.value)


def test_within_takes_a_symmetry_report_not_a_look_alike():
    proj = pt.models.projectile()
    sym = pt.scaling_symmetries(proj.equations, proj.system)
    look_alike = SimpleNamespace(variables=sym.variables, basis=sym.basis)  # what the old attribute check accepted
    for bad in (look_alike, {"variables": sym.variables}, None.__class__):
        with pytest.raises(pt.InvalidRequestError, match="within must be a SymmetryReport"):
            pt.search(proj.system, scale={"x": 1}, fixed=("t", "g"), within=bad)


def _search_module():
    import pitheorem.scalesearch as module  # the module; pt.search is its function

    return module


@pytest.mark.parametrize(
    "attr",
    [
        "feasible",
        "scale",
        "fixed",
        "notes",
        "certificate",
        "certificate_power",
        "particular",
        "directions",
        "system",
        "n_scalings",
    ],
)
def test_result_attributes_cannot_be_assigned(rod, attr):
    res = pt.search(rod, scale={"g": 1})
    with pytest.raises(AttributeError):
        setattr(res, attr, None)
    with pytest.raises(AttributeError):
        res.new_attribute = 1  # slots: no attribute outside the fields either
    with pytest.raises(TypeError):
        res.scale["g"] = 2  # the prescribed exponents are a read-only mapping
    assert res.feasible
    assert res.scale == {"g": 1}


def test_repr_does_not_enumerate_and_the_enumeration_runs_once(rod):
    module = _search_module()
    with mock.patch.object(module, "_minimal_points", wraps=module._minimal_points) as spy:
        res = pt.search(rod, scale={"g": 1})
        text = repr(res)
        assert spy.call_count == 0
        assert text == (
            "<SearchResult g by s with t fixed: feasible, a family of dimension 1, at most 7 minimal solution(s)>"
        )
        assert res.max_n_scalings == 7  # known without enumerating
        assert spy.call_count == 0
        assert res.n_scalings == 3
        assert len(res.scalings) == 3
        str(res), res.table(), res._repr_html_(), list(res.iter_scalings())
        assert spy.call_count == 1
    infeasible = pt.search(rod, scale={"g": 1}, fixed=("t", "m", "k_theta"))
    assert repr(infeasible) == (
        "<SearchResult g by s with t, m, k_theta fixed: infeasible, certificate g**2*m*t**2/k_theta>"
    )
    assert repr(pt.search(rod, scale={"g": 1, "l": -1}, fixed=("m", "k_theta"))) == (
        "<SearchResult g by s, l by 1/s with m, k_theta fixed: feasible, unique>"
    )


def test_equal_requests_give_equal_hashable_results(rod):
    a, b = pt.search(rod, scale={"g": 1}), pt.search(rod, scale={"g": 1})
    assert a.n_scalings == 3  # one enumerated, one not: still equal
    assert a == b
    assert hash(a) == hash(b)
    assert a != pt.search(rod, scale={"g": 1}, fixed=())


def test_results_pickle_before_and_after_enumerating(rod):

    for res in (pt.search(rod, scale={"g": 1}), pt.search(rod, scale={"g": 1}, fixed=("t", "m", "k_theta"))):
        again = pickle.loads(pickle.dumps(res))
        assert again == res
        assert again.scalings == res.scalings  # enumerates both
        assert pickle.loads(pickle.dumps(res)).n_scalings == res.n_scalings
        with pytest.raises(TypeError):
            again.scale["g"] = 2


def test_notes_are_data_phrased_by_each_front_end(rod):
    res = pt.search(rod, scale={"g": 1})
    (note,) = res.notes
    assert (note.kind, note.variables) == ("time_fixed", ("t",))
    assert str(note) == "Time variable t is held fixed by default; pass fixed=() to let time change"
    assert str(note) in str(res).splitlines()
    with pytest.raises(AttributeError):
        note.kind = "outside_equations"
    with pytest.raises(pt.InvalidRequestError, match="unknown note kind"):
        pt.SearchNote("a sentence", ("t",))
    two = pt.System({"l": "L", "g": "L T^-2", "t": "T", "dt": "T"})
    assert str(pt.search(two, scale={"g": 1}).notes[0]).startswith("Time variables t, dt are held fixed")


ROD = {"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "c_theta": "M L^2 T^-1", "theta_r": "1", "t": "T"}


LT = pt.System({"l": "L", "t": "T"})


def test_search_with_two_large_coprime_denominators():
    # was: OverflowError (the lcm of the denominators, ~1e24, entered an int64 array)
    s = pt.System({"l": "L", "t": "T", "m": "M", "v": "L/T"})
    q1, q2 = 999_999_999_989, 999_999_999_959
    res = pt.search(s, scale={"l": Fraction(1, q1), "t": Fraction(1, q2)}, fixed=())
    assert res.n_scalings == 1
    sc = res.scalings[0]
    assert sc.exponents["v"] == Fraction(1, q1) - Fraction(1, q2)
    assert sc.exponents["m"] == 0


@pytest.mark.parametrize("p", [2, 3, 5, 7, 11, 13, 17, 19, 23, 29])
def test_exponent_one_over_prime(p):
    rod = pt.System(ROD)
    res = pt.search(rod, scale={"g": Fraction(1, p)})
    assert res.feasible
    for sc in res.scalings:
        assert sc.exponents["g"] == Fraction(1, p)
        assert sc.exponents["t"] == 0


@pytest.mark.parametrize("value", [1e-13, np.float64(3e-13)])
def test_float_exponent_beyond_denominator_limit_is_named(value):
    with pytest.raises(pt.LimitError) as info:
        pt.search(LT, scale={"l": value}, fixed=())
    assert str(MAX_DENOMINATOR) in str(info.value)
    assert "Fraction(1, 3)" in str(info.value)  # says how to write it exactly


@pytest.mark.parametrize("value", [1 / 3e12, 1 / 1001, 2**0.5, np.float64(np.pi)])
def test_a_computed_float_exponent_of_no_simple_fraction_is_named(value):
    # issue 33: a computed float's simplest fraction must have a denominator of at most 1000 to be an exponent
    with pytest.raises(pt.NumberError, match="may not exceed 1000") as info:
        pt.search(LT, scale={"l": value}, fixed=())
    assert info.value.culprit == value
    assert "exponent of 'l'" in str(info.value)


@pytest.mark.parametrize(
    ("value", "exponent"),
    [
        (Fraction(1, 10**9), Fraction(1, 10**9)),
        (1e-9, Fraction(1, 10**9)),
        (0.123456789, Fraction(123456789, 10**9)),
        (1 / 3, Fraction(1, 3)),  # a computed float: the simplest fraction that rounds to it
        (np.float64(2 / 7), Fraction(2, 7)),
        (np.float64(0.5), Fraction(1, 2)),
        (np.float32(0.1), Fraction(1, 10)),
        (np.int64(2), Fraction(2)),
        ("1/3", Fraction(1, 3)),
    ],
)
def test_exponents_read_as_written(value, exponent):
    res = pt.search(LT, scale={"l": value}, fixed=())
    assert res.n_scalings == 1
    assert res.scalings[0].exponents["l"] == exponent


def test_fraction_one_over_ten_to_twenty_is_named():
    with pytest.raises(pt.LimitError, match=str(MAX_DENOMINATOR)):
        pt.search(LT, scale={"l": Fraction(1, 10**20)}, fixed=())


@pytest.mark.parametrize("g", [Fraction(1, 3), Fraction(1, 10**9), Fraction(1, 10**12)])
def test_search_with_large_denominators_on_the_rod(g):
    rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k_theta": "M L^2 T^-2", "c_theta": "M L^2 T^-1", "t": "T"})
    result = pt.search(rod, scale={"g": g}, fixed=())
    expected = oracle_search(rod, {"g": g}, ())
    assert result.n_scalings == len(expected)
    assert [s.vector for s in result.scalings] == expected


def test_denominator_over_the_limit_is_named():
    rod = pt.System({"l": "L", "g": "L T^-2", "t": "T"})
    with pytest.raises(pt.errors.LimitError, match="denominator"):
        pt.search(rod, scale={"g": Fraction(1, 10**20)}, fixed=())


def test_search_one_third_on_length_and_time():
    system = pt.System({"l": "L", "t": "T"})
    result = pt.search(system, scale={"l": Fraction(1, 3)}, fixed=())
    assert result.n_scalings == len(oracle_search(system, {"l": Fraction(1, 3)}, ())) == 1


@settings(max_examples=50, deadline=None)
@given(systems(exponent=st.sampled_from([-2, -1, 0, 0, 1, 2, Fraction(1, 2)]), max_vars=6, max_bases=3), st.data())
def test_search_equals_brute_force_in_order(system, data):
    name = data.draw(st.sampled_from(system.variables))
    power = data.draw(st.sampled_from([1, -1, 2, Fraction(1, 3), Fraction(-3, 2)]))
    others = [n for n in system.variables if n != name]
    fixed = tuple(data.draw(st.lists(st.sampled_from(others), unique=True, max_size=2))) if others else ()
    result = pt.search(system, scale={name: power}, fixed=fixed)
    if not result.feasible:
        return
    expected = oracle_search(system, {name: power}, fixed)
    assert [s.vector for s in result.scalings] == expected
    # the exact fallback agrees, coordinates included
    with mock.patch.object(family_module, "minimal_points", return_value=None):
        exact = pt.search(system, scale={name: power}, fixed=fixed)
        assert list(exact._enumerate()) == list(result._enumerate())
    with mock.patch.object(family_module, "_MERGE_EVERY", 1), mock.patch.object(bases_module, "_CHUNK", 2):
        assert list(pt.search(system, scale={name: power}, fixed=fixed)._enumerate()) == list(result._enumerate())


def test_batched_search_takes_the_vectorised_path_and_scalings_are_units():
    system = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k": "M T^-2", "t": "T", "v": "L/T"})
    result = pt.search(system, scale={"g": 1}, fixed=())
    assert isinstance(result._enumerate(), family_module.MinimalPoints)
    for scaling in result.scalings:
        exps = scaling.vector
        unit = scaling.unit_change
        for j, n in enumerate(system.variables):
            assert exps[j] == sum(system.dimension(n).exponent_of(b) * unit[b] for b in system.base_dimensions)


def support(group) -> set[str]:
    return {n for n, p in group.exponents.items() if p}


@pytest.mark.parametrize(
    ("variables", "expected"),
    [
        # four lengths: every pair is a certificate; the first pair in system order is chosen
        ({"a": "L", "b": "L", "c": "L", "d": "L"}, {"a", "b"}),
        # a/d (two variables) beats a*b/c (three)
        ({"c": "L M", "b": "M", "a": "L", "d": "L"}, {"a", "d"}),
        ({"d": "L", "c": "L M", "b": "M", "a": "L"}, {"a", "d"}),
    ],
)
def test_certificate_has_fewest_variables(variables, expected):
    res = pt.search(pt.System(variables), scale={"a": 1}, fixed=tuple(n for n in variables if n != "a"))
    assert not res.feasible
    assert support(res.certificate) == expected


def test_certificate_is_as_small_as_any_changing_product():
    # oracle: brute force over small integer exponent vectors of the fixed and scaled variables
    names = ("m", "l", "g", "k", "t")
    dims = {"m": (1, 0, 0), "l": (0, 1, 0), "g": (0, 1, -2), "k": (1, 2, -2), "t": (0, 0, 1)}
    system = pt.System({"m": "M", "l": "L", "g": "L T^-2", "k": "M L^2 T^-2", "t": "T"})
    res = pt.search(system, scale={"g": 1}, fixed=("m", "k", "t"))
    smallest = min(
        sum(1 for e in vec if e)
        for vec in product(range(-2, 3), repeat=len(names))
        if vec[names.index("g")] != 0
        and vec[names.index("l")] == 0
        and all(sum(e * dims[n][i] for e, n in zip(vec, names, strict=True)) == 0 for i in range(3))
    )
    assert len(support(res.certificate)) == smallest == 4  # g^2 t^2 m / k, as in the paper


def test_search_with_reciprocal_prime_exponents():
    variables = {
        f"x{p}": {"L": Fraction(1, p), "T": Fraction(1, q)} for p, q in zip(PRIMES, (*PRIMES[1:], 2), strict=True)
    }
    small = pt.System({n: variables[n] for n in ("x2", "x3", "x23", "x29")} | {"t": "T"})
    result = pt.search(small, scale={"x23": 1}, fixed=())
    assert [s.vector for s in result.scalings] == oracle_search(small, {"x23": 1}, ())


def test_a_search_holds_every_time_variable_by_default():
    system = pt.System({"l": "L", "g": "L T^-2", "t": "T", "tau": "T"})
    res = pt.search(system, scale={"g": 1})
    assert res.notes[0].variables == system.time_variables == ("t", "tau")
    assert all(sc.exponents["t"] == sc.exponents["tau"] == 0 for sc in res.scalings)
    # a scaled time variable is not held as well
    assert pt.search(system, scale={"tau": 1}).notes[0].variables == ("t",)


def test_search_needs_a_system():
    with pytest.raises(pt.InvalidRequestError, match="System"):
        pt.search({"g": "L"}, scale={"g": 1})


@pytest.mark.parametrize(
    ("variables", "name", "power"),
    [
        # found by mutating _exact_points (gcd(den // z_den, ...)): solutions whose denominator exceeds the
        # system's common one came out with the prescribed exponent 2 turned into 95/47
        (
            {
                "x0": {"M": Fraction(2, 3), "L": 2, "T": 3},
                "x1": {"M": 2, "L": Fraction(1, 3)},
                "x2": {"M": 3, "L": Fraction(1, 3), "T": Fraction(2, 3)},
                "x3": {"M": 3, "T": 2},
                "x4": {"L": Fraction(1, 2)},
            },
            "x0",
            2,
        ),
        (
            {
                "x0": {"M": Fraction(1, 2), "T": 3},
                "x1": {"M": Fraction(2, 3), "L": 3, "T": 3},
                "x2": {"M": -1, "T": Fraction(1, 2)},
                "x3": {"L": 2, "T": Fraction(-3, 2)},
                "x4": {"M": 3, "L": -1, "T": 3},
                "x5": {"T": 2},
            },
            "x3",
            2,
        ),
    ],
)
def test_exact_fallback_with_solution_denominators_beyond_the_systems(variables, name, power):
    system = pt.System(variables)
    expected = oracle_search(system, {name: power}, ())
    with mock.patch.object(family_module, "minimal_points", return_value=None):  # the exact path, one solve each
        result = pt.search(system, scale={name: power}, fixed=())
        assert [s.vector for s in result.scalings] == expected
    assert [s.vector for s in pt.search(system, scale={name: power}, fixed=()).scalings] == expected


@pytest.mark.parametrize("variables", ["t", ["t", 3]])
def test_a_notes_variables_are_a_sequence_of_names(variables):
    with pytest.raises(pt.InvalidRequestError, match="sequence of names"):
        pt.SearchNote("time_fixed", variables)


def test_an_infeasible_search_has_no_scalings_to_count():
    res = pt.search(pt.System({"l": "L", "t": "T", "g": "L T^-2"}), scale={"g": 1}, fixed=("l", "t"))
    assert not res.feasible
    assert res.max_n_scalings == 0


def test_a_search_within_symmetries_of_equations():
    import sympy

    # the projectile's horizontal motion (x' = vx, vx' = 0) is free of g: stretching x and vx alone
    # keeps every equation; m appears in none of them
    proj = pt.models.projectile()
    sym = pt.scaling_symmetries(proj.equations, proj.system)
    res = pt.search(proj.system, scale={"x": 1}, fixed=("t", "g"), within=sym)
    assert res.notes == (pt.SearchNote("outside_equations", ("m",)),)
    assert [exps(sc) for sc in res.scalings] == [{"x": 1, "vx": 1}]
    assert [sc.is_unit_change for sc in res.scalings] == [False]
    assert [sc.unit_change_vector for sc in res.iter_scalings()] == [None]
    x, q = sympy.symbols("x q")
    three = pt.System({"x": "L", "t": "T", "u": "T"})
    with pytest.raises(pt.InvalidRequestError) as caught:
        pt.search(three, scale={"t": 1}, within=pt.scaling_symmetries([sympy.Eq(x, 0)], three, time=None))
    assert str(caught.value) == "'t' does not appear in the equations, so their symmetries say nothing about scaling it"
    other = pt.System({"x": "L", "q": "T"})
    with pytest.raises(pt.UnknownVariableError) as caught:
        pt.search(
            pt.System({"x": "L", "t": "T"}),
            scale={"x": 1},
            within=pt.scaling_symmetries([sympy.Eq(x, q)], other, time=None),
        )
    assert str(caught.value) == "unknown variable 'q' in within (the equations' symbols); the system has x, t"


def test_search_plot_draws_into_the_given_axes():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    res = pt.search(pt.System({"l": "L", "t": "T", "g": "L T^-2"}), scale={"g": 1})
    fig, ax = plt.subplots()
    try:
        assert res.plot(ax=ax) is fig
        assert len(res.scalings) == 1
        assert ax.get_title() == "g by s: 1 minimal scaling"  # one scaling, no plural
        own = res.plot()
        assert own is not fig
        assert own.axes[0].get_title() == ax.get_title()
    finally:
        plt.close("all")


def test_an_unknown_note_kind_names_the_kinds():
    with pytest.raises(pt.InvalidRequestError) as caught:
        pt.SearchNote("a sentence", ("t",))
    assert str(caught.value) == "unknown note kind 'a sentence'; the kinds are time_fixed, outside_equations"


def test_the_certificate_is_written_with_the_scaled_variable_on_top():
    # v cannot scale with l and t fixed: v t / l (by hand) is a dimensionless product the request
    # changes; its exponents follow the system's order, with a positive one on the scaled variable
    lt = pt.System({"l": "L", "t": "T", "v": "L/T"})
    for s_power in (1, -1, Fraction(1, 2)):
        res = pt.search(lt, scale={"v": s_power}, fixed=("l", "t"))
        assert not res.feasible
        assert list(res.certificate.exponents.items()) == [("l", -1), ("t", 1), ("v", 1)]
        assert res.certificate_power == s_power
    # a scaled variable the certificate does not use (a, scaled freely by the mass unit) is passed over
    mlt = pt.System({"a": "M", "l": "L", "t": "T", "v": "L/T"})
    res = pt.search(mlt, scale={"a": 1, "v": 1}, fixed=("l", "t"))
    assert list(res.certificate.exponents.items()) == [("l", -1), ("t", 1), ("v", 1)]
    assert res.certificate_power == 1
    # with the fixed variable first in the request and in the system, the scaled one still decides
    tl = pt.System({"t": "T", "l": "L", "v": "L/T"})
    res = pt.search(tl, scale={"v": 1}, fixed=("t", "l"))
    assert list(res.certificate.exponents.items()) == [("t", 1), ("l", -1), ("v", 1)]
    assert res.certificate_power == 1


def test_the_particular_solution_and_directions_are_changes_of_units():
    rod = pt.System({"m": "M", "l": "L", "g": "L T^-2", "t": "T", "k": "M L^2 T^-2"})
    res = pt.search(rod, scale={"g": 1}, fixed=("t",))
    dims = {"m": {"M": 1}, "l": {"L": 1}, "g": {"L": 1, "T": -2}, "t": {"T": 1}, "k": {"M": 1, "L": 2, "T": -2}}

    def from_units(units):  # the exponent of each variable under a change of units, by hand
        return {n: sum(Fraction(p) * units[b] for b, p in d.items()) for n, d in dims.items()}

    assert isinstance(res.particular, pt.Scaling)
    assert res.particular.is_unit_change
    assert res.particular.exponents["g"] == 1
    assert res.particular.exponents["t"] == 0
    assert res.particular.exponents == from_units(res.particular.unit_change)
    assert len(res.directions) == 1
    for direction in res.directions:
        assert direction.is_unit_change
        assert (direction.exponents["g"], direction.exponents["t"]) == (0, 0)
        assert direction.exponents == from_units(direction.unit_change)
        assert direction.changed


def test_search_refusals_in_full():
    lt = pt.System({"l": "L", "t": "T", "v": "L/T"})
    cases = [
        (lambda: pt.search(3, scale={"l": 1}), "search needs a System, got int"),
        (lambda: pt.search(lt, scale={"q": 1}), "unknown variable 'q' in scale; the system has l, t, v"),
        (lambda: pt.search(lt, scale={"l": 1}, fixed=("q",)), "unknown variable 'q' in fixed; the system has l, t, v"),
        (lambda: pt.search(lt, scale={"l": 1}, allow=("q",)), "unknown variable 'q' in allow; the system has l, t, v"),
        (
            lambda: pt.search(lt, scale={}),
            "empty request: scale must prescribe at least one variable, e.g. scale={'g': 1}",
        ),
    ]
    for call, message in cases:
        with pytest.raises(pt.PiTheoremError) as caught:
            call()
        assert str(caught.value) == message
    with pytest.raises(pt.NumberError) as caught:
        pt.search(lt, scale={"l": "x"})
    assert str(caught.value).startswith("exponent of 'l' must be a finite real number")
