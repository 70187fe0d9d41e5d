"""Chapter 8: the velocity field, continuity, Euler's equation for an ideal fluid,
Bernoulli's theorem and Torricelli's outflow (Example 8.1).

General fields are undefined sympy functions of (x, y, z, t), so the vector identities
are proved for every smooth field; the integral theorems (Gauss on a box) are proved
for general quadratic fields with symbolic coefficients.  The extraction lost the
density symbol ρ everywhere: ``(r, t)`` in (8.13) is ρ(r, t), ``0`` in (8.30)–(8.36)
is ρ0 (see ``reading=``).
"""

from __future__ import annotations

import itertools

import numpy as np
import sympy as sp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, floats, vec
from mechanics import fluids
from mechanics._floats import EPS

#: mechanics.fluids differentiates with 4th-order central differences: about
#: eps^(4/5) ≈ 3e-13 of the field's scale (its Conventions); 2^14 eps = 3.6e-12 leaves
#: a factor ten for fields of size ~1 and the products in Euler's equation.
FD_ATOL = 2**14 * EPS
#: a closed form evaluated in float64 (a square root, a few products): 8 eps relative.
CODE_RTOL = 8 * EPS

x, y, z, t = sp.symbols("x y z t", real=True)
X = (x, y, z)
rho_0, g, h, p_0 = sp.symbols("rho_0 g h p_0", positive=True)
a, b, c = sp.symbols("a b c", positive=True)

_READING_RHO = (
    "the extraction drops ρ: '(r, t)' is ρ(r, t), '0' before v², gz and under p is ρ0, "
    "and '∇p' in (8.27)/(8.29) stands over ρ"
)


# -- vector analysis from the definitions ----------------------------------------------
def grad(f) -> sp.Matrix:
    return vec(*(sp.diff(f, s) for s in X))


def div(v) -> sp.Expr:
    return sum(sp.diff(v[i], X[i]) for i in range(3))


def curl(v) -> sp.Matrix:
    return vec(
        sp.diff(v[2], y) - sp.diff(v[1], z),
        sp.diff(v[0], z) - sp.diff(v[2], x),
        sp.diff(v[1], x) - sp.diff(v[0], y),
    )


def advect(v, w) -> sp.Matrix:
    """(w·∇) v."""
    return vec(*(sum(w[j] * sp.diff(v[i], X[j]) for j in range(3)) for i in range(3)))


def general_field(name: str, *args) -> sp.Matrix:
    """A general smooth vector field: three undefined functions of ``args``."""
    return vec(*(sp.Function(f"{name}_{i + 1}", real=True)(*args) for i in range(3)))


def quadratic(name: str, variables) -> sp.Expr:
    """The general polynomial of degree ≤ 2 in ``variables``, symbolic coefficients."""
    monomials = [sp.Integer(1), *variables]
    monomials += [u * w for u, w in itertools.combinations_with_replacement(variables, 2)]
    return sum(sp.Symbol(f"{name}{k}", real=True) * m for k, m in enumerate(monomials))


def box_flux(F: sp.Matrix, *, outward: int = 1) -> sp.Expr:
    """∮ F · dA over the box [0, a]×[0, b]×[0, c] with outward (or inward) normals."""
    lims = {x: a, y: b, z: c}
    total = sp.Integer(0)
    for i, s in enumerate(X):
        others = [u for u in X if u != s]
        face = F[i].subs(s, lims[s]) - F[i].subs(s, 0)  # +e_i face minus −e_i face
        total += sp.integrate(
            face, (others[0], 0, lims[others[0]]), (others[1], 0, lims[others[1]])
        )
    return outward * total


def box_integral(f) -> sp.Expr:
    return sp.integrate(f, (x, 0, a), (y, 0, b), (z, 0, c))


def _field_fn(expr_vec, params: dict):
    """A numeric field r, t -> (..., 3) (or scalar) from sympy components."""
    comps = [
        sp.sympify(e).subs(params) for e in (expr_vec if isinstance(expr_vec, list) else [expr_vec])
    ]
    fns = [sp.lambdify((x, y, z, t), e, "numpy") for e in comps]

    def field(r, tt=0.0):
        r = np.asarray(r, dtype=float)
        vals = [np.broadcast_to(f(r[..., 0], r[..., 1], r[..., 2], tt), r.shape[:-1]) for f in fns]
        return np.stack(vals, axis=-1) if len(vals) > 1 else vals[0]

    return field


# -- 8.1 the velocity field ---------------------------------------------------------------
@check(
    "eq8.5",
    "Volume change of a material region and Gauss' theorem (8.4)-(8.6), (8.16)",
    kind="proof",
    covers=("eq8.4", "eq8.5", "eq8.16"),
    defines=("eq8.1", "eq8.2", "eq8.3"),
    statement="∮_S v·dA = ∫_Ω ∇·v dV (Gauss), so dV/dt = ∮_S v·dA = ∫_Ω ∇·v dV",
    reading="proved on the box [0,a]×[0,b]×[0,c] for a general quadratic field (30 free "
    "coefficients); (8.16) is the same theorem for the field ρv",
)
def gauss_box(d: Derivation) -> None:
    v = vec(*(quadratic(f"k{i}_", X) for i in range(3)))
    d.note("a general quadratic velocity field v(r) on the box [0,a]×[0,b]×[0,c]")
    flux = box_flux(v)
    d.prove_equal(flux, box_integral(div(v)), strategy="expand", claim="∮ v·dA = ∫ ∇·v dV")
    d.reject(
        box_flux(v, outward=-1),
        box_integral(div(v)),
        strategy="expand",
        claim="the flux with inward normals equals ∫ ∇·v dV",
    )
    rho = quadratic("q", X)
    d.prove_equal(
        box_flux(rho * v),
        box_integral(div(rho * v)),
        strategy="expand",
        claim="(8.16): ∮ ρv·dA = ∫ ∇·(ρv) dV for quadratic ρ and v",
    )


@check(
    "eq8.6",
    "The local form of (8.6): a material volume element grows at the rate ∇·v",
    kind="proof",
    covers=("eq8.6",),
    statement="for the flow map r(r0, t) with F = ∂r/∂r0 and dF/dt = (∇v) F, "
    "d(det F)/dt = (∇·v) det F (Euler's expansion formula)",
)
def expansion_formula(d: Derivation) -> None:
    F = sp.Matrix(3, 3, lambda i, j: sp.Function(f"F_{i + 1}{j + 1}", real=True)(t))
    G = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"G_{i + 1}{j + 1}", real=True))
    rate = {sp.diff(F[i, j], t): (G * F)[i, j] for i in range(3) for j in range(3)}
    dJ = sp.diff(F.det(), t).subs(rate)
    d.prove_equal(dJ, G.trace() * F.det(), strategy="expand", claim="dJ/dt = tr(∇v) J")
    d.reject(dJ, -G.trace() * F.det(), strategy="expand", claim="dJ/dt = −tr(∇v) J")
    d.reject(dJ, (G * G.T).trace() * F.det(), strategy="expand", claim="dJ/dt = tr(G Gᵀ) J")


@check(
    "eq8.8",
    "Rigid flow: zero divergence and curl 2ω (8.7)-(8.8)",
    kind="proof",
    covers=("eq8.7", "eq8.8"),
    statement="v = v(0) + ω × r has ∇·v = 0 and ∇×v = 2ω",
)
def rigid_flow(d: Derivation) -> None:
    v0 = vec(*sp.symbols("v_01 v_02 v_03", real=True))
    w = vec(*sp.symbols("omega_1 omega_2 omega_3", real=True))
    v = v0 + cross(w, vec(*X))
    d.prove_zero(div(v), strategy="expand", claim="∇·(v(0) + ω×r) = 0")
    d.prove_equal(curl(v), 2 * w, strategy="expand", claim="(8.8): ∇×(v(0) + ω×r) = 2ω")
    d.reject(curl(v), w, strategy="expand", claim="∇×v = ω (the factor 2 dropped)")
    point = {**dict(zip(v0, [1, -2, sp.Rational(1, 2)], strict=True))}
    point.update(dict(zip(w, [sp.Rational(3, 10), -1, sp.Rational(1, 2)], strict=True)))
    field = fluids.rigid_velocity_field(floats(v0, point).ravel(), floats(w, point).ravel())
    r = np.array([[1.0, 2.0, 3.0], [-4.0, 0.5, 2.0]])
    d.confirm(
        fluids.curl(field, r),
        np.broadcast_to(floats(2 * w, point).ravel(), (2, 3)),
        atol=FD_ATOL,
        route="mechanics.fluids.curl of the rigid field at two points",
    )
    d.confirm(
        fluids.divergence(field, r), np.zeros(2), atol=FD_ATOL, route="mechanics.fluids.divergence"
    )


@check(
    "eq8.11",
    "The total (material) time derivative (8.9)-(8.12)",
    kind="proof",
    covers=("eq8.10", "eq8.11", "eq8.12"),
    defines=("eq8.9",),
    statement="d/dt T(r(t), t) = ∂T/∂t + v·∇T along a trajectory with dr/dt = v",
    reading="checked for the general quadratic T(x, y, z, t) (15 free coefficients) along a "
    "general trajectory r(t)",
)
def material_derivative(d: Derivation) -> None:
    T = quadratic("c", (x, y, z, t))
    path = [sp.Function(n, real=True)(t) for n in ("x_p", "y_p", "z_p")]
    on_path = dict(zip(X, path, strict=True))
    lhs = sp.diff(T.subs(on_path), t)
    vel = vec(*(sp.diff(q, t) for q in path))
    rhs = (sp.diff(T, t) + vel.dot(grad(T))).subs(on_path)
    d.prove_equal(lhs, rhs, strategy="expand", claim="(8.11): dT/dt = ∂T/∂t + v·∇T")
    d.reject(
        lhs, vel.dot(grad(T)).subs(on_path), strategy="expand", claim="dT/dt = v·∇T (no ∂T/∂t)"
    )
    # independent route: mechanics.fluids.material_derivative on a numeric field
    c0 = {
        s: sp.Rational(k % 7 - 3, 4)
        for k, s in enumerate(sorted(T.free_symbols - {x, y, z, t}, key=str))
    }
    Tn = _field_fn(T, c0)
    v = fluids.rigid_velocity_field([0.5, -1.0, 0.25], [0.2, 0.3, -0.7])
    r0 = np.array([0.7, -0.4, 1.1])
    exact = (sp.diff(T, t) + vec(*v(r0)).dot(grad(T))).subs(c0).subs(dict(zip(X, r0, strict=True)))
    d.confirm(
        fluids.material_derivative(Tn, v, r0, 0.3),
        float(exact.subs(t, sp.Rational(3, 10))),
        atol=FD_ATOL,
        route="mechanics.fluids.material_derivative of the quadratic T in a rigid flow",
    )


# -- 8.1.3 continuity --------------------------------------------------------------------
@check(
    "eq8.18",
    "The equation of continuity (8.13)-(8.18)",
    kind="proof",
    covers=("eq8.14", "eq8.15", "eq8.17", "eq8.18"),
    defines=("eq8.13",),
    statement="mass conservation of every fluid element, ρ J = const, with dJ/dt = (∇·v) J "
    "(8.6), is ∂ρ/∂t + ∇·(ρ v) = 0",
    reading=_READING_RHO,
)
def continuity(d: Derivation) -> None:
    rho = sp.Function("rho", real=True)(x, y, z, t)
    v = general_field("v", x, y, z, t)
    D_rho = sp.diff(rho, t) + v.dot(grad(rho))
    d.prove_equal(
        sp.diff(rho, t) + div(rho * v),
        D_rho + rho * div(v),
        strategy="expand",
        claim="∂ρ/∂t + ∇·(ρv) = dρ/dt + ρ ∇·v (8.12 and the product rule)",
    )
    d.reject(
        sp.diff(rho, t) + rho * div(v),
        D_rho + rho * div(v),
        strategy="expand",
        claim="∇·(ρv) = ρ ∇·v (the v·∇ρ term dropped)",
    )
    # Lagrangian mass conservation: d(ρ J)/dt = 0 with J' = (∇·v) J gives dρ/dt = −ρ ∇·v
    rl, J = (sp.Function(n, real=True)(t) for n in ("rho_L", "J"))
    divv = sp.Symbol("div_v", real=True)
    mass_rate = sp.diff(rl * J, t).subs(sp.diff(J, t), divv * J)
    d.prove_equal(
        mass_rate,
        J * (sp.diff(rl, t) + rl * divv),
        strategy="expand",
        claim="d(ρJ)/dt = J (dρ/dt + ρ ∇·v), so ρJ = const ⇔ dρ/dt + ρ∇·v = 0",
    )
    # (8.14): the rate of the mass in a fixed box is the integral of ∂ρ/∂t
    rq = quadratic("q", (x, y, z, t))
    d.prove_equal(
        sp.diff(box_integral(rq), t),
        box_integral(sp.diff(rq, t)),
        strategy="expand",
        claim="(8.14) on a fixed box for a quadratic ρ(r, t)",
    )
    # an exact solution: uniform expansion r = (1 + αt) r0
    alpha = sp.Symbol("alpha", positive=True)
    vel = vec(*X) * alpha / (1 + alpha * t)
    dens = rho_0 / (1 + alpha * t) ** 3
    d.prove_zero(
        sp.diff(dens, t) + div(dens * vel),
        strategy="cancel",
        claim="uniform expansion v = αr/(1+αt), ρ = ρ0/(1+αt)³ satisfies (8.18)",
    )
    d.reject(
        sp.diff(dens * (1 + alpha * t), t) + div(dens * (1 + alpha * t) * vel),
        0,
        strategy="cancel",
        claim="ρ = ρ0/(1+αt)² for the same expansion",
    )
    pt = {alpha: sp.Rational(1, 2), rho_0: 3}
    res = fluids.continuity_residual(
        _field_fn(dens, pt), _field_fn(list(vel), pt), [[0.3, -1.0, 2.0], [1.0, 1.0, 1.0]], 0.7
    )
    d.confirm(res, np.zeros(2), atol=FD_ATOL, route="mechanics.fluids.continuity_residual")


# -- 8.2 Euler's equation -----------------------------------------------------------------
@check(
    "eq8.25",
    "The pressure force on a region: −∮ p dA = −∫ ∇p dV (8.22)-(8.26)",
    kind="proof",
    covers=("eq8.23", "eq8.24", "eq8.25"),
    defines=("eq8.22", "eq8.26"),
    statement="a·∮ p dA = ∫ ∇·(p a) dV = a·∫ ∇p dV for every constant a, so F_p = −∫ ∇p dV",
    reading="(8.25) proved on the box [0,a]×[0,b]×[0,c] for a general quadratic p",
)
def pressure_force(d: Derivation) -> None:
    p = sp.Function("p", real=True)(x, y, z, t)
    A = vec(*sp.symbols("A_1 A_2 A_3", real=True))
    d.prove_equal(div(p * A), A.dot(grad(p)), strategy="expand", claim="(8.24): ∇·(pa) = a·∇p")
    d.reject(div(p * A), p * div(A) - A.dot(grad(p)), strategy="expand", claim="∇·(pa) = −a·∇p")
    pq = quadratic("c", X)
    surface = vec(*(box_flux(pq * e) for e in sp.eye(3).columnspace()))
    volume = vec(*(box_integral(gc) for gc in grad(pq)))
    d.prove_equal(-surface, -volume, strategy="expand", claim="(8.25): −∮ p dA = −∫ ∇p dV")
    d.reject(-surface, volume, strategy="expand", claim="−∮ p dA = +∫ ∇p dV")


def _forced_vortex():
    w = sp.Symbol("omega", positive=True)
    v = vec(-w * y, w * x, 0)
    p = p_0 + rho_0 * w**2 * (x**2 + y**2) / 2 - rho_0 * g * z
    return w, v, p


def _stagnation_flow():
    k = sp.Symbol("k", positive=True)
    v = vec(k * x, -k * y, 0)
    p = p_0 - rho_0 * k**2 * (x**2 + y**2) / 2 - rho_0 * g * z
    return k, v, p


def _euler_residual(v, p, rho):
    g_vec = vec(0, 0, -g)
    return sp.diff(v, t) + advect(v, v) - g_vec + grad(p) / rho


@check(
    "eq8.27",
    "Euler's equation for an ideal fluid (8.19)-(8.21), (8.27)",
    kind="proof",
    covers=("eq8.20", "eq8.27"),
    defines=("eq8.19", "eq8.21"),
    statement="(ρ dV)(∂/∂t + v·∇)v = (ρ dV) g − ∇p dV, i.e. ∂v/∂t + (v·∇)v = g − ∇p/ρ; "
    "it holds for the forced vortex and the plane stagnation flow with their pressures",
    reading=_READING_RHO,
)
def euler_equation(d: Derivation) -> None:
    # (8.20) for the general quadratic field v(r, t) along a particle path dr/dt = v
    vq = vec(*(quadratic(f"k{i}_", (x, y, z, t)) for i in range(3)))
    path = [sp.Function(n, real=True)(t) for n in ("x_p", "y_p", "z_p")]
    on_path = dict(zip(X, path, strict=True))
    vel = vec(*(sp.diff(q, t) for q in path))
    accel_lhs = sp.diff(vq.subs(on_path), t).subs({vel[i]: vq[i].subs(on_path) for i in range(3)})
    accel_rhs = (sp.diff(vq, t) + advect(vq, vq)).subs(on_path)
    d.prove_equal(
        accel_lhs,
        accel_rhs,
        strategy="expand",
        claim="(8.20): the acceleration of a fluid particle is (∂/∂t + v·∇)v",
    )
    d.reject(
        accel_lhs,
        sp.diff(vq, t).subs(on_path),
        strategy="expand",
        claim="the acceleration is ∂v/∂t (no convective term)",
    )
    v = general_field("v", x, y, z, t)
    dV = sp.Symbol("dV", positive=True)
    rho = sp.Function("rho", real=True)(x, y, z, t)
    p = sp.Function("p", real=True)(x, y, z, t)
    g_vec = vec(0, 0, -g)
    newton = (rho * dV) * (sp.diff(v, t) + advect(v, v)) - (rho * dV * g_vec - grad(p) * dV)
    d.prove_equal(
        newton / (rho * dV),
        _euler_residual(v, p, rho),
        strategy="cancel",
        claim="dp = dW + dF_p divided by ρ dV is (8.27)",
    )
    for name, (par, vf, pf) in (
        ("forced vortex", _forced_vortex()),
        ("stagnation", _stagnation_flow()),
    ):
        d.prove_zero(
            _euler_residual(vf, pf, rho_0), strategy="expand", claim=f"the {name} solves (8.27)"
        )
        wrong = pf.subs(rho_0 * g * z, -rho_0 * g * z)
        d.reject(
            _euler_residual(vf, wrong, rho_0),
            sp.zeros(3, 1),
            strategy="expand",
            claim=f"the {name} with hydrostatic pressure of the wrong sign",
        )
        pt = {par: sp.Rational(3, 2), rho_0: 1000, g: sp.Rational(981, 100), p_0: 10**5}
        r = np.array([[0.5, -0.3, 0.2], [-1.0, 2.0, -0.5]])
        scale = 1000 * 9.81 * 4  # |∇p|/ρ ~ g + k² |r|: residual relative to O(10)
        d.confirm(
            fluids.euler_residual(
                _field_fn(list(vf), pt), _field_fn(pf, pt), r, rho=1000.0, g=9.81
            ),
            np.zeros((2, 3)),
            atol=FD_ATOL * scale / 1000,
            route=f"mechanics.fluids.euler_residual for the {name}",
        )


@check(
    "eq8.28",
    "The vector identity ½∇v² = v × (∇×v) + (v·∇)v and Euler's equation (8.29)",
    kind="proof",
    covers=("eq8.28", "eq8.29"),
    statement="for every smooth v: ½∇(v·v) = v×(∇×v) + (v·∇)v, so (8.27) ⇔ (8.29)",
    reading=_READING_RHO,
)
def lamb_identity(d: Derivation) -> None:
    v = general_field("v", x, y, z, t)
    lhs = grad(v.dot(v)) / 2
    d.prove_equal(lhs, cross(v, curl(v)) + advect(v, v), strategy="expand", claim="(8.28)")
    d.reject(lhs, -cross(v, curl(v)) + advect(v, v), strategy="expand", claim="with −v×(∇×v)")
    d.reject(lhs, cross(curl(v), v) + advect(v, v), strategy="expand", claim="with (∇×v)×v")
    p = sp.Function("p", real=True)(x, y, z, t)
    rho = sp.Function("rho", real=True)(x, y, z, t)
    form_29 = sp.diff(v, t) + lhs - cross(v, curl(v)) - vec(0, 0, -g) + grad(p) / rho
    d.prove_equal(form_29, _euler_residual(v, p, rho), strategy="expand", claim="(8.29) ⇔ (8.27)")


# -- 8.2.4 Bernoulli --------------------------------------------------------------------
@check(
    "eq8.34",
    "Bernoulli's theorem for steady incompressible flow (8.30)-(8.34)",
    kind="proof",
    covers=("eq8.30", "eq8.32", "eq8.33", "eq8.34"),
    defines=("eq8.31",),
    statement="if ∂v/∂t = 0 and ρ = ρ0, Euler's equation gives v·∇(½ρ0v² + ρ0gz + p) = 0: "
    "the sum is constant along streamlines dr/dt = v",
    reading=_READING_RHO,
)
def bernoulli(d: Derivation) -> None:
    v = general_field("v", x, y, z)  # steady
    p = sp.Function("p", real=True)(x, y, z)
    g_vec = vec(0, 0, -g)
    d.prove_equal(
        _euler_residual(v, p, rho_0),
        -cross(v, curl(v)) + grad(v.dot(v)) / 2 - g_vec + grad(p) / rho_0,
        strategy="expand",
        claim="(8.30): steady incompressible (8.29)",
    )
    d.prove_equal(grad(g_vec.dot(vec(*X))), g_vec, strategy="expand", claim="∇(g·r) = g")
    d.prove_zero(
        cross(v, curl(v)).dot(v), strategy="expand", claim="(8.32): [v×(∇×v)]·v = 0 along v"
    )
    d.reject(
        cross(v, curl(v))[0],
        0,
        strategy="expand",
        claim="[v×(∇×v)]·e_x = 0 (a direction that is not a streamline)",
    )
    # Euler's equation solved for ∇p: the directional derivative of B along v
    B_grad = rho_0 * grad(v.dot(v)) / 2 + rho_0 * g * vec(0, 0, 1)
    grad_p = rho_0 * (g_vec - advect(v, v))
    d.prove_zero(
        v.dot(B_grad + grad_p),
        strategy="expand",
        claim="(8.33)-(8.34): v·∇(½ρ0v² + ρ0gz + p) = 0 when (8.27) holds with ∂v/∂t = 0",
    )
    vu = general_field("v", x, y, z, t)
    grad_p_unsteady = rho_0 * (g_vec - sp.diff(vu, t) - advect(vu, vu))
    d.reject(
        vu.dot(rho_0 * grad(vu.dot(vu)) / 2 + rho_0 * g * vec(0, 0, 1) + grad_p_unsteady),
        0,
        strategy="expand",
        claim="the same for an unsteady flow (ρ0 v·∂v/∂t remains)",
    )
    # the forced vortex is rotational: B is constant on each circle, not across them
    w, vf, pf = _forced_vortex()
    B = rho_0 * vf.dot(vf) / 2 + rho_0 * g * z + pf
    d.prove_zero(vf.dot(grad(B)), strategy="expand", claim="forced vortex: v·∇B = 0")
    d.witness_unequal(
        B.subs({x: 1, y: 0}),
        B.subs({x: 2, y: 0}),
        {w: 1, rho_0: 1},
        claim="forced vortex (∇×v = 2ω e_z ≠ 0): B differs between the streamlines r = 1 and 2",
    )
    k, vs, ps = _stagnation_flow()
    Bs = rho_0 * vs.dot(vs) / 2 + rho_0 * g * z + ps
    d.prove_zero(grad(Bs), strategy="expand", claim="irrotational stagnation flow: ∇B = 0")
    pt = {k: sp.Rational(1, 2), rho_0: 1000, g: sp.Rational(981, 100), p_0: 10**5}
    vn, pn = _field_fn(list(vs), pt), _field_fn(ps, pt)
    line = fluids.streamline(vn, [1.0, 2.0, 0.5], np.linspace(0.0, 3.0, 7))
    Bn = fluids.bernoulli_constant(vn(line), pn(line), line[:, 2], rho_0=1000.0, g=9.81)
    d.confirm(
        Bn,
        np.full(7, float(Bs.subs(pt).subs({x: 1, y: 2, z: sp.Rational(1, 2)}))),
        atol=2**10 * EPS * 1e5,  # DOP853 at rtol 1e-12 along the line; B ~ 1e5 Pa
        route="mechanics.fluids.streamline + bernoulli_constant along a stagnation streamline",
    )


@check(
    "E8.1",
    "Example 8.1: Torricelli's outflow speed u = √(2gh) (8.35)-(8.37)",
    kind="derivation",
    covers=("E8.1", "eq8.35", "eq8.36", "eq8.37"),
    statement="Bernoulli from the still surface A (v = 0, z = 0, p = p0) to the hole B "
    "(z = −h, p = p0): ½ρ0u² − ρ0gh + p0 = p0, u = √(2gh)",
    reading=_READING_RHO,
)
def torricelli(d: Derivation) -> None:
    u = sp.Symbol("u", positive=True)
    const = 0 + 0 + p_0  # (8.35)
    at_hole = rho_0 * u**2 / 2 - rho_0 * g * h + p_0  # (8.36)
    (sol,) = sp.solve(sp.Eq(at_hole, const), u)
    d.quantity("u", sol)
    printed = sp.sqrt(2 * g * h)
    d.prove_equal(sol, printed, strategy="expand", claim="(8.37): u = √(2gh)")
    d.reject(sol, sp.sqrt(g * h), strategy="expand", claim="u = √(gh)")
    dm = sp.Symbol("dm", positive=True)
    d.confirm_exact(
        sp.sqrt(2 * (dm * g * h) / dm),
        sol,
        route="energy: a mass dm falling h from rest gains ½ dm u² = dm g h",
    )
    hs = np.array([0.01, 1.0, 25.0])
    d.confirm(
        fluids.torricelli_speed(hs, g=9.81) / np.sqrt(2 * 9.81 * hs),
        np.ones(3),
        atol=CODE_RTOL,
        route="mechanics.fluids.torricelli_speed against (8.37)",
    )
