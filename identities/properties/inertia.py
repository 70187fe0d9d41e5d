"""Randomised invariants of the inertia tensor (Essén 4.1) for :mod:`mechanics.inertia`.

The tensor of drawn particle systems about any point C equals the definition (4.34)
summed in extended precision, and the parallel-axis (Steiner) theorem (4.38)
J_C = J_G + m (|R|² 1 − R ⊗ R), R = GC, moves it from the centre of mass.
"""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from identities.verify.catalogue import check
from mechanics import inertia as I
from mechanics import strategies as ms
from mechanics._floats import EPS

#: A tensor summed over N ≤ 6 particles (each term a few rounded products) or rotated
#: (each entry nine rounded products): 64 eps of the trace bounds the difference of two
#: such computations.
SUM_ATOL = 64 * EPS

#: Underflow: a product of float64 coordinates below the smallest subnormal flushes to
#: 0 (the extended-precision reference keeps it), so each of the ≤ 6 terms of an entry
#: may be off by m × smallest subnormal whatever the relative tolerance; 2 such per
#: term (|s|² and s sᵀ) bound it.
UNDERFLOW_TERMS = 2

#: Examples per property in the catalogue (a draw and a check take ~0.5 ms).
EXAMPLES = 300

__all__ = ["SUM_ATOL", "direct_tensor", "parallel_axis_theorem_holds", "points"]

#: points C anywhere in a box of ±1e3
points = st.tuples(*(st.floats(-1e3, 1e3),) * 3).map(np.array)


def direct_tensor(m, r, C):
    """Σ m (|s|² 1 − s sᵀ), s = r − C (4.34), summed in extended precision; and its
    scale Σ m |s|²."""
    s = (r - C).astype(np.longdouble)
    mm = m.astype(np.longdouble)
    sq = (s * s).sum(axis=-1)
    J = (mm[:, None, None] * (sq[:, None, None] * np.eye(3) - s[:, :, None] * s[:, None, :])).sum(0)
    return J.astype(np.float64), float((mm * sq).sum())


def parallel_axis_theorem_holds(system, C, *, shift=None) -> None:
    """J_C from the particles equals the definition (4.34), and J_G moved to C by the
    parallel-axis theorem (4.38) equals it too.  ``shift(J_G, m, R)`` replaces the
    theorem (the negative control)."""
    m, r = system.m, system.r
    J_C = I.inertia_tensor(m, r, about=C)
    J_ref, scale = direct_tensor(m, r, C)
    tiny = UNDERFLOW_TERMS * float(m.sum()) * np.finfo(float).smallest_subnormal
    err = float(np.abs(J_C - J_ref).max())
    assert err <= SUM_ATOL * scale + tiny, f"J_C against (4.34): {err:.3g}, scale {scale:.3g}"
    M = m.sum()
    G = (m[:, None] * r).sum(0) / M
    J_G = I.inertia_tensor(m, r, about=G)
    if shift is None:
        shifted = I.parallel_axis(J_G, M, C - G, allow_singular=True)
    else:
        shifted = shift(J_G, M, C - G)
    err = float(np.abs(shifted - J_ref).max())
    assert err <= SUM_ATOL * scale + tiny, f"J_G moved to C (4.38): {err:.3g}, scale {scale:.3g}"


def _shift_wrong_sign(J_G, m, R):
    """A wrong theorem: J_G + m R ⊗ R (the sign of the dyadic, and no |R|² 1)."""
    return J_G + m * np.outer(R, R)


@check(
    "thm.parallel-axis",
    "The parallel-axis (Steiner) theorem holds for every drawn particle system and point",
    kind="property",
    covers=("eq4.34", "eq4.38"),
    statement="J_C = J_G + m (|R|² 1 − R ⊗ R), R = GC, for any particle system and point C",
)
def _parallel_axis(d) -> None:
    systems = st.tuples(ms.particle_systems(max_particles=6), points)
    d.holds_for_examples(
        parallel_axis_theorem_holds,
        systems,
        examples=EXAMPLES,
        claim="(4.34), (4.38): J_C by definition and by the parallel-axis theorem",
    )
    d.reject_property(
        lambda s, C: parallel_axis_theorem_holds(s, C, shift=_shift_wrong_sign),
        systems,
        examples=EXAMPLES,
        claim="J_C = J_G + m R ⊗ R",
    )
