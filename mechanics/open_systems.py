"""Open systems: the momentum principle with mass flows, rockets, jets, carousels.

Conventions (Essén 1996, ch. 7)
-------------------------------
- **Mass flows are non-negative.**  ``q_out`` (the book's q⁻) is the mass per unit
  time that *leaves* the open system, ``q_in`` (q⁺) the mass per unit time that
  *enters* it; both are ≥ 0 (the book's q ≥ 0).  Direction is given by the name,
  never by a sign.  A negative flow raises :class:`~mechanics.errors.NegativeMassError`.
- **Velocities of the flows.**  ``v_out``, ``v_in`` are *absolute* velocities
  (relative to an inertial frame O), as in (7.19) and (7.35); ``u_out``, ``u_in``
  are velocities *relative to the open system*, u = v − v_o, as in (7.25).
- **Shapes.**  Vectors are ``(..., 3)``.  Several flows are given as ``q`` of
  shape ``(..., n)`` with velocities (and positions) of shape ``(..., n, 3)``; one
  flow may be given as a scalar ``q`` with a ``(3,)`` vector.  Everything
  broadcasts over leading axes.
- **Point.**  Angular momenta and moments are taken about a fixed point ``about``
  (a required keyword, never a silent origin); the book uses the origin (7.31).
- **The rocket** (Example 7.2) rises vertically along +e_z from rest at t = 0;
  ``q`` > 0 is its constant burn rate, ``u`` > 0 the exhaust speed *relative to
  the rocket* (the exhaust moves at −u e_z relative to it), ``g`` ≥ 0 the
  magnitude of gravity (g = −g e_z; ``g=0`` is free space), ``m_0`` the initial
  mass and ``m_f`` < ``m_0`` the fuel mass, burnt out at T = m_f/q.  Mass ratio
  m/m_0 = 1 − x with the burnt fraction x = q t/m_0.
- **Lift-off.**  With g > 0 the rocket lifts off at t = 0 iff q u ≥ m_0 g (at
  equality the acceleration is 0 at t = 0 and positive after, so the velocity
  (7.30) is ≥ 0).  If q u < m_0 g the rocket stands on the pad and (7.30) would
  give negative velocities: the rocket functions raise
  :class:`~mechanics.errors.OutOfDomainError` naming q u and m_0 g.
- **Burn-out.**  For t > T the rocket functions raise
  :class:`~mechanics.errors.OutOfDomainError` by default
  (``after_burn_out="raise"``); with ``after_burn_out="coast"`` they continue with
  free ballistic flight at constant mass m_0 − m_f (no ground: the height may
  become negative on the way down).  t < 0 always raises.
- **The carousel** (Example 7.3) turns about e_z; bullets (mass flow ``q`` ≥ 0,
  speed ``v``) travel along a line at signed perpendicular distance ``r`` from the
  axis, oriented as in the book's figure 7.3 so that their angular momentum flux
  is −r q v e_z, and stick at radius ``R`` (|r| ≤ R).

Accuracy
--------
Stated per function and enforced by ``tests/stability/test_open_systems_stability.py``
against mpmath at 50 digits.  The rocket formulas never form log(m_0/m) or
1 − (1 − x): the velocity uses ``log1p`` and the height a cancellation-free form
of φ(x) = (1/x)∫₀ˣ −log(1 − y) dy (a series in s = x/(2 − x), see
:func:`rocket_height`).  With gravity the result is a difference u L − g t whose
terms nearly cancel close to the lift-off threshold; the error is then stated
relative to the size of the terms (u L + g t), which is the conditioning of the
problem (a relative change of eps in g moves the result by eps g t).
"""

from __future__ import annotations

import math
from typing import cast

import numpy as np
import numpy.typing as npt

from ._floats import EPS
from ._validate import as_float_array, finite_result
from .errors import (
    NegativeMassError,
    NonPositiveParameterError,
    OutOfDomainError,
    ShapeError,
    UnknownOptionError,
)

__all__ = [
    "EPS",
    "G_STANDARD",
    "ROCKET_RTOL",
    "angular_momentum_rate",
    "burn_out_time",
    "carousel_angular_acceleration",
    "carousel_angular_velocity",
    "carousel_limit_angular_velocity",
    "falling_chain_table_force",
    "jet_velocity",
    "mass_rate",
    "momentum_rate",
    "open_system_acceleration",
    "pipe_bend_force",
    "pipe_bend_force_magnitude",
    "rim_rocket_angular_velocity",
    "rim_rocket_spin_up_time",
    "rocket_height",
    "rocket_mass",
    "rocket_velocity",
    "thrust",
]


#: Standard gravity (m/s²), CGPM 1901; offered for convenience, never a default.
G_STANDARD = 9.80665

#: Promised accuracy of :func:`rocket_velocity` and :func:`rocket_height` for
#: burnt fractions x ≤ 1/2, relative to the size of the terms u L + g t
#: (velocity) or u t φ + g t²/2 (height), i.e. relative for g = 0.  A few
#: roundings of O(1) factors (log1p within an ulp, the series in s within 2 ulps);
#: measured worst 1.32 eps (velocity) and 2.10 eps (height), tests/stability.
ROCKET_RTOL = 4 * EPS

#: Series in s = x/(2 − x) for φ(x) up to s = 1/2 (x = 2/3): the terms of
#: A(s) = Σ_{j≥1} s^{2j}/(2j + 1) fall by s² ≤ 1/4, so 28 terms leave a tail below
#: 4^-27 · 3/57 ≈ 3e-18 of the first; above, the direct form 1 + (1 − x) log1p(−x)/x
#: loses at most a factor 1.2 to cancellation (at x = 2/3).
_PHI_SERIES_S_MAX = 0.5
_PHI_SERIES_TERMS = 28

_AFTER_BURN_OUT = ("raise", "coast")


# ---------------------------------------------------------------- validation


def _nonnegative(x: object, name: str) -> npt.NDArray[np.float64]:
    a = as_float_array(x, name)
    if (a < 0).any():
        bad = a[a < 0].flat[0]
        raise NegativeMassError(
            f"{name} must be ≥ 0 (mass flows are non-negative); got {float(bad)!r}"
        )
    return a


def _positive(x: object, name: str) -> npt.NDArray[np.float64]:
    a = as_float_array(x, name)
    if (a <= 0).any():
        bad = a[a <= 0].flat[0]
        raise NonPositiveParameterError(f"{name} must be > 0; got {float(bad)!r}")
    return a


def _flows(
    q: object, w: object, qname: str, wname: str
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Validated flows q (..., n) and vectors w (..., n, 3); one flow may be (), (3,)."""
    qa = _nonnegative(q, qname)
    wa = as_float_array(w, wname, (3,))
    if wa.ndim == 1:
        wa = wa[None, :]
        qa = qa[..., None]
    if qa.ndim == 0:
        qa = qa[None]
    try:
        np.broadcast_shapes(qa.shape, wa.shape[:-1])
    except ValueError:
        raise ShapeError(
            f"{qname} has shape {qa.shape} and {wname} {wa.shape}; "
            "expected (..., n) and (..., n, 3)"
        ) from None
    return qa, wa


def _flux(
    q: npt.ArrayLike | None, w: npt.ArrayLike | None, qname: str, wname: str
) -> npt.NDArray[np.float64]:
    """Σ_a q_a w_a over the flows (zero for no flows)."""
    if q is None and w is None:
        return np.zeros(3)
    if q is None or w is None:
        raise ShapeError(f"{qname} and {wname} must be given together")
    qa, wa = _flows(q, w, qname, wname)
    flux: npt.NDArray[np.float64] = np.sum(qa[..., None] * wa, axis=-2)
    return flux


def _option(after_burn_out: str) -> str:
    if after_burn_out not in _AFTER_BURN_OUT:
        raise UnknownOptionError(
            f"after_burn_out must be one of {_AFTER_BURN_OUT}; got {after_burn_out!r}"
        )
    return after_burn_out


# ------------------------------------------------------- the momentum principle


def thrust(q: npt.ArrayLike, u_rel: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Force on an open system from an outflow q with relative velocity u_rel: −q u.

    Domain: q ≥ 0 (else NegativeMassError), finite u_rel (..., 3); a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    q : array_like, shape (...)
        Mass flow leaving the system, kg/s (≥ 0).
    u_rel : array_like, shape (..., 3)
        Velocity of the leaving matter relative to the system, m/s.

    Returns
    -------
    F : ndarray, shape (..., 3)
        −q u_rel, the outflow term of (7.25), N.

    Raises
    ------
    NegativeMassError
        If a flow q is negative.
    ShapeError
        If u_rel does not end in 3, an input is not real numeric, or the leading axes of
        q and u_rel do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the product exceeds float64's range.

    Examples
    --------
    A rocket ejecting 2 kg/s at 3000 m/s backwards (−e_z) is pushed up with 6 kN:

    >>> thrust(2.0, [0.0, 0.0, -3000.0]).tolist()
    [-0.0, -0.0, 6000.0]
    """
    qa = _nonnegative(q, "q")
    ua = as_float_array(u_rel, "u_rel", (3,))
    F: npt.NDArray[np.float64] = -qa[..., None] * ua
    return F


thrust = finite_result(thrust)


def momentum_rate(
    F_e: npt.ArrayLike,
    *,
    q_out: npt.ArrayLike | None = None,
    v_out: npt.ArrayLike | None = None,
    q_in: npt.ArrayLike | None = None,
    v_in: npt.ArrayLike | None = None,
) -> npt.NDArray[np.float64]:
    """dp_o/dt of an open system, the momentum principle (7.19).

    Domain: finite F_e (..., 3); each flow q ≥ 0 (else NegativeMassError) of shape (..., n) given
    together with its velocities (..., n, 3) (else ShapeError); a result beyond float64 raises
    ResultOverflowError.

    dp_o/dt = F_e − Σ_a q⁻_a v⁻_a + Σ_b q⁺_b v⁺_b, velocities absolute (inertial).

    Parameters
    ----------
    F_e : array_like, shape (..., 3)
        Total external force, N.
    q_out, v_out : array_like, shapes (..., n) and (..., n, 3), optional
        Outflows (kg/s, ≥ 0) and their absolute velocities (m/s); omit both for none.
        One flow may be a scalar q with a (3,) velocity.
    q_in, v_in : array_like, shapes (..., k) and (..., k, 3), optional
        Inflows (kg/s, ≥ 0) and their absolute velocities (m/s); omit both for none.

    Returns
    -------
    dp_dt : ndarray, shape (..., 3)
        The rate of change dp_o/dt of the open system's momentum, N.

    Raises
    ------
    NegativeMassError
        If a flow q_out or q_in is negative.
    ShapeError
        If a flow is given without its velocities (or they without it), a vector does not
        end in 3, the numbers of flows n (k) of q and its velocities differ, or the leading
        axes do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    The pipe bend of Example 7.1 at rest: water enters along e_y, leaves along
    −e_x, q = 1 kg/s, v = 1 m/s; the holding force F = (−1, −1, 0) N balances it:

    >>> momentum_rate([-1.0, -1.0, 0.0], q_out=1.0, v_out=[-1.0, 0.0, 0.0],
    ...               q_in=1.0, v_in=[0.0, 1.0, 0.0]).tolist()
    [0.0, 0.0, 0.0]
    """
    F = as_float_array(F_e, "F_e", (3,))
    rate: npt.NDArray[np.float64] = (
        F - _flux(q_out, v_out, "q_out", "v_out") + _flux(q_in, v_in, "q_in", "v_in")
    )
    return rate


momentum_rate = finite_result(momentum_rate)


def mass_rate(
    *, q_out: npt.ArrayLike | None = None, q_in: npt.ArrayLike | None = None
) -> npt.NDArray[np.float64]:
    """Rate of change of the mass of an open system, dm/dt = Σ q⁺ − Σ q⁻ (7.21).

    Domain: flows q ≥ 0 (else NegativeMassError), the last axis listing the flows; a result beyond
    float64 raises ResultOverflowError.

    ``q_out``, ``q_in`` of shape (..., n); None for none.

    Parameters
    ----------
    q_out : array_like, shape (..., n) or (), optional
        Outflows q⁻, kg/s (≥ 0); the last axis lists the flows, a scalar is one flow.
        None (the default) for none.
    q_in : array_like, shape (..., k) or (), optional
        Inflows q⁺, kg/s (≥ 0), as ``q_out``.

    Returns
    -------
    dm_dt : ndarray, shape (...)
        Σ q_in − Σ q_out, kg/s (0 when no flow is given).

    Raises
    ------
    NegativeMassError
        If a flow is negative.
    ShapeError
        If a flow is not a real numeric array, or the leading axes of the two sums do not
        broadcast.
    NonFiniteError
        If a flow holds NaN or an infinity.
    ResultOverflowError
        If a sum exceeds float64's range.

    Examples
    --------
    >>> float(mass_rate(q_out=[1.0, 0.5], q_in=2.0))
    0.5

    A rocket burning q = 4 kg/s loses 4 kg in its first second (7.27):

    >>> m1 = rocket_mass(1.0, m_0=1000.0, q=4.0, m_f=600.0)
    >>> float(mass_rate(q_out=4.0)), float(m1 - 1000.0)
    (-4.0, -4.0)
    """
    total: np.float64 | np.ndarray = np.float64(0.0)
    for q, name, sign in ((q_in, "q_in", 1.0), (q_out, "q_out", -1.0)):
        if q is not None:
            qa = _nonnegative(q, name)
            total = total + sign * (np.sum(qa, axis=-1) if qa.ndim else qa)
    return np.asarray(total)


mass_rate = finite_result(mass_rate)


def open_system_acceleration(
    m: npt.ArrayLike,
    F_e: npt.ArrayLike,
    *,
    q_out: npt.ArrayLike | None = None,
    u_out: npt.ArrayLike | None = None,
    q_in: npt.ArrayLike | None = None,
    u_in: npt.ArrayLike | None = None,
) -> npt.NDArray[np.float64]:
    """a_o = (F_e − Σ q⁻ u⁻ + Σ q⁺ u⁺)/m, (7.25), velocities relative to the system.

    Domain: m > 0 (else NonPositiveParameterError), finite F_e (..., 3), flows as
    :func:`momentum_rate`; a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (...)
        Current mass of the open system, kg (> 0).
    F_e : array_like, shape (..., 3)
        Total external force, N.
    q_out, u_out : array_like, shapes (..., n) and (..., n, 3), optional
        Outflows (kg/s, ≥ 0) and their velocities relative to the system, u = v − v_o
        (m/s); omit both for none.  One flow may be a scalar q with a (3,) velocity.
    q_in, u_in : array_like, shapes (..., k) and (..., k, 3), optional
        Inflows (kg/s, ≥ 0) and their velocities relative to the system (m/s).

    Returns
    -------
    a : ndarray, shape (..., 3)
        Acceleration a_o of the open system, m/s².

    Raises
    ------
    NonPositiveParameterError
        If a mass m is ≤ 0.
    NegativeMassError
        If a flow q_out or q_in is negative.
    ShapeError
        If a flow is given without its velocities (or they without it), a vector does not
        end in 3, the numbers of flows of q and its velocities differ, or the leading axes
        do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    Example 7.2 at t = 0: m_0 = 1000 kg, q = 10 kg/s, u = 2000 m/s, g = 9.81 m/s²:

    >>> a = open_system_acceleration(1000.0, [0, 0, -1000.0 * 9.81],
    ...                              q_out=10.0, u_out=[0, 0, -2000.0])
    >>> round(float(a[2]), 12)
    10.19
    """
    ma = _positive(m, "m")
    F = as_float_array(F_e, "F_e", (3,))
    rate = F - _flux(q_out, u_out, "q_out", "u_out") + _flux(q_in, u_in, "q_in", "u_in")
    a: npt.NDArray[np.float64] = rate / ma[..., None]
    return a


open_system_acceleration = finite_result(open_system_acceleration)


def angular_momentum_rate(
    M_e: npt.ArrayLike,
    *,
    about: npt.ArrayLike,
    q_out: npt.ArrayLike | None = None,
    r_out: npt.ArrayLike | None = None,
    v_out: npt.ArrayLike | None = None,
    q_in: npt.ArrayLike | None = None,
    r_in: npt.ArrayLike | None = None,
    v_in: npt.ArrayLike | None = None,
) -> npt.NDArray[np.float64]:
    """dL_o/dt about a fixed point A of an open system, (7.35).

    Domain: finite M_e and about (..., 3); each flow q ≥ 0 (else NegativeMassError) given with its
    points and velocities (else ShapeError); a result beyond float64 raises ResultOverflowError.

    dL_o/dt = M_e − Σ_a (r⁻_a − A) × q⁻_a v⁻_a + Σ_b (r⁺_b − A) × q⁺_b v⁺_b.

    Parameters
    ----------
    M_e : array_like, shape (..., 3)
        Total moment of the external forces about ``about``, N m.
    about : array_like, shape (..., 3)
        The fixed point A, m (required; the book uses the origin).
    q_out, r_out, v_out : array_like, shapes (..., n), (..., n, 3), (..., n, 3), optional
        Outflows (kg/s, ≥ 0), the positions where they cross the boundary (m), their
        absolute velocities (m/s); give all three or none.  One flow may be a scalar q
        with (3,) vectors.
    q_in, r_in, v_in : array_like, shapes (..., k), (..., k, 3), (..., k, 3), optional
        The same for inflows.

    Returns
    -------
    dL_dt : ndarray, shape (..., 3)
        The rate of change dL_o/dt of the angular momentum about A, N m.

    Raises
    ------
    NegativeMassError
        If a flow q_out or q_in is negative.
    ShapeError
        If a flow is given without its positions and velocities (all three or none), a
        vector does not end in 3, the numbers of flows differ, or the leading axes do not
        broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    Example 7.3: bullets along +e_x at height y = r = 0.5 m, q = 0.1 kg/s, v = 400 m/s,
    give the carousel −r q v e_z = −20 N m e_z about its centre:

    >>> angular_momentum_rate([0, 0, 0], about=[0, 0, 0], q_in=0.1,
    ...                       r_in=[-2.0, 0.5, 0.0], v_in=[400.0, 0, 0]).tolist()
    [0.0, 0.0, -20.0]
    """
    M = as_float_array(M_e, "M_e", (3,))
    A = as_float_array(about, "about", (3,))
    total = M
    for q, r, v, names, sign in (
        (q_out, r_out, v_out, ("q_out", "r_out", "v_out"), -1.0),
        (q_in, r_in, v_in, ("q_in", "r_in", "v_in"), 1.0),
    ):
        given = [x is not None for x in (q, r, v)]
        if not any(given):
            continue
        if not all(given):
            raise ShapeError(f"{', '.join(names)} must be given together")
        qa, va = _flows(q, v, names[0], names[2])
        ra = as_float_array(r, names[1], (3,))
        if ra.ndim == 1:
            ra = ra[None, :]
        arm = ra - A[..., None, :]
        total = total + sign * np.sum(np.cross(arm, qa[..., None] * va), axis=-2)
    return total


angular_momentum_rate = finite_result(angular_momentum_rate)


# ------------------------------------------------------------------- the rocket


def _rate_ratio(
    *factors: npt.NDArray[np.float64], over: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """The product of ``factors`` over ``over`` formed on their mantissas, (f_1 f_2 …)/f_over
    left to right, scaled once by 2**(e_1 + e_2 + … − e_over): the same bits as the plain
    (x_1 x_2 …)/over wherever the product neither under- nor overflows.  The plain product
    lost the ratio of a mass scale: m = 2**-1000 · 1000, q = 2**-1000 · 4, t = 1e-30 made
    q t subnormal (a rocket's v = 0 for the exact 1.2e-29), and so did a jet's k = q t/m; a
    rim rocket's q r² overflowed for a valid wheel (q r² = 2**1040, t = 2**-60, J_0 = 20 ·
    2**980: x = 0.05 refused as ≥ 1) and q r² t lost digits as a subnormal."""
    f, e = np.frexp(factors[0])
    for x in factors[1:]:
        fx, ex = np.frexp(x)
        f, e = f * fx, e + ex
    fo, eo = np.frexp(over)
    out: npt.NDArray[np.float64] = np.ldexp(f / fo, e - eo)
    return out


def _less_product(
    a: npt.NDArray[np.float64],
    b: npt.NDArray[np.float64],
    c: npt.NDArray[np.float64],
    d: npt.NDArray[np.float64],
) -> npt.NDArray[np.bool_]:
    """a b < c d for a, b, c, d ≥ 0, of the mantissas' products brought to one exponent: the
    plain a b < c d wherever neither product under- nor overflows, and right where they do
    (q u = 1e309 against m_0 g = 1.1e309 read as inf < inf and let a grounded rocket fly)."""
    fa, ea = np.frexp(a)
    fb, eb = np.frexp(b)
    fc, ec = np.frexp(c)
    fd, ed = np.frexp(d)
    p, e = fa * fb, ea + eb
    r, k = fc * fd, ec + ed
    top = np.maximum(e, k)
    out: npt.NDArray[np.bool_] = np.ldexp(p, e - top) < np.ldexp(r, k - top)
    return out


def _phi(x: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """φ(x) = (1/x) ∫₀ˣ −log(1 − y) dy = 1 + (1 − x) log(1 − x)/x, 0 ≤ x < 1, φ(0) = 0.

    With s = x/(2 − x) (so 1 − x = (1 − s)/(1 + s), −log(1 − x) = 2 atanh s),
    φ = s − (1 − s) A(s), A(s) = atanh(s)/s − 1 = Σ_{j≥1} s^{2j}/(2j + 1): positive
    terms, s dominating (A ≤ s²/2.6 for s ≤ 1/2), no cancellation.
    """
    x = np.asarray(x, dtype=float)
    s = x / (2.0 - x)
    small = s <= _PHI_SERIES_S_MAX
    s2 = np.where(small, s, 0.0) ** 2
    A = np.zeros_like(s2)
    for j in range(_PHI_SERIES_TERMS, 0, -1):  # Horner in s²
        A = (A + 1.0 / (2 * j + 1)) * s2
    series = s - (1.0 - s) * A
    with np.errstate(divide="ignore", invalid="ignore"):
        direct = 1.0 + (1.0 - x) * np.log1p(-x) / x
    phi: npt.NDArray[np.float64] = np.where(small, series, direct)
    return phi


def burn_out_time(*, m_f: npt.ArrayLike, q: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """T = m_f/q, the time at which the fuel m_f = q T is gone (Example 7.2).

    Domain: m_f ≥ 0 (else NegativeMassError), q > 0 (else NonPositiveParameterError); a result
    beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    m_f : array_like, shape (...)
        Fuel mass, kg (≥ 0).
    q : array_like, shape (...)
        Constant burn rate, kg/s (> 0).

    Returns
    -------
    T : ndarray, shape (...)
        Burn-out time, s, broadcast over the inputs.

    Raises
    ------
    NegativeMassError
        If m_f is negative.
    NonPositiveParameterError
        If q is ≤ 0.
    ShapeError
        If an input is not a real numeric array, or m_f and q do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If m_f/q exceeds float64's range.

    Examples
    --------
    >>> float(burn_out_time(m_f=600.0, q=4.0))
    150.0

    At T the rocket has lost its fuel, m(T) = m_0 − m_f:

    >>> T = burn_out_time(m_f=600.0, q=4.0)
    >>> float(rocket_mass(T, m_0=1000.0, q=4.0, m_f=600.0)), 1000.0 - 600.0
    (400.0, 400.0)
    """
    T: npt.NDArray[np.float64] = _nonnegative(m_f, "m_f") / _positive(q, "q")
    return T


burn_out_time = finite_result(burn_out_time)


def _shown_product(a: npt.ArrayLike, b: npt.ArrayLike, mask: npt.ArrayLike) -> str:
    """a b at the first entry where ``mask`` holds, for a message: the product where it is a
    float, else the factors as given (not the inf of an overflowed product)."""
    x, y = _first(a, mask), _first(b, mask)
    with np.errstate(over="ignore"):
        p = float(np.float64(x) * np.float64(y))
    return repr(p) if math.isfinite(p) and (p != 0 or x == 0 or y == 0) else f"{x!r} * {y!r}"


def _first(values: npt.ArrayLike, mask: npt.ArrayLike) -> float:
    """The first entry of ``values`` where ``mask`` holds (both broadcast)."""
    v, m = np.broadcast_arrays(values, mask)
    return float(v[m].flat[0])


#: rocket_mass needs neither u nor g (a None given for them elsewhere is refused by name)
_UNUSED = object()


def _rocket_inputs(
    t: npt.ArrayLike,
    m_0: npt.ArrayLike,
    q: npt.ArrayLike,
    u: object,
    m_f: npt.ArrayLike,
    g: object,
    after_burn_out: str,
) -> tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64] | None,
    npt.NDArray[np.float64],
    npt.NDArray[np.float64] | None,
    npt.NDArray[np.float64],
]:
    """Validate the rocket's inputs; return them as float arrays and T = m_f/q."""
    _option(after_burn_out)
    ta = as_float_array(t, "t")
    m0 = _positive(m_0, "m_0")
    qa = _positive(q, "q")
    mf = _nonnegative(m_f, "m_f")
    if (mf >= m0).any():
        raise OutOfDomainError(
            "the fuel mass m_f must be < m_0 (the rocket has a structure); "
            f"got m_f = {_first(mf, mf >= m0)!r} with m_0 = {_first(m0, mf >= m0)!r}"
        )
    if (ta < 0).any():
        raise OutOfDomainError(
            f"t must be ≥ 0 (the burn starts at t = 0); got {_first(ta, ta < 0)!r}"
        )
    ua = None if u is _UNUSED else _positive(u, "u")
    ga = None if g is _UNUSED else as_float_array(g, "g")
    if ga is not None and (ga < 0).any():
        raise OutOfDomainError(
            "g is the magnitude of gravity (g = −g e_z) and must be ≥ 0; "
            f"got {_first(ga, ga < 0)!r}"
        )
    if ua is not None and ga is not None:
        grounded = _less_product(qa, ua, m0, ga)
        if grounded.any():
            raise OutOfDomainError(
                f"no lift-off: the thrust q u = {_shown_product(qa, ua, grounded)} is less than "
                f"the weight m_0 g = {_shown_product(m0, ga, grounded)} (the rocket stands on "
                "the pad; (7.30) would give v < 0)"
            )
    T = mf / qa
    beyond = ta > T
    if after_burn_out == "raise" and beyond.any():
        raise OutOfDomainError(
            f"t = {_first(ta, beyond)!r} is beyond burn-out T = m_f/q = {_first(T, beyond)!r}; "
            "pass after_burn_out='coast' for free flight after burn-out"
        )
    return ta, m0, qa, ua, mf, ga, T


def rocket_mass(
    t: npt.ArrayLike,
    *,
    m_0: npt.ArrayLike,
    q: npt.ArrayLike,
    m_f: npt.ArrayLike,
    after_burn_out: str = "raise",
) -> npt.NDArray[np.float64]:
    """m(t) = m_0 − q t (7.27) up to burn-out, m_0 − m_f after (with ``"coast"``).

    Domain: t ≥ 0, m_0 > 0, q > 0, 0 ≤ m_f < m_0; t beyond burn-out only with after_burn_out='coast'
    (else OutOfDomainError; a nonpositive m_0 or q raises NonPositiveParameterError, a negative
    m_f NegativeMassError, any other option UnknownOptionError).

    Parameters
    ----------
    t : array_like, shape (...)
        Time since ignition, s (≥ 0).
    m_0 : array_like, shape (...)
        Initial mass, kg (> 0).
    q : array_like, shape (...)
        Constant burn rate, kg/s (> 0).
    m_f : array_like, shape (...)
        Fuel mass, kg, 0 ≤ m_f < m_0; burn-out at T = m_f/q.
    after_burn_out : {"raise", "coast"}, optional
        t > T raises :class:`~mechanics.errors.OutOfDomainError` (``"raise"``, the
        default), or gives the constant mass m_0 − m_f (``"coast"``).

    Returns
    -------
    m : ndarray, shape (...)
        Mass of the rocket at t, kg, broadcast over the inputs.

    Raises
    ------
    UnknownOptionError
        If ``after_burn_out`` is not ``"raise"`` or ``"coast"``.
    NonPositiveParameterError
        If m_0 or q is ≤ 0.
    NegativeMassError
        If m_f is negative.
    OutOfDomainError
        If m_f ≥ m_0, t < 0, or t > T = m_f/q with ``after_burn_out="raise"``.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.

    Examples
    --------
    >>> float(rocket_mass(10.0, m_0=1000.0, q=5.0, m_f=600.0))
    950.0
    >>> float(rocket_mass(500.0, m_0=1000.0, q=5.0, m_f=600.0, after_burn_out="coast"))
    400.0
    """
    ta, m0, qa, _, mf, _, T = _rocket_inputs(t, m_0, q, _UNUSED, m_f, _UNUSED, after_burn_out)
    m: npt.NDArray[np.float64] = np.where(ta > T, m0 - mf, m0 - qa * np.minimum(ta, T))
    return m


rocket_mass = finite_result(rocket_mass)


def _burn_velocity(
    t: npt.NDArray[np.float64],
    m0: npt.NDArray[np.float64],
    q: npt.NDArray[np.float64],
    u: npt.NDArray[np.float64],
    g: npt.NDArray[np.float64],
) -> npt.NDArray[np.float64]:
    """u L(x) − g t, L = −log1p(−x), x = q t/m_0: (7.30)."""
    v: npt.NDArray[np.float64] = u * -np.log1p(-_rate_ratio(q, t, over=m0)) - g * t
    return v


def _burn_height(
    t: npt.NDArray[np.float64],
    m0: npt.NDArray[np.float64],
    q: npt.NDArray[np.float64],
    u: npt.NDArray[np.float64],
    g: npt.NDArray[np.float64],
) -> npt.NDArray[np.float64]:
    """u t φ(x) − g t²/2: the integral of (7.30) from 0 to t."""
    z: npt.NDArray[np.float64] = u * t * _phi(_rate_ratio(q, t, over=m0)) - 0.5 * g * t * t
    return z


def rocket_velocity(
    t: npt.ArrayLike,
    *,
    m_0: npt.ArrayLike,
    q: npt.ArrayLike,
    u: npt.ArrayLike,
    m_f: npt.ArrayLike,
    g: npt.ArrayLike,
    after_burn_out: str = "raise",
) -> npt.NDArray[np.float64]:
    """Vertical velocity of the rocket of Example 7.2, (7.30).

    Domain: t ≥ 0, m_0 > 0, q > 0, 0 ≤ m_f < m_0, u > 0 and g ≥ 0 with lift-off q u ≥ m_0 g (else
    OutOfDomainError; but a nonpositive m_0, q or u raises NonPositiveParameterError, a negative
    m_f NegativeMassError); t beyond burn-out T = m_f/q only with after_burn_out='coast' (else
    OutOfDomainError; any other option: UnknownOptionError); a result beyond float64 raises
    ResultOverflowError.

    v(t) = −g t − u log(1 − q t/m_0), computed as u·(−log1p(−q t/m_0)) − g t.

    Parameters
    ----------
    t : array_like, shape (...)
        Time since ignition, s (≥ 0).
    m_0, q, u : array_like, shape (...)
        Initial mass (kg), burn rate (kg/s), exhaust speed relative to the rocket (m/s),
        all > 0.
    m_f : array_like, shape (...)
        Fuel mass, kg, 0 ≤ m_f < m_0; burn-out at T = m_f/q.
    g : array_like, shape (...)
        Magnitude of gravity, m/s², ≥ 0 (0 in free space).  Required: q u ≥ m_0 g.
    after_burn_out : {"raise", "coast"}, optional
        t > T raises :class:`~mechanics.errors.OutOfDomainError` (``"raise"``, the
        default), or continues as free flight v(T) − g (t − T) (``"coast"``).

    Returns
    -------
    v : ndarray, shape (...)
        v(t) along +e_z, m/s, broadcast over the inputs.

    Raises
    ------
    UnknownOptionError
        If ``after_burn_out`` is not ``"raise"`` or ``"coast"``.
    NonPositiveParameterError
        If m_0, q or u is ≤ 0.
    NegativeMassError
        If m_f is negative.
    OutOfDomainError
        If m_f ≥ m_0, t < 0, g < 0, q u < m_0 g (no lift-off), or t > T = m_f/q with
        ``after_burn_out="raise"``.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Notes
    -----
    Accuracy: ``ROCKET_RTOL`` (4 eps) relative to u L + g t for burnt fractions
    x ≤ 1/2, measured against mpmath for x from 1e-15 to 1e-3 and beyond.  For
    x → 1 the problem itself is ill-conditioned in t (dL/dx = 1/(1 − x)).

    References
    ----------
    Essén (1996), Example 7.2, eqs. (7.26)–(7.30).

    Examples
    --------
    Without gravity the velocity is u log(m_0/m); burning half the mass gives u ln 2:

    >>> v = rocket_velocity(50.0, m_0=1000.0, q=10.0, u=3000.0, m_f=800.0, g=0.0)
    >>> bool(abs(v - 3000.0 * np.log(2.0)) < 1e-12)
    True

    A mass ratio of 1 − 1e-12: log1p keeps every digit (log(m_0/m) would keep four):

    >>> float(rocket_velocity(1e-12, m_0=1.0, q=1.0, u=1.0, m_f=0.5, g=0.0))
    1.0000000000005e-12
    """
    ta, m0, qa, ua, _, ga, T = _rocket_inputs(t, m_0, q, u, m_f, g, after_burn_out)
    # u and g were given (not _UNUSED), so _rocket_inputs returned them validated, not None
    ua, ga = cast("npt.NDArray[np.float64]", ua), cast("npt.NDArray[np.float64]", ga)
    tb = np.minimum(ta, T)
    v = _burn_velocity(tb, m0, qa, ua, ga)
    if after_burn_out == "coast":
        v = np.where(ta > T, v - ga * (ta - T), v)
    return v


rocket_velocity = finite_result(rocket_velocity)


def rocket_height(
    t: npt.ArrayLike,
    *,
    m_0: npt.ArrayLike,
    q: npt.ArrayLike,
    u: npt.ArrayLike,
    m_f: npt.ArrayLike,
    g: npt.ArrayLike,
    after_burn_out: str = "raise",
) -> npt.NDArray[np.float64]:
    """Height z(t) of the rocket of Example 7.2: the integral of (7.30), z(0) = 0.

    Domain: t ≥ 0, m_0 > 0, q > 0, 0 ≤ m_f < m_0, u > 0 and g ≥ 0 with lift-off q u ≥ m_0 g (else
    OutOfDomainError; but a nonpositive m_0, q or u raises NonPositiveParameterError, a negative
    m_f NegativeMassError); t beyond burn-out T = m_f/q only with after_burn_out='coast' (else
    OutOfDomainError; any other option: UnknownOptionError); a result beyond float64 raises
    ResultOverflowError.

    z(t) = u t φ(x) − g t²/2,  x = q t/m_0,
    φ(x) = (1/x)∫₀ˣ −log(1 − y) dy = 1 + (1 − x) log(1 − x)/x = x/2 + x²/6 + x³/12 + …

    Parameters
    ----------
    t : array_like, shape (...)
        Time since ignition, s (≥ 0).
    m_0, q, u : array_like, shape (...)
        Initial mass (kg), burn rate (kg/s), exhaust speed relative to the rocket (m/s),
        all > 0.
    m_f : array_like, shape (...)
        Fuel mass, kg, 0 ≤ m_f < m_0; burn-out at T = m_f/q.
    g : array_like, shape (...)
        Magnitude of gravity, m/s², ≥ 0 (0 in free space).  Required: q u ≥ m_0 g.
    after_burn_out : {"raise", "coast"}, optional
        t > T raises :class:`~mechanics.errors.OutOfDomainError` (``"raise"``, the
        default), or continues as free flight (``"coast"``, see Notes).

    Returns
    -------
    z : ndarray, shape (...)
        Height z(t) above the launch point, m, broadcast over the inputs.

    Raises
    ------
    UnknownOptionError
        If ``after_burn_out`` is not ``"raise"`` or ``"coast"``.
    NonPositiveParameterError
        If m_0, q or u is ≤ 0.
    NegativeMassError
        If m_f is negative.
    OutOfDomainError
        If m_f ≥ m_0, t < 0, g < 0, q u < m_0 g (no lift-off), or t > T = m_f/q with
        ``after_burn_out="raise"``.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Notes
    -----
    The direct form of φ cancels catastrophically for small x (1 − (1 − x)(1 + x/2 +
    …) loses −log10(x) digits).  Here φ is evaluated, for x ≤ 2/3, as
    φ = s − (1 − s) A(s), s = x/(2 − x), A(s) = Σ_{j≥1} s^{2j}/(2j + 1) (28 terms,
    Horner), which has no cancellation; above 2/3 by the direct form (a factor ≤
    1.2 lost).  Accuracy: ``ROCKET_RTOL`` relative to u t φ + g t²/2.  After
    burn-out (``"coast"``): z(T) + v(T)(t − T) − g (t − T)²/2.

    Examples
    --------
    Free space, tiny burn: z = u t (x/2 + x²/6 + x³/12 + …), every digit kept
    (the direct form 1 + (1 − x) log1p(−x)/x keeps only ten here):

    >>> z = rocket_height(1e-6, m_0=1.0, q=1.0, u=1.0, m_f=0.5, g=0.0)
    >>> bool(abs(z / (0.5e-12 + 1e-18 / 6 + 1e-24 / 12) - 1) < 4 * EPS)
    True
    """
    ta, m0, qa, ua, _, ga, T = _rocket_inputs(t, m_0, q, u, m_f, g, after_burn_out)
    # u and g were given (not _UNUSED), so _rocket_inputs returned them validated, not None
    ua, ga = cast("npt.NDArray[np.float64]", ua), cast("npt.NDArray[np.float64]", ga)
    tb = np.minimum(ta, T)
    z = _burn_height(tb, m0, qa, ua, ga)
    if after_burn_out == "coast":
        vT = _burn_velocity(T, m0, qa, ua, ga)
        zT = _burn_height(T, m0, qa, ua, ga)
        dt = np.maximum(ta - T, 0.0)
        z = np.where(ta > T, zT + vT * dt - 0.5 * ga * dt * dt, z)
    return z


rocket_height = finite_result(rocket_height)


# ---------------------------------------------------------- jets, bends, chains


def jet_velocity(
    t: npt.ArrayLike, *, m: npt.ArrayLike, q: npt.ArrayLike, w: npt.ArrayLike, v_0: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Speed of a jet plane taking in still air at q and expelling it at w relative.

    Domain: t ≥ 0 (else OutOfDomainError), m > 0, q > 0, w > 0 (else NonPositiveParameterError),
    finite v_0; a result beyond float64 raises ResultOverflowError.

    From (7.19) with inflow velocity 0 and outflow velocity v − w (Problem 7.1):
    m dv/dt = q (w − v), so v(t) = w + (v_0 − w) e^{−q t/m}, evaluated as
    v_0 e^{−k} − w expm1(−k), k = q t/m (no cancellation for v_0, w ≥ 0).

    Parameters
    ----------
    t : array_like, shape (...)
        Time, s (≥ 0).
    m, q : array_like, shape (...)
        Mass of the plane (kg) and air flow through the engine (kg/s), both > 0.
    w : array_like, shape (...)
        Exhaust speed relative to the engine, m/s (> 0).
    v_0 : array_like, shape (...)
        Speed at t = 0, m/s.

    Returns
    -------
    v : ndarray, shape (...)
        Speed v(t), m/s, broadcast over the inputs; it tends to w as t grows.

    Raises
    ------
    OutOfDomainError
        If t < 0.
    NonPositiveParameterError
        If m, q or w is ≤ 0.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    >>> round(float(jet_velocity(1e9, m=1e4, q=100.0, w=600.0, v_0=50.0)), 9)
    600.0
    """
    ta = as_float_array(t, "t")
    if (ta < 0).any():
        raise OutOfDomainError(f"t must be ≥ 0; got {float(ta[ta < 0].flat[0])!r}")
    k = _rate_ratio(_positive(q, "q"), ta, over=_positive(m, "m"))
    v0 = as_float_array(v_0, "v_0")
    v: npt.NDArray[np.float64] = v0 * np.exp(-k) - _positive(w, "w") * np.expm1(-k)
    return v


jet_velocity = finite_result(jet_velocity)


def pipe_bend_force(
    q: npt.ArrayLike, v: npt.ArrayLike, angle: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Force that holds a pipe bend at rest: F = q (v_out − v_in), from (7.19).

    Domain: q ≥ 0 (else NegativeMassError), finite v and angle; a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    q : array_like, shape (...)
        Mass flow through the pipe, kg/s (≥ 0).
    v : array_like, shape (...)
        Flow speed, m/s (constant cross-section: the same in and out).
    angle : array_like, shape (...)
        Turning angle α of the flow, rad (positive to the left).

    Returns
    -------
    F : ndarray, shape (..., 3)
        The holding force, N.  Components in the inflow frame: e_1 along the incoming
        flow, e_2 to its left (the side the flow turns to for α > 0), e_3 = e_1 × e_2:
        F = q v (cos α − 1, sin α, 0), with cos α − 1 computed as −2 sin²(α/2).

    Raises
    ------
    NegativeMassError
        If q is negative.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Notes
    -----
    |F| = 2 q v |sin(α/2)| (:func:`pipe_bend_force_magnitude`); 90° gives √2 q v.

    Examples
    --------
    Example 7.1 (inflow along e_y, turning left to −e_x, so e_1 = e_y, e_2 = −e_x):
    F_y = F_1 = −q v, F_x = −F_2 = −q v:

    >>> pipe_bend_force(1.0, 1.0, np.pi / 2).round(15).tolist()
    [-1.0, 1.0, 0.0]
    """
    qa = _nonnegative(q, "q")
    va = as_float_array(v, "v")
    a = as_float_array(angle, "angle")
    qv = qa * va
    F1 = -2.0 * qv * np.sin(0.5 * a) ** 2
    F2 = qv * np.sin(a)
    F1, F2 = np.broadcast_arrays(F1, F2)
    F: npt.NDArray[np.float64] = np.stack([F1, F2, np.zeros_like(F1)], axis=-1)
    return F


pipe_bend_force = finite_result(pipe_bend_force)


def pipe_bend_force_magnitude(
    q: npt.ArrayLike, v: npt.ArrayLike, angle: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """|F| = 2 q |v| |sin(α/2)| for the pipe bend of :func:`pipe_bend_force`.

    Domain: q ≥ 0 (else NegativeMassError), finite v and angle; a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    q : array_like, shape (...)
        Mass flow through the pipe, kg/s (≥ 0).
    v : array_like, shape (...)
        Flow speed, m/s.
    angle : array_like, shape (...)
        Turning angle α of the flow, rad.

    Returns
    -------
    F : ndarray, shape (...)
        Magnitude of the holding force, N, broadcast over the inputs.

    Raises
    ------
    NegativeMassError
        If q is negative.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    >>> bool(np.isclose(pipe_bend_force_magnitude(1.0, 1.0, np.pi / 2), np.sqrt(2.0)))
    True
    """
    qa = _nonnegative(q, "q")
    va = as_float_array(v, "v")
    a = as_float_array(angle, "angle")
    F: npt.NDArray[np.float64] = 2.0 * qa * np.abs(va) * np.abs(np.sin(0.5 * a))
    return F


pipe_bend_force_magnitude = finite_result(pipe_bend_force_magnitude)


def falling_chain_table_force(
    x: npt.ArrayLike, *, lam: npt.ArrayLike, h: npt.ArrayLike, g: npt.ArrayLike, ell: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Force from a falling chain on a table when a length x has landed (Problem 7.4).

    Domain: lam > 0, g > 0, ell > 0 (else NonPositiveParameterError), 0 ≤ x ≤ ell, h ≥ 0 (else
    OutOfDomainError); a result beyond float64 raises ResultOverflowError.

    A uniform chain (λ per length, length ℓ) hangs with its lower end at height h
    and is released from rest.  The hanging part falls freely; when x has landed
    it moves at v² = 2 g (h + x).  The chain on the table (an open system at rest,
    mass λ x, gaining mass λ v at velocity −v e_z) needs, by (7.19),
    F = λ g x + λ v² = λ g (3 x + 2 h) for 0 < x ≤ ℓ (and λ g ℓ once all has landed).

    Parameters
    ----------
    x : array_like, shape (...)
        Landed length, m, 0 ≤ x ≤ ℓ.
    lam, g, ell : array_like, shape (...)
        Mass per length (kg/m), gravity (m/s²), chain length ℓ (m), all > 0.
    h : array_like, shape (...)
        Initial height of the lower end, m (≥ 0).

    Returns
    -------
    F : ndarray, shape (...)
        Magnitude of the force between the table and the chain, N, λ g (3 x + 2 h),
        broadcast over the inputs.

    Raises
    ------
    NonPositiveParameterError
        If lam, g or ell is ≤ 0.
    OutOfDomainError
        If x lies outside [0, ell] or h < 0.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    The weight of the landed part plus the momentum flux λ v², v² = 2 g (h + x):

    >>> lam, g, x, h = 2.0, 10.0, 0.5, 0.25
    >>> float(falling_chain_table_force(x, lam=lam, h=h, g=g, ell=1.0))
    40.0
    >>> lam * g * x + lam * 2 * g * (h + x)
    40.0
    """
    xa = as_float_array(x, "x")
    L = _positive(ell, "ell")
    if ((xa < 0) | (xa > L)).any():
        raise OutOfDomainError(
            f"x must lie in [0, ell]; got {float(xa[(xa < 0) | (xa > L)].flat[0])!r}"
        )
    ha = as_float_array(h, "h")
    if (ha < 0).any():
        raise OutOfDomainError(f"h must be ≥ 0; got {float(ha[ha < 0].flat[0])!r}")
    F: npt.NDArray[np.float64] = _positive(lam, "lam") * _positive(g, "g") * (3.0 * xa + 2.0 * ha)
    return F


falling_chain_table_force = finite_result(falling_chain_table_force)


# ------------------------------------------------------------ rotating systems


def _carousel_inputs(
    t: npt.ArrayLike,
    J_0: npt.ArrayLike,
    q: npt.ArrayLike,
    v: npt.ArrayLike,
    r: npt.ArrayLike,
    R: npt.ArrayLike,
) -> tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]:
    ta = as_float_array(t, "t")
    if (ta < 0).any():
        raise OutOfDomainError(
            f"t must be ≥ 0 (shooting starts at t = 0); got {float(ta[ta < 0].flat[0])!r}"
        )
    J0 = _positive(J_0, "J_0")
    qa = _nonnegative(q, "q")
    va = as_float_array(v, "v")
    ra = as_float_array(r, "r")
    Ra = _positive(R, "R")
    if (np.abs(ra) > Ra).any():
        raise OutOfDomainError("the bullets miss: |r| must be ≤ R")
    return ta, J0, qa, va, ra, Ra


def carousel_angular_velocity(
    t: npt.ArrayLike,
    *,
    J_0: npt.ArrayLike,
    q: npt.ArrayLike,
    v: npt.ArrayLike,
    r: npt.ArrayLike,
    R: npt.ArrayLike,
    phidot_0: npt.ArrayLike = 0.0,
) -> npt.NDArray[np.float64]:
    """φ̇(t) of the carousel under fire, Example 7.3: the solution of (7.39).

    Domain: t ≥ 0, |r| ≤ R (else OutOfDomainError), J_0 > 0, R > 0 (else
    NonPositiveParameterError), q ≥ 0 (else NegativeMassError), finite v and phidot_0; a result
    beyond float64 raises ResultOverflowError.

    d/dt (J φ̇) = −r q v with J(t) = J_0 + q R² t (7.36)–(7.38) integrates to
    φ̇(t) = (J_0 φ̇_0 − r q v t)/(J_0 + q R² t) → −r v/R² (7.40) as t → ∞.

    Parameters
    ----------
    t : array_like, shape (...)
        Time since the shooting started, s (≥ 0).
    J_0 : array_like, shape (...)
        Moment of inertia about the axis at t = 0, kg m² (> 0).
    q, v : array_like, shape (...)
        Mass flow (kg/s, ≥ 0) and speed (m/s) of the bullets.
    r, R : array_like, shape (...)
        Signed perpendicular distance of the bullet line (m, |r| ≤ R), carousel radius
        (m, > 0).
    phidot_0 : array_like, shape (...), optional
        φ̇(0), rad/s (default 0, as in the book).

    Returns
    -------
    phidot : ndarray, shape (...)
        Angular velocity φ̇(t) about e_z, rad/s, broadcast over the inputs.

    Raises
    ------
    OutOfDomainError
        If t < 0 or |r| > R (the bullets miss).
    NonPositiveParameterError
        If J_0 or R is ≤ 0.
    NegativeMassError
        If q is negative.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    The limit (7.40) is approached as t grows:

    >>> w = carousel_angular_velocity(1e12, J_0=500.0, q=0.1, v=400.0, r=1.5, R=2.0)
    >>> bool(abs(w - (-1.5 * 400.0 / 4.0)) < 1e-6)
    True
    """
    ta, J0, qa, va, ra, Ra = _carousel_inputs(t, J_0, q, v, r, R)
    w0 = as_float_array(phidot_0, "phidot_0")
    w: npt.NDArray[np.float64] = (J0 * w0 - ra * qa * va * ta) / (J0 + qa * Ra**2 * ta)
    return w


carousel_angular_velocity = finite_result(carousel_angular_velocity)


def carousel_angular_acceleration(
    t: npt.ArrayLike,
    *,
    J_0: npt.ArrayLike,
    q: npt.ArrayLike,
    v: npt.ArrayLike,
    r: npt.ArrayLike,
    R: npt.ArrayLike,
    phidot_0: npt.ArrayLike = 0.0,
) -> npt.NDArray[np.float64]:
    """φ̈(t) from (7.39): (−r q v − q R² φ̇)/(J_0 + q R² t), φ̇ from the solution.

    Domain: as :func:`carousel_angular_velocity`; a result beyond float64 raises
    ResultOverflowError.

    Equals −q (r v + R² φ̇_0) J_0/J(t)²; negative at t = 0 for φ̇_0 = 0 (and r v > 0).

    Parameters
    ----------
    t : array_like, shape (...)
        Time since the shooting started, s (≥ 0).
    J_0 : array_like, shape (...)
        Moment of inertia about the axis at t = 0, kg m² (> 0).
    q, v : array_like, shape (...)
        Mass flow (kg/s, ≥ 0) and speed (m/s) of the bullets.
    r, R : array_like, shape (...)
        Signed perpendicular distance of the bullet line (m, |r| ≤ R), carousel radius
        (m, > 0).
    phidot_0 : array_like, shape (...), optional
        φ̇(0), rad/s (default 0, as in the book).

    Returns
    -------
    phiddot : ndarray, shape (...)
        Angular acceleration φ̈(t) about e_z, rad/s², broadcast over the inputs.

    Raises
    ------
    OutOfDomainError
        If t < 0 or |r| > R (the bullets miss).
    NonPositiveParameterError
        If J_0 or R is ≤ 0.
    NegativeMassError
        If q is negative.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    >>> float(carousel_angular_acceleration(0.0, J_0=500.0, q=0.1, v=400.0, r=1.5, R=2.0))
    -0.12
    """
    ta, J0, qa, va, ra, Ra = _carousel_inputs(t, J_0, q, v, r, R)
    w0 = as_float_array(phidot_0, "phidot_0")
    J = J0 + qa * Ra**2 * ta
    a: npt.NDArray[np.float64] = -qa * (ra * va + Ra**2 * w0) * J0 / J**2
    return a


carousel_angular_acceleration = finite_result(carousel_angular_acceleration)


def carousel_limit_angular_velocity(
    *, v: npt.ArrayLike, r: npt.ArrayLike, R: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """φ̇_lim = −r v/R² (7.40): the bullets then arrive with the rim's angular velocity.

    Domain: R > 0 (else NonPositiveParameterError), |r| ≤ R (else OutOfDomainError), finite v; a
    result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    v : array_like, shape (...)
        Speed of the bullets, m/s.
    r : array_like, shape (...)
        Signed perpendicular distance of the bullet line from the axis, m (|r| ≤ R).
    R : array_like, shape (...)
        Carousel radius, m (> 0).

    Returns
    -------
    phidot : ndarray, shape (...)
        The limit angular velocity as t → ∞, rad/s, broadcast over the inputs.

    Raises
    ------
    NonPositiveParameterError
        If R is ≤ 0.
    OutOfDomainError
        If |r| > R (the bullets miss).
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    >>> float(carousel_limit_angular_velocity(v=400.0, r=1.5, R=2.0))
    -150.0
    """
    ra, Ra = as_float_array(r, "r"), _positive(R, "R")
    if (np.abs(ra) > Ra).any():
        raise OutOfDomainError("the bullets miss: |r| must be ≤ R")
    # (r/R)·v/R: |r/R| ≤ 1, so no step overflows unless the result does, and R² (which
    # underflows to a subnormal or 0 for R below about 1e-154) is never formed
    w: npt.NDArray[np.float64] = -(ra / Ra) * as_float_array(v, "v") / Ra
    return w


carousel_limit_angular_velocity = finite_result(carousel_limit_angular_velocity)


def rim_rocket_angular_velocity(
    t: npt.ArrayLike, *, J_0: npt.ArrayLike, q: npt.ArrayLike, u: npt.ArrayLike, r: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Spin-up of a wheel by rockets on its rim that eject mass tangentially.

    Domain: t ≥ 0 with q r² t < J_0 (else OutOfDomainError), J_0, q, u, r > 0 (else
    NonPositiveParameterError); a result beyond float64 raises ResultOverflowError.

    The expelled mass (total flow q, exhaust speed u relative to the rocket) sits at
    radius r, so J(t) = J_0 − q r² t, and (7.35) gives J dω/dt = q r u (Problem
    7.3), ω(0) = 0:  ω(t) = −(u/r) log1p(−q r² t/J_0), for q r² t < J_0.

    Parameters
    ----------
    t : array_like, shape (...)
        Time since ignition, s (≥ 0, with q r² t < J_0).
    J_0 : array_like, shape (...)
        Moment of inertia of the wheel with its rockets at t = 0, kg m² (> 0).
    q : array_like, shape (...)
        Total mass flow of the rockets, kg/s (> 0).
    u : array_like, shape (...)
        Exhaust speed relative to the rockets, m/s (> 0).
    r : array_like, shape (...)
        Radius of the rim, m (> 0).

    Returns
    -------
    omega : ndarray, shape (...)
        Angular velocity ω(t), rad/s, broadcast over the inputs.

    Raises
    ------
    OutOfDomainError
        If t < 0, or q r² t ≥ J_0 (the wheel cannot expel all its inertia).
    NonPositiveParameterError
        If J_0, q, u or r is ≤ 0.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    >>> w = rim_rocket_angular_velocity(10.0, J_0=1e6, q=2.0, u=3000.0, r=50.0)
    >>> bool(abs(w - 60.0 * np.log(1e6 / (1e6 - 5e4))) < 1e-12)
    True
    """
    ta = as_float_array(t, "t")
    if (ta < 0).any():
        raise OutOfDomainError(f"t must be ≥ 0; got {float(ta[ta < 0].flat[0])!r}")
    qq, rr = _positive(q, "q"), _positive(r, "r")
    x = _rate_ratio(qq, rr, rr, ta, over=_positive(J_0, "J_0"))
    if (x >= 1).any():
        raise OutOfDomainError("q r² t must be < J_0 (the wheel cannot expel all its inertia)")
    w: npt.NDArray[np.float64] = -(_positive(u, "u") / rr) * np.log1p(-x)
    return w


rim_rocket_angular_velocity = finite_result(rim_rocket_angular_velocity)


def rim_rocket_spin_up_time(
    omega: npt.ArrayLike,
    *,
    J_0: npt.ArrayLike,
    q: npt.ArrayLike,
    u: npt.ArrayLike,
    r: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """Time for the rim rockets of :func:`rim_rocket_angular_velocity` to reach ω.

    Domain: ω ≥ 0 (else OutOfDomainError), J_0, q, u, r > 0 (else NonPositiveParameterError); a
    result beyond float64 raises ResultOverflowError.

    t = −J_0 expm1(−r ω/u)/(q r²) (the inverse; expm1 keeps small r ω/u accurate).

    Parameters
    ----------
    omega : array_like, shape (...)
        Target angular velocity ω, rad/s (≥ 0).
    J_0 : array_like, shape (...)
        Moment of inertia of the wheel with its rockets at t = 0, kg m² (> 0).
    q : array_like, shape (...)
        Total mass flow of the rockets, kg/s (> 0).
    u : array_like, shape (...)
        Exhaust speed relative to the rockets, m/s (> 0).
    r : array_like, shape (...)
        Radius of the rim, m (> 0).

    Returns
    -------
    t : ndarray, shape (...)
        Time at which ω is reached, s, broadcast over the inputs.

    Raises
    ------
    OutOfDomainError
        If omega < 0.
    NonPositiveParameterError
        If J_0, q, u or r is ≤ 0.
    ShapeError
        If an input is not a real numeric array, or the inputs do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    >>> t = rim_rocket_spin_up_time(0.2, J_0=1e6, q=2.0, u=3000.0, r=50.0)
    >>> bool(abs(rim_rocket_angular_velocity(t, J_0=1e6, q=2.0, u=3000.0, r=50.0) - 0.2) < 1e-15)
    True
    """
    w = as_float_array(omega, "omega")
    if (w < 0).any():
        raise OutOfDomainError(
            f"omega must be ≥ 0 (the rockets push forward); got {float(w[w < 0].flat[0])!r}"
        )
    ra = _positive(r, "r")
    t: npt.NDArray[np.float64] = (
        -_positive(J_0, "J_0")
        * np.expm1(-ra * w / _positive(u, "u"))
        / _positive(q, "q")  # q·r could underflow to 0: divide one at a time
        / ra
        / ra
    )
    return t


rim_rocket_spin_up_time = finite_result(rim_rocket_spin_up_time)
