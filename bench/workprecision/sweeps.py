"""The sweeps: every method of a problem over its error levels, timed; the energy drift,
the batched runs, the exact evaluation and the MuJoCo peer.

Part of :mod:`bench.workprecision` (its docstring states the conventions).
"""

from __future__ import annotations

import itertools
import math
import statistics
import sys
import time
from collections.abc import Callable

import numpy as np
from scipy.integrate import solve_ivp

from mechanics.integrators import (
    free_rigid_body_rhs,
    free_rigid_body_splitting,
    integrate,
    rigid_body_parts,
    rigid_body_state,
    time_grid,
)
from mechanics.tops import FreeAsymmetricTop

from .problems import _PERM, FREE_J, FREE_W0, Problem, Run, _scipy_solve
from .settings import (
    BATCH_BODIES,
    BATCH_RTOL,
    BATCH_SCIPY_SAMPLE,
    BATCH_SEED,
    FREE_TOP_ROTATIONS,
    LONG_RUN_S,
    MUJOCO_DT,
    MUJOCO_EXTRA,
    MUJOCO_J,
    MUJOCO_T,
    MUJOCO_W0,
)


class _Progress:
    """A one-line progress bar on stderr (nothing when disabled)."""

    def __init__(self, total: int, enabled: bool):
        self.total, self.done, self.enabled = max(total, 1), 0, enabled
        self.t0 = time.perf_counter()

    def step(self, label: str) -> None:
        self.done += 1
        if not self.enabled:
            return
        width = 30
        fill = int(width * self.done / self.total)
        el = time.perf_counter() - self.t0
        sys.stderr.write(
            f"\r[{'#' * fill}{'.' * (width - fill)}] {self.done}/{self.total} "
            f"{el:6.1f}s {label[:48]:<48}"
        )
        sys.stderr.flush()

    def close(self) -> None:
        if self.enabled:
            sys.stderr.write("\n")
            sys.stderr.flush()


def _timed(fn: Callable[[], Run], repeats: int) -> tuple[Run, float, int]:
    times = []
    run = None
    for i in range(max(repeats, 1)):
        t0 = time.perf_counter()
        run = fn()
        times.append(time.perf_counter() - t0)
        if i == 0 and times[0] > LONG_RUN_S:
            break
    return run, statistics.median(times), len(times)


def _finite_or_none(x):
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def warm_compiled() -> None:
    """Run each compiled kernel once on a tiny problem before anything is timed: the
    first call in a process compiles it (or loads numba's on-disk cache), which costs up
    to seconds on a fresh clone and is not the method's cost (the JIT's cold and warm
    figures are in the README; ``tools/jit_cost.py`` measures them)."""
    J = np.array([1.0, 2.0, 3.0])
    y0 = rigid_body_state(J * np.array([0.4, 0.2, 1.0]), np.eye(3))
    for method, kw in (("rk4", {"h": 0.05}), ("dop853", {"rtol": 1e-6})):
        integrate(free_rigid_body_rhs(J), y0, (0.0, 0.1), method=method, **kw)
    L0, R0 = rigid_body_parts(y0)
    for order in (2, 4, 6, 8):
        for comp in (False, True):
            free_rigid_body_splitting(J, L0, R0, (0.0, 0.1), 0.05, order=order, compensated=comp)
            free_rigid_body_splitting(J, L0[None], R0, (0.0, 0.1), 0.05, order=order)
    integrate(
        free_rigid_body_rhs(J), y0[None], (0.0, 0.1), method="dop853", rtol=1e-6, batch_ndim=1
    )


def sweep(problem: Problem, *, repeats: int, budget: float, progress: _Progress) -> dict:
    """Run every method of ``problem`` over its parameters; records and skipped points."""
    records, skipped = [], []
    for name, (pname, params, runner) in problem.methods.items():
        over = False
        for p in params:
            label = f"{problem.name} {name} {'' if p is None else p}"
            if over:
                skipped.append({"method": name, "param": p, "reason": f"budget {budget} s"})
                progress.step(label + " (skipped)")
                continue
            run, t, nruns = _timed(lambda p=p, runner=runner: runner(p), repeats)
            records.append(
                {
                    "method": name,
                    "family": "exact"
                    if name == "exact"
                    else ("scipy" if name.startswith("scipy-") else "ours"),
                    "param_name": pname,
                    "param": p,
                    "error": float(run.error),
                    "error_parts": run.parts,
                    "time_s": t,
                    "runs": nruns,
                    "steps": run.steps,
                    "rhs_evals": run.rhs_evals,
                    "rejected_steps": run.rejected_steps,
                }
            )
            progress.step(label)
            over = t > budget
        p_new = None if over or problem.target is None else _refine(records, name, problem.target)
        if p_new is not None:
            run, t, nruns = _timed(lambda p=p_new, f=runner: f(p), repeats)
            records.append(
                {
                    **records[-1],
                    "param": p_new,
                    "error": float(run.error),
                    "error_parts": run.parts,
                    "time_s": t,
                    "runs": nruns,
                    "steps": run.steps,
                    "rhs_evals": run.rhs_evals,
                    "rejected_steps": run.rejected_steps,
                    "refined": True,
                }
            )
            progress.step(f"{problem.name} {name} {p_new:.3g} (refined)")
    return {
        "title": problem.title,
        "description": problem.description,
        "horizon": problem.horizon,
        "error_measure": problem.error_measure,
        "records": records,
        "skipped": skipped,
    }


def _refine(records, method, target):
    """The parameter at which ``method``'s error reaches ``target``, by log-log
    interpolation between the two sweep points that bracket it (None if none do)."""
    rs = [r for r in records if r["method"] == method and r["param"] is not None]
    for a, b in itertools.pairwise(rs):
        if a["error"] > target >= b["error"] and a["error"] > 0 and b["error"] > 0:
            la, lb = math.log(a["param"]), math.log(b["param"])
            ea, eb = math.log(a["error"]), math.log(b["error"])
            lp = la + (math.log(target) - ea) * (lb - la) / (eb - ea)
            lp += 0.1 * (1 if lb > la else -1)  # 10 % toward the accurate side
            p = math.exp(lp)
            return math.ceil(p) if isinstance(a["param"], int) else float(f"{p:.2g}")
    return None


def _energy(L, J):
    return 0.5 * (L * L / J).sum(-1)


def energy_drift(quick: bool, progress: _Progress) -> dict:
    """Max relative energy error of the free top up to each horizon (10 … 10⁴ rotations).

    RK4, our DOP853 (rtol = atol = 1e-8), scipy DOP853 (rtol = atol = 1e-8) and the
    splittings of order 2 and 6 at 50 steps per rotation, every one to the longest
    horizon (the slowest, scipy's, takes ~20 s for 10⁴ rotations); the energy is
    sampled 8 times per rotation."""
    J, w0 = FREE_J, FREE_W0
    rot = 2 * math.pi / float(np.linalg.norm(w0))
    horizons = [10, 30] if quick else [10, 100, 1000, 10000]
    n_out = 8 * horizons[-1]
    grid = time_grid(0.0, rot / 8, n_out)
    L0 = J * w0
    E0 = float(_energy(L0, J))
    y0 = rigid_body_state(L0, np.eye(3))
    h = rot / 50
    curves, seconds = {}, {}

    def timed(name, fn):
        t0 = time.perf_counter()
        curves[name] = fn()
        seconds[name] = time.perf_counter() - t0
        progress.step(f"energy drift {name}")

    timed(
        "rk4 (h = rotation/50)",
        lambda: np.abs(
            _energy(integrate(free_rigid_body_rhs(J), y0, grid, method="rk4", h=h).y[:, :3], J) / E0
            - 1
        ),
    )
    timed(
        "dop853 (rtol = 1e-8)",
        lambda: np.abs(
            _energy(
                integrate(free_rigid_body_rhs(J), y0, grid, method="dop853", rtol=1e-8).y[:, :3],
                J,
            )
            / E0
            - 1
        ),
    )

    def scipy_curve():
        sp = solve_ivp(
            free_rigid_body_rhs(J),
            (0.0, float(grid[-1])),
            y0,
            method="DOP853",
            rtol=1e-8,
            atol=1e-8,
            t_eval=grid,
        )
        return np.abs(_energy(sp.y[:3].T, J) / E0 - 1)

    timed("scipy-DOP853 (rtol = 1e-8)", scipy_curve)
    for order in (2, 6):

        def split_curve(order=order):
            s = free_rigid_body_splitting(J[[1, 2, 0]], _PERM @ L0, _PERM, grid, h, order=order)
            return np.abs(_energy(s.y[:, :3], J[[1, 2, 0]]) / E0 - 1)

        timed(f"splitting-{order} (h = rotation/50)", split_curve)
    out = {"horizons_rotations": horizons, "curves": {}, "time_s": seconds}
    for name, c in curves.items():
        running = np.maximum.accumulate(c)
        out["curves"][name] = [float(max(running[8 * n], 0.0)) for n in horizons]
    return out


def batched(quick: bool, repeats: int, progress: _Progress) -> dict:
    """1000 bodies as one array against one body, RK4 and the splitting (order 4)."""
    J = FREE_J
    rot = 2 * math.pi / float(np.linalg.norm(FREE_W0))
    n_bodies = 1000
    steps = 20 if quick else 200
    h = rot / 50
    span = (0.0, steps * h)
    rng = np.random.default_rng(20240919)
    d = rng.normal(size=(n_bodies, 3))
    w = d / np.linalg.norm(d, axis=-1, keepdims=True)
    L = J * w
    yb = rigid_body_state(L, np.eye(3))
    rhs = free_rigid_body_rhs(J)
    out = {"bodies": n_bodies, "steps": steps}
    cases = {
        "rk4": (
            lambda: integrate(rhs, yb[0], span, method="rk4", h=h),
            lambda: integrate(rhs, yb, span, method="rk4", h=h, batch_ndim=1),
        ),
        "splitting-4": (
            lambda: free_rigid_body_splitting(J, L[0], np.eye(3), span, h, order=4),
            lambda: free_rigid_body_splitting(J, L, np.eye(3), span, h, order=4),
        ),
    }
    for name, (one, many) in cases.items():
        res = {}
        for key, fn in (("one_s", one), ("batch_s", many)):
            fn()  # untimed: the first call in a process loads the kernel
            times = []
            for _ in range(max(repeats, 1)):
                t0 = time.perf_counter()
                sol = fn()
                times.append(time.perf_counter() - t0)
            res[key] = statistics.median(times)
            res[key + "_sol"] = sol
        # the batch's first member is the single body's run
        diff = float(np.abs(res["batch_s_sol"].y[-1][0] - res["one_s_sol"].y[-1]).max())
        out[name] = {
            "one_body_s": res["one_s"],
            "batch_s": res["batch_s"],
            "batch_over_one": res["batch_s"] / res["one_s"],
            "member_0_max_diff": diff,
        }
        progress.step(f"batched {name}")
    return out


def batched_vs_scipy(
    quick: bool, repeats: int, progress: _Progress, bodies: int | None = None
) -> dict:
    """:data:`BATCH_BODIES` free bodies (J = (1, 2, 3), random unit ω0, identity
    attitude) over one rotation at |ω| = 1: compiled ``"dop853"`` on the whole batch
    (``batch_ndim=1``, one common step) against scipy's DOP853 run body by body, both at
    rtol = atol = :data:`BATCH_RTOL`.  scipy runs the first :data:`BATCH_SCIPY_SAMPLE`
    bodies; its time per body is scaled to the batch.  Errors against the exact top.
    ``bodies`` replaces the batch's size (``bodycheck bench --check``)."""
    n, k = BATCH_BODIES[quick] if bodies is None else bodies, BATCH_SCIPY_SAMPLE[quick]
    rng = np.random.default_rng(BATCH_SEED)
    d = rng.normal(size=(n, 3))
    w0 = d / np.linalg.norm(d, axis=-1, keepdims=True)
    J = FREE_J
    y0 = rigid_body_state(J * w0, np.eye(3))
    rhs = free_rigid_body_rhs(J)
    t1 = 2 * math.pi

    def ours():
        return integrate(rhs, y0, (0.0, t1), method="dop853", rtol=BATCH_RTOL, batch_ndim=1)

    def theirs():
        return [_scipy_solve(rhs, y0[i], t1, "DOP853", BATCH_RTOL).y[:, -1] for i in range(k)]

    ours()  # untimed: the first call in a process loads the kernel (README: JIT cost)
    sol, t_ours, _ = _timed(ours, repeats)
    progress.step("batch vs scipy: ours")
    ys, t_sample, _ = _timed(theirs, repeats)
    progress.step("batch vs scipy: scipy")
    err_ours = err_scipy = 0.0
    for i in range(k):
        top = FreeAsymmetricTop(J, w0[i])
        wt, Rt = top.state(t1)
        for y, which in ((sol.y[-1, i], "ours"), (ys[i], "scipy")):
            L, R = rigid_body_parts(y)
            e = max(float(np.abs(L / J - wt).max()), float(np.abs(R - Rt).max()))
            if which == "ours":
                err_ours = max(err_ours, e)
            else:
                err_scipy = max(err_scipy, e)
    t_scipy = t_sample / k * n
    return {
        "bodies": n,
        "scipy_bodies_run": k,
        "rtol": BATCH_RTOL,
        "ours_s": t_ours,
        "ours_steps": sol.steps,
        "scipy_sample_s": t_sample,
        "scipy_s": t_scipy,
        "ratio": t_scipy / t_ours,
        "worst_error_ours": err_ours,
        "worst_error_scipy": err_scipy,
    }


def exact_evaluation(repeats: int) -> dict:
    """The exact free top at the free-top problem's horizon: one evaluation of
    ``FreeAsymmetricTop.state`` (the median over ``repeats`` batches of 200 calls, per
    call) and the construction (its elliptic parameters, once per body)."""
    T = FREE_TOP_ROTATIONS[False] * 2 * math.pi / float(np.linalg.norm(FREE_W0))
    top = FreeAsymmetricTop(FREE_J, FREE_W0)
    calls, per_call, build = 200, [], []
    for _ in range(max(repeats, 3)):
        t0 = time.perf_counter()
        for _ in range(calls):
            top.state(T)
        per_call.append((time.perf_counter() - t0) / calls)
        t0 = time.perf_counter()
        FreeAsymmetricTop(FREE_J, FREE_W0)
        build.append(time.perf_counter() - t0)
    return {
        "rotations": FREE_TOP_ROTATIONS[False],
        "evaluation_s": statistics.median(per_call),
        "construction_s": statistics.median(build),
    }


def _mujoco_model(integrator: str):
    import mujoco

    xml = (
        '<mujoco><option gravity="0 0 0" timestep="{dt!r}" integrator="{integ}"/>'
        '<worldbody><body name="top"><freejoint/><inertial pos="0 0 0" mass="1" '
        'diaginertia="{J}"/></body></worldbody></mujoco>'
    ).format(dt=MUJOCO_DT, integ=integrator, J=" ".join(repr(x) for x in MUJOCO_J))
    return mujoco.MjModel.from_xml_string(xml)


def mujoco_peer(quick: bool, repeats: int, progress: _Progress) -> dict:
    """MuJoCo's RK4 and Euler on the torque-free body :data:`MUJOCO_J`, ω0 =
    :data:`MUJOCO_W0` over :data:`MUJOCO_T` s at dt = :data:`MUJOCO_DT` (issue 15), and
    the project's methods on the same run: the fastest that reaches MuJoCo RK4's error.

    MuJoCo runs a ``freejoint`` body with ``diaginertia`` J and no gravity; ``qvel[3:6]``
    is ω in body components and ``xmat = (^A R^O)ᵀ`` (``mj_forward`` after the last
    step makes ``xmat`` that of the final state).  Error, as the free-top problem's:
    max(|Δω_A|/|ω0|, |Δ ^A R^O|) at t = 20 s against :class:`FreeAsymmetricTop`.  The
    MuJoCo time is ``mj_step(model, data, nstep=20000)`` (no Python loop).  Without
    ``mujoco`` the result says which extra to install."""
    try:
        import mujoco
    except ImportError:
        progress.step("mujoco peer (not installed)")
        return {"available": False, "install": MUJOCO_EXTRA}
    J, w0 = np.array(MUJOCO_J), np.array(MUJOCO_W0)
    T = MUJOCO_T
    top = FreeAsymmetricTop(J, w0)
    wT, RT = top.state(T)
    wn = float(np.linalg.norm(w0))

    def err(w, R):
        return max(float(np.abs(w - wT).max()) / wn, float(np.abs(R - RT).max()))

    out: dict = {"available": True, "version": mujoco.__version__, "peers": {}, "ours": []}
    nstep = round(T / MUJOCO_DT)
    for integ in ("RK4", "Euler"):
        model = _mujoco_model(integ)
        data = mujoco.MjData(model)

        def run(model=model, data=data):
            mujoco.mj_resetData(model, data)
            data.qvel[3:6] = w0
            mujoco.mj_step(model, data, nstep=nstep)
            mujoco.mj_forward(model, data)
            return np.array(data.qvel[3:6]), np.array(data.xmat[1]).reshape(3, 3).T

        (w, R), t, _ = _timed(run, repeats)
        out["peers"][f"mujoco-{integ}"] = {"dt": MUJOCO_DT, "error": err(w, R), "time_s": t}
        progress.step(f"mujoco {integ}")
    rhs = free_rigid_body_rhs(J)
    y0 = rigid_body_state(J * w0, np.eye(3))
    cands = [("dop853", "rtol", r) for r in (1e-12, 1e-13, 1e-14, 1e-15)]
    cands += [("rk4", "h", h) for h in (4e-3, 2e-3, 1e-3)]
    cands += [(f"splitting-{o}", "h", h) for o in (6, 8) for h in (0.1, 0.05, 0.025)]
    for name, pname, p in cands:

        def go(name=name, p=p):
            if name == "dop853":
                y = integrate(rhs, y0, (0.0, T), method="dop853", rtol=p).y[-1]
            elif name == "rk4":
                y = integrate(rhs, y0, (0.0, T), method="rk4", h=p).y[-1]
            else:
                order = int(name.split("-")[1])
                y = free_rigid_body_splitting(J, J * w0, np.eye(3), (0.0, T), p, order=order).y[-1]
            L, R = rigid_body_parts(y)
            return L / J, R

        (w, R), t, _ = _timed(go, max(repeats, 5))  # sub-millisecond runs: 5 at least
        out["ours"].append(
            {"method": name, "param_name": pname, "param": p, "error": err(w, R), "time_s": t}
        )
    progress.step("mujoco peer: ours")
    ref = out["peers"]["mujoco-RK4"]
    ok = [r for r in out["ours"] if r["error"] <= ref["error"]]
    best = min(ok, key=lambda r: r["time_s"]) if ok else None
    out["best_at_mujoco_rk4_error"] = best
    out["ratio"] = ref["time_s"] / best["time_s"] if best else None
    return out
