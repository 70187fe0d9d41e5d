"""MuJoCo, PyBullet and Drake adapters (issue 19, part 3): the protocol, the
conventions proven against exact motions, restitution as each engine expresses it, the
scenarios they cannot express, and the missing extra.

Each engine's tests skip with the extra to install when the engine is absent.  The
scenarios and the measurements (rebound ratio at the height of first touch, nutation
period) are those of ``bench/engines.py``, which prints the figures for every variant.

Tolerances of the smooth motions come from step halving: with runs at h, h/2, h/4 of a
method of order p, the error at h/4 is d₂/(2^p − 1) asymptotically, d₂ the largest
difference of the h/2 and h/4 runs; the test allows twice that (the non-asymptotic
remainder) plus the exact solution's own rounding, and checks the order from the ratio
d₁/d₂ of successive differences.
"""

from __future__ import annotations

import dataclasses
import math
import subprocess
import sys

import numpy as np
import pytest

from bench.engines import (
    BALL_RADIUS,
    ball_drop,
    free_top,
    heavy_top,
    nutation_period,
    rebound,
    theta_of,
)
from mechanics._floats import EPS
from mechanics.conformance.adapters._engines import MissingExtraError
from mechanics.conformance.protocol import (
    Body,
    Ground,
    Pivot,
    Scenario,
    Thrust,
    check_trajectory,
)
from mechanics.errors import MechanicsValueError, UnknownOptionError

#: the exact solutions' own error: a few hundred roundings of O(1) terms
EXACT_ATOL = 2**10 * EPS
#: the initial state written into an engine and read back at t = 0: a quaternion or
#: roll-pitch-yaw conversion each way, a few eps each; 2^6 eps relative to the size
READBACK_RTOL = 2**6 * EPS
#: the halving margin: the error at h/4 is d₂/(2^p − 1) plus higher-order terms
HALVING_MARGIN = 2.0
#: Drake's RK3 controls the local error per step (relative, target CONTINUOUS_ACCURACY);
#: over the few hundred steps of these runs the global error measured 6× the target
#: (free top, 4 s) and 0.4× (heavy top); 2^6 leaves a factor of 10
DRAKE_GLOBAL_FACTOR = 2**6


def _mujoco():
    return pytest.importorskip(
        "mujoco", reason="MuJoCo is not installed: pip install 'bodycheck[mujoco]'"
    )


def _pybullet():
    from mechanics.conformance.adapters._engines import quiet_stdout

    with quiet_stdout():
        return pytest.importorskip(
            "pybullet", reason="PyBullet is not installed: pip install 'bodycheck[pybullet]'"
        )


def _drake():
    return pytest.importorskip(
        "pydrake.all", reason="Drake is not installed: pip install 'bodycheck[drake]'"
    )


def _dart():
    return pytest.importorskip(
        "dartpy", reason="DART is not installed: pip install 'bodycheck[dart]'"
    )


def _adapter(engine: str, *args):
    if engine == "dart":
        _dart()
        from mechanics.conformance.adapters.dart import DartAdapter

        return DartAdapter(*args)
    if engine == "mujoco":
        _mujoco()
        from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

        return MuJoCoAdapter(*args)
    if engine == "pybullet":
        _pybullet()
        from mechanics.conformance.adapters.pybullet import PyBulletAdapter

        return PyBulletAdapter(*args)
    _drake()
    from mechanics.conformance.adapters.drake import DrakeAdapter

    return DrakeAdapter(*args)


VARIANTS = [
    ("mujoco", ("RK4", "default")),
    ("mujoco", ("RK4", "tuned")),
    ("mujoco", ("Euler", "tuned")),
    ("mujoco", ("implicitfast", "tuned")),
    ("pybullet", ("default", "default")),
    ("pybullet", ("default", "tuned")),
    ("pybullet", ("fine", "tuned")),
    ("drake", ("discrete", "point")),
    ("drake", ("discrete", "hydroelastic")),
    ("drake", ("continuous", "point")),
    ("drake", ("continuous", "hydroelastic")),
    ("dart", ("dantzig",)),
    ("dart", ("pgs",)),
]
IDS = [f"{e}-{'-'.join(a)}" for e, a in VARIANTS]


def _general_pivot() -> Scenario:
    """The heavy top with a general initial ω (all three body components), 0.1 s."""
    s, _ = heavy_top(duration=0.1, samples=11)
    b = s.bodies[0]
    R = np.array(b.R_A_O)
    omega = np.array([1.5, -2.0, 30.0])
    arm = -np.array(s.pivot.point)  # pivot to G, body components
    v = R.T @ np.cross(omega, arm)
    return dataclasses.replace(
        s, bodies=(dataclasses.replace(b, omega=tuple(omega), velocity=tuple(v)),)
    )


def _two_bodies_and_ground() -> Scenario:
    """Two free boxes above the ground, tumbling: every body field, two bodies."""
    s, _ = free_top(duration=0.1, samples=11)
    a = s.bodies[0]
    b = dataclasses.replace(
        a, name="other", position=(1.0, -1.0, 2.0), omega=(-0.3, 0.8, 0.1), mass=0.5
    )
    return dataclasses.replace(
        s,
        bodies=(dataclasses.replace(a, position=(0.0, 0.0, 1.0)), b),
        ground=Ground(0.5),
        gravity=(0.0, 0.0, -9.81),
    )


# ------------------------------------------------------------------ the protocol


@pytest.mark.parametrize(("engine", "args"), VARIANTS, ids=IDS)
@pytest.mark.parametrize("case", ["two_bodies", "pivot"])
def test_each_variant_returns_valid_samples_that_start_at_the_initial_state(
    engine, args, case
) -> None:
    a = _adapter(engine, *args)
    s = _two_bodies_and_ground() if case == "two_bodies" else _general_pivot()
    assert a.supports(s) is None
    step = 1e-3 if a.takes_step else None
    tr = check_trajectory(s, a.run(s, step))
    for k, b in enumerate(s.bodies):
        for got, want in (
            (tr.position[0, k], b.position),
            (tr.velocity[0, k], b.velocity),
            (tr.R_A_O[0, k], b.R_A_O),
            (tr.omega[0, k], b.omega),
        ):
            want = np.asarray(want, dtype=float)
            tol = READBACK_RTOL * max(1.0, np.abs(want).max())
            assert np.abs(got - want).max() <= tol, (a.name, b.name, got, want)
    assert isinstance(a.name, str)
    assert a.name


@pytest.mark.parametrize(
    ("engine", "args", "order"),
    [
        ("mujoco", ("RK4",), 4),
        ("mujoco", ("Euler",), 1),
        ("mujoco", ("implicitfast",), 1),
        ("pybullet", ("default",), 1),
        ("pybullet", ("fine",), 1),
        ("drake", ("discrete",), 1),
    ],
    ids=[
        "mujoco-RK4",
        "mujoco-Euler",
        "mujoco-implicitfast",
        "pybullet-default",
        "pybullet-fine",
        "drake-discrete",
    ],
)
def test_free_asymmetric_top_agrees_with_the_exact_motion_to_the_step_halving_error(
    engine, args, order
) -> None:
    a = _adapter(engine, *args)
    s, exact = free_top(duration=2.0, samples=21)
    t = np.asarray(s.sample_times)
    w_ex, R_ex = exact.state(t)

    def run(h):
        tr = check_trajectory(s, a.run(s, h))
        return np.concatenate([tr.R_A_O[:, 0].reshape(-1, 9), tr.omega[:, 0]], -1)

    coarse, mid, fine = (run(h) for h in s.steps)
    d1, d2 = np.abs(coarse - mid).max(), np.abs(mid - fine).max()
    assert 2 ** (order - 0.5) <= d1 / d2 <= 2 ** (order + 0.5), (a.name, d1 / d2)
    err = np.abs(fine - np.concatenate([R_ex.reshape(-1, 9), w_ex], -1)).max()
    bound = HALVING_MARGIN * d2 / (2**order - 1) + EXACT_ATOL
    assert err <= bound, f"{a.name}: error {err:.3g} > step-halving bound {bound:.3g}"
    # the centre moves uniformly: any engine gets that to rounding
    x = np.asarray(s.bodies[0].position) + t[:, None] * np.asarray(s.bodies[0].velocity)
    assert np.abs(a.run(s, s.steps[-1]).position[:, 0] - x).max() <= 2**8 * EPS


def test_drake_continuous_free_top_agrees_with_the_exact_motion_to_its_accuracy() -> None:
    _drake()
    from mechanics.conformance.adapters.drake import CONTINUOUS_ACCURACY, DrakeAdapter

    a = DrakeAdapter("continuous")
    assert a.takes_step is False
    s, exact = free_top(duration=2.0, samples=21)
    tr = check_trajectory(s, a.run(s, None))
    w_ex, R_ex = exact.state(np.asarray(s.sample_times))
    err = max(np.abs(tr.R_A_O[:, 0] - R_ex).max(), np.abs(tr.omega[:, 0] - w_ex).max())
    assert err <= DRAKE_GLOBAL_FACTOR * CONTINUOUS_ACCURACY, err
    assert a.last_stats["steps"] > 0


@pytest.mark.parametrize(
    ("engine", "args", "order"),
    [("mujoco", ("RK4",), 4), ("pybullet", ("fine",), 1)],
    ids=["mujoco-RK4", "pybullet-fine"],
)
def test_pivoted_heavy_top_nutates_like_the_elliptic_solution(engine, args, order) -> None:
    a = _adapter(engine, *args)
    s, exact = heavy_top(duration=1.0, samples=101)
    t = np.asarray(s.sample_times)
    coarse, mid, fine = (theta_of(check_trajectory(s, a.run(s, h))) for h in s.steps)
    d1, d2 = np.abs(coarse - mid).max(), np.abs(mid - fine).max()
    assert 2 ** (order - 0.5) <= d1 / d2 <= 2 ** (order + 0.5), (a.name, d1 / d2)
    err = np.abs(fine - exact.theta(t)).max()
    assert err <= HALVING_MARGIN * d2 / (2**order - 1) + EXACT_ATOL, (a.name, err, d2)


def test_drake_continuous_pivoted_top_nutates_with_the_exact_period() -> None:
    _drake()
    from mechanics.conformance.adapters.drake import CONTINUOUS_ACCURACY, DrakeAdapter

    s, exact = heavy_top(duration=1.0, samples=1001)
    t = np.asarray(s.sample_times)
    th = theta_of(check_trajectory(s, DrakeAdapter("continuous").run(s, None)))
    assert np.abs(th - exact.theta(t)).max() <= DRAKE_GLOBAL_FACTOR * CONTINUOUS_ACCURACY
    # the period from two maxima of the samples (1 ms apart: the parabola's error
    # ~ (h/T)^2 θ-range / curvature, 1e-5 of the period)
    assert nutation_period(t, th) == pytest.approx(exact.nutation_period(), rel=1e-5)


# ------------------------------------------------------------------ restitution


def test_mujoco_tuned_contact_rebounds_at_the_no_tension_restitution() -> None:
    _mujoco()
    from mechanics.conformance.adapters.mujoco import (
        TUNED_TIMECONST,
        MuJoCoAdapter,
        zeta_without_tension,
    )

    e, h = 0.8, 1e-5
    s = ball_drop(e)
    ratio, depth = rebound(s, check_trajectory(s, MuJoCoAdapter("RK4", "tuned").run(s, h)))
    # the ball lets go at e v, still 2 v τ ζ² e deep, and climbs out of the dent against
    # g (test_mujoco_reference): the rebound at the height of first touch
    v, g, tau, zeta = math.sqrt(2 * 9.81 * 1.0), 9.81, TUNED_TIMECONST, zeta_without_tension(e)
    expected = math.sqrt(e * e - 2 * g * (2 * v * tau * zeta * zeta * e) / (v * v))
    # the damping switches on inside a step: a first-order error ~ 2h/τ (= 0.01)
    assert ratio == pytest.approx(expected, rel=2 * h / tau)
    c = math.sqrt(1 - zeta * zeta)
    deepest = v * tau * zeta * math.exp(-zeta * math.atan2(c, zeta) / c)
    # sampled every Δt = 0.1 ms: the nearest sample is within Δt/2 of the bottom, where
    # x ≈ x_max (1 − (ω Δt/2)²/2), ω = 1/(τζ) the contact's frequency
    sampling = 0.5 * (1e-4 / (2 * tau * zeta)) ** 2
    assert depth <= deepest * (1 + 2 * h / tau)
    assert depth >= deepest * (1 - sampling - 2 * h / tau)
    default, deep = rebound(s, MuJoCoAdapter("RK4", "default").run(s, h))
    # the default contact (τ = 20 ms) sinks ten times as deep (depth ∝ τ at one ζ)
    assert deep > 5 * depth, (deep, depth)
    assert 0 < default < 1


def test_mujoco_restitution_maps_are_inverse_to_their_laws() -> None:
    from mechanics.conformance.adapters.mujoco import (
        restitution_without_tension,
        zeta_textbook,
        zeta_without_tension,
    )

    # the no-tension law reaches down to e^-2 only (critical damping); the textbook one to 0
    for e in (math.exp(-2), 0.2, 0.5, 0.8, 5 / 6, 1.0):
        assert restitution_without_tension(zeta_without_tension(e)) == pytest.approx(e, abs=4 * EPS)
    for e in (0.0, 0.2, 0.5, 0.8, 5 / 6, 1.0):
        z = zeta_textbook(e)
        assert (math.exp(-math.pi * z / math.sqrt(1 - z * z)) if z < 1 else 0.0) == (
            pytest.approx(e, abs=4 * EPS)
        )
    with pytest.raises(MechanicsValueError, match=r"\[0, 1\]; got 1.5"):
        zeta_without_tension(1.5)


@pytest.mark.parametrize("variant", ["default", "fine"])
@pytest.mark.parametrize("h", [1e-3, 1e-4])
@pytest.mark.parametrize("e", [0.8, 0.4])
def test_pybullet_tuned_contact_rebounds_with_its_restitution_parameter(variant, h, e) -> None:
    _pybullet()
    from mechanics.conformance.adapters.pybullet import FINE_SUBSTEPS, PyBulletAdapter

    s = ball_drop(e, fine=h)
    ratio, _ = rebound(s, check_trajectory(s, PyBulletAdapter(variant, "tuned").run(s, h)))
    # Newton's law at the impact step: the speed then is v + g δt (δt < h_internal), and
    # the ball climbs out of at most one step's travel: each ~ g h/v relative
    h_internal = h / FINE_SUBSTEPS if variant == "fine" else h
    v = math.sqrt(2 * 9.81 * 1.0)
    assert ratio == pytest.approx(e, rel=4 * 9.81 * h_internal / v)


def test_pybullet_default_contact_swallows_the_bounce_at_small_steps() -> None:
    """Bullet's speculative contact stops the ball in front of the plane when a step
    moves it less than the contact threshold: nothing is left to restitute."""
    _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    s = ball_drop(0.8)
    ratio, depth = rebound(s, PyBulletAdapter("default", "default").run(s, 1e-4))
    assert ratio == 0.0
    assert depth < 1e-4


@pytest.mark.parametrize("contact", ["point", "hydroelastic"])
def test_drake_contact_without_dissipation_is_elastic(contact) -> None:
    _drake()
    from mechanics.conformance.adapters.drake import CONTINUOUS_ACCURACY, DrakeAdapter

    s = ball_drop(1.0)
    ratio, depth = rebound(s, check_trajectory(s, DrakeAdapter("continuous", contact).run(s, None)))
    # d = 0: a conservative spring (point) or pressure field (hydroelastic)
    assert ratio == pytest.approx(1.0, abs=DRAKE_GLOBAL_FACTOR * CONTINUOUS_ACCURACY)
    assert 0 < depth < BALL_RADIUS


@pytest.mark.parametrize("e", [0.8, 0.5])
def test_drake_point_contact_rebounds_at_the_hunt_crossley_restitution(e) -> None:
    """The effective e, measured: the linear Hunt–Crossley law gives e exactly at the
    approach speed without gravity; gravity acts during the contact time t_c and moves
    the rebound speed by at most g t_c."""
    _drake()
    from mechanics.conformance.adapters.drake import DrakeAdapter

    s = ball_drop(e)
    tr = check_trajectory(s, DrakeAdapter("continuous", "point").run(s, None))
    ratio, _ = rebound(s, tr)
    t = np.asarray(s.sample_times)
    pressed = t[tr.position[:, 0, 2] < BALL_RADIUS]
    t_c = pressed[-1] - pressed[0] + 2e-4  # the samples are 0.1 ms apart near the contact
    v = math.sqrt(2 * 9.81 * 1.0)
    assert ratio == pytest.approx(e, abs=9.81 * t_c / v)
    print(f"Drake continuous point contact, e = {e}: measured {ratio:.5f}, t_c = {t_c:.4g} s")


# ------------------------------------------------------------------ what cannot be said


def _rocket() -> Scenario:
    s, _ = free_top(duration=0.1, samples=2)
    return dataclasses.replace(s, thrust=Thrust(0, 0.1, 100.0, 1.0))


@pytest.mark.parametrize(
    ("engine", "args"),
    [("mujoco", ()), ("pybullet", ()), ("drake", ()), ("dart", ())],
    ids=["mujoco", "pybullet", "drake", "dart"],
)
def test_a_rocket_is_unsupported_with_the_reason_and_never_run(engine, args) -> None:
    a = _adapter(engine, *args)
    s = _rocket()
    why = a.supports(s)
    assert why is not None
    assert "mass changes" in why
    assert "Tsiolkovsky" in why
    with pytest.raises(MechanicsValueError, match="cannot run it"):
        a.run(s, 0.05)


def test_pybullet_says_when_no_per_body_restitution_gives_the_pairs() -> None:
    _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    s = _two_bodies_and_ground()
    s = dataclasses.replace(s, pair_restitution=((0, 1, 0.9),))  # ground 0.5: 0.25 ≠ 0.9
    why = PyBulletAdapter().supports(s)
    assert why is not None
    assert "product" in why
    assert "(0, 1)" in why
    # 0.5 · 0.5 = 0.25 is what the ground's 0.5 on both bodies gives: supported
    assert (
        PyBulletAdapter().supports(dataclasses.replace(s, pair_restitution=((0, 1, 0.25),))) is None
    )


def test_drake_refuses_a_pivot_whose_line_to_the_centre_starts_along_gravity() -> None:
    _drake()
    from mechanics.conformance.adapters.drake import DrakeAdapter

    upright = Scenario(
        "sleeping_top",
        "an upright top",
        "(5.77)",
        (Body("top", 1.0, (0.004, 0.004, 0.006), position=(0.0, 0.0, 0.1)),),
        0.1,
        (0.0, 0.1),
        gravity=(0.0, 0.0, -9.81),
        pivot=Pivot(0, (0.0, 0.0, -0.1)),
    )
    why = DrakeAdapter().supports(upright)
    assert why is not None
    assert "BallRpyJoint" in why
    s, _ = heavy_top(duration=0.1, samples=2)
    assert DrakeAdapter().supports(s) is None


def test_mujoco_expresses_pairs_and_ground_together() -> None:
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    s = dataclasses.replace(_two_bodies_and_ground(), pair_restitution=((0, 1, 0.9),))
    assert MuJoCoAdapter().supports(s) is None
    xml = MuJoCoAdapter().mjcf(s, 1e-3)
    assert xml.count("<pair ") == 3  # the ground with each body, and the pair


# ------------------------------------------------------------------ the engines' inertia


def test_each_engine_holds_the_scenario_inertia_not_its_shape_inertia() -> None:
    """The box of free_top would have moments of 0.06 kg m² from its shape; each engine
    must hold the scenario's (1, 2, 3)."""
    s, _ = free_top(duration=0.1, samples=2)
    J = np.array(s.bodies[0].inertia)
    checked = 0
    try:
        _mujoco()
    except pytest.skip.Exception:
        pass
    else:
        from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

        model, _ = MuJoCoAdapter().build(s, 1e-3)
        np.testing.assert_array_equal(model.body_inertia[1], J)
        checked += 1
    try:
        p = _pybullet()
    except pytest.skip.Exception:
        pass
    else:
        from mechanics.conformance.adapters.pybullet import PyBulletAdapter

        cid, ids = PyBulletAdapter().build(s, 1e-3)
        info = p.getDynamicsInfo(*ids[0], physicsClientId=cid)
        p.disconnect(cid)
        np.testing.assert_array_equal(info[2], J)
        checked += 1
    try:
        _drake()
    except pytest.skip.Exception:
        pass
    else:
        from mechanics.conformance.adapters.drake import DrakeAdapter

        _, _, bodies = DrakeAdapter().build(s, 1e-3)
        I = bodies[0].default_rotational_inertia().CopyToFullMatrix3()
        np.testing.assert_array_equal(I, np.diag(J))
        checked += 1
    if not checked:
        pytest.skip("no engine installed: pip install 'bodycheck[engines]'")


# ------------------------------------------------------------------ bad input


@pytest.mark.parametrize(
    ("module", "cls", "extra", "blocked"),
    [
        ("mujoco", "MuJoCoAdapter", "mujoco", "mujoco"),
        ("pybullet", "PyBulletAdapter", "pybullet", "pybullet"),
        ("drake", "DrakeAdapter", "drake", "pydrake.all"),
    ],
)
def test_a_missing_engine_names_the_extra_to_install(monkeypatch, module, cls, extra, blocked):
    import importlib

    mod = importlib.import_module(f"mechanics.conformance.adapters.{module}")
    monkeypatch.setitem(sys.modules, blocked, None)  # import of it now fails
    with pytest.raises(
        MissingExtraError,
        match=rf"needs the {extra} package: pip install "
        rf"'bodycheck\[{extra}\]'",
    ):
        getattr(mod, cls)()
    assert issubclass(MissingExtraError, ImportError)


def test_the_adapters_import_without_their_engines() -> None:
    code = (
        "import sys\n"
        "for m in ('mujoco', 'pybullet', 'pydrake', 'dartpy'): sys.modules[m] = None\n"
        "from mechanics.conformance.adapters import dart, drake, mujoco, pybullet\n"
        "import bench.engines\n"
        "for f in (mujoco.variants, pybullet.variants, drake.variants, dart.variants):\n"
        "    try:\n"
        "        f()\n"
        "    except ImportError as exc:\n"
        "        print(exc)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=60
    ).stdout
    for extra in ("mujoco", "pybullet", "drake", "dart"):
        assert f"pip install 'bodycheck[{extra}]'" in out


def test_pybullet_import_prints_no_banner() -> None:
    _pybullet()
    code = (
        "from mechanics.conformance.adapters.pybullet import PyBulletAdapter\nPyBulletAdapter()\n"
    )
    r = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=60
    )
    assert "build time" not in r.stdout + r.stderr, r.stdout + r.stderr


@pytest.mark.parametrize(
    ("module", "cls", "args", "what"),
    [
        ("mujoco", "MuJoCoAdapter", ("RK45",), "MuJoCo integrator"),
        ("mujoco", "MuJoCoAdapter", ("RK4", "soft"), "MuJoCo contact"),
        ("pybullet", "PyBulletAdapter", ("coarse",), "PyBullet variant"),
        ("drake", "DrakeAdapter", ("implicit",), "Drake mode"),
        ("drake", "DrakeAdapter", ("discrete", "mesh"), "Drake contact"),
    ],
)
def test_an_unknown_variant_is_named(module, cls, args, what) -> None:
    import importlib

    mod = importlib.import_module(f"mechanics.conformance.adapters.{module}")
    with pytest.raises(UnknownOptionError, match=rf"{what} must be one of .*; got '{args[-1]}'"):
        getattr(mod, cls)(*args)


def test_a_step_that_does_not_divide_the_sample_times_is_refused() -> None:
    a = _adapter("mujoco", "RK4")
    s, _ = free_top(duration=0.1, samples=3)
    with pytest.raises(MechanicsValueError, match=r"sample time 0.05 is not a whole number"):
        a.run(s, 0.03)
    with pytest.raises(MechanicsValueError, match=r"needs a step > 0; got -0.01"):
        a.run(s, -0.01)
