"""Randomised invariants of rigid-body impact (Essén ch. 6) for :mod:`mechanics.impact`.

For hypothesis-drawn contacts (``mechanics.strategies.contacts``: masses with ratios up
to 1e15, inertia tensors of spheres, laminae, near-degenerate and rod-like bodies turned
by drawn rotations, contact points, normals, approaching velocities and e in [0, 1]
including its ends and within 1e-15 of them):

- the normal relative velocity after is −e times the one before (6.36);
- total linear momentum is conserved (6.16); angular momentum about any fixed point is
  conserved for free bodies (6.18), about the contact point against a fixed body (6.22);
- kinetic energy never increases (6.35); the loss is ½ μ (1 − e²) v_n² with the
  effective mass μ of the contact (6.41).

Every invariant is evaluated from the returned velocities by the book's definitions
(momentum m v_G, angular momentum r_G × m v_G + J_G ω, energy ½ m v² + ½ ωᵀ J ω), never
from the impulse the code used.  Tolerances are named multiples of eps times the
magnitudes of the terms that are summed, each with its reason.
"""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from identities.verify.catalogue import check
from mechanics import impact as im
from mechanics import strategies as ms
from mechanics._floats import EPS

#: Sums of a few products of correctly rounded numbers (momentum, angular momentum,
#: contact velocities): each term carries at most a few roundings, the sum a few more;
#: 32 eps of the sum of magnitudes bounds it with room.
SUM_RTOL = 32 * EPS

#: Kinetic energies are sums of positive terms, each rounded a few times; their
#: difference T_before − T_after loses nothing beyond that: 32 eps of T.
ENERGY_RTOL = 32 * EPS

#: Examples per property in the catalogue: a rigid contact takes ~2 ms to draw and
#: check, so 200 examples keep each check near a second; the theorem tests draw their
#: own number (the hypothesis profile's).
EXAMPLES = 200

__all__ = [
    "ENERGY_RTOL",
    "SUM_RTOL",
    "angular_momentum_about_contact_point_is_conserved",
    "angular_momentum_is_conserved",
    "check_energy_loss",
    "loss_6_41",
    "momentum_is_conserved",
    "restitution_law_holds",
]


# ------------------------------------------------------------------ helpers


def _norm(v) -> float:
    return float(np.linalg.norm(v))


def bodies(c: ms.Contact, out: im.RigidImpact):
    """(before, after) pairs of the bodies that move."""
    pairs = [(c.body_1, out.body_1)]
    if c.body_2 is not None:
        pairs.append((c.body_2, out.body_2))
    return pairs


def _kappa(J) -> float:
    lam = np.linalg.eigvalsh(J)
    return float(lam[-1] / lam[0])


def contact_normal_velocity(c: ms.Contact, b1, b2) -> tuple[float, float]:
    """n · (v_S1 − v_S2) by the connection formula (2.73), and its magnitude scale."""
    rel = b1.v_G + np.cross(b1.omega, c.r_S - b1.r_G)
    scale = _norm(b1.v_G) + _norm(b1.omega) * _norm(c.r_S - b1.r_G)
    if b2 is not None:
        rel = rel - (b2.v_G + np.cross(b2.omega, c.r_S - b2.r_G))
        scale += _norm(b2.v_G) + _norm(b2.omega) * _norm(c.r_S - b2.r_G)
    return float(c.n @ rel), scale


def kinetic_energy(b) -> float:
    """½ m v_G² + ½ ωᵀ J_G ω (3.30)."""
    return 0.5 * b.m * float(b.v_G @ b.v_G) + 0.5 * float(b.omega @ b.J_G @ b.omega)


def solve_error_scale(c: ms.Contact, out: im.RigidImpact) -> float:
    """κ |S| Σ |r_k|²/λ_min,k: the forward error of J⁻¹(r × S n) in velocity units.

    A backward-stable solve is accurate to κ eps relative to |J⁻¹ u| ≤ |u|/λ_min, and
    that error moves the contact point by |r| times it.
    """
    total = 0.0
    for before, _ in bodies(c, out):
        r = c.r_S - before.r_G
        lam = np.linalg.eigvalsh(before.J_G)
        total += (lam[-1] / lam[0]) * abs(out.S) * float(r @ r) / lam[0]
    return total


def angular_momentum(b, about) -> np.ndarray:
    """(r_G − about) × m v_G + J_G ω: the body's angular momentum about a point (1.21)."""
    return np.cross(b.r_G - about, b.m * b.v_G) + b.J_G @ b.omega


def _angular_scale(b, about) -> float:
    return _norm(b.r_G - about) * b.m * _norm(b.v_G) + np.linalg.norm(b.J_G, 2) * _norm(b.omega)


def _impact(c: ms.Contact) -> im.RigidImpact:
    return im.rigid_impact(c.body_1, c.body_2, r_S=c.r_S, n=c.n, e=c.e)


# --------------------------------------------------------------- properties


def restitution_law_holds(c: ms.Contact, *, e_claimed: float | None = None) -> None:
    """n · (v_S1 − v_S2) after = −e times before (6.36); ``e_claimed`` states a wrong
    law (the negative control) in place of the contact's e."""
    out = _impact(c)
    e = c.e if e_claimed is None else e_claimed
    v_before, scale_before = contact_normal_velocity(c, c.body_1, c.body_2)
    v_after, scale_after = contact_normal_velocity(c, out.body_1, out.body_2)
    assert v_before < 0, f"the strategy draws impacts; v_n = {v_before}"
    # sums of the contact velocities, plus the solve's forward error
    tol = SUM_RTOL * (scale_before + scale_after + abs(out.S) / out.mu) + 4 * EPS * (
        solve_error_scale(c, out)
    )
    assert abs(v_after - (-e * v_before)) <= tol, (v_after, v_before, e, tol)


def momentum_is_conserved(c: ms.Contact, *, only_body_1: bool = False) -> None:
    """Total linear momentum is conserved (6.16); against a fixed body, body 1's changes
    by the impulse S n.  ``only_body_1`` claims body 1's momentum alone is conserved (the
    negative control)."""
    out = _impact(c)
    if c.body_2 is None or only_body_1:
        # the fixed body takes −S n: momentum of body 1 changes by S n
        kick = out.S * c.n if c.body_2 is None else 0.0
        p_before = c.body_1.m * c.body_1.v_G + kick
        p_after = out.body_1.m * out.body_1.v_G
        scale = _norm(p_before) + _norm(p_after) + abs(out.S)
    else:
        p_before = c.body_1.m * c.body_1.v_G + c.body_2.m * c.body_2.v_G
        p_after = out.body_1.m * out.body_1.v_G + out.body_2.m * out.body_2.v_G
        scale = sum(b.m * _norm(b.v_G) for pair in bodies(c, out) for b in pair)
    assert _norm(p_after - p_before) <= SUM_RTOL * scale, (p_before, p_after)


def angular_momentum_is_conserved(c: ms.Contact, about, *, spin_only: bool = False) -> None:
    """Angular momentum of the free bodies about any fixed point ``about`` is conserved
    (6.18).  ``spin_only`` drops the orbital part r_G × m v_G (the negative control)."""
    out = _impact(c)
    about = np.asarray(about, dtype=float)

    def L(b):
        return b.J_G @ b.omega if spin_only else angular_momentum(b, about)

    L_before = sum(L(b) for b in (c.body_1, c.body_2))
    L_after = sum(L(b) for b in (out.body_1, out.body_2))
    scale = sum(_angular_scale(b, about) for pair in bodies(c, out) for b in pair)
    scale += _norm(c.r_S - about) * abs(out.S)  # the internal impulses' moments cancel
    assert _norm(L_after - L_before) <= SUM_RTOL * scale, (L_before, L_after)


def angular_momentum_about_contact_point_is_conserved(c: ms.Contact) -> None:
    """Against a fixed body the impulse acts at S: L of body 1 about S is unchanged (6.22)."""
    out = im.rigid_impact(c.body_1, None, r_S=c.r_S, n=c.n, e=c.e)
    L_before = angular_momentum(c.body_1, c.r_S)
    L_after = angular_momentum(out.body_1, c.r_S)
    scale = _angular_scale(c.body_1, c.r_S) + _angular_scale(out.body_1, c.r_S)
    assert _norm(L_after - L_before) <= SUM_RTOL * scale, (L_before, L_after)


def loss_6_41(mu, e, v_n):
    """The book's energy loss ½ μ (1 − e²) v_n² (6.41)."""
    return 0.5 * mu * (1.0 - e * e) * v_n * v_n


def loss_wrong(mu, e, v_n):
    """A wrong variant: (1 − e) instead of (1 − e²)."""
    return 0.5 * mu * (1.0 - e) * v_n * v_n


def check_energy_loss(loss, c: ms.Contact) -> None:
    """Raise AssertionError unless T_before − T_after = ``loss(μ, e, v_n)`` and T does
    not increase (6.35).

    The same procedure for the book's (6.41) and for any variant: T from the returned
    velocities by definition, μ by :func:`mechanics.impact.effective_mass`, v_n by the
    connection formula.  Tolerance: the roundings of the energies (ENERGY_RTOL of T),
    the solve's backward error moving ½ ωᵀJω by eps ‖J‖ |ω'| |Δω|, and the relative
    error κ eps of μ on the loss.
    """
    out = _impact(c)
    pairs = bodies(c, out)
    T_before = sum(kinetic_energy(b) for b, _ in pairs)
    T_after = sum(kinetic_energy(a) for _, a in pairs)
    args = [c.body_1.m, c.body_1.J_G, c.r_S - c.body_1.r_G, c.n]
    if c.body_2 is not None:
        args += [c.body_2.m, c.body_2.J_G, c.r_S - c.body_2.r_G]
    mu = float(im.effective_mass(*args))
    v_n, _ = contact_normal_velocity(c, c.body_1, c.body_2)
    Q = loss(mu, c.e, v_n)
    kappa = max(_kappa(b.J_G) for b, _ in pairs)
    solve = sum(
        np.linalg.norm(b.J_G, 2) * _norm(a.omega) * _norm(a.omega - b.omega) for b, a in pairs
    )
    tol = ENERGY_RTOL * (T_before + T_after + solve) + 4 * kappa * EPS * abs(Q)
    assert T_after <= T_before + tol, ("energy increased", T_before, T_after, tol)
    assert abs((T_before - T_after) - Q) <= tol, (T_before - T_after, Q, tol)


# --------------------------------------------------------------- the checks

_CONTACTS = st.tuples(ms.contacts())
#: contacts with an interior e (a wrong law must differ from the right one there)
_INTERIOR = st.tuples(ms.contacts(restitution=st.floats(0.1, 0.9)))


@check(
    "thm.impact-restitution",
    "Newton's law of restitution holds for every drawn rigid-body impact",
    kind="property",
    covers=("eq6.36",),
    statement="(n · v_rel)⁺ = −e (n · v_rel)⁻ at the contact point, for any two rigid "
    "bodies, contact point, normal and e in [0, 1]",
)
def _restitution(d) -> None:
    d.holds_for_examples(
        restitution_law_holds,
        _CONTACTS,
        examples=EXAMPLES,
        claim="(6.36): the normal relative velocity after is −e times the one before",
    )
    d.reject_property(
        lambda c: restitution_law_holds(c, e_claimed=1.0),
        _INTERIOR,
        examples=EXAMPLES,
        claim="every impact is elastic (e = 1 in place of the contact's e)",
    )


@check(
    "thm.impact-momentum",
    "Momentum and angular momentum are conserved in every drawn rigid-body impact",
    kind="property",
    covers=("eq6.16", "eq6.18", "eq6.22"),
    statement="Σ m v_G is conserved (6.16); Σ (r_G − A) × m v_G + J_G ω about any fixed A "
    "is conserved for free bodies (6.18), about the contact point against a fixed body (6.22)",
)
def _momentum(d) -> None:
    d.holds_for_examples(
        momentum_is_conserved,
        _CONTACTS,
        examples=EXAMPLES,
        claim="(6.16): total linear momentum is conserved",
    )
    free = ms.contacts(regimes=["free-free", "central", "planar", "mass-ratio"])
    d.holds_for_examples(
        lambda c, anywhere: angular_momentum_is_conserved(c, anywhere.r_G),
        st.tuples(free, ms.impact_bodies()),
        examples=EXAMPLES,
        claim="(6.18): angular momentum about any fixed point is conserved",
    )
    d.holds_for_examples(
        angular_momentum_about_contact_point_is_conserved,
        st.tuples(ms.contacts(regimes=["fixed-body-2"])),
        examples=EXAMPLES,
        claim="(6.22): against a fixed body, angular momentum about the contact point",
    )
    d.reject_property(
        lambda c: momentum_is_conserved(c, only_body_1=True),
        st.tuples(ms.contacts(regimes=["free-free"])),
        examples=EXAMPLES,
        claim="the momentum of body 1 alone is conserved",
    )
    d.reject_property(
        lambda c, anywhere: angular_momentum_is_conserved(c, anywhere.r_G, spin_only=True),
        st.tuples(free, ms.impact_bodies()),
        examples=EXAMPLES,
        claim="the spins J_G ω alone are conserved (no orbital part r_G × m v_G)",
    )


@check(
    "thm.impact-energy-loss",
    "The kinetic energy lost in every drawn rigid-body impact is ½ μ (1 − e²) v_n²",
    kind="property",
    covers=("eq6.35", "eq6.41"),
    statement="T⁻ − T⁺ = ½ μ (1 − e²) v_n² ≥ 0 with μ the contact's effective mass",
)
def _energy_loss(d) -> None:
    d.holds_for_examples(
        lambda c: check_energy_loss(loss_6_41, c),
        _CONTACTS,
        examples=EXAMPLES,
        claim="(6.35), (6.41): T never increases and the loss is ½ μ (1 − e²) v_n²",
    )
    d.reject_property(
        lambda c: check_energy_loss(loss_wrong, c),
        _INTERIOR,
        examples=EXAMPLES,
        claim="the loss is ½ μ (1 − e) v_n²",
    )
