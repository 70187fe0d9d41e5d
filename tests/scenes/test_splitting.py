"""The splitting of conservative scenes (``method = "splitting"``): its order against an
independent reference, its bounded energy error, a wrong kick caught by its own check,
and what it refuses."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes import SceneError, run_scene
from mechanics.scenes.engine import Engine

from .builders import box, point, scene

_scene = functools.partial(scene, name="split", samples=41)


BOX = box("b", a=0.3, b=0.2, c=0.1, omega=[0.5, 2.0, 0.3])
#: an off-centre spring: a force and a moment on a spinning asymmetric body
SPRING = [
    {"type": "spring", "body": "b", "at": [0.15, 0, 0], "anchor": [0.5, 0, 0], "stiffness": 3.0}
]


def _ecc_orbit(duration, **scene):
    """Two unit masses, G = 1, launched at 0.8 of the circular speed: an eccentric orbit."""
    w = 0.8 * math.sqrt(2.0) / 2
    pts = [point("a", [0.5, 0, 0], [0, w, 0]), point("c", [-0.5, 0, 0], [0, -w, 0])]
    return _scene(pts, [{"type": "newton_gravity", "G": 1.0}], duration=duration, **scene)


def test_the_splitting_converges_at_its_order_to_an_independent_reference() -> None:
    """A spinning box on an off-centre spring: the end state at steps h and h/2 against
    the project's DOP853 at rtol 1e-13 (an independent method); the error falls by
    2⁴ = 16 for order 4 (between 12 and 20: the asymptotic regime), by 4 for order 2."""
    ref = run_scene(_scene([BOX], SPRING, duration=2.0, method="integrate", rtol=1e-13, atol=1e-13))
    keys = ("x", "y", "z", "omega1", "omega2", "omega3")
    want = np.array([ref.trajectory.series[k][-1] for k in keys])
    for order, (lo, hi) in ((4, (12.0, 20.0)), (2, (3.0, 5.0))):
        errs = []
        for h in (0.025, 0.0125):  # dividing the sample interval 0.05
            r = run_scene(
                _scene([BOX], SPRING, duration=2.0, method="splitting", step=h, order=order)
            )
            assert r.passed, r.summary()
            assert r.method.startswith(f"integrated: splitting of order {order}")
            got = np.array([r.trajectory.series[k][-1] for k in keys])
            errs.append(float(np.abs(got - want).max()))
        assert lo <= errs[0] / errs[1] <= hi, (order, errs)


def test_the_splitting_keeps_the_energy_error_bounded_and_the_momentum() -> None:
    """An eccentric two-body orbit: the energy error of the splitting over 10 orbits is
    that over 2 (it oscillates within each orbit, peaking at periapsis, and does not
    drift: ratio < 1.5, where a secular drift would give 5); the momentum is kept to
    rounding (the kicks are equal and opposite)."""
    mu, v = 2.0, 0.8 * math.sqrt(2.0)  # G (m1 + m2); the relative speed at d = 1
    a = 1.0 / (2.0 - v * v / mu)  # vis-viva
    T = 2 * math.pi * math.sqrt(a**3 / mu)
    drifts = []
    for n in (2, 10):
        r = run_scene(_ecc_orbit(n * T, samples=20 * n + 1, method="splitting", step=T / 200))
        assert r.passed, r.summary()
        conserved = {c.name: c for c in r.conserved}
        drifts.append(conserved["E"].drift)
        assert conserved["p_x"].drift <= 64 * EPS * 20 * n
    assert drifts[1] < 1.5 * drifts[0], drifts


def test_a_wrong_kick_fails_the_energy_check(monkeypatch) -> None:
    """Negative control: forces 1 % too strong keep a (wrong) energy, not this one, and
    its error does not shrink with the step: the run says FAILED."""
    real = Engine.loads

    def strong(self, t, s):
        F, M = real(self, t, s)
        return 1.01 * F, 1.01 * M

    monkeypatch.setattr(Engine, "loads", strong)
    r = run_scene(_scene([BOX], SPRING, duration=1.0, method="splitting", step=0.02))
    assert not r.passed
    assert [c.name for c in r.self_checks if not c.ok] == ["energy error at order 4"]


@pytest.mark.parametrize(
    ("effects", "scene", "where", "match"),
    [
        (
            [{"type": "impact", "body": "b", "restitution": 0.5, "plane_point": [0, 0, -1]}],
            {},
            "scene.method",
            "cannot locate impacts",
        ),
        (
            [{"type": "drag", "body": "b", "linear": 0.1}],
            {},
            "scene.method",
            "'drag' effect is not conservative",
        ),
        (
            [{"type": "fixed_point", "body": "b", "distance": 0.1}],
            {},
            "scene.method",
            "free rigid bodies only",
        ),
        ([], {"order": 3}, "scene.order", "expected one of"),
        ([], {"step": 0.0}, "scene.step", "> 0"),
    ],
)
def test_the_splitting_refuses_what_it_cannot_run(effects, scene, where, match) -> None:
    with pytest.raises(SceneError, match=match) as info:
        run_scene(_scene([BOX], effects, duration=1.0, method="splitting", **scene))
    assert info.value.field == where


def test_step_and_order_belong_to_the_splitting() -> None:
    with pytest.raises(SceneError, match="only with method 'splitting'") as info:
        _scene([BOX], SPRING, duration=1.0, step=0.01)
    assert info.value.field == "scene.step"
