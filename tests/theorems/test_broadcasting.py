"""Every function that promises to broadcast does: row i of a batched call is the call on row i.

The batches come from :func:`mechanics.strategies.batches` over the strategies with
the hard regimes, so one call mixes rows that take different branches (a tiny, a
huge and a beyond-π rotation vector; gimbal lock and a general matrix; extreme
mass ratios), which is where a kernel that treats rows apart could mix them up.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import Phase, find, given, settings
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from mechanics import impact as im
from mechanics import inertia as I
from mechanics import rotation as rot
from mechanics import strategies as ms
from mechanics._floats import EPS

#: A row computed in a batch against the same row alone: the same formulas, but
#: numpy's vectorised and scalar loops of sin, cos and sqrt may round differently
#: (an ulp each), and a few such roundings reach an entry.
BROADCAST_RTOL = 8 * EPS

#: Fewer examples than the profile's: each one is a whole batch of draws.
BATCH_SETTINGS = settings(max_examples=40)


def _rows(batch_shape):
    return list(np.ndindex(*batch_shape))


def _same(batched, single, what: str) -> None:
    batched, single = np.asarray(batched, dtype=float), np.asarray(single, dtype=float)
    assert batched.shape == single.shape, what
    scale = max(float(np.abs(single).max(initial=0.0)), 1.0)
    err = float(np.abs(batched - single).max(initial=0.0))
    assert err <= BROADCAST_RTOL * scale, f"{what}: {err:.3g} > {BROADCAST_RTOL * scale:.3g}"


def _check_rows(func, args, n_lead: int, what: str) -> None:
    """func(*args) against func(*row args) for each row of the leading n_lead axes."""
    out = func(*args)
    lead = np.shape(args[0])[:n_lead]
    for idx in _rows(lead):
        single = func(*(a[idx] for a in args))
        if isinstance(out, tuple):
            for k, (b, s) in enumerate(zip(out, single, strict=True)):
                _same(np.asarray(b)[idx], s, f"{what}[{k}] row {idx}")
        else:
            _same(np.asarray(out)[idx], single, f"{what} row {idx}")


# ------------------------------------------------------------------ rotation

VECTOR_FUNCTIONS = [rot.matrix_from_rotvec, rot.quat_from_rotvec]
QUAT_FUNCTIONS = [rot.matrix_from_quat, rot.rotvec_from_quat]
MATRIX_FUNCTIONS = [
    rot.quat_from_matrix,
    rot.rotvec_from_matrix,
    rot.euler_from_matrix,
    rot.nearest_rotation,
    rot.check_rotation,
    rot.is_rotation,
    rot.active_from_passive,
]


@pytest.mark.parametrize("func", VECTOR_FUNCTIONS, ids=lambda f: f.__name__)
def test_rotation_vector_functions_broadcast(func):
    @BATCH_SETTINGS
    @given(ms.batches(ms.rotvecs()))
    def check(v):
        _check_rows(func, (v,), v.ndim - 1, func.__name__)

    check()


@pytest.mark.parametrize("func", QUAT_FUNCTIONS, ids=lambda f: f.__name__)
def test_quaternion_functions_broadcast(func):
    @BATCH_SETTINGS
    @given(ms.batches(ms.quaternions()))
    def check(q):
        _check_rows(func, (q,), q.ndim - 1, func.__name__)

    check()


@pytest.mark.parametrize("func", MATRIX_FUNCTIONS, ids=lambda f: f.__name__)
def test_matrix_functions_broadcast(func):
    @BATCH_SETTINGS
    @given(ms.batches(ms.rotation_matrices()))
    def check(R):
        _check_rows(func, (R,), R.ndim - 2, func.__name__)

    check()


def test_euler_angles_to_matrix_broadcasts():
    @BATCH_SETTINGS
    @given(ms.batches(ms.euler_angles().map(np.array)))
    def check(e):
        psi, theta, phi = np.moveaxis(e, -1, 0)
        _check_rows(rot.matrix_from_euler, (psi, theta, phi), psi.ndim, "matrix_from_euler")

    check()


def test_two_argument_rotation_functions_broadcast():
    @BATCH_SETTINGS
    @given(ms.batches(st.tuples(ms.rotation_matrices(), ms.rotation_matrices()).map(np.array)))
    def check(pair):
        A, B = pair[..., 0, :, :], pair[..., 1, :, :]
        n = A.ndim - 2
        _check_rows(rot.compose, (A, B), n, "compose")
        v = B[..., 0] * 3.0  # a vector per row
        _check_rows(rot.rotate_vector, (A, v), n, "rotate_vector")
        _check_rows(rot.components_A_from_O, (A, v), n, "components_A_from_O")
        q, p = rot.quat_from_matrix(A), rot.quat_from_matrix(B)
        _check_rows(rot.compose_quat, (q, p), n, "compose_quat")
        _check_rows(rot.quat_multiply, (q, p), n, "quat_multiply")

    check()


# ------------------------------------------------------------- impact, inertia


def test_direct_impact_broadcasts_over_masses_velocities_and_e():
    row = st.tuples(ms.mass_pairs(), ms.direct_velocities(), ms.restitution_coefficients())
    flat = row.map(lambda t: np.array([*t[0], *t[1], t[2]]))

    @BATCH_SETTINGS
    @given(ms.batches(flat))
    def check(b):
        args = tuple(np.moveaxis(b, -1, 0))
        n = args[0].ndim
        for func in (
            im.direct_impact,
            im.impulse_direct,
            im.energy_loss_direct,
            im.compression_restitution_impulses,
        ):
            _check_rows(func, args, n, func.__name__)

    check()


def _flat_body():
    """m (1), J_G (9), r (3), n (3): one row of an effective-mass or transfer problem."""
    return st.tuples(
        ms.impact_masses(min_value=1e-3, max_value=1e3),
        ms.impact_inertia_tensors(),
        st.tuples(*(st.floats(-10.0, 10.0),) * 3),
        ms.contact_normals(),
    ).map(lambda t: np.concatenate([[t[0]], np.ravel(t[1]), t[2], t[3]]))


def _unflatten(b):
    m = b[..., 0]
    J = b[..., 1:10].reshape(*b.shape[:-1], 3, 3)
    return m, J, b[..., 10:13], b[..., 13:16]


def test_effective_mass_and_transfer_functions_broadcast():
    @BATCH_SETTINGS
    @given(ms.batches(_flat_body()))
    def check(b):
        m, J, r, n = _unflatten(b)
        k = m.ndim
        _check_rows(im.effective_mass, (m, J, r, n), k, "effective_mass")
        _check_rows(I.parallel_axis, (J, m, r), k, "parallel_axis")
        _check_rows(lambda J: I.principal_axes(J)[0], (J,), k, "principal moments")
        # Principal axes of equal moments are any basis of their plane, and the
        # batched Jacobi sweeps may pick another one than a lone call: compare the
        # realisation by what it promises, the masses and the tensor it realises.
        masses, pos = I.four_particle_realisation(m, J)
        for idx in _rows(m.shape):
            m1, _ = I.four_particle_realisation(m[idx], J[idx])
            _same(masses[idx], m1, f"four_particle_realisation masses row {idx}")
            J_back = I.inertia_tensor(masses[idx], pos[idx], about=np.zeros(3))
            _same(J_back, J[idx], f"four_particle_realisation tensor row {idx}")

    check()


def test_batches_have_the_documented_shapes():
    @settings(max_examples=50)
    @given(ms.batches(ms.rotvecs(), max_rows=6))
    def check(v):
        assert v.shape[-1] == 3
        assert v.ndim in (2, 3)
        assert 1 <= math.prod(v.shape[:-1]) <= 6
        assert v.dtype == np.float64

    check()


BATCH_REGIMES = {
    "one": lambda b: b.shape[:-1] == (1,),
    "rows": lambda b: b.ndim == 2 and b.shape[0] >= 2,
    "grid": lambda b: b.ndim == 3 and min(b.shape[:2]) >= 2,
}


@pytest.mark.parametrize(("regime", "predicate"), list(BATCH_REGIMES.items()))
def test_batches_reach_every_regime(regime, predicate):
    value = find(
        ms.batches(ms.unit_vectors()),
        predicate,
        settings=settings(max_examples=500, database=None, phases=[Phase.generate]),
    )
    assert predicate(value)
    assert set(BATCH_REGIMES) == set(ms.BATCH_REGIMES)


@pytest.mark.parametrize(
    ("kwargs", "quoted"),
    [
        ({"elements": 3.0}, "elements=3.0"),
        ({"max_rows": 3}, "max_rows=3"),
        ({"max_rows": 4.5}, "max_rows=4.5"),
    ],
)
def test_batches_reject_bad_arguments_quoting_them(kwargs, quoted):
    args = {"elements": ms.unit_vectors(), **kwargs}
    elements = args.pop("elements")
    with pytest.raises(InvalidArgument, match=re.escape(quoted)):
        ms.batches(elements, **args)
