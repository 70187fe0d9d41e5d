"""Cost of the exact free top and of the elliptic functions, with the error achieved.

- ``ellipj`` of 10^4 arguments: :func:`mechanics.elliptic.ellipj` next to
  ``scipy.special.ellipj`` (same group), at an ordinary parameter and just below
  m = 1; ``extra_info`` holds each one's worst error in eps against mpmath on a
  subsample (the conditioned metric of ``tests/stability/test_elliptic_stability.py``).
- ``FreeAsymmetricTop.omega`` and ``.attitude`` at 10^4 times, generic and near
  the separatrix; ``extra_info`` holds the worst error against the mpmath ODE
  reference of ``tests/data/elliptic_reference.json`` (eps relative to |ω|, and
  max-abs in the attitude matrix) and the cost per evaluation.

- Tops in bulk (issue 30, item 3; ``-k bulk``): building each kind of top, the free
  top's ``state`` over 10^6 instants, and :class:`mechanics.tops.FreeTopBatch` at one
  instant over 10^4 tops, each as a ratio against scipy's DOP853 (or the one-by-one
  calls) timed in the same run; see the section below.

Under the default ``--benchmark-disable`` each test runs once as a correctness
test; nothing asserts a time.  ``make bench`` times them (and asserts the bulk ratios).
"""

from __future__ import annotations

import json
import time
from pathlib import Path

import mpmath
import numpy as np
import pytest
import scipy.special as sc
from scipy.integrate import solve_ivp

from mechanics import elliptic as el
from mechanics import tops
from mechanics._floats import EPS
from mechanics.integrators import free_rigid_body_rhs, rigid_body_state
from mechanics.rotation import matrix_from_euler

N = 10**4
SEED = 20261123
DATA = Path(__file__).resolve().parent.parent / "data" / "elliptic_reference.json"

# The accuracy each call must still have when timed (the stability tests hold the
# tight bounds): ours within ELLIPJ_EPS; the top within 1e4 eps of |ω| over t ≤ 20
# near the separatrix (measured: see the report in extra_info).
TOP_OMEGA_EPS = 1e4


def _ellipj_error(fn, u, m):
    """Worst conditioned error in eps of fn(u, m) on 40 points against mpmath."""
    worst = 0.0
    with mpmath.workdps(40):
        M = mpmath.mpf(m)
        vals = fn(u[:40], m)
        for i, uu in enumerate(u[:40]):
            U = mpmath.mpf(float(uu))
            sn, cn, dn = (mpmath.ellipfun(f, U, m=M) for f in ("sn", "cn", "dn"))
            for f, r, d in (
                (vals[0][i], sn, cn * dn),
                (vals[1][i], cn, sn * dn),
                (vals[2][i], dn, M * sn * cn),
            ):
                scale = EPS * (abs(r) + abs(U * d)) + 2.0**-1022
                worst = max(worst, float(abs(mpmath.mpf(float(f)) - r) / scale))
    return worst


def _ours(u, m):
    return el.ellipj(u, m, m1=1.0 - m)  # 1 − m is exact for 1/2 ≤ m ≤ 1


@pytest.mark.parametrize("m", [0.5, 1 - 1e-12])
@pytest.mark.parametrize("impl", ["mechanics", "scipy"])
def test_bench_ellipj(benchmark, impl, m):
    benchmark.group = f"ellipj m={m}"
    u = np.random.default_rng(SEED).uniform(-30, 30, N)
    m1 = 1.0 - m
    fn = _ours if impl == "mechanics" else sc.ellipj
    out = benchmark(fn, u, m)
    assert np.isfinite(np.stack(out)).all()
    err = _ellipj_error(fn, u, m)
    benchmark.extra_info.update({"n": N, "m1": m1, "max_error_eps": err})
    if impl == "mechanics":
        assert err <= el.ELLIPJ_EPS


def _reference_tops():
    data = json.loads(DATA.read_text())
    return {i: case for i, case in enumerate(data["free_top"])}


@pytest.mark.parametrize("index", [0, 2, 5])
@pytest.mark.parametrize("what", ["omega", "attitude"])
def test_bench_free_top(benchmark, what, index):
    case = _reference_tops()[index]
    J = [float(x) for x in case["J"]]
    w0 = [float(x) for x in case["omega_0"]]
    R0 = matrix_from_euler(*(float(x) for x in case["euler_0"]))
    top = tops.FreeAsymmetricTop(J, w0, R0)
    benchmark.group = f"free top {what}"
    t = np.linspace(0.0, 20.0, N)
    fn = top.omega if what == "omega" else top.attitude
    out = benchmark(fn, t)
    assert np.isfinite(out).all()
    ts = np.array([float(s["t"]) for s in case["samples"]])
    w = top.omega(ts)
    wref = np.array([[float(x) for x in s["omega"]] for s in case["samples"]])
    werr = float(np.abs(w - wref).max() / (EPS * np.linalg.norm(w0)))
    info = {"n": N, "regime": top.regime, "m1": top.m1, "omega_error_eps": werr}
    if case["samples"][0]["R"] is not None:
        R = top.attitude(ts)
        Rref = np.array([[float(x) for x in s["R"]] for s in case["samples"]]).reshape(-1, 3, 3)
        info["attitude_error_eps"] = float(np.abs(R - Rref).max() / EPS)
    stats = getattr(benchmark, "stats", None)
    if stats is not None and getattr(stats, "stats", None) is not None:
        info["seconds_per_evaluation"] = stats.stats.mean / N
    benchmark.extra_info.update(info)
    assert werr <= TOP_OMEGA_EPS


# ------------------------------------------------------------ tops in bulk (issue 30, item 3)
#
# Each figure is a ratio against a peer timed in the same run (best of REPEATS wall times,
# ``time.perf_counter``), so that the load of a shared machine cancels:
#
# - building a top (FreeAsymmetricTop, FreeSymmetricTop, HeavySymmetricTop), against one
#   run of scipy's DOP853 over one rotation of the free top J = (1, 2, 3), ω0 = (0.4, 0.2,
#   1.0) at rtol = atol = 1e-13 (the integration a user would run instead);
# - FreeAsymmetricTop.state over 10^6 instants spanning 1000 rotations, against DOP853
#   over the same 1000 rotations (which gives the state at its own steps only);
# - FreeTopBatch.state of 10^4 different tops at one instant, against the same tops' one-
#   instant path called one by one (FreeAsymmetricTop.state of a float), and against
#   DOP853 top by top to that instant (its time per top measured on a sample).
#
# The absolute targets (build ≤ 20 µs, ≤ 1 µs per instant) are printed and kept in
# extra_info, not asserted (a shared machine's load is not the code's); the ratios are
# asserted under --benchmark-enable at the floors below, the accuracy always.  Measure with
#
#     .venv/bin/python -m pytest tests/benchmarks/test_bench_tops.py -k bulk \
#         --benchmark-enable -p no:randomly -s

BULK_J = np.array([1.0, 2.0, 3.0])
BULK_W0 = np.array([0.4, 0.2, 1.0])
BULK_ROTATION = 2 * np.pi / float(np.linalg.norm(BULK_W0))
BULK_RTOL = 1e-13
BULK_INSTANTS = {True: 10**6, False: 3 * 2**14 + 5}  # timed / correctness run (3+ chunks)
BULK_BATCH = {True: 10**4, False: 300}
BULK_SCIPY_SAMPLE = {True: 20, False: 3}
BULK_REPEATS = {True: 5, False: 1}
BULK_BUILDS = {True: 2000, False: 20}
# floors of the ratios, asserted when timed (measured on the shared 2-core machine of
# issue 30, see docs/guide/accuracy.md): building a free asymmetric top costs under 1/30 of one DOP853
# rotation (1/74 to 1/130 measured; the Fraction construction before issue 30 was ~1/6);
# 10^6 instants cost less than DOP853 over the same 1000 rotations (measured 10–16×); the
# batch call beats the one-by-one calls by 5× (measured 39–52×) and DOP853 top by top by
# 10^3× (measured 5.7e3–8.2e3)
BUILD_RATIO_REQUIRED = 30.0
MANY_RATIO_REQUIRED = 1.0
BATCH_OVER_ONE_BY_ONE_REQUIRED = 5.0
BATCH_OVER_SCIPY_REQUIRED = 1e3
# E = ½ Σ J ω² of every instant and every top of the batch: as tests/mechanics/test_tops_bulk.py
BULK_CONSERVATION_RTOL = 64 * EPS


def _best(fn, repeats):
    best, out = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _dop853_rotation():
    rhs = free_rigid_body_rhs(BULK_J)
    y0 = rigid_body_state(BULK_J * BULK_W0, np.eye(3))
    return lambda: solve_ivp(
        rhs, (0.0, BULK_ROTATION), y0, method="DOP853", rtol=BULK_RTOL, atol=BULK_RTOL
    )


_BUILDERS = {
    "FreeAsymmetricTop": lambda: tops.FreeAsymmetricTop(BULK_J, BULK_W0),
    "FreeSymmetricTop": lambda: tops.FreeSymmetricTop(2.0, 1.0, [0.3, 0.0, 1.0]),
    "HeavySymmetricTop": lambda: tops.HeavySymmetricTop(
        1.0, 0.5, 1.0, theta=1.0, psi_dot=0.3, phi_dot=20.0
    ),
}


@pytest.mark.parametrize("kind", list(_BUILDERS))
def test_bench_bulk_building_a_top_against_one_dop853_rotation(benchmark, timed, kind):
    build = _BUILDERS[kind]
    n = BULK_BUILDS[timed]
    t_scipy, _ = _best(_dop853_rotation(), BULK_REPEATS[timed])

    def many():
        for _ in range(n):
            build()

    t_build = _best(many, BULK_REPEATS[timed])[0] / n
    ratio = t_scipy / t_build
    benchmark.group = "bulk: building a top"
    benchmark.extra_info.update(
        seconds_per_build=t_build, scipy_rotation=t_scipy, ratio_scipy_over_build=ratio
    )
    print(f"\n{kind}: build {1e6 * t_build:.1f} µs; one DOP853 rotation / build = {ratio:.0f}")
    top = benchmark(build)
    assert np.isfinite(top.energy)
    if timed and kind == "FreeAsymmetricTop":
        assert ratio >= BUILD_RATIO_REQUIRED


def test_bench_bulk_state_over_many_instants_against_dop853(benchmark, timed):
    top = tops.FreeAsymmetricTop(BULK_J, BULK_W0)
    rotations = 1000
    n = BULK_INSTANTS[timed]
    ts = np.linspace(0.0, rotations * BULK_ROTATION, n)
    rhs = free_rigid_body_rhs(BULK_J)
    y0 = rigid_body_state(BULK_J * BULK_W0, np.eye(3))
    t_scipy = np.inf
    if timed:
        t_scipy, _ = _best(
            lambda: solve_ivp(
                rhs, (0.0, ts[-1]), y0, method="DOP853", rtol=BULK_RTOL, atol=BULK_RTOL
            ),
            3,
        )
    t_many, (w, _) = _best(lambda: top.state(ts), BULK_REPEATS[timed])
    E = 0.5 * (BULK_J * w * w).sum(-1)
    phase = 1.0 + top._lam * ts
    assert (np.abs(E - top.energy) <= BULK_CONSERVATION_RTOL * phase * top.energy).all()
    ratio = t_scipy / t_many
    benchmark.group = "bulk: state over many instants"
    benchmark.extra_info.update(
        instants=n, seconds_per_instant=t_many / n, scipy_time=t_scipy, ratio_scipy_over_many=ratio
    )
    print(
        f"\nstate over {n} instants: {1e6 * t_many / n:.3f} µs per instant "
        f"(DOP853 over the same {rotations} rotations / ours = {ratio:.2f})"
    )
    benchmark.pedantic(top.state, args=(ts,), rounds=1, iterations=1)
    if timed:
        assert ratio >= MANY_RATIO_REQUIRED


def test_bench_bulk_batch_of_tops_at_one_instant(benchmark, timed):
    n = BULK_BATCH[timed]
    rng = np.random.default_rng(SEED)
    J = np.sort(rng.uniform(0.5, 1.0, (n, 3)), axis=-1)
    J[:, 2] = np.minimum(J[:, 2], J[:, 0] + J[:, 1])
    d = rng.normal(size=(n, 3))
    w0 = d / np.linalg.norm(d, axis=-1, keepdims=True)
    t1 = 7.5
    t_build, batch = _best(lambda: tops.FreeTopBatch(J, w0), 1)
    t_batch, (w, R) = _best(lambda: batch.state(t1), BULK_REPEATS[timed])
    t_one, _ = _best(lambda: [top.state(t1) for top in batch.tops], BULK_REPEATS[timed])
    k = BULK_SCIPY_SAMPLE[timed]

    def scipy_sample():
        for i in range(k):
            rhs = free_rigid_body_rhs(J[i])
            y0 = rigid_body_state(J[i] * w0[i], np.eye(3))
            solve_ivp(rhs, (0.0, t1), y0, method="DOP853", rtol=BULK_RTOL, atol=BULK_RTOL)

    t_scipy = _best(scipy_sample, BULK_REPEATS[timed])[0] / k * n
    E = 0.5 * (J * w * w).sum(-1)
    assert (np.abs(E - batch.energy) <= BULK_CONSERVATION_RTOL * batch.energy * 2).all()
    for i in range(0, n, max(1, n // 20)):  # the batch against each top's own array path
        w1, R1 = batch.tops[i].state(np.array(t1))
        tol = tops.BATCH_EPS * EPS * (1.0 + batch.tops[i]._lam * t1)
        assert np.abs(w[i] - w1).max() <= tol
        assert np.abs(R[i] - R1).max() <= tol
    r_one, r_scipy = t_one / t_batch, t_scipy / t_batch
    benchmark.group = "bulk: a batch of tops at one instant"
    benchmark.extra_info.update(
        tops=n,
        build_seconds_per_top=t_build / n,
        batch_call=t_batch,
        one_by_one=t_one,
        scipy_extrapolated=t_scipy,
        ratio_one_by_one_over_batch=r_one,
        ratio_scipy_over_batch=r_scipy,
    )
    print(
        f"\nbatch of {n} tops at one instant: {1e3 * t_batch:.2f} ms "
        f"({1e6 * t_batch / n:.2f} µs per top; built at {1e6 * t_build / n:.1f} µs per top); "
        f"one by one / batch = {r_one:.1f}, DOP853 top by top / batch = {r_scipy:.3g}"
    )
    benchmark.pedantic(batch.state, args=(t1,), rounds=1, iterations=1)
    if timed:
        assert r_one >= BATCH_OVER_ONE_BY_ONE_REQUIRED
        assert r_scipy >= BATCH_OVER_SCIPY_REQUIRED
