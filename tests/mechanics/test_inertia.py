"""API, validation and edge cases of :mod:`mechanics.inertia`.

The catalogue of homogeneous bodies is checked against an independent route:
the body's mass distribution is replaced by Gauss–Legendre quadrature nodes
(as particles), whose inertia tensor :func:`inertia_tensor` sums.  The
quadrature is exact for the polynomial integrands, so the two routes agree to
rounding.
"""

from __future__ import annotations

import math
import re
import warnings

import mpmath
import numpy as np
import pytest

from mechanics import inertia as I
from mechanics.errors import (
    NegativeMassError,
    NonFiniteError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    NotARotationError,
    ShapeError,
    ZeroTotalMassError,
)
from mechanics.rotation import EPS, R3, matrix_from_rotvec

#: Quadrature sums of a few hundred nodes against a closed form: each node's
#: contribution is rounded once or twice and the sum accumulates about √N
#: roundings; 64 eps of the largest moment bounds it.
QUADRATURE_ATOL = 64 * EPS

#: A rotated or shifted tensor: every entry is a short sum of rounded products.
ENTRY_ATOL = 8 * EPS

ORIGIN = np.zeros(3)


def _gl(n: int, a: float, b: float) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (b - a) * x + 0.5 * (b + a), 0.5 * (b - a) * w


def _ring_nodes(n: int) -> np.ndarray:
    """Angles of the n-point trapezoid rule on the circle: exact for degree < n."""
    return 2 * np.pi * (np.arange(n) + 0.5) / n


def _grid(*axes):
    """Tensor-product nodes and weights from (nodes, weights) pairs."""
    nodes = np.meshgrid(*(a[0] for a in axes), indexing="ij")
    weights = np.prod(np.meshgrid(*(a[1] for a in axes), indexing="ij"), axis=0)
    return [n.ravel() for n in nodes], weights.ravel()


def _particles_of(body: str, m: float, *dims: float) -> tuple[np.ndarray, np.ndarray]:
    """Masses and positions (G at the origin) of a quadrature of the body."""
    n = 8
    if body == "rod":
        (z,), w = _grid(_gl(n, -dims[0] / 2, dims[0] / 2))
        r = np.stack([0 * z, 0 * z, z], -1)
    elif body == "ring":
        t = _ring_nodes(n)
        w = np.full(n, 1.0)
        r = dims[0] * np.stack([np.cos(t), np.sin(t), 0 * t], -1)
    elif body == "disc":
        (rho, t), w = _grid(_gl(n, 0, dims[0]), (_ring_nodes(n), np.ones(n)))
        w = w * rho
        r = np.stack([rho * np.cos(t), rho * np.sin(t), 0 * t], -1)
    elif body == "cylinder":
        R, h = dims
        (rho, t, z), w = _grid(_gl(n, 0, R), (_ring_nodes(n), np.ones(n)), _gl(n, -h / 2, h / 2))
        w = w * rho
        r = np.stack([rho * np.cos(t), rho * np.sin(t), z], -1)
    elif body == "cylindrical_shell":
        R, h = dims
        (t, z), w = _grid((_ring_nodes(n), np.ones(n)), _gl(n, -h / 2, h / 2))
        r = np.stack([R * np.cos(t), R * np.sin(t), z], -1)
    elif body in ("solid_sphere", "hollow_sphere"):
        R = dims[0]
        radial = _gl(n, 0, R) if body == "solid_sphere" else (np.array([R]), np.ones(1))
        (rho, c, t), w = _grid(radial, _gl(n, -1, 1), (_ring_nodes(n), np.ones(n)))
        w = w * rho**2
        s = np.sqrt((1 - c) * (1 + c))
        r = np.stack([rho * s * np.cos(t), rho * s * np.sin(t), rho * c], -1)
    elif body == "rectangular_plate":
        a, b = dims
        (x, y), w = _grid(_gl(n, -a / 2, a / 2), _gl(n, -b / 2, b / 2))
        r = np.stack([x, y, 0 * x], -1)
    elif body == "box":
        a, b, c = dims
        (x, y, z), w = _grid(_gl(n, -a / 2, a / 2), _gl(n, -b / 2, b / 2), _gl(n, -c / 2, c / 2))
        r = np.stack([x, y, z], -1)
    elif body == "solid_cone":
        R, h = dims  # apex at z = 3h/4 above G, base at z = −h/4
        (u, rho_frac, t), w = _grid(_gl(n, 0, 1), _gl(n, 0, 1), (_ring_nodes(n), np.ones(n)))
        radius = R * u  # u = distance from the apex / h
        rho = rho_frac * radius
        w = w * rho * radius  # area element ρ dρ dθ, dρ = radius d(rho_frac)
        z = 0.75 * h - u * h
        r = np.stack([rho * np.cos(t), rho * np.sin(t), z], -1)
    else:  # pragma: no cover
        raise AssertionError(body)
    return m * w / w.sum(), r


BODIES = [
    ("rod", (1.7,)),
    ("ring", (0.9,)),
    ("disc", (1.3,)),
    ("cylinder", (0.7, 2.1)),
    ("cylindrical_shell", (0.7, 2.1)),
    ("solid_sphere", (1.1,)),
    ("hollow_sphere", (1.1,)),
    ("rectangular_plate", (0.6, 1.9)),
    ("box", (0.6, 1.9, 1.2)),
    ("solid_cone", (0.8, 1.5)),
]


@pytest.mark.parametrize(("body", "dims"), BODIES, ids=[b for b, _ in BODIES])
def test_body_formula_matches_quadrature_of_its_mass_distribution(body, dims):
    m = 2.3
    J = getattr(I, body)(m, *dims)
    masses, r = _particles_of(body, m, *dims)
    J_quad = I.inertia_tensor(masses, r, about=ORIGIN)
    scale = np.trace(J_quad)
    np.testing.assert_allclose(J, J_quad, rtol=0, atol=QUADRATURE_ATOL * scale)


@pytest.mark.parametrize(("body", "dims"), BODIES, ids=[b for b, _ in BODIES])
def test_body_quadrature_has_its_centre_of_mass_at_the_origin(body, dims):
    masses, r = _particles_of(body, 1.0, *dims)
    G = masses @ r
    assert np.abs(G).max() <= QUADRATURE_ATOL * max(dims)


@pytest.mark.parametrize(("body", "dims"), BODIES, ids=[b for b, _ in BODIES])
def test_body_tensors_are_physical_and_broadcast(body, dims):
    f = getattr(I, body)
    J = f(np.array([1.0, 2.0]), *dims)
    assert J.shape == (2, 3, 3)
    np.testing.assert_array_equal(J[1], 2 * J[0])
    assert I.is_physical_inertia(J, allow_singular=True).all()


@pytest.mark.parametrize(("body", "dims"), BODIES, ids=[b for b, _ in BODIES])
def test_body_rejects_negative_mass_and_non_positive_lengths(body, dims):
    f = getattr(I, body)
    with pytest.raises(NegativeMassError, match=r"-1\.0"):
        f(-1.0, *dims)
    with pytest.raises(NonPositiveParameterError, match="must be > 0"):
        f(1.0, *((0.0, *dims[1:])))
    with pytest.raises(NonFiniteError):
        f(float("nan"), *dims)


def test_the_book_moments_of_the_standard_bodies():
    # Values the book uses: rod about G m l²/12 (Example 4.3 via 4.54), disc
    # about its axis mR²/2 (Example 3.5), cylinder mr²/2 (Example 4.5), cube of
    # side 2a: (2/3) m a² (Problem 4.4), spherical shell (2/3) m r² (Problem 6.4).
    m, l, R, a = 3.0, 2.0, 0.5, 0.25
    assert I.rod(m, l)[0, 0] == pytest.approx(m * l**2 / 12, rel=EPS)
    assert I.disc(m, R)[2, 2] == pytest.approx(m * R**2 / 2, rel=EPS)
    assert I.cylinder(m, R, 1.0)[2, 2] == pytest.approx(m * R**2 / 2, rel=EPS)
    np.testing.assert_allclose(I.box(m, 2 * a, 2 * a, 2 * a), np.eye(3) * 2 / 3 * m * a**2)
    np.testing.assert_allclose(I.hollow_sphere(m, R), np.eye(3) * 2 / 3 * m * R**2)


# ---------------------------------------------------------------- check_inertia


def test_check_inertia_returns_the_input_unchanged_as_float64():
    J = np.array([[2, 0, 0], [0, 3, 0], [0, 0, 4]])
    out = I.check_inertia(J)
    assert out.dtype == np.float64
    np.testing.assert_array_equal(out, J)
    # A rounding-level asymmetry is accepted and *not* repaired.
    Jb = np.diag([2.0, 3.0, 4.0])
    Jb[0, 1] = 1e-16
    np.testing.assert_array_equal(I.check_inertia(Jb), Jb)


@pytest.mark.parametrize(
    ("J", "condition", "amount"),
    [
        pytest.param(
            [[2.0, 0.1, 0.0], [0.0, 3.0, 0.0], [0.0, 0.0, 4.0]],
            "not symmetric",
            "0.1",
            id="asymmetric",
        ),
        pytest.param(np.diag([-1.0, 3.0, 3.5]), "not positive semidefinite", "-1", id="negative"),
        pytest.param(np.diag([1.0, 1.0, 2.5]), "triangle inequality", "-0.5", id="triangle"),
        pytest.param(np.diag([0.0, 1.0, 1.0]), "not positive definite", "allow_singular", id="rod"),
    ],
)
def test_check_inertia_names_the_violated_condition_and_the_amount(J, condition, amount):
    with pytest.raises(NonPhysicalInertiaError, match=re.escape(condition)) as info:
        I.check_inertia(J)
    assert amount in str(info.value)


def test_check_inertia_accepts_a_line_mass_only_when_asked():
    J = I.rod(1.0, 1.0)
    with pytest.raises(NonPhysicalInertiaError):
        I.check_inertia(J)
    I.check_inertia(J, allow_singular=True)
    I.check_inertia(np.zeros((3, 3)), allow_singular=True)  # a point mass about itself


def test_check_inertia_accepts_a_flat_body_rotated_in_float64():
    J = I.rotate_inertia(I.rectangular_plate(1.0, 1.0, 3.0), matrix_from_rotvec([0.3, 1.0, -2]))
    I.check_inertia(J)


def test_check_inertia_names_the_index_in_a_batch_and_the_point():
    J = np.stack([np.eye(3), np.diag([1.0, 1.0, 3.0])])
    with pytest.raises(NonPhysicalInertiaError, match=r"about G.*index \(1,\)"):
        I.check_inertia(J)
    with pytest.raises(NonPhysicalInertiaError, match="about the given point"):
        I.check_inertia(J, about_centre_of_mass=False)


@pytest.mark.parametrize(
    ("J", "error"),
    [
        pytest.param(np.eye(2), ShapeError, id="shape"),
        pytest.param([[1, 0, 0], [0, np.nan, 0], [0, 0, 1]], NonFiniteError, id="nan"),
        pytest.param(np.eye(3) * 1j, ShapeError, id="complex"),
    ],
)
def test_check_inertia_rejects_bad_arrays(J, error):
    with pytest.raises(error):
        I.check_inertia(J)


def test_is_physical_inertia_is_elementwise():
    J = np.stack([np.eye(3), np.diag([1.0, 1.0, 3.0]), I.rod(1.0, 1.0)])
    assert I.is_physical_inertia(J).tolist() == [True, False, False]
    assert I.is_physical_inertia(J, allow_singular=True).tolist() == [True, False, True]


# ---------------------------------------------------------------- inertia_tensor


def test_inertia_tensor_requires_the_point():
    with pytest.raises(TypeError):
        I.inertia_tensor([1.0], [[0.0, 0.0, 0.0]])  # type: ignore[call-arg]


def test_inertia_tensor_of_one_particle_is_its_point_mass_tensor():
    r = np.array([1.0, 2.0, 3.0])
    J = I.inertia_tensor([2.0], [r], about=ORIGIN)
    expected = 2.0 * (r @ r * np.eye(3) - np.outer(r, r))
    np.testing.assert_array_equal(J, expected)


def test_inertia_tensor_is_exact_for_a_compact_system_far_from_the_origin():
    # Two unit masses 1 apart at 1e8 from the origin: about G, J = diag(0, ½, ½)
    # (each at 1/2 from G).  A naïve Σ m (|r|² 1 − r rᵀ) − M(|G|² 1 − G Gᵀ) would
    # cancel 1e16 against 1e16 and return noise.
    far = np.array([1e8, -3e7, 2e8])
    r = far + np.array([[0.5, 0.0, 0.0], [-0.5, 0.0, 0.0]])
    J = I.inertia_tensor([1.0, 1.0], r, about=far)
    np.testing.assert_array_equal(J, np.diag([0.0, 0.5, 0.5]))


@pytest.mark.parametrize(
    ("m", "r", "error"),
    [
        pytest.param([1.0, -1.0], [[0, 0, 0], [1, 0, 0]], NegativeMassError, id="negative"),
        pytest.param([0.0, 0.0], [[0, 0, 0], [1, 0, 0]], ZeroTotalMassError, id="zero-total"),
        pytest.param([1.0], [[0, 0, 0], [1, 0, 0]], ShapeError, id="mismatch"),
        pytest.param([1.0, 1.0], [[0, 0, np.inf], [1, 0, 0]], NonFiniteError, id="inf"),
        pytest.param(np.ones(0), np.zeros((0, 3)), ZeroTotalMassError, id="empty"),
    ],
)
def test_inertia_tensor_rejects_bad_input(m, r, error):
    with pytest.raises(error):
        I.inertia_tensor(m, r, about=ORIGIN)


# ---------------------------------------------------------------- parallel_axis


def test_parallel_axis_diagonal_is_steiners_theorem_4_40():
    J_G = I.rotate_inertia(np.diag([1.0, 2.0, 2.5]), matrix_from_rotvec([0.2, -0.4, 0.9]))
    m, d = 1.5, np.array([0.3, -1.2, 0.7])
    J_C = I.parallel_axis(J_G, m, d)
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        assert J_C[i, i] == pytest.approx(J_G[i, i] + m * (d[j] ** 2 + d[k] ** 2), rel=2 * EPS)


def test_parallel_axis_adds_the_tensor_of_a_point_mass_at_d():
    J_G = np.diag([1.0, 2.0, 2.5])
    m, d = 1.5, np.array([0.3, -1.2, 0.7])
    point = I.inertia_tensor([m], [d], about=ORIGIN)
    np.testing.assert_allclose(I.parallel_axis(J_G, m, d), J_G + point, rtol=0, atol=ENTRY_ATOL * 4)


def test_parallel_axis_is_exactly_symmetric_and_broadcasts():
    J_G = I.box(1.0, 1.0, 2.0, 3.0)
    d = np.random.default_rng(1).normal(size=(5, 3)) * 1e3
    J = I.parallel_axis(J_G, np.arange(1.0, 6.0), d)
    assert J.shape == (5, 3, 3)
    np.testing.assert_array_equal(J, np.swapaxes(J, -1, -2))


def test_parallel_axis_validates_its_inputs():
    with pytest.raises(NonPhysicalInertiaError):
        I.parallel_axis(np.diag([1.0, 1.0, 3.0]), 1.0, [0, 0, 1])
    with pytest.raises(NegativeMassError):
        I.parallel_axis(np.eye(3), -1.0, [0, 0, 1])
    with pytest.raises(ShapeError):
        I.parallel_axis(np.eye(3), 1.0, [0, 1])
    with pytest.raises(NonFiniteError):
        I.parallel_axis(np.eye(3), 1.0, [0, np.nan, 1])


def test_parallel_axis_reports_overflow():
    from mechanics.errors import ResultOverflowError

    with pytest.raises(ResultOverflowError):
        I.parallel_axis(np.eye(3), 1.0, [1e200, 0, 0])


# ---------------------------------------------------------------- rotate_inertia


def test_rotate_inertia_reproduces_example_4_2():
    Jx, Jy, Jz, psi = 1.0, 2.0, 2.5, 0.7
    c, s = math.cos(psi), math.sin(psi)
    book = np.array(  # (4.30)
        [
            [c * c * Jx + s * s * Jy, c * s * (Jx - Jy), 0],
            [c * s * (Jx - Jy), s * s * Jx + c * c * Jy, 0],
            [0, 0, Jz],
        ]
    )
    J_O = I.rotate_inertia(np.diag([Jx, Jy, Jz]), R3(psi))
    np.testing.assert_allclose(J_O, book, rtol=0, atol=ENTRY_ATOL * Jz)
    # (4.31): the product of inertia D_xy = −cos ψ sin ψ (J'x − J'y) = −J_O[0, 1].
    assert -J_O[0, 1] == pytest.approx(-c * s * (Jx - Jy), rel=4 * EPS)


def test_rotate_inertia_of_a_symmetric_top_about_its_axis_leaves_it_diagonal():
    J = np.diag([2.0, 2.0, 3.0])
    out = I.rotate_inertia(J, R3(0.9))
    np.testing.assert_allclose(out, J, rtol=0, atol=ENTRY_ATOL * 3)


def test_rotate_inertia_is_exactly_symmetric_and_inverted_by_inertia_A_from_O():
    R = matrix_from_rotvec(np.random.default_rng(2).normal(size=(50, 3)))
    J = I.rotate_inertia(np.diag([1.0, 2.0, 2.5]), R)
    np.testing.assert_array_equal(J, np.swapaxes(J, -1, -2))
    back = I.inertia_A_from_O(J, R)
    np.testing.assert_allclose(
        back,
        np.broadcast_to(np.diag([1.0, 2.0, 2.5]), back.shape),
        rtol=0,
        atol=ENTRY_ATOL * 2.5 * 2,
    )


def test_rotate_inertia_rejects_a_reflection():
    with pytest.raises(NotARotationError):
        I.rotate_inertia(np.eye(3), np.diag([1.0, 1.0, -1.0]))


# ---------------------------------------------------------------- principal axes


def test_principal_axes_of_a_diagonal_tensor_are_the_basis_sorted():
    moments, R = I.principal_axes(np.diag([3.0, 1.0, 2.0]))
    assert moments.tolist() == [1.0, 2.0, 3.0]
    np.testing.assert_array_equal(np.abs(R), np.eye(3)[[1, 2, 0]])
    assert np.linalg.det(R) == pytest.approx(1.0, abs=EPS)


def test_principal_axes_rows_are_eigenvectors_4_13():
    J = I.rotate_inertia(np.diag([1.0, 2.0, 2.5]), matrix_from_rotvec([0.3, -0.8, 1.9]))
    moments, R = I.principal_axes(J)
    for i in range(3):
        np.testing.assert_allclose(J @ R[i], moments[i] * R[i], rtol=0, atol=8 * EPS * 2.5)


@pytest.mark.parametrize("scale", [1e-300, 1.0, 1e160, 1e300, 1e307])
def test_principal_axes_at_any_scale_give_the_moments(scale):
    """Regression: beyond 1e154 the convergence test formed √|a_pp a_qq|, whose product
    overflowed to inf, so the sweeps stopped unrotated and returned the diagonal of a
    rotated tensor as its moments (1.21, 1.39, 1.90 for 1, 1.5, 2).  Against LAPACK's
    eigvalsh on the tensor scaled to 1 (an independent route); 16 eps of the largest
    moment: Jacobi's error (the module's bound) and the rotation's rounding."""
    R = matrix_from_rotvec([0.4, 0.1, -0.7])
    J = I.rotate_inertia(np.diag([1.0, 1.5, 2.0]) * scale, R)
    moments, _ = I.principal_axes(J)
    want = np.linalg.eigvalsh(J / scale)
    np.testing.assert_allclose(moments / scale, want, rtol=0, atol=16 * EPS * 2.0)


def test_principal_axes_is_a_proper_rotation_with_fixed_signs():
    rng = np.random.default_rng(3)
    J = I.rotate_inertia(np.diag([1.0, 2.0, 2.5]), matrix_from_rotvec(rng.normal(size=(200, 3))))
    _, R = I.principal_axes(J)
    det = np.linalg.det(R)
    np.testing.assert_allclose(det, 1.0, rtol=0, atol=8 * EPS)
    for i in (0, 1):
        row = R[:, i, :]
        k = np.argmax(np.abs(row), axis=-1)
        assert (row[np.arange(len(k)), k] > 0).all()


def test_principal_axes_of_a_spherical_top_and_of_a_rod():
    moments, R = I.principal_axes(I.solid_sphere(5.0, 1.0))
    np.testing.assert_array_equal(moments, [2.0, 2.0, 2.0])
    moments, R = I.principal_axes(I.rod(12.0, 1.0))
    assert moments.tolist() == [0.0, 1.0, 1.0]
    assert np.abs(R[0]).tolist() == [0.0, 0.0, 1.0]  # the rod's axis
    with pytest.raises(NonPhysicalInertiaError):
        I.principal_axes(I.rod(12.0, 1.0), allow_singular=False)


def test_principal_axes_rejects_a_non_physical_tensor():
    with pytest.raises(NonPhysicalInertiaError, match="triangle"):
        I.principal_axes(np.diag([1.0, 1.0, 3.0]))


def test_principal_subspaces_of_a_symmetric_top_are_unique():
    J = I.rotate_inertia(np.diag([2.0, 2.0, 3.0]), matrix_from_rotvec([0.3, -0.8, 1.9]))
    _moments, P = I.principal_subspaces(J)
    e3 = I.principal_axes(J)[1][2]
    plane = np.eye(3) - np.outer(e3, e3)
    np.testing.assert_allclose(P[0], plane, rtol=0, atol=16 * EPS)
    np.testing.assert_allclose(P[1], plane, rtol=0, atol=16 * EPS)
    np.testing.assert_allclose(np.trace(P, axis1=-2, axis2=-1), [2.0, 2.0, 1.0], atol=16 * EPS)


def test_principal_subspaces_rtol_decides_what_coincides():
    J = np.diag([1.0, 1.0 + 1e-10, 2.0])
    _, P = I.principal_subspaces(J)  # default √eps: one plane
    assert np.trace(P[0]) == pytest.approx(2.0)
    _, P = I.principal_subspaces(J, rtol=1e-12)  # separated
    assert np.trace(P[0]) == pytest.approx(1.0)
    with pytest.raises(NonPositiveParameterError):
        I.principal_subspaces(J, rtol=-1.0)


@pytest.mark.parametrize(
    ("rtol", "error", "condition"),
    [
        pytest.param([1, 2], ShapeError, r"^rtol must be a scalar; got shape \(2,\)$", id="list"),
        pytest.param("a", ShapeError, r"^rtol has dtype <U1; a real numeric array", id="string"),
        pytest.param(np.nan, NonFiniteError, r"^rtol must be finite; found nan", id="nan"),
        pytest.param(np.inf, NonFiniteError, r"^rtol must be finite; found inf", id="inf"),
        pytest.param(
            -1.0,
            NonPositiveParameterError,
            r"^rtol must be a finite number >= 0; got -1\.0$",
            id="negative",
        ),
    ],
)
def test_principal_subspaces_refuses_a_bad_rtol_by_name(rtol, error, condition):
    # as check_rotation's atol: a scalar (else ShapeError), finite (else NonFiniteError), >= 0
    with pytest.raises(error, match=condition):
        I.principal_subspaces(np.eye(3), rtol=rtol)


# ------------------------------------------------------------- Example 4.1


def test_four_particle_realisation_reproduces_example_4_1():
    m, Jx, Jy, Jz = 2.0, 1.0, 2.0, 2.5
    masses, r = I.four_particle_realisation(m, np.diag([Jx, Jy, Jz]))
    assert masses.tolist() == [0.5] * 4
    a = math.sqrt((Jz - Jx + Jy) / m)  # (4.29)
    b = math.sqrt((Jz + Jx - Jy) / m)
    c = math.sqrt((Jx + Jy - Jz) / (2 * m))
    book = np.array([[a, 0, c], [-a, 0, c], [0, b, -c], [0, -b, -c]])  # (4.15)-(4.18)
    np.testing.assert_allclose(np.abs(r), np.abs(book), rtol=0, atol=4 * EPS)
    # (4.19)-(4.25): the particles have the tensor they were built for.
    np.testing.assert_allclose(
        I.inertia_tensor(masses, r, about=ORIGIN), np.diag([Jx, Jy, Jz]), rtol=0, atol=8 * EPS
    )


def test_four_particles_of_a_spherical_top_form_a_regular_tetrahedron():
    _, r = I.four_particle_realisation(1.0, np.eye(3))
    dist = np.linalg.norm(r[:, None, :] - r[None, :, :], axis=-1)[np.triu_indices(4, 1)]
    np.testing.assert_allclose(dist, dist[0], rtol=4 * EPS)


def test_four_particle_realisation_of_a_flat_body_is_planar():
    # J1 + J2 = J3: c = 0, all four particles in one plane (the book's remark
    # on three-particle systems, read backward).
    _masses, r = I.four_particle_realisation(1.0, I.rectangular_plate(1.0, 2.0, 1.0))
    assert np.abs(r[:, 2]).max() == 0.0


def test_four_particle_realisation_validates():
    with pytest.raises(NonPositiveParameterError):
        I.four_particle_realisation(0.0, np.eye(3))
    with pytest.raises(NegativeMassError):
        I.four_particle_realisation(-1.0, np.eye(3))
    with pytest.raises(NonPhysicalInertiaError):
        I.four_particle_realisation(1.0, np.diag([1.0, 1.0, 3.0]))


def test_rotate_inertia_reports_overflow():
    from mechanics.errors import ResultOverflowError

    with pytest.raises(ResultOverflowError):
        I.rotate_inertia(np.eye(3) * 1.7e308, matrix_from_rotvec([0.3, 0.4, 0.5]))


def test_rotate_inertia_rejects_an_asymmetric_matrix_instead_of_symmetrising_it():
    J = np.diag([1.0, 2.0, 2.5])
    J[0, 1] = 1e-3
    with pytest.raises(NonPhysicalInertiaError, match="J_A is not symmetric"):
        I.rotate_inertia(J, np.eye(3))
    with pytest.raises(NonPhysicalInertiaError, match="J_O is not symmetric"):
        I.inertia_A_from_O(J, np.eye(3))


# ------------------------------------------ broadcasting and repeated validations


def _general_tensors(n: int) -> np.ndarray:
    """n physical tensors with distinct moments, turned about different axes."""
    out = []
    for k in range(n):
        R = matrix_from_rotvec([0.3 + k, -0.5 * k, 0.2])
        out.append(R.T @ np.diag([1.0 + k, 2.0 + k, 2.5 + 1.5 * k]) @ R)
    return np.array(out)


def test_inertia_tensor_of_particles_broadcasts_over_systems():
    # Two systems of three particles, each about its own point: row by row.
    m = np.array([[1.0, 2.0, 0.5], [3.0, 0.25, 1.0]])
    r = np.array(
        [
            [[1.0, 0, 0], [0, 1.0, -1.0], [0.5, 0.5, 2.0]],
            [[-1.0, 2.0, 0], [0, 0, 3.0], [1.0, 1.0, 1.0]],
        ]
    )
    about = np.array([[0.0, 0, 0], [0.5, -0.5, 1.0]])
    J = I.inertia_tensor(m, r, about=about)
    assert J.shape == (2, 3, 3)
    for i in range(2):
        np.testing.assert_allclose(
            J[i], I.inertia_tensor(m[i], r[i], about=about[i]), rtol=0, atol=ENTRY_ATOL * 16
        )
    # and one point for both systems
    J0 = I.inertia_tensor(m, r, about=ORIGIN)
    np.testing.assert_allclose(
        J0[1], I.inertia_tensor(m[1], r[1], about=ORIGIN), rtol=0, atol=ENTRY_ATOL * 16
    )


def test_parallel_axis_broadcasts_over_a_batch_of_tensors():
    J_G = _general_tensors(3)
    m = np.array([1.0, 2.5, 0.5])
    d = np.array([[1.0, 0, 0], [0.5, -1.0, 2.0], [0.0, 0.0, 0.0]])
    J = I.parallel_axis(J_G, m, d)
    assert J.shape == (3, 3, 3)
    for i in range(3):
        # (4.38): J_A = J_G + m (d² 1 − d dᵀ), by hand
        want = J_G[i] + m[i] * (d[i] @ d[i] * np.eye(3) - np.outer(d[i], d[i]))
        np.testing.assert_allclose(J[i], want, rtol=0, atol=ENTRY_ATOL * 8)
    # one J_G, a batch of offsets
    J1 = I.parallel_axis(J_G[1], 2.0, d)
    assert J1.shape == (3, 3, 3)
    np.testing.assert_allclose(J1[0], I.parallel_axis(J_G[1], 2.0, d[0]), rtol=0, atol=ENTRY_ATOL)


def test_four_particle_realisation_broadcasts_and_reproduces_each_tensor():
    J = _general_tensors(3)
    m = np.array([1.0, 4.0, 0.5])
    masses, r = I.four_particle_realisation(m, J)
    assert masses.shape == (3, 4)
    assert r.shape == (3, 4, 3)
    for i in range(3):
        mi, ri = I.four_particle_realisation(m[i], J[i])
        np.testing.assert_allclose(masses[i], mi, rtol=0, atol=0)
        np.testing.assert_allclose(r[i], ri, rtol=0, atol=ENTRY_ATOL * 4)
        np.testing.assert_allclose(masses[i].sum(), m[i], rtol=ENTRY_ATOL)
        np.testing.assert_allclose(
            I.inertia_tensor(masses[i], r[i], about=ORIGIN),
            J[i],
            rtol=0,
            atol=ENTRY_ATOL * 16 * np.abs(J[i]).max(),
        )


def test_parallel_axis_rejects_a_singular_centroidal_tensor_unless_allowed():
    rod = np.diag([0.0, 1.0, 1.0])
    with pytest.raises(
        NonPhysicalInertiaError,
        match=r"^J_G is not positive definite: smallest principal moment J1 = 0.*allow_singular=True",
    ):
        I.parallel_axis(rod, 1.0, [0.0, 1.0, 0.0])
    J = I.parallel_axis(rod, 1.0, [0.0, 1.0, 0.0], allow_singular=True)
    np.testing.assert_allclose(J, np.diag([1.0, 1.0, 2.0]), rtol=0, atol=ENTRY_ATOL)


#: four particles at the origin and the unit points (the particle-input cases below)
_FOUR = np.array([[0.0, 0, 0], [1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]])


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        pytest.param(
            lambda: I.four_particle_realisation(0.0, np.eye(3)),
            NonPositiveParameterError,
            r"^m must be > 0; found 0\.0",
            id="four-zero-mass",
        ),
        pytest.param(
            lambda: I.four_particle_realisation(-1.0, np.eye(3)),
            NegativeMassError,
            r"^m .*-1\.0",
            id="four-negative-mass",
        ),
        pytest.param(
            lambda: I.parallel_axis(np.eye(3), -2.0, [1.0, 0, 0]),
            NegativeMassError,
            r"^m .*-2\.0",
            id="parallel-negative-mass",
        ),
        pytest.param(
            lambda: I.parallel_axis(np.eye(3), 1.0, [1.0, 0]),
            ShapeError,
            r"^d has shape \(2,\); expected \(\.\.\., 3\)",
            id="parallel-d-shape",
        ),
        pytest.param(
            lambda: I.parallel_axis(np.eye(2), 1.0, [1.0, 0, 0]),
            ShapeError,
            r"^J_G has shape \(2, 2\)",
            id="parallel-J-shape",
        ),
        pytest.param(
            lambda: I.inertia_tensor([1.0], [[1.0, 0]], about=ORIGIN),
            ShapeError,
            r"^r has shape \(1, 2\)",
            id="particles-r-shape",
        ),
        pytest.param(
            lambda: I.inertia_tensor([1.0], [[1.0, 0, 0]], about=[0, 0]),
            ShapeError,
            r"^about has shape \(2,\)",
            id="particles-about-shape",
        ),
        pytest.param(
            # the first negative mass is reported, not the first mass below 1 or at 0
            lambda: I.inertia_tensor([0.5, 0.0, -2.0, 1.0], _FOUR, about=ORIGIN),
            NegativeMassError,
            r"^m must be >= 0; found -2\.0$",
            id="particles-negative-mass",
        ),
        pytest.param(
            lambda: I.parallel_axis(np.eye(3), [0.5, 0.0, -3.0], [1.0, 0, 0]),
            NegativeMassError,
            r"^m must be >= 0; found -3\.0$",
            id="parallel-negative-mass-batched",
        ),
        pytest.param(
            lambda: I.inertia_tensor([1.0], _FOUR[:2], about=ORIGIN),
            ShapeError,
            r"^m has shape \(1,\) and r \(2, 3\); expected \(\.\.\., N\) and \(\.\.\., N, 3\)$",
            id="particles-count-mismatch",
        ),
    ],
)
def test_each_inertia_function_validates_its_own_inputs(call, error, match):
    with pytest.raises(error, match=match):
        call()


def _overflow_error():
    from mechanics.errors import ResultOverflowError

    return ResultOverflowError


_TRIANGLE = np.diag([1.0, 1.0, 3.0])  # J1 + J2 < J3


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        pytest.param(
            lambda: I.rod(np.nan, 1.0), NonFiniteError, r"^m must be finite", id="rod-m-nan"
        ),
        pytest.param(
            lambda: I.rod(1.0, np.nan), NonFiniteError, r"^ell must be finite", id="rod-ell-nan"
        ),
        pytest.param(
            lambda: I.rod(1.0, 0.0),
            NonPositiveParameterError,
            r"^ell must be > 0; found 0\.0$",
            id="rod-ell-zero",
        ),
        pytest.param(
            lambda: I.cylinder(1.0, 0.0, 1.0),
            NonPositiveParameterError,
            r"^R must be > 0; found 0\.0$",
            id="cylinder-R",
        ),
        pytest.param(
            lambda: I.cylinder(1.0, 1.0, -2.0),
            NonPositiveParameterError,
            r"^h must be > 0; found -2\.0$",
            id="cylinder-h",
        ),
        pytest.param(
            lambda: I.cylinder(1.0, [1.0, 2.0], [[1.0], [0.0]]),
            NonPositiveParameterError,
            r"^h must be > 0; found 0\.0$",
            id="cylinder-h-batched",
        ),
        pytest.param(
            lambda: I.cylindrical_shell(1.0, 0.0, 1.0),
            NonPositiveParameterError,
            r"^R must be > 0; found 0\.0$",
            id="shell-R",
        ),
        pytest.param(
            lambda: I.rectangular_plate(1.0, 1.0, -1.0),
            NonPositiveParameterError,
            r"^b must be > 0; found -1\.0$",
            id="plate-b",
        ),
        pytest.param(
            lambda: I.box(1.0, -1.0, 1.0, 1.0),
            NonPositiveParameterError,
            r"^a must be > 0; found -1\.0$",
            id="box-a",
        ),
        pytest.param(
            lambda: I.solid_cone(1.0, -1.0, 1.0),
            NonPositiveParameterError,
            r"^R must be > 0; found -1\.0$",
            id="cone-R",
        ),
        pytest.param(
            lambda: I.solid_cone(1.0, 1.0, 0.0),
            NonPositiveParameterError,
            r"^h must be > 0; found 0\.0$",
            id="cone-h",
        ),
        pytest.param(
            lambda: I.check_inertia(_TRIANGLE),
            NonPhysicalInertiaError,
            r"^J breaks the triangle inequality J1 \+ J2 >= J3 about G: principal moments \[1\.0, 1\.0, 3\.0\] give J1 \+ J2 - J3 = -1 \(-0\.333 of J3; index \(\)\)$",
            id="check-triangle-about-G",
        ),
        pytest.param(
            lambda: I.check_inertia(_TRIANGLE, about_centre_of_mass=False),
            NonPhysicalInertiaError,
            r"^J breaks the triangle inequality J1 \+ J2 >= J3 about the given point: ",
            id="check-triangle-about-point",
        ),
        pytest.param(
            lambda: I.principal_axes(_TRIANGLE),
            NonPhysicalInertiaError,
            r"^J breaks the triangle inequality J1 \+ J2 >= J3: principal",
            id="principal-triangle",
        ),
        pytest.param(
            lambda: I.check_inertia(np.diag([-1.0, 2.0, 2.0])),
            NonPhysicalInertiaError,
            r"^J is not positive semidefinite: smallest principal moment J1 = -1 < 0 \(by 0\.5 of the largest moment; index \(\)\)$",
            id="check-negative-moment",
        ),
        pytest.param(
            lambda: I.check_inertia(np.array([[2.0, 0.5, 0], [0, 2.0, 0], [0, 0, 2.0]])),
            NonPhysicalInertiaError,
            r"^J is not symmetric: max \|J - J\^T\| = 0\.5 = 1e\+15 eps of the largest moment, more than 64 eps \(index \(\)\)$",
            id="check-asymmetric",
        ),
        pytest.param(
            lambda: I.check_inertia(np.diag([1e-300, 2.0, 2.0])),
            NonPhysicalInertiaError,
            r"^J is not positive definite: smallest principal moment J1 = 1e-300 is zero to rounding \(5e-301 of the largest moment, index \(\)\)",
            id="check-singular-ratio",
        ),
        pytest.param(
            lambda: I.principal_axes(np.eye(2)),
            ShapeError,
            r"^J has shape \(2, 2\); expected \(\.\.\., 3, 3\)",
            id="principal-shape",
        ),
        pytest.param(
            lambda: I.is_physical_inertia(np.eye(2)),
            ShapeError,
            r"^J has shape \(2, 2\); expected \(\.\.\., 3, 3\)",
            id="is-physical-shape",
        ),
        pytest.param(
            lambda: I.inertia_A_from_O(np.eye(2), np.eye(3)),
            ShapeError,
            r"^J_O has shape \(2, 2\)",
            id="A-from-O-shape",
        ),
        pytest.param(
            lambda: I.inertia_tensor([], np.zeros((0, 3)), about=ORIGIN),
            ZeroTotalMassError,
            r"^no particles: the centre of mass is undefined$",
            id="particles-none",
        ),
        pytest.param(
            lambda: I.inertia_tensor(
                [[0.25, 0.25], [0.0, 0.0]], [[[1.0, 0, 0], [0, 1.0, 0]]] * 2, about=ORIGIN
            ),
            ZeroTotalMassError,
            r"^total mass is 0 \(index \(1,\)\): G is undefined$",
            id="particles-zero-total-batched",
        ),
        pytest.param(
            lambda: I.parallel_axis(np.eye(3), 1e300, [1e300, 0, 0]),
            _overflow_error(),
            r"^the shifted inertia tensor overflows float64 \(finite inputs, result beyond 1\.8e308\)$",
            id="parallel-overflow",
        ),
        pytest.param(
            lambda: I.parallel_axis(np.eye(3), np.nan, [1.0, 0, 0]),
            NonFiniteError,
            r"^m must be finite",
            id="parallel-m-nan",
        ),
        pytest.param(
            lambda: I.four_particle_realisation(np.nan, np.eye(3)),
            NonFiniteError,
            r"^m must be finite",
            id="four-m-nan",
        ),
        pytest.param(
            lambda: I.principal_subspaces(np.eye(3), rtol=-1.0),
            NonPositiveParameterError,
            r"^rtol must be a finite number >= 0; got -1\.0$",
            id="subspaces-rtol",
        ),
    ],
)
def test_inertia_messages_name_the_argument_the_value_and_the_condition(call, error, match):
    with pytest.raises(error, match=match):
        call()


def test_inertia_tolerances_are_inclusive_and_rtol_zero_is_allowed():
    # a tensor exactly at the triangle inequality's edge (a lamina) is physical
    assert I.is_physical_inertia(np.diag([1.0, 2.0, 3.0]))
    # rtol = 0: only exactly equal moments share a subspace
    _, P = I.principal_subspaces(np.diag([2.0, 2.0, 3.0]), rtol=0.0)
    assert np.diag(P[0]).tolist() == [1.0, 1.0, 0.0]
    _, P = I.principal_subspaces(np.diag([2.0, 2.0 * (1 + 4 * EPS), 3.0]), rtol=0.0)
    assert np.diag(P[0]).tolist() == [1.0, 0.0, 0.0]


def test_principal_subspaces_group_moments_relative_to_the_largest():
    # gaps of 1e-9 of J3 = 1e6: within the default rtol (2**-26 = 1.5e-8) of the
    # largest moment, so J2 and J3 share a subspace; 1e-9 absolute would not.
    J = np.diag([1e5, 1e6, 1e6 * (1 + 1e-9)])
    _, P = I.principal_subspaces(J)
    np.testing.assert_allclose(np.diag(P[2]), [0.0, 1.0, 1.0], atol=ENTRY_ATOL)
    _, P = I.principal_subspaces(J / 1e12)  # the same, scaled: the grouping is scale-free
    np.testing.assert_allclose(np.diag(P[2]), [0.0, 1.0, 1.0], atol=ENTRY_ATOL)


def test_is_physical_inertia_judges_each_tensor_of_a_batch_on_its_own():
    slightly_asymmetric = np.diag([1.0, 2.0, 2.5])
    slightly_asymmetric[0, 1] += 1e-3
    batch = np.array([np.eye(3), slightly_asymmetric, np.diag([2.0, 2.0, 3.0]), -np.eye(3)])
    assert I.is_physical_inertia(batch).tolist() == [True, False, True, False]


_ASYM = np.array([[2.0, 0.5, 0], [0, 2.0, 0], [0, 0, 2.0]])


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        pytest.param(
            lambda: I.rotate_inertia(_ASYM, np.eye(3)),
            NonPhysicalInertiaError,
            r"^J_A is not symmetric: max \|J - J\^T\| = 0\.5, more than 64 eps of its largest entry \(index \(\)\)$",
            id="rotate-asym",
        ),
        pytest.param(
            lambda: I.rotate_inertia(np.array([np.eye(3), _ASYM]), np.eye(3)),
            NonPhysicalInertiaError,
            r"^J_A is not symmetric: .*\(index \(1,\)\)$",
            id="rotate-asym-batched",
        ),
        pytest.param(
            lambda: I.rotate_inertia(_TINY_ASYM, np.eye(3)),
            NonPhysicalInertiaError,
            r"^J_A is not symmetric: max \|J - J\^T\| = 1e-20",
            id="rotate-asym-tiny-tensor",
        ),
        pytest.param(
            lambda: I.rotate_inertia(np.full((3, 3), np.nan), np.eye(3)),
            NonFiniteError,
            r"^J_A must be finite",
            id="rotate-nan",
        ),
        pytest.param(
            lambda: I.rotate_inertia(np.eye(2), np.eye(3)),
            ShapeError,
            r"^J_A has shape \(2, 2\)",
            id="rotate-shape",
        ),
        pytest.param(
            lambda: I.inertia_A_from_O(np.full((3, 3), np.inf), np.eye(3)),
            NonFiniteError,
            r"^J_O must be finite",
            id="A-from-O-inf",
        ),
        pytest.param(
            lambda: I.rotate_inertia(_HUGE_OFFDIAG, R3(np.pi / 4)),
            _overflow_error(),
            r"^the rotated inertia tensor overflows float64 \(finite inputs",
            id="rotate-overflow",
        ),
        pytest.param(
            lambda: I.inertia_A_from_O(_HUGE_OFFDIAG, R3(np.pi / 4)),
            _overflow_error(),
            r"^the rotated inertia tensor overflows float64 \(finite inputs",
            id="A-from-O-overflow",
        ),
        pytest.param(
            lambda: I.box(1e200, 1e200, 1e200, 1e200),
            _overflow_error(),
            r"^the inertia tensor overflows float64 \(finite inputs, result beyond 1\.8e308\)$",
            id="box-overflow",
        ),
        pytest.param(
            # physical (moments 0.6, 1.5, 1.8 times 1e308), but 1.8e308 is beyond float64
            lambda: I.principal_axes(1e308 * np.array([[1.2, 0.6, 0], [0.6, 1.2, 0], [0, 0, 1.5]])),
            _overflow_error(),
            r"^the principal moments \(entries near the float64 limit\) overflows float64",
            id="principal-overflow",
        ),
        pytest.param(
            # moments (0, 0, 3e308): refused as unphysical first, the moment printed as inf
            lambda: I.principal_axes(np.full((3, 3), 1e308)),
            NonPhysicalInertiaError,
            r"^J breaks the triangle inequality J1 \+ J2 >= J3: principal moments \[.*, inf\]",
            id="principal-unphysical-near-1e308",
        ),
        pytest.param(
            lambda: I.check_inertia(np.array([np.eye(3), _ASYM])),
            NonPhysicalInertiaError,
            r"^J is not symmetric: .*\(index \(1,\)\)$",
            id="check-asym-batched",
        ),
    ],
)
def test_inertia_messages_for_rotation_and_overflow(call, error, match):
    with pytest.raises(error, match=match):
        call()


# a tensor of size 2e-10, asymmetric by 1e-20: 3.6e6 eps of its size (1e-20 is far below
# eps in absolute terms: the tolerance must be relative to the tensor)
_TINY_ASYM = 1e-10 * np.diag([2.0, 2.0, 2.0])
_TINY_ASYM[0, 1] += 1e-20

_HUGE_OFFDIAG = np.array([[1.7e308, 1.7e308, 0], [1.7e308, 1.7e308, 0], [0, 0, 1.0]])


def test_principal_axes_of_a_block_with_equal_diagonal_entries():
    """[[2, 1], [1, 2]] beside 3: the rotation by π/4 (equal diagonal entries, θ = 0),
    moments 2 ∓ 1 and 3 (principal_axes scales the tensor by 2^-2 first, so Jacobi sees
    an off-diagonal entry of 1/4; the entry of exactly 1 is Jacobi's own test below)."""
    moments, _ = I.principal_axes(np.array([[2.0, 1.0, 0], [1.0, 2.0, 0], [0, 0, 3.0]]))
    np.testing.assert_allclose(moments, [1.0, 3.0, 3.0], rtol=0, atol=ENTRY_ATOL * 3)


def test_jacobi_annihilates_an_off_diagonal_entry_of_exactly_one():
    """The Jacobi kernel on its own, unscaled (its callers scale tensors below 1 first,
    but it is stated for any symmetric matrix, and an entry can reach 1 within a sweep):
    [[2, 1, 0], [1, 2, 0], [0, 0, 3]] has eigenvalues 1, 3, 3, and its eigenvectors
    rebuild it (V diag(w) Vᵀ = A, V orthogonal)."""
    A = np.array([[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 3.0]])
    w, V = I._jacobi(A)
    np.testing.assert_allclose(np.sort(w), [1.0, 3.0, 3.0], rtol=0, atol=ENTRY_ATOL * 3)
    np.testing.assert_allclose(V @ np.diag(w) @ V.T, A, rtol=0, atol=ENTRY_ATOL * 3)
    np.testing.assert_allclose(V.T @ V, np.eye(3), rtol=0, atol=ENTRY_ATOL)


def test_parallel_axis_near_the_overflow_threshold_uses_the_plain_formula_correctly():
    # m beyond 2**996: Dekker's split overflows, the plain J_G + m(|d|² 1 − d dᵀ) is used
    J_G, m, d = 1e300 * np.eye(3), 1e301, np.array([1.0, 2.0, 0.5])
    want = J_G + m * (d @ d * np.eye(3) - np.outer(d, d))
    np.testing.assert_allclose(I.parallel_axis(J_G, m, d), want, rtol=ENTRY_ATOL * 4, atol=0)


def test_batched_shapes_follow_every_argument():
    J_G = _general_tensors(3)
    assert I.parallel_axis(J_G, 2.0, [1.0, 0, 0]).shape == (3, 3, 3)
    np.testing.assert_allclose(
        I.parallel_axis(J_G, 2.0, [1.0, 0, 0])[2],
        I.parallel_axis(J_G[2], 2.0, [1.0, 0, 0]),
        rtol=0,
        atol=ENTRY_ATOL * 4,
    )
    rods = I.rod(1.0, [1.0, 2.0])
    assert rods.shape == (2, 3, 3)
    assert rods[1, 0, 0] == pytest.approx(4.0 / 12.0, rel=ENTRY_ATOL)
    cyl = I.cylinder(2.0, [[1.0], [2.0]], [1.0, 3.0, 4.0])
    assert cyl.shape == (2, 3, 3, 3)
    np.testing.assert_array_equal(cyl[1, 2], I.cylinder(2.0, 2.0, 4.0))
    _, P = I.principal_subspaces(J_G)
    assert P.shape == (3, 3, 3, 3)
    for i in range(3):
        _, Pi = I.principal_subspaces(J_G[i])
        np.testing.assert_allclose(P[i], Pi, rtol=0, atol=ENTRY_ATOL * 8)


# ------------------------------------------------- issue 16: the last known bad inputs


def test_batches_that_do_not_broadcast_raise_a_shape_error_listing_each_shape():
    with pytest.raises(ShapeError, match=r"cylinder: .* m \(2,\), R \(3,\), h \(\)$"):
        I.cylinder([1.0, 1.0], [1.0, 1.0, 1.0], 1.0)


def test_no_domain_says_batches_end_in_numpys_bare_value_error():
    text = " ".join((getattr(I, n).__doc__ or "") for n in I.__all__ if callable(getattr(I, n)))
    assert "bare ValueError" not in " ".join(text.split())


def test_four_particles_of_huge_moments_over_a_tiny_mass_are_the_scaled_ones_exactly():
    """J 2^1000 over m 2^-1000: the squared distances J/m (2^2000) overflowed on the way; the
    distances are 2^1000 times those of (m, J), bit for bit (an exact power-of-two scaling)."""
    J = np.array([[2.0, 0.1, 0.0], [0.1, 3.0, 0.0], [0.0, 0.0, 4.0]])
    masses, r = I.four_particle_realisation(4.0 * 2.0**-1000, J * 2.0**1000)
    masses_1, r_1 = I.four_particle_realisation(4.0, J)
    np.testing.assert_array_equal(r, np.ldexp(r_1, 1000))
    np.testing.assert_array_equal(masses, np.ldexp(masses_1, -1000))
    # and those are a realisation of J (the independent route: the particles' tensor)
    np.testing.assert_allclose(
        I.inertia_tensor(masses_1, r_1, about=ORIGIN), J, rtol=0, atol=ENTRY_ATOL * 4.0
    )


def test_four_particles_of_a_mass_near_float64s_limit_keep_their_distances():
    # 2 m overflows for m = 1e308; c² = (x/2)/m does not
    J = np.diag([1.0, 2.0, 2.5])
    _, r = I.four_particle_realisation(1e308, J)
    _, r_1 = I.four_particle_realisation(1.0, J)
    np.testing.assert_allclose(r * 1e154, r_1, rtol=4 * EPS, atol=0)


# ------------------------------ the edges of check_inertia's tolerance, names in messages

#: INERTIA_ATOL of a tensor whose largest moment is 0.75: 64 eps · 0.75 = 3·2⁻⁴⁸, exact.
#: Every tensor below has largest entry 0.75 (so check_inertia's power-of-two scaling is
#: the identity) and moments a hand can read off: a diagonal tensor's are its entries
#: (LAPACK's tridiagonal solver splits at the zero off-diagonals and returns them exactly),
#: and a 2×2 block [[a, δ/2], [δ/2, a]] decoupled from 0.75 leaves 0.75 untouched.
_EDGE = 64 * EPS * 0.75
_BEYOND = np.nextafter(_EDGE, 1.0)  # the next float above the edge


def _asym(delta: float) -> np.ndarray:
    J = np.diag([0.5, 0.5, 0.75])
    J[0, 1] = delta  # |J − Jᵀ| = delta exactly; largest moment 0.75
    return J


@pytest.mark.parametrize(
    ("J", "allow_singular", "refusal"),
    [
        # 'by more than INERTIA_ATOL of the largest moment': the edge itself is accepted
        pytest.param(_asym(_EDGE), False, None, id="asymmetry-at-edge"),
        pytest.param(_asym(_BEYOND), False, "is not symmetric", id="asymmetry-beyond"),
        # J1 = −tol, and J1 + J2 − J3 = −tol too: both at the edge of semidefinite
        pytest.param(np.diag([-_EDGE, 0.75, 0.75]), True, None, id="negative-J1-at-edge"),
        # one ulp below −tol; J1 + J2 rounds back to 0.75 − tol, so only J1 says no
        pytest.param(
            np.diag([-_BEYOND, 0.75, 0.75]), True, "is not positive semidefinite", id="J1-beyond"
        ),
        # positive definite: J1 at the tolerance is 'zero to rounding'; one ulp more is not
        pytest.param(
            np.diag([_EDGE, 0.75, 0.75]), False, "is not positive definite", id="J1-at-tol"
        ),
        pytest.param(np.diag([_BEYOND, 0.75, 0.75]), False, None, id="J1-above-tol"),
        # J1 + J2 − J3 = 0.25 + (0.5 − tol) − 0.75 = −tol exactly: accepted ...
        pytest.param(np.diag([0.25, 0.5 - _EDGE, 0.75]), False, None, id="triangle-at-edge"),
        # ... and 2⁻⁵³ (one ulp of 0.75 − tol) further: refused
        pytest.param(
            np.diag([0.25, 0.5 - _EDGE - 2.0**-53, 0.75]),
            False,
            "breaks the triangle inequality",
            id="triangle-beyond",
        ),
        # J1 < J2: the sum is J1 + J2, not 2 J2 (2 + 2 > 3.5 > 1 + 2)
        pytest.param(
            np.diag([1.0, 2.0, 3.5]), False, "breaks the triangle inequality", id="triangle-J1<J2"
        ),
        pytest.param(
            np.diag([-1.0, 2.0, 2.0]), True, "is not positive semidefinite", id="negative-J1"
        ),
    ],
)
def test_check_inertia_and_is_physical_inertia_agree_at_the_edges_of_the_tolerance(
    J, allow_singular, refusal
):
    assert bool(I.is_physical_inertia(J, allow_singular=allow_singular)) is (refusal is None)
    if refusal is None:
        np.testing.assert_array_equal(I.check_inertia(J, allow_singular=allow_singular), J)
    else:
        with pytest.raises(NonPhysicalInertiaError, match=f"^J {refusal}"):
            I.check_inertia(J, allow_singular=allow_singular)


def test_the_singular_refusal_ends_with_its_remedy():
    with pytest.raises(
        NonPhysicalInertiaError,
        match=r"an ideal line mass or point has this: pass allow_singular=True to accept it$",
    ):
        I.check_inertia(I.rod(12.0, 1.0))


def test_an_empty_batch_of_tensors_is_checked_and_rotated_to_an_empty_batch():
    empty = np.zeros((0, 3, 3))
    for allow_singular in (False, True):
        out = I.check_inertia(empty, allow_singular=allow_singular)
        assert out.shape == (0, 3, 3)
    assert I.is_physical_inertia(empty).shape == (0,)
    assert I.rotate_inertia(empty, np.eye(3)).shape == (0, 3, 3)


def test_rotate_inertia_judges_symmetry_against_each_tensors_own_size():
    # a 1e6 tensor next to a tensor of size 2 that is asymmetric by 1e-12, i.e. 2e3 eps of
    # its size: refused at index 1, although 1e-12 is far below 64 eps of 1e6
    lopsided = 2.0 * np.eye(3)
    lopsided[0, 1] += 1e-12
    batch = np.array([1e6 * np.eye(3), lopsided])
    with pytest.raises(
        NonPhysicalInertiaError, match=r"^J_A is not symmetric: .*\(index \(1,\)\)$"
    ):
        I.rotate_inertia(batch, np.eye(3))
    with pytest.raises(
        NonPhysicalInertiaError, match=r"^J_O is not symmetric: .*\(index \(1,\)\)$"
    ):
        I.inertia_A_from_O(batch, np.eye(3))


#: Each body's lengths, in order, with the name its messages use.
_LENGTHS = {
    "rod": ["ell"],
    "ring": ["R"],
    "disc": ["R"],
    "cylinder": ["R", "h"],
    "cylindrical_shell": ["R", "h"],
    "solid_sphere": ["R"],
    "hollow_sphere": ["R"],
    "rectangular_plate": ["a", "b"],
    "box": ["a", "b", "c"],
    "solid_cone": ["R", "h"],
}


@pytest.mark.parametrize(
    ("body", "k"),
    [(b, k) for b, names in _LENGTHS.items() for k in range(len(names))],
    ids=[f"{b}-{n}" for b, names in _LENGTHS.items() for n in names],
)
def test_each_body_names_the_length_that_is_not_positive(body, k):
    name = _LENGTHS[body][k]
    lengths = [1.0] * len(_LENGTHS[body])
    lengths[k] = 0.0
    with pytest.raises(NonPositiveParameterError, match=rf"^{name} must be > 0; found 0\.0$"):
        getattr(I, body)(1.0, *lengths)


def test_a_massless_rod_has_the_zero_tensor():
    # m = 0 is in the domain (m >= 0): m ℓ²/12 = 0 and the axial moment 0 · m = 0
    np.testing.assert_array_equal(I.rod(0.0, 2.0), np.zeros((3, 3)))


# ---------------------------------------------------------- _shift's overflow fallback


def test_parallel_axis_uses_the_plain_formula_only_where_the_exact_one_overflows():
    """A batch of two shifts: the first needs the plain formula (m = 1e301, beyond Dekker's
    split), the second is exact, and must stay so: about C = G + (1e8, 1, 0) with J_G = 1,
    m = 1, the plain |d|² − d_x² would give J_xx = 1 + (1e16 + 1 − 1e16) = 1 + 0 (cancelled),
    the exact m(d_y² + d_z²) gives 1 + 1 = 2."""
    J_G = np.array([1e300 * np.eye(3), np.eye(3)])
    m = np.array([1e301, 1.0])
    d = np.array([[1.0, 2.0, 0.5], [1e8, 1.0, 0.0]])
    J = I.parallel_axis(J_G, m, d)
    # by hand: J_xx = 1 + 1, J_xy = −1e8, J_yy = 1 + 1e16 (= 1e16 + 1, a tie, even: 1e16),
    # J_zz = 1 + (1e16 + 1) = 1e16 + 2 (exact)
    want = np.array([[2.0, -1e8, 0.0], [-1e8, 1e16, 0.0], [0.0, 0.0, 1e16 + 2.0]])
    np.testing.assert_array_equal(J[1], want)
    np.testing.assert_array_equal(J[1], I.parallel_axis(J_G[1], m[1], d[1]))


def test_parallel_axis_broadcasts_a_batch_of_masses_over_one_tensor_and_offset():
    J = I.parallel_axis(np.eye(3), [1.0, 2.0], [0.0, 0.0, 1.0])
    # J_G + m (|d|² 1 − d dᵀ) with d = e3: diag(1 + m, 1 + m, 1)
    np.testing.assert_array_equal(J, [np.diag([2.0, 2.0, 1.0]), np.diag([3.0, 3.0, 1.0])])


# --------------------------------------------------------------- four particles, Jacobi


def test_four_particles_realise_a_line_mass():
    """Singular tensors are in the domain (a thin rod): moments (0, 1, 1) give
    m a² = 1 − 0 + 1 = 2, b = 0, c = 0 (4.26)-(4.29): two particles at ±√2 on the rod's
    axis e3, two at G."""
    masses, r = I.four_particle_realisation(1.0, I.rod(12.0, 1.0))
    assert masses.tolist() == [0.25] * 4
    a = math.sqrt(2.0)
    np.testing.assert_allclose(np.abs(r), [[0, 0, a], [0, 0, a], [0, 0, 0], [0, 0, 0]], atol=0)
    np.testing.assert_allclose(
        I.inertia_tensor(masses, r, about=ORIGIN), I.rod(12.0, 1.0), rtol=0, atol=ENTRY_ATOL
    )


def test_four_particles_broadcast_one_tensor_over_masses_and_one_mass_over_tensors():
    J = np.diag([1.0, 2.0, 2.5])
    masses, r = I.four_particle_realisation([1.0, 4.0], J)
    assert masses.shape == (2, 4)
    assert r.shape == (2, 4, 3)
    # four times the mass: half the distances (a, b, c ∝ 1/√m)
    np.testing.assert_array_equal(r[1], r[0] / 2.0)
    masses, r = I.four_particle_realisation(2.0, np.array([J, 4.0 * J]))
    assert masses.tolist() == [[0.5] * 4] * 2
    np.testing.assert_array_equal(r[1], 2.0 * r[0])  # four times the tensor: twice the distances


def test_four_particles_of_a_product_of_inertia_of_exactly_one():
    """[[2, 1, 0], [1, 2, 0], [0, 0, 3]] (moments 1, 3, 3: the block [[2, 1], [1, 2]] has
    eigenvalues 2 ∓ 1) reaches Jacobi scaled by 2**-2, with a_00 = a_11 = 1/2 and a_01 = 1/4:
    the rotation by π/4 must be made."""
    J = np.array([[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 3.0]])
    masses, r = I.four_particle_realisation(4.0, J)
    np.testing.assert_allclose(
        I.inertia_tensor(masses, r, about=ORIGIN), J, rtol=0, atol=ENTRY_ATOL * 3.0
    )


#: The particles' own tensor Σ (m/4)(|r|² 1 − r rᵀ), summed by mpmath at 50 digits on the
#: returned floats (exact there: no rounding, overflow or underflow), against J, in eps of J3:
#: Jacobi's moments are within 8 eps of J3 (the module's bound), a², b², c² add three of them,
#: and the square roots, the turn back into the basis of J and the quotients by m add a few
#: roundings each.  Measured 1.15 and 0.45 eps for the two tensors below.
REALISATION_EPS = 16.0


def _realisation_error_eps(masses: np.ndarray, r: np.ndarray, J: np.ndarray) -> float:
    """max |Σ m_i (|r_i|² 1 − r_i r_iᵀ) − J| over the entries, in eps of J3, with the sum and
    J3 (mpmath's symmetric eigen-solver) at 50 digits on the floats as exact binary numbers."""
    with mpmath.workdps(50):
        Jm = mpmath.matrix([[mpmath.mpf(float(x)) for x in row] for row in J])
        E, _ = mpmath.eigsy(Jm)
        J3 = max(E[i] for i in range(3))
        q = [[mpmath.mpf(float(x)) for x in ri] for ri in r]
        n2 = [sum(x * x for x in qi) for qi in q]
        worst = max(
            abs(
                sum(
                    mpmath.mpf(float(mi)) * ((n if i == j else 0) - qi[i] * qi[j])
                    for mi, qi, n in zip(masses, q, n2, strict=True)
                )
                - Jm[i, j]
            )
            for i in range(3)
            for j in range(3)
        )
        return float(worst / J3 / EPS)


@pytest.mark.parametrize(
    ("J", "power"),
    [
        # entries 2**-1059, 2**-1063, 3 * 2**-1060, 2**-1058: subnormal and exact
        pytest.param(
            [[2.0, 0.125, 0.0], [0.125, 3.0, 0.0], [0.0, 0.0, 4.0]], -1060, id="subnormal"
        ),
        # entries up to 0.9 * 2**1024 (finite), moments 0.4, 0.9, 1.2 times 2**1024: the
        # largest is beyond float64, the distances √(J/m) are of order 1
        pytest.param(
            [[1.6, 0.8, 0.0], [0.8, 1.6, 0.0], [0.0, 0.0, 1.8]], 1023, id="moment-beyond-float64"
        ),
    ],
)
def test_four_particles_at_any_scale_are_the_scaled_ones(J, power):
    """Scaling m and J by one power of two leaves the distances √(J/m) unchanged: the
    realisation at 2**power is that of the tensor at scale 1, bit for bit, the masses scaled
    exactly; and the particles have the tensor J·2**power (mpmath, :data:`REALISATION_EPS`)."""
    # Jacobi on the unscaled tensor (before the fix): the subnormal tensor lost digits (its
    # particles' tensor 8.0e9 eps of J3 = 1.8e-6 off, the distances 2.1e-6 relative), and
    # the tensor whose largest moment is beyond float64 raised ResultOverflowError
    J = np.array(J)
    Jp = np.ldexp(J, power)
    masses_1, r_1 = I.four_particle_realisation(0.25, J)
    masses, r = I.four_particle_realisation(np.ldexp(0.25, power), Jp)
    np.testing.assert_array_equal(masses, np.ldexp(masses_1, power))
    np.testing.assert_array_equal(r, r_1)
    assert _realisation_error_eps(masses, r, Jp) <= REALISATION_EPS


def test_principal_axes_of_a_subnormal_tensor_are_exact():
    """Entries 3, 1, 5 times 2**-1074 (subnormal): the moments are those of [[3, 1], [1, 3]]
    and 5, i.e. 2, 4, 5 times 2**-1074, all representable; Jacobi on the tensor scaled to
    [1/2, 1) finds them exactly (one rotation by π/4: 3 ∓ 1)."""
    tiny = 2.0**-1074
    J = np.array([[3.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0, 0.0, 5.0]]) * tiny
    moments, R = I.principal_axes(J)
    np.testing.assert_array_equal(moments, np.array([2.0, 4.0, 5.0]) * tiny)
    np.testing.assert_allclose(np.abs(R[0]), [2**-0.5, 2**-0.5, 0.0], rtol=0, atol=ENTRY_ATOL)


def test_principal_axes_of_a_subnormal_product_of_inertia_warn_of_nothing():
    """A product of inertia of 1e-310 next to unequal moments: the rotation angle's
    cotangent (0.5 − 0.75)/(2e-310) overflows to -inf, which Jacobi takes as 'no rotation';
    the caller sees no RuntimeWarning (an error under -W error) and LAPACK's moments."""
    J = np.array([[0.75, 1e-310, 0.1], [1e-310, 0.5, 0.0], [0.1, 0.0, 0.6]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        moments, _ = I.principal_axes(J)
    # the 1e-310 is far below eps² of the tensor: the moments are those of J without it,
    # 0.5 and the eigenvalues 0.675 ∓ √(0.075² + 0.1²) = 0.675 ∓ 0.125 of the (0, 2) block
    np.testing.assert_allclose(moments, [0.5, 0.55, 0.8], rtol=0, atol=ENTRY_ATOL)


def test_principal_subspaces_with_rtol_zero_group_exactly_equal_upper_moments():
    # J2 = J3 exactly: gap 0 <= 0 · J3, one plane (the J1 = J2 case is tested above)
    _, P = I.principal_subspaces(np.diag([1.0, 3.0, 3.0]), rtol=0.0)
    assert np.diag(P[0]).tolist() == [1.0, 0.0, 0.0]
    assert np.diag(P[1]).tolist() == [0.0, 1.0, 1.0]
    assert np.diag(P[2]).tolist() == [0.0, 1.0, 1.0]
