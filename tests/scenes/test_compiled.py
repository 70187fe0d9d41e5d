"""The compiled forward dynamics of a scene (issue 30, item 1:
:mod:`mechanics.scenes.compiled`, :mod:`mechanics.scenes._kernels`) held to the Python
path, the reference, over random scenes of every kind of body and every load that
compiles:

- the rates at random states and phases, and a pinned body's acceleration of G with the
  loads on it (its reaction), agree to the rounding of their terms;
- a whole run on the compiled steps agrees with the run on the reference's, both
  passing their own checks;
- a model that cannot compile says why and runs the Python path (which the run's
  ``how`` names); numba failing to compile gives one warning and the same run; numba
  absent, the Python path runs silently (``tests/test_lean_install.py`` runs the
  battery so);
- a run whose rates blow up fails as the reference's does.

Under mutation (``NUMBA_DISABLE_JIT=1``) the kernels run as Python against these tests.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mechanics.scenes
from mechanics._floats import EPS
from mechanics.integrators import CompiledPathWarning
from mechanics.scenes import SceneError, run_scene
from mechanics.scenes import compiled as sc_compiled
from mechanics.scenes.effects import Loads
from mechanics.scenes.engine import Engine

from .builders import box, cylinder, point, scene, scene_data

BUILTIN = Path(mechanics.scenes.__file__).parent / "builtin"

#: The rates: each component is a sum of a few dozen terms (products of up to three
#: factors) that the kernel adds in the reference's order except where numpy's einsum
#: and matrix products choose theirs; each of the two roundings per term, relative to
#: the largest term (:func:`_term_scale`): 2^6 eps.
RATES_RTOL = 2**6 * EPS
#: Two whole runs: each step's local error is below atol + rtol |y|, and the two step
#: sequences differ by rounding (an acceptance may flip), so over the ≲ 10³ steps of
#: these short runs their states part by at most 2 × 10³ (atol + rtol × the scene's size,
#: its largest state component): 2^11 of that (as tests/scenes/test_engine_properties.py
#: derives, without its impacts' gain).  Compared on the state (r, v, L_A, R_A_O), not
#: on derived series such as ω = L/J, which divide a component held at atol's level by
#: a small moment.
RUN_STEPS = 2**11

#: Where a run into a singularity stalls: at the step that falls below 10 ulp(t), a
#: little past the encounter, as the error of the separation grows with the collapsing
#: steps (measured 2.7e-13 relative on both paths): 2^16 eps.
STALL_RTOL = 2**16 * EPS

#: examples per test: many under the explore profile, a smoke run otherwise (a run
#: test's example runs two scenes)
MANY = settings.default.max_examples >= 1000

_u = st.floats


def _vec(lo: float, hi: float):
    return st.lists(_u(lo, hi), min_size=3, max_size=3)


def _direction():
    return _vec(-1.0, 1.0).filter(lambda v: math.hypot(*v) > 0.1)


@st.composite
def _bodies(draw, pin: bool):
    """One to three bodies: points, boxes, boxes on a fixed axis (``hinged``, the
    table of each joint), and at most one top on a fixed point (the first, with
    ``pin``)."""
    n = draw(st.integers(1, 3))
    out, pinned, hinged = [], None, []
    for k in range(n):
        kinds = ["point", "box", "hinged"] + (["pinned"] if pinned is None else [])
        kind = "pinned" if pin and k == 0 else draw(st.sampled_from(kinds))
        name = f"b{k}"
        if kind == "hinged":
            dims = {d: draw(_u(0.1, 1.0)) for d in "abc"}
            init = {"angle": draw(_u(-3, 3)), "angular_velocity": draw(_u(-3, 3))}
            out.append(box(name, mass=draw(_u(0.5, 2)), **dims, **init))
            hinged.append(
                {
                    "type": "fixed_axis",
                    "body": name,
                    "axis": draw(_direction()),
                    "distance": draw(_u(0.0, 0.5)),
                    "body_axis": draw(st.sampled_from("xyz")),
                    "point": draw(_vec(-1, 1)),
                }
            )
            continue
        if kind == "point":
            out.append(point(name, draw(_vec(-2, 2)), draw(_vec(-1, 1)), mass=draw(_u(0.5, 2))))
            continue
        angles = {a: draw(_u(-3, 3)) for a in ("psi", "theta", "phi")}
        omega = draw(_vec(-3, 3))
        if kind == "box":
            dims = {d: draw(_u(0.1, 1.0)) for d in "abc"}
            out.append(
                box(
                    name,
                    draw(_vec(-2, 2)),
                    draw(_vec(-1, 1)),
                    mass=draw(_u(0.5, 2)),
                    **dims,
                    **angles,
                    omega=omega,
                )
            )
        else:
            pinned = (name, draw(_u(0.0, 0.5)), draw(_vec(-1, 1)))
            out.append(
                cylinder(
                    name,
                    mass=draw(_u(0.5, 2)),
                    radius=draw(_u(0.15, 0.3)),
                    height=draw(_u(0.1, 0.8)),
                    **angles,
                    omega=omega,
                )
            )
    return out, pinned, hinged


@st.composite
def compiled_scenes(draw, *, duration: float = 1.0, samples: int = 11, pin: bool = False) -> dict:
    """A scene's tables whose bodies and loads all compile: gravity, springs and
    dampers (between bodies, or to an anchor; at points off G), drag (linear, quadratic,
    rotational), applied forces and couples (space or body frame, in a window),
    Newtonian gravity, a fixed point (always, with ``pin``)."""
    bodies, pinned, hinged = draw(_bodies(pin))
    names = [b["name"] for b in bodies]
    solid = [b["name"] for b in bodies if b["shape"] != "point"]
    effects: list[dict] = []
    if pinned is not None:
        name, dist, at = pinned
        effects.append({"type": "fixed_point", "body": name, "distance": dist, "point": at})
    effects += hinged
    for joint in hinged:
        if draw(st.booleans()):
            effects.append(
                {"type": "torsion", "body": joint["body"], "stiffness": draw(_u(0.1, 5.0))}
            )
    if draw(st.booleans()):
        effects.append({"type": "gravity", "g": draw(_u(1, 20)), "direction": draw(_direction())})
    for _ in range(draw(st.integers(0, 2))):
        kind = draw(st.sampled_from(["spring", "damper"]))
        i = draw(st.sampled_from(names))
        e: dict = {"type": kind, "body": i}
        if i in solid and draw(st.booleans()):
            e["at"] = draw(_vec(-0.3, 0.3))
        others = [n for n in names if n != i]
        if others and draw(st.booleans()):
            e["other"] = j = draw(st.sampled_from(others))
            if j in solid and draw(st.booleans()):
                e["other_at"] = draw(_vec(-0.3, 0.3))
        else:
            e["anchor"] = draw(_vec(-2, 2))
        if kind == "spring":
            e["stiffness"] = draw(_u(0.5, 20))
            e["rest_length"] = draw(_u(0.0, 1.0))
            e["damping"] = draw(st.sampled_from([0.0, 0.3]))
        else:
            e["damping"] = draw(_u(0.1, 2))
        effects.append(e)
    if draw(st.booleans()):
        i = draw(st.sampled_from(names))
        e = {"type": "drag", "body": i, "linear": draw(_u(0.0, 1)), "quadratic": draw(_u(0.01, 1))}
        # at most 0.05 N m s: 60 /s against the smallest moment (8.3e-4 kg m², a 0.1 m cube
        # of 0.5 kg), inside DOP853's stability region at these runs' steps (on a stiffer
        # mode the explicit steps hold it only at atol's level, and the attitude drifts)
        if i in solid:
            e["angular_linear"], e["angular_quadratic"] = draw(_u(0.0, 0.05)), draw(_u(0.0, 0.05))
        effects.append(e)
    for kind in draw(st.lists(st.sampled_from(["force", "torque"]), max_size=2)):
        pool = solid if kind == "torque" else names
        if not pool:
            continue
        i = draw(st.sampled_from(pool))
        start = draw(_u(0.0, 0.5 * duration))
        e = {
            "type": kind,
            "body": i,
            kind: draw(_vec(-2, 2)),
            "start": start,
            "end": start + draw(_u(0.1, duration)),
            "frame": draw(st.sampled_from(["space", "body"])),
        }
        if kind == "force" and i in solid and draw(st.booleans()):
            e["at"] = draw(_vec(-0.3, 0.3))
        effects.append(e)
    free = pinned is None and not hinged  # (their centres follow from the joints)
    if len(names) > 1 and free and _apart(bodies) and draw(st.booleans()):
        effects.append({"type": "newton_gravity", "G": draw(_u(0.01, 0.5))})
    return scene_data(
        bodies, effects, name="compiled", duration=duration, samples=samples, method="integrate"
    )


def _apart(bodies) -> bool:
    """Are the centres at least 0.5 m apart (Newtonian gravity is singular at 0)?"""
    r = np.array([b["initial"]["position"] for b in bodies])
    d = np.linalg.norm(r[:, None] - r[None], axis=-1) + np.eye(len(r))
    return bool(d.min() >= 0.5)


def _engine(data: dict) -> Engine:
    from mechanics.scenes import parse_scene

    return Engine(parse_scene(data, source="compiled.toml"))


def _term_scale(fwd, t: float, y: np.ndarray, phase: float) -> float:
    """The largest term the rates sum: speeds, each effect's force per unit mass and
    moment (a pinned body's moment of its force about the pivot included; a hinged
    body's generalised force over its moment, (h |F| + |M|)/J_a), the products L ω and
    ω R of Euler's equations and the attitude's rate."""
    s = fwd.snapshot(t, y)
    s.phase = phase
    md = fwd.model
    terms = [float(np.abs(s.v).max(initial=0.0))]
    arm = max((float(np.abs(g).sum()) for _, g, _, _ in md.layout.pins.values()), default=0.0)
    for e in md.forces:
        out = Loads(md.n, s)
        e.loads(t, s, out)
        for b in range(md.n):
            F = float(np.abs(out.F[b]).sum())
            M = float(np.abs(out.M_A[b]).sum())
            terms += [F / md.m0[b], M + arm * F]
            hinge = md.layout.guides.get(b)
            if hinge is not None:
                terms.append((hinge.h * F + M) / hinge.J_a)
    for b in range(md.n):
        L, w = float(np.abs(s.L_A[b]).sum()), float(np.abs(s.omega[b]).sum())
        JC = md.layout.pins[b][2] if b in md.layout.pins else None
        if JC is not None:
            L = float(np.abs(JC).sum() * w)
        terms += [L * w, 3.0 * w]
    return max(terms)


@settings(max_examples=1000 if MANY else 60, deadline=None)
@given(data=compiled_scenes(), draw=st.data())
def test_the_kernel_gives_the_reference_rates_at_random_states(data, draw) -> None:
    eng = _engine(data)
    fwd = eng.forward
    assert not isinstance(sc_compiled.build(eng.model), str), sc_compiled.build(eng.model)
    n = eng.y0.size
    y = eng.y0 + np.array(draw.draw(st.lists(_u(-0.5, 0.5), min_size=n, max_size=n)))
    t = draw.draw(_u(0.0, 1.0))
    phase = draw.draw(_u(0.0, 1.0))
    fwd.phase = phase
    got, want = fwd.rhs(t, y), fwd.reference_rhs(t, y)
    tol = RATES_RTOL * _term_scale(fwd, t, y, phase)
    np.testing.assert_allclose(got, want, rtol=0, atol=tol)


@settings(max_examples=500 if MANY else 40, deadline=None)
@given(data=compiled_scenes(pin=True), draw=st.data())
def test_a_pinned_body_s_acceleration_and_loads_are_the_reference_s(data, draw) -> None:
    """The reactions' inputs at samples (each its own time): a_G and Σ F of every
    pinned body from the kernel, against Forward.point_accelerations and the loads."""
    eng = _engine(data)
    fwd, md = eng.forward, eng.model
    k = 3
    n = eng.y0.size
    dY = draw.draw(st.lists(_u(-0.3, 0.3), min_size=k * n, max_size=k * n))
    Y = eng.y0 + np.reshape(dY, (k, n))
    T = np.array(draw.draw(st.lists(_u(0.0, 1.0), min_size=k, max_size=k)))
    fast = sc_compiled.build(md)
    assert not isinstance(fast, str)
    got = fast.accelerations(T, Y)
    assert got is not None
    A, F = got
    for j in range(k):
        s = fwd.snapshot(float(T[j]), Y[j])
        loads = Loads(md.n, s)
        for e in md.forces:
            e.loads(float(T[j]), s, loads)
        with sc_compiled.reference_path():
            ref = _engine(data).forward
        acc = ref.point_accelerations(float(T[j]), Y[j], s, {i: s.r[i] for i in md.layout.pins})
        tol = RATES_RTOL * _term_scale(ref, float(T[j]), Y[j], float(T[j]))
        arm = 1.0 + float(np.abs(s.r).max())  # α × ρ, ω × (ω × ρ): the arm multiplies
        for i, a in acc.items():
            np.testing.assert_allclose(A[j, i], a, rtol=0, atol=tol * arm * arm)
        np.testing.assert_allclose(F[j], loads.F, rtol=0, atol=tol * float(md.m0.max()))


@settings(max_examples=300 if MANY else 15, deadline=None)
@given(data=compiled_scenes(duration=0.5, samples=6))
def test_a_compiled_run_is_the_reference_run(data) -> None:
    a = run_scene(_engine(data).scene)
    with sc_compiled.reference_path():
        b = run_scene(_engine(data).scene)
    assert a.trajectory.method.endswith(
        "right-hand side compiled (numba: mechanics.scenes._kernels)"
    )
    assert "right-hand side in Python (the reference path was asked for" in b.trajectory.method
    assert a.passed, a.summary()
    assert b.passed, b.summary()
    assert a.trajectory.series.keys() == b.trajectory.series.keys()
    sa, sb = a.trajectory.snapshot, b.trajectory.snapshot
    parts = ("r", "v", "L_A", "R")
    size = max(float(np.abs(getattr(sb, p)).max()) for p in parts)
    sc = a.scene
    tol = RUN_STEPS * (sc.rtol * size + sc.atol)
    for p in parts:
        np.testing.assert_allclose(getattr(sa, p), getattr(sb, p), rtol=0, atol=tol, err_msg=p)


# ---------------------------------------------------------------- the Python path


def _tank():
    from mechanics.scenes import load_scene

    return load_scene(BUILTIN / "tank_draining.toml")


def _rolling():
    from mechanics.scenes import load_scene

    return load_scene(BUILTIN / "rolling_incline.toml")


@pytest.mark.parametrize(
    ("make", "says"),
    [
        (_tank, "body 'tank' is tank"),
        (_rolling, "body 'cylinder' rolls or slides"),
        (
            lambda: scene(
                [point("rocket", mass=2.0)],
                [
                    {
                        "type": "thrust",
                        "body": "rocket",
                        "mass_flow": 0.1,
                        "exhaust_speed": 10.0,
                        "fuel_mass": 1.0,
                        "direction": [0, 0, 1],
                    }
                ],
                duration=1.0,
            ),
            "the effect 'thrust' (effects[0]) has no compiled loads",
        ),
    ],
    ids=["tank", "rolling", "thrust"],
)
def test_a_model_that_does_not_compile_says_why_and_runs_the_python_path(make, says) -> None:
    sc = make()
    why = sc_compiled.build(Engine(sc).model)
    assert isinstance(why, str)
    assert says in why
    eng = Engine(sc)
    y = eng.y0
    assert np.array_equal(eng.forward.rhs(0.1, y), eng.forward.reference_rhs(0.1, y))
    assert eng.forward.path() == f"right-hand side in Python ({why})"


def test_without_numba_the_python_path_runs_silently_and_says_which_extra(monkeypatch) -> None:
    monkeypatch.setattr(sc_compiled, "_KERNELS", False)  # as after numba's import failed
    sc = scene(
        [point("p", [0, 0, 0], [1, 0, 0])],
        [{"type": "gravity", "g": 9.81}],
        method="integrate",
        duration=0.5,
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = run_scene(sc)
    assert r.passed
    assert r.trajectory.method.endswith(
        "right-hand side in Python (numba is not installed: pip install 'bodycheck[fast]')"
    )
    assert sc_compiled.warm() is False


@pytest.mark.parametrize("kernel", ["scene_rhs", "scene_step"])
def test_a_kernel_that_fails_to_compile_warns_once_and_the_run_is_the_reference_s(
    monkeypatch, kernel
) -> None:
    """(A point under gravity: its compiled rates are the reference's to the bit.)"""
    k = sc_compiled._kernels()
    assert k is not None

    def broken(*args):
        raise TypeError("a typing error numba might raise")

    sc = scene(
        [point("p", [0, 0, 0], [1, 0, 2])],
        [{"type": "gravity", "g": 9.81}],
        method="integrate",
        duration=0.3,
    )
    with sc_compiled.reference_path():
        want = run_scene(sc)
    monkeypatch.setattr(k, kernel, broken)
    monkeypatch.setattr(sc_compiled, "_KERNELS", k)
    with pytest.warns(CompiledPathWarning, match="a typing error numba might raise") as seen:
        got = run_scene(sc)
    assert len(seen) == 1
    assert sc_compiled._kernels() is None  # given up for the process (restored after)
    assert got.passed
    for name, v in want.trajectory.series.items():
        assert np.array_equal(got.trajectory.series[name], v), name


def test_a_run_whose_rates_blow_up_fails_as_the_reference_run_does() -> None:
    """Two unit points 1 m apart falling into each other under Newtonian gravity (G = 1):
    the radial Kepler fall r̈ = −2/r² from rest meets at t = (π/2) √(r³/(2 G M)) = π/4,
    where the rates grow without bound and both paths stall, with the same error, there."""
    bodies = [point("a", [-0.5, 0, 0]), point("b", [0.5, 0, 0])]
    sc = scene(bodies, [{"type": "newton_gravity", "G": 1.0}], method="integrate", duration=2.0)
    with pytest.raises(SceneError) as compiled_run:
        run_scene(sc)
    with sc_compiled.reference_path(), pytest.raises(SceneError) as reference_run:
        run_scene(sc)
    errors = [compiled_run.value, reference_run.value]
    heads = [str(e).split(" at t = ")[0] for e in errors]
    assert heads[0] == heads[1] == "scene.toml: scene.rtol: the integration stalled"
    for e in errors:
        t = float(str(e).split(" at t = ")[1].split(" s ")[0])
        assert t == pytest.approx(math.pi / 4, rel=STALL_RTOL)


def test_warm_loads_the_kernels() -> None:
    assert sc_compiled.warm() is True
