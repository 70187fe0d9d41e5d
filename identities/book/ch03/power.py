"""Chapter 3.1–3.2: power, kinetic energy and work of particle systems.
Equations (3.1)–(3.7) and (3.36)–(3.59).

Particle systems are general: N = 3 particles with positive symbolic masses and
free symbolic positions, velocities and forces (every identity here is a sum of
per-particle or per-pair terms, so three particles exhibit every kind of term: a
particle, a pair, a pair not involving a given particle).  Motions are undefined
functions of time; after differentiation they become independent symbols
(:func:`identities.verify.proof.is_zero`), which keeps ``expand``/``cancel`` fast.

Numeric routes go through :mod:`mechanics` (``mechanics.energy``,
``mechanics.particles``) and through an independent numpy/scipy computation: a
simulation of the equations of motion with the power integrated alongside.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import functions_of_time, t, vec
from mechanics import energy as en
from mechanics import particles as pt
from mechanics._floats import EPS

__all__ = ["EPS", "particle_system"]

#: a float evaluation of sums of a few products of O(1) numbers: 64 eps.
NUM_ATOL = 64 * EPS
#: relative tolerance requested of solve_ivp (DOP853) in the simulations: 2^16 eps ≈ 1.5e-11.
ODE_RTOL = 2**16 * EPS
#: composite Simpson on 501 samples (h = 0.01, spring periods ≈ 0.5) of the power:
#: relative error O((h ω)⁴/180), measured 1e-8 of the energy scale; 2^30 eps ≈ 2.4e-7.
SIMPSON_RTOL = 2**30 * EPS
#: an energy balance along the simulation, relative to the largest kinetic energy:
#: the global error of DOP853 at ODE_RTOL (measured 7e-13 relative) is bounded by
#: 2^16 eps ≈ 1.5e-11, a 20-fold margin for other platforms' libm.
ODE_CHECK = 2**16 * EPS

N = 3
HALF = sp.Rational(1, 2)


def particle_system(tag: str = "", n: int = N):
    """Masses m_k > 0 and free position, velocity symbols of n particles."""
    m = sp.symbols(f"m_1:{n + 1}{tag}", positive=True)
    r = [vec(*sp.symbols(f"x_{k}{tag} y_{k}{tag} z_{k}{tag}", real=True)) for k in range(1, n + 1)]
    v = [
        vec(*sp.symbols(f"vx_{k}{tag} vy_{k}{tag} vz_{k}{tag}", real=True)) for k in range(1, n + 1)
    ]
    return m, r, v


def _kinetic(m, v) -> sp.Expr:
    """(3.2): T = Σ ½ m_k v_k · v_k."""
    return sum((HALF * mk * vk.dot(vk) for mk, vk in zip(m, v, strict=True)), sp.S.Zero)


def _trajectories(n: int = N) -> list[sp.Matrix]:
    return [sp.Matrix(functions_of_time(f"x{k}", f"y{k}", f"z{k}")) for k in range(1, n + 1)]


@check(
    "eq3.4",
    "Power equals the rate of change of kinetic energy",
    kind="proof",
    covers=("eq3.3", "eq3.4"),
    defines=("eq3.1", "eq3.2"),
    statement="with P = Σ F_k · v_k (3.1), T = Σ ½ m_k v_k² (3.2) and m_k a_k = F_k: "
    "dT_k/dt = F_k · v_k (3.3) and P = dT/dt (3.4)",
)
def power_is_rate_of_kinetic_energy(d: Derivation) -> None:
    m = sp.symbols("m_1:4", positive=True)
    r = _trajectories()
    v = [sp.diff(rk, t) for rk in r]
    F = [mk * sp.diff(vk, t) for mk, vk in zip(m, v, strict=True)]  # Newton: F_k = m_k a_k
    T = _kinetic(m, v)
    P = sum((Fk.dot(vk) for Fk, vk in zip(F, v, strict=True)), sp.S.Zero)
    Tk = HALF * m[0] * v[0].dot(v[0])
    d.prove_equal(
        sp.diff(Tk, t), F[0].dot(v[0]), strategy="expand", claim="dT_k/dt = F_k·v_k (3.3)"
    )
    d.prove_equal(sp.diff(T, t), P, strategy="expand", claim="P = dT/dt (3.4)")
    d.reject(sp.diff(T, t), 2 * P, strategy="expand", claim="dT/dt = 2P (the ½ dropped)")
    # numeric: three particles, springs, gravity and drag; P integrated alongside
    sim = _simulate_system()
    d.confirm(
        sim["W"][-1],
        sim["T"][-1] - sim["T"][0],
        atol=ODE_CHECK * sim["scale"],
        route="scipy simulation: ∫ P dt of all forces = T(t2) - T(t1) (springs, gravity, drag)",
    )
    d.confirm(
        sim["T_mechanics"] / sim["T"],
        np.ones_like(sim["T"]),
        atol=NUM_ATOL,
        route="mechanics.particles.kinetic_energy along the simulated motion (relative)",
    )
    P_mech = [en.power(F, v) for F, v in zip(sim["F"], sim["v"], strict=True)]
    d.confirm(
        en.work_from_power(np.array(P_mech), sim["t"]),
        sim["W"][-1],
        atol=SIMPSON_RTOL * sim["scale"],
        route="mechanics.energy.power sampled along the motion, mechanics.energy.work_from_power",
    )


@check(
    "eq3.7",
    "König's theorem: T = ½ m v_G² + T′",
    kind="proof",
    covers=("eq3.5", "eq3.6", "eq3.7"),
    statement="with v_k = v_G + v′_k and v_G = Σ m_k v_k / m: T = ½ m v_G² + Σ ½ m_k v′_k², "
    "the middle term of (3.6) vanishing by Σ m_k v′_k = 0 (1.10)",
)
def koenig(d: Derivation) -> None:
    m, _, v = particle_system()
    M = sum(m)
    vG = sum((mk * vk for mk, vk in zip(m, v, strict=True)), sp.zeros(3, 1)) / M
    vp = [vk - vG for vk in v]
    T = _kinetic(m, v)
    Tp = _kinetic(m, vp)
    middle = vG.dot(sum((mk * vpk for mk, vpk in zip(m, vp, strict=True)), sp.zeros(3, 1)))
    d.prove_equal(
        T,
        HALF * vG.dot(vG) * M + middle + Tp,
        strategy="together",
        claim="(3.5) = (3.6): T = ½ v_G² Σm_k + v_G · Σ m_k v′_k + Σ ½ m_k v′_k²",
    )
    d.prove_zero(middle, strategy="together", claim="the middle term vanishes: Σ m_k v′_k = 0")
    d.prove_equal(T, HALF * M * vG.dot(vG) + Tp, strategy="together", claim="König (3.7)")
    d.reject(T, M * vG.dot(vG) + Tp, strategy="together", claim="T = m v_G² + T′ (no ½)")
    d.reject(T, HALF * M * vG.dot(vG), strategy="together", claim="T = ½ m v_G² (T′ dropped)")
    # numeric: a large common velocity on top of small internal motions
    rng = np.random.default_rng(3)
    mn = rng.uniform(0.5, 2.0, 5)
    vn = rng.normal(size=(5, 3)) + np.array([1e3, -2e3, 5e2])
    vGn = (mn[:, None] * vn).sum(axis=0) / mn.sum()
    Tn = 0.5 * np.sum(mn * np.sum(vn * vn, axis=1))
    Tp_n = 0.5 * np.sum(mn * np.sum((vn - vGn) ** 2, axis=1))
    parts = 0.5 * mn.sum() * vGn @ vGn + Tp_n
    # T ≈ 1e7 here: a sum of 5 squares of size 1e6 rounds at ~8 ulp of T
    d.confirm(
        parts / Tn,
        1.0,
        atol=NUM_ATOL,
        route="numpy: ½ m v_G² + T′ over T for 5 particles moving at 2e3 with O(1) internal motion",
    )
    T_int, T_cm = pt.kinetic_energy_decomposition(mn, vn)
    d.confirm(
        [T_int / Tp_n, T_cm / (0.5 * mn.sum() * vGn @ vGn)],
        [1.0, 1.0],
        atol=NUM_ATOL,
        route="mechanics.particles.kinetic_energy_decomposition: T′ and ½ m v_G² (relative)",
    )


# ----------------------------------------------------------------------- work


def _poly_path(tag: str, deg: int = 3) -> sp.Matrix:
    """A general polynomial path of degree ``deg`` in t (free vector coefficients)."""
    cs = [
        vec(*sp.symbols(f"a{i}x_{tag} a{i}y_{tag} a{i}z_{tag}", real=True)) for i in range(deg + 1)
    ]
    return sum((c * t**i for i, c in enumerate(cs)), sp.zeros(3, 1))


@check(
    "eq3.37",
    "The work–energy theorem: W_12 = T(t2) - T(t1)",
    kind="proof",
    covers=("eq3.37", "eq3.38", "eq3.39"),
    defines=("eq3.36",),
    statement="W_12 = ∫ P dt (3.36) equals T(t2) - T(t1) (3.37); as line integrals ∫ F_k · dr_k "
    "(3.38) it does not depend on how the configuration-space curve is traversed (3.39)",
)
def work_energy_theorem(d: Derivation) -> None:
    m = sp.symbols("m_1:3", positive=True)
    t1, t2 = sp.symbols("t_1 t_2", real=True)
    r = [_poly_path("1"), _poly_path("2")]
    v = [sp.diff(rk, t) for rk in r]
    P = sum((mk * sp.diff(vk, t).dot(vk) for mk, vk in zip(m, v, strict=True)), sp.S.Zero)
    W = sp.integrate(sp.expand(P), (t, t1, t2))
    T = _kinetic(m, v)
    d.prove_equal(
        W,
        T.subs(t, t2) - T.subs(t, t1),
        strategy="expand",
        claim="∫_{t1}^{t2} P dt = T(t2) - T(t1) (3.37) for two particles on general cubic paths",
    )
    d.note("for any motion: P = dT/dt (3.4) and the fundamental theorem of calculus")
    d.reject(W, T.subs(t, t2) + T.subs(t, t1), strategy="expand", claim="W_12 = T(t2) + T(t1)")
    # (3.38)-(3.39): a position-dependent, non-conservative force field along a path r(s),
    # traversed in time as s = t^2 (t from 0 to 1) or s = t: the same line integral
    s = sp.Symbol("s", real=True)
    c1, c2, c3 = sp.symbols("c_1 c_2 c_3", real=True)

    def F(x):
        return vec(-c1 * x[1] + c2 * x[2] ** 2, c1 * x[0], c3 * x[0] * x[1])

    path = _poly_path("s", deg=2).subs(t, s)
    line = sp.integrate(sp.expand(F(path).dot(sp.diff(path, s))), (s, 0, 1))
    timed = path.subs(s, t**2)
    in_time = sp.integrate(sp.expand(F(timed).dot(sp.diff(timed, t))), (t, 0, 1))
    d.prove_equal(
        in_time,
        line,
        strategy="expand",
        claim="∫ F·v dt = ∫_C F·dr, whatever the timing along C (3.38)-(3.39)",
    )
    backwards = sp.integrate(sp.expand(F(path).dot(sp.diff(path, s))), (s, 1, 0))
    d.reject(in_time, backwards, strategy="expand", claim="the curve traversed backwards")
    sim = _simulate_system()
    d.confirm(
        sim["W"][-1],
        sim["T"][-1] - sim["T"][0],
        atol=ODE_CHECK * sim["scale"],
        route="scipy simulation: accumulated ∫ P dt against the change of T",
    )


@check(
    "eq3.46",
    "Internal work depends only on relative displacements",
    kind="proof",
    covers=("eq3.42", "eq3.43", "eq3.44", "eq3.45", "eq3.46"),
    defines=("eq3.40", "eq3.41"),
    statement="with F_k = F^e_k + Σ_j f_kj and f_jk = -f_kj: "
    "Σ_k Σ_j f_kj · dr_k = ½ Σ_kj f_kj · d(r_k - r_j)",
)
def internal_work(d: Derivation) -> None:
    f = {}
    for k in range(1, N + 1):
        for j in range(k + 1, N + 1):
            f[k, j] = vec(*sp.symbols(f"f{k}{j}x f{k}{j}y f{k}{j}z", real=True))
            f[j, k] = -f[k, j]  # Newton's third law
        f[k, k] = sp.zeros(3, 1)
    dr = [None] + [vec(*sp.symbols(f"dx_{k} dy_{k} dz_{k}", real=True)) for k in range(1, N + 1)]
    Fe = [None] + [vec(*sp.symbols(f"Fe{k}x Fe{k}y Fe{k}z", real=True)) for k in range(1, N + 1)]
    idx = range(1, N + 1)
    Fi = {k: sum((f[k, j] for j in idx), sp.zeros(3, 1)) for k in idx}  # (3.42)
    total = sum(((Fe[k] + Fi[k]).dot(dr[k]) for k in idx), sp.S.Zero)
    We = sum((Fe[k].dot(dr[k]) for k in idx), sp.S.Zero)
    Wi = sum((f[k, j].dot(dr[k]) for k in idx for j in idx), sp.S.Zero)
    d.prove_equal(total, We + Wi, strategy="expand", claim="dW = dW^e + dW^i (3.43)")
    sym = HALF * sum((f[k, j].dot(dr[k]) + f[j, k].dot(dr[j]) for k in idx for j in idx), sp.S.Zero)
    d.prove_equal(Wi, sym, strategy="expand", claim="symmetrised double sum (3.44)-(3.45)")
    rel = HALF * sum((f[k, j].dot(dr[k] - dr[j]) for k in idx for j in idx), sp.S.Zero)
    d.prove_equal(Wi, rel, strategy="expand", claim="dW^i = ½ Σ f_kj · dr_kj (3.45)-(3.46)")
    # negative control: without the third law the internal work is not relative
    g = {
        (k, j): vec(*sp.symbols(f"g{k}{j}x g{k}{j}y g{k}{j}z", real=True)) for k in idx for j in idx
    }
    Wg = sum((g[k, j].dot(dr[k]) for k in idx for j in idx if k != j), sp.S.Zero)
    relg = HALF * sum((g[k, j].dot(dr[k] - dr[j]) for k in idx for j in idx if k != j), sp.S.Zero)
    d.reject(Wg, relg, strategy="expand", claim="the same without f_jk = -f_kj")
    # numeric: a common translation of all particles does no internal work
    rng = np.random.default_rng(5)
    fn = rng.normal(size=(N, N, 3))
    fn = fn - np.swapaxes(fn, 0, 1)
    shift = rng.normal(size=3)
    d.confirm(
        np.einsum("kjx,x->", fn, shift),
        0.0,
        atol=NUM_ATOL,
        route="numpy: third-law pair forces do no work in a common displacement",
    )


def _spring_potential_sym(k, ell0, a, b):
    """½ k (|a - b| - ℓ_0)²."""
    return HALF * k * (sp.sqrt((a - b).dot(a - b)) - ell0) ** 2


@check(
    "eq3.54",
    "Work as decrease of external and internal potential energies plus non-conservative work",
    kind="proof",
    covers=("eq3.49", "eq3.50", "eq3.51", "eq3.54"),
    defines=("eq3.47", "eq3.48", "eq3.52", "eq3.53"),
    statement="F^e_k = -∇_k Φ_k + F^en_k, f_kj = -∇_kj Φ_kj(r_kj) + f^n_kj give "
    "dW = -dΦ^e - dΦ^i + dW^en + dW^in with Φ^e = Σ Φ_k, Φ^i = ½ Σ Φ_kj",
)
def work_decomposition(d: Derivation) -> None:
    r = _trajectories()
    v = [sp.diff(rk, t) for rk in r]
    X = sp.symbols("X Y Z", real=True)
    Phi = [sp.Function(f"Phi_{k}") for k in range(1, N + 1)]

    def grad(fn, rk):
        return vec(*[sp.diff(fn(*X), x).subs(dict(zip(X, rk, strict=True))) for x in X])

    Phi_e = sum((Phi[k](*r[k]) for k in range(N)), sp.S.Zero)  # (3.52)
    Pe = sum((-grad(Phi[k], r[k]).dot(v[k]) for k in range(N)), sp.S.Zero)
    d.prove_equal(
        Pe,
        -sp.diff(Phi_e, t),
        strategy="expand",
        claim="Σ -∇_k Φ_k · v_k = -dΦ^e/dt, general Φ_k: its integral is -[Φ^e(2) - Φ^e(1)] (3.49)-(3.50)",
    )
    d.reject(Pe, sp.diff(Phi_e, t), strategy="expand", claim="the conservative power is +dΦ^e/dt")
    # internal: a linear spring between a pair k, j; Φ^i and W^i are sums over pairs, so
    # the pair identity gives (3.51) for any number of particles and springs
    rk, rj = _trajectories(2)
    vk, vj = sp.diff(rk, t), sp.diff(rj, t)
    k, ell = sp.symbols("k_kj ell_kj", positive=True)
    R = sp.symbols("R_x R_y R_z", real=True)
    phi = _spring_potential_sym(k, ell, vec(*R), sp.zeros(3, 1))  # Φ_kj(r_kj)
    grad_phi = vec(*[sp.diff(phi, x) for x in R])

    def at(expr, rel):
        return expr.subs(dict(zip(R, rel, strict=True)))

    f_kj, f_jk = -at(grad_phi, rk - rj), -at(grad_phi, rj - rk)  # (3.48), conservative part
    d.prove_equal(f_jk, -f_kj, strategy="cancel", claim="the spring pair forces obey f_jk = -f_kj")
    Phi_i = HALF * (at(phi, rk - rj) + at(phi, rj - rk))  # (3.53): both orders of the pair
    Pi = HALF * (f_kj.dot(vk - vj) + f_jk.dot(vj - vk))  # (3.46) for this pair
    d.prove_equal(
        Pi,
        -sp.diff(Phi_i, t),
        strategy="cancel",
        claim="½ Σ f_kj · v_kj = -dΦ^i/dt for a spring pair; summed over pairs (3.51)",
    )
    d.reject(
        Pi,
        -2 * sp.diff(Phi_i, t),
        strategy="cancel",
        claim="Φ^i without the ½ of (3.53) (each pair counted twice)",
    )
    d.note(
        "(3.54): dW = dW^e + dW^i (3.43) with the conservative parts just proved; the "
        "non-conservative parts F^en, f^n_kj are carried as W^en, W^in"
    )
    sim = _simulate_system()
    balance = sim["T"] + sim["Phi_e"] + sim["Phi_i"] - sim["W_n"]
    d.confirm(
        balance - balance[0],
        np.zeros_like(balance),
        atol=ODE_CHECK * sim["scale"],
        route="scipy simulation: T + Φ^e + Φ^i - W^en stays constant (3.54) along the motion",
    )


@check(
    "eq3.58",
    "The change of mechanical energy is the non-conservative work",
    kind="proof",
    covers=("eq3.58",),
    defines=("eq3.59",),
    statement="equating (3.37) and (3.54): [T + Φ^e + Φ^i](2) - [T + Φ^e + Φ^i](1) = "
    "W^en + W^in, i.e. ΔE_m = W^en + W^in with E_m = T + Φ^e + Φ^i",
)
def mechanical_energy_balance(d: Derivation) -> None:
    T1, T2, E1, E2, I1, I2, Wen, Win = sp.symbols(
        "T_1 T_2 Phi^e_1 Phi^e_2 Phi^i_1 Phi^i_2 W^en W^in", real=True
    )
    W = -(E2 - E1) + Wen - (I2 - I1) + Win  # (3.54)
    T2_sol = sp.solve(sp.Eq(T2 - T1, W), T2)[0]  # (3.37) = (3.54)
    d.prove_equal(
        (T2_sol + E2 + I2) - (T1 + E1 + I1),
        Wen + Win,
        strategy="expand",
        claim="(3.58) follows from (3.37) and (3.54)",
    )
    d.reject(
        (T2_sol + E2 + I2) - (T1 + E1 + I1),
        Wen - Win,
        strategy="expand",
        claim="the internal non-conservative work with the wrong sign",
    )
    sim = _simulate_system()
    Em = sim["T"] + sim["Phi_e"] + sim["Phi_i"]
    d.confirm(
        Em - Em[0],
        sim["W_n"],
        atol=ODE_CHECK * sim["scale"],
        route="scipy simulation: E_m(t) - E_m(0) = W^en(t) (drag) along the motion",
    )
    if abs(sim["W_n"][-1]) < sim["scale"] / 10:  # the drag must matter, or this shows nothing
        raise AssertionError("the simulated drag did not dissipate a tenth of the energy scale")
    sim0 = _simulate_system(drag=0.0)
    Em0 = sim0["T"] + sim0["Phi_e"] + sim0["Phi_i"]
    d.confirm(
        Em0 - Em0[0],
        np.zeros_like(Em0),
        atol=ODE_CHECK * sim0["scale"],
        route="scipy simulation without drag: E_m = const",
    )


# ------------------------------------------------------------- the simulation

_SIM_CACHE: dict[float, dict[str, np.ndarray]] = {}


def _simulate_system(drag: float = 0.3) -> dict[str, np.ndarray]:
    """Three particles joined by linear springs, under gravity and linear drag.

    The state carries the drag work W^en and the total work ∫ P dt as extra
    components, so they are integrated to the solver's accuracy.  Springs (internal,
    conservative), gravity (external, conservative) and drag (external,
    non-conservative) exercise every term of (3.54) except W^in.
    """
    if drag in _SIM_CACHE:
        return _SIM_CACHE[drag]
    m = np.array([1.0, 2.0, 0.5])
    k = {(0, 1): 30.0, (0, 2): 20.0, (1, 2): 45.0}
    ell0 = {(0, 1): 1.0, (0, 2): 1.2, (1, 2): 0.8}
    g = np.array([0.0, 0.0, -9.81])
    r0 = np.array([[0.0, 0.0, 1.0], [1.1, 0.2, 1.0], [0.3, 1.0, 1.3]])
    v0 = np.array([[0.5, 0.0, 2.0], [-0.2, 0.4, 0.0], [0.0, -1.0, 0.5]])

    def forces(r, v):
        F_cons = m[:, None] * g
        F = F_cons.copy()
        for (a, b), kab in k.items():
            rab = r[a] - r[b]
            dist = np.linalg.norm(rab)
            fab = -kab * (dist - ell0[a, b]) * rab / dist
            F[a] += fab
            F[b] -= fab
        F_drag = -drag * v
        return F + F_drag, F_drag

    def rhs(_, y):
        r, v = y[:9].reshape(3, 3), y[9:18].reshape(3, 3)
        F, F_drag = forces(r, v)
        return np.concatenate(
            [v.ravel(), (F / m[:, None]).ravel(), [np.sum(F_drag * v), np.sum(F * v)]]
        )

    y0 = np.concatenate([r0.ravel(), v0.ravel(), [0.0, 0.0]])
    ts = np.linspace(0.0, 5.0, 501)
    sol = solve_ivp(rhs, (0.0, 5.0), y0, method="DOP853", rtol=ODE_RTOL, atol=ODE_RTOL, t_eval=ts)
    r = sol.y[:9].T.reshape(-1, 3, 3)
    v = sol.y[9:18].T.reshape(-1, 3, 3)
    T = 0.5 * np.einsum("k,nkx,nkx->n", m, v, v)
    Phi_e = -np.einsum("k,x,nkx->n", m, g, r)  # (3.55)-(3.56)
    Phi_i = np.zeros_like(T)
    for (a, b), kab in k.items():
        Phi_i += 0.5 * kab * (np.linalg.norm(r[:, a] - r[:, b], axis=1) - ell0[a, b]) ** 2
    out = {"T": T, "Phi_e": Phi_e, "Phi_i": Phi_i, "W_n": sol.y[18], "W": sol.y[19]}
    out["scale"] = float(np.max(T))
    out["T_mechanics"] = pt.kinetic_energy(m, v)  # vectorised over the time samples
    out["t"], out["v"] = ts, v
    out["F"] = np.array([forces(rn, vn)[0] for rn, vn in zip(r, v, strict=True)])
    _SIM_CACHE[drag] = out
    return out
