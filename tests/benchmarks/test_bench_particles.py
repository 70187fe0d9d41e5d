"""Centre of mass, momentum and angular momentum of 10^6 particles 1e8 from the origin.

Each kernel runs twice in one benchmark group: :mod:`mechanics.particles`
(compensated sums) and the naive numpy one-liner (``m @ r / m.sum()``,
``m @ v``, ``np.cross(r - A, m[:, None] * v).sum(0)``), so that
``--benchmark-enable`` shows the price of the accuracy next to it.  Each test
stores its achieved error in ``benchmark.extra_info``, in ulps of the exact
result, against exact integer arithmetic: masses are multiples of 2**-40,
positions of 2**-26 (all in [2**26, 2**27)), velocities of 2**-30, so every sum
of products is an exact Python integer and ``float(Fraction)`` rounds it
correctly.

Under the default ``--benchmark-disable`` each test runs once, as a plain
correctness test; nothing asserts a time.  Measured on this machine (median of
3 rounds, shared cores, ``--benchmark-enable``): bodycheck 0.14–0.16 s per
kernel, naive numpy 0.008 s (r_G, p) and 0.06 s (L_O); worst errors bodycheck
0.59 (r_G), 0.28 (p), 0.86 (L_O) ulps, naive 207, 380, 281 ulps.
"""

from __future__ import annotations

import math
import operator
from fractions import Fraction

import numpy as np
import pytest

from mechanics import particles as mp

N = 10**6
SEED = 20261123
ORIGIN = np.zeros(3)

#: The bodycheck kernels promise ≤ 2 ulps (tests/stability); the naive ones
#: promise nothing and are only recorded.
OURS_ULPS = 2.0


@pytest.fixture(scope="module")
def system():
    rng = np.random.default_rng(SEED)
    m = np.ldexp(np.round(np.ldexp(10.0 ** rng.uniform(-6, 6, N), 40)), -40)
    r = np.ldexp(np.round(np.ldexp(1e8 + rng.uniform(-1.0, 1.0, (N, 3)), 26)), -26)
    v = np.ldexp(np.round(np.ldexp(rng.uniform(-1e3, 1e3, (N, 3)), 30)), -30)
    return m, r, v


def _ints(x, e):
    X = np.ldexp(x, e).astype(np.int64)
    assert np.array_equal(np.ldexp(X.astype(float), -e), x)
    return X.tolist()


@pytest.fixture(scope="module")
def exact(system):
    """Exact r_G, p and L_O as Fractions."""
    m, r, v = system
    K = _ints(m, 40)
    R = [_ints(r[:, c], 26) for c in range(3)]
    V = [_ints(v[:, c], 30) for c in range(3)]
    M = sum(K)
    rG = [Fraction(sum(map(operator.mul, K, R[c])), M * 2**26) for c in range(3)]
    p = [Fraction(sum(map(operator.mul, K, V[c])), 2**70) for c in range(3)]
    KR = [list(map(operator.mul, K, R[c])) for c in range(3)]

    def cross(i, j):
        return sum(map(operator.mul, KR[i], V[j]))

    L = [
        Fraction(cross(1, 2) - cross(2, 1), 2**96),
        Fraction(cross(2, 0) - cross(0, 2), 2**96),
        Fraction(cross(0, 1) - cross(1, 0), 2**96),
    ]
    return {"rG": rG, "p": p, "L": L}


def _max_ulps(x, ref) -> float:
    return max(
        float(abs(Fraction(float(xi)) - ri) / Fraction(math.ulp(float(ri))))
        for xi, ri in zip(x, ref, strict=True)
    )


def _naive_com(m, r, v):
    return (m @ r) / m.sum()


def _naive_momentum(m, r, v):
    return m @ v


def _naive_L(m, r, v):
    return np.cross(r - ORIGIN, m[:, None] * v).sum(axis=0)


KERNELS = {
    "rG": (lambda m, r, v: mp.centre_of_mass(m, r), _naive_com),
    "p": (lambda m, r, v: mp.momentum(m, v), _naive_momentum),
    "L": (lambda m, r, v: mp.angular_momentum(m, r, v, about=ORIGIN), _naive_L),
}


@pytest.mark.parametrize("impl", ["bodycheck", "numpy-naive"])
@pytest.mark.parametrize(
    "what",
    [
        pytest.param("rG", marks=pytest.mark.benchmark(group="centre of mass, 1e6 at 1e8")),
        pytest.param("p", marks=pytest.mark.benchmark(group="momentum, 1e6 cancelling")),
        pytest.param("L", marks=pytest.mark.benchmark(group="angular momentum L_O, 1e6 at 1e8")),
    ],
)
def test_bench_particle_sums(benchmark, system, exact, what, impl):
    m, r, v = system
    ours, naive = KERNELS[what]
    func = ours if impl == "bodycheck" else naive
    out = benchmark(func, m, r, v)
    err = _max_ulps(out, exact[what])
    benchmark.extra_info["implementation"] = impl
    benchmark.extra_info["n"] = N
    benchmark.extra_info[f"max_err_ulps_{what}"] = err
    assert out.shape == (3,)
    if impl == "bodycheck":
        assert err <= OURS_ULPS
