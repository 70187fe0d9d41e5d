"""The eps assertions of :mod:`mechanics.testing`, called directly.

Each assertion passes on close values and fails on far ones with a message that names the
error in eps, the worst index and the two values; it refuses what is not a real finite
number naming the argument and where.  The differences built here are exact multiples of
eps (1 + k·eps and k·eps are floats for small k), so a tolerance is met exactly at its
boundary: an error of exactly the tolerance passes, one eps more fails.  Expected messages
are written from the documented wording with the numbers formed by hand.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import mechanics.testing as mt
from mechanics._floats import EPS
from mechanics.testing import (
    ALLCLOSE_EPS_MULTIPLE,
    QUATERNIONS_CLOSE_ATOL,
    ROTATIONS_CLOSE_ATOL,
    assert_allclose_eps,
    assert_quaternions_close,
    assert_rotations_close,
)

#: The documented default of all three assertions (module docstring, README): 4 eps.
DOCUMENTED_DEFAULT_EPS = 4

Q_IDENTITY = [1.0, 0.0, 0.0, 0.0]


def off_by(k: int, kind: str):
    """A pair of arguments for assertion `kind` whose error is exactly k eps."""
    if kind == "allclose":  # relative error |1 + k eps - 1| / 1
        return 1.0 + k * EPS, 1.0
    if kind == "rotations":  # entry (1, 2) differs by k eps
        R2 = np.eye(3)
        R2[1, 2] = k * EPS
        return np.eye(3), R2
    q2 = np.array(Q_IDENTITY)
    q2[2] = k * EPS  # max |q1 - q2| = k eps; max |q1 + q2| = 2
    return np.array(Q_IDENTITY), q2


def check(kind: str, a, b, tol_eps: float | None = None, err_msg: str = "") -> None:
    """Call assertion `kind` with its tolerance given in eps (None: its default)."""
    if kind == "allclose":
        kw = {} if tol_eps is None else {"eps_multiple": tol_eps}
        assert_allclose_eps(a, b, err_msg=err_msg, **kw)
    elif kind == "rotations":
        kw = {} if tol_eps is None else {"atol": tol_eps * EPS}
        assert_rotations_close(a, b, err_msg=err_msg, **kw)
    else:
        kw = {} if tol_eps is None else {"atol": tol_eps * EPS}
        assert_quaternions_close(a, b, err_msg=err_msg, **kw)


KINDS = ["allclose", "rotations", "quaternions"]


# -- defaults and tolerance boundaries ------------------------------------------------


def test_the_named_defaults_are_the_documented_four_eps():
    assert mt.EPS == EPS
    assert ROTATIONS_CLOSE_ATOL == DOCUMENTED_DEFAULT_EPS * EPS
    assert QUATERNIONS_CLOSE_ATOL == DOCUMENTED_DEFAULT_EPS * EPS
    assert ALLCLOSE_EPS_MULTIPLE == DOCUMENTED_DEFAULT_EPS


@pytest.mark.parametrize("kind", KINDS)
def test_the_default_tolerance_passes_at_four_eps_and_fails_at_five(kind):
    check(kind, *off_by(DOCUMENTED_DEFAULT_EPS, kind))
    with pytest.raises(AssertionError, match=r"\b5 eps\b.*\b4 eps\b"):
        check(kind, *off_by(DOCUMENTED_DEFAULT_EPS + 1, kind))


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("tol", [1, 10, 100])
def test_an_explicit_tolerance_passes_at_its_value_and_fails_one_eps_beyond(kind, tol):
    check(kind, *off_by(tol, kind), tol_eps=tol)
    with pytest.raises(AssertionError, match=rf"\b{tol + 1} eps\b.*\b{tol} eps\b"):
        check(kind, *off_by(tol + 1, kind), tol_eps=tol)


@pytest.mark.parametrize("kind", KINDS)
def test_a_zero_tolerance_passes_only_equal_values(kind):
    check(kind, *off_by(0, kind), tol_eps=0)
    with pytest.raises(AssertionError, match=r"\b1 eps\b.*\b0 eps\b"):
        check(kind, *off_by(1, kind), tol_eps=0)


@pytest.mark.parametrize("kind", KINDS)
def test_far_values_fail_even_with_a_large_tolerance(kind):
    a, b = off_by(2**40, kind)  # about 2.4e-4 apart
    check(kind, a, b, tol_eps=2**40)
    with pytest.raises(AssertionError, match=r"\bexceeds\b|\bmore than\b"):
        check(kind, a, b, tol_eps=2**39)


# -- messages --------------------------------------------------------------------------


def test_allclose_names_the_worst_relative_error_its_index_and_the_values():
    desired = [1.0, 2.0, 4.0, 8.0]
    # errors: 2 eps relative at 0, none at 1, 8 eps at 2 (32 eps on 4), 6 eps at 3
    actual = [1.0 + 2 * EPS, 2.0, 4.0 + 32 * EPS, 8.0 - 48 * EPS]
    with pytest.raises(AssertionError) as info:
        assert_allclose_eps(actual, desired)
    assert str(info.value) == (
        f"not close: relative error 8 eps at index (2,) exceeds 4 eps "
        f"(actual {4.0 + 32 * EPS!r}, desired 4.0)"
    )


def test_allclose_with_a_scale_reports_the_error_against_it():
    # absolute: scale 1, |0.5 + 6 eps - 0.5| = 6 eps; entry (1, 0) is the worst
    actual = [[0.5, 0.25], [0.5 + 6 * EPS, 0.0]]
    desired = [[0.5, 0.25 + EPS], [0.5, 0.0]]
    with pytest.raises(AssertionError) as info:
        assert_allclose_eps(actual, desired, scale=1, eps_multiple=5, err_msg="energy")
    assert str(info.value) == (
        f"energy: not close: error 6 eps at index (1, 0) exceeds 5 eps "
        f"(actual {0.5 + 6 * EPS!r}, desired 0.5)"
    )


def test_allclose_scale_applies_entrywise():
    # 1e6 eps of error is allowed against a scale of 1e6, not against 1
    assert_allclose_eps([1.0, 1e6 * EPS], [1.0, 0.0], scale=[1.0, 1e6], eps_multiple=1)
    with pytest.raises(AssertionError, match=r"error 1e\+06 eps at index \(1,\)"):
        assert_allclose_eps([1.0, 1e6 * EPS], [1.0, 0.0], scale=[1e6, 1.0], eps_multiple=1)


def test_allclose_takes_exact_zeros_as_equal_with_a_zero_scale():
    assert_allclose_eps(0.0, 0.0)
    assert_allclose_eps([0.0, -0.0, 1.0], [0.0, 0.0, 1.0])
    assert_allclose_eps([0.0, 3.0], [0.0, 3.0], scale=0.0)
    assert_allclose_eps([0.0, 3.0], [0.0, 3.0], eps_multiple=0)


@pytest.mark.parametrize("scale", [None, 0.0, [0.0, 1.0]])
def test_allclose_against_a_zero_scale_needs_an_exact_match_and_says_scale_0(scale):
    with pytest.raises(AssertionError) as info:
        assert_allclose_eps([1e-300, 1.0], [0.0, 1.0], scale=scale, eps_multiple=2**50)
    kind = "relative error" if scale is None else "error"
    assert str(info.value) == (
        f"not close: {kind} 1e-300 (scale 0) at index (0,) exceeds "
        f"{2**50:.3g} eps (actual 1e-300, desired 0.0)"
    )


def test_allclose_reports_a_relative_error_beyond_float64_against_a_tiny_desired():
    # 1e300 / (eps · 1e-300) = 4.5e615: no float64 holds it, and no warning escapes
    with pytest.raises(AssertionError) as info:
        assert_allclose_eps(1e300, 1e-300)
    assert str(info.value) == (
        "not close: relative error beyond 1.8e+308 eps at index () exceeds 4 eps "
        "(actual 1e+300, desired 1e-300)"
    )


def test_allclose_measures_opposite_huge_values_whose_difference_overflows():
    # |1e308 − (−1e308)| = 2e308 overflows; relative to 1e308 it is 2, that is 2/eps
    with pytest.raises(AssertionError) as info:
        assert_allclose_eps([1.0, 1e308], [1.0, -1e308])
    assert str(info.value) == (
        f"not close: relative error {2 / EPS:.3g} eps at index (1,) exceeds 4 eps "
        "(actual 1e+308, desired -1e+308)"
    )
    with pytest.raises(AssertionError) as info:
        assert_allclose_eps(1e308, -1e308, scale=0.0)
    assert "error beyond 1.8e+308 (scale 0) at index ()" in str(info.value)
    # two huge values within tolerance still pass
    assert_allclose_eps(1e308 * (1 + 2 * EPS), 1e308)


def test_rotations_name_the_worst_entry_its_error_in_eps_and_the_values():
    R2 = np.eye(3)
    R2[1, 2] = 10 * EPS
    R2[0, 1] = -7 * EPS
    R2[2, 2] = 1.0 - 3 * EPS
    with pytest.raises(AssertionError) as info:
        assert_rotations_close(np.eye(3), R2)
    assert str(info.value) == (
        f"rotations differ by 10 eps at entry (1, 2), more than atol = 4 eps "
        f"(R1 0.0, R2 {10 * EPS!r})"
    )


def test_rotations_broadcast_and_report_the_index_in_the_broadcast_shape():
    R1 = np.stack([np.eye(3), np.eye(3)])  # (2, 3, 3) against one (3, 3)
    R1[1, 2, 0] = 9 * EPS
    assert_rotations_close(R1, np.eye(3), atol=9 * EPS)
    with pytest.raises(AssertionError) as info:
        assert_rotations_close(R1, np.eye(3), err_msg="batch")
    assert str(info.value) == (
        f"batch: rotations differ by 9 eps at entry (1, 2, 0), more than atol = 4 eps "
        f"(R1 {9 * EPS!r}, R2 0.0)"
    )


def test_rotations_are_compared_as_matrices_not_parameters():
    from mechanics.rotation import matrix_from_euler, matrix_from_rotvec

    # gimbal lock: only phi + psi matters; a rotation by pi about e_a or -e_a is one
    assert_rotations_close(matrix_from_euler(0.3, 0.0, 0.5), matrix_from_euler(0.8, 0.0, 0.0))
    a = np.array([2.0, -1.0, 2.0]) / 3.0
    assert_rotations_close(matrix_from_rotvec(np.pi * a), matrix_from_rotvec(-np.pi * a))
    with pytest.raises(AssertionError, match="rotations differ"):
        assert_rotations_close(matrix_from_euler(0.3, 0.0, 0.5), matrix_from_euler(0.3, 0.0, 0.6))


def test_quaternions_are_the_same_rotation_up_to_sign_for_each_quaternion():
    rng = np.random.default_rng(20261125)
    q = rng.normal(size=(5, 4))
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    signs = np.array([1.0, -1.0, -1.0, 1.0, -1.0])[:, None]  # mixed within the batch
    assert_quaternions_close(q, signs * q, atol=0.0)
    with pytest.raises(AssertionError, match="quaternions differ"):
        assert_quaternions_close(q, np.roll(q, 1, axis=0))


def test_quaternions_name_the_worst_its_error_in_eps_and_the_closer_sign():
    q1 = np.array([Q_IDENTITY, [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    q2 = q1.copy()
    q2[0, 1] = 3 * EPS  # 3 eps from +q1
    q2[1] = [0.0, -1.0, 12 * EPS, 0.0]  # 12 eps from -q1: the worst
    with pytest.raises(AssertionError) as info:
        assert_quaternions_close(q1, q2, err_msg="attitude")
    assert str(info.value) == (
        f"attitude: quaternions differ by 12 eps (up to sign, closer with -q2) at index (1,), "
        f"more than atol = 4 eps (q1 [0.0, 1.0, 0.0, 0.0], q2 [0.0, -1.0, {12 * EPS!r}, 0.0])"
    )


def test_quaternions_closer_with_plus_q2_say_so():
    q2 = [0.5, 0.5, 0.5, 0.5 + 8 * EPS]
    with pytest.raises(AssertionError) as info:
        assert_quaternions_close([0.5, 0.5, 0.5, 0.5], q2)
    assert str(info.value) == (
        f"quaternions differ by 8 eps (up to sign, closer with q2) at index (), more than "
        f"atol = 4 eps (q1 [0.5, 0.5, 0.5, 0.5], q2 [0.5, 0.5, 0.5, {0.5 + 8 * EPS!r}])"
    )


def test_quaternions_at_a_tie_between_the_signs_name_q2():
    # |q1 - q2| and |q1 + q2| both have max 1 (the docstring's example)
    with pytest.raises(AssertionError, match=r"\(up to sign, closer with q2\) at index \(\)"):
        assert_quaternions_close([1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0])


@pytest.mark.parametrize("kind", KINDS)
def test_the_message_starts_with_err_msg_only_when_given(kind):
    a, b = off_by(100, kind)
    with pytest.raises(AssertionError) as plain:
        check(kind, a, b)
    with pytest.raises(AssertionError) as tagged:
        check(kind, a, b, err_msg="step 3")
    assert str(tagged.value) == "step 3: " + str(plain.value)
    assert not str(plain.value).startswith(":")
    assert str(plain.value).split()[0] in {"not", "rotations", "quaternions"}


@pytest.mark.parametrize(
    ("func", "a", "b"),
    [
        (assert_allclose_eps, np.zeros((0,)), np.zeros((0,))),
        (assert_allclose_eps, np.zeros((0, 2)), 1.0),
        (assert_rotations_close, np.zeros((0, 3, 3)), np.eye(3)),
        (assert_quaternions_close, np.zeros((2, 0, 4)), Q_IDENTITY),
    ],
)
def test_an_empty_batch_passes(func, a, b):
    func(a, b)


def test_array_likes_of_ints_bools_and_unsigned_ints_are_compared_as_numbers():
    assert_allclose_eps([True, False], [1.0, 0.0])
    assert_allclose_eps(np.array([3, 250], dtype=np.uint8), [3.0, 250.0])
    assert_rotations_close(np.eye(3, dtype=int).tolist(), np.eye(3))
    assert_quaternions_close((1, 0, 0, 0), (-1, 0, 0, 0))
    with pytest.raises(AssertionError, match=r"index \(1,\)"):
        assert_allclose_eps(np.array([3, 250], dtype=np.uint8), [3.0, 251.0])


def test_pytest_shows_the_callers_line_not_the_assertions_own_frame():
    """pytest leaves out a frame whose locals set ``__tracebackhide__`` (its documented
    mechanism); the failure must then point at the caller, for each assertion."""
    for kind in KINDS:
        with pytest.raises(AssertionError) as info:
            check(kind, *off_by(100, kind))
        own = []
        tb = info.value.__traceback__
        while tb is not None:
            if tb.tb_frame.f_code.co_filename == mt.__file__:
                own.append(bool(tb.tb_frame.f_locals.get("__tracebackhide__")))
            tb = tb.tb_next
        assert own, f"{kind}: no frame of mechanics/testing.py in the traceback"
        assert all(own), f"{kind}: a frame of mechanics/testing.py is shown by pytest: {own}"


# -- bad input: what is not a real finite number, shapes, tolerances -------------------

# (call with the bad value in place, the argument's name in the message)
BAD_SLOTS = [
    (lambda v: assert_allclose_eps(v, 1.0), "actual"),
    (lambda v: assert_allclose_eps(1.0, v), "desired"),
    (lambda v: assert_allclose_eps(1.0, 1.0, scale=v), "scale"),
    (lambda v: assert_rotations_close(v, np.eye(3)), "R1"),
    (lambda v: assert_rotations_close(np.eye(3), v), "R2"),
    (lambda v: assert_quaternions_close(v, Q_IDENTITY), "q1"),
    (lambda v: assert_quaternions_close(Q_IDENTITY, v), "q2"),
]


def _shaped(name: str, values, where):
    """A valid-shaped array for slot `name` holding `values`' entry at index `where`."""
    shape = {"R1": (3, 3), "R2": (3, 3), "q1": (4,), "q2": (4,)}.get(name, (2, 2))
    a = np.eye(3) if shape == (3, 3) else np.ones(shape)
    a = a.astype(np.asarray(values).dtype)
    a[where] = values
    return a


@pytest.mark.parametrize(("call", "name"), BAD_SLOTS)
@pytest.mark.parametrize(
    ("value", "dtype"),
    [
        ("abc", "<U3"),
        (1.0 + 2.0j, "complex128"),
        (None, "object"),
    ],
)
def test_a_value_that_is_not_a_real_number_is_refused_naming_the_argument_and_dtype(
    call, name, value, dtype
):
    bad = np.full((3, 3) if name in ("R1", "R2") else (4,), value)
    with pytest.raises(AssertionError) as info:
        call(bad)
    assert str(info.value) == f"{name} has dtype {dtype}; real numbers are required"


@pytest.mark.parametrize(("call", "name"), BAD_SLOTS)
@pytest.mark.parametrize(
    ("value", "shown"), [(math.nan, "nan"), (math.inf, "inf"), (-math.inf, "-inf")]
)
def test_a_non_finite_value_fails_naming_the_argument_the_value_and_its_index(
    call, name, value, shown
):
    where = (1, 2) if name in ("R1", "R2") else (1,) if name in ("q1", "q2") else (1, 0)
    with pytest.raises(AssertionError) as info:
        call(_shaped(name, value, where))
    assert str(info.value) == f"{name} holds {shown} at index {where}; it must be finite"


@pytest.mark.parametrize(("call", "name"), [BAD_SLOTS[0], BAD_SLOTS[1], BAD_SLOTS[2]])
def test_a_non_finite_scalar_is_named_at_the_empty_index(call, name):
    with pytest.raises(AssertionError) as info:
        call(math.nan)
    assert str(info.value) == f"{name} holds nan at index (); it must be finite"


@pytest.mark.parametrize(
    ("call", "name", "shape", "want"),
    [
        (BAD_SLOTS[3][0], "R1", (3,), "(..., 3, 3)"),
        (BAD_SLOTS[3][0], "R1", (), "(..., 3, 3)"),
        (BAD_SLOTS[3][0], "R1", (3, 4), "(..., 3, 3)"),
        (BAD_SLOTS[4][0], "R2", (2, 4, 3), "(..., 3, 3)"),
        (BAD_SLOTS[5][0], "q1", (3,), "(..., 4)"),
        (BAD_SLOTS[5][0], "q1", (), "(..., 4)"),
        (BAD_SLOTS[6][0], "q2", (4, 3), "(..., 4)"),
    ],
)
def test_a_wrong_shape_fails_naming_the_argument_its_shape_and_the_expected_one(
    call, name, shape, want
):
    with pytest.raises(AssertionError) as info:
        call(np.zeros(shape))
    assert str(info.value) == f"{name} has shape {shape}; expected {want}"


@pytest.mark.parametrize(
    ("func", "a", "b"),
    [
        (assert_allclose_eps, np.zeros(2), np.zeros(3)),
        (assert_rotations_close, np.zeros((2, 3, 3)), np.zeros((4, 3, 3))),
        (assert_quaternions_close, np.zeros((2, 4)), np.zeros((3, 4))),
    ],
)
def test_shapes_that_do_not_broadcast_fail_naming_both(func, a, b):
    with pytest.raises(AssertionError) as info:
        func(a, b)
    assert str(info.value) == (
        f"shapes {a.shape} and {b.shape} do not broadcast against each other"
    )


def test_shapes_broadcast_like_numpys():
    assert_allclose_eps(np.ones((2, 1, 3)), np.ones((4, 1)))
    assert_quaternions_close(np.tile(Q_IDENTITY, (2, 1, 1)), np.tile(Q_IDENTITY, (3, 1)))
    q1 = np.tile(Q_IDENTITY, (3, 1))  # (3, 4) against (2, 1, 4): broadcast (2, 3, 4)
    q1[2, 3] = 1e-3
    q2 = np.tile(Q_IDENTITY, (2, 1, 1))
    q2[1, 0, 3] = -1e-3  # against q1[2]: 2e-3 apart, the worst pair
    with pytest.raises(AssertionError, match=r"at index \(1, 2\)"):
        assert_quaternions_close(q1, q2)


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda t: assert_allclose_eps(1.0, 1.0, eps_multiple=t), "eps_multiple"),
        (lambda t: assert_rotations_close(np.eye(3), np.eye(3), atol=t), "atol"),
        (lambda t: assert_quaternions_close(Q_IDENTITY, Q_IDENTITY, atol=t), "atol"),
    ],
)
@pytest.mark.parametrize(
    ("tol", "shown"), [(-1e-300, "-1e-300"), (math.nan, "nan"), (math.inf, "inf")]
)
def test_a_tolerance_that_is_negative_or_not_finite_is_refused_naming_it(call, name, tol, shown):
    with pytest.raises(ValueError, match=r"must be a finite number >= 0") as info:
        call(tol)
    assert str(info.value) == f"{name}={shown} must be a finite number >= 0"


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda t: assert_allclose_eps(1.0, 1.0, eps_multiple=t), "eps_multiple"),
        (lambda t: assert_rotations_close(np.eye(3), np.eye(3), atol=t), "atol"),
        (lambda t: assert_quaternions_close(Q_IDENTITY, Q_IDENTITY, atol=t), "atol"),
    ],
)
@pytest.mark.parametrize(
    ("tol", "shown", "kind"),
    [("4", "'4'", "str"), (True, "True", "bool"), (None, "None", "NoneType")],
)
def test_a_tolerance_that_is_not_a_real_number_is_refused_not_coerced(call, name, tol, shown, kind):
    with pytest.raises(ValueError, match=r"must be a finite number >= 0; got a") as info:
        call(tol)
    assert str(info.value) == f"{name}={shown} must be a finite number >= 0; got a {kind}"


def test_a_tolerance_may_be_an_integer_or_a_numpy_scalar():
    assert_allclose_eps(1.0 + 2 * EPS, 1.0, eps_multiple=np.float32(2))
    with pytest.raises(AssertionError, match=r"exceeds 1 eps"):
        assert_allclose_eps(1.0 + 2 * EPS, 1.0, eps_multiple=np.int64(1))


@pytest.mark.parametrize(("scale", "shown"), [(-1.0, "-1.0"), ([1.0, -2.0], "[1.0, -2.0]")])
def test_a_negative_scale_is_refused_naming_it(scale, shown):
    with pytest.raises(ValueError, match=r"\bscale must be >= 0") as info:
        assert_allclose_eps([1.0, 1.0], [1.0, 1.0], scale=scale)
    assert str(info.value) == f"scale must be >= 0; got {shown}"


def test_rtol_is_a_plain_fraction_and_the_message_states_the_error_as_one():
    assert_allclose_eps([1.0, 2.0], [1.0, 2.0 * (1 + 0.0099)], rtol=1e-2)
    with pytest.raises(AssertionError) as e:
        assert_allclose_eps([1.0, 2.0], [1.0, 1.95], rtol=1e-2, err_msg="q")
    assert str(e.value) == (
        f"q: not close: relative error {0.05 / 1.95:.3g} at index (1,) exceeds rtol 0.01 "
        "(actual 2.0, desired 1.95)"
    )
    # the bound itself passes, one ulp beyond it does not
    d = 1.0
    a = d * (1 + 2.0**-7)
    assert_allclose_eps(a, d, rtol=2.0**-7)
    with pytest.raises(AssertionError, match=r"exceeds rtol 0\.00781"):
        assert_allclose_eps(np.nextafter(a, 2.0), d, rtol=2.0**-7)


def test_eps_is_the_one_spelling_eps_multiple_its_older_alias_and_one_tolerance_at_a_time():
    a, d = 1.0 + 6 * EPS, 1.0
    assert_allclose_eps(a, d, eps=6)
    assert_allclose_eps(a, d, eps_multiple=6)
    for kwargs in ({"eps": 5}, {"eps_multiple": 5}):
        with pytest.raises(
            AssertionError, match=r"relative error 6 eps at index \(\) exceeds 5 eps"
        ):
            assert_allclose_eps(a, d, **kwargs)
    for kwargs, names in [
        ({"eps": 4, "rtol": 1e-2}, "eps and rtol"),
        ({"rtol": 1e-2, "eps_multiple": 4}, "rtol and eps_multiple"),
    ]:
        with pytest.raises(TypeError) as e:
            assert_allclose_eps(a, d, **kwargs)
        assert str(e.value) == f"give one tolerance, eps or rtol; got {names}"
    for bad in (-1.0, math.nan, "1e-2", True):
        with pytest.raises(ValueError, match=r"^rtol="):
            assert_allclose_eps(a, d, rtol=bad)
