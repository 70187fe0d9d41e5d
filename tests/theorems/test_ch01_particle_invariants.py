"""Chapter 1 of Essén (1996), systems of particles, as randomised invariants.

Systems come from :func:`mechanics.strategies.particle_systems` (1 to 50
particles, masses 1e-6 … 1e6, far offsets and fast translations included) and
internal forces from :func:`mechanics.strategies.pair_forces` (Newton's third
law by construction, central or not).

Two kinds of test:

- **Instantaneous**: at one instant, with accelerations a_k = F_k/m_k from the
  external and internal forces, the rates of p and L computed by
  :mod:`mechanics.particles` equal the external force and moment (1.24), (1.33),
  (1.50) to rounding; tolerances are multiples of eps times the sum of the
  magnitudes of the terms (the condition of the sum).
- **Along a motion**: the equations of motion are integrated (velocity Verlet,
  or scipy's DOP853 at rtol 1e-12) and Δp, ΔL are compared with the impulse and
  angular impulse of the external forces (1.56), (1.60).  With non-central pair
  forces the angular momentum principle fails, as the book says it must
  (figure 1.2): that is the negative control.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from mechanics import particles as mp
from mechanics import strategies as ms
from mechanics._floats import EPS

# ------------------------------------------------------------------ tolerances

#: dp/dt = Σ m_k a_k against Σ F^e: each a_k = F_k/m_k and m_k a_k round once
#: (1 eps of |F_k| each), F_k = F^e_k + Σ_j f_kj rounds once more, and the
#: compensated sums add at most 1 eps of the result: 8 eps of Σ|terms|.
RATE_TOL = 8 * EPS

#: Angular rates: the same roundings, plus AP_j = r_j − A (1 eps of |AP_j|) and
#: the two products of each cross-product component: 16 eps of Σ|terms|.
MOMENT_TOL = 16 * EPS

#: L_A against L_B + AB × p, or against L_G + AG × p: each side is a compensated
#: sum of products (≤ 2 eps of Σ|terms| each, the offsets r − A rounded), and r_G,
#: v_G are within 2 ulps: 16 eps of Σ m |AP| |v| (and of |AG| |p|).
CONNECTION_TOL = 16 * EPS

#: A Richardson-extrapolated central difference with step 1 of the cubic L_B(t):
#: exact in exact arithmetic; the four evaluations of L, each within a few eps
#: of Σ m |BP(t)| |v(t)| at |t| ≤ 1, are combined with weights of total size
#: (8 + 2)/3 / (2h): 64 eps of that scale leaves room.
RICHARDSON_TOL = 64 * EPS

#: Velocity Verlet updates each velocity by dt/2 (a_n + a_{n+1}): p changes by
#: exactly the trapezoid impulse in exact arithmetic, since the internal forces
#: cancel.  Each step rounds v (1 eps of |v|), dt a (1 eps), and the sums (2 eps):
#: 8 eps of Σ_steps Σ_k m_k (|v_k| + dt |a_k|).
VERLET_TOL = 8 * EPS

#: DOP853 at rtol = atol·scale = 1e-12 over t ≤ 2: the global error of smooth,
#: non-stiff motions stays within ~1e2 rtol (measured ≤ 3e-11 relative on these
#: systems); 2**20 eps = 2.3e-10 relative to the scale of the compared quantity.
SIM_TOL = 2**20 * EPS

SIM_RTOL = 1e-12


def _scale_sum(*terms) -> float:
    return float(sum(np.abs(np.asarray(t, dtype=float)).sum() for t in terms))


#: Absolute floor on every tolerance: drawn floats may be as small as 1e-300,
#: and products of two of them underflow (to 0 or a subnormal), an absolute
#: error of at most 2**-1022 per operation that no relative bound covers.
UNDERFLOW_FLOOR = 1e-290


def _assert_close(actual, desired, tol, what=""):
    tol = tol + UNDERFLOW_FLOOR
    err = float(np.max(np.abs(np.asarray(actual) - np.asarray(desired))))
    assert err <= tol, (
        f"{what}: error {err:.3g} exceeds {tol:.3g} ({err / max(tol, 1e-300):.3g} x tol)"
    )


def _fsum_rows(x: np.ndarray) -> np.ndarray:
    """Correctly rounded Σ over axis 0 of (N, 3): an exact oracle for a sum of floats."""
    return np.array([math.fsum(x[:, i]) for i in range(x.shape[1])])


# ------------------------------------------------------------------ strategies

vectors = st.tuples(*(st.floats(-1e3, 1e3, allow_subnormal=False),) * 3).map(np.array)


def _arrays(shape, bound):
    """Floats in [−bound, bound) of the given shape from one byte draw (fast for
    hundreds of numbers; zero bytes shrink to 0)."""
    k = int(np.prod(shape))
    return st.binary(min_size=8 * k, max_size=8 * k).map(
        lambda bs: np.frombuffer(bs, dtype="<i8").astype(float).reshape(shape) * (bound / 2.0**63)
    )


@st.composite
def systems_with_forces(draw, regimes=None, **kw):
    """(system, internal pair forces, external forces)."""
    s = draw(ms.particle_systems(**kw))
    f = draw(ms.pair_forces(s.r, regimes=regimes))
    n = len(s.m)
    return s, f, draw(_arrays((n, 3), 1e3))


def _accelerations(m, f, Fe):
    F = Fe + mp.internal_forces(f)
    return F / m[:, None], F


# ------------------------------------------------------ instantaneous invariants


@given(systems_with_forces())
def test_internal_forces_cancel_in_the_momentum_principle(data):
    # (1.20)–(1.24): dp/dt = Σ m_k a_k = F^e, whatever the pair forces obey
    # besides Newton's third law (central or not).
    s, f, Fe = data
    a, _ = _accelerations(s.m, f, Fe)
    pdot = mp.momentum(s.m, a)
    scale = _scale_sum(Fe, f)
    _assert_close(pdot, _fsum_rows(Fe), RATE_TOL * scale, "dp/dt - F^e")


def _rate_scale(s, f, Fe, A, vA=0.0):
    d = np.abs(s.r - A).sum(axis=-1)
    forces = np.abs(Fe).sum(axis=-1) + np.abs(f).sum(axis=(-2, -1))
    speeds = np.abs(s.v).sum(axis=-1)
    return float((d * forces).sum() + (s.m * speeds * (speeds + np.abs(vA).sum())).sum())


@given(systems_with_forces(regimes=["none", "central"]), vectors)
@example(
    (
        ms.ParticleSystem(
            np.array([1.0, 1.0]),
            np.array([[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]),
            np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]]),
        ),
        np.zeros((2, 2, 3)),
        np.zeros((2, 3)),
    ),
    np.zeros(3),
)
def test_central_internal_forces_drop_out_of_the_angular_momentum_principle_about_any_fixed_point(
    data, A
):
    # (1.25)–(1.33): dL_A/dt = M^e_A for a fixed A when every f_kj ∥ r_kj.
    s, f, Fe = data
    a, _ = _accelerations(s.m, f, Fe)
    Ldot = mp.angular_momentum_rate(s.m, s.r, s.v, a, about=A, about_velocity=np.zeros(3))
    M = mp.moment_of_forces(s.r, Fe, about=A)
    _assert_close(Ldot, M, MOMENT_TOL * _rate_scale(s, f, Fe, A), "dL_A/dt - M^e_A")


@given(systems_with_forces(regimes=["non-central"]), vectors)
def test_non_central_pair_forces_change_angular_momentum_by_their_internal_moment(data, A):
    # (1.27)–(1.31): dL_A/dt = M^e_A + M^i, and M^i = ½ Σ r_jk × f_jk is the
    # same about every point: the internal moment that (1.32) assumes away.
    s, f, Fe = data
    a, _ = _accelerations(s.m, f, Fe)
    Ldot = mp.angular_momentum_rate(s.m, s.r, s.v, a, about=A, about_velocity=np.zeros(3))
    M = mp.moment_of_forces(s.r, Fe, about=A)
    Mi = mp.internal_moment(s.r, f)
    scale = _rate_scale(s, f, Fe, A) + _scale_sum(f) * float(np.abs(s.r - A).max(initial=0) * 2)
    _assert_close(Ldot - M, Mi, MOMENT_TOL * scale, "dL_A/dt - M^e_A - M^i")


@st.composite
def two_separated_particles(draw):
    """Two particles at distance ≥ 0.1 (valid by construction), at rest or moving."""
    m = draw(ms.masses(min_particles=2, max_particles=2))
    r1 = draw(vectors) * 1e-3
    e = draw(ms.unit_vectors())
    r = np.stack([r1, r1 + draw(st.floats(0.1, 10.0)) * e])
    v = np.stack([draw(vectors), draw(vectors)]) * 1e-3
    return ms.ParticleSystem(m, r, v)


@given(
    two_separated_particles().flatmap(
        lambda s: st.tuples(st.just(s), ms.pair_forces(s.r, regimes=["non-central"]))
    ),
    vectors,
)
def test_non_central_pair_forces_break_the_angular_momentum_principle(data, A):
    # The negative control of (1.33): one non-central pair (figure 1.2, right)
    # has |M^i| = |r_12| |f_perp| ≥ 0.1 × 0.5 (the strategy's perpendicular part
    # is ≥ 5e-4 of its bound 1e3), far above rounding, and dL_A/dt ≠ M^e_A.
    s, f = data
    Fe = np.zeros((2, 3))
    a, _ = _accelerations(s.m, f, Fe)
    Ldot = mp.angular_momentum_rate(s.m, s.r, s.v, a, about=A, about_velocity=np.zeros(3))
    residual = float(np.abs(Ldot - mp.moment_of_forces(s.r, Fe, about=A)).max())
    assert residual > 1e6 * MOMENT_TOL * _rate_scale(s, f, Fe, A)
    assert residual >= 0.1 * 0.5 / math.sqrt(3) * (1 - 1e-9)


@given(systems_with_forces(regimes=["none", "central"]), vectors, vectors)
def test_angular_momentum_principle_holds_about_a_moving_base_point_with_the_extra_term(
    data, B, vB
):
    # (1.50): dL_B/dt + v_B × p = M_B for a base point moving with any v_B.
    s, f, Fe = data
    a, _ = _accelerations(s.m, f, Fe)
    Ldot = mp.angular_momentum_rate(s.m, s.r, s.v, a, about=B, about_velocity=vB)
    extra = mp.moving_base_point_term(s.m, s.v, about_velocity=vB)
    M = mp.moment_of_forces(s.r, Fe, about=B)
    scale = _rate_scale(s, f, Fe, B, vB)
    _assert_close(Ldot + extra, M, MOMENT_TOL * scale, "dL_B/dt + v_B x p - M_B")


@given(systems_with_forces(regimes=["none"]), vectors)
def test_the_moving_base_point_term_is_needed_when_v_B_is_not_parallel_to_v_G(data, vB):
    # Negative control of (1.50): leaving out v_B × p fails exactly when it is
    # not negligible (it vanishes for p = 0 or v_B ∥ v_G, section 1.2.1).
    s, f, Fe = data
    a, _ = _accelerations(s.m, f, Fe)
    B = s.r.mean(axis=0)
    Ldot = mp.angular_momentum_rate(s.m, s.r, s.v, a, about=B, about_velocity=vB)
    M = mp.moment_of_forces(s.r, Fe, about=B)
    extra = mp.moving_base_point_term(s.m, s.v, about_velocity=vB)
    tol = MOMENT_TOL * _rate_scale(s, f, Fe, B, vB)
    if float(np.abs(extra).max()) > 4 * tol:
        assert float(np.abs(Ldot - M).max()) > tol


@given(ms.particle_systems())
def test_centre_of_mass_base_point_needs_no_extra_term(s):
    # (1.51): for B = G, v_B × p = v_G × m v_G = 0 however G moves.
    vG = mp.centre_of_mass_velocity(s.m, s.v)
    extra = mp.moving_base_point_term(s.m, s.v, about_velocity=vG)
    p = mp.momentum(s.m, s.v)
    # v_G and p/m agree within 3 ulps, so v_G × p is within 6 eps |v_G| |p|.
    _assert_close(extra, 0.0, 8 * EPS * float(np.abs(vG).sum() * np.abs(p).sum()), "v_G x p")


@st.composite
def polynomial_motions(draw):
    s = draw(ms.particle_systems(max_particles=10))
    acc = draw(_arrays(s.r.shape, 10.0))
    B = draw(vectors)
    vB = draw(vectors)
    return s, acc, B, vB


@given(polynomial_motions())
def test_angular_momentum_rate_is_the_time_derivative_of_the_book_L_B(data):
    # d/dt of (1.8) along r_j(t) = r + v t + a t²/2, B(t) = B + v_B t: L_B(t) is
    # a cubic, so a Richardson-extrapolated central difference is exact.
    s, acc, B, vB = data

    def L(t):
        r = s.r + s.v * t + 0.5 * acc * t * t
        return mp.angular_momentum(s.m, r, s.v + acc * t, about=B + vB * t)

    def D(h):
        return (L(h) - L(-h)) / (2 * h)

    fd = (4 * D(0.5) - D(1.0)) / 3
    rate = mp.angular_momentum_rate(s.m, s.r, s.v, acc, about=B, about_velocity=vB)
    d = np.abs(s.r - B).sum(-1) + np.abs(s.v).sum(-1) + np.abs(acc).sum(-1) + np.abs(vB).sum()
    w = np.abs(s.v).sum(-1) + np.abs(acc).sum(-1)
    _assert_close(rate, fd, RICHARDSON_TOL * float((s.m * d * w).sum()), "dL_B/dt")


# ------------------------------------------------ identities about any base point


def _L_scale(s, *points):
    speeds = np.abs(s.v).sum(-1)
    return float(sum((s.m * np.abs(s.r - P).sum(-1) * speeds).sum() for P in points))


@given(ms.particle_systems(), vectors, vectors)
def test_connection_formula_holds_between_any_two_points(s, A, B):
    # (1.46): L_B = L_A + BA × p.
    L_A = mp.angular_momentum(s.m, s.r, s.v, about=A)
    L_B = mp.angular_momentum(s.m, s.r, s.v, about=B)
    p = mp.momentum(s.m, s.v)
    scale = _L_scale(s, A, B)
    _assert_close(L_B, L_A + np.cross(A - B, p), CONNECTION_TOL * scale, "L_B - L_A - BA x p")


@given(ms.particle_systems(), vectors)
def test_angular_momentum_is_the_centre_of_mass_part_plus_the_internal_part(s, A):
    # (1.12): L_A = AG × m v_G + L'_G, about any point A; L'_G = L_G (1.15).
    L_A = mp.angular_momentum(s.m, s.r, s.v, about=A)
    L_G, L_ext = mp.angular_momentum_decomposition(s.m, s.r, s.v, about=A)
    rG = mp.centre_of_mass(s.m, s.r)
    scale = _L_scale(s, A, rG)
    _assert_close(L_G + L_ext, L_A, CONNECTION_TOL * scale, "L_G + AG x p - L_A")
    vG = mp.centre_of_mass_velocity(s.m, s.v)
    L_G_abs = mp.angular_momentum(s.m, s.r, s.v, about=rG)
    L_G_rel = mp.angular_momentum(s.m, s.r, s.v, about=rG, about_velocity=vG)
    _assert_close(L_G_abs, L_G, CONNECTION_TOL * scale, "L_G (1.13) - L'_G")
    _assert_close(L_G_rel, L_G, CONNECTION_TOL * scale, "L'_G (1.12) - L'_G")


@given(ms.particle_systems(), vectors, vectors)
def test_relative_angular_momentum_about_a_moving_point(s, A, vA):
    # With velocities relative to A: Σ AP_j × m_j (v_j − v_A) = L_A − AG × m v_A.
    rel = mp.angular_momentum(s.m, s.r, s.v, about=A, about_velocity=vA)
    L_A = mp.angular_momentum(s.m, s.r, s.v, about=A)
    rG = mp.centre_of_mass(s.m, s.r)
    M = mp.total_mass(s.m)
    scale = _L_scale(s, A) + float((s.m * np.abs(s.r - A).sum(-1)).sum() * np.abs(vA).sum())
    _assert_close(rel, L_A - np.cross(rG - A, M * vA), CONNECTION_TOL * scale, "relative L_A")


@given(ms.particle_systems())
def test_momentum_is_total_mass_times_centre_of_mass_velocity(s):
    # (1.6)–(1.7): p = m v_G; p and m are within 1 ulp, v_G within 2.
    p = mp.momentum(s.m, s.v)
    mvG = mp.total_mass(s.m) * mp.centre_of_mass_velocity(s.m, s.v)
    scale = float((s.m * np.abs(s.v).max(axis=-1)).sum())
    _assert_close(p, mvG, 4 * EPS * scale, "p - m v_G")


@given(ms.particle_systems())
def test_positions_and_velocities_relative_to_the_centre_of_mass_have_zero_moment(s):
    # (1.10): Σ m_j r'_j = Σ m_j v'_j = 0.  r_G is within 2 ulps and each
    # r_j − r_G rounds by an ulp of it: 4 eps of Σ m_j (|r_G| + |r'_j|).
    for x in (s.r, s.v):
        G = mp.centre_of_mass(s.m, x)
        first = mp.momentum(s.m, x - G)
        scale = float((s.m * (np.abs(G).max() + np.abs(x - G).max(axis=-1))).sum())
        _assert_close(first, 0.0, 4 * EPS * scale, "sum m r'")


@given(ms.particle_systems(), ms.unit_vectors())
def test_axial_angular_momentum_is_moment_of_inertia_times_average_angular_velocity(s, e):
    # (1.66)–(1.72): L_Oz = Σ m ρ² ϕ̇ = J_z ω_av, about an axis through the origin.
    O = np.zeros(3)
    Jz = mp.moment_of_inertia_about_axis(s.m, s.r, about=O, axis=e)
    if Jz <= 0:
        return
    L_z = mp.axial_component(mp.angular_momentum(s.m, s.r, s.v, about=O), axis=e)
    w_av = mp.average_angular_velocity(s.m, s.r, s.v, about=O, axis=e)
    rho = np.linalg.norm(s.r - np.outer(s.r @ e, e), axis=-1)
    off = rho > 1e-3 * max(1.0, float(np.abs(s.r).max()))
    if off.all():
        # (1.69) particle by particle, with ϕ̇ from the cylindrical components.
        c = mp.cylindrical_components(s.r, s.v, about=O, axis=e)
        direct = math.fsum((s.m * c.rho**2 * c.phidot).tolist())
        # ρ² ϕ̇ = (x ẏ − y ẋ): a few roundings of |r| |v|, divided and multiplied by ρ².
        cond = float((s.m * np.abs(s.r).sum(-1) ** 2 * np.abs(s.v).sum(-1) / rho).sum())
        assert abs(direct - float(L_z)) <= 64 * EPS * max(cond, _L_scale(s, O))
    _assert_close(Jz * w_av, L_z, 8 * EPS * _L_scale(s, O), "J_z w_av - L_z")


# --------------------------------------------------------------- along a motion


def _pair_law(r, k, b, n_hat):
    """Pair forces f_kj = −k_kj r_kj (zero-length springs, central) + b_kj n̂ × r_kj
    (non-central, b symmetric): both obey f_jk = −f_kj."""
    rkj = r[:, None, :] - r[None, :, :]
    return -k[..., None] * rkj + b[..., None] * np.cross(n_hat, rkj)


def _external(m, t, g, A, w):
    """Uniform gravity plus a time-dependent push A_k cos(w t)."""
    return m[:, None] * g + A * np.cos(w * t)


def _external_impulse(m, t0, t1, g, A, w):
    return m.sum() * g * (t1 - t0) + A.sum(axis=0) * (np.sin(w * t1) - np.sin(w * t0)) / w


@st.composite
def sim_setups(draw, non_central=False):
    n = draw(st.integers(2, 4))
    m = np.array(draw(st.lists(st.floats(0.1, 10.0), min_size=n, max_size=n)))
    # Vertices of a tetrahedron, moved by at most 0.3: distinct, not collinear.
    base = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [-1.0, -1.0, -1.0]])[:n]
    dr = draw(st.lists(st.floats(-0.3, 0.3), min_size=3 * n, max_size=3 * n))
    r = base + np.array(dr).reshape(n, 3)
    v = np.array(draw(st.lists(st.floats(-1, 1), min_size=3 * n, max_size=3 * n))).reshape(n, 3)
    kk = np.array(draw(st.lists(st.floats(0.1, 2.0), min_size=n * n, max_size=n * n)))
    k = np.triu(kk.reshape(n, n), 1)
    k = k + k.T
    if non_central:
        bb = np.array(draw(st.lists(st.floats(0.5, 2.0), min_size=n * n, max_size=n * n)))
        b = np.triu(bb.reshape(n, n), 1)
        b = b + b.T
    else:
        b = np.zeros((n, n))
    g = np.array([0.0, 0.0, -9.81])
    A = np.array(draw(st.lists(st.floats(-1, 1), min_size=3 * n, max_size=3 * n))).reshape(n, 3)
    w = draw(st.floats(0.5, 3.0))
    n_hat = draw(ms.unit_vectors())
    return m, r, v, k, b, g, A, w, n_hat


def _simulate(setup, t_end, dense=False):
    """Integrate with DOP853; the state carries ∫ M^e_O dt alongside r and v."""
    m, r0, v0, k, b, g, A, w, n_hat = setup
    n = len(m)

    def rhs(t, y):
        r = y[: 3 * n].reshape(n, 3)
        v = y[3 * n : 6 * n].reshape(n, 3)
        Fe = _external(m, t, g, A, w)
        F = Fe + _pair_law(r, k, b, n_hat).sum(axis=1)
        M_O = np.cross(r, Fe).sum(axis=0)
        return np.concatenate([v.ravel(), (F / m[:, None]).ravel(), M_O])

    y0 = np.concatenate([r0.ravel(), v0.ravel(), np.zeros(3)])
    sol = solve_ivp(rhs, (0.0, t_end), y0, method="DOP853", rtol=SIM_RTOL, atol=SIM_RTOL)
    assert sol.success
    y = sol.y[:, -1]
    return y[: 3 * n].reshape(n, 3), y[3 * n : 6 * n].reshape(n, 3), y[6 * n :]


@settings(max_examples=20)
@given(sim_setups(non_central=True), st.floats(0.5, 1.0))
def test_momentum_changes_only_by_the_external_impulse_along_a_simulated_motion(setup, t_end):
    # (1.54)–(1.56) by velocity Verlet: the internal forces (central and not)
    # cancel step by step, so Δp equals the trapezoid impulse of F^e to rounding.
    m, r, v, k, b, g, A, w, n_hat = setup
    steps = 200
    dt = t_end / steps

    def forces(r, t):
        Fe = _external(m, t, g, A, w)
        return Fe, Fe + _pair_law(r, k, b, n_hat).sum(axis=1)

    p0 = mp.momentum(m, v)
    Fe, F = forces(r, 0.0)
    impulse = np.zeros(3)
    scale = 0.0
    for i in range(steps):
        t1 = (i + 1) * dt
        vh = v + 0.5 * dt * F / m[:, None]
        r = r + dt * vh
        Fe1, F1 = forces(r, t1)
        v = vh + 0.5 * dt * F1 / m[:, None]
        impulse += 0.5 * dt * (Fe.sum(axis=0) + Fe1.sum(axis=0))
        scale += float((m[:, None] * np.abs(v)).sum() + dt * (np.abs(F) + np.abs(F1)).sum())
        Fe, F = Fe1, F1
    dp = mp.momentum(m, v) - p0
    _assert_close(dp, impulse, VERLET_TOL * scale, "Δp - trapezoid impulse")
    # The trapezoid impulse is within dt²/12 t_end max|d²F/dt²| of the exact
    # one (1.55), plus the rounding of the accumulated sum.
    exact = _external_impulse(m, 0.0, t_end, g, A, w)
    bound = dt**2 / 12 * t_end * w**2 * float(np.abs(A).sum()) + VERLET_TOL * scale
    assert float(np.abs(impulse - exact).max()) <= bound


@settings(max_examples=8)
@given(sim_setups(), st.floats(0.5, 1.0))
def test_angular_momentum_changes_only_by_the_external_angular_impulse_with_central_forces(
    setup, t_end
):
    # (1.58)–(1.60) about the fixed origin: ΔL_O = H_O = ∫ M^e_O dt.
    m, r0, v0 = setup[:3]
    r, v, H = _simulate(setup, t_end)
    O = np.zeros(3)
    dL = mp.angular_momentum(m, r, v, about=O) - mp.angular_momentum(m, r0, v0, about=O)
    scale = _L_scale(ms.ParticleSystem(m, r, v), O) + float(np.abs(H).sum()) + 1.0
    _assert_close(dL, H, SIM_TOL * scale, "ΔL_O - H_O")


@settings(max_examples=8)
@given(sim_setups(non_central=True), st.floats(0.5, 1.0))
def test_angular_momentum_principle_fails_along_a_motion_with_non_central_forces(setup, t_end):
    # Negative control: with non-central pair forces b n̂ × r_kj (b ≥ 0.5),
    # ΔL_O − H_O is the time integral of M^i = ½ Σ b (n̂ |r_kj|² − r_kj (r_kj · n̂)),
    # whose n̂-component ½ Σ b |r_kj ⊥ n̂|² is > 0 at every instant: it cannot cancel.
    m, r0, v0 = setup[:3]
    n_hat = setup[-1]
    r, v, H = _simulate(setup, t_end)
    O = np.zeros(3)
    dL = mp.angular_momentum(m, r, v, about=O) - mp.angular_momentum(m, r0, v0, about=O)
    scale = _L_scale(ms.ParticleSystem(m, r, v), O) + float(np.abs(H).sum()) + 1.0
    assert float((dL - H) @ n_hat) > 1e3 * SIM_TOL * scale
