"""The derived quantities of a scene, exact and measured (issue 17, part 4), for a user's
scene as for a built-in one."""

from __future__ import annotations

import json

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes import builtin_path, load_scene, parse_scene, run_scene


def _rows(result) -> dict:
    return {n: (x, m) for n, x, m in result.trajectory.derived}


def test_a_users_torque_free_box_reports_its_regime_and_flip_period() -> None:
    """Measured from the samples' sign changes of ω2 (linear interpolation, dt = 0.01 s):
    the crossing times are off by O(dt²) of the curvature, so within dt of 4K/λ."""
    box = {
        "name": "b",
        "shape": "box",
        "mass": 1.0,
        "a": 0.3,
        "b": 0.2,
        "c": 0.1,
        "initial": {"omega": [0.01, 3.0, 0.02]},
    }
    r = run_scene(
        parse_scene(
            {"scene": {"name": "mine", "duration": 20.0, "samples": 2001}, "bodies": [box]},
            source="mine.toml",
        )
    )
    rows = _rows(r)
    assert any(n.startswith("regime: axis") for n in rows)
    exact, measured = rows["period of ω (two flips)"]
    dt = r.trajectory.t[1] - r.trajectory.t[0]
    assert measured == pytest.approx(exact, abs=dt)
    assert "period of ω" in r.summary()
    assert json.loads(r.to_json())["derived"]


def test_the_heavy_top_reports_its_nutation_from_the_solution_and_the_motion() -> None:
    r = run_scene(load_scene(builtin_path("heavy_top")))
    rows = _rows(r)
    exact, measured = rows["nutation period"]
    dt = r.trajectory.t[1] - r.trajectory.t[0]
    # each maximum is a parabola's vertex through three samples: O(dt³) per peak
    assert measured == pytest.approx(exact, abs=dt**2)
    # ψ is read at the first and last maximum by linear interpolation between samples
    # (off by ≤ ⅛ max|Δ²ψ| at each end), at peak times off by ≤ dt² (above: ψ moves by
    # max|ψ̇| dt² more), over the maxima's distance ≥ duration − 2 periods
    rate, measured_rate = rows["mean precession rate ψ̇ (rad/s)"]
    psi, t = r.trajectory.series["psi"], r.trajectory.t
    ends = 2 * (0.125 * float(np.abs(np.diff(psi, 2)).max()) + np.abs(np.diff(psi)).max() * dt)
    assert rate != 0.0
    assert measured_rate == pytest.approx(rate, abs=ends / (t[-1] - t[0] - 2 * exact))
    lo, hi = rows["θ min (rad)"], rows["θ max (rad)"]
    # a sampled extreme misses the true one by at most ½ max|θ̈| dt² (θ̈ read off the
    # samples' second differences)
    theta = r.trajectory.series["theta"]
    miss = 0.5 * float(np.abs(np.diff(theta, 2)).max())
    assert lo[1] == pytest.approx(lo[0], abs=miss)
    assert hi[1] == pytest.approx(hi[0], abs=miss)


@pytest.mark.parametrize(
    ("name", "row"),
    [
        ("bouncing_ball", "kinetic energy lost in impacts (6.41)"),
        ("rocket", "speed gained by burn-out (7.30)"),
    ],
)
def test_impacts_and_rockets_report_their_book_formula_beside_the_motion(name, row) -> None:
    r = run_scene(load_scene(builtin_path(name)))
    exact, measured = _rows(r)[row]
    assert measured == pytest.approx(exact, rel=1024 * EPS)


def test_a_scene_with_nothing_to_derive_reports_nothing() -> None:
    pt = {"name": "p", "shape": "point", "mass": 1.0, "initial": {"velocity": [1.0, 0, 0]}}
    r = run_scene(
        parse_scene({"scene": {"name": "n", "duration": 1.0}, "bodies": [pt]}, source="n.toml")
    )
    assert r.trajectory.derived == []
