"""Batched rotation conversions, timed side by side with scipy's ``Rotation``.

Each conversion of 10^6 rotations runs twice in one benchmark group, once by
:mod:`mechanics.rotation` and once by scipy doing the same job (producing or
reading the book's passive matrix ^A R^O, i.e. scipy's matrix transposed), so
``--benchmark-enable`` shows the pair next to each other.  Each test stores the
achieved max error, in eps, against a float64 reference computed in extended
precision (``np.longdouble``, 64-bit mantissa on x86; on platforms where it is
plain float64 the reference carries float64 rounding and the recorded errors are
upper bounds).

Under the default ``--benchmark-disable`` (pyproject addopts) each test runs
once, as a plain correctness test; nothing asserts a time.  ``make bench`` times
them.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from mechanics import rotation as rot
from mechanics._floats import EPS

LD = np.longdouble
#: entries per batch: a million when timed (make bench); when only checked (make test), 2·10⁴
#: draws of the same distributions (the accuracy against the extended-precision reference
#: is the same claim on fewer samples; tests/stability holds the hard cases against mpmath)
N = {True: 10**6, False: 2 * 10**4}
SEED = 20240919

# A single conversion rounds sin/cos and a few products per entry: each library
# stays within 8 eps of the correctly rounded matrix (measured ≤ 6.5 eps).
CONVERSION_ATOL = 8 * EPS

# Two libraries each within CONVERSION_ATOL of the truth differ by at most twice that.
SCIPY_ATOL = 2 * CONVERSION_ATOL

# A rotation vector read from a matrix whose entries are off by CONVERSION_ATOL:
# for angles ≤ π − 1e-6 its conditioning is at most φ/(2 sin(φ/2)) ≤ π/2 per
# unit of angle, times |φ| ≤ π for the axis part; 4π × CONVERSION_ATOL bounds it.
ROTVEC_ATOL = 4 * np.pi * CONVERSION_ATOL


# ------------------------------------------------------------- reference data


def _rotvec_matrix_ld(v: np.ndarray) -> np.ndarray:
    """^A R^O of rotation vectors by (2.29), in extended precision."""
    v = v.astype(LD)
    angle = np.sqrt((v * v).sum(axis=-1))
    e = v / angle[:, None]
    c, s = np.cos(angle), np.sin(angle)
    one_minus_c = 2 * np.sin(angle / 2) ** 2
    e1, e2, e3 = e.T
    M = one_minus_c[:, None, None] * e[:, :, None] * e[:, None, :]
    M[:, 0, 0] += c
    M[:, 1, 1] += c
    M[:, 2, 2] += c
    M[:, 0, 1] += s * e3
    M[:, 0, 2] -= s * e2
    M[:, 1, 0] -= s * e3
    M[:, 1, 2] += s * e1
    M[:, 2, 0] += s * e2
    M[:, 2, 1] -= s * e1
    return M


def _euler_matrix_ld(angles: np.ndarray) -> np.ndarray:
    """^A R^O(ψ, θ, φ) by (2.36), in extended precision."""
    psi, theta, phi = angles.astype(LD).T
    cf, sf, ct, st, cp, sp = (
        np.cos(phi),
        np.sin(phi),
        np.cos(theta),
        np.sin(theta),
        np.cos(psi),
        np.sin(psi),
    )
    return np.stack(
        [
            np.stack([cf * cp - sf * ct * sp, cf * sp + sf * ct * cp, sf * st], axis=-1),
            np.stack([-sf * cp - cf * ct * sp, -sf * sp + cf * ct * cp, cf * st], axis=-1),
            np.stack([st * sp, -st * cp, ct], axis=-1),
        ],
        axis=-2,
    )


@pytest.fixture(scope="module")
def n(timed) -> int:
    return N[timed]


@pytest.fixture(scope="module")
def rotvecs(n) -> np.ndarray:
    """Rotation vectors uniform in the ball of radius π − 1e-6.

    The cap keeps each rotation vector unique (at exactly π, ±π e_a are the same
    rotation and either may be returned).
    """
    rng = np.random.default_rng(SEED)
    axis = rng.normal(size=(n, 3))
    axis /= np.linalg.norm(axis, axis=-1, keepdims=True)
    angle = (np.pi - 1e-6) * rng.uniform(0.0, 1.0, n) ** (1 / 3)
    return axis * angle[:, None]


@pytest.fixture(scope="module")
def rotvec_matrices(rotvecs) -> np.ndarray:
    """The correctly rounded float64 matrices of ``rotvecs``."""
    return _rotvec_matrix_ld(rotvecs).astype(np.float64)


@pytest.fixture(scope="module")
def eulers(n) -> np.ndarray:
    """Euler angles of uniformly distributed rotations (cos θ uniform).

    Uniform rotations essentially never come within 1e-7 of gimbal lock, where
    scipy warns (and pytest turns warnings into errors).
    """
    rng = np.random.default_rng(SEED + 1)
    psi = rng.uniform(-np.pi, np.pi, n)
    theta = np.arccos(rng.uniform(-1.0, 1.0, n))
    phi = rng.uniform(-np.pi, np.pi, n)
    return np.stack([psi, theta, phi], axis=-1)


@pytest.fixture(scope="module")
def euler_matrices(eulers) -> np.ndarray:
    return _euler_matrix_ld(eulers).astype(np.float64)


def _max_err(x, ref) -> float:
    """Max-abs difference in float64; ``ref`` is correctly rounded, so this is
    within half an ulp of the error against the exact value."""
    return float(np.abs(np.asarray(x, np.float64) - np.asarray(ref, np.float64)).max())


def _record(benchmark, impl: str, what: str, err: float, n: int) -> None:
    benchmark.extra_info["implementation"] = impl
    benchmark.extra_info["n"] = n
    benchmark.extra_info[f"max_abs_err_eps_{what}"] = err / EPS


@pytest.fixture(scope="module")
def outputs() -> dict:
    """Results of this run, so that each pair is compared without recomputing."""
    return {}


def _both(outputs, key, impl, out, ours, theirs):
    """(ours, scipy) for ``key``: this test's output and the other one's."""
    outputs[key, impl] = out
    other = "scipy" if impl == "bodycheck" else "bodycheck"
    if (key, other) not in outputs:
        outputs[key, other] = (theirs if impl == "bodycheck" else ours)()
    return outputs[key, "bodycheck"], outputs[key, "scipy"]


IMPLS = ["bodycheck", "scipy"]


# ---------------------------------------------------------- rotvec -> matrix


def _scipy_matrix_from_rotvec(v):
    return Rotation.from_rotvec(v).as_matrix().swapaxes(-1, -2)


@pytest.mark.benchmark(group="rotvec -> matrix")
@pytest.mark.parametrize("impl", IMPLS)
def test_bench_matrix_from_rotvec(benchmark, impl, n, rotvecs, rotvec_matrices, outputs):
    func = rot.matrix_from_rotvec if impl == "bodycheck" else _scipy_matrix_from_rotvec
    out = benchmark(func, rotvecs)
    err = _max_err(out, rotvec_matrices)
    _record(benchmark, impl, "vs_reference_matrix", err, n)
    assert out.shape == (n, 3, 3)
    assert err <= CONVERSION_ATOL
    ours, scipy = _both(
        outputs,
        "rotvec->matrix",
        impl,
        out,
        lambda: rot.matrix_from_rotvec(rotvecs),
        lambda: _scipy_matrix_from_rotvec(rotvecs),
    )
    assert _max_err(ours, scipy) <= SCIPY_ATOL


# ---------------------------------------------------------- matrix -> rotvec


def _scipy_rotvec_from_matrix(M):
    return Rotation.from_matrix(M.swapaxes(-1, -2)).as_rotvec()


@pytest.mark.benchmark(group="matrix -> rotvec")
@pytest.mark.parametrize("impl", IMPLS)
def test_bench_rotvec_from_matrix(benchmark, impl, n, rotvecs, rotvec_matrices, outputs):
    func = rot.rotvec_from_matrix if impl == "bodycheck" else _scipy_rotvec_from_matrix
    out = benchmark(func, rotvec_matrices)
    err = _max_err(out, rotvecs)
    backward = _max_err(_rotvec_matrix_ld(out).astype(np.float64), rotvec_matrices)
    _record(benchmark, impl, "vs_reference_rotvec", err, n)
    _record(benchmark, impl, "backward_matrix", backward, n)
    assert out.shape == (n, 3)
    assert err <= ROTVEC_ATOL
    assert backward <= CONVERSION_ATOL
    ours, scipy = _both(
        outputs,
        "matrix->rotvec",
        impl,
        out,
        lambda: rot.rotvec_from_matrix(rotvec_matrices),
        lambda: _scipy_rotvec_from_matrix(rotvec_matrices),
    )
    assert _max_err(ours, scipy) <= ROTVEC_ATOL


# ----------------------------------------------------------- Euler -> matrix


def _ours_matrix_from_euler(a):
    return rot.matrix_from_euler(a[:, 0], a[:, 1], a[:, 2])


def _scipy_matrix_from_euler(a):
    return Rotation.from_euler("ZXZ", a).as_matrix().swapaxes(-1, -2)


@pytest.mark.benchmark(group="euler -> matrix")
@pytest.mark.parametrize("impl", IMPLS)
def test_bench_matrix_from_euler(benchmark, impl, n, eulers, euler_matrices, outputs):
    func = _ours_matrix_from_euler if impl == "bodycheck" else _scipy_matrix_from_euler
    out = benchmark(func, eulers)
    err = _max_err(out, euler_matrices)
    _record(benchmark, impl, "vs_reference_matrix", err, n)
    assert out.shape == (n, 3, 3)
    assert err <= CONVERSION_ATOL
    ours, scipy = _both(
        outputs,
        "euler->matrix",
        impl,
        out,
        lambda: _ours_matrix_from_euler(eulers),
        lambda: _scipy_matrix_from_euler(eulers),
    )
    assert _max_err(ours, scipy) <= SCIPY_ATOL


# ----------------------------------------------------------- matrix -> Euler


def _ours_euler_from_matrix(M):
    return np.stack(rot.euler_from_matrix(M), axis=-1)


def _scipy_euler_from_matrix(M):
    return Rotation.from_matrix(M.swapaxes(-1, -2)).as_euler("ZXZ")


@pytest.mark.benchmark(group="matrix -> euler")
@pytest.mark.parametrize("impl", IMPLS)
def test_bench_euler_from_matrix(benchmark, impl, n, eulers, euler_matrices, outputs):
    func = _ours_euler_from_matrix if impl == "bodycheck" else _scipy_euler_from_matrix
    out = benchmark(func, euler_matrices)
    # ψ and φ are conditioned like 1/sin θ, so the angles are compared with the
    # input through the matrix they make (the backward error), and θ directly.
    rebuilt = _euler_matrix_ld(out).astype(np.float64)
    backward = _max_err(rebuilt, euler_matrices)
    _record(benchmark, impl, "backward_matrix", backward, n)
    _record(benchmark, impl, "vs_reference_theta", _max_err(out[:, 1], eulers[:, 1]), n)
    assert out.shape == (n, 3)
    assert backward <= CONVERSION_ATOL
    assert ((out[:, 1] >= 0) & (out[:, 1] <= np.pi)).all()
    # Compared with scipy through the matrices the two angle sets make.
    ours, scipy = _both(
        outputs,
        "matrix->euler",
        impl,
        rebuilt,
        lambda: _euler_matrix_ld(_ours_euler_from_matrix(euler_matrices)).astype(np.float64),
        lambda: _euler_matrix_ld(_scipy_euler_from_matrix(euler_matrices)).astype(np.float64),
    )
    assert _max_err(ours, scipy) <= SCIPY_ATOL
