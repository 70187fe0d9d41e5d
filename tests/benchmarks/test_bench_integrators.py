"""One step of each integrator on the free rigid body, single and a batch of 1000.

Each benchmark times one step (the call with its validation) of one method, side
by side with scipy's ``solve_ivp(method="DOP853")`` doing the same step, and
stores in ``extra_info`` the error against the exact motion
(:class:`mechanics.tops.FreeAsymmetricTop`, Jacobi elliptic functions) after a
fixed horizon at the method's setting (step or tolerance), with the work done.
Under the default ``--benchmark-disable`` each test runs once, as a plain
correctness test; nothing asserts a time.  ``make bench`` times them.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from mechanics.integrators import (
    free_rigid_body_rhs,
    free_rigid_body_splitting,
    integrate,
    rigid_body_parts,
    rigid_body_state,
)
from mechanics.tops import FreeAsymmetricTop

SEED = 20240919
J = np.array([1.0, 2.0, 2.5])
W_NORM = 1.0
ROTATION = 2 * np.pi / W_NORM
H = ROTATION / 50  # the fixed step of every fixed-step method
RTOL = 1e-9  # the tolerance (rtol = atol) of both DOP853s
HORIZON = {1: 10 * ROTATION, 1000: 2 * ROTATION}  # the batch's error run is shorter
CHECKED_MEMBERS = 10  # batch members compared with the exact motion

# Error bounds at the horizon (max-abs over L_A and ^A R^O, |L| ~ 2; h = 1/50
# rotation, rtol = atol = 1e-9).  Measured, single body over 10 rotations / batch
# over 2: rk4 8.2e-5 / 2.6e-5, splitting-2 4.9e-2 / 4.8e-2 (a phase error of the
# attitude), splitting-4 1.7e-4 / 2.1e-4, splitting-6 7.5e-6 / 6.9e-6, dop853 and
# scipy's DOP853 1.4e-8 / 5e-9.  Each bound is 5–10× the measurement.
ERROR_BOUND = {
    "rk4": 5e-4,
    "splitting-2": 0.3,
    "splitting-4": 2e-3,
    "splitting-6": 5e-5,
    "dop853": 1e-7,
    "scipy-DOP853": 1e-7,
}
METHODS = list(ERROR_BOUND)
BATCHES = [1, 1000]


def _omegas(batch: int) -> np.ndarray:
    rng = np.random.default_rng(SEED)
    d = rng.normal(size=(batch, 3))
    return W_NORM * d / np.linalg.norm(d, axis=-1, keepdims=True)


def _run(method: str, w0: np.ndarray, t1: float) -> tuple[np.ndarray, dict]:
    """States (batch, 12) at t1 and the work, by ``method`` from t = 0."""
    batch = w0.shape[0]
    y0 = rigid_body_state(J * w0, np.eye(3))
    rhs = free_rigid_body_rhs(J)
    if method.startswith("splitting"):
        sol = free_rigid_body_splitting(J, J * w0, np.eye(3), (0.0, t1), H, order=int(method[-1]))
    elif method == "rk4":
        sol = integrate(rhs, y0, (0.0, t1), method="rk4", h=H)
    elif method == "dop853":
        sol = integrate(rhs, y0, (0.0, t1), method="dop853", rtol=RTOL, atol=RTOL, batch_ndim=1)
    else:
        flat = lambda t, y: rhs(t, y.reshape(batch, 12)).reshape(-1)  # noqa: E731
        r = solve_ivp(flat, (0.0, t1), y0.reshape(-1), method="DOP853", rtol=RTOL, atol=RTOL)
        assert r.success
        return r.y[:, -1].reshape(batch, 12), {"steps": r.t.size - 1, "rhs_evals": r.nfev}
    return sol.y[-1], {"steps": sol.steps, "rhs_evals": sol.rhs_evals}


def _error(y: np.ndarray, w0: np.ndarray, t1: float) -> float:
    worst = 0.0
    for i in range(min(CHECKED_MEMBERS, w0.shape[0])):
        top = FreeAsymmetricTop(J, w0[i])
        L, R = rigid_body_parts(y[i])
        worst = max(worst, np.abs(L - J * top.omega(t1)).max(), np.abs(R - top.attitude(t1)).max())
    return float(worst)


@pytest.mark.benchmark(group="free rigid body: one step")
@pytest.mark.parametrize("batch", BATCHES)
@pytest.mark.parametrize("method", METHODS)
def test_bench_one_step(benchmark, method, batch):
    w0 = _omegas(batch)
    t1 = HORIZON[batch]
    y, work = _run(method, w0, t1)
    err = _error(y, w0, t1)
    benchmark.extra_info.update(
        method=method,
        batch=batch,
        setting=f"h={H:.6g}"
        if method in ("rk4",) or method.startswith("splitting")
        else f"rtol={RTOL:g}",
        horizon=t1,
        error_at_horizon=err,
        **work,
    )
    assert err <= ERROR_BOUND[method]
    step = benchmark(_run, method, w0, H)
    assert np.isfinite(step[0]).all()
    assert step[1]["steps"] >= 1
