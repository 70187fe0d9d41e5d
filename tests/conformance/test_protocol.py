"""check_trajectory (mechanics.conformance.protocol): an adapter's answer is accepted as
float64 arrays, or refused with a ConformanceError naming the scenario, the field and
what was expected (docs/conformance.md, "Bad answers").  Built on a small hand-made
scenario: no engine runs."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pytest

from mechanics.conformance.protocol import (
    ORTHOGONALITY_ATOL,
    SAMPLE_TIME_RTOL,
    Body,
    ConformanceError,
    Event,
    Ground,
    Scenario,
    Shape,
    Trajectory,
    check_trajectory,
)
from mechanics.errors import MechanicsValueError

T = (0.0, 0.5, 1.0, 2.0)
M, N = len(T), 2


def scenario(times=T) -> Scenario:
    b = Body("b", 1.0, (1.0, 1.0, 1.0))
    return Scenario("pair", "two bodies at rest", "(1.1)", (b, b), times[-1], times)


def answer(times=T, **fields) -> Trajectory:
    """A valid answer (ints where floats are due, to see them converted), then ``fields``."""
    m = len(times)
    z = np.zeros((m, N, 3), dtype=int)
    R = np.broadcast_to(np.eye(3, dtype=int), (m, N, 3, 3))
    base = Trajectory(np.array(times), z, z, R, z, np.ones((m, N), dtype=int))
    return dataclasses.replace(base, **fields)


def refused(tr, s=None) -> str:
    with pytest.raises(ConformanceError) as info:
        check_trajectory(scenario() if s is None else s, tr)
    return str(info.value)


def test_a_valid_answer_comes_back_as_float64_arrays_of_the_same_values() -> None:
    ev = (Event(0.5, "impact", (0, -1)),)
    tr = check_trajectory(scenario(), answer(events=ev))
    for name, shape in [
        ("t", (M,)),
        ("position", (M, N, 3)),
        ("velocity", (M, N, 3)),
        ("R_A_O", (M, N, 3, 3)),
        ("omega", (M, N, 3)),
        ("masses", (M, N)),
    ]:
        a = getattr(tr, name)
        assert a.dtype == np.float64, name
        assert a.shape == shape, name
    assert tr.t.tolist() == list(T)
    np.testing.assert_array_equal(tr.R_A_O, np.broadcast_to(np.eye(3), (M, N, 3, 3)))
    assert (tr.masses == 1.0).all()
    assert tr.events == ev
    assert check_trajectory(scenario(), answer(masses=None)).masses is None


def test_a_conformance_error_is_a_value_error_of_the_library() -> None:
    assert issubclass(ConformanceError, MechanicsValueError)
    assert issubclass(ConformanceError, ValueError)


def test_an_answer_that_is_not_a_trajectory_is_named_by_its_type() -> None:
    assert refused({"t": T}) == (
        "scenario 'pair': the adapter must return a mechanics.conformance.Trajectory; got dict"
    )


SHAPES = {
    "t": (M,),
    "position": (M, N, 3),
    "velocity": (M, N, 3),
    "R_A_O": (M, N, 3, 3),
    "omega": (M, N, 3),
    "masses": (M, N),
}


@pytest.mark.parametrize("name", list(SHAPES))
def test_a_wrong_shape_names_the_field_the_shape_expected_and_the_shape_got(name) -> None:
    good = getattr(answer(), name)
    bad = np.asarray(good)[..., :1] if name != "t" else np.asarray(good)[:-1]
    got = bad.shape
    assert refused(answer(**{name: bad})) == (
        f"scenario 'pair': trajectory field {name!r} must have shape {SHAPES[name]}; got {got}"
    )


@pytest.mark.parametrize("name", list(SHAPES))
def test_something_that_is_not_a_float_array_names_the_field_and_shape(name) -> None:
    msg = refused(answer(**{name: "fast"}))
    assert msg.startswith(
        f"scenario 'pair': trajectory field {name!r} must be a float array of shape "
        f"{SHAPES[name]}; "
    ), msg
    assert "fast" in msg  # numpy's reason, quoting the value


@pytest.mark.parametrize("name", [n for n in SHAPES if n != "t"])
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_a_non_finite_entry_names_the_field_the_value_and_its_first_index(name, bad) -> None:
    a = np.array(getattr(answer(), name), dtype=float)
    idx = (2, 1) + (0,) * (a.ndim - 2)
    a[idx] = bad
    later = (3, 1) + (0,) * (a.ndim - 2)
    a[later] = np.nan  # a later one is not the one reported
    assert refused(answer(**{name: a})) == (
        f"scenario 'pair': trajectory field {name!r} must be finite; got {bad!r} at index {idx}"
    )


def test_a_non_finite_time_is_named_with_its_index() -> None:
    assert refused(answer(t=np.array([0.0, 0.5, np.inf, 2.0]))) == (
        "scenario 'pair': trajectory field 't' must be finite; got inf at index (2,)"
    )


@pytest.mark.parametrize(
    ("times", "k"),
    [
        ((0.0, 0.5, 0.5, 2.0), 1),  # equal times: not strictly increasing
        ((0.0, 1.0, 0.5, 2.0), 1),
        ((0.0, 0.5, 2.0, 1.0), 2),
    ],
)
def test_times_that_do_not_increase_strictly_are_named_with_the_first_pair(times, k) -> None:
    assert refused(answer(t=np.array(times))) == (
        f"scenario 'pair': trajectory field 't' must increase strictly; "
        f"t[{k}] = {times[k]!r}, t[{k + 1}] = {times[k + 1]!r}"
    )


def test_two_samples_out_of_order_are_refused_and_one_sample_is_accepted() -> None:
    two = scenario((0.0, 1.0))
    assert refused(answer((1.0, 0.0)), two) == (
        "scenario 'pair': trajectory field 't' must increase strictly; t[0] = 1.0, t[1] = 0.0"
    )
    one = scenario((0.0,))
    assert check_trajectory(one, answer((0.0,))).t.tolist() == [0.0]


def test_times_off_the_scenarios_are_named_with_the_expected_time() -> None:
    assert refused(answer(t=np.array([0.0, 0.5, 1.5, 2.0]))) == (
        "scenario 'pair': trajectory field 't' must be the scenario's sample times; "
        "t[2] = 1.5, expected 1.0"
    )


def test_sample_time_tolerance_is_relative_to_the_larger_of_the_time_and_one() -> None:
    tol = SAMPLE_TIME_RTOL
    # at t = 2 the bound is 2 tol; below 1 it is tol (not tol * t)
    inside = np.array([0.0, 0.5 + 0.5 * tol, 1.0, 2.0 * (1 + 0.5 * tol)])
    assert check_trajectory(scenario(), answer(t=inside)).t.tolist() == inside.tolist()
    below_one = np.array([0.0, 0.5 + 0.75 * tol, 1.0, 2.0])  # beyond tol * 0.5, within tol
    check_trajectory(scenario(), answer(t=below_one))
    for k, t in [(1, 0.5 + 2 * tol), (3, 2.0 * (1 + 2 * tol)), (0, -2 * tol)]:
        bad = np.array(T)
        bad[k] = t
        msg = refused(answer(t=bad))
        assert re.search(rf"t\[{k}\] = .*, expected {T[k]!r}$", msg), msg


def test_a_time_off_by_exactly_the_tolerance_is_accepted() -> None:
    # 1 + 2^6 eps is exact in binary: |t − T| equals the bound itself, which is allowed
    at_bound = np.array([0.0, 0.5, 1.0 + SAMPLE_TIME_RTOL, 2.0])
    assert check_trajectory(scenario(), answer(t=at_bound)).t[2] == 1.0 + SAMPLE_TIME_RTOL


def test_attitudes_within_the_orthogonality_bound_are_accepted() -> None:
    R = np.array(answer().R_A_O, dtype=float)
    R[1, 0, 0, 0] += 0.25 * ORTHOGONALITY_ATOL  # R Rᵀ - I and det R - 1 about half the bound
    assert check_trajectory(scenario(), answer(R_A_O=R)).R_A_O[1, 0, 0, 0] == R[1, 0, 0, 0]


@pytest.mark.parametrize(
    ("spoil", "off"),
    [
        (lambda R: R * 1.5, "2.38"),  # R Rᵀ = 2.25 I, det R = 3.375
        (lambda R: R * np.array([1.0, 1.0, -1.0])[:, None], "2"),  # a reflection: det R = -1
        # I + a J (J the exchange matrix): R Rᵀ - I has 2a + a² on the diagonal, a = 4 bounds
        (lambda R: R + 4 * ORTHOGONALITY_ATOL * np.eye(3)[::-1], "1.82e-12"),
    ],
)
def test_a_matrix_that_is_not_a_rotation_is_named_with_sample_body_and_how_far_off(
    spoil, off
) -> None:
    R = np.array(answer().R_A_O, dtype=float)
    R[2, 1] = spoil(R[2, 1])
    assert refused(answer(R_A_O=R)) == (
        "scenario 'pair': trajectory field 'R_A_O' must hold rotations (R Rᵀ = I, det R = +1 "
        f"within 2.27e-13); sample 2, body 1 is off by {off}"
    )


@pytest.mark.parametrize("bad", [0.0, -0.0, -1.0])
def test_masses_that_are_not_positive_are_named_with_sample_and_body(bad) -> None:
    m = np.ones((M, N))
    m[1, 1] = bad
    m[3, 0] = -2.0  # a later one is not the one reported
    assert refused(answer(masses=m)) == (
        f"scenario 'pair': trajectory field 'masses' must be > 0; got {bad!r} at sample 1, body 1"
    )


def test_events_must_be_events() -> None:
    assert refused(answer(events=((0.5, "impact", (0, -1)),))) == (
        "scenario 'pair': trajectory field 'events' must hold mechanics.conformance.Event; "
        "got tuple"
    )


def test_a_zero_mass_alone_is_refused() -> None:
    m = np.ones((M, N))
    m[2, 0] = 0.0
    assert refused(answer(masses=m)) == (
        "scenario 'pair': trajectory field 'masses' must be > 0; got 0.0 at sample 2, body 0"
    )


@pytest.mark.parametrize(
    ("normal", "length"),
    [((0.0, 0.0, 2.0), "2.0"), ((0.0, 0.0, 0.0), "0.0"), ((0.6, 0.8, 1e-7), "1.0000000000000049")],
)
def test_a_ground_normal_that_is_not_a_unit_vector_is_refused(normal, length):
    # n · x = height and "height along the normal" are one plane only for |n| = 1: the
    # engines' adapters read the second, the scene engine the first (issue 16)
    with pytest.raises(MechanicsValueError) as info:
        Ground(0.5, normal, 1.0)
    assert str(info.value) == (
        f"Ground.normal must be a unit vector (3 components, length 1 within 16 eps); "
        f"got {normal!r} of length {length}"
    )


def test_a_unit_ground_normal_within_a_few_roundings_is_taken():
    n = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
    assert Ground(0.5, tuple(n), 1.0).normal == tuple(n)
    assert Ground(0.5, (0.6, 0.8, 0.0)).normal == (0.6, 0.8, 0.0)
    with pytest.raises(MechanicsValueError, match=r"3 components"):
        Ground(0.5, (0.0, 1.0), 1.0)


@pytest.mark.parametrize("mu", [-0.1, math.nan, math.inf, "0.5", None])
def test_a_ground_friction_that_is_not_a_finite_number_at_least_0_is_refused(mu):
    with pytest.raises(MechanicsValueError, match=r"Ground\.friction .* >= 0; got"):
        Ground(0.5, friction=mu)


def test_ground_friction_is_said_unsupported_by_an_adapter_that_does_not_map_it():
    from mechanics.conformance.adapters._engines import common_unsupported

    body = Body("b", 1.0, (0.4, 0.4, 0.4), Shape("sphere", (1.0,)), position=(0.0, 0.0, 2.0))
    rough = Scenario("rough", "d", "b", (body,), 1.0, (0.0, 1.0), ground=Ground(0.5, friction=0.3))
    assert "friction with the ground (mu = 0.3)" in common_unsupported(rough)
    assert common_unsupported(rough, friction=True) is None
    assert common_unsupported(dataclasses.replace(rough, ground=Ground(0.5))) is None
