"""Chapter 8 as properties of mechanics.fluids: rigid and linear flows, Euler's
equation for exact solutions, Bernoulli along streamlines (and not across them)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from mechanics import fluids
from mechanics.rotation import EPS

finite = st.floats(-10.0, 10.0, allow_nan=False, allow_infinity=False)
vectors = arrays(np.float64, (3,), elements=finite)
matrices = arrays(np.float64, (3, 3), elements=finite)
points = arrays(np.float64, (4, 3), elements=st.floats(-5.0, 5.0))

#: Linear fields are differentiated exactly by the stencil up to rounding:
#: ~1.5 eps |v| / h per entry with |v| ≤ 3·10·(1 + 5) and h = H_REL(1 + |r|∞);
#: relative to the field scale that is ≤ 2^16 eps.
LINEAR_RTOL = 2**16 * EPS


@given(v0=vectors, w=vectors, r=points)
def test_rigid_flow_has_no_divergence_and_curl_twice_omega(v0, w, r):
    v = fluids.rigid_velocity_field(v0, w)
    scale = 1.0 + np.abs(v0).max() + np.abs(w).max() * 6
    np.testing.assert_allclose(fluids.divergence(v, r), 0.0, atol=LINEAR_RTOL * scale)
    np.testing.assert_allclose(
        fluids.curl(v, r), np.broadcast_to(2 * w, r.shape), atol=LINEAR_RTOL * scale
    )


@given(A=matrices, r=points)
def test_linear_flow_divergence_is_the_trace_and_curl_the_axial_vector(A, r):
    def v(x, t):
        return x @ A.T

    scale = 1.0 + np.abs(A).max() * 6
    np.testing.assert_allclose(fluids.divergence(v, r), np.trace(A), atol=LINEAR_RTOL * scale)
    axial = [A[2, 1] - A[1, 2], A[0, 2] - A[2, 0], A[1, 0] - A[0, 1]]
    np.testing.assert_allclose(
        fluids.curl(v, r), np.broadcast_to(axial, r.shape), atol=LINEAR_RTOL * scale
    )


def forced_vortex(w, rho, g):
    v = fluids.rigid_velocity_field([0.0, 0.0, 0.0], [0.0, 0.0, w])

    def p(r, t):
        return rho * w**2 * (r[..., 0] ** 2 + r[..., 1] ** 2) / 2 - rho * g * r[..., 2]

    return v, p


@given(w=st.floats(0.1, 5.0), rho=st.floats(1.0, 2000.0), g=st.floats(0.5, 20.0), r=points)
def test_forced_vortex_solves_euler_and_the_wrong_pressure_does_not(w, rho, g, r):
    v, p = forced_vortex(w, rho, g)
    scale = g + w**2 * 10  # the sizes of the terms of (8.27)
    res = fluids.euler_residual(v, p, r, rho=rho, g=g)
    np.testing.assert_allclose(res, 0.0, atol=LINEAR_RTOL * scale)

    def p_static(x, t):  # hydrostatic only: no centripetal pressure gradient
        return -rho * g * x[..., 2]

    wrong = fluids.euler_residual(v, p_static, r, rho=rho, g=g)
    radius = np.hypot(r[:, 0], r[:, 1])
    # the residual is the missing centripetal acceleration ω² ρ_⊥ (where it is resolvable)
    np.testing.assert_allclose(
        np.linalg.norm(wrong, axis=-1), w**2 * radius, atol=LINEAR_RTOL * scale
    )


# each example integrates two streamlines with DOP853 (~0.1 s): fewer examples
@settings(max_examples=25)
@given(w=st.floats(0.2, 3.0), r0=st.floats(0.5, 3.0), r1=st.floats(0.5, 3.0))
def test_bernoulli_is_constant_along_streamlines_of_a_rotational_flow_but_not_across(w, r0, r1):
    rho, g = 1000.0, 9.81
    v, p = forced_vortex(w, rho, g)
    s = np.linspace(0.0, 4.0, 9)
    line = fluids.streamline(v, [r0, 0.0, 0.3], s)
    B = fluids.bernoulli_constant(v(line), p(line, 0.0), line[:, 2], rho_0=rho, g=g)
    scale = rho * (w * 3) ** 2 + rho * g
    # DOP853 at rtol 1e-12 over a few revolutions keeps the circle to ~1e-12
    np.testing.assert_allclose(B, B[0], atol=2**13 * EPS * scale)
    other = fluids.streamline(v, [r1, 0.0, 0.3], s)
    B1 = fluids.bernoulli_constant(v(other), p(other, 0.0), other[:, 2], rho_0=rho, g=g)
    # across streamlines B changes by ρ ω² (r1² − r0²) (the flow has curl 2ω)
    np.testing.assert_allclose(B1[0] - B[0], rho * w**2 * (r1**2 - r0**2), atol=2**13 * EPS * scale)
