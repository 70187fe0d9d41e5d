"""MuJoCo as an external reference (issue 14): three scenes of the engine run again in
MuJoCo, what agrees, what differs and why.

MuJoCo (the ``mujoco`` package of the ``test`` extra) integrates with a fixed step and
resolves contacts as *soft* constraints: for smooth motion it is an independent route to
the same equations, for impacts a different model.  Every MuJoCo run uses
``integrator="RK4"``.  Conventions (:func:`_quat_from_R_A_O`): MuJoCo's ``xmat`` is the
active matrix, columns = body axes in space, so ``xmat = (^A R^O)ᵀ``; the angular velocity
of a free or ball joint (``qvel``) is in body components, like the engine's ``omega``.

Smooth motion: agreement to MuJoCo's own step error
    Each comparison runs MuJoCo at h, h/2, h/4.  If the error at least halves per
    halving, the finest run's error is below its largest difference from the h/2 run:
    that difference plus the engine's own error is the tolerance, nothing chosen by
    hand.  The ratio of successive differences is checked too: 16 with mujoco >= 4.0
    (measured 15.9 for the box, 18 for the top), 4 before (4.0, 4.0): until 4.0 MuJoCo's
    RK4 combined the stages' angular velocities without the Runge-Kutta-Munthe-Kaas
    correction, so orientations converged at second order (its changelog, 4.0.0).

    - *Torqued free box* (``freejoint``; a body-fixed force at an off-centre point by a
      site actuator, ``gear = (F, 0, 0, 0, 0, 0)``; a space-fixed force and couple by
      ``xfrc_applied``; no gravity; h = 2, 1, 0.5 ms; 2 s).  Position, velocity, ω in
      body and in space components and the spin angular momentum in space components
      (with ω, these fix the attitude) agree to 1.9e-12 of their size with mujoco 4.0
      (bound 8.8e-12; MuJoCo computes the box's inertia itself, equal to ours), and to
      5.9e-7 with 3.x (bound 1.8e-6).
    - *Heavy symmetric top* (the built-in ``heavy_top``, exact elliptic solution; a
      ``ball`` joint at the pivot and a ``cylinder`` geom; h = 0.4, 0.2, 0.1 ms; 2 s,
      θ nutating between 0.5 and 1.9 rad): θ(t) agrees to 1.2e-9 rad, the symmetry axis
      to 2.1e-9 (bound 2.3e-8) with mujoco 4.0; 5.5e-5 rad with 3.x (bound 2.7e-4).

Impacts: MuJoCo's contact is a spring-damper, not Newton's law
    A contact row obeys a_c = d·a_ref + (1 − d)·a_u, with the reference acceleration
    a_ref = −b v − k r (MuJoCo's documentation, "Solver parameters").  With the
    impedance d held constant (``solimp = "0.9999 0.9999 …"``) and ``solref = (τ, ζ)``,
    the depth x obeys x'' + (2/τ) x' + x/(τζ)² = 0 while pressed (gravity only through
    (1 − d) g): an oscillator of frequency ω = 1/(τζ) and damping ratio ζ.  Its force
    cannot pull, so the ball lets go at ω_d t = π − 2 arcsin ζ, still 2 v τ ζ² e deep, at

        e(ζ) = exp(−ζ (π − 2 arcsin ζ) / √(1 − ζ²))            (no tension)

    of its speed, not the textbook exp(−π ζ / √(1 − ζ²)) of a spring-damper that may
    pull.  The ball (built-in ``bouncing_ball``) is started 1 mm above the plane at its
    12 m/s impact speed; the rebound ratio is taken back at the height of first touch.

    - *Default contact* (``solref = "0.02 1"``, critically damped; h = 10 µs): rebound
      ratio 0.098 where the engine's e = 5/6.  The ball sinks 88 mm = v τ/ℯ (0.88 of its
      radius), lets go at ω t = 2 with e^{-2} of its speed 65 mm deep, and climbs out
      (estimate 0.097).  MuJoCo's default stops objects; it does not bounce them.
    - *Tuned contact* (``condim = 1``, the engine's smooth plane; ``solimp`` above;
      ``solref = (2 ms, ζ)`` with e(ζ) = e; h = 1 µs): rebound ratio e(1 − 1.8e-4),
      e(1 − 6.0e-4), e(1 − 8.9e-3) for e = 5/6, 1/2, 1/5 (ζ = 0.060, 0.255, 0.731).
      Beyond the step error (1.7e-4 here, tolerance 2h/τ = 1e-3: the damping force
      switches on inside a step) the difference is the climb out of the dent,
      2 g τ ζ² / (e v): a soft contact gives back less than e at the surface.  The ball
      sinks 1.3, 4.3, 7.8 mm (v τ ζ exp(−ζ arccos ζ / √(1 − ζ²)), to 1.7e-4), where the
      engine's impact is instantaneous at zero depth.  The textbook ζ (0.0579 for
      e = 5/6) rebounds at 0.8388, e(1 + 6.6e-3), as e(ζ) predicts.
"""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
from scipy.optimize import brentq

from mechanics._floats import EPS
from mechanics.rotation import matrix_from_euler
from mechanics.scenes import builtin_path, parse_scene, run_scene

mujoco = pytest.importorskip(
    "mujoco", reason="install the test extra: pip install -e '.[test]' (mujoco)"
)

#: the engine's DOP853 at rtol = atol = 1e-12 over a few turns of an O(1) motion: ~1e-11
#: relative (tests/scenes/test_engine.py); 2^20 eps = 2.3e-10 leaves a factor of 20
ENGINE_RTOL = 2**20 * EPS
#: the heavy top's elliptic closed form: a few hundred roundings of O(1) terms
EXACT_RTOL = 2**10 * EPS
#: MuJoCo's RK4 is fourth order for the orientations of ball and free joints since 4.0.0
#: (its changelog: the Runge-Kutta-Munthe-Kaas correction); second order before
RK4_ORDER = 4 if tuple(int(x) for x in mujoco.__version__.split(".")[:2]) >= (4, 0) else 2
#: differences of runs at h, h/2, h/4 are in ratio 2^order, within half an order
RK4_RATIO_RANGE = (2 ** (RK4_ORDER - 0.5), 2 ** (RK4_ORDER + 0.5))

#: the tuned contact: a time constant a tenth of MuJoCo's default (a stiffer contact, a
#: shallower dent) and a step 2000 times smaller
CONTACT_TAU = 2e-3
CONTACT_STEP = 1e-6
#: the default contact (τ = 0.02 s), also resolved by 2000 steps per τ
DEFAULT_STEP = 1e-5
#: the damping force b v (b = 2/τ) switches on inside a step at the first touch: a
#: first-order error of the rebound speed ~ b h = 2 h/τ (measured 1.7e-4; 3.3e-4 at 2 µs)
REBOUND_RTOL = 2 * CONTACT_STEP / CONTACT_TAU
#: impedance held constant at MuJoCo's largest (mjMAXIMP): a_c = d a_ref + (1 − d) a_u
CONSTANT_IMPEDANCE = "0.9999 0.9999 0.001 0.5 2"
#: the ball starts this far above the plane (free fall to it is exact under RK4)
DROP_GAP = 1e-3


# ------------------------------------------------------------------ helpers


def _quat_from_R_A_O(R_A_O) -> np.ndarray:
    """MuJoCo's quaternion (w, x, y, z) of a body whose passive matrix is ^A R^O."""
    q = np.empty(4)
    mujoco.mju_mat2Quat(q, np.ascontiguousarray(np.asarray(R_A_O).T).ravel())
    return q


def _sample(model, data, times, read) -> np.ndarray:
    """Step MuJoCo to each of ``times`` (multiples of the step) and ``read(data)`` there."""
    h, n, out = model.opt.timestep, 0, []
    for T in times:
        k = round(T / h)
        assert abs(k * h - T) <= 64 * EPS * max(T, 1.0), f"{T} is not a multiple of {h}"
        while n < k:
            mujoco.mj_step(model, data)
            n += 1
        mujoco.mj_forward(model, data)
        out.append(read(data))
    return np.array(out)


def _three_steps(run, h) -> tuple[np.ndarray, np.ndarray, float]:
    """MuJoCo at h, h/2, h/4: the finest samples, a bound on their step error and the
    observed ratio of successive differences (16 for a fourth-order method).

    The bound is the largest difference of each quantity from the h/2 run over the run
    (an envelope: a difference can pass through zero at one sample); it holds once the
    error at least halves per halving."""
    coarse, mid, fine = run(h), run(h / 2), run(h / 4)
    d1, d2 = np.abs(coarse - mid), np.abs(mid - fine)
    return fine, np.broadcast_to(d2.max(axis=0), fine.shape), float(d1.max() / d2.max())


def _assert_close_to_step_error(ours, theirs, step_error, scale, our_rtol, what) -> None:
    tol = step_error + our_rtol * scale
    err = np.abs(ours - theirs)
    worst = np.unravel_index(np.argmax(err - tol), err.shape)
    assert np.all(err <= tol), (
        f"{what}: engine and MuJoCo differ by {err[worst]:.3g} at sample {worst}, "
        f"more than MuJoCo's step error {step_error[worst]:.3g} + ours {our_rtol * scale[worst]:.3g}"
    )


# ------------------------------------------------------------------ smooth motion

BOX = {"a": 0.2, "b": 0.4, "c": 0.6, "mass": 1.0}
BOX_INITIAL = {
    "position": [0.0, 0.0, 1.0],
    "velocity": [0.1, 0.2, 0.3],
    "psi": 0.3,
    "theta": 0.7,
    "phi": 0.2,
    "omega": [0.5, -1.0, 2.0],
}
PUSH_BODY = {"force": [0.0, 0.0, 0.4], "at": [0.0, 0.2, 0.0]}  # a thruster on the hull
PULL_SPACE = [0.1, 0.0, -0.05]
COUPLE_SPACE = [0.05, -0.02, 0.03]


def _box_in_mujoco(h):
    a, b, c = BOX["a"], BOX["b"], BOX["c"]
    F, at = PUSH_BODY["force"], PUSH_BODY["at"]
    xml = f"""
    <mujoco>
      <option integrator="RK4" timestep="{h!r}" gravity="0 0 0"/>
      <worldbody>
        <body name="box">
          <freejoint/>
          <geom type="box" size="{a / 2!r} {b / 2!r} {c / 2!r}" mass="{BOX["mass"]!r}"/>
          <site name="thruster" pos="{at[0]!r} {at[1]!r} {at[2]!r}"/>
        </body>
      </worldbody>
      <actuator>
        <general site="thruster" gear="{F[0]!r} {F[1]!r} {F[2]!r} 0 0 0"/>
      </actuator>
    </mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    ini = BOX_INITIAL
    data.qpos[:3] = ini["position"]
    data.qpos[3:] = _quat_from_R_A_O(matrix_from_euler(ini["psi"], ini["theta"], ini["phi"]))
    data.qvel[:3] = ini["velocity"]
    data.qvel[3:] = ini["omega"]  # body components, as the engine's omega
    data.ctrl[0] = 1.0  # the site actuator's force is gear · ctrl, in the site's frame
    data.xfrc_applied[1, :3] = PULL_SPACE  # at the centre of mass, space components
    data.xfrc_applied[1, 3:] = COUPLE_SPACE
    return model, data


def _box_state(model):
    J = model.body_inertia[1]

    def read(data):
        R = data.xmat[1].reshape(3, 3)  # (^A R^O)ᵀ
        w = data.qvel[3:]
        return np.concatenate([data.qpos[:3], data.qvel[:3], w, R @ w, R @ (J * w)])

    return read


def test_mujoco_rk4_follows_a_free_box_under_body_and_space_loads_to_its_step_error() -> None:
    duration, samples = 2.0, 11
    scene = parse_scene(
        {
            "scene": {"name": "mujoco_box", "duration": duration, "samples": samples},
            "bodies": [{"name": "box", "shape": "box", **BOX, "initial": BOX_INITIAL}],
            "effects": [
                {"type": "force", "body": "box", **PUSH_BODY, "frame": "body"},
                {"type": "force", "body": "box", "force": PULL_SPACE},
                {"type": "torque", "body": "box", "torque": COUPLE_SPACE},
            ],
        },
        source="mujoco_box.toml",
    )
    r = run_scene(scene)
    assert r.passed, r.summary()
    tr = r.trajectory
    s, m = tr.series, BOX["mass"]
    r_O = np.stack([s["x"], s["y"], s["z"]], -1)
    v_O = np.stack([s["vx"], s["vy"], s["vz"]], -1)
    L_spin = np.stack([s["L_x"], s["L_y"], s["L_z"]], -1) - np.cross(r_O, m * v_O)
    ours = np.concatenate(
        [
            r_O,
            v_O,
            np.stack([s["omega1"], s["omega2"], s["omega3"]], -1),
            np.stack([s["wx"], s["wy"], s["wz"]], -1),
            L_spin,
        ],
        -1,
    )[1:]
    times = tr.t[1:]

    def run(h):
        model, data = _box_in_mujoco(h)
        return _sample(model, data, times, _box_state(model))

    model, _ = _box_in_mujoco(1e-3)
    a, b, c = BOX["a"], BOX["b"], BOX["c"]
    # MuJoCo computes the box's inertia itself: the engine's catalogue, principal axes kept
    np.testing.assert_allclose(
        model.body_inertia[1],
        np.array([b * b + c * c, a * a + c * c, a * a + b * b]) * BOX["mass"] / 12,
        rtol=16 * EPS,
    )
    np.testing.assert_array_equal(model.body_iquat[1], [1.0, 0.0, 0.0, 0.0])

    theirs, step_error, ratio = _three_steps(run, 2e-3)
    lo, hi = RK4_RATIO_RANGE
    assert lo <= ratio <= hi, (
        f"MuJoCo {mujoco.__version__}'s RK4 converges with ratio {ratio:.3g} per halving, "
        f"not 2^{RK4_ORDER}"
    )
    # each group (position, velocity, ω, w, L) relative to its largest size over the run
    scale = np.repeat([np.abs(ours[:, 3 * k : 3 * k + 3]).max() for k in range(5)], 3)
    _assert_close_to_step_error(
        ours, theirs, step_error, np.broadcast_to(scale, ours.shape), ENGINE_RTOL, "free box"
    )


def _top_scene(duration, samples) -> dict:
    with builtin_path("heavy_top").open("rb") as f:
        data = tomllib.load(f)
    data["scene"].update(duration=duration, samples=samples)
    return data


def _top_in_mujoco(h, top, ell, g, R_A_O, omega):
    xml = f"""
    <mujoco>
      <option integrator="RK4" timestep="{h!r}" gravity="0 0 {-g!r}"/>
      <worldbody>
        <body name="top">
          <joint type="ball"/>
          <geom type="cylinder" pos="0 0 {ell!r}" size="{top["radius"]!r} {top["height"] / 2!r}"
                mass="{top["mass"]!r}"/>
        </body>
      </worldbody>
    </mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    data.qpos[:] = _quat_from_R_A_O(R_A_O)
    data.qvel[:] = omega  # body components
    return model, data


def _top_state(data) -> np.ndarray:
    e3 = data.xmat[1].reshape(3, 3)[:, 2]  # the symmetry axis, space components
    theta = math.atan2(math.hypot(e3[0], e3[1]), e3[2])
    return np.concatenate([[theta], e3, data.qvel])


def test_mujoco_ball_joint_top_nutates_like_the_elliptic_solution() -> None:
    data = _top_scene(duration=2.0, samples=21)
    r = run_scene(parse_scene(data, source="heavy_top.toml"))
    assert r.passed, r.summary()
    assert r.method.startswith("exact")
    tr = r.trajectory
    s = tr.series
    assert s["theta"].max() - s["theta"].min() > 1.0, "a large nutation, not a fast top"
    (top,) = data["bodies"]
    ini = top["initial"]
    (ell,) = [e["distance"] for e in data["effects"] if e["type"] == "fixed_point"]
    (g,) = [e["g"] for e in data["effects"] if e["type"] == "gravity"]
    R_A_O = matrix_from_euler(ini["psi"], ini["theta"], ini["phi"])
    omega0 = [s[f"omega{k}"][0] for k in (1, 2, 3)]
    ours = np.stack(
        [s["theta"], s["axis_x"], s["axis_y"], s["axis_z"], s["omega1"], s["omega2"], s["omega3"]],
        -1,
    )[1:]
    times = tr.t[1:]

    def run(h):
        model, d = _top_in_mujoco(h, top, ell, g, R_A_O, omega0)
        return _sample(model, d, times, _top_state)

    theirs, step_error, ratio = _three_steps(run, 4e-4)
    lo, hi = RK4_RATIO_RANGE
    assert lo <= ratio <= hi, (
        f"MuJoCo {mujoco.__version__}'s RK4 converges with ratio {ratio:.3g} per halving, "
        f"not 2^{RK4_ORDER}"
    )
    scale = np.array([math.pi, 1.0, 1.0, 1.0, *[np.abs(ours[:, 4:]).max()] * 3])
    _assert_close_to_step_error(
        ours, theirs, step_error, np.broadcast_to(scale, ours.shape), EXACT_RTOL, "heavy top"
    )


# ------------------------------------------------------------------ impacts


def _bouncing_ball(restitution) -> tuple[dict, float, float, float]:
    """The built-in bouncing ball with restitution e: its body, g, the engine's rebound
    ratio at the first impact and the speed there."""
    with builtin_path("bouncing_ball").open("rb") as f:
        data = tomllib.load(f)
    (imp,) = [e for e in data["effects"] if e["type"] == "impact"]
    imp["restitution"] = restitution
    data["scene"]["duration"] = 1.3  # the first impact only, at 1.22 s
    r = run_scene(parse_scene(data, source="bouncing_ball.toml"))
    assert r.passed, r.summary()
    first = next(ev for ev in r.trajectory.events if ev.kind == "impact")
    (g,) = [e["g"] for e in data["effects"] if e["type"] == "gravity"]
    ratio = first.detail["normal_speed_after"] / first.detail["normal_speed_before"]
    return data["bodies"][0], g, ratio, first.detail["normal_speed_before"]


def _drop_in_mujoco(ball, g, v_in, h, contact="") -> tuple[float, float]:
    """A sphere on a plane in MuJoCo (RK4, step h), started DROP_GAP above the plane so
    that it touches at v_in; ``contact`` is a ``<default><geom>`` attribute string.
    Returns the rebound ratio at the height of first touch and the deepest penetration."""
    a = ball["radius"]
    xml = f"""
    <mujoco>
      <option integrator="RK4" timestep="{h!r}" gravity="0 0 {-g!r}"/>
      <default><geom {contact}/></default>
      <worldbody>
        <geom type="plane" size="1 1 0.1"/>
        <body pos="0 0 {a + DROP_GAP!r}">
          <freejoint/>
          <geom type="sphere" size="{a!r}" mass="{ball["mass"]!r}"/>
        </body>
      </worldbody>
    </mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    data.qvel[2] = -math.sqrt(v_in * v_in - 2 * g * DROP_GAP)
    depth, touched = 0.0, False
    for _ in range(round(1.0 / h)):
        mujoco.mj_step(model, data)
        z, vz = data.qpos[2], data.qvel[2]
        depth = max(depth, a - z)
        touched = touched or z < a
        if touched and z > a and vz > 0:
            # back at the height of first touch: free flight since, energy gives the speed
            return math.sqrt(vz * vz + 2 * g * (z - a)) / v_in, depth
    raise AssertionError(f"the ball did not come back out within 1 s (depth {depth:.3g} m)")


def _restitution_without_tension(zeta) -> float:
    """Speed ratio of a spring-damper of damping ratio ζ < 1 that cannot pull: it lets go
    at ω_d t = π − 2 arcsin ζ, where the force k x + b x' first falls to zero."""
    c = math.sqrt(1 - zeta * zeta)
    return math.exp(-zeta * (math.pi - 2 * math.atan2(zeta, c)) / c)


def _deepest_without_tension(v_in, tau, zeta) -> float:
    """Deepest penetration of that spring-damper (ω = 1/(τζ)), at ω_d t = arccos ζ."""
    c = math.sqrt(1 - zeta * zeta)
    return v_in * tau * zeta * math.exp(-zeta * math.atan2(c, zeta) / c)


def _rebound_at_touch_height(v_in, tau, zeta, g) -> float:
    """The rebound ratio at the height of first touch: the ball lets go at e(ζ) v_in,
    still x_s = 2 v_in τ ζ² e(ζ) deep, and climbs out of that dent against g.  (While
    pressed, gravity acts only through (1 − d) g, d = 0.9999.)"""
    e = _restitution_without_tension(zeta)
    return math.sqrt(e * e - 2 * g * (2 * v_in * tau * zeta * zeta * e) / (v_in * v_in))


def _tuned(zeta) -> str:
    return f'condim="1" solimp="{CONSTANT_IMPEDANCE}" solref="{CONTACT_TAU!r} {zeta!r}"'


def test_mujoco_default_contact_is_nearly_dead_and_sinks_deep() -> None:
    """Documents the difference: MuJoCo's default contact (solref "0.02 1", critically
    damped) does not model restitution; the ball sinks to v τ/ℯ and lets go with e^{-2}
    of its speed, deep in the plane, then climbs out."""
    e = 5 / 6
    ball, g, ours, v_in = _bouncing_ball(e)
    assert ours == pytest.approx(e, rel=64 * EPS)
    tau = 0.02  # MuJoCo's default solref = (0.02, 1)
    ratio, depth = _drop_in_mujoco(ball, g, v_in, DEFAULT_STEP)
    # the impedance ramps 0.9 → 0.95 over the first 1 mm (solimp width) of 88: 1 %
    assert depth == pytest.approx(v_in * tau / math.e, rel=0.01)
    assert depth > 0.8 * ball["radius"]
    # ζ = 1: it lets go at ω t = 2 with e^{-2} v_in, 2 v_in τ e^{-2} deep, and climbs out
    let_go = math.exp(-2)
    estimate = math.sqrt(let_go**2 - 2 * g * 2 * v_in * tau * let_go / v_in**2)
    # the bias (1 − d) g = 0.05 g acting through the 40 ms contact: a few per cent
    assert ratio == pytest.approx(estimate, rel=0.05)
    assert ratio < e / 5, f"MuJoCo's default rebound ratio {ratio:.3g}, the engine's {ours:.3g}"


@pytest.mark.parametrize("e", [5 / 6, 1 / 2, 1 / 5], ids=["5/6", "1/2", "1/5"])
def test_mujoco_contact_tuned_by_its_damping_ratio_rebounds_with_the_restitution(e) -> None:
    ball, g, ours, v_in = _bouncing_ball(e)
    assert ours == pytest.approx(e, rel=64 * EPS)
    # the damping ratio whose no-tension restitution is the engine's e
    zeta = brentq(lambda z: _restitution_without_tension(z) - ours, 1e-6, 1 - 1e-6, xtol=EPS)
    ratio, depth = _drop_in_mujoco(ball, g, v_in, CONTACT_STEP, _tuned(zeta))
    expected = _rebound_at_touch_height(v_in, CONTACT_TAU, zeta, g)
    assert ratio == pytest.approx(expected, rel=REBOUND_RTOL), f"ζ = {zeta:.4g}"
    # what separates it from e is the climb out of the dent, 2 g τ ζ² / (e v_in) relative
    climb = 2 * g * CONTACT_TAU * zeta**2 / (ours * v_in)
    assert abs(ratio / ours - 1) <= REBOUND_RTOL + climb
    assert depth == pytest.approx(
        _deepest_without_tension(v_in, CONTACT_TAU, zeta), rel=REBOUND_RTOL
    )


def test_the_textbook_damping_ratio_misses_the_restitution_because_contact_cannot_pull() -> None:
    e = 5 / 6
    ball, g, ours, v_in = _bouncing_ball(e)
    # exp(−π ζ / √(1 − ζ²)) = e: right for a spring-damper that may pull, not for a contact
    zeta = -math.log(ours) / math.hypot(math.pi, math.log(ours))
    ratio, _ = _drop_in_mujoco(ball, g, v_in, CONTACT_STEP, _tuned(zeta))
    assert ratio == pytest.approx(
        _rebound_at_touch_height(v_in, CONTACT_TAU, zeta, g), rel=REBOUND_RTOL
    )
    assert abs(ratio / ours - 1) > 4 * REBOUND_RTOL
