"""Chapter 3 of Essén (1996), energy of particle systems and bodies, as randomised invariants.

Instantaneous identities (Koenig's theorem, the rigid-body kinetic energy in
matrix and fixed-axis form, P = dT/dt, the power of internal forces, forces that
do no work) are checked on systems from :func:`mechanics.strategies.particle_systems`
with tolerances that are multiples of eps times the size of the terms.  The
work–energy theorem and the conservation of mechanical energy are checked along
motions integrated by scipy's DOP853 at rtol 1e-12, where the tolerance is the
integrator's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from mechanics import energy as me
from mechanics import particles as mp
from mechanics import strategies as ms
from mechanics._floats import EPS

#: Sums of positive terms (kinetic energies, ½ m v²): each term rounds a few
#: times (v², m v², ½) and the compensated sum adds one rounding: 8 eps relative
#: to Σ ½ m |v|² (measured ≤ 3 eps).
ENERGY_TOL = 8 * EPS

#: Rigid-body energies from ω, J and v_G against Σ ½ m v_k²: v_k = v_G + ω × r'_k
#: rounds |v_G| + |ω||r'| (2 eps), J = Σ m (|r'|² 1 − r' r'ᵀ) rounds m |r'|²
#: (4 eps), and ωᵀ J ω sums nine products: 32 eps of Σ ½ m (|v_G| + |ω||r'|)².
RIGID_TOL = 32 * EPS

#: Powers Σ F·v against their rigid-body or pairwise forms: a dot product of
#: sums of a few rounded products each: 16 eps of Σ |F| |v|.
POWER_TOL = 16 * EPS

#: DOP853 at rtol = atol = 1e-12 over t ≤ 1 for these smooth, non-stiff motions:
#: global errors ~1e2 rtol (measured ≤ 2e-11 relative); 2**20 eps = 2.3e-10
#: relative to the energy scale.
SIM_TOL = 2**20 * EPS
SIM_RTOL = 1e-12


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


def _arrays(shape, bound):
    """Floats in [−bound, bound) of the given shape from one byte draw."""
    k = int(np.prod(shape))
    return st.binary(min_size=8 * k, max_size=8 * k).map(
        lambda bs: np.frombuffer(bs, dtype="<i8").astype(float).reshape(shape) * (bound / 2.0**63)
    )


vectors = st.tuples(*(st.floats(-10.0, 10.0, allow_subnormal=False),) * 3).map(np.array)


def _inertia_tensor(m, r, about):
    """J about a point by the book's definitions (3.16), (3.17), (3.23).

    Both terms are sums of the same products (m d_i) d_j: formed as m (d·d) the trace
    term underflowed where (m d_z) d_z did not (d ~ 1e-163, m = 1e6), and J_zz came out
    −2e-319 (found by a random run)."""
    d = r - about
    md = m[:, None] * d
    trace = np.einsum("ni,ni->", md, d)
    return trace * np.eye(3) - np.einsum("ni,nj->ij", md, d)


# ------------------------------------------------------------ kinetic energy


@given(ms.particle_systems())
def test_kinetic_energy_is_the_centre_of_mass_part_plus_the_internal_part(s):
    # Koenig's theorem (3.5)–(3.7): T = ½ m v_G² + T'.
    T = mp.kinetic_energy(s.m, s.v)
    T_G, T_cm = mp.kinetic_energy_decomposition(s.m, s.v)
    scale = 0.5 * float((s.m * np.einsum("ni,ni->n", s.v, s.v)).sum())
    _assert_close(T_G + T_cm, T, ENERGY_TOL * scale, "T' + ½ m v_G² − T")


@given(ms.particle_systems(regimes=["simple", "generic", "wide-mass-ratio"]), vectors)
def test_internal_kinetic_energy_does_not_see_a_common_translation(s, U):
    # T' is the same in every frame moving uniformly (it refers only to v − v_G),
    # and the centred computation keeps it accurate at speeds of 1e6: adding
    # V = 1e5 U rounds each v_k by ulp(|V|), i.e. 2 eps |V| per component.
    V = 1e5 * U
    T1, _ = mp.kinetic_energy_decomposition(s.m, s.v)
    T2, _ = mp.kinetic_energy_decomposition(s.m, s.v + V)
    vG = mp.centre_of_mass_velocity(s.m, s.v)
    rel = np.abs(s.v - vG).sum(-1)
    # Each v_k + V − v_G(v + V) is off by δ ≤ 2 ulps of |v + V| (the rounding of
    # v + V and of v_G): T' changes by at most Σ m (|v'| δ + δ²).
    delta = 4 * EPS * (np.abs(V).sum() + np.abs(s.v).sum(-1))
    tol = 2 * float((s.m * (rel + delta) * delta).sum()) + ENERGY_TOL * float(T1)
    _assert_close(T2, T1, tol, "T'(v + V) − T'(v)")


@st.composite
def rigid_motions(draw):
    """A rigid body of particles: v_k = v_G + ω × (r_k − r_G)."""
    s = draw(ms.particle_systems(regimes=["simple", "generic", "wide-mass-ratio"]))
    omega = draw(vectors)
    rG = mp.centre_of_mass(s.m, s.r)
    vG = draw(vectors)
    v = vG + np.cross(omega, s.r - rG)
    return s.m, s.r, v, rG, vG, omega


def _rigid_scale(m, r, rG, vG, omega):
    speeds = np.abs(vG).sum() + np.abs(omega).sum() * np.abs(r - rG).sum(-1)
    # r_G is within an ulp or two of the exact centre of mass, so the particles'
    # own v_G differs from the drawn one by ω × δ, |δ| ≲ eps |r_G|: T moves by
    # m v_G · (ω × δ), hence the term m |v_G| |ω| |r_G|.
    drift = float(m.sum() * np.abs(vG).sum() * np.abs(omega).sum() * np.abs(rG).sum())
    return 0.5 * float((m * speeds**2).sum()) + drift


@given(rigid_motions())
def test_rigid_body_kinetic_energy_is_the_quadratic_form_in_omega_plus_translation(data):
    # (3.8)–(3.24): T = ½ m v_G² + ½ ωᵀ J_G ω with J_G from (3.16), (3.17), (3.23).
    m, r, v, rG, vG, omega = data
    J_G = _inertia_tensor(m, r, rG)
    T = mp.kinetic_energy(m, v)
    T_rigid = me.kinetic_energy_rigid(mp.total_mass(m), vG, omega, J_G)
    _assert_close(T_rigid, T, RIGID_TOL * _rigid_scale(m, r, rG, vG, omega), "T rigid − Σ ½ m v²")


@given(rigid_motions(), vectors)
@example(  # the helper's J about C had a trace term that underflowed (see _inertia_tensor)
    data=(np.array([1e-6, 1e6]), *(np.zeros((2, 3)),) * 2, *(np.zeros(3),) * 3),
    C=np.array([0.0, 0.0, 4.6052096092334834e-163]),
)
def test_pure_rotation_about_a_fixed_point_has_kinetic_energy_half_omega_J_C_omega(data, C):
    # (3.18)–(3.21): v_k = ω × CP_k gives T = ½ ωᵀ J_C ω.
    m, r, _, _, _, omega = data
    v = np.cross(omega, r - C)
    J_C = _inertia_tensor(m, r, C)
    T = mp.kinetic_energy(m, v)
    T_rot = me.kinetic_energy_rigid(mp.total_mass(m), np.zeros(3), omega, J_C)
    _assert_close(T_rot, T, RIGID_TOL * _rigid_scale(m, r, C, np.zeros(3), omega), "½ ωᵀJ_Cω − T")


@given(rigid_motions(), ms.unit_vectors(), st.floats(-10.0, 10.0))
def test_fixed_axis_kinetic_energy_is_half_J_axis_phidot_squared(data, e, phidot):
    # (3.25)–(3.30): ω = φ̇ e about an axis through C gives T = ½ J_C φ̇².
    m, r, _, rG, _, _ = data
    C = rG + np.array([0.5, -1.0, 2.0])
    v = np.cross(phidot * e, r - C)
    J_axis = mp.moment_of_inertia_about_axis(m, r, about=C, axis=e)
    T = mp.kinetic_energy(m, v)
    scale = _rigid_scale(m, r, C, np.zeros(3), phidot * e)
    _assert_close(me.kinetic_energy_fixed_axis(J_axis, phidot), T, RIGID_TOL * scale, "½ J φ̇² − T")


@given(rigid_motions(), st.floats(-10.0, 10.0), st.floats(-5.0, 5.0), st.floats(-5.0, 5.0))
def test_plane_motion_energy_about_the_instantaneous_centre_is_koenig(data, phidot, cx, cy):
    # Example 3.1, (3.31)–(3.35): ½ J^C_z φ̇² = ½ m v_G² + ½ J^G_z φ̇², with
    # v_G = ω × CG and C in the plane of G (parallel axis theorem (3.32)).
    m, r, _, rG, _, _ = data
    ez = np.array([0.0, 0.0, 1.0])
    C = rG + np.array([cx, cy, 0.0])
    M = mp.total_mass(m)
    vG = np.cross(phidot * ez, rG - C)
    J_C = mp.moment_of_inertia_about_axis(m, r, about=C, axis=ez)
    J_G = mp.moment_of_inertia_about_axis(m, r, about=rG, axis=ez)
    lhs = me.kinetic_energy_fixed_axis(J_C, phidot)
    rhs = 0.5 * M * float(vG @ vG) + me.kinetic_energy_fixed_axis(J_G, phidot)
    # r_G is within an ulp or two (δ) of the exact centre of mass, and ½ m v_G²
    # depends on it at first order: m φ̇² |CG| |δ|, δ ≲ eps |r_G|.
    drift = float(M * phidot**2 * np.abs(rG - C).sum() * np.abs(rG).sum())
    scale = _rigid_scale(m, r, C, np.zeros(3), phidot * ez) + drift
    _assert_close(lhs, rhs, RIGID_TOL * scale, "Example 3.1")


# ---------------------------------------------------------------- power, work


@given(ms.particle_systems(max_particles=20), st.data())
def test_power_is_the_time_derivative_of_the_kinetic_energy(s, data):
    # (3.1)–(3.4): along v_k(t) = v_k + a_k t, T(t) is quadratic, so the central
    # difference with step 1 is exact; P = Σ F·v with F = m a.
    a = data.draw(_arrays(s.v.shape, 10.0))
    F = s.m[:, None] * a

    def T(t):
        return mp.kinetic_energy(s.m, s.v + a * t)

    Tdot = (T(1.0) - T(-1.0)) / 2
    scale = float((s.m * (np.abs(s.v).sum(-1) + np.abs(a).sum(-1)) ** 2).sum())
    _assert_close(me.power(F, s.v), Tdot, ENERGY_TOL * scale, "P − dT/dt")


@given(
    ms.particle_systems(max_particles=20).flatmap(
        lambda s: st.tuples(st.just(s), ms.pair_forces(s.r))
    )
)
def test_internal_power_is_half_the_sum_over_pairs_of_f_kj_dot_relative_velocity(data):
    # (3.43)–(3.46) per unit time: Σ_k F^i_k · v_k = ½ Σ_kj f_kj · (v_k − v_j),
    # by Newton's third law alone (central or not).
    s, f = data
    P_i = me.power(mp.internal_forces(f), s.v)
    rel = s.v[:, None, :] - s.v[None, :, :]
    pairs = 0.5 * math.fsum((f * rel).ravel().tolist())
    scale = float((np.abs(f) * (np.abs(s.v)[:, None, :] + np.abs(s.v)[None, :, :])).sum())
    _assert_close(P_i, pairs, POWER_TOL * scale, "P^i − ½ Σ f_kj · v_kj")


@given(
    rigid_motions().flatmap(
        lambda d: st.tuples(st.just(d), ms.pair_forces(d[1], regimes=["central"]))
    )
)
def test_central_internal_forces_do_no_work_in_a_rigid_body(data):
    # (3.64), (3.66)–(3.67): dr_kj = δφ × r_kj ⊥ f_kj ∥ r_kj.
    (_, r, v, rG, vG, omega), f = data
    P_i = me.power(mp.internal_forces(f), v)
    scale = float(np.abs(f).sum() * (np.abs(vG).sum() + np.abs(omega).sum() * np.abs(r - rG).max()))
    _assert_close(P_i, 0.0, POWER_TOL * scale, "internal power in a rigid body")


@given(st.floats(0.1, 10.0), ms.unit_vectors(), st.floats(0.5, 5.0), st.floats(-math.pi, math.pi))
def test_non_central_internal_forces_can_work_in_a_rigid_body(dist, e, w, ang):
    # Negative control of (3.67): f_12 ⊥ r_12 in the plane of rotation about
    # ω ∥ (r_12 × f_12) gives P^i = f_12 · (ω × r_12) = |f||ω||r_12| ≠ 0.
    r = np.stack([np.zeros(3), -dist * e])  # r_12 = dist e
    a = np.zeros(3)
    a[int(np.argmin(np.abs(e)))] = 1.0
    n1 = np.cross(e, a)
    n1 /= np.linalg.norm(n1)
    f = np.zeros((2, 2, 3))
    f[0, 1] = n1
    f[1, 0] = -n1
    omega = w * np.cross(e, n1)
    v = np.cross(omega, r)
    P_i = float(me.power(mp.internal_forces(f), v))
    assert P_i == pytest.approx(w * dist, rel=64 * EPS)  # a few products and a cross


@given(rigid_motions(), st.data())
def test_power_on_a_rigid_body_is_force_dot_v_A_plus_moment_dot_omega_about_any_body_point(
    data, draws
):
    # (3.60)–(3.65) per unit time, for any body point A.
    _, r, v, rG, vG, omega = data
    F = draws.draw(_arrays(r.shape, 10.0))
    A = draws.draw(vectors)
    v_A = vG + np.cross(omega, A - rG)
    P = me.power(F, v)
    P_rigid = me.rigid_body_power(F.sum(axis=0), mp.moment_of_forces(r, F, about=A), v_A, omega)
    lever = np.abs(r - A).sum(-1)
    scale = float((np.abs(F).sum(-1) * (np.abs(v_A).sum() + np.abs(omega).sum() * lever)).sum())
    _assert_close(P_rigid, P, POWER_TOL * scale, "F·v_A + M_A·ω − Σ F·v")


@given(ms.particle_systems(), vectors)
def test_gravity_potential_is_total_mass_times_g_dot_centre_of_mass(s, g):
    # Example 3.2 (3.55)–(3.56): Φ^e = −Σ m_k g·r_k = −m g·r_G.
    Phi = me.gravity_potential(s.m, s.r, g=g)
    direct = -mp.total_mass(s.m) * float(g @ mp.centre_of_mass(s.m, s.r))
    scale = float((s.m * np.abs(s.r).sum(-1)).sum() * np.abs(g).sum())
    _assert_close(Phi, direct, 8 * EPS * scale, "Φ^e + m g·r_G")


@given(vectors, vectors, vectors, st.floats(0.1, 10.0), st.integers(2, 50))
def test_work_of_a_linear_spring_along_a_straight_path_is_the_potential_drop(a, b, c, k, K):
    # (3.49)–(3.50): along a straight path the zero-length spring force
    # −k (r − c) is affine in the path parameter, so the trapezoid rule is exact:
    # W = Φ(a) − Φ(b) to rounding.
    s = np.linspace(0.0, 1.0, K)[:, None]
    path = a + s * (b - a)
    F = -k * (path - c)
    W = me.work_along_path(F, path)
    dPhi = me.spring_potential(k, 0.0, b, c) - me.spring_potential(k, 0.0, a, c)
    # ΔΦ is a difference of ½ k |b − c|² and ½ k |a − c|², each within a few eps.
    scale = k * float((np.abs(a - c).sum() + np.abs(b - c).sum()) ** 2) + 1e-300
    _assert_close(W, -dPhi, 64 * EPS * scale, "W + ΔΦ")


def test_work_along_a_curved_path_converges_at_second_order_to_the_potential_drop():
    # (3.50): path independence of conservative work, and the documented O(h²)
    # of work_along_path: halving the step divides the error by ~4.
    k, ell_0, c = 3.0, 0.5, np.array([0.2, -0.1, 0.0])
    errs = []
    for K in (50, 100, 200, 400):
        s = np.linspace(0.0, 1.0, K)
        path = np.stack([1 + np.cos(4 * s), np.sin(4 * s), s**2], axis=-1)
        F = me.spring_force(k, ell_0, path, c)
        dPhi = me.spring_potential(k, ell_0, path[-1], c) - me.spring_potential(
            k, ell_0, path[0], c
        )
        errs.append(abs(float(me.work_along_path(F, path) + dPhi)))
    ratios = [errs[i] / errs[i + 1] for i in range(3)]
    assert all(3.5 < q < 4.5 for q in ratios), (errs, ratios)


# ------------------------------------------------------ forces that do no work


@given(vectors, vectors, ms.unit_vectors(), st.floats(0.01, 10.0))
def test_contact_force_at_a_rolling_contact_does_no_work(F, omega, n, radius):
    # 3.2.2: rolling without slipping, v_C = v_G + ω × GC = 0, so F · v_C = 0
    # for the normal force and static friction alike.
    GC = -radius * n
    v_G = -np.cross(omega, GC)
    P = float(me.rolling_contact_power(F, v_G, omega, GC))
    scale = float(np.abs(F).sum() * np.abs(omega).sum() * radius)
    assert abs(P) <= 8 * EPS * scale + UNDERFLOW_FLOOR


@given(vectors, vectors, ms.unit_vectors(), st.floats(0.01, 10.0), vectors)
def test_contact_force_on_a_slipping_body_works_at_the_slip_velocity(F, omega, n, radius, slip):
    # Negative control: add a slip velocity u to the contact point; the power is F · u.
    GC = -radius * n
    v_G = -np.cross(omega, GC) + slip
    P = float(me.contact_power(F, v_G, omega, GC))
    scale = float(np.abs(F).sum() * (np.abs(omega).sum() * radius + np.abs(slip).sum()))
    assert abs(P - float(F @ slip)) <= 8 * EPS * scale + UNDERFLOW_FLOOR


@given(vectors, vectors, vectors, ms.unit_vectors())
def test_normal_force_pair_between_moving_bodies_does_no_net_work(N_mag, v1, dv, n):
    # 3.2.2: N on body 1 and −N on body 2, with the same velocity component
    # along N (v_2 = v_1 + a tangential difference), deliver zero net power.
    N = float(N_mag[0]) * n
    t = dv - (dv @ n) * n  # tangential part, exactly ⊥ n up to rounding
    P = float(me.pair_power(N, v1, v1 + t))
    # v_1 − (v_1 + t) is −t within an ulp of |v_1| + |t|.
    scale = float(np.abs(N).sum() * (np.abs(dv).sum() + np.abs(v1).sum()))
    assert abs(P) <= 8 * EPS * scale + UNDERFLOW_FLOOR


@given(vectors, vectors, vectors, vectors)
def test_the_power_of_a_couple_on_a_rigid_body_is_its_moment_dot_omega(F, r1, r2, omega):
    # (3.62), (3.70): forces F at P1 and −F at P2 of a rigid body have power
    # F · (v_1 − v_2) = ((r_1 − r_2) × F) · ω whatever v_A; the work over a
    # small turn δφ = ω dt is work_of_couple(M, ω dt).
    v1, v2 = np.cross(omega, r1), np.cross(omega, r2)
    P = float(me.power(np.stack([F, -F]), np.stack([v1, v2])))
    M = np.cross(r1 - r2, F)
    scale = float(np.abs(F).sum() * np.abs(omega).sum() * (np.abs(r1).sum() + np.abs(r2).sum()))
    assert abs(P - float(M @ omega)) <= POWER_TOL * scale + UNDERFLOW_FLOOR
    dt = 1e-3
    W = float(me.work_of_couple(M, omega * dt))
    assert abs(W - P * dt) <= POWER_TOL * scale * dt + UNDERFLOW_FLOOR


# --------------------------------------------------------------- along a motion


@st.composite
def spring_systems(draw, driven=True):
    """2–4 particles near tetrahedron vertices joined by springs of natural
    lengths 0.8–1.2 of their initial distances: no collision within t ≤ 1."""
    n = draw(st.integers(2, 4))
    m = np.array(draw(st.lists(st.floats(0.1, 10.0), min_size=n, max_size=n)))
    base = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [-1.0, -1.0, -1.0]])[:n]
    r = base + draw(_arrays((n, 3), 0.2))
    v = draw(_arrays((n, 3), 0.5))
    k = np.triu(0.1 + 1.9 * np.abs(draw(_arrays((n, n), 1.0))), 1)
    k = k + k.T
    d0 = np.linalg.norm(r[:, None] - r[None, :], axis=-1)
    ell = np.triu(d0 * (1.0 + 0.2 * draw(_arrays((n, n), 1.0))), 1)
    ell = ell + ell.T
    A = draw(_arrays((n, 3), 1.0)) if driven else np.zeros((n, 3))
    w = draw(st.floats(0.5, 3.0))
    return m, r, v, k, ell, np.array([0.0, 0.0, -9.81]), A, w


def _spring_forces(r, k, ell):
    n = len(r)
    i, j = np.triu_indices(n, 1)
    fij = me.spring_force(k[i, j], ell[i, j], r[i], r[j])  # on i from j
    F = np.zeros_like(r)
    np.add.at(F, i, fij)
    np.add.at(F, j, -fij)
    return F


def _spring_energy(r, k, ell):
    i, j = np.triu_indices(len(r), 1)
    return float(me.spring_potential(k[i, j], ell[i, j], r[i], r[j]).sum())


def _simulate(setup, t_end):
    """DOP853; the state carries ∫P_total dt, ∫P_external dt and ∫P_driving dt."""
    m, r0, v0, k, ell, g, A, w = setup
    n = len(m)

    def rhs(t, y):
        r = y[: 3 * n].reshape(n, 3)
        v = y[3 * n : 6 * n].reshape(n, 3)
        drive = A * np.cos(w * t)
        Fe = m[:, None] * g + drive
        F = Fe + _spring_forces(r, k, ell)
        works = [np.sum(F * v), np.sum(Fe * v), np.sum(drive * v)]
        return np.concatenate([v.ravel(), (F / m[:, None]).ravel(), works])

    y0 = np.concatenate([r0.ravel(), v0.ravel(), np.zeros(3)])
    sol = solve_ivp(rhs, (0.0, t_end), y0, method="DOP853", rtol=SIM_RTOL, atol=SIM_RTOL)
    assert sol.success
    y = sol.y[:, -1]
    return y[: 3 * n].reshape(n, 3), y[3 * n : 6 * n].reshape(n, 3), y[6 * n :]


def _energy_scale(setup, r, v):
    m, _, _, k, ell, g, _, _ = setup
    T = float(mp.kinetic_energy(m, v))
    return T + abs(float(me.gravity_potential(m, r, g=g))) + _spring_energy(r, k, ell) + 1.0


@settings(max_examples=8)
@given(spring_systems(), st.floats(0.3, 1.0))
def test_change_of_kinetic_energy_equals_the_work_of_all_forces_internal_included(setup, t_end):
    # (3.36)–(3.37), (3.43): ΔT = W^e + W^i along the motion.
    m, r0, v0, k, ell = setup[:5]
    r, v, (W, W_e, _) = _simulate(setup, t_end)
    dT = float(mp.kinetic_energy(m, v) - mp.kinetic_energy(m, v0))
    tol = SIM_TOL * _energy_scale(setup, r, v)
    assert abs(dT - W) <= tol
    # The internal work is the decrease of the internal potential energy (3.51):
    # so ΔT − W^e = −ΔΦ^i, and leaving the internal work out fails whenever the
    # springs' energy changed (the negative control).
    dPhi_i = _spring_energy(r, k, ell) - _spring_energy(r0, k, ell)
    assert abs((dT - W_e) + dPhi_i) <= tol
    if abs(dPhi_i) > 1e3 * tol:
        assert abs(dT - W_e) > tol


@settings(max_examples=8)
@given(spring_systems(driven=False), st.floats(0.3, 1.0))
def test_mechanical_energy_is_conserved_when_all_forces_are_conservative(setup, t_end):
    # (3.58)–(3.59): E_m = T + Φ^e + Φ^i is constant (gravity and springs only).
    m, r0, v0, k, ell, g = setup[:6]
    r, v, _ = _simulate(setup, t_end)

    def E(r, v):
        return (
            float(mp.kinetic_energy(m, v))
            + float(me.gravity_potential(m, r, g=g))
            + _spring_energy(r, k, ell)
        )

    assert abs(E(r, v) - E(r0, v0)) <= SIM_TOL * _energy_scale(setup, r, v)


@settings(max_examples=8)
@given(spring_systems(), st.floats(0.3, 1.0))
def test_mechanical_energy_changes_by_the_work_of_the_non_conservative_forces(setup, t_end):
    # (3.58): ΔE_m = W^en, the work of the time-dependent drive A cos(w t).
    m, r0, v0, k, ell, g = setup[:6]
    r, v, (_, _, W_en) = _simulate(setup, t_end)

    def E(r, v):
        return (
            float(mp.kinetic_energy(m, v))
            + float(me.gravity_potential(m, r, g=g))
            + _spring_energy(r, k, ell)
        )

    assert abs(E(r, v) - E(r0, v0) - W_en) <= SIM_TOL * _energy_scale(setup, r, v)
