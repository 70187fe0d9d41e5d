"""Impact and restitution: direct central impact, free and hinged rigid bodies.

Conventions (Essén 1996, ch. 6)
-------------------------------
- **The normal.**  ``n`` is the impact normal e_n of the book: it points *into
  body 1*, i.e. from body 2 toward body 1.  Any non-zero vector is accepted and
  normalised; a zero normal raises :class:`~mechanics.errors.ZeroNormalError`.
- **The impulse.**  The contact impulse is S n with S ≥ 0: S n acts on body 1
  and −S n on body 2 (action and reaction, S_12 = −S_21 of (6.19)).  The
  functions of the direct impact work on an X axis and return the signed
  x-component S_12 = m_1 (ẋ_1f − ẋ_1i) of the impulse from body 2 on body 1.
- **Normal relative velocity** v_n = n · (v_S1 − v_S2), the velocity of the
  contact point of body 1 relative to that of body 2 along n.  v_n < 0:
  approaching (an impact); v_n > 0: separating; v_n = 0: grazing, the impulse
  is zero.
- **Newton's coefficient of restitution** e ∈ [0, 1] acts on v_n: after the
  impact v_n' = −e v_n (6.36).  e = 1 is elastic, e = 0 plastic.  Outside
  [0, 1] raises :class:`~mechanics.errors.RestitutionRangeError`.
- **Smooth contact**: no tangential impulse, so tangential slip velocities
  change only through the rotation the normal impulse causes.
- **Direct impact on an X axis** (6.36)–(6.41): body 1 lies on the −X side of
  body 2 (behind it) and n = −e_x, so v_n = ẋ_2 − ẋ_1 = Δẋ, the book's relative
  velocity; bodies approach when ẋ_1 > ẋ_2.
- **Separating contacts** (v_n > 0) are not impacts.  By default
  (``separating="raise"``) they raise
  :class:`~mechanics.errors.SeparatingContactError` naming the first one;
  ``separating="ignore"`` is a documented no-op: those contacts get a zero
  impulse and zero energy loss, and their velocities are returned unchanged.
  Never a NaN.
- **Rigid bodies** are :class:`RigidBody` records ``(m, J_G, r_G, v_G, omega)``:
  mass, inertia tensor about the centre of mass G, position of G, velocity of
  G and angular velocity, all in one fixed (observer) basis O.  The contact
  point is a position ``r_S`` in the same basis; it is a required keyword.
  During the impact positions do not change (6.11).
- Masses of rigid bodies must be > 0; in the direct impact one mass may be 0
  (a massless body), not both.  Inertia tensors must be symmetric, positive
  definite and obey the triangle inequality (:func:`mechanics.inertia.check_inertia`).
- Everything is float64 and broadcasts over leading axes: scalars ``(...)``,
  vectors ``(..., 3)``, tensors ``(..., 3, 3)``.

Accuracy (``tests/stability/test_impact_stability.py``, against the exact
rational value of the float inputs, mass ratios 1e-15 … 1e15 at absolute
scales 1e-200 … 1e200, e across [0, 1] including 1e-15, 1 − 1e-12 and one ulp
below 1): :func:`direct_impact`, :func:`impulse_direct`,
:func:`energy_loss_direct` and :func:`compression_restitution_impulses` carry
the relative velocity, 1 ± e, the mass fractions m_k/(m_1 + m_2) and their
products in double-double (error-free transformations) on inputs scaled by
powers of two, so each result is within :data:`DIRECT_ULPS` = 2 ulps of the
exact value (unless the exact result cancels to below 2^-100 of the input
velocities, where the error is bounded by that floor instead); measured worst
0.50 ulp, i.e. correctly rounded in every case met.  The energy loss is
½ μ (1 − e)(1 + e) Δẋ Δẋ: a product of positive factors, no difference of
kinetic energies, no 1 − e*e.  The rigid-body functions use plain float64 and
one 3 × 3 solve per body; their errors scale with the condition number of the
inertia tensor (tests/theorems/test_ch06_restitution.py states the bounds;
10^5 random contacts with condition numbers ≤ 1e2 restitute to 1.2 eps and
conserve momentum to 1.0 eps, tests/benchmarks/test_bench_impact.py).

Speed (``tests/benchmarks/test_bench_impact.py``, 10^5 contacts, 2 shared
cores): the direct impact (velocities and loss) takes ~0.1 s, ~14 times the
naive float64 formulas, whose loss is off by up to 3.4e3 ulps there (1 − e*e
near e = 1) and whose velocities by 1e2 ulps.  The 3-D rigid impact of two free
:class:`RigidBody` records is the solves only, a RigidBody being validated (the
eigenvalues of its tensor) when built: 0.05 s against 0.16 s when the call
validated both bodies (measured on one machine, one after the other, with
``pytest tests/benchmarks/test_bench_impact.py -k rigid --benchmark-enable``).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any, NamedTuple, Self, cast

import numpy as np
import numpy.typing as npt

from ._floats import EPS, SPLIT_LIMIT, Pair
from ._floats import dd_add_float as _dd_add_float
from ._floats import dd_div as _dd_div
from ._floats import dd_mul as _dd_mul
from ._floats import fast_two_sum as _fast_two_sum
from ._floats import two_prod as _two_prod
from ._floats import two_sum as _two_sum
from ._validate import as_float_array, broadcast_checked, finite_result
from .errors import (
    NegativeMassError,
    NonPositiveParameterError,
    OutOfDomainError,
    RestitutionRangeError,
    ResultOverflowError,
    SeparatingContactError,
    ShapeError,
    UnknownOptionError,
    ZeroNormalError,
    ZeroTotalMassError,
)
from .inertia import check_inertia

__all__ = [
    "DIRECT_ULPS",
    "CentreOfPercussion",
    "HingedImpact",
    "RigidBody",
    "RigidImpact",
    "centre_of_percussion",
    "compression_restitution_impulses",
    "direct_impact",
    "effective_mass",
    "energy_loss_direct",
    "hinged_effective_mass",
    "hinged_impact",
    "impulse_direct",
    "normal_relative_velocity",
    "rigid_impact",
]


#: Promised accuracy of the direct-impact functions, in ulps of the exact
#: result: the double-double products carry ~2^-104 relative error, so only the
#: final rounding (½ ulp) and, for velocities, the last addition remain; the
#: stability tests measure at most 0.5 ulp (see the module docstring).
DIRECT_ULPS = 2.0

_SEPARATING = ("raise", "ignore")


class _RigidBodyFields(NamedTuple):
    m: np.ndarray
    J_G: np.ndarray
    r_G: np.ndarray
    v_G: np.ndarray
    omega: np.ndarray


class RigidBody(_RigidBodyFields):
    """A free rigid body's state, all vectors in one fixed basis O.

    Domain: validated when built (``RigidBody(...)``, ``_replace``, ``_make``), each error naming
    the field: ``m`` > 0 (else NegativeMassError or NonPositiveParameterError), ``J_G`` positive
    definite as :func:`~mechanics.inertia.check_inertia` (else NonPhysicalInertiaError), finite
    ``r_G``, ``v_G``, ``omega`` (..., 3); NaN, inf, strings, ``None`` and wrong shapes raise
    NonFiniteError or ShapeError.  The batch axes of the fields must broadcast together, else
    ShapeError listing each field's shape.  The fields are kept as float64 arrays, otherwise as
    given (``J_G`` is not symmetrised).

    A named tuple: it unpacks as ``m, J_G, r_G, v_G, omega``.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass, kg, > 0.
    J_G : array_like, shape (..., 3, 3)
        Inertia tensor about the centre of mass G, kg m², positive definite.
    r_G : array_like, shape (..., 3)
        Position of G, m.
    v_G : array_like, shape (..., 3)
        Velocity of G, m/s.
    omega : array_like, shape (..., 3)
        Angular velocity, rad/s.

    Raises
    ------
    NegativeMassError
        If ``m`` < 0.
    NonPositiveParameterError
        If ``m`` = 0 (a rigid body has a mass).
    NonPhysicalInertiaError
        If ``J_G`` is not symmetric, not positive definite or breaks the triangle
        inequality (:func:`~mechanics.inertia.check_inertia`).
    NonFiniteError
        If a field holds NaN or an infinity.
    ShapeError
        If a field is not a real numeric array, has the wrong trailing shape, or the
        fields' batch axes do not broadcast.

    Examples
    --------
    The momentum m v_G of the unpacked fields, and the validation of every field:

    >>> m, J_G, r_G, v_G, omega = RigidBody(2.0, np.eye(3), [0, 0, 0], [1, 0, 0], [0, 0, 0])
    >>> (m * v_G).tolist()
    [2.0, 0.0, 0.0]
    >>> RigidBody(-1.0, np.eye(3), [0, 0, 0], [0, 0, 0], [0, 0, 0])
    Traceback (most recent call last):
    ...
    mechanics.errors.NegativeMassError: m must be >= 0; found -1.0 at index ()
    """

    __slots__ = ()

    def __new__(
        cls,
        m: npt.ArrayLike,
        J_G: npt.ArrayLike,
        r_G: npt.ArrayLike,
        v_G: npt.ArrayLike,
        omega: npt.ArrayLike,
    ) -> Self:
        return tuple.__new__(cls, _body_fields(m, J_G, r_G, v_G, omega, ""))

    # namedtuple's own bypasses __new__ (and so would _replace).  The ignore: mypy synthesises
    # the NamedTuple's _make as a generic function of `_cls: type[_NT]` and reports every
    # classmethod override of it as incompatible, even one of the same signature (mypy 2.4)
    @classmethod
    def _make(cls, iterable: Iterable[Any]) -> Self:  # type: ignore[override]
        return cls(*iterable)


def _body_fields(
    m: npt.ArrayLike,
    J_G: npt.ArrayLike,
    r_G: npt.ArrayLike,
    v_G: npt.ArrayLike,
    omega: npt.ArrayLike,
    prefix: str,
) -> tuple[np.ndarray, ...]:
    """The validated fields of a :class:`RigidBody`, errors naming ``prefix + field``."""
    fields = (
        _check_mass(m, prefix + "m", allow_zero=False),
        check_inertia(J_G, name=prefix + "J_G"),
        as_float_array(r_G, prefix + "r_G", (3,)),
        as_float_array(v_G, prefix + "v_G", (3,)),
        as_float_array(omega, prefix + "omega", (3,)),
    )
    batches = [fields[0].shape, fields[1].shape[:-2], *(f.shape[:-1] for f in fields[2:])]
    try:
        np.broadcast_shapes(*batches)
    except ValueError:
        shapes = ", ".join(
            f"{prefix}{name} {f.shape}"
            for name, f in zip(_RigidBodyFields._fields, fields, strict=True)
        )
        raise ShapeError(
            f"the batch axes of the rigid body's fields do not broadcast: {shapes}"
        ) from None
    return fields


def _trusted_body(
    m: np.ndarray, J_G: np.ndarray, r_G: np.ndarray, v_G: np.ndarray, omega: np.ndarray
) -> RigidBody:
    """A :class:`RigidBody` of fields computed here from validated ones (the bodies after an
    impact): not checked again (``finite_result`` checks them as a result)."""
    return tuple.__new__(RigidBody, (m, J_G, r_G, v_G, omega))


class RigidImpact(NamedTuple):
    """Result of :func:`rigid_impact`.

    A named tuple of the fields below, as :func:`rigid_impact` returns them; it
    validates nothing.

    Parameters
    ----------
    S : ndarray, shape (...)
        The impulse magnitude, N s, ≥ 0 (S n on body 1, −S n on body 2).
    mu : ndarray, shape (...)
        The effective mass of the contact, kg (:func:`effective_mass`).
    v_n : ndarray, shape (...)
        The normal relative velocity before, m/s.
    Q : ndarray, shape (...)
        The kinetic energy lost ½ μ (1 − e²) v_n², J.
    body_1 : RigidBody
        The state of body 1 after.
    body_2 : RigidBody or None
        The state of body 2 after; ``None`` for a fixed body 2.

    Examples
    --------
    The impulse is S = −(1 + e) μ v_n, and the loss ½ μ (1 − e²) v_n²:

    >>> ball = RigidBody(2.0, 0.8 * np.eye(3), [0, 0, 1], [0, 0, -3], [0, 0, 0])
    >>> out = rigid_impact(ball, r_S=[0, 0, 0], n=[0, 0, 1], e=0.5)
    >>> float(out.S), float(-(1 + 0.5) * out.mu * out.v_n)
    (9.0, 9.0)
    >>> float(out.Q), float(0.5 * out.mu * (1 - 0.5**2) * out.v_n**2)
    (6.75, 6.75)
    """

    S: np.ndarray
    mu: np.ndarray
    v_n: np.ndarray
    Q: np.ndarray
    body_1: RigidBody
    body_2: RigidBody | None


class HingedImpact(NamedTuple):
    """Result of :func:`hinged_impact`.

    A named tuple of the fields below, as :func:`hinged_impact` returns them; it
    validates nothing.

    Parameters
    ----------
    omega : ndarray, shape (...)
        The angular velocity about the axis after the blow (component along the
        unit axis), rad/s.
    S_axis : ndarray, shape (..., 3)
        The total reaction impulse of the axis on the body, N s.
    M_axis : ndarray, shape (..., 3)
        The reaction impulsive moment about the axis point, N m s (perpendicular
        to the axis: the bearings are frictionless).
    S_bearings : ndarray, shape (..., 2, 3), or None
        The reaction impulses at the two bearings when asked for, N s (their axial
        parts are statically indeterminate: the total axial impulse is given to
        the first bearing), else ``None``.

    Examples
    --------
    The two bearings' impulses add up to the axis's:

    >>> out = hinged_impact(3.0, np.diag([1e-6, 4.0, 4.0]), [1, 0, 0], axis_point=[0, 0, 0],
    ...                     axis=[0, 0, 1], omega=0.0, r_P=[1.5, 0, 0], S_P=[0, 1.0, 0],
    ...                     bearings=(-1.0, 1.0))
    >>> out.S_bearings.sum(axis=0).round(12).tolist(), out.S_axis.round(12).tolist()
    ([0.0, 0.125, 0.0], [0.0, 0.125, 0.0])
    """

    omega: np.ndarray
    S_axis: np.ndarray
    M_axis: np.ndarray
    S_bearings: np.ndarray | None


class CentreOfPercussion(NamedTuple):
    """Result of :func:`centre_of_percussion`: where and along what to strike.

    A named tuple of the fields below, as :func:`centre_of_percussion` returns
    them; it validates nothing.

    Parameters
    ----------
    point : ndarray, shape (..., 3)
        The point of a blow that loads the axis with no impulse, m.
    direction : ndarray, shape (..., 3)
        The unit direction of that blow.

    Examples
    --------
    A rod of length 3 hinged at one end: the point 2ℓ/3 = 2 from the hinge, struck
    across the rod:

    >>> P, b = centre_of_percussion(2.0, np.diag([1e-6, 6.0, 6.0]), [1.5, 0, 0],
    ...                             axis_point=[0, 0, 0], axis=[0, 0, 1])
    >>> P.round(12).tolist(), b.tolist(), float(np.dot(b, b))
    ([2.0, 0.0, 0.0], [0.0, 1.0, 0.0], 1.0)
    """

    point: np.ndarray
    direction: np.ndarray


# ------------------------------------------------------------- validation


def _check_e(e: npt.ArrayLike) -> np.ndarray:
    a = as_float_array(e, "e")
    bad = (a < 0) | (a > 1)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        raise RestitutionRangeError(
            f"coefficient of restitution e must lie in [0, 1]; found {float(a[idx])!r}"
            f" at index {idx}"
        )
    return a


def _check_mass(m: npt.ArrayLike, name: str, *, allow_zero: bool) -> np.ndarray:
    a = as_float_array(m, name)
    neg = a < 0
    if neg.any():
        idx = tuple(int(i) for i in np.argwhere(neg)[0])
        raise NegativeMassError(f"{name} must be >= 0; found {float(a[idx])!r} at index {idx}")
    if not allow_zero and (a == 0).any():
        idx = tuple(int(i) for i in np.argwhere(a == 0)[0])
        raise NonPositiveParameterError(
            f"{name} must be > 0 for a rigid body; found 0.0 at index {idx}"
        )
    return a


def _check_option(separating: str) -> str:
    if separating not in _SEPARATING:
        raise UnknownOptionError(f"separating must be 'raise' or 'ignore'; got {separating!r}")
    return separating


def _unit(n: npt.ArrayLike, name: str) -> np.ndarray:
    a = as_float_array(n, name, (3,))
    scale = np.abs(a).max(axis=-1, keepdims=True)
    zero = scale[..., 0] == 0
    if zero.any():
        idx = tuple(int(i) for i in np.argwhere(zero)[0])
        raise ZeroNormalError(f"{name} must be a non-zero vector; found {a[idx].tolist()}")
    b = a / scale  # scaled first: |n|² cannot overflow or underflow
    out: np.ndarray = b / np.sqrt((b * b).sum(axis=-1, keepdims=True))
    return out


def _check_inertia(J: npt.ArrayLike, name: str) -> np.ndarray:
    """:func:`mechanics.inertia.check_inertia` (positive definite: J⁻¹ is needed),
    returned symmetrised so that the solves below see an exactly symmetric tensor."""
    return _symmetrised(check_inertia(J, name=name))


def _symmetrised(a: np.ndarray) -> np.ndarray:
    """(J + Jᵀ)/2, exactly symmetric; halved first where J + Jᵀ would overflow."""
    with np.errstate(over="ignore"):
        s: np.ndarray = 0.5 * (a + np.swapaxes(a, -1, -2))
    if not np.isfinite(s).all():
        s = 0.5 * a + 0.5 * np.swapaxes(a, -1, -2)
    return s


def _first(mask: np.ndarray) -> tuple[int, ...]:
    return tuple(int(i) for i in np.argwhere(mask)[0])


def _batches(what: str, **shapes: tuple[int, ...]) -> tuple[int, ...]:
    """The common batch shape of the named arguments' batch axes (a body's: of all its
    fields), else a ShapeError listing each one."""
    try:
        return np.broadcast_shapes(*shapes.values())
    except ValueError:
        listed = ", ".join(f"{k} {v}" for k, v in shapes.items())
        raise ShapeError(
            f"{what}: the batch axes of the arguments do not broadcast: {listed}"
        ) from None


def _body_batch(b: RigidBody) -> tuple[int, ...]:
    return np.broadcast_shapes(b.m.shape, b.J_G.shape[:-2], *(f.shape[:-1] for f in b[2:]))


def _separation(v_n: np.ndarray, separating: str, scale: np.ndarray | None = None) -> np.ndarray:
    """The mask of approaching-or-grazing contacts; raise on separating ones if asked.

    ``scale``: exponents k of a v_n given as v_n 2^-k (the message shows v_n).
    """
    sep = v_n > 0
    if separating == "raise" and sep.any():
        idx = _first(sep) if sep.ndim else ()
        shown = v_n[idx] if scale is None else np.ldexp(v_n[idx], scale[idx])
        raise SeparatingContactError(
            f"the bodies separate (normal relative velocity v_n = {float(shown)!r} > 0"
            f" at index {idx}); there is no impact. Pass separating='ignore' for a no-op"
        )
    return ~sep


def _overflow(x: np.ndarray, what: str) -> np.ndarray:
    if not np.isfinite(x).all():
        idx = _first(~np.isfinite(x)) if x.ndim else ()
        raise ResultOverflowError(f"{what} overflows float64 at index {idx} (finite input)")
    return x


def _scale_exponent(*xs: np.ndarray) -> np.ndarray:
    """k with max |x| < 2**k (0 when all are 0): x * 2**-k is exact and <= 1."""
    big = np.abs(xs[0])
    for x in xs[1:]:
        big = np.maximum(big, np.abs(x))
    out: np.ndarray = np.frexp(big)[1]
    return out


class _Direct(NamedTuple):
    """Scaled inputs and exact or double-double intermediates of a direct impact."""

    m1s: np.ndarray  # m_1 2^-km
    v1s: np.ndarray  # ẋ_1 2^-kv
    v2s: np.ndarray
    e: np.ndarray
    km: np.ndarray
    kv: np.ndarray
    delta: Pair  # Δẋ 2^-kv, exact
    approach: np.ndarray  # not separating
    w1: Pair  # m_2/(m_1 + m_2)
    w2: Pair  # m_1/(m_1 + m_2)


def _reduced_mass(d: _Direct) -> Pair:
    """μ 2^-km = m_1 2^-km · m_2/(m_1 + m_2), double-double."""
    p, err = _two_prod(d.m1s, d.w1[0])
    return _fast_two_sum(p, err + d.m1s * d.w1[1])


def _direct_parts(
    m_1: npt.ArrayLike,
    m_2: npt.ArrayLike,
    v_1: npt.ArrayLike,
    v_2: npt.ArrayLike,
    e: npt.ArrayLike,
    separating: str,
) -> _Direct:
    m1 = _check_mass(m_1, "m_1", allow_zero=True)
    m2 = _check_mass(m_2, "m_2", allow_zero=True)
    v1 = as_float_array(v_1, "v_1")
    v2 = as_float_array(v_2, "v_2")
    ee = _check_e(e)
    _check_option(separating)
    m1, m2, v1, v2, ee = np.broadcast_arrays(m1, m2, v1, v2, ee)
    zero = (m1 == 0) & (m2 == 0)
    if zero.any():
        idx = _first(zero) if zero.ndim else ()
        raise ZeroTotalMassError(f"m_1 + m_2 must be > 0; both masses are 0 at index {idx}")
    km = _scale_exponent(m1, m2)
    kv = _scale_exponent(v1, v2)
    m1s, m2s = np.ldexp(m1, -km), np.ldexp(m2, -km)
    v1s, v2s = np.ldexp(v1, -kv), np.ldexp(v2, -kv)
    delta = _two_sum(v2s, -v1s)  # Δẋ = ẋ_2 − ẋ_1, exact
    # _two_sum is typed for floats or arrays; given arrays, it returns arrays
    approach = _separation(cast(np.ndarray, delta[0]), separating, kv)
    total = _two_sum(m1s, m2s)  # m_1 + m_2, exact
    w1 = _dd_div(m2s, total)  # m_2 / (m_1 + m_2)
    w2 = _dd_div(m1s, total)  # m_1 / (m_1 + m_2)
    return _Direct(m1s, v1s, v2s, ee, km, kv, delta, approach, w1, w2)


# ---------------------------------------------------------- direct impact


def direct_impact(
    m_1: npt.ArrayLike,
    m_2: npt.ArrayLike,
    v_1: npt.ArrayLike,
    v_2: npt.ArrayLike,
    e: npt.ArrayLike,
    *,
    separating: str = "raise",
) -> tuple[np.ndarray, np.ndarray]:
    """Velocities after a direct central impact, (6.36)–(6.38).

    Domain: masses ``m_1``, ``m_2`` ≥ 0, not both 0 (else NegativeMassError, ZeroTotalMassError),
    any finite ``v_1``, ``v_2`` and ``e`` in [0, 1] (else RestitutionRangeError), broadcast
    together; any magnitudes, 1e-300 to 1e300 (operands are scaled by powers of two: no intermediate
    overflows), a result beyond float64 raising ResultOverflowError.  ``separating``: 'raise'
    (SeparatingContactError where ẋ_2 > ẋ_1) or 'ignore' (else UnknownOptionError).  Batches that do
    not broadcast (2 against 3) raise ShapeError listing each argument's shape.

    Parameters
    ----------
    m_1, m_2 : array_like, shape (...)
        Masses, kg, ≥ 0, not both 0.
    v_1, v_2 : array_like, shape (...)
        Velocities ẋ_1, ẋ_2 along the X axis before, m/s; body 1 is behind body 2,
        so they approach when ẋ_1 > ẋ_2.
    e : array_like, shape (...)
        Coefficient of restitution in [0, 1].
    separating : {"raise", "ignore"}
        What to do where ẋ_2 > ẋ_1 (see the module Conventions).

    Returns
    -------
    v_1f, v_2f : ndarray, shape (...)
        Velocities after, m/s, within :data:`DIRECT_ULPS` ulps of the exact ones.

    Raises
    ------
    NegativeMassError
        If a mass is negative.
    ZeroTotalMassError
        Where both masses are 0.
    RestitutionRangeError
        If ``e`` lies outside [0, 1].
    SeparatingContactError
        Where ẋ_2 > ẋ_1 (the bodies separate), with ``separating="raise"``.
    UnknownOptionError
        If ``separating`` is neither "raise" nor "ignore".
    ResultOverflowError
        If a velocity after exceeds float64's range.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, or the arguments do not broadcast.

    Notes
    -----
    With μ = m_1 m_2 / (m_1 + m_2) and Δẋ = ẋ_2 − ẋ_1, momentum (6.37) and
    restitution (6.38) give ẋ_1f = ẋ_1 + (1 + e) m_2/(m_1 + m_2) Δẋ and
    ẋ_2f = ẋ_2 − (1 + e) m_1/(m_1 + m_2) Δẋ, evaluated in double-double.

    References
    ----------
    Essén (1996), eqs. (6.36)–(6.38).

    Examples
    --------
    Momentum before equals momentum after, and Δẋ_f = −e Δẋ_i:

    >>> v1f, v2f = direct_impact(1.0, 3.0, 5.0, -3.0, 0.5)
    >>> float(v1f), float(v2f)
    (-4.0, 0.0)
    >>> bool(1.0 * 5.0 + 3.0 * (-3.0) == 1.0 * v1f + 3.0 * v2f)
    True
    >>> bool(v2f - v1f == -0.5 * (-3.0 - 5.0))
    True
    """
    d = _direct_parts(m_1, m_2, v_1, v_2, e, separating)
    one_plus_e = _two_sum(1.0, d.e)
    k1 = _dd_mul(one_plus_e, d.w1)
    k2 = _dd_mul(one_plus_e, d.w2)
    c1 = _dd_mul(k1, d.delta)
    c2 = _dd_mul(k2, d.delta)
    v1f = _dd_add_float(d.v1s, c1)
    v2f = _dd_add_float(d.v2s, (-c2[0], -c2[1]))
    v1f = np.where(d.approach, v1f, d.v1s)
    v2f = np.where(d.approach, v2f, d.v2s)
    with np.errstate(over="ignore"):
        out1, out2 = np.ldexp(v1f, d.kv), np.ldexp(v2f, d.kv)
    return _overflow(out1, "v_1f")[()], _overflow(out2, "v_2f")[()]


direct_impact = broadcast_checked(direct_impact)


def impulse_direct(
    m_1: npt.ArrayLike,
    m_2: npt.ArrayLike,
    v_1: npt.ArrayLike,
    v_2: npt.ArrayLike,
    e: npt.ArrayLike,
    *,
    separating: str = "raise",
) -> np.ndarray:
    """The impulse S_12 = m_1 (ẋ_1f − ẋ_1i) from body 2 on body 1 along X, (6.19).

    Domain: as :func:`direct_impact`: ``m_1``, ``m_2`` ≥ 0 not both 0, finite velocities, ``e`` in
    [0, 1], any magnitudes (scaled by powers of two), a result beyond float64 raising
    ResultOverflowError; batches that do not broadcast raise ShapeError listing each argument's
    shape.

    S_12 = (1 + e) μ Δẋ with μ = m_1 m_2/(m_1 + m_2), Δẋ = ẋ_2 − ẋ_1; body 2
    receives −S_12 (6.46).

    Parameters
    ----------
    m_1, m_2 : array_like, shape (...)
        Masses, kg, ≥ 0, not both 0.
    v_1, v_2 : array_like, shape (...)
        Velocities ẋ_1, ẋ_2 along the X axis before, m/s; body 1 is behind body 2,
        so they approach when ẋ_1 > ẋ_2.
    e : array_like, shape (...)
        Coefficient of restitution in [0, 1].
    separating : {"raise", "ignore"}
        What to do where ẋ_2 > ẋ_1 (see the module Conventions).

    Returns
    -------
    S_12 : ndarray, shape (...)
        The x-component of the impulse on body 1, N s (≤ 0 for an impact: body 1 is
        behind and is pushed back; 0 for an ignored separating contact), within
        :data:`DIRECT_ULPS` ulps.

    Raises
    ------
    NegativeMassError
        If a mass is negative.
    ZeroTotalMassError
        Where both masses are 0.
    RestitutionRangeError
        If ``e`` lies outside [0, 1].
    SeparatingContactError
        Where ẋ_2 > ẋ_1 (the bodies separate), with ``separating="raise"``.
    UnknownOptionError
        If ``separating`` is neither "raise" nor "ignore".
    ResultOverflowError
        If the impulse exceeds float64's range.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, or the arguments do not broadcast.

    References
    ----------
    Essén (1996), eqs. (6.19), (6.36)–(6.38).

    Examples
    --------
    The impulse is the change of momentum of body 1, and minus that of body 2:

    >>> S = impulse_direct(1.0, 3.0, 5.0, -3.0, 0.5)
    >>> v1f, v2f = direct_impact(1.0, 3.0, 5.0, -3.0, 0.5)
    >>> float(S), float(1.0 * (v1f - 5.0)), float(-3.0 * (v2f - (-3.0)))
    (-9.0, -9.0, -9.0)
    """
    d = _direct_parts(m_1, m_2, v_1, v_2, e, separating)
    mu = _reduced_mass(d)
    s = _dd_mul(_dd_mul(mu, _two_sum(1.0, d.e)), d.delta)
    with np.errstate(over="ignore"):
        out = np.ldexp(np.where(d.approach, s[0] + s[1], 0.0), d.km + d.kv)
    return _overflow(out, "the impulse S_12")[()]


impulse_direct = broadcast_checked(impulse_direct)


def energy_loss_direct(
    m_1: npt.ArrayLike,
    m_2: npt.ArrayLike,
    v_1: npt.ArrayLike,
    v_2: npt.ArrayLike,
    e: npt.ArrayLike,
    *,
    separating: str = "raise",
) -> np.ndarray:
    """Kinetic energy lost in a direct impact, Q = ½ μ (1 − e²) (Δẋ)², (6.41).

    Domain: as :func:`direct_impact`: ``m_1``, ``m_2`` ≥ 0 not both 0, finite velocities, ``e`` in
    [0, 1], any magnitudes (no overflow of m_1 m_2 or Δẋ² where Q is representable), a Q beyond
    float64 raising ResultOverflowError; batches that do not broadcast raise ShapeError listing each
    argument's shape.

    Evaluated as ½ μ (1 − e)(1 + e) Δẋ Δẋ with μ = m_1 · m_2/(m_1 + m_2), every
    factor positive and exact or carried in double-double on operands scaled by
    powers of two: no difference of kinetic energies, no overflow of m_1 m_2 or
    Δẋ² where Q itself is representable, within :data:`DIRECT_ULPS` ulps for
    any mass ratio and e (1 − e is exact for e ≥ ½).

    Parameters
    ----------
    m_1, m_2 : array_like, shape (...)
        Masses, kg, ≥ 0, not both 0.
    v_1, v_2 : array_like, shape (...)
        Velocities ẋ_1, ẋ_2 along the X axis before, m/s; body 1 is behind body 2,
        so they approach when ẋ_1 > ẋ_2.
    e : array_like, shape (...)
        Coefficient of restitution in [0, 1].
    separating : {"raise", "ignore"}
        What to do where ẋ_2 > ẋ_1 (see the module Conventions).

    Returns
    -------
    Q : ndarray, shape (...)
        The kinetic energy lost, J, ≥ 0, within :data:`DIRECT_ULPS` ulps; a
        separating contact loses nothing under ``separating="ignore"``.

    Raises
    ------
    NegativeMassError
        If a mass is negative.
    ZeroTotalMassError
        Where both masses are 0.
    RestitutionRangeError
        If ``e`` lies outside [0, 1].
    SeparatingContactError
        Where ẋ_2 > ẋ_1 (the bodies separate), with ``separating="raise"``.
    UnknownOptionError
        If ``separating`` is neither "raise" nor "ignore".
    ResultOverflowError
        If Q exceeds float64's range.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, or the arguments do not broadcast.

    References
    ----------
    Essén (1996), eqs. (6.35), (6.40), (6.41).

    Examples
    --------
    The loss is the drop of the kinetic energy (6.39):

    >>> Q = energy_loss_direct(1.0, 3.0, 5.0, -3.0, 0.5)
    >>> v1f, v2f = direct_impact(1.0, 3.0, 5.0, -3.0, 0.5)
    >>> T = lambda v1, v2: 0.5 * 1.0 * v1**2 + 0.5 * 3.0 * v2**2
    >>> float(Q), float(T(5.0, -3.0) - T(v1f, v2f))
    (18.0, 18.0)
    """
    d = _direct_parts(m_1, m_2, v_1, v_2, e, separating)
    mu = _reduced_mass(d)
    restitution = _dd_mul(_two_sum(1.0, -d.e), _two_sum(1.0, d.e))  # (1 − e)(1 + e)
    q = _dd_mul(_dd_mul(mu, restitution), _dd_mul(d.delta, d.delta))
    with np.errstate(over="ignore"):
        out = np.ldexp(np.where(d.approach, q[0] + q[1], 0.0), d.km + 2 * d.kv - 1)
    return _overflow(out, "the energy loss Q")[()]


energy_loss_direct = broadcast_checked(energy_loss_direct)


def compression_restitution_impulses(
    m_1: npt.ArrayLike,
    m_2: npt.ArrayLike,
    v_1: npt.ArrayLike,
    v_2: npt.ArrayLike,
    e: npt.ArrayLike,
    *,
    separating: str = "raise",
) -> tuple[np.ndarray, np.ndarray]:
    """The impulses on body 1 in the compression and restitution phases (Example 6.3).

    Domain: as :func:`direct_impact`: ``m_1``, ``m_2`` ≥ 0 not both 0, finite velocities, ``e`` in
    [0, 1] (down to the smallest normal keeps its digits), a result beyond float64 raising
    ResultOverflowError; batches that do not broadcast raise ShapeError listing each argument's
    shape.

    During compression the bodies reach the common velocity ẋ_G of the centre
    of mass, so S_1 = m_1 (ẋ_G − ẋ_1i) = μ Δẋ; during restitution
    S_2 = m_1 (ẋ_1f − ẋ_G) = e μ Δẋ, so S_2/S_1 = e (6.42).  Both are
    x-components of the impulse from body 2 on body 1 (body 2 receives their
    negatives, (6.46)); S_1 + S_2 is :func:`impulse_direct`.

    Parameters
    ----------
    m_1, m_2 : array_like, shape (...)
        Masses, kg, ≥ 0, not both 0.
    v_1, v_2 : array_like, shape (...)
        Velocities ẋ_1, ẋ_2 along the X axis before, m/s; body 1 is behind body 2,
        so they approach when ẋ_1 > ẋ_2.
    e : array_like, shape (...)
        Coefficient of restitution in [0, 1].
    separating : {"raise", "ignore"}
        What to do where ẋ_2 > ẋ_1 (see the module Conventions).

    Returns
    -------
    S_1, S_2 : ndarray, shape (...)
        Compression and restitution impulses, N s, each within :data:`DIRECT_ULPS`
        ulps (S_2 rounds the exact e μ Δẋ once).

    Raises
    ------
    NegativeMassError
        If a mass is negative.
    ZeroTotalMassError
        Where both masses are 0.
    RestitutionRangeError
        If ``e`` lies outside [0, 1].
    SeparatingContactError
        Where ẋ_2 > ẋ_1 (the bodies separate), with ``separating="raise"``.
    UnknownOptionError
        If ``separating`` is neither "raise" nor "ignore".
    ResultOverflowError
        If an impulse exceeds float64's range.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, or the arguments do not broadcast.

    References
    ----------
    Essén (1996), Example 6.3, eqs. (6.42)–(6.50).

    Examples
    --------
    The compression impulse brings body 1 to the centre-of-mass velocity:

    >>> S1, S2 = compression_restitution_impulses(1.0, 3.0, 5.0, -3.0, 0.5)
    >>> v_G = (1.0 * 5.0 + 3.0 * (-3.0)) / 4.0
    >>> float(S1), 1.0 * (v_G - 5.0), float(S2 / S1)
    (-6.0, -6.0, 0.5)
    """
    d = _direct_parts(m_1, m_2, v_1, v_2, e, separating)
    mu = _reduced_mass(d)
    s1 = _dd_mul(mu, d.delta)
    k = d.km + d.kv
    with np.errstate(over="ignore", invalid="ignore"):
        out1 = np.ldexp(np.where(d.approach, s1[0] + s1[1], 0.0), k)
        # e S1 at full scale: in the scaled units a tiny e (down to the smallest normal)
        # would push the product into the subnormals and lose its digits there.  Dekker's
        # split overflows from SPLIT_LIMIT on: a huge S1 is multiplied 2**64 lower and
        # scaled back (powers of two: the same rounding)
        hi, lo = np.ldexp(s1[0], k), np.ldexp(s1[1], k)
        down = np.where(np.abs(hi) >= SPLIT_LIMIT, -64, 0)
        s2 = _dd_mul((np.ldexp(hi, down), np.ldexp(lo, down)), (d.e, np.zeros_like(d.e)))
        out2 = np.where(d.approach, np.ldexp(s2[0] + s2[1], -down), 0.0)
    out1 = _overflow(out1, "S_1")
    return out1[()], _overflow(out2, "S_2")[()]


compression_restitution_impulses = broadcast_checked(compression_restitution_impulses)


# ------------------------------------------------------------ rigid bodies


def _body(body: RigidBody | Sequence[npt.ArrayLike], name: str) -> RigidBody:
    """``body`` (a RigidBody, validated when built, or a 5-tuple, validated here with errors
    naming ``name.field``) with ``J_G`` symmetrised for the solves."""
    if isinstance(body, RigidBody):
        m, J, r, v, w = body
    else:
        try:
            m0, J0, r0, v0, w0 = body
        except (TypeError, ValueError):
            raise OutOfDomainError(
                f"{name} must be a RigidBody(m, J_G, r_G, v_G, omega); got {body!r}"
            ) from None
        m, J, r, v, w = _body_fields(m0, J0, r0, v0, w0, f"{name}.")
    return _trusted_body(m, _symmetrised(J), r, v, w)


def _normalised(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(w, k) with v = w 2^k (exact) and the largest |w_i| in [1/2, 1) (w = 0, k = 0 for
    v = 0), over the last axis."""
    k = np.frexp(np.abs(v).max(axis=-1))[1]
    return np.ldexp(v, -k[..., None]), k


def _solve(J: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(x, k) with J⁻¹ b = x 2^k, for (..., 3, 3) and (..., 3), broadcasting: the solve on
    J and b each scaled by a power of two to a largest entry in [1/2, 1) (exact), whose
    factor the caller applies where its product is formed, so that nothing under- or
    overflows on the way unless the product does.  A tensor with subnormal entries keeps
    its digits (solved unscaled, μ came out 5.5 % off at moments ~2^-1040 and 0 at
    2^-1052, for a normal exact μ).  The same bits as the unscaled solve wherever that
    neither under- nor overflows."""
    shape = np.broadcast_shapes(J.shape[:-2], b.shape[:-1])
    J = np.broadcast_to(J, (*shape, 3, 3))
    bs, j = _normalised(np.broadcast_to(b, (*shape, 3)))
    k = np.frexp(np.abs(J).max(axis=(-2, -1)))[1]  # > 0: J is positive definite
    x = np.linalg.solve(np.ldexp(J, -k[..., None, None]), bs[..., None])[..., 0]
    return x, j - k


def _quadratic(u: np.ndarray, J: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(u·J⁻¹u, x, k) with J⁻¹u = x 2^k (:func:`_solve`): the dot formed on the scaled u
    and x, then scaled once."""
    us, j = _normalised(u)  # u = us 2^j
    x, k = _solve(J, us)  # J⁻¹us = x 2^k
    q: np.ndarray = np.ldexp(_dot(us, x), 2 * j + k)
    return q, x, k + j


def _times(S: np.ndarray, x: np.ndarray, k: np.ndarray) -> np.ndarray:
    """S x 2^k (S of shape (...), x (..., 3)): S's mantissa times x, then one scaling."""
    ms, e = np.frexp(S)
    out: np.ndarray = np.ldexp(ms[..., None] * x, (e + k)[..., None])
    return out


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    out: np.ndarray = (a * b).sum(axis=-1)
    return out


def _inverse_mass(m: np.ndarray, J: np.ndarray, r: np.ndarray, n: np.ndarray) -> np.ndarray:
    out: np.ndarray = 1.0 / m + _quadratic(np.cross(r, n), J)[0]
    return out


def effective_mass(
    m_1: npt.ArrayLike,
    J_1: npt.ArrayLike,
    r_1: npt.ArrayLike,
    n: npt.ArrayLike,
    m_2: npt.ArrayLike | None = None,
    J_2: npt.ArrayLike | None = None,
    r_2: npt.ArrayLike | None = None,
) -> np.ndarray:
    """Effective mass μ of a contact of one or two free rigid bodies along ``n``.

    Domain: ``m_1`` (and ``m_2``) > 0 (else NegativeMassError or NonPositiveParameterError), ``J_1``
    (``J_2``) positive definite as :func:`~mechanics.inertia.check_inertia` (else
    NonPhysicalInertiaError), finite arms ``r_1`` (``r_2``) (..., 3), a non-zero ``n`` (else
    ZeroNormalError), body 2 given whole or not at all (else OutOfDomainError).  Arms so long that
    (r × n)·J⁻¹(r × n) overflows (beyond about 1e154 radii of gyration) give μ = 0: the exact μ then
    lies below about 1e-308, in the subnormals or below them; batches that do not broadcast raise
    ShapeError listing each argument's shape.

    1/μ = 1/m_1 + (r_1 × n)·J_1⁻¹(r_1 × n) + 1/m_2 + (r_2 × n)·J_2⁻¹(r_2 × n),
    where r_k is the arm from the centre of mass G_k to the contact point and
    J_k the inertia tensor about G_k (same basis).  With body 2 omitted (a fixed
    body 2, infinitely massive) its terms vanish.  For two particles (r = 0)
    this is the reduced mass of (6.40).  A normal impulse S changes the normal
    relative velocity of the contact points by S/μ.

    Parameters
    ----------
    m_1 : array_like, shape (...)
        Mass of body 1, kg, > 0.
    J_1 : array_like, shape (..., 3, 3)
        Inertia tensor of body 1 about its centre of mass G_1, kg m².
    r_1 : array_like, shape (..., 3)
        Arm from G_1 to the contact point, m.
    n : array_like, shape (..., 3)
        Normal, non-zero (normalised here).
    m_2 : array_like, shape (...), optional
        Mass of body 2, kg, > 0; all three of ``m_2``, ``J_2``, ``r_2`` or none
        (a fixed body 2).
    J_2 : array_like, shape (..., 3, 3), optional
        Inertia tensor of body 2 about G_2, kg m².
    r_2 : array_like, shape (..., 3), optional
        Arm from G_2 to the contact point, m.

    Returns
    -------
    mu : ndarray, shape (...)
        The effective mass, kg, > 0; 0 where the exact μ lies below about 1e-308
        (arms beyond about 1e154 radii of gyration, or subnormal masses, whose
        reciprocals overflow to inf).

    Raises
    ------
    NegativeMassError
        If a mass is negative.
    NonPositiveParameterError
        If a mass is 0.
    NonPhysicalInertiaError
        If a tensor is not symmetric, not positive definite or breaks the triangle
        inequality (:func:`~mechanics.inertia.check_inertia`).
    OutOfDomainError
        If only some of ``m_2``, ``J_2``, ``r_2`` are given.
    ZeroNormalError
        If ``n`` is the zero vector.
    ResultOverflowError
        If μ exceeds float64 (a mass within rounding of float64's largest, 1.8e308,
        whose subnormal reciprocal inverts beyond it).
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, has the wrong trailing shape, or the
        arguments do not broadcast.

    Examples
    --------
    Two particles: the reduced mass m_1 m_2/(m_1 + m_2).

    >>> J = np.eye(3)
    >>> round(float(effective_mass(2.0, J, [0, 0, 0], [1, 0, 0], 3.0, J, [0, 0, 0])), 15)
    1.2
    >>> 2.0 * 3.0 / (2.0 + 3.0)
    1.2

    A rod of mass m, length ℓ, hit at its end perpendicular to it (Example
    6.2 at x = 0): 1/μ = 1/m + (ℓ/2)²/(mℓ²/12) = 4/m.

    >>> m, ell = 1.0, 2.0
    >>> J_rod = np.diag([0.0, m * ell**2 / 12, m * ell**2 / 12]) + 1e-9 * np.eye(3)
    >>> round(float(effective_mass(m, J_rod, [-ell / 2, 0, 0], [0, 1, 0])), 6)
    0.25
    """
    given = [x is not None for x in (m_2, J_2, r_2)]
    if any(given) and not all(given):
        raise OutOfDomainError("body 2 needs all of m_2, J_2 and r_2, or none of them")
    nn = _unit(n, "n")
    inv = _inverse_mass(
        _check_mass(m_1, "m_1", allow_zero=False),
        _check_inertia(J_1, "J_1"),
        as_float_array(r_1, "r_1", (3,)),
        nn,
    )
    if m_2 is not None and J_2 is not None and r_2 is not None:  # all(given), narrowed for mypy
        inv = inv + _inverse_mass(
            _check_mass(m_2, "m_2", allow_zero=False),
            _check_inertia(J_2, "J_2"),
            as_float_array(r_2, "r_2", (3,)),
            nn,
        )
    return (1.0 / inv)[()]


effective_mass = finite_result(effective_mass)


def _contact_velocity(b: RigidBody, r_S: np.ndarray) -> np.ndarray:
    return b.v_G + np.cross(b.omega, r_S - b.r_G)


def normal_relative_velocity(
    body_1: RigidBody | Sequence[npt.ArrayLike],
    body_2: RigidBody | Sequence[npt.ArrayLike] | None = None,
    *,
    r_S: npt.ArrayLike,
    n: npt.ArrayLike,
) -> np.ndarray:
    """Normal relative velocity v_n = n · (v_S1 − v_S2) of two bodies at a contact point.

    The normal velocity of the contact point of body 1 relative to body 2 (``None``:
    fixed) at the position ``r_S``; < 0 approaching.

    Domain: bodies given as :class:`RigidBody` or 5-tuples (else OutOfDomainError), validated: ``m``
    > 0, ``J_G`` positive definite (NonPhysicalInertiaError), finite (..., 3) vectors; ``r_S``
    finite (..., 3), ``n`` non-zero (else ZeroNormalError).  A v_n beyond float64 (ω × (r_S − r_G)
    with both near 1e300) raises ResultOverflowError; batches that do not broadcast raise ShapeError
    listing each argument's batch shape (a body's: that of its fields together).

    Parameters
    ----------
    body_1 : RigidBody or tuple
        The body the normal points into: a :class:`RigidBody` or its five fields
        ``(m, J_G, r_G, v_G, omega)``, validated as a RigidBody's.
    body_2 : RigidBody, tuple or None, optional
        The other body, likewise; ``None`` (default) is a fixed body.
    r_S : array_like, shape (..., 3)
        Position of the contact point S, m.
    n : array_like, shape (..., 3)
        Impact normal e_n, into body 1, non-zero (normalised here).

    Returns
    -------
    v_n : ndarray, shape (...)
        The normal relative velocity, m/s: < 0 approaching, > 0 separating.

    Raises
    ------
    OutOfDomainError
        If a body is neither a :class:`RigidBody` nor a sequence of five fields.
    NegativeMassError
        If the mass of a body given as a 5-tuple is negative.
    NonPositiveParameterError
        If the mass of a body given as a 5-tuple is 0.
    NonPhysicalInertiaError
        If the ``J_G`` of a body given as a 5-tuple is not a physical inertia tensor.
    ZeroNormalError
        If ``n`` is the zero vector.
    ResultOverflowError
        If v_n exceeds float64's range (ω × (r_S − r_G) with both near 1e300).
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input has the wrong trailing shape or is not numeric, or the batches do
        not broadcast.

    Examples
    --------
    A ball moving down onto the fixed floor (n = e_z points into the ball):

    >>> ball = RigidBody(1.0, 0.4 * np.eye(3), [0, 0, 1.0], [3.0, 0, -2.0], [0, 0, 0])
    >>> float(normal_relative_velocity(ball, r_S=[0, 0, 0], n=[0, 0, 1]))
    -2.0
    """
    b1 = _body(body_1, "body_1")
    b2 = None if body_2 is None else _body(body_2, "body_2")
    rS = as_float_array(r_S, "r_S", (3,))
    nn = _unit(n, "n")
    bodies = {"body_1": _body_batch(b1)} | ({} if b2 is None else {"body_2": _body_batch(b2)})
    _batches("normal_relative_velocity", **bodies, r_S=rS.shape[:-1], n=nn.shape[:-1])
    rel = _contact_velocity(b1, rS)
    if b2 is not None:
        rel = rel - _contact_velocity(b2, rS)
    return _dot(nn, rel)[()]


normal_relative_velocity = finite_result(normal_relative_velocity)


def rigid_impact(
    body_1: RigidBody | Sequence[npt.ArrayLike],
    body_2: RigidBody | Sequence[npt.ArrayLike] | None = None,
    *,
    r_S: npt.ArrayLike,
    n: npt.ArrayLike,
    e: npt.ArrayLike,
    separating: str = "raise",
) -> RigidImpact:
    """Smooth impact of two free rigid bodies (or one against a fixed body) in 3-D.

    Domain: bodies as in :func:`normal_relative_velocity` (RigidBody or 5-tuple, else
    OutOfDomainError; ``m`` > 0, ``J_G`` positive definite, finite vectors), ``r_S`` finite (...,
    3), ``n`` non-zero (else ZeroNormalError), ``e`` in [0, 1] (else RestitutionRangeError),
    ``separating`` 'raise' (SeparatingContactError where v_n > 0) or 'ignore' (else
    UnknownOptionError).  A result beyond float64 on the way (velocities or arms near 1e300, or
    1e300 and 1e-300 mixed) raises ResultOverflowError, never inf, NaN or a numpy warning; batches
    that do not broadcast raise ShapeError listing each argument's batch shape (a body's: that of
    its fields together).

    The impulse S n at the contact point r_S changes the momenta by (6.19) and
    the angular momenta about the centres of mass by (6.21):
    m_1 Δv_G1 = S n, J_1 Δω_1 = (r_S − r_G1) × S n, and the opposite for body
    2.  Newton's restitution v_n' = −e v_n fixes S = −(1 + e) μ v_n with the
    :func:`effective_mass` μ.  The plane is the special case of vectors in the
    XY plane, n in it and e_z a principal axis of both tensors: the result
    stays in the plane.

    Parameters
    ----------
    body_1 : RigidBody or tuple
        The body the normal points into: a :class:`RigidBody` or its five fields
        ``(m, J_G, r_G, v_G, omega)``, validated as a RigidBody's.
    body_2 : RigidBody, tuple or None, optional
        The other body, likewise; ``None`` (default) is a fixed, immovable body (the
        ground).
    r_S : array_like, shape (..., 3)
        Position of the point of impact S, m.
    n : array_like, shape (..., 3)
        Impact normal e_n, into body 1, non-zero (normalised here).
    e : array_like, shape (...)
        Coefficient of restitution in [0, 1].
    separating : {"raise", "ignore"}
        See the module Conventions.

    Returns
    -------
    RigidImpact
        ``S`` (N s), ``mu`` (kg), ``v_n`` (before, m/s), ``Q`` = ½ μ (1 − e)(1 + e) v_n²
        (J) and the bodies after (positions unchanged).

    Raises
    ------
    OutOfDomainError
        If a body is neither a :class:`RigidBody` nor a sequence of five fields.
    NegativeMassError
        If the mass of a body given as a 5-tuple is negative.
    NonPositiveParameterError
        If the mass of a body given as a 5-tuple is 0.
    NonPhysicalInertiaError
        If the ``J_G`` of a body given as a 5-tuple is not a physical inertia tensor.
    ZeroNormalError
        If ``n`` is the zero vector.
    RestitutionRangeError
        If ``e`` lies outside [0, 1].
    SeparatingContactError
        Where v_n > 0 (the bodies separate), with ``separating="raise"``.
    UnknownOptionError
        If ``separating`` is neither "raise" nor "ignore".
    ResultOverflowError
        If v_n or a result exceeds float64's range on the way.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input has the wrong trailing shape or is not numeric, or the batches do
        not broadcast.

    References
    ----------
    Essén (1996), eqs. (6.16), (6.18), (6.19), (6.21), (6.36), (6.41).

    Examples
    --------
    A rod (Example 6.2: m = 1, ℓ = 2, J_G = mℓ²/12 about e_z) at rest, struck at
    its end by a particle-like ball of mass 0.5 moving at −2 e_y, e = 1.  The
    linear momentum before equals that after:

    >>> J_rod = np.diag([1e-3, 1 / 3, 1 / 3])
    >>> rod = RigidBody(1.0, J_rod, [0, 0, 0], [0, 0, 0], [0, 0, 0])
    >>> ball = RigidBody(0.5, 1e-3 * np.eye(3), [-1, 1, 0], [0, -2, 0], [0, 0, 0])
    >>> out = rigid_impact(ball, rod, r_S=[-1, 1, 0], n=[0, 1, 0], e=1.0)
    >>> p_after = 1.0 * out.body_2.v_G + 0.5 * out.body_1.v_G
    >>> p_after.round(12).tolist(), [0.0, 0.5 * -2.0, 0.0]
    ([0.0, -1.0, 0.0], [0.0, -1.0, 0.0])
    """
    _check_option(separating)
    b1 = _body(body_1, "body_1")
    b2 = None if body_2 is None else _body(body_2, "body_2")
    rS = as_float_array(r_S, "r_S", (3,))
    nn = _unit(n, "n")
    ee = _check_e(e)
    bodies = {"body_1": _body_batch(b1)} | ({} if b2 is None else {"body_2": _body_batch(b2)})
    _batches("rigid_impact", **bodies, r_S=rS.shape[:-1], n=nn.shape[:-1], e=ee.shape)
    # x_k = J_k⁻¹ (r_k × n): one solve per body serves μ and the new ω (the
    # impulse S n has the moment r_k × S n = S u_k).
    q1, x1, k1 = _quadratic(np.cross(rS - b1.r_G, nn), b1.J_G)  # J⁻¹ u1 = x1 2^k1
    inv = 1.0 / b1.m + q1
    rel = _contact_velocity(b1, rS)
    if b2 is not None:
        q2, x2, k2 = _quadratic(np.cross(rS - b2.r_G, nn), b2.J_G)
        inv = inv + (1.0 / b2.m + q2)
        rel = rel - _contact_velocity(b2, rS)
    if not np.isfinite(inv).all():  # μ underflows to 0, and with it the impulse S
        raise ResultOverflowError(
            "rigid_impact: 1/μ = 1/m + (r × n)·J⁻¹(r × n) exceeds float64's range (~1.8e308: an "
            "arm beyond ~1e154 radii of gyration, or 1e300 and 1e-300 mixed), so μ and the "
            "impulse underflow and the change of ω they make (finite) is lost; rescale the "
            "inputs (choose units)"
        )
    mu = 1.0 / inv
    v_n = _dot(nn, rel)
    if not np.isfinite(v_n).all():  # before the sign test: an inf v_n is no separation
        raise ResultOverflowError(
            "rigid_impact: the normal relative velocity v_n exceeds float64's range (~1.8e308) "
            "for these finite inputs; rescale the inputs (choose units)"
        )
    approach = _separation(v_n, separating)
    S = np.where(approach, -(1.0 + ee) * mu * v_n, 0.0)
    Q = np.where(approach, 0.5 * mu * ((1.0 - ee) * (1.0 + ee)) * v_n * v_n, 0.0)
    P = S[..., None] * nn  # the impulse vector on body 1
    new_1 = _trusted_body(
        b1.m,
        b1.J_G,
        b1.r_G,
        b1.v_G + P / b1.m[..., None],
        b1.omega + _times(S, x1, k1),
    )
    new_2 = None
    if b2 is not None:
        new_2 = _trusted_body(
            b2.m,
            b2.J_G,
            b2.r_G,
            b2.v_G - P / b2.m[..., None],
            b2.omega - _times(S, x2, k2),
        )
    return RigidImpact(S[()], mu[()], v_n[()], Q[()], new_1, new_2)


rigid_impact = finite_result(rigid_impact)


# ------------------------------------------------------------ hinged body


def _hinge(
    J_A: npt.ArrayLike, r_G: npt.ArrayLike, axis_point: npt.ArrayLike, axis: npt.ArrayLike
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    J = _check_inertia(J_A, "J_A")
    rG = as_float_array(r_G, "r_G", (3,))
    A = as_float_array(axis_point, "axis_point", (3,))
    a = _unit(axis, "axis")
    J_aa = _dot(a, (J @ a[..., None])[..., 0])
    return J, rG - A, A, a, J_aa


def hinged_effective_mass(
    J_A: npt.ArrayLike,
    r_P: npt.ArrayLike,
    n: npt.ArrayLike,
    *,
    axis_point: npt.ArrayLike,
    axis: npt.ArrayLike,
) -> np.ndarray:
    """Effective mass at the point ``r_P`` along ``n`` of a body hinged on a fixed axis.

    Domain: ``J_A`` positive definite as :func:`~mechanics.inertia.check_inertia` (else
    NonPhysicalInertiaError), finite ``axis_point`` and ``r_P`` (..., 3), non-zero ``axis`` and
    ``n`` (else ZeroNormalError).  A blow that cannot turn the body, with no lever arm
    a·(AP × n) = 0 (``r_P`` on the axis, or ``n`` in the plane of the axis and P), is refused
    naming ``r_P`` (OutOfDomainError: the effective mass is infinite).  A μ beyond float64 (a lever
    arm near 1e-300) raises ResultOverflowError; a μ below the smallest subnormal (an arm near
    1e300) is returned as 0, its rounded value.  Batches that do not broadcast raise ShapeError
    listing each argument's shape.

    A blow S n at P turns the body by Δω = a·(AP × n) S/J_a, and P's velocity
    along n changes by S (a·(AP × n))²/J_a, so 1/μ = (a·(AP × n))²/J_a with
    J_a = aᵀ J_A a the moment of inertia about the axis, evaluated as
    (J_a/arm)/arm so that arm² cannot overflow where μ is representable.

    Parameters
    ----------
    J_A : array_like, shape (..., 3, 3)
        Inertia tensor about ``axis_point`` A, kg m², positive definite.
    r_P : array_like, shape (..., 3)
        The point P struck, m.
    n : array_like, shape (..., 3)
        Direction of the blow, non-zero (normalised here).
    axis_point : array_like, shape (..., 3)
        A point A of the fixed axis, m.
    axis : array_like, shape (..., 3)
        Direction a of the axis, non-zero (normalised here).

    Returns
    -------
    mu : ndarray, shape (...)
        The effective mass at P along n, kg: J_a/(a·(AP × n))²; 0 where it lies
        below the smallest subnormal.

    Raises
    ------
    NonPhysicalInertiaError
        If ``J_A`` is not symmetric, not positive definite or breaks the triangle
        inequality (:func:`~mechanics.inertia.check_inertia`).
    ZeroNormalError
        If ``axis`` or ``n`` is the zero vector.
    OutOfDomainError
        If the blow has no lever arm about the axis, a·(AP × n) = 0 (an infinite μ).
    ResultOverflowError
        If μ exceeds float64's range (a lever arm near 1e-300).
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, has the wrong trailing shape, or the
        arguments' batches do not broadcast.

    Examples
    --------
    A rod hinged at its end (J_a = mℓ²/3) hit at x: μ = J_a/x².

    >>> m, ell, x = 3.0, 2.0, 1.5
    >>> J_A = np.diag([1e-6, m * ell**2 / 3, m * ell**2 / 3])
    >>> mu = hinged_effective_mass(J_A, [x, 0, 0], [0, 1, 0], axis_point=[0, 0, 0], axis=[0, 0, 1])
    >>> round(float(mu), 12), round(m * ell**2 / 3 / x**2, 12)
    (1.777777777778, 1.777777777778)
    """
    _, _, A, a, J_aa = _hinge(J_A, np.zeros(3), axis_point, axis)
    rP = as_float_array(r_P, "r_P", (3,)) - A
    nn = _unit(n, "n")
    arm = _dot(a, np.cross(rP, nn))
    none = arm == 0
    if np.any(none):
        idx = _first(none) if none.ndim else ()
        raise OutOfDomainError(
            f"r_P gives the blow no lever arm about the axis (a.(AP x n) = 0 at index {idx}: P on "
            "the axis, or n in the plane of the axis and P); the blow cannot turn the body and "
            "its effective mass is infinite"
        )
    out: np.ndarray = (J_aa / arm / arm)[()]
    return out


hinged_effective_mass = finite_result(hinged_effective_mass)


def hinged_impact(
    m: npt.ArrayLike,
    J_A: npt.ArrayLike,
    r_G: npt.ArrayLike,
    *,
    axis_point: npt.ArrayLike,
    axis: npt.ArrayLike,
    omega: npt.ArrayLike,
    r_P: npt.ArrayLike,
    S_P: npt.ArrayLike,
    bearings: Sequence[npt.ArrayLike] | None = None,
) -> HingedImpact:
    """A body turning on a fixed frictionless axis struck by the impulse ``S_P`` at ``r_P``.

    Domain: ``m`` > 0 (else NegativeMassError or NonPositiveParameterError), ``J_A`` positive
    definite (else NonPhysicalInertiaError), finite ``r_G``, ``axis_point``, ``r_P``, ``S_P`` (...,
    3) and ``omega``, a non-zero ``axis`` (else ZeroNormalError); ``bearings`` two finite axial
    positions, different (else OutOfDomainError).  A result beyond float64 on the way (AP × S_P
    with both near 1e300, a moment over a J_a near 1e-300) raises ResultOverflowError; batches that
    do not broadcast (``omega`` against the vectors included) raise ShapeError listing each
    argument's batch shape.

    The angular momentum about the axis (6.21) gives J_a Δω = a·(AP × S_P), so
    ω' = ω + a·(AP × S_P)/J_a; the momentum principle (6.19) for the whole body,
    m Δv_G = S_P + S_axis with Δv_G = Δω a × AG, gives the reaction impulse of
    the axis S_axis = m Δω a × AG − S_P; the angular momentum about A,
    J_A Δω a = AP × S_P + M_axis, the reaction impulsive moment M_axis.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass, kg, > 0.
    J_A : array_like, shape (..., 3, 3)
        Inertia tensor about ``axis_point`` A (the fixed basis O), kg m².
    r_G : array_like, shape (..., 3)
        Position of the centre of mass G, m.
    axis_point, axis : array_like, shape (..., 3)
        A point A of the fixed axis (m) and its direction a (non-zero, normalised
        here).
    omega : array_like, shape (...)
        Angular velocity about a before the blow, rad/s.
    r_P, S_P : array_like, shape (..., 3)
        Where the blow strikes (m), and its impulse on the body (N s).
    bearings : tuple of two array_like, shape (...), optional
        Axial positions s_1 ≠ s_2 of two bearings, B_k = A + s_k a, m.  Their
        reaction impulses (perpendicular to a) carry S_axis and M_axis:
        S_B1 + S_B2 = S_axis, s_1 a × S_B1 + s_2 a × S_B2 = M_axis; the axial
        part of S_axis (statically indeterminate) goes to the first bearing.

    Returns
    -------
    HingedImpact
        ``omega`` after (rad/s), the axis's reaction impulse ``S_axis`` (N s) and
        impulsive moment ``M_axis`` (N m s), and ``S_bearings`` (N s) when
        ``bearings`` are given.

    Raises
    ------
    NegativeMassError
        If ``m`` < 0.
    NonPositiveParameterError
        If ``m`` = 0.
    NonPhysicalInertiaError
        If ``J_A`` is not symmetric, not positive definite or breaks the triangle
        inequality (:func:`~mechanics.inertia.check_inertia`).
    ZeroNormalError
        If ``axis`` is the zero vector.
    OutOfDomainError
        If ``bearings`` is not two positions, or the two are equal.
    ResultOverflowError
        If a result exceeds float64's range on the way.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, has the wrong trailing shape, or the
        arguments' batches do not broadcast.

    References
    ----------
    Essén (1996), eqs. (6.19), (6.21); Problems 6.3, 6.5.

    Examples
    --------
    A rod hinged at one end (m = 3, ℓ = 2) struck at rest at x = 1.5, with
    S = 1: Δω = x S/J_A = 1.5/4, and the axis reacts with m Δω ℓ/2 − S.  The
    momentum of the rod after equals the sum of the two impulses:

    >>> J_A = np.diag([1e-6, 4.0, 4.0])
    >>> out = hinged_impact(3.0, J_A, [1, 0, 0], axis_point=[0, 0, 0], axis=[0, 0, 1],
    ...                     omega=0.0, r_P=[1.5, 0, 0], S_P=[0, 1.0, 0])
    >>> float(out.omega), out.S_axis.round(12).tolist()
    (0.375, [0.0, 0.125, 0.0])
    >>> float(3.0 * out.omega * 1.0) == float(1.0 + out.S_axis[1])
    True
    """
    mm = _check_mass(m, "m", allow_zero=False)
    J, AG, A, a, J_aa = _hinge(J_A, r_G, axis_point, axis)
    w = as_float_array(omega, "omega")
    AP = as_float_array(r_P, "r_P", (3,)) - A
    S = as_float_array(S_P, "S_P", (3,))
    _batches(
        "hinged_impact",
        m=mm.shape,
        J_A=J.shape[:-2],
        r_G=AG.shape[:-1],
        axis_point=A.shape[:-1],
        axis=a.shape[:-1],
        omega=w.shape,
        r_P=AP.shape[:-1],
        S_P=S.shape[:-1],
    )
    moment = np.cross(AP, S)
    dw = _dot(a, moment) / J_aa
    S_axis = (mm * dw)[..., None] * np.cross(a, AG) - S
    M_axis = dw[..., None] * (J @ a[..., None])[..., 0] - moment
    # Frictionless bearings take no moment about the axis itself; remove rounding.
    M_axis = M_axis - _dot(M_axis, a)[..., None] * a
    S_bearings = None
    if bearings is not None:
        if len(bearings) != 2:
            raise OutOfDomainError(f"bearings must be two axial positions; got {bearings!r}")
        s1 = as_float_array(bearings[0], "bearings[0]")
        s2 = as_float_array(bearings[1], "bearings[1]")
        same = s1 == s2
        if np.any(same):
            raise OutOfDomainError(
                f"the two bearings must be at different axial positions; got {bearings!r}"
            )
        axial = _dot(S_axis, a)[..., None] * a
        perp = S_axis - axial
        X = np.cross(M_axis, a)  # s_1 S_B1⊥ + s_2 S_B2⊥
        d = (s1 - s2)[..., None]
        B1 = (X - s2[..., None] * perp) / d + axial
        B2 = (s1[..., None] * perp - X) / d
        S_bearings = np.stack(np.broadcast_arrays(B1, B2), axis=-2)
    return HingedImpact((w + dw)[()], S_axis, M_axis, S_bearings)


hinged_impact = finite_result(hinged_impact)


def centre_of_percussion(
    m: npt.ArrayLike,
    J_A: npt.ArrayLike,
    r_G: npt.ArrayLike,
    *,
    axis_point: npt.ArrayLike,
    axis: npt.ArrayLike,
) -> CentreOfPercussion:
    """The point where a blow loads a body hinged on a fixed axis with no reaction impulse.

    Domain: ``m`` > 0 (else NegativeMassError or NonPositiveParameterError), ``J_A`` positive
    definite (else NonPhysicalInertiaError), finite ``r_G`` and ``axis_point`` (..., 3), a non-zero
    ``axis`` (else ZeroNormalError), G off the axis by more than 4 eps of |AG| (else
    OutOfDomainError).  Any distance |AG| (scaled by a power of two for the distance h, which so
    cannot overflow); a point beyond float64 raises ResultOverflowError; batches that do not
    broadcast raise ShapeError listing each argument's shape.

    Let a be the unit axis, h > 0 the distance of G from the axis, û the unit
    vector from the axis to G perpendicular to it, b = a × û, and J_xz = ûᵀ J_A a,
    J_zz = aᵀ J_A a in the basis (û, b, a) at A.  A blow along b at
    P = A + (J_zz/(m h)) û − (J_xz/(m h)) a gives zero reaction impulse S_axis
    and no reaction moment about û; the moment about b is Δω bᵀ J_A a, zero
    when the plane of the axis and G is a plane of symmetry (the bats and doors
    of the book).  In the plane: the point at J_A/(m h) from the axis on the
    line through G (Example 6.2: ℓ/3 from the end of a rod, 2ℓ/3 from the hand).

    Parameters
    ----------
    m : array_like, shape (...)
        Mass, kg, > 0.
    J_A : array_like, shape (..., 3, 3)
        Inertia tensor about ``axis_point`` A, kg m², positive definite.
    r_G : array_like, shape (..., 3)
        Position of the centre of mass G, m.
    axis_point : array_like, shape (..., 3)
        A point A of the fixed axis, m.
    axis : array_like, shape (..., 3)
        Direction a of the axis, non-zero (normalised here).

    Returns
    -------
    CentreOfPercussion
        The ``point`` P (m) and the unit ``direction`` b of the blow.

    Raises
    ------
    OutOfDomainError
        When G lies on the axis (h ≤ 4 eps |AG|): every blow loads the axis.
    NegativeMassError
        If ``m`` < 0.
    NonPositiveParameterError
        If ``m`` = 0.
    NonPhysicalInertiaError
        If ``J_A`` is not symmetric, not positive definite or breaks the triangle
        inequality (:func:`~mechanics.inertia.check_inertia`).
    ZeroNormalError
        If ``axis`` is the zero vector.
    ResultOverflowError
        If the point exceeds float64's range.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, has the wrong trailing shape, or the
        arguments' batches do not broadcast.

    Examples
    --------
    A rod of length ℓ = 3 hinged at one end: the centre of percussion is at
    2ℓ/3 = J_A/(m ℓ/2) with J_A = m ℓ²/3; a blow there leaves the axis free.

    >>> m, ell = 2.0, 3.0
    >>> J_A = np.diag([1e-6, m * ell**2 / 3, m * ell**2 / 3])
    >>> P, b = centre_of_percussion(m, J_A, [ell / 2, 0, 0], axis_point=[0, 0, 0], axis=[0, 0, 1])
    >>> P.round(12).tolist(), b.tolist()
    ([2.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    >>> out = hinged_impact(m, J_A, [ell / 2, 0, 0], axis_point=[0, 0, 0], axis=[0, 0, 1],
    ...                     omega=0.0, r_P=P, S_P=b)
    >>> bool(np.abs(out.S_axis).max() < 1e-15)
    True
    """
    mm = _check_mass(m, "m", allow_zero=False)
    J, AG, A, a, J_aa = _hinge(J_A, r_G, axis_point, axis)
    # |AG|² overflows beyond 1e154: work on AG/2**k, its largest component in [1/2, 1)
    _, k = np.frexp(np.abs(AG).max(axis=-1))
    AGs = np.ldexp(AG, -k[..., None])
    perp_s = AGs - _dot(AGs, a)[..., None] * a
    h_s = np.sqrt(_dot(perp_s, perp_s))
    on_axis = h_s <= 4 * EPS * np.sqrt(_dot(AGs, AGs))  # G within rounding of the axis
    h = np.ldexp(h_s, k)
    if np.any(on_axis):
        idx = _first(on_axis) if on_axis.ndim else ()
        raise OutOfDomainError(
            f"the centre of mass lies on the axis (distance h = {float(h[idx])!r} at index "
            f"{idx}); no blow leaves the axis unloaded"
        )
    u = perp_s / h_s[..., None]
    b = np.cross(a, u)
    J_xz = _dot(u, (J @ a[..., None])[..., 0])
    # J/m/h, not J/(m h): m h may overflow where the distances do not
    point = A + (J_aa / mm / h)[..., None] * u - (J_xz / mm / h)[..., None] * a
    return CentreOfPercussion(point, b)


centre_of_percussion = finite_result(centre_of_percussion)
