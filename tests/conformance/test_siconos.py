"""The Siconos adapter (issue 27, item 5, under issue 29's design): its conventions
proven against exact motions, Newton's law at its impacts, the flat box, what it does
not map, and the missing package.

Siconos runs in a worker under Debian's ``python3`` (``apt-get install python3-siconos``;
``.ci/run`` installs it); where it cannot be imported every test here skips and says
which package to install.

Bounds, derived:

- Between impacts Moreau–Jean with θ = 1/2 advances the velocity by h F/m and the
  position by h times the mean of the two velocities: exact for a constant force, so a
  parabola is exact up to the rounding of its n steps (n × 2^4 eps of its size).
- On a free top the scheme converges at order 2 (θ = 1/2) or 1 (θ = 1): runs at h, h/2,
  h/4 have differences d₁, d₂ with d₁/d₂ ≈ 2^p, and the error at h/4 is d₂/(2^p − 1)
  asymptotically; allowed twice that.
- An impact is resolved at the step it falls in: the body is at most one step's travel
  v h from the surface and its speed differs by at most g h from that at contact, so a
  rebound's velocity later errs by at most (1 + e) g h, and an apex height by v h for
  the position plus v g h / g for the speed, each bounce adding its own: allowed twice.
- With no force during the impact (two spheres in free space) Newton's law gives the
  velocities after exactly: they differ from the closed form by the friction solver's
  tolerance (SOLVER_TOLERANCE, relative) of the speeds.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.conformance.adapters import MissingExtraError
from mechanics.conformance.adapters import siconos as siconos_module
from mechanics.conformance.protocol import Body, Ground, Pivot, Scenario, Shape, check_trajectory
from mechanics.conformance.scenarios import SCENARIOS, measure, reference
from mechanics.errors import OutOfDomainError

G = 9.81
#: the initial state written as a quaternion and read back (a conversion each way, and
#: JSON's exact round trip of a float's repr): a few eps of the size
READBACK_RTOL = 2**6 * EPS
#: the velocities after an impact in free space: the solver's residual, relative
SOLVER_RTOL = 4 * siconos_module.SOLVER_TOLERANCE
#: the halving margin on the free top (module docstring)
HALVING_MARGIN = 2.0


def _adapter(theta=0.5):
    try:
        return siconos_module.SiconosAdapter(theta)
    except MissingExtraError as exc:
        pytest.skip(f"Siconos is not available: {exc}")


# ------------------------------------------------------------------ conventions


def test_the_initial_state_reads_back_as_written() -> None:
    """A tilted, spinning body at t = 0: attitude (passive R_A_O from Siconos's active
    scalar-first quaternion) and ω in body components, as the scenario gives them."""
    sc = SCENARIOS["free_top_axis1"]
    tr = check_trajectory(sc, _adapter().run(sc, max(sc.steps)))
    b = sc.bodies[0]
    np.testing.assert_allclose(tr.R_A_O[0, 0], b.R_A_O, rtol=0, atol=READBACK_RTOL)
    w = np.asarray(b.omega)
    np.testing.assert_allclose(tr.omega[0, 0], w, rtol=0, atol=READBACK_RTOL * np.abs(w).max())


def test_a_parabola_is_exact_between_impacts() -> None:
    sc = SCENARIOS["parabola"]
    ref = reference(sc).trajectory
    for h in sc.steps:
        tr = check_trajectory(sc, _adapter().run(sc, h))
        n = round(sc.duration / h)
        size = float(np.abs(ref.position).max() + np.abs(ref.velocity).max())
        np.testing.assert_allclose(tr.position, ref.position, rtol=0, atol=n * 2**4 * EPS * size)
        np.testing.assert_allclose(tr.velocity, ref.velocity, rtol=0, atol=n * 2**4 * EPS * size)


@pytest.mark.parametrize(("theta", "order"), [(0.5, 2), (1.0, 1)])
def test_a_free_top_converges_at_the_scheme_s_order(theta, order) -> None:
    """Euler's equations (4.47) with the gyroscopic term in body components: the
    attitude and ω converge to the elliptic-function solution at order 2 (θ = 1/2,
    measured ratio 4.0) or 1 (θ = 1, 2.0); a transposed attitude or ω in the wrong
    components would not converge at all."""
    sc = SCENARIOS["free_top_axis1"]
    ref = reference(sc).trajectory
    runs = [_adapter(theta).run(sc, h) for h in sorted(sc.steps, reverse=True)]
    for field in ("R_A_O", "omega"):
        a, b, c = (getattr(r, field) for r in runs)
        d1, d2 = np.abs(a - b).max(), np.abs(b - c).max()
        assert d1 / d2 > 2**order * 0.9, (field, d1 / d2)
        err = np.abs(c - getattr(ref, field)).max()
        assert err <= HALVING_MARGIN * d2 / (2**order - 1), (field, err, d2)


# ------------------------------------------------------------------ impacts


def test_two_spheres_leave_with_newton_s_velocities() -> None:
    sc = SCENARIOS["two_body_impact"]
    ref = reference(sc).trajectory
    for h in sc.steps:
        tr = _adapter().run(sc, h)
        speed = float(np.abs(ref.velocity).max())
        np.testing.assert_allclose(
            tr.velocity[-1], ref.velocity[-1], rtol=0, atol=SOLVER_RTOL * speed
        )


def test_a_bouncing_ball_rebounds_within_one_step_s_error() -> None:
    sc = SCENARIOS["bouncing_ball"]
    ref = reference(sc)
    e = sc.ground.restitution
    h0 = ref.figures["apex_heights"][0] / e**2  # the drop height of G above its rest
    v = math.sqrt(2 * G * h0)  # the first (fastest) impact's speed
    for h in sc.steps:
        got = measure(sc, _adapter().run(sc, h))["apex_heights"]
        for k, (z, want) in enumerate(zip(got, ref.figures["apex_heights"], strict=False)):
            bound = 2 * (k + 1) * 2 * v * h  # v h of position and v g h / g of speed
            assert abs(z - want) <= bound, (h, k, z, want, bound)


def _flat_box(e=0.5, z=1.0):
    a, b, c = 0.1, 0.2, 0.3  # half extents: the 0.2 × 0.4 × 0.6 m box, 1 kg
    J = ((4 * b * b + 4 * c * c) / 12, (4 * a * a + 4 * c * c) / 12, (4 * a * a + 4 * b * b) / 12)
    body = Body("box", 1.0, J, Shape("box", (a, b, c)), position=(0.0, 0.0, z))
    return Scenario(
        "flat_box",
        "a box landing flat on its 0.2 x 0.4 face",
        "(6.6), four simultaneous contacts",
        (body,),
        duration=0.5,
        sample_times=tuple(k / 64 for k in range(33)),
        gravity=(0.0, 0.0, -G),
        ground=Ground(e),
        steps=(2**-10, 2**-12),
    )


def test_the_flat_box_lands_flat_and_rebounds_at_e_v() -> None:
    """Four corners at once: by symmetry no spin and no sideways motion (to the solver's
    tolerance of the speed), and v_z after = e √(2 g 0.7) − g (t − t₁) within one
    step's error; the same box as issue 27's first case."""
    e = 0.5
    sc = _flat_box(e)
    t1 = math.sqrt(2 * 0.7 / G)
    for h in sc.steps:
        tr = check_trajectory(sc, _adapter().run(sc, h))
        v_in = math.sqrt(2 * G * 0.7)
        after = np.asarray(sc.sample_times) > t1 + 2 * h
        want = e * v_in - G * (np.asarray(sc.sample_times)[after] - t1)
        bound = 2 * (1 + e) * G * h
        np.testing.assert_allclose(tr.velocity[after, 0, 2], want, rtol=0, atol=bound)
        sym = SOLVER_RTOL * v_in
        arm = min(sc.bodies[0].shape.dims)  # |ω| × the shortest arm is a speed
        np.testing.assert_allclose(tr.omega, 0.0, rtol=0, atol=sym / arm)
        np.testing.assert_allclose(tr.velocity[:, 0, :2], 0.0, rtol=0, atol=sym)
        np.testing.assert_allclose(tr.position[:, 0, :2], 0.0, rtol=0, atol=sym)


# ------------------------------------------------------------------ refusals


def test_what_the_adapter_does_not_map_is_said() -> None:
    a = _adapter()
    assert "pivot" in a.supports(SCENARIOS["heavy_top"])
    assert "mass changes" in a.supports(SCENARIOS["rocket"])
    box = _flat_box()
    cyl = dataclasses.replace(box.bodies[0], shape=Shape("cylinder", (0.1, 0.3)))
    assert "cylinder" in a.supports(dataclasses.replace(box, bodies=(cyl,)))
    two = dataclasses.replace(
        box,
        bodies=(box.bodies[0], dataclasses.replace(box.bodies[0], position=(1.0, 0.0, 1.0))),
        ground=None,
        pair_restitution=((0, 1, 1.0),),
    )
    assert "two spheres only" in a.supports(two)
    with pytest.raises(Exception, match="Siconos cannot run it: a pivot"):
        a.run(SCENARIOS["heavy_top"], None)
    pivot = dataclasses.replace(SCENARIOS["parabola"], pivot=Pivot(0, (0.0, 0.0, 0.1)))
    assert "pivot" in a.supports(pivot)


def test_theta_outside_its_range_is_refused_naming_it() -> None:
    for bad in (0.25, 1.5, math.nan):
        with pytest.raises(Exception, match="theta"):
            siconos_module.SiconosAdapter(bad)
    with pytest.raises(OutOfDomainError, match=r"\[0.5, 1\].*0.25"):
        siconos_module.SiconosAdapter(0.25)


def test_a_missing_siconos_names_the_debian_package(monkeypatch) -> None:
    monkeypatch.setenv(siconos_module.PYTHON_VARIABLE, "/nonexistent/python3")
    with pytest.raises(MissingExtraError, match="apt-get install python3-siconos"):
        siconos_module.SiconosAdapter()
