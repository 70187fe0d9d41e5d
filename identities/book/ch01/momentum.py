"""Chapter 1.1, 1.3, 1.4: momentum of particle systems, the elimination of the
internal forces, impulse, and continuous mass distributions.  Equations (1.1)–(1.7),
(1.16)–(1.24), (1.39), (1.41), (1.54)–(1.57), (1.62)–(1.64).

Particle systems are general: N = 4 particles with positive symbolic masses and
positions that are arbitrary (undefined) functions of time.  Pair forces obey
Newton's third law by construction: f_jk is a free symbol for j < k and
f_kj = −f_jk.  Newton's law m_j r̈_j = F_j is imposed by replacing each second
derivative by F_j/m_j, so a proof holds for every motion the forces allow.  A
"wrong variant" (forces without the third law, an unweighted centroid) is the
negative control.

The numeric routes use :mod:`mechanics.particles` where it exists (``total_mass``,
``centre_of_mass``, ``momentum``, ``angular_momentum``, ``moment_of_forces``) and
plain numpy otherwise; the route text says which one ran.  A scipy simulation of
four particles with spring (central) pair forces and an external force pulse
(cached, shared with :mod:`identities.book.ch01.angular_momentum`) checks the
integrated principles.
"""

from __future__ import annotations

from functools import cache
from itertools import combinations

import numpy as np
import sympy as sp
from sympy import QQ
from sympy.polys.rings import ring

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, floats, functions_of_time, t, vec
from mechanics import particles
from mechanics._floats import EPS

#: a float evaluation of a closed form vs mechanics: sums of a few products of O(10)
#: numbers (lengths ≤ 3, masses ≤ 3, speeds ≤ 3): a few roundings of numbers ≤ 100.
CODE_ATOL = 256 * EPS
#: the DOP853 simulation at rtol = atol = 1e-13 over t ∈ [0, 4]: measured errors of
#: Δp - I ≈ 1e-13 and ΔL_O - H_O ≈ 6e-13 for |L_O| ≤ 115; 2**16 eps ≈ 1.5e-11 leaves margin.
SIM_ATOL = 2**16 * EPS
N = 4  # particles in the symbolic systems: every pair and every triple of indices occurs


# ---------------------------------------------------------------- symbolic systems


def masses(n: int = N) -> list[sp.Symbol]:
    return list(sp.symbols(f"m_1:{n + 1}", positive=True))


def positions(n: int = N, tag: str = "") -> list[sp.Matrix]:
    """r_j(t) = (x_j(t), y_j(t), z_j(t)), arbitrary functions of time."""
    return [
        vec(*functions_of_time(f"x{tag}_{j}", f"y{tag}_{j}", f"z{tag}_{j}"))
        for j in range(1, n + 1)
    ]


def d_dt(rs: list[sp.Matrix]) -> list[sp.Matrix]:
    return [sp.diff(r, t) for r in rs]


def pair_forces(
    n: int = N, *, kind: str, r: list[sp.Matrix] | None = None
) -> dict[tuple[int, int], sp.Matrix]:
    """f[j, k]: the force on particle j from particle k (1.17), with f[j, j] = 0.

    ``kind``: ``"third-law"`` (f_kj = −f_jk, otherwise free), ``"central"``
    (f_jk = φ_jk (r_j − r_k), φ_jk = φ_kj free: the strong form), ``"non-central"``
    (f_jk = ψ_jk e_z × (r_j − r_k): third law, not central) or ``"free"`` (no law).
    """
    f = {(j, j): sp.zeros(3, 1) for j in range(n)}
    for j, k in combinations(range(n), 2):
        if kind == "free":
            f[j, k] = vec(*sp.symbols(f"f_{j + 1}{k + 1}x:z", real=True))
            f[k, j] = vec(*sp.symbols(f"f_{k + 1}{j + 1}x:z", real=True))
            continue
        if kind == "third-law":
            fjk = vec(*sp.symbols(f"f_{j + 1}{k + 1}x:z", real=True))
        elif kind == "central":
            fjk = sp.Symbol(f"phi_{j + 1}{k + 1}", real=True) * (r[j] - r[k])
        elif kind == "non-central":
            fjk = sp.Symbol(f"psi_{j + 1}{k + 1}", real=True) * cross(vec(0, 0, 1), r[j] - r[k])
        else:
            raise ValueError(f"unknown pair-force kind {kind!r}")
        f[j, k], f[k, j] = fjk, -fjk
    return f


def internal_forces(f: dict, n: int = N) -> list[sp.Matrix]:
    """F^i_j = Σ_k f_jk (1.18)."""
    return [sum((f[j, k] for k in range(n)), sp.zeros(3, 1)) for j in range(n)]


def external_forces(n: int = N) -> list[sp.Matrix]:
    return [vec(*sp.symbols(f"F_{j}x:z", real=True)) for j in range(1, n + 1)]


def newton(expr, m, r, F):
    """Impose m_j r̈_j = F_j: every second derivative of r_j becomes F_j/m_j."""
    reps = {}
    for mj, rj, Fj in zip(m, r, F, strict=True):
        for i in range(3):
            reps[sp.diff(rj[i], t, 2)] = Fj[i] / mj
    return (
        sp.Matrix(expr).xreplace(reps) if isinstance(expr, sp.MatrixBase) else expr.xreplace(reps)
    )


def msum(vectors) -> sp.Matrix:
    return sum(vectors, sp.zeros(3, 1))


def at_point(expr, rs, values: np.ndarray, rates: np.ndarray):
    """Evaluate an expression in r_j(t), ṙ_j(t) at given positions and velocities."""
    reps = {}
    for rj, pos, vel in zip(rs, values, rates, strict=True):
        for i in range(3):
            reps[sp.diff(rj[i], t)] = sp.Rational(vel[i])
            reps[rj[i]] = sp.Rational(pos[i])
    expr = sp.Matrix(expr)
    return expr.xreplace({k: v for k, v in reps.items() if isinstance(k, sp.Derivative)}).xreplace(
        reps
    )


# ------------------------------------------------------------------ numeric routes


def num_total_mass(m) -> tuple[float, str]:
    return particles.total_mass(m), "mechanics.particles.total_mass"


def num_momentum(m, v) -> tuple[np.ndarray, str]:
    return particles.momentum(m, v), "mechanics.particles.momentum"


def num_centre_of_mass(m, r) -> tuple[np.ndarray, str]:
    return particles.centre_of_mass(m, r), "mechanics.particles.centre_of_mass"


def num_centre_of_mass_velocity(m, v) -> tuple[np.ndarray, str]:
    return (
        particles.centre_of_mass_velocity(m, v),
        "mechanics.particles.centre_of_mass_velocity",
    )


def num_angular_momentum(m, r, v, about) -> tuple[np.ndarray, str]:
    return particles.angular_momentum(m, r, v, about=about), "mechanics.particles.angular_momentum"


def num_moment_of_forces(r, F, about) -> tuple[np.ndarray, str]:
    return particles.moment_of_forces(r, F, about=about), "mechanics.particles.moment_of_forces"


#: the rational test point for numeric routes: 4 particles, exact binary fractions
M_NUM = np.array([1.0, 2.5, 0.75, 3.0])
R_NUM = np.array([[1.0, -2.0, 0.5], [0.25, 1.5, -1.0], [-3.0, 0.5, 2.0], [2.0, 2.0, -0.5]])
V_NUM = np.array([[0.5, 1.0, -1.5], [-2.0, 0.25, 1.0], [1.0, -1.0, 0.0], [0.0, 3.0, 0.5]])


# ------------------------------------------------------------------ the simulation

SIM_MASSES = np.array([1.0, 2.0, 0.5, 3.0])
SIM_T = 4.0
#: samples of the simulation on [0, SIM_T]: h = 0.005, fine enough that Simpson's rule
#: over the force pulse (width 0.4) errs by ~ h⁴/180 · max|f⁗| · T ≈ 1e-7 of its scale.
SIM_SAMPLES = 801
#: Simpson's rule on SIM_SAMPLES samples of smooth integrands of size ≲ 10 (the pulse
#: moments): the bound above, ≈ 1e-7; 2**30 eps ≈ 2.4e-7.
QUADRATURE_ATOL = 2**30 * EPS


def _pulse(tt):
    """The external force on particle 1: a Gaussian pulse F0 exp(−((t − t0)/w)²)."""
    return np.array([3.0, -1.0, 2.0]) * np.exp(-(((tt - 1.5) / 0.4) ** 2))


SIM_GRAVITY = np.array([0.0, 0.0, -9.81])


@cache
def simulate(*, external: bool, noncentral: float) -> dict:
    """Four particles joined pairwise by springs (central forces, third law), plus, if
    ``noncentral`` ≠ 0, pair forces ψ e_z × (r_j − r_k) (third law, not central);
    with ``external``, uniform gravity and a force pulse on particle 1.  The state carries
    the running external impulse I(t) and angular impulse H_O(t) (1.55), (1.59)."""
    from scipy.integrate import solve_ivp

    m = SIM_MASSES
    n = len(m)
    k = np.array([[0, 5, 3, 2], [5, 0, 4, 6], [3, 4, 0, 1], [2, 6, 1, 0]], dtype=float)
    rest = np.full((n, n), 1.5)
    ez = np.array([0.0, 0.0, 1.0])
    r0 = np.array([[1.0, 0.0, 0.0], [-0.5, 1.0, 0.2], [0.0, -1.0, 0.5], [0.3, 0.2, -1.0]])
    v0 = np.array([[0.0, 1.0, 0.0], [0.5, 0.0, -0.3], [-1.0, 0.2, 0.0], [0.0, -0.4, 0.6]])

    def forces(tt, r):
        d = r[:, None, :] - r[None, :, :]  # r_j - r_k
        dist = np.linalg.norm(d, axis=-1) + np.eye(n)
        f = (-k * (dist - rest) / dist)[..., None] * d  # f_jk = φ_jk (r_j - r_k), φ symmetric
        f = f + noncentral * np.cross(ez, d)  # ψ e_z × (r_j - r_k): antisymmetric in j, k
        Fi = f.sum(axis=1)
        Fe = np.zeros_like(r)
        if external:
            Fe = Fe + m[:, None] * SIM_GRAVITY
            Fe[0] += _pulse(tt)
        return Fi, Fe

    def rhs(tt, y):
        r, v = y[: 3 * n].reshape(n, 3), y[3 * n : 6 * n].reshape(n, 3)
        Fi, Fe = forces(tt, r)
        a = (Fi + Fe) / m[:, None]
        return np.concatenate([v.ravel(), a.ravel(), Fe.sum(axis=0), np.cross(r, Fe).sum(axis=0)])

    y0 = np.concatenate([r0.ravel(), v0.ravel(), np.zeros(6)])
    ts = np.linspace(0.0, SIM_T, SIM_SAMPLES)
    sol = solve_ivp(rhs, (0.0, SIM_T), y0, method="DOP853", rtol=1e-13, atol=1e-13, t_eval=ts)
    if not sol.success:
        raise RuntimeError(f"simulation failed: {sol.message}")
    Y = sol.y.T
    return {
        "t": ts,
        "m": m,
        "r": Y[:, : 3 * n].reshape(-1, n, 3),
        "v": Y[:, 3 * n : 6 * n].reshape(-1, n, 3),
        "I": Y[:, 6 * n : 6 * n + 3],
        "H_O": Y[:, 6 * n + 3 :],
    }


# ------------------------------------------------------------------------ checks


@check(
    "eq1.2",
    "The principles of momentum and angular momentum for one particle",
    kind="proof",
    covers=("eq1.2",),
    defines=("eq1.1",),
    statement="with ṗ = F (1.1), p = m v: d/dt (AP × m v) = AP × F for a base point A at rest",
)
def single_particle(d: Derivation) -> None:
    m = sp.Symbol("m", positive=True)
    (r,) = positions(1)
    A = vec(*sp.symbols("a_x a_y a_z", real=True))
    F = vec(*sp.symbols("F_x F_y F_z", real=True))
    L_A = cross(r - A, m * sp.diff(r, t))
    d.prove_equal(
        newton(sp.diff(L_A, t), [m], [r], [F]),
        cross(r - A, F),
        strategy="expand",
        claim="L̇_A = M_A = AP × F (1.2), A at rest",
    )
    (A_t,) = positions(1, tag="A")
    L_moving = cross(r - A_t, m * sp.diff(r, t))
    d.reject(
        newton(sp.diff(L_moving, t), [m], [r], [F]),
        cross(r - A_t, F),
        strategy="expand",
        claim="the same about a moving base point A(t)",
    )
    # numeric: a projectile, L_A(T) - L_A(0) against the time integral of AP × m g
    mn, g = 2.0, np.array([0.0, 0.0, -9.81])
    r0, v0, An, T = (
        np.array([0.0, 1.0, 0.0]),
        np.array([2.0, 0.0, 5.0]),
        np.array([1.0, 2.0, 3.0]),
        0.75,
    )
    rT, vT = r0 + v0 * T + 0.5 * g * T**2, v0 + g * T
    L0, route = num_angular_momentum([mn], r0[None], v0[None], An)
    LT, _ = num_angular_momentum([mn], rT[None], vT[None], An)
    # ∫_0^T (r(t) - A) × m g dt with r(t) = r0 + v0 t + g t²/2 (the g t² term is ∥ g)
    H = np.cross((r0 - An) * T + v0 * T**2 / 2, mn * g)
    d.confirm(LT - L0, H, atol=CODE_ATOL, route=f"{route}: ΔL_A of a projectile = ∫ AP × m g dt")


@check(
    "eq1.7",
    "The momentum of a system is total mass times centre-of-mass velocity",
    kind="proof",
    covers=("eq1.6", "eq1.7", "eq1.41"),
    defines=("eq1.3", "eq1.4", "eq1.5"),
    statement="p = Σ m_j v_j (1.3), m = Σ m_j (1.4), r_G = Σ m_j r_j / m (1.5) give p = m v_G",
)
def momentum_is_m_vG(d: Derivation) -> None:
    m, r = masses(), positions()
    v = d_dt(r)
    p = msum(mj * vj for mj, vj in zip(m, v, strict=True))  # (1.3)
    m_tot = sum(m)  # (1.4)
    r_G = msum(mj * rj for mj, rj in zip(m, r, strict=True)) / m_tot  # (1.5)
    v_G = sp.diff(r_G, t)
    d.prove_equal(p, m_tot * v_G, strategy="cancel", claim="p = m v_G (1.6)-(1.7), N = 4")
    centroid = msum(r) / N
    d.reject(
        p,
        m_tot * sp.diff(centroid, t),
        strategy="cancel",
        claim="p = m times the velocity of the unweighted centroid",
    )
    mt, route_m = num_total_mass(M_NUM)
    vg, route_v = num_centre_of_mass_velocity(M_NUM, V_NUM)
    p_num, route_p = num_momentum(M_NUM, V_NUM)
    p_sym = floats(at_point(m_tot * v_G, r, R_NUM, V_NUM).subs(dict(zip(m, M_NUM, strict=True))))
    d.confirm(p_num, p_sym.ravel(), atol=CODE_ATOL, route=f"{route_p} = m v_G evaluated")
    d.confirm(
        mt * np.asarray(vg), p_sym.ravel(), atol=CODE_ATOL, route=f"{route_m} × {route_v} = m v_G"
    )


@check(
    "eq1.24",
    "Internal forces cancel in the momentum principle",
    kind="proof",
    covers=("eq1.20", "eq1.21", "eq1.22", "eq1.23", "eq1.24", "eq1.39"),
    defines=("eq1.16", "eq1.17", "eq1.18", "eq1.19"),
    statement="F_k = F^i_k + F^e_k (1.16), F^i_k = Σ_j f_kj (1.18), f_jk = -f_kj (1.19): "
    "F^i = Σ F^i_j = 0 and ṗ = F^e, for any N = 4 forces obeying the third law",
)
def internal_forces_cancel(d: Derivation) -> None:
    m, r = masses(), positions()
    f = pair_forces(kind="third-law")
    Fi = internal_forces(f)
    Fe = external_forces()
    F = [a + b for a, b in zip(Fi, Fe, strict=True)]  # (1.16)
    p = msum(mj * vj for mj, vj in zip(m, d_dt(r), strict=True))
    pdot = newton(sp.diff(p, t), m, r, F)
    d.prove_equal(pdot, msum(F), strategy="cancel", claim="ṗ = Σ m_j r̈_j = Σ F_j (1.20)-(1.21)")
    d.prove_zero(msum(Fi), strategy="expand", claim="F^i = Σ_j Σ_k f_jk = 0 (1.22)-(1.23)")
    d.prove_equal(pdot, msum(Fe), strategy="cancel", claim="ṗ = F^e (1.24), (1.39)")
    d.reject(
        msum(internal_forces(pair_forces(kind="free"))),
        sp.zeros(3, 1),
        strategy="expand",
        claim="F^i = 0 for pair forces without the third law",
    )
    sim = simulate(external=False, noncentral=0.0)
    p_num, route = num_momentum(sim["m"], sim["v"])
    d.confirm(
        p_num - p_num[0],
        np.zeros_like(p_num),
        atol=SIM_ATOL,
        route=f"simulation of 4 particles with springs, no external force: {route} is constant",
    )


@check(
    "eq1.56",
    "Impulse: the change of momentum is the impulse of the external forces",
    kind="proof",
    covers=("eq1.54", "eq1.56", "eq1.57"),
    defines=("eq1.55",),
    statement="p(t2) - p(t1) = ∫ F^e dt = I (1.54)-(1.56); p constant when F^e = 0 (1.57)",
)
def impulse(d: Derivation) -> None:
    n = 3
    m = masses(n)
    v = [vec(*functions_of_time(f"u_{j}", f"v_{j}", f"w_{j}")) for j in range(1, n + 1)]
    t1, t2 = sp.symbols("t_1 t_2", real=True)
    f = {(j, j): sp.zeros(3, 1) for j in range(n)}
    for j, k in combinations(range(n), 2):  # pair forces as arbitrary functions of time
        f[j, k] = vec(*functions_of_time(*(f"f_{j + 1}{k + 1}{c}" for c in "xyz")))
        f[k, j] = -f[j, k]
    Fi = internal_forces(f, n)
    Fe = [m[j] * sp.diff(v[j], t) - Fi[j] for j in range(n)]  # the external force the motion needs

    def integral(e):  # term by term: ∫ m u̇ dt = m Δu, ∫ f(t) dt stays an Integral
        return sp.Add(*(sp.integrate(x, (t, t1, t2)) for x in sp.Add.make_args(sp.expand(e))))

    I = msum(fe.applyfunc(integral) for fe in Fe)  # (1.55), one external force at a time
    p = msum(mj * vj for mj, vj in zip(m, v, strict=True))
    d.prove_equal(
        p.subs(t, t2) - p.subs(t, t1),
        I,
        strategy="expand",
        claim="Δp = Σ_j ∫ F^e_j dt = I (1.54), (1.56), any motion, third-law pair forces",
    )
    d.prove_zero(
        sp.diff(p, t) - msum(Fe) - msum(Fi),
        strategy="expand",
        claim="F^e ≡ 0 makes ṗ = F^i = 0: p constant (1.57)",
    )
    g = {
        (j, k): vec(*functions_of_time(*(f"g_{j + 1}{k + 1}{c}" for c in "xyz")))
        for j in range(n)
        for k in range(n)
        if j != k
    }
    g.update({(j, j): sp.zeros(3, 1) for j in range(n)})
    Gi = internal_forces(g, n)
    Ge = [m[j] * sp.diff(v[j], t) - Gi[j] for j in range(n)]
    I_wrong = msum(fe.applyfunc(integral) for fe in Ge)
    d.reject(
        p.subs(t, t2) - p.subs(t, t1),
        I_wrong,
        strategy="expand",
        claim="Δp = I when the pair forces break the third law",
    )
    sim = simulate(external=True, noncentral=0.0)
    p_num, route = num_momentum(sim["m"], sim["v"])
    d.confirm(
        p_num - p_num[0],
        sim["I"],
        atol=SIM_ATOL,
        route=f"simulation (springs, gravity, force pulse): {route} changes by the integrated impulse",
    )
    from math import erf, pi, sqrt

    T = SIM_T
    I_exact = (
        np.array([3.0, -1.0, 2.0]) * 0.4 * sqrt(pi) / 2 * (erf((T - 1.5) / 0.4) + erf(1.5 / 0.4))
    )
    I_exact = I_exact + SIM_MASSES.sum() * SIM_GRAVITY * T
    d.confirm(
        p_num[-1] - p_num[0],
        I_exact,
        atol=SIM_ATOL,
        route="and by the closed-form impulse m g T + F0 w √π/2 (erf((T - t0)/w) + erf(t0/w))",
    )


def _box_integral(expr, a) -> sp.Expr:
    """∫ over the unit cube of a polynomial in the labels a (coefficients anything):
    the monomial a1^i a2^j a3^k integrates to 1/((i + 1)(j + 1)(k + 1))."""
    out = []
    for term in sp.Add.make_args(sp.expand(expr)):
        coeff, mono = term.as_independent(*a, as_Add=False)
        powers = mono.as_powers_dict()
        out.append(coeff / sp.prod([powers.get(x, 0) + 1 for x in a]))
    return sp.Add(*out)


def _instant(expr):
    """At one instant, r(t) and its rates are independent numbers: name them as symbols."""
    derivs = sorted(expr.atoms(sp.Derivative), key=str)
    expr = expr.xreplace({dv: sp.Symbol(f"{dv.expr.func}dot", real=True) for dv in derivs})
    funcs = sorted(expr.atoms(sp.Function), key=str)
    return expr.xreplace({f_: sp.Symbol(str(f_.func), real=True) for f_ in funcs})


@check(
    "thm.continuum-momentum",
    "Continuous mass distributions: p = m v_G and the decomposition of L_A",
    kind="proof",
    defines=("eq1.62", "eq1.63", "eq1.64"),
    statement="a body of material points labelled by a ∈ [0, 1]³ with density ρ0(a) and motion "
    "r(a, t): r_G = ∫ r dm/m (1.62), p = ∫ v dm (1.63) = m v_G, and "
    "L_A = ∫ (r - r_A) × v dm (1.64) = AG × m v_G + ∫ r' × v' dm, A at rest",
)
def continuum(d: Derivation) -> None:
    a = sp.symbols("a_1:4", real=True)
    c = sp.symbols("c_1:3", positive=True)
    rho = 1 + c[0] * a[0] + c[1] * a[1] * a[2]  # positive on the cube
    X = vec(*functions_of_time("X_1", "X_2", "X_3"))
    Q = [vec(*functions_of_time(*(f"q_{i}{j}" for j in (1, 2, 3)))) for i in (1, 2, 3)]
    r = X + Q[0] * a[0] + Q[1] * a[1] + Q[2] * a[2]  # a general affine motion: the body deforms
    v = sp.diff(r, t)

    def integral(field):
        return sp.Matrix(field).applyfunc(lambda e: _box_integral(e * rho, a))

    m = _box_integral(rho, a)
    S = integral(r)  # m r_G (1.62)
    p = integral(v)  # (1.63)
    d.prove_equal(p, m * sp.diff(S / m, t), strategy="cancel", claim="∫ v dm = m v_G")
    half = {x: sp.Rational(1, 2) for x in a}
    d.reject(
        p,
        m * sp.diff(r.subs(half), t),
        strategy="cancel",
        claim="p = m × the velocity of the cube's geometric centre (density ignored)",
    )
    A = vec(*sp.symbols("A_1:4", real=True))
    rI, vI = _instant(r), _instant(v)
    # the quadratic integrals in a sparse polynomial ring (fast), multiplied by m² to
    # stay polynomial: m r' = m r - S, m v' = m v - p
    gens = sorted(set().union(*(x.free_symbols for x in (rI, vI, A, rho))), key=str)
    R, *_ = ring(gens, QQ)
    ia = [gens.index(x) for x in a]

    def rvec(x):
        return [R.from_expr(sp.expand(e)) for e in x]

    def rcross(u, w):
        return [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]

    rho_R, m_R = R.from_expr(rho), R.from_expr(m)

    def r_integral(e):
        out = R.zero
        for mono, coeff in (e * rho_R).terms():
            k = list(mono)
            div = 1
            for i in ia:
                div, k[i] = div * (k[i] + 1), 0
            out += R({tuple(k): coeff / div})
        return out

    def expr(u):
        return vec(*(x.as_expr() for x in u))

    rR, vR, AR = rvec(rI), rvec(vI), rvec(A)
    SR, pR = [r_integral(x) for x in rR], [r_integral(x) for x in vR]
    m2_L_A = [
        m_R**2 * r_integral(x) for x in rcross([x - y for x, y in zip(rR, AR, strict=True)], vR)
    ]  # (1.64)
    rel_r = [m_R * x - y for x, y in zip(rR, SR, strict=True)]
    rel_v = [m_R * x - y for x, y in zip(vR, pR, strict=True)]
    m2_L_rel = [r_integral(x) for x in rcross(rel_r, rel_v)]
    m2_AG_p = [m_R * x for x in rcross([x - m_R * y for x, y in zip(SR, AR, strict=True)], pR)]
    d.prove_equal(
        expr(m2_L_A),
        expr([x + y for x, y in zip(m2_AG_p, m2_L_rel, strict=True)]),
        strategy="expand",
        claim="m² L_A = m² (AG × p + L'_G), L'_G = ∫ r' × v' dm",
    )
    d.reject(
        expr(m2_L_A),
        expr([m_R * r_integral(x) for x in rcross(rel_r, vR)]),
        strategy="expand",
        claim="L_A = ∫ r' × v dm (the AG × p term dropped)",
    )
    L_sum = [x + y for x, y in zip(m2_AG_p, m2_L_rel, strict=True)]
    # numeric: 3-point Gauss-Legendre nodes per axis integrate the degree-≤5 integrands
    # exactly, so the 27 weighted nodes are a particle system with the body's p and L_A
    x, w = np.polynomial.legendre.leggauss(3)
    x, w = (x + 1) / 2, w / 2
    grid = np.stack(np.meshgrid(x, x, x, indexing="ij"), axis=-1).reshape(-1, 3)
    wts = np.prod(np.stack(np.meshgrid(w, w, w, indexing="ij"), axis=-1).reshape(-1, 3), axis=1)
    pt = {c[0]: 1, c[1]: 2}
    syms = sorted(rI.free_symbols | vI.free_symbols - set(a), key=str)
    syms = [s for s in syms if s not in a]
    vals = {s: sp.Rational((-1) ** i * (i % 5), 2) for i, s in enumerate(syms)}
    vals.update(pt)
    rn = sp.lambdify(a, list(rI.subs(vals)))
    vn = sp.lambdify(a, list(vI.subs(vals)))
    rhon = sp.lambdify(a, rho.subs(vals))
    mk = np.array([rhon(*g) for g in grid]) * wts
    rk = np.array([np.broadcast_to(np.array(rn(*g), dtype=float), 3) for g in grid])
    vk = np.array([np.broadcast_to(np.array(vn(*g), dtype=float), 3) for g in grid])
    p_num, route = num_momentum(mk, vk)
    d.confirm(
        p_num,
        floats(_instant(p).subs(vals)).ravel(),
        atol=CODE_ATOL,
        route=f"{route} of 27 Gauss-Legendre mass elements = ∫ v dm",
    )
    An = [sp.Rational(1, 2), -1, 2]
    L_num, route = num_angular_momentum(mk, rk, vk, np.array(An, dtype=float))
    allv = {**vals, **dict(zip(A, An, strict=True)), **dict.fromkeys(a, 0)}
    point = [allv[s] for s in gens]
    m2 = m.subs(vals) ** 2
    d.confirm(
        L_num,
        [float(QQ.to_sympy(x(*point)) / m2) for x in L_sum],
        atol=CODE_ATOL,
        route=f"{route} of the elements = AG × p + L'_G",
    )
