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


def _ecc_period() -> float:
    """The period of :func:`_ecc_orbit`'s relative orbit, 2π √(a³/μ)."""
    mu, v = 2.0, 0.8 * math.sqrt(2.0)  # G (m1 + m2); the relative speed at d = 1
    a = 1.0 / (2.0 - v * v / mu)  # vis-viva
    return 2 * math.pi * math.sqrt(a**3 / mu)


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


#: the energy error over ORBITS orbits against that over the first.  A splitting's error
#: oscillates, the same swing in every orbit (measured: 1 + 6e-10 over 5 orbits); a drift
#: of d per orbit (in units of the first orbit's swing) gives (1 + 5 d)/(1 + d), above this
#: bound from d = 1/79 (the bound of 1.5 on 10 orbits against 2 let through d < 1/14)
BOUNDED_GROWTH = 1.05
#: five orbits against the first: a secular drift gives 5, as 10 against 2 did
ORBITS = 5


def _energy_growth(r) -> float:
    """The energy's swing (max − min) over the whole run over that over its first orbit
    (its first 21 samples)."""
    E = r.trajectory.series["E"]
    return float(np.ptp(E)) / float(np.ptp(E[:21]))


def test_the_splitting_keeps_the_energy_error_bounded_and_the_momentum() -> None:
    """An eccentric two-body orbit: the energy error of the splitting over 5 orbits is
    that over the first (it oscillates within each orbit, peaking at periapsis, and does
    not drift: ratio < BOUNDED_GROWTH, where a secular drift would give 5); the momentum
    is kept to rounding (the kicks are equal and opposite), over every whole number of
    orbits.

    One run: the first orbit is its first 21 samples.  Launched at apoapsis, the orbit
    passes its periapsis, where the error peaks, at T/2 (the 11th sample) and is back
    at apoapsis at T, so one orbit holds the whole swing.  (Two runs of 2 and 10 orbits
    took 2.4 times the steps, each run repeated at half the step by the engine's own
    order check, for a bound of 1.5 that a drift 5.6 times larger per orbit passed.)"""
    T = _ecc_period()
    r = run_scene(_ecc_orbit(ORBITS * T, samples=20 * ORBITS + 1, method="splitting", step=T / 200))
    assert r.passed, r.summary()
    conserved = {c.name: c for c in r.conserved}
    assert conserved["p_x"].drift <= 64 * EPS * 20 * ORBITS
    px = r.trajectory.series["p_x"]
    size = max(r.trajectory.scales.get("p_x", 0.0), float(np.max(np.abs(px))), 1e-300)
    for k in range(1, ORBITS + 1):  # each prefix of k orbits within its own bound
        assert np.ptp(px[: 20 * k + 1]) <= 64 * EPS * 20 * k * size, k
    assert _energy_growth(r) < BOUNDED_GROWTH


def test_an_adaptive_runge_kutta_run_of_the_orbit_fails_the_bounded_energy_check() -> None:
    """Negative control of the bound above: the same orbit by DOP853 (``integrate``) at
    rtol = atol = 1e-6, whose energy error grows from orbit to orbit, is over
    BOUNDED_GROWTH (measured 8.3; between 1.3 and 8.3 at each rtol from 2e-7 to 3e-6)."""
    T = _ecc_period()
    r = run_scene(
        _ecc_orbit(ORBITS * T, samples=20 * ORBITS + 1, method="integrate", rtol=1e-6, atol=1e-6)
    )
    assert r.method.startswith("integrated: DOP853")
    assert _energy_growth(r) > BOUNDED_GROWTH


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
