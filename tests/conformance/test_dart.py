"""The DART adapter (the battery's fifth engine): the protocol, the conventions proven
against exact motions, restitution and friction as DART combines them, the scenarios it
cannot express, and the missing extra.

The DART tests skip with the extra to install when dartpy is absent; the tests of the
module's own pieces (the coefficient assignment, the missing extra) run without it.

Tolerances of the smooth motions come from step halving, as in ``test_engines.py``: with
runs at h, h/2, h/4 of a method of order p, the error at h/4 is d₂/(2^p − 1)
asymptotically, d₂ the largest difference of the h/2 and h/4 runs; the test allows
twice that plus the exact solution's own rounding, and checks the order from the ratio
d₁/d₂ of successive differences.
"""

from __future__ import annotations

import dataclasses
import math
import sys

import numpy as np
import pytest

from bench.engines import ball_drop, heavy_top, rebound, theta_of
from mechanics._floats import EPS
from mechanics.conformance import reference, run_battery
from mechanics.conformance.adapters import dart as dart_module
from mechanics.conformance.adapters._engines import MissingExtraError
from mechanics.conformance.adapters.dart import contact_coefficients
from mechanics.conformance.protocol import Ground, check_trajectory
from mechanics.conformance.scenarios import get_scenario
from mechanics.errors import MechanicsValueError, UnknownOptionError

from .test_engines import _two_bodies_and_ground

#: the exact solutions' own error: a few hundred roundings of O(1) terms
EXACT_ATOL = 2**10 * EPS
#: a few hundred fixed steps, each adding one rounding of numbers of size ~10 (the
#: parabola's speed): measured 212 eps at 384 steps; 2^10 eps relative to the size
STEPPED_ROUNDING_RTOL = 2**10 * EPS
#: the halving margin: the error at h/4 is d₂/(2^p − 1) plus higher-order terms
HALVING_MARGIN = 2.0
#: DART's order (semi-implicit Euler): the ratio of successive differences is 2^p
DART_ORDER = 1
#: a product of per-body coefficients meets the pair's e: a square root and a product
PRODUCT_ATOL = 4 * EPS
G = 9.81
SOLVERS = ("dantzig", "pgs")


def _dart():
    return pytest.importorskip(
        "dartpy", reason="DART is not installed: pip install 'bodycheck[dart]'"
    )


def _adapter(solver: str = "dantzig"):
    _dart()
    from mechanics.conformance.adapters.dart import DartAdapter

    return DartAdapter(solver)


# ------------------------------------------------------------------ the protocol


def test_variants_are_the_two_boxed_lcp_solvers():
    _dart()
    got = dart_module.variants()
    assert [a.solver for a in got] == list(SOLVERS)
    assert [repr(a) for a in got] == ["DartAdapter('dantzig')", "DartAdapter('pgs')"]
    assert "Dantzig" in got[0].name
    assert "PGS" in got[1].name


@pytest.mark.parametrize("solver", SOLVERS)
def test_the_pgs_variant_solves_with_pgs_alone_and_the_default_with_dantzig(solver):
    a = _adapter(solver)
    world, _, _ = a.build(get_scenario("bouncing_ball"), 2.0**-8)
    cs = world.getConstraintSolver()
    want = "DantzigBoxedLcpSolver" if solver == "dantzig" else "PgsBoxedLcpSolver"
    assert cs.getBoxedLcpSolver().getType() == want
    if solver == "pgs":
        assert cs.getSecondaryBoxedLcpSolver() is None
    assert world.getDeactivationOptions().mEnabled is False


# ------------------------------------------------------------------ conventions, exactly


def test_free_asymmetric_top_agrees_with_the_exact_motion_with_an_error_shrinking_with_the_step():
    """A transposed attitude or ω in the wrong components would be off by O(1) at t = 0
    already (the scenario starts tilted); the error here is DART's step error alone."""
    a = _adapter()
    s = get_scenario("free_top_axis1")
    ex = reference(s).trajectory
    want = np.concatenate([ex.R_A_O[:, 0].reshape(-1, 9), ex.omega[:, 0]], -1)

    def run(h):
        tr = check_trajectory(s, a.run(s, h))
        # the centre moves uniformly: DART gets that to rounding
        assert np.abs(tr.position - ex.position).max() <= EXACT_ATOL, h
        return np.concatenate([tr.R_A_O[:, 0].reshape(-1, 9), tr.omega[:, 0]], -1)

    coarse, mid, fine = (run(h) for h in s.steps)
    errors = [np.abs(x - want).max() for x in (coarse, mid, fine)]
    assert errors[0] > errors[1] > errors[2], errors
    d1, d2 = np.abs(coarse - mid).max(), np.abs(mid - fine).max()
    assert 2 ** (DART_ORDER - 0.5) <= d1 / d2 <= 2 ** (DART_ORDER + 0.5), d1 / d2
    bound = HALVING_MARGIN * d2 / (2**DART_ORDER - 1) + EXACT_ATOL
    assert errors[2] <= bound, f"error {errors[2]:.3g} > step-halving bound {bound:.3g}"


def test_parabola_lags_by_semi_implicit_eulers_g_h_t_over_2_and_is_exact_otherwise():
    """DART steps the velocity first (v += h g), then the position with the new
    velocity: x_n = x₀ + v₀ t + g t²/2 + g h t/2 exactly, v_n exact; the spin of a
    ball (equal moments) is exact under the exponential map."""
    a = _adapter()
    s = get_scenario("parabola")
    ex = reference(s).trajectory
    t = np.asarray(s.sample_times)[:, None, None]
    g = np.asarray(s.gravity)
    for h in s.steps:
        tr = check_trajectory(s, a.run(s, h))
        size = max(np.abs(ex.position).max(), np.abs(ex.velocity).max())
        tol = STEPPED_ROUNDING_RTOL * size
        assert np.abs(tr.position - ex.position - 0.5 * h * t * g).max() <= tol, h
        assert np.abs(tr.velocity - ex.velocity).max() <= tol, h
        assert np.abs(tr.R_A_O - ex.R_A_O).max() <= STEPPED_ROUNDING_RTOL, h
        assert np.abs(tr.omega - ex.omega).max() <= tol, h


def test_pivoted_heavy_top_nutates_like_the_elliptic_solution():
    a = _adapter()
    s, exact = heavy_top(duration=1.0, samples=101)
    t = np.asarray(s.sample_times)
    coarse, mid, fine = (theta_of(check_trajectory(s, a.run(s, h))) for h in s.steps)
    d1, d2 = np.abs(coarse - mid).max(), np.abs(mid - fine).max()
    assert 2 ** (DART_ORDER - 0.5) <= d1 / d2 <= 2 ** (DART_ORDER + 0.5), d1 / d2
    err = np.abs(fine - exact.theta(t)).max()
    assert err <= HALVING_MARGIN * d2 / (2**DART_ORDER - 1) + EXACT_ATOL, (err, d2)


def test_dart_holds_the_scenario_mass_and_inertia_not_its_shapes():
    """The box of free_top_axis1 would have far smaller moments from its shape; DART
    must hold the scenario's, with G at the body origin."""
    a = _adapter()
    s = _two_bodies_and_ground()
    _, nodes, _ = a.build(s, 2.0**-8)
    for node, b in zip(nodes, s.bodies, strict=True):
        assert node.getMass() == b.mass
        np.testing.assert_array_equal(node.getInertia().getMoment(), np.diag(b.inertia))
        np.testing.assert_array_equal(node.getLocalCOM(), np.zeros(3))


# ------------------------------------------------------------------ the battery


#: the scenarios DART passes at the first-order profile (measured; docs/conformance-engines.md)
FIRST_ORDER_PASSES = (
    "free_top_axis1",
    "free_top_axis3",
    "free_top_near_separatrix",
    "heavy_top",
    "parabola",
    "two_body_impact",
    "bouncing_ball",
    "box_landing_flat",
    "sliding_stop",
    "incline_rolling",
    "bounce_to_rest",
    "oblique_impact_sticks",
    "oblique_impact_slips",
)


@pytest.mark.parametrize("solver", SOLVERS)
def test_dart_passes_the_battery_at_the_first_order_profile_but_the_cradle(solver):
    a = _adapter(solver)
    report = run_battery(
        a, scenarios=[*FIRST_ORDER_PASSES, "newtons_cradle", "rocket"], profile="first-order"
    )
    for name in FIRST_ORDER_PASSES:
        assert report[name].status == "pass", (name, report[name].message)
    assert report["rocket"].status == "unsupported"
    # DART solves the three balls' contacts at once: the momentum is shared, not passed
    # down the row, (-1/3, 2/3, 2/3) (energy and momentum kept: only velocities tell)
    assert report["newtons_cradle"].status == "fail"


def test_newtons_cradle_is_solved_simultaneously():
    a = _adapter()
    s = get_scenario("newtons_cradle")
    tr = check_trajectory(s, a.run(s, min(s.steps)))
    # the ERP push-out and the step blur the thirds: measured 1.1e-4 m/s off at 2^-8 s
    np.testing.assert_allclose(tr.velocity[-1, :, 0], [-1 / 3, 2 / 3, 2 / 3], atol=2.0**-10)


# ------------------------------------------------------------------ restitution, friction


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("h", [1e-3, 1e-4])
@pytest.mark.parametrize("e", [0.8, 0.4])
def test_dart_rebounds_with_the_product_of_the_restitution_coefficients(solver, h, e):
    a = _adapter(solver)
    s = ball_drop(e, fine=h)
    ratio, depth = rebound(s, check_trajectory(s, a.run(s, h)))
    # Newton's law at the impact step: the speed then is v + g δt (δt < h), and the ball
    # climbs out of at most one step's travel: each ~ g h/v relative
    v = math.sqrt(2 * G * 1.0)
    assert ratio == pytest.approx(e, rel=4 * G * h / v)
    assert depth <= v * h  # at most one step's travel deep


def test_sliding_box_stops_where_coulomb_friction_stops_it():
    a = _adapter()
    s = get_scenario("sliding_stop")
    figures = reference(s).figures
    report = run_battery(a, scenarios=["sliding_stop"], profile="first-order")
    r = report["sliding_stop"]
    assert r.status == "pass", r.message
    got = {f.name: f.value for f in r.figures}
    # a first-order engine at 2^-8 s: the stop distance within 1 % (measured 0.95 %)
    assert got["stop_distance"] <= 2.0**-6, (got, figures)


def test_contact_coefficients_give_each_contact_its_e_and_mu():
    # the ground's e on the body, 1 on the ground: the product is the ground's e
    r, mu, why = contact_coefficients(get_scenario("bouncing_ball"))
    assert why is None
    assert r == [0.8]
    assert mu == [0.0]
    r, mu, why = contact_coefficients(get_scenario("sliding_stop"))
    assert why is None
    assert mu == [0.5]  # the least of the ground's μ and the body's: μ
    # pairs only: √e on each
    r, mu, why = contact_coefficients(get_scenario("newtons_cradle"))
    assert why is None
    assert all(
        abs(r[i] * r[j] - e) <= PRODUCT_ATOL
        for i, j, e in get_scenario("newtons_cradle").pair_restitution
    )
    assert mu == [0.0, 0.0, 0.0]
    r, _, why = contact_coefficients(get_scenario("two_body_impact"))
    assert why is None
    assert abs(r[0] * r[1] - 0.6) <= PRODUCT_ATOL


def test_pairs_that_no_per_body_product_gives_are_refused_with_the_reason():
    s = dataclasses.replace(_two_bodies_and_ground(), pair_restitution=((0, 1, 0.9),))
    r, mu, why = contact_coefficients(s)  # the ground's 0.5 on both: 0.25 ≠ 0.9
    assert (r, mu) == ([], [])
    assert why is not None
    assert "product" in why
    assert "(0, 1)" in why
    s = dataclasses.replace(s, pair_restitution=((0, 1, 0.25),))
    assert contact_coefficients(s)[2] is None


def test_pairs_beside_a_rough_ground_are_refused_with_the_reason():
    s = _two_bodies_and_ground()
    s = dataclasses.replace(s, ground=Ground(0.5, friction=0.3), pair_restitution=((0, 1, 0.25),))
    why = contact_coefficients(s)[2]
    assert why is not None
    assert "least" in why
    assert "mu = 0.3" in why


# ------------------------------------------------------------------ bad input


def test_a_missing_engine_names_the_extra_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "dartpy", None)  # import of it now fails
    with pytest.raises(
        MissingExtraError,
        match=r"the DART adapter needs the dartpy package: "
        r"pip install 'bodycheck\[dart\]'",
    ):
        dart_module.DartAdapter()
    with pytest.raises(MissingExtraError, match=r"bodycheck\[dart\]"):
        dart_module.variants()


def test_an_unknown_solver_is_named():
    with pytest.raises(UnknownOptionError, match=r"DART solver must be one of .*; got 'lemke'"):
        dart_module.DartAdapter("lemke")


def test_a_step_that_does_not_divide_the_sample_times_is_refused():
    a = _adapter()
    s = get_scenario("parabola")
    with pytest.raises(MechanicsValueError, match=r"is not a whole number of steps 0.03"):
        a.run(s, 0.03)
    with pytest.raises(MechanicsValueError, match=r"needs a step > 0; got -0.01"):
        a.run(s, -0.01)
