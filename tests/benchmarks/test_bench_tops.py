"""Cost of the exact free top and of the elliptic functions, with the error achieved.

- ``ellipj`` of 10^4 arguments: :func:`mechanics.elliptic.ellipj` next to
  ``scipy.special.ellipj`` (same group), at an ordinary parameter and just below
  m = 1; ``extra_info`` holds each one's worst error in eps against mpmath on a
  subsample (the conditioned metric of ``tests/stability/test_elliptic_stability.py``).
- ``FreeAsymmetricTop.omega`` and ``.attitude`` at 10^4 times, generic and near
  the separatrix; ``extra_info`` holds the worst error against the mpmath ODE
  reference of ``tests/data/elliptic_reference.json`` (eps relative to |ω|, and
  max-abs in the attitude matrix) and the cost per evaluation.

Under the default ``--benchmark-disable`` each test runs once as a correctness
test; nothing asserts a time.  ``make bench`` times them.
"""

from __future__ import annotations

import json
from pathlib import Path

import mpmath
import numpy as np
import pytest
import scipy.special as sc

from mechanics import elliptic as el
from mechanics import tops
from mechanics._floats import EPS
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
