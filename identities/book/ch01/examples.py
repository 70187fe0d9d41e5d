"""Chapter 1 worked examples: 1.1 (the skew rotating dumbbell, (1.34)–(1.38)) and 1.2
(a person walking on a free platform, (1.78)–(1.83)).  Each is re-derived from the
book's definitions and compared with the printed result.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.book.ch01.momentum import (
    CODE_ATOL,
    EPS,
    num_angular_momentum,
    num_moment_of_forces,
    num_momentum,
)
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, floats, functions_of_time, t, vec

#: scipy quad / solve_ivp at rtol 1e-12 on O(1) integrands: 2**14 eps ≈ 3.6e-12
INTEGRATION_ATOL = 2**14 * EPS


@check(
    "E1.1",
    "Example 1.1: a skew rotating dumbbell",
    kind="derivation",
    covers=("E1.1", "eq1.34", "eq1.35", "eq1.36", "eq1.37", "eq1.38"),
    statement="masses m at ±r1, r1 = R sin ϑ (cos ωt, sin ωt, 0) + R cos ϑ e_z: p = 0, "
    "L_O = 2mR² sin ϑ ω (-cos ϑ cos ωt, -cos ϑ sin ωt, sin ϑ), "
    "M_O = L̇_O = 2mR²ω² sin ϑ cos ϑ (sin ωt, -cos ωt, 0)",
)
def example_1_1(d: Derivation) -> None:
    m, R, omega = sp.symbols("m R omega", positive=True)
    theta = sp.Symbol("vartheta", real=True)
    wt = omega * t
    r1 = R * sp.sin(theta) * vec(sp.cos(wt), sp.sin(wt), 0) + R * sp.cos(theta) * vec(0, 0, 1)
    v1 = sp.diff(r1, t)
    d.prove_equal(
        v1,
        R * sp.sin(theta) * omega * vec(-sp.sin(wt), sp.cos(wt), 0),
        strategy="expand",
        claim="(1.35) as printed",
    )
    r2, v2 = -r1, sp.diff(-r1, t)
    p = d.quantity("p", m * v1 + m * v2)
    d.prove_zero(p, strategy="expand", claim="p = 0 (1.36), so F^e = ṗ = 0")
    L_O = d.quantity("L_O", sp.expand(cross(r1, m * v1) + cross(r2, m * v2)))
    printed_L = (
        2
        * m
        * R**2
        * sp.sin(theta)
        * omega
        * vec(-sp.cos(theta) * sp.cos(wt), -sp.cos(theta) * sp.sin(wt), sp.sin(theta))
    )
    d.prove_equal(L_O, printed_L, strategy="trigsimp", claim="(1.37) as printed")
    d.reject(
        L_O,
        printed_L.applyfunc(lambda e: e.subs(sp.cos(theta), -sp.cos(theta))),
        strategy="trigsimp",
        claim="(1.37) with +cos ϑ in the horizontal part",
    )
    M_O = d.quantity("M_O", sp.diff(L_O, t))
    printed_M = (
        2 * m * R**2 * omega**2 * sp.sin(theta) * sp.cos(theta) * vec(sp.sin(wt), -sp.cos(wt), 0)
    )
    d.prove_equal(M_O, printed_M, strategy="trigsimp", claim="(1.38) as printed")
    # numeric: mechanics at m = 1.5, R = 0.8, ω = 2, ϑ = 0.6, t = 0.9
    pt = {m: 1.5, R: 0.8, omega: 2, theta: 0.6, t: 0.9}
    rn, vn = floats(r1, pt).ravel(), floats(v1, pt).ravel()
    pos, vel = np.stack([rn, -rn]), np.stack([vn, -vn])
    L_num, route = num_angular_momentum([1.5, 1.5], pos, vel, np.zeros(3))
    d.confirm(L_num, floats(printed_L, pt).ravel(), atol=CODE_ATOL, route=f"{route}: (1.37)")
    p_num, route_p = num_momentum([1.5, 1.5], vel)
    d.confirm(p_num, np.zeros(3), atol=CODE_ATOL, route=f"{route_p}: (1.36)")
    acc = floats(sp.diff(r1, t, 2), pt).ravel()  # the forces that keep the balls on their cones
    M_num, route_M = num_moment_of_forces(pos, 1.5 * np.stack([acc, -acc]), np.zeros(3))
    d.confirm(M_num, floats(printed_M, pt).ravel(), atol=CODE_ATOL, route=f"{route_M}: (1.38)")


@check(
    "E1.2",
    "Example 1.2: a person walking on a freely rotating platform",
    kind="derivation",
    covers=("E1.2", "eq1.78", "eq1.79", "eq1.80", "eq1.81", "eq1.82", "eq1.83"),
    statement="L_z = J_z α̇ + m ρ² (α̇ + φ̇) = 0 gives dα = -m ρ² dφ/(J_z + m ρ²); "
    "Δα = -∫ m ρ² dφ/(J_z + m ρ²), = -m ρ0² Δφ/(J_z + m ρ0²) for ρ = ρ0: path dependent",
)
def example_1_2(d: Derivation) -> None:
    J_z, m = sp.symbols("J_z m", positive=True)
    alpha, rho, phi = functions_of_time("alpha", "rho", "phi")
    # the person as a particle at radius ρ and absolute angle α + φ; the platform rigid
    P = vec(rho * sp.cos(alpha + phi), rho * sp.sin(alpha + phi), 0)
    L_person = cross(P, m * sp.diff(P, t))[2]
    L_z = d.quantity("L_z", J_z * sp.diff(alpha, t) + L_person)
    ad, fd = sp.diff(alpha, t), sp.diff(phi, t)
    d.prove_equal(
        L_z, J_z * ad + m * rho**2 * (ad + fd), strategy="trigsimp", claim="(1.78) as printed"
    )
    d.reject(
        L_z, J_z * ad + m * rho**2 * fd, strategy="trigsimp", claim="the person's φ̇ alone (1.78)"
    )
    alpha_dot = d.quantity("alpha_dot", sp.solve(J_z * ad + m * rho**2 * (ad + fd), ad)[0])
    d.prove_equal(
        alpha_dot,
        -m * rho**2 * fd / (J_z + m * rho**2),
        strategy="cancel",
        claim="(1.79)-(1.81) as printed, L_z = 0",
    )
    rho0, dphi = sp.symbols("rho_0 Delta_phi", positive=True)
    s = sp.Symbol("s", real=True)
    d_alpha = d.quantity(
        "Delta_alpha_rho0",
        sp.integrate(-m * rho0**2 / (J_z + m * rho0**2), (s, 0, dphi)),
    )
    d.prove_equal(
        d_alpha,
        -m * rho0**2 * dphi / (J_z + m * rho0**2),
        strategy="cancel",
        claim="(1.82)-(1.83) as printed for ρ = ρ0",
    )
    # path dependence: ρ(φ) = ρ0 (1 + φ/Δφ) vs ρ = ρ0, the same end points of φ
    rho_path = rho0 * (1 + s / dphi)
    pt = {J_z: 1, m: 1, rho0: 1, dphi: sp.pi / 2}
    I2 = sp.Integral(-m * rho_path**2 / (J_z + m * rho_path**2), (s, 0, dphi))
    d.witness_unequal(
        I2.subs(pt).doit(),
        d_alpha.subs(pt),
        {},
        claim="(b): two paths from φ = 0 to Δφ turn the platform by different Δα",
    )
    # numeric: integrate (1.80) along a walk with scipy and check L_z = 0 by mechanics
    from scipy.integrate import quad, solve_ivp

    Jn, mn, r0, T = 2.0, 0.7, 1.3, 3.0
    rho_t = lambda tt: r0 * (1 + 0.3 * np.sin(tt))  # noqa: E731
    phi_t = lambda tt: 0.8 * tt + 0.2 * np.sin(2 * tt)  # noqa: E731
    phid_t = lambda tt: 0.8 + 0.4 * np.cos(2 * tt)  # noqa: E731

    def rhs(tt, y):
        r2 = rho_t(tt) ** 2
        return [-mn * r2 * phid_t(tt) / (Jn + mn * r2)]

    sol = solve_ivp(rhs, (0, T), [0.0], method="DOP853", rtol=1e-13, atol=1e-13)
    Da = sol.y[0, -1]
    ref, _ = quad(
        lambda tt: -mn * rho_t(tt) ** 2 * phid_t(tt) / (Jn + mn * rho_t(tt) ** 2),
        0,
        T,
        epsabs=1e-14,
    )
    d.confirm(Da, ref, atol=INTEGRATION_ATOL, route="scipy solve_ivp of (1.80) vs quad of (1.82)")
    # mechanics: the platform as a ring of 12 particles with moment of inertia J_z, plus the
    # person; at t = T the total L_z must vanish
    rhodot_T = r0 * 0.3 * np.cos(T)
    ad_T = rhs(T, [Da])[0]
    ang = 2 * np.pi * np.arange(12) / 12 + Da
    ring = np.stack([np.cos(ang), np.sin(ang), 0 * ang], axis=-1)  # radius 1: J_z = Σ m_k
    ring_v = ad_T * np.cross([0.0, 0.0, 1.0], ring)
    th = Da + phi_t(T)
    pos = np.array([rho_t(T) * np.cos(th), rho_t(T) * np.sin(th), 0.0])
    vel = rhodot_T * pos / rho_t(T) + rho_t(T) * (ad_T + phid_t(T)) * np.array(
        [-np.sin(th), np.cos(th), 0.0]
    )
    L_num, route = num_angular_momentum(
        np.append(np.full(12, Jn / 12), mn),
        np.vstack([ring, pos]),
        np.vstack([ring_v, vel]),
        np.zeros(3),
    )
    d.confirm(L_num[2], 0.0, atol=CODE_ATOL, route=f"{route}: platform ring + person, L_z = 0")
    # (1.83) numerically for a constant radius
    rc = 1.1
    Da_c, _ = quad(lambda f_: -mn * rc**2 / (Jn + mn * rc**2), 0, 1.7)
    d.confirm(
        Da_c,
        float(d_alpha.subs({m: mn, J_z: Jn, rho0: rc, dphi: 1.7})),
        atol=INTEGRATION_ATOL,
        route="quad of (1.82) at ρ = 1.1, Δφ = 1.7 against (1.83)",
    )
