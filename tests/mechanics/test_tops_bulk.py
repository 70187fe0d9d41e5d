"""Tops in bulk (issue 30, item 3): the integer construction of the free top, its state
over many instants in chunks, and :class:`mechanics.tops.FreeTopBatch` against each top
alone.  Speed is measured in ``tests/benchmarks/test_bench_tops.py``, never here."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from mechanics import tops
from mechanics._floats import EPS
from mechanics.errors import NonPhysicalInertiaError, ShapeError
from mechanics.strategies import principal_moments, rotation_matrices

# E = ½ Σ J ω² and L_O = Rᵀ J ω from the batch's state: as for one top
# (tests/theorems/test_ch05_tops.py), each ω component within ~8 eps relative and the
# attitude's entries within ~16 eps, per unit of elliptic phase, so the sums of three
# products within 64 eps (E) and 256 eps (L_O, times |L|) of the exact constants.
CONSERVATION_RTOL = 64 * EPS
L_SPACE_RTOL = 256 * EPS

# The chunked state over many instants against omega() and attitude() in one pass: the
# same steps elementwise, but the hyperbolic AGM's step count is set per chunk by its
# largest argument (a step more adds terms below 2^-64 of φ): 4 eps covers a last bit
# either way on ω (relative to |ω0|) and on the attitude's entries.
CHUNK_EPS = 4

# |t| of the property tests: 20 time units, as the stability tests' horizon
HORIZON = 20.0


# ----------------------------------------------------------------- draws of free tops
_deltas = st.sampled_from([0.0, 1e-3, 1e-8, -1e-8, 1e-13, -1e-13, 1e-15, -1e-15])
_components = st.one_of(
    st.just(0.0),
    st.builds(lambda s, x: s * x, st.sampled_from([-1.0, 1.0]), st.floats(1e-12, 1.0)),
)


@st.composite
def free_tops(draw):
    """(J in a drawn order, ω0, R0): J from the project's principal_moments (every regime:
    equal, symmetric, near-degenerate, flat, near-flat, thin, wide scales), ω0 generic or
    within δ of the separatrix (D = L² − 2EJ2 ≈ δ J1 (J2 − J1) ω1², δ = 0 on it; 1e-15
    is a few ulps of D), R0 from rotation_matrices."""
    Js = [float(x) for x in draw(principal_moments(min_scale=1e-3, max_scale=1e3))]
    # the "flat" regime's J3 = fl(J1 + J2) may exceed the exact sum by its rounding
    # (0.05 + 1.0 = 1.05 does): step it down to the flat body it means
    while Fraction(Js[2]) > Fraction(Js[0]) + Fraction(Js[1]):
        Js[2] = math.nextafter(Js[2], 0.0)
    scale = draw(st.floats(0.1, 10.0))
    distinct = Js[0] < Js[1] < Js[2]
    if distinct and draw(st.booleans()):  # near the separatrix, on either side
        delta = draw(_deltas)
        w1 = draw(st.floats(0.05, 1.0))
        ratio = Js[0] * (Js[1] - Js[0]) * (1 + delta) / (Js[2] * (Js[2] - Js[1]))
        w_sorted = [w1, draw(_components), w1 * math.sqrt(ratio)]
    else:
        w_sorted = [draw(_components) for _ in range(3)]
    order = draw(st.permutations([0, 1, 2]))
    J = [Js[i] for i in order]
    w = [scale * w_sorted[i] for i in order]
    return J, w, draw(rotation_matrices())


def _fsqrt(x: Fraction) -> float:
    if x == 0:
        return 0.0
    k = (x.numerator.bit_length() - x.denominator.bit_length()) // 2
    y = x / Fraction(2) ** (2 * k) if k >= 0 else x * Fraction(2) ** (-2 * k)
    return math.ldexp(math.sqrt(float(y)), k)


def _constants_in_fractions(J, w):
    """The free top's rounded-once constants by ``fractions.Fraction`` (the construction's
    own way before issue 30, written out again here as the reference)."""
    k = math.frexp(max(J))[1]
    Jn = [math.ldexp(x, -k) for x in J]
    order = sorted(range(3), key=Jn.__getitem__)
    Js = [Jn[i] for i in order]
    ws = [w[i] for i in order]
    J1, J2, J3 = (Fraction(x) for x in Js)
    w1, w2, w3 = (Fraction(x) for x in ws)  # signs do not matter below but s, sigma
    E2 = sum(Fraction(a) * Fraction(b) ** 2 for a, b in zip(Jn, w, strict=True))
    L2 = sum((Fraction(a) * Fraction(b)) ** 2 for a, b in zip(Jn, w, strict=True))
    A = J1 * (J3 - J1) * w1**2 + J2 * (J3 - J2) * w2**2
    B = J2 * (J2 - J1) * w2**2 + J3 * (J3 - J1) * w3**2
    D = J3 * (J3 - J2) * w3**2 - J1 * (J2 - J1) * w1**2
    out = {
        "energy": float(E2 / 2 * Fraction(2) ** k),
        "_Lm": _fsqrt(L2),
        "separatrix_distance": float(D * Fraction(2) ** (2 * k)),
    }
    nz = [i for i in range(3) if ws[i] != 0]
    if not nz or all(Js[i] == Js[nz[0]] for i in nz):
        return out, None
    if D >= 0:
        m = (J2 - J1) * A / ((J3 - J2) * B)
        m1 = (J3 - J1) * D / ((J3 - J2) * B)
        amp = (A / (J1 * (J3 - J1)), A / (J2 * (J3 - J2)), B / (J3 * (J3 - J1)))
        lam2 = (J3 - J2) * B / (J1 * J2 * J3)
        n1, n3 = -J1 * A / (J3 * B), -J3 * (J2 - J1) / (J1 * (J3 - J2))
        pole_first = abs(n1) <= abs(n3)
        regime = "separatrix" if D == 0 else "axis3"
    else:
        m = (J3 - J2) * B / ((J2 - J1) * A)
        m1 = (J3 - J1) * (-D) / ((J2 - J1) * A)
        amp = (A / (J1 * (J3 - J1)), B / (J2 * (J2 - J1)), B / (J3 * (J3 - J1)))
        lam2 = (J2 - J1) * A / (J1 * J2 * J3)
        n1, n3 = -J1 * (J3 - J2) / (J3 * (J2 - J1)), -J3 * B / (J1 * A)
        pole_first = abs(n1) < abs(n3)
        regime = "axis1"
    n = n1 if pole_first else n3
    out.update(
        m=float(m),
        m1=float(m1),
        _lam=_fsqrt(lam2),
        _n=float(n),
        _C=float((J3 - J1) / (J1 * J3)) * out["_Lm"],
        _pole_first=pole_first,
        regime=regime,
    )
    return out, [_fsqrt(a) for a in amp]


# an exactly flat body (J3 = J1 + J2, the benchmark's), the separatrix itself, J2 = J3
# to the ulp, and a spin 1e-15 off the separatrix
@example(([1.0, 2.0, 3.0], [0.4, 0.2, 1.0], np.eye(3)))
@example(([3.0, 4.0, 6.0], [2.0, 0.5, 1.0], np.eye(3)))
@example(([1.0, 2.0, math.nextafter(2.0, 3.0)], [0.3, 0.2, 1.0], np.eye(3)))
@example(([1.0, 2.0, 3.0], [1.0, 1e-3, math.sqrt(1 / 3) * (1 + 1e-15)], np.eye(3)))
@given(free_tops())
@settings(suppress_health_check=[HealthCheck.too_slow])
def test_the_integer_construction_gives_the_floats_of_exact_rational_arithmetic(case):
    J, w, R0 = case
    top = tops.FreeAsymmetricTop(J, w, R0)
    want, amp = _constants_in_fractions(J, w)
    for name, value in want.items():
        assert getattr(top, name) == value, name  # the same float, bit for bit
    if amp is not None:
        assert top._amp.tolist() == amp


@given(free_tops())
@settings(max_examples=10, deadline=None)
def test_state_over_many_instants_in_chunks_is_the_one_pass_path(case):
    J, w, R0 = case
    top = tops.FreeAsymmetricTop(J, w, R0)
    ts = np.linspace(-HORIZON, HORIZON, 2 * tops._CHUNK + 7)
    wc, Rc = top.state(ts)
    # each chunk is exactly the state of its own times
    i = tops._CHUNK
    w1, R1 = top.state(ts[i : 2 * i])
    assert np.array_equal(wc[i : 2 * i], w1)
    assert np.array_equal(Rc[i : 2 * i], R1)
    scale = float(np.abs(w).max()) or 1.0
    assert np.abs(wc - top.omega(ts)).max() <= CHUNK_EPS * EPS * scale
    assert np.abs(Rc - top.attitude(ts)).max() <= CHUNK_EPS * EPS
    # the invariants at every instant: E = ½ Σ J ω² and |L| = |J ω|
    phase = 1.0 + getattr(top, "_lam", 0.0) * np.abs(ts)
    Jv = np.array(J)
    E = 0.5 * (Jv * wc * wc).sum(-1)
    assert (np.abs(E - top.energy) <= CONSERVATION_RTOL * phase * top.energy).all()
    L = np.linalg.norm(Jv * wc, axis=-1)
    L0 = top.angular_momentum_norm
    assert (np.abs(L - L0) <= CONSERVATION_RTOL * phase * L0).all()


def _phase(top, t):
    """1 + λ|t|: the elliptic phase the accuracy figures are per unit of."""
    return 1.0 + getattr(top, "_lam", 0.0) * abs(t)


@example(
    [([1.0, 2.0, 3.0], [0.4, 0.2, 1.0], np.eye(3)), ([3.0, 4.0, 6.0], [2.0, 0.5, 1.0], np.eye(3))],
    7.5,
)
@given(st.lists(free_tops(), min_size=1, max_size=6), st.floats(-HORIZON, HORIZON))
@settings(suppress_health_check=[HealthCheck.too_slow], deadline=None)
def test_a_batch_of_tops_moves_each_top_as_it_moves_alone(cases, t):
    J = np.array([c[0] for c in cases])
    w0 = np.array([c[1] for c in cases])
    R0 = np.array([c[2] for c in cases])
    batch = tops.FreeTopBatch(J, w0, R0)
    w, R = batch.state(t)
    assert w.shape == (len(cases), 3)
    assert R.shape == (len(cases), 3, 3)
    for i, (Ji, wi, Ri) in enumerate(cases):
        top = tops.FreeAsymmetricTop(Ji, wi, Ri)
        # built alike: the same constants
        for name in ("energy", "m", "m1", "_lam", "_u0", "_G0", "_n", "_C"):
            assert getattr(batch.tops[i], name, None) == getattr(top, name, None), name
        w1, R1 = top.state(np.array(t))
        tol = tops.BATCH_EPS * EPS * _phase(top, t)
        scale = float(np.abs(wi).max()) or 1.0
        assert np.abs(w[i] - w1).max() <= tol * scale, i
        assert np.abs(R[i] - R1).max() <= tol, i
        # the invariants: E and L_O from the batch's state
        E = 0.5 * float(np.sum(np.array(Ji) * w[i] ** 2))
        assert abs(E - top.energy) <= CONSERVATION_RTOL * _phase(top, t) * top.energy
        L_O = R[i].T @ (np.array(Ji) * w[i])
        L = top.angular_momentum_norm
        err = np.abs(L_O - top.angular_momentum_space).max()
        assert err <= L_SPACE_RTOL * _phase(top, t) * L


def test_a_batch_takes_each_top_at_its_own_instant_and_broadcasts_one_body():
    J = [1.0, 2.0, 3.0]
    w0 = np.array([[0.4, 0.2, 1.0], [1.0, 0.1, 0.5], [0.0, 0.0, 0.0]])
    batch = tops.FreeTopBatch(J, w0)  # one body, three spins
    ts = np.array([0.5, -3.0, 2.0])
    w, R = batch.state(ts)
    for i in range(3):
        w1, R1 = tops.FreeAsymmetricTop(J, w0[i]).state(np.array(ts[i]))
        np.testing.assert_array_equal(w[i], w1)
        np.testing.assert_array_equal(R[i], R1)
    assert batch.energy.shape == (3,)
    assert batch.angular_momentum_space.shape == (3, 3)


@pytest.mark.parametrize(
    ("kwargs", "named"),
    [
        ({"J": np.ones((4, 3)) * [1, 2, 2.5], "omega_0": np.ones((5, 3))}, "omega_0"),
        (
            {
                "J": np.ones((4, 3)) * [1, 2, 2.5],
                "omega_0": np.ones((4, 3)),
                "R_A_O_0": np.broadcast_to(np.eye(3), (2, 3, 3)),
            },
            "R_A_O_0",
        ),
        ({"J": np.ones((4, 2)), "omega_0": np.ones((4, 3))}, "J"),
        ({"J": [1.0, 2.0, 2.5], "omega_0": np.ones((4, 4))}, "omega_0"),
    ],
)
def test_a_batch_with_mismatched_shapes_is_a_shape_error_naming_the_argument(kwargs, named):
    with pytest.raises(ShapeError, match=named):
        tops.FreeTopBatch(**kwargs)


def test_a_batch_refuses_times_that_do_not_broadcast_and_names_a_bad_top():
    batch = tops.FreeTopBatch([[1.0, 2.0, 2.5]] * 4, np.ones((4, 3)))
    with pytest.raises(ShapeError, match="t has shape"):
        batch.state(np.zeros(3))
    with pytest.raises(NonPhysicalInertiaError, match=r"top \(1,\)"):
        tops.FreeTopBatch([[1.0, 2.0, 2.5], [1.0, 1.0, 3.0]], np.ones((2, 3)))
