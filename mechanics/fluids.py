"""Velocity fields of ideal fluids: divergence, curl, material derivative, Euler, Bernoulli.

Conventions (Essén 1996, ch. 8)
-------------------------------
- A **field** is a Python callable ``f(r, t)`` vectorised over leading axes:
  ``r`` has shape ``(..., 3)`` (Cartesian components in a fixed frame O), ``t`` is a
  float, and the callable returns ``(..., 3)`` for a vector field (the velocity
  v(r, t)) or ``(...)`` for a scalar field (density ρ(r, t), pressure p(r, t),
  temperature).  Every function here calls a field once per stencil with all
  stencil points stacked, so the Python overhead is paid once, not per point.
- The velocity gradient is ``G[..., i, j] = ∂v_i/∂x_j``; div v = tr G; curl v is
  the axial vector of G − Gᵀ; (v·∇)v = G v.
- Spatial and time derivatives are fourth-order central differences
  (f(x−2h) − 8 f(x−h) + 8 f(x+h) − f(x+2h))/(12 h), exact for polynomials of
  degree ≤ 4 up to rounding.  The default step is ``h = H_REL (1 + |r|∞)``
  (respectively ``H_REL (1 + |t|)``) with ``H_REL = EPS**(1/5)``, which balances the
  truncation error O(h⁴) against the rounding error O(eps/h): the relative error is
  then about eps^(4/5) ≈ 3e-13 of the field's scale for smooth fields.  Pass
  ``h=`` to choose another step.
- Gravity points along −e_z: g = −g e_z with g > 0 the magnitude (8.34); z is the
  third component of r, upward.
- Example 8.1 (Torricelli): a small hole at depth h below the free surface; the
  book neglects the speed of the surface.  :func:`torricelli_speed` and
  :func:`tank_level` take ``area_ratio`` = (hole area)/(surface area) in [0, 1),
  default 0 (the book's assumption); a nonzero ratio keeps the surface speed in
  Bernoulli's equation (quasi-steady flow).

Every function validates its numeric input (finite, right shapes, positive
densities and g) and checks that the fields return finite values of the right shape.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import numpy.typing as npt
from scipy.integrate import solve_ivp

from ._validate import as_float_array, as_float_scalar, as_positive_scalar, finite_result
from .errors import (
    NonFiniteError,
    NonPositiveParameterError,
    OutOfDomainError,
    ShapeError,
    StepSizeError,
)
from .rotation import EPS

__all__ = [
    "H_REL",
    "bernoulli_constant",
    "continuity_residual",
    "curl",
    "divergence",
    "drain_time",
    "euler_residual",
    "gradient",
    "material_derivative",
    "partial_time_derivative",
    "rigid_velocity_field",
    "streamline",
    "tank_level",
    "torricelli_speed",
    "velocity_gradient",
]

#: Relative step of the fourth-order central differences: the h that balances the
#: truncation error h⁴ f⁽⁵⁾/30 against the rounding error ~1.5 eps |f|/h for fields
#: whose derivatives are of the order of the field over a unit length.
H_REL = EPS ** (1 / 5)

Field = Callable[[np.ndarray, float], np.ndarray]

#: The fourth-order central-difference stencil: offsets and weights (× 1/(12 h)).
_OFFSETS = np.array([-2.0, -1.0, 1.0, 2.0])
_WEIGHTS = np.array([1.0, -8.0, 8.0, -1.0]) / 12.0


def _call(f: Field, r: np.ndarray, t: float, name: str, *, vector: bool | None) -> np.ndarray:
    """Evaluate a field and check its output (shape and finiteness)."""
    out = np.asarray(f(r, t), dtype=float)
    base = r.shape[:-1]
    if vector is None:
        vector = out.shape == r.shape and out.shape != base
    want = r.shape if vector else base
    if out.shape != want:
        kind = "vector" if vector else "scalar"
        raise ShapeError(
            f"{name}(r, t) returned shape {out.shape} for r of shape {r.shape}; "
            f"a {kind} field must return {want}"
        )
    if not np.isfinite(out).all():
        raise NonFiniteError(f"{name}(r, t) returned a non-finite value at t = {t!r}")
    return out


def _points(r: npt.ArrayLike) -> npt.NDArray[np.float64]:
    return as_float_array(r, "r", (3,))


def _time(t: npt.ArrayLike) -> float:
    tt = as_float_array(t, "t")
    if tt.ndim != 0:
        raise ShapeError(f"t must be a scalar time; got shape {tt.shape}")
    return float(tt)


def _space_step(r: npt.NDArray[np.float64], h: npt.ArrayLike | None) -> npt.NDArray[np.float64]:
    if h is None:
        step: npt.NDArray[np.float64] = H_REL * (1.0 + np.max(np.abs(r), axis=-1))
        return step
    hh = as_float_array(h, "h")
    if np.any(hh <= 0):
        raise NonPositiveParameterError(f"the step h must be > 0; got {h!r}")
    return np.broadcast_to(hh, r.shape[:-1]).astype(float)


def _spatial_derivatives(
    f: Field, r: npt.ArrayLike, t: float, h: npt.ArrayLike | None, name: str, *, vector: bool | None
) -> npt.NDArray[np.float64]:
    """∂f/∂x_j for j = 0, 1, 2 stacked on a new last axis: ``(..., [3,] 3)``."""
    r = _points(r)
    t = _time(t)
    step = _space_step(r, h)  # (...)
    # stencil points: (4 offsets, 3 directions, ..., 3)
    shift = _OFFSETS[:, None, None] * np.eye(3)[None, :, :]  # (4, 3, 3)
    shift = shift.reshape((4, 3) + (1,) * (r.ndim - 1) + (3,))
    pts = r[None, None] + shift * step[..., None]
    vals = _call(f, pts, t, name, vector=vector)
    if vector is None:
        vector = vals.shape == pts.shape
    w = _WEIGHTS.reshape((4,) + (1,) * (vals.ndim - 1))
    d = (w * vals).sum(axis=0)  # (3 directions, ..., [3])
    d = d / (step[..., None] if vector else step)
    return np.moveaxis(d, 0, -1)


def velocity_gradient(
    v: Field, r: npt.ArrayLike, t: float = 0.0, *, h: npt.ArrayLike | None = None
) -> npt.NDArray[np.float64]:
    """The velocity gradient G[..., i, j] = ∂v_i/∂x_j at the points ``r``.

    Domain: finite points r (..., 3), a scalar time t, a step h > 0 (default H_REL·(1 + |r|∞)); the
    field must return finite values of its shape at the stencil points r ± h, r ± 2h (else
    NonFiniteError or ShapeError naming it); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    v : callable
        Velocity field ``v(r, t) -> (..., 3)``, m/s.
    r : array_like, shape (..., 3)
        Points, m (finite).
    t : float, optional
        Time, s (a scalar; default 0).
    h : float or array_like, shape (...), optional
        Spatial finite-difference step, m (> 0), broadcasting over the leading axes of r
        (default ``H_REL (1 + |r|∞)``).

    Returns
    -------
    G : ndarray, shape (..., 3, 3)
        G[..., i, j] = ∂v_i/∂x_j, 1/s (fourth-order central differences).

    Raises
    ------
    ShapeError
        If r does not end in 3, t is not a scalar, h does not broadcast over the points, an
        input is not real numeric, or v returns another shape than (..., 3).
    NonFiniteError
        If r, t or h holds NaN or an infinity, or v returns a non-finite value at a
        stencil point.
    NonPositiveParameterError
        If a step h is ≤ 0.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    A linear field v = A r has gradient A (the stencil is exact for it):

    >>> import numpy as np
    >>> A = np.array([[0.0, 1.0, 2.0], [3.0, 0.5, 0.0], [0.0, 0.0, -1.0]])
    >>> G = velocity_gradient(lambda r, t: r @ A.T, [0.3, -0.2, 1.0])
    >>> bool(np.allclose(G, A, rtol=0, atol=1e-11))
    True
    """
    return _spatial_derivatives(v, r, t, h, "v", vector=True)


velocity_gradient = finite_result(velocity_gradient)


def divergence(
    v: Field, r: npt.ArrayLike, t: float = 0.0, *, h: npt.ArrayLike | None = None
) -> npt.NDArray[np.float64]:
    """div v = ∇·v at the points ``r`` (8.6); shape ``(...)``.

    Domain: finite points r (..., 3), a scalar time t, a step h > 0 (default H_REL·(1 + |r|∞)); the
    field must return finite values of its shape at the stencil points r ± h, r ± 2h (else
    NonFiniteError or ShapeError naming it); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    v : callable
        Velocity field ``v(r, t) -> (..., 3)``, m/s.
    r : array_like, shape (..., 3)
        Points, m (finite).
    t : float, optional
        Time, s (a scalar; default 0).
    h : float or array_like, shape (...), optional
        Spatial finite-difference step, m (> 0), broadcasting over the leading axes of r
        (default ``H_REL (1 + |r|∞)``).

    Returns
    -------
    div : ndarray, shape (...)
        ∇·v = tr G, 1/s: the relative rate of change of volume of a fluid element.

    Raises
    ------
    ShapeError
        If r does not end in 3, t is not a scalar, h does not broadcast over the points, an
        input is not real numeric, or v returns another shape than (..., 3).
    NonFiniteError
        If r, t or h holds NaN or an infinity, or v returns a non-finite value at a
        stencil point.
    NonPositiveParameterError
        If a step h is ≤ 0.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    A rigid motion (8.7) does not change volumes: its divergence vanishes.

    >>> import numpy as np
    >>> v = rigid_velocity_field([1.0, 0.0, 2.0], [0.3, -1.0, 0.5])
    >>> abs(float(divergence(v, [1.0, 2.0, 3.0]))) < 1e-11
    True
    """
    div: npt.NDArray[np.float64] = np.trace(velocity_gradient(v, r, t, h=h), axis1=-2, axis2=-1)
    return div


divergence = finite_result(divergence)


def curl(
    v: Field, r: npt.ArrayLike, t: float = 0.0, *, h: npt.ArrayLike | None = None
) -> npt.NDArray[np.float64]:
    """curl v = ∇×v at the points ``r``; shape ``(..., 3)``.

    Domain: finite points r (..., 3), a scalar time t, a step h > 0 (default H_REL·(1 + |r|∞)); the
    field must return finite values of its shape at the stencil points r ± h, r ± 2h (else
    NonFiniteError or ShapeError naming it); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    v : callable
        Velocity field ``v(r, t) -> (..., 3)``, m/s.
    r : array_like, shape (..., 3)
        Points, m (finite).
    t : float, optional
        Time, s (a scalar; default 0).
    h : float or array_like, shape (...), optional
        Spatial finite-difference step, m (> 0), broadcasting over the leading axes of r
        (default ``H_REL (1 + |r|∞)``).

    Returns
    -------
    curl : ndarray, shape (..., 3)
        ∇×v, the axial vector of G − Gᵀ, 1/s (the vorticity).

    Raises
    ------
    ShapeError
        If r does not end in 3, t is not a scalar, h does not broadcast over the points, an
        input is not real numeric, or v returns another shape than (..., 3).
    NonFiniteError
        If r, t or h holds NaN or an infinity, or v returns a non-finite value at a
        stencil point.
    NonPositiveParameterError
        If a step h is ≤ 0.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    The curl of a rigid motion is twice its angular velocity (8.8):

    >>> import numpy as np
    >>> w = np.array([0.3, -1.0, 0.5])
    >>> c = curl(rigid_velocity_field([1.0, 0.0, 2.0], w), [1.0, 2.0, 3.0])
    >>> bool(np.allclose(c, 2 * w, rtol=0, atol=1e-11))
    True
    """
    G = velocity_gradient(v, r, t, h=h)
    return np.stack(
        [G[..., 2, 1] - G[..., 1, 2], G[..., 0, 2] - G[..., 2, 0], G[..., 1, 0] - G[..., 0, 1]],
        axis=-1,
    )


curl = finite_result(curl)


def gradient(
    f: Field, r: npt.ArrayLike, t: float = 0.0, *, h: npt.ArrayLike | None = None
) -> npt.NDArray[np.float64]:
    """∇f of a scalar field at the points ``r``; shape ``(..., 3)``.

    Domain: finite points r (..., 3), a scalar time t, a step h > 0 (default H_REL·(1 + |r|∞)); the
    field must return finite values of its shape at the stencil points r ± h, r ± 2h (else
    NonFiniteError or ShapeError naming it); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    f : callable
        Scalar field ``f(r, t) -> (...)`` (a pressure, a density, a temperature).
    r : array_like, shape (..., 3)
        Points, m (finite).
    t : float, optional
        Time, s (a scalar; default 0).
    h : float or array_like, shape (...), optional
        Spatial finite-difference step, m (> 0), broadcasting over the leading axes of r
        (default ``H_REL (1 + |r|∞)``).

    Returns
    -------
    grad : ndarray, shape (..., 3)
        ∂f/∂x_j, in the units of f per m.

    Raises
    ------
    ShapeError
        If r does not end in 3, t is not a scalar, h does not broadcast over the points, an
        input is not real numeric, or f returns another shape than (...).
    NonFiniteError
        If r, t or h holds NaN or an infinity, or f returns a non-finite value at a
        stencil point.
    NonPositiveParameterError
        If a step h is ≤ 0.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    >>> import numpy as np
    >>> g = gradient(lambda r, t: r[..., 0] ** 2 * r[..., 2], [1.0, 5.0, 3.0])
    >>> bool(np.allclose(g, [6.0, 0.0, 1.0], rtol=0, atol=1e-10))
    True
    """
    return _spatial_derivatives(f, r, t, h, "f", vector=False)


gradient = finite_result(gradient)


def partial_time_derivative(
    f: Field, r: npt.ArrayLike, t: float = 0.0, *, h: float | None = None
) -> npt.NDArray[np.float64]:
    """∂f/∂t at fixed points ``r`` (8.9), for a scalar or a vector field.

    Domain: finite r (..., 3), scalar t, time step h > 0 (else ShapeError, NonFiniteError or
    NonPositiveParameterError); f finite at t ± h, t ± 2h; a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    f : callable
        Field ``f(r, t)`` returning ``(...)`` (scalar) or ``(..., 3)`` (vector).
    r : array_like, shape (..., 3)
        Points, m (finite).
    t : float, optional
        Time, s (a scalar; default 0).
    h : float, optional
        Time step of the fourth-order central difference, s (> 0; default
        ``H_REL (1 + |t|)``).

    Returns
    -------
    df_dt : ndarray, shape (...) or (..., 3)
        ∂f/∂t, in the units of f per s, the shape of f's values.

    Raises
    ------
    ShapeError
        If r does not end in 3, t or h is not a scalar, an input is not real numeric, or f
        returns another shape than ``(...)`` or ``(..., 3)``.
    NonFiniteError
        If r, t or h holds NaN or an infinity, or f returns a non-finite value at a stencil
        time.
    NonPositiveParameterError
        If h is ≤ 0.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    >>> d = partial_time_derivative(lambda r, t: r[..., 0] * t**2, [2.0, 0.0, 0.0], 3.0)
    >>> round(float(d), 10)
    12.0
    """
    r = _points(r)
    t = _time(t)
    if h is None:
        step = H_REL * (1.0 + abs(t))
    else:
        step = as_float_scalar(h, "h")
        if step <= 0:
            raise NonPositiveParameterError(f"the step h must be > 0; got {h!r}")
    vals = [_call(f, r, t + o * step, "f", vector=None) for o in _OFFSETS]
    d: npt.NDArray[np.float64] = sum(w * val for w, val in zip(_WEIGHTS, vals, strict=True)) / step
    return d


partial_time_derivative = finite_result(partial_time_derivative)


def material_derivative(
    f: Field, v: Field, r: npt.ArrayLike, t: float = 0.0, *, h: npt.ArrayLike | None = None
) -> npt.NDArray[np.float64]:
    """The total (material) time derivative (8.12): df/dt = ∂f/∂t + (v·∇) f.

    Domain: finite points r (..., 3), a scalar time t, a step h > 0 (default H_REL·(1 + |r|∞)); the
    field must return finite values of its shape at the stencil points r ± h, r ± 2h (else
    NonFiniteError or ShapeError naming it); a result beyond float64 raises ResultOverflowError.

    ``f`` may be a scalar field (result ``(...)``) or a vector field (result
    ``(..., 3)``; with ``f = v`` this is the acceleration of a fluid particle, 8.20).

    Parameters
    ----------
    f : callable
        Field ``f(r, t)`` returning ``(...)`` (scalar) or ``(..., 3)`` (vector).
    v : callable
        Velocity field ``v(r, t) -> (..., 3)``, m/s.
    r : array_like, shape (..., 3)
        Points, m (finite).
    t : float, optional
        Time, s (a scalar; default 0).
    h : float or array_like, shape (...), optional
        Spatial finite-difference step, m (> 0), broadcasting over the leading axes of r
        (default ``H_REL (1 + |r|∞)``); ∂f/∂t always takes the default time step of
        :func:`partial_time_derivative`.

    Returns
    -------
    df_dt : ndarray, shape (...) or (..., 3)
        df/dt following the fluid, in the units of f per s, the shape of f's values.

    Raises
    ------
    ShapeError
        If r does not end in 3, t is not a scalar, h does not broadcast over the points, an
        input is not real numeric, or v returns another shape than (..., 3), or f another
        than (...) or (..., 3).
    NonFiniteError
        If r, t or h holds NaN or an infinity, or f or v returns a non-finite value at a
        stencil point.
    NonPositiveParameterError
        If a step h is ≤ 0.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    Following a particle of the rigid rotation v = ω e_z × r, the field f = x
    changes at the rate v_x = −ω y:

    >>> v = rigid_velocity_field([0.0, 0.0, 0.0], [0.0, 0.0, 2.0])
    >>> round(float(material_derivative(lambda r, t: r[..., 0], v, [1.0, 3.0, 0.0])), 10)
    -6.0
    """
    r = _points(r)
    vel = _call(v, r, _time(t), "v", vector=True)
    df_dt = partial_time_derivative(f, r, t, h=None)
    grad = _spatial_derivatives(f, r, t, h, "f", vector=None)  # (..., [3,] 3)
    rate: npt.NDArray[np.float64]
    if grad.ndim == r.ndim:  # scalar field: (..., 3)
        rate = df_dt + np.einsum("...j,...j->...", grad, vel)
        return rate
    rate = df_dt + np.einsum("...ij,...j->...i", grad, vel)
    return rate


material_derivative = finite_result(material_derivative)


def rigid_velocity_field(v_0: npt.ArrayLike, omega: npt.ArrayLike) -> Field:
    """The velocity field of a rigid motion, v(r) = v(0) + ω × r (8.7).

    Domain: finite v_0 and omega of shape (3,) (else ShapeError); the field takes any finite points
    (..., 3).

    Parameters
    ----------
    v_0 : array_like, shape (3,)
        Velocity at the origin, m/s.
    omega : array_like, shape (3,)
        Angular velocity, rad/s.

    Returns
    -------
    field : callable
        ``field(r, t=0.0) -> ndarray, shape (..., 3)``, m/s, for points r of shape
        ``(..., 3)``; t is ignored (the motion is steady).  The field does not validate its
        points: non-finite points, or products beyond float64, give non-finite values.

    Raises
    ------
    ShapeError
        If v_0 or omega is not of shape (3,) or not real numeric.
    NonFiniteError
        If v_0 or omega holds NaN or an infinity.

    Examples
    --------
    >>> v = rigid_velocity_field([1.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    >>> v([[0.0, 2.0, 0.0]], 0.0).tolist()
    [[-1.0, 0.0, 0.0]]
    """
    v0 = as_float_array(v_0, "v_0", (3,))
    w = as_float_array(omega, "omega", (3,))
    if v0.shape != (3,) or w.shape != (3,):
        raise ShapeError("v_0 and omega of a rigid velocity field must have shape (3,)")

    def field(r: npt.ArrayLike, t: float = 0.0) -> npt.NDArray[np.float64]:
        return v0 + np.cross(w, np.asarray(r, dtype=float))

    return field


rigid_velocity_field = finite_result(rigid_velocity_field)


def continuity_residual(
    rho: Field, v: Field, r: npt.ArrayLike, t: float = 0.0, *, h: npt.ArrayLike | None = None
) -> npt.NDArray[np.float64]:
    """∂ρ/∂t + ∇·(ρ v) at the points ``r``: zero when mass is conserved (8.18).

    Domain: finite points r (..., 3), a scalar time t, a step h > 0 (default H_REL·(1 + |r|∞)); the
    field must return finite values of its shape at the stencil points r ± h, r ± 2h (else
    NonFiniteError or ShapeError naming it); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    rho : callable
        Density field ``rho(r, t) -> (...)``, kg/m³.
    v : callable
        Velocity field ``v(r, t) -> (..., 3)``, m/s.
    r : array_like, shape (..., 3)
        Points, m (finite).
    t : float, optional
        Time, s (a scalar; default 0).
    h : float or array_like, shape (...), optional
        Spatial finite-difference step, m (> 0), broadcasting over the leading axes of r
        (default ``H_REL (1 + |r|∞)``); ∂ρ/∂t takes the default time step of
        :func:`partial_time_derivative`.

    Returns
    -------
    residual : ndarray, shape (...)
        ∂ρ/∂t + ∇·(ρ v), kg/(m³ s).

    Raises
    ------
    ShapeError
        If r does not end in 3, t is not a scalar, h does not broadcast over the points, an
        input is not real numeric, or rho returns another shape than (...), or v another
        than (..., 3).
    NonFiniteError
        If r, t or h holds NaN or an infinity, or rho or v returns a non-finite value at a
        stencil point.
    NonPositiveParameterError
        If a step h is ≤ 0.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    A uniform expansion v = (x, 0, 0) (div v = 1) thins a uniform density as ρ = e^{−t}:
    ∂ρ/∂t = −ρ and ∇·(ρ v) = ρ div v = ρ cancel.

    >>> import numpy as np
    >>> res = continuity_residual(lambda r, t: np.exp(-t) + 0 * r[..., 0],
    ...                           lambda r, t: r * [1.0, 0.0, 0.0], [0.5, 1.0, -2.0], 0.3)
    >>> bool(abs(res) < 1e-11)  # the finite differences' truncation, not a rounding
    True
    """
    r = _points(r)

    def flux(x: npt.NDArray[np.float64], s: float) -> npt.NDArray[np.float64]:
        rho_v: npt.NDArray[np.float64] = _call(rho, x, s, "rho", vector=False)[..., None] * _call(
            v, x, s, "v", vector=True
        )
        return rho_v

    div_flux = np.trace(_spatial_derivatives(flux, r, t, h, "rho*v", vector=True), 0, -2, -1)
    res: npt.NDArray[np.float64] = partial_time_derivative(rho, r, t) + div_flux
    return res


continuity_residual = finite_result(continuity_residual)


_positive = as_positive_scalar


def euler_residual(
    v: Field,
    p: Field,
    r: npt.ArrayLike,
    t: float = 0.0,
    *,
    rho: float,
    g: float,
    h: npt.ArrayLike | None = None,
) -> npt.NDArray[np.float64]:
    """Residual of Euler's equation (8.27) at the points ``r``: ∂v/∂t + (v·∇)v − g_vec + ∇p/ρ.

    Zero for a flow of an ideal fluid of constant density ``rho`` under gravity
    g_vec = −g e_z (8.27).

    Domain: rho > 0, g > 0 (scalars), finite points r (..., 3), a scalar time t, a step h > 0
    (default H_REL·(1 + |r|∞)); the fields must return finite values of their shape at the stencil
    points (else NonFiniteError or ShapeError naming them); a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    v : callable
        Velocity field ``v(r, t) -> (..., 3)``, m/s.
    p : callable
        Pressure field ``p(r, t) -> (...)``, Pa.
    r : array_like, shape (..., 3)
        Points, m (finite).
    t : float, optional
        Time, s (a scalar; default 0).
    rho : float
        Constant density, kg/m³ (> 0).
    g : float
        Magnitude of gravity, m/s² (> 0).
    h : float or array_like, shape (...), optional
        Spatial finite-difference step, m (> 0), broadcasting over the leading axes of r
        (default ``H_REL (1 + |r|∞)``); ∂v/∂t takes the default time step of
        :func:`partial_time_derivative`.

    Returns
    -------
    residual : ndarray, shape (..., 3)
        The acceleration of the fluid minus the force per mass, m/s².

    Raises
    ------
    NonPositiveParameterError
        If rho, g or a step h is ≤ 0.
    ShapeError
        If r does not end in 3, t, rho or g is not a scalar, h does not broadcast over the
        points, an input is not real numeric, or v returns another shape than (..., 3), or p
        another than (...).
    NonFiniteError
        If r, t, rho, g or h holds NaN or an infinity, or v or p returns a non-finite value
        at a stencil point.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    Water rotating rigidly in a bucket (the forced vortex) with the paraboloid
    pressure p = ρ ω² (x² + y²)/2 − ρ g z solves Euler's equation:

    >>> import numpy as np
    >>> w, rho, g = 2.0, 1000.0, 9.81
    >>> v = rigid_velocity_field([0.0, 0.0, 0.0], [0.0, 0.0, w])
    >>> def p(r, t):
    ...     return rho * w**2 * (r[..., 0] ** 2 + r[..., 1] ** 2) / 2 - rho * g * r[..., 2]
    >>> res = euler_residual(v, p, [0.5, -0.3, 0.2], rho=rho, g=g)
    >>> bool(np.all(np.abs(res) < 1e-9))
    True
    """
    r = _points(r)
    rho_0 = _positive(rho, "rho")
    g_mag = _positive(g, "g")
    accel = material_derivative(v, v, r, t, h=h)
    grad_p = _spatial_derivatives(p, r, t, h, "p", vector=False)
    g_vec = np.array([0.0, 0.0, -g_mag])
    res: npt.NDArray[np.float64] = accel - g_vec + grad_p / rho_0
    return res


euler_residual = finite_result(euler_residual)


def bernoulli_constant(
    v: npt.ArrayLike, p: npt.ArrayLike, z: npt.ArrayLike, *, rho_0: float, g: float
) -> npt.NDArray[np.float64]:
    """Bernoulli's constant ½ ρ0 v² + ρ0 g z + p (8.34) at given velocities, pressures, heights.

    It is constant along a streamline of a steady incompressible ideal flow.

    Domain: rho_0 > 0, g > 0 (else NonPositiveParameterError), finite v (..., 3), p and z; a result
    (or one of its terms) beyond float64 raises ResultOverflowError.  The terms are formed from
    the mantissas with their powers of two apart, so |v|² or ρ0 g beyond float64's range on the
    way to an ordinary term (ρ0 = 1e-100, |v| = 1e160) does not matter.

    Parameters
    ----------
    v : array_like, shape (..., 3)
        Velocities, m/s.
    p, z : array_like, shape (...)
        Pressures (Pa) and heights (m, z upward).
    rho_0, g : float
        Density (kg/m³) and gravitational acceleration (m/s²), both > 0.

    Returns
    -------
    B : ndarray, shape (...)
        ½ ρ0 |v|² + ρ0 g z + p, Pa (J/m³), broadcast over the inputs.

    Raises
    ------
    NonPositiveParameterError
        If rho_0 or g is ≤ 0.
    ShapeError
        If v does not end in 3, rho_0 or g is not a scalar, an input is not real numeric, or
        the leading axes of v, p and z do not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    Torricelli (Example 8.1): the free surface (v = 0, z = 0, p = p0) and the jet
    at depth h (speed √(2gh), p = p0) have the same constant.

    >>> import numpy as np
    >>> g, h = 9.81, 2.0
    >>> B = bernoulli_constant([[0, 0, 0], [np.sqrt(2 * g * h), 0, 0]], [1e5, 1e5], [0, -h],
    ...                        rho_0=1000.0, g=g)
    >>> bool(np.isclose(B[0], B[1], rtol=1e-15))
    True
    """
    vel = as_float_array(v, "v", (3,))
    pp = as_float_array(p, "p")
    zz = as_float_array(z, "z")
    rho = _positive(rho_0, "rho_0")
    g_mag = _positive(g, "g")
    B: npt.NDArray[np.float64] = _kinetic_density(vel, rho) + _weight_density(zz, rho, g_mag) + pp
    return B


def _kinetic_density(v: npt.NDArray[np.float64], rho: float) -> npt.NDArray[np.float64]:
    """½ ρ |v|² with v scaled by a power of two (its largest component into [1/2, 1)) and ρ's
    mantissa, the exponents added once: |v|² alone overflows beyond |v| ~ 1e154 and
    underflows below ~1e-154 where ½ ρ |v|² may be an ordinary float."""
    k = np.frexp(np.abs(v).max(axis=-1))[1]
    vs = np.ldexp(v, -k[..., None])
    f, e = math.frexp(rho)
    out: npt.NDArray[np.float64] = np.ldexp(
        (0.5 * f) * np.einsum("...i,...i->...", vs, vs), e + 2 * k
    )
    return out


def _weight_density(z: npt.NDArray[np.float64], rho: float, g: float) -> npt.NDArray[np.float64]:
    """ρ g z from the three mantissas, the exponents added once (ρ g may over- or underflow
    where ρ g z does not)."""
    fz, ez = np.frexp(z)
    fr, er = math.frexp(rho)
    fg, eg = math.frexp(g)
    out: npt.NDArray[np.float64] = np.ldexp((fr * fg) * fz, er + eg + ez)
    return out


bernoulli_constant = finite_result(bernoulli_constant)


#: the smallest rtol of a streamline: scipy's solve_ivp raises it to 100 eps with a warning
STREAMLINE_MIN_RTOL = 100 * EPS

#: the evaluations of the field a streamline may take (10⁴ DOP853 steps of 12 stages): bounded
#: time for any input; a span of 1e300 would otherwise integrate for ever
STREAMLINE_MAX_EVALS = 12 * 10**4


def streamline(
    v: Field, r_0: npt.ArrayLike, s: npt.ArrayLike, *, t: float = 0.0, rtol: float = 1e-12
) -> npt.NDArray[np.float64]:
    """Points of the streamline dr/ds = v(r, t) through ``r_0`` (8.31) at parameter values ``s``.

    Time is frozen at ``t``; for a steady flow s is time.

    Domain: r_0 of shape (3,), s 1-D and non-empty, a scalar t (else ShapeError), s strictly
    increasing (else OutOfDomainError), rtol in [STREAMLINE_MIN_RTOL, 1) (else OutOfDomainError);
    the field finite along the way (else NonFiniteError); at most ``STREAMLINE_MAX_EVALS`` field
    evaluations (else StepSizeError: bounded time); a streamline that escapes to infinity before
    s[-1] raises OutOfDomainError (the integration fails) or ResultOverflowError.

    Integrated with scipy's DOP853 at relative tolerance ``rtol``; returns
    ``(len(s), 3)``.

    Parameters
    ----------
    v : callable
        Velocity field ``v(r, t) -> (..., 3)``, m/s (called with r of shape (3,)).
    r_0 : array_like, shape (3,)
        Starting point, m, at s = s[0].
    s : array_like, shape (n,)
        Parameter values, strictly increasing, n ≥ 1 (s for a steady flow).
    t : float, optional
        The frozen time, s (a scalar; default 0).
    rtol : float, optional
        Relative tolerance of the integration, in [``STREAMLINE_MIN_RTOL``, 1) (default
        1e-12); the absolute tolerance is rtol (1 + |r_0|∞).

    Returns
    -------
    points : ndarray, shape (n, 3)
        r(s_i), m; the first is r_0.

    Raises
    ------
    ShapeError
        If r_0 is not of shape (3,), s is not 1-D with at least one value, t or rtol is not
        a scalar, an input is not real numeric, or v returns another shape than (3,).
    OutOfDomainError
        If s is not strictly increasing, rtol lies outside [STREAMLINE_MIN_RTOL, 1), or the
        integration fails (scipy's message; e.g. a streamline that escapes to infinity).
    NonFiniteError
        If an input holds NaN or an infinity, or v returns a non-finite value.
    StepSizeError
        If the integration needs more than ``STREAMLINE_MAX_EVALS`` evaluations of v.
    ResultOverflowError
        If a point exceeds float64's range.

    Examples
    --------
    The streamlines of a rigid rotation about e_z are circles:

    >>> import numpy as np
    >>> v = rigid_velocity_field([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    >>> pts = streamline(v, [1.0, 0.0, 0.5], np.linspace(0.0, 3.0, 4))
    >>> bool(np.allclose(np.hypot(pts[:, 0], pts[:, 1]), 1.0, rtol=1e-10))
    True
    """
    r0 = as_float_array(r_0, "r_0", (3,))
    if r0.shape != (3,):
        raise ShapeError(f"r_0 must be one point of shape (3,); got {r0.shape}")
    ss = as_float_array(s, "s")
    if ss.ndim != 1 or ss.size < 1:
        raise ShapeError(f"s must be a 1-D array of parameter values; got shape {ss.shape}")
    if np.any(np.diff(ss) <= 0):
        raise OutOfDomainError("s must be strictly increasing")
    tt = _time(t)
    rtol = as_float_scalar(rtol, "rtol")
    if not STREAMLINE_MIN_RTOL <= rtol < 1.0:
        raise OutOfDomainError(
            f"rtol must lie in [{STREAMLINE_MIN_RTOL:.3g}, 1) (scipy's DOP853 floor 100 eps); "
            f"got {rtol!r}"
        )
    if ss.size == 1:
        return r0[None, :].copy()
    calls = [0]

    def rhs(_s: float, y: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        calls[0] += 1
        if calls[0] > STREAMLINE_MAX_EVALS:
            raise StepSizeError(
                f"streamline: more than {STREAMLINE_MAX_EVALS} evaluations of v over "
                f"s = [{float(ss[0])!r}, {float(ss[-1])!r}] at rtol = {rtol!r}; "
                "shorten s or loosen rtol"
            )
        return _call(v, y, tt, "v", vector=True)

    sol = solve_ivp(
        rhs,
        (ss[0], ss[-1]),
        r0,
        method="DOP853",
        t_eval=ss,
        rtol=rtol,
        atol=rtol * (1.0 + np.abs(r0).max()),
    )
    if not sol.success:  # pragma: no cover - scipy reports why
        raise OutOfDomainError(f"streamline integration failed: {sol.message}")
    points: npt.NDArray[np.float64] = sol.y.T  # scipy ships no types
    return points


streamline = finite_result(streamline)


def _area_ratio(area_ratio: float) -> float:
    aa = as_float_array(area_ratio, "area_ratio")
    if aa.shape != ():
        raise ShapeError(f"area_ratio must be a scalar; got shape {aa.shape}")
    a = float(aa)
    if not 0.0 <= a < 1.0:
        raise OutOfDomainError(
            f"area_ratio = (hole area)/(surface area) must lie in [0, 1); got {area_ratio!r}"
        )
    return a


def _root(x: npt.NDArray[np.float64], c: float, e: int) -> npt.NDArray[np.float64]:
    """√(x c 2**e) for x ≥ 0, a float c > 0 and an integer e: x c formed on the mantissas and
    the power of two halved exactly, so a product beyond float64 (2 g h = 2e600) or below its
    normal range (1e-600) on the way to an ordinary root rounds as the root of one in range."""
    fx, ex = np.frexp(x)
    fc, ec = math.frexp(c)
    k, odd = np.divmod(ex + (ec + e), 2)
    root: npt.NDArray[np.float64] = np.ldexp(np.sqrt(np.ldexp(fx * fc, odd)), k)
    return root


def torricelli_speed(
    h: npt.ArrayLike, *, g: float, area_ratio: float = 0.0
) -> npt.NDArray[np.float64]:
    """Outflow speed u from a small hole at depth ``h`` (Example 8.1, 8.37).

    Domain: h ≥ 0, a scalar area_ratio in [0, 1) (else OutOfDomainError), g > 0 (else
    NonPositiveParameterError); a result beyond float64 raises ResultOverflowError.

    u = √(2 g h) with the book's assumption of a still surface (``area_ratio = 0``);
    u = √(2 g h / (1 − a²)) when the surface sinks with speed a u (continuity),
    a = ``area_ratio``.  The product 2 g h is formed on the mantissas with its power of two
    apart (any magnitudes: u(1e300, g=1e300) = 1.4e300, u(1e-300, g=1e-300) = 1.4e-300).

    Parameters
    ----------
    h : array_like, shape (...)
        Depth of the hole below the free surface, m (≥ 0).
    g : float
        Magnitude of gravity, m/s² (> 0).
    area_ratio : float, optional
        a = (hole area)/(surface area), in [0, 1) (default 0: the book's still surface).

    Returns
    -------
    u : ndarray, shape (...)
        Outflow speed, m/s.

    Raises
    ------
    OutOfDomainError
        If h < 0 or area_ratio lies outside [0, 1).
    NonPositiveParameterError
        If g is ≤ 0.
    ShapeError
        If g or area_ratio is not a scalar, an input is not real numeric, or the inputs do
        not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    >>> round(float(torricelli_speed(5.0, g=9.8)), 12)
    9.899494936612
    """
    hh = as_float_array(h, "h")
    if np.any(hh < 0):
        raise OutOfDomainError(f"the depth h must be ≥ 0; got {h!r}")
    g_mag = _positive(g, "g")
    a = _area_ratio(area_ratio)
    f_g, e_g = math.frexp(g_mag)
    return _root(hh, f_g / ((1.0 - a) * (1.0 + a)), e_g + 1)


torricelli_speed = finite_result(torricelli_speed)


def drain_time(h_0: npt.ArrayLike, *, g: float, area_ratio: float) -> npt.NDArray[np.float64]:
    """Time for a prismatic tank to empty through a small hole in its bottom.

    Quasi-steady Torricelli outflow: T = √(2 h0 (1 − a²)/g) / a, taken as the root of
    2 h0 (1 − a)(1 + a)/(g a²) formed on the mantissas with its power of two apart (any
    magnitudes: T(1e300, g=1e-300, a=0.5) = 2.4e300, T(1e-300, g=1e300) = 1.2e-300).

    Domain: h_0 ≥ 0, a scalar area_ratio in (0, 1) (0: the tank never drains; else
    OutOfDomainError), g > 0 (else NonPositiveParameterError); a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    h_0 : array_like, shape (...)
        Initial level above the hole, m (≥ 0).
    g : float
        Magnitude of gravity, m/s² (> 0).
    area_ratio : float
        a = (hole area)/(tank cross-section), in (0, 1).

    Returns
    -------
    T : ndarray, shape (...)
        Drain time, s.

    Raises
    ------
    OutOfDomainError
        If h_0 < 0 or area_ratio lies outside (0, 1).
    NonPositiveParameterError
        If g is ≤ 0.
    ShapeError
        If g or area_ratio is not a scalar, an input is not real numeric, or the inputs do
        not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    The level falls as (T − t)², so a quarter of it is left at T/2:

    >>> T = drain_time(2.0, g=9.8, area_ratio=0.01)
    >>> round(float(tank_level(T / 2, h_0=2.0, g=9.8, area_ratio=0.01)), 12)
    0.5
    """
    hh = as_float_array(h_0, "h_0")
    if np.any(hh < 0):
        raise OutOfDomainError(f"the initial level h_0 must be ≥ 0; got {h_0!r}")
    g_mag = _positive(g, "g")
    a = _area_ratio(area_ratio)
    if a == 0.0:
        raise OutOfDomainError("area_ratio = 0 (no hole): the tank never drains")
    f_g, e_g = math.frexp(g_mag)
    f_a, e_a = math.frexp(a)
    return _root(hh, (1.0 - a) * (1.0 + a) / (f_g * (f_a * f_a)), 1 - e_g - 2 * e_a)


drain_time = finite_result(drain_time)


def tank_level(
    t: npt.ArrayLike, *, h_0: npt.ArrayLike, g: float, area_ratio: float
) -> npt.NDArray[np.float64]:
    """Liquid level above a small hole in the bottom of a prismatic tank at times ``t``.

    Domain: t ≥ 0, h_0 ≥ 0, a scalar area_ratio in (0, 1) (else OutOfDomainError), g > 0 (else
    NonPositiveParameterError); after the drain time the level stays 0; a result beyond float64
    raises ResultOverflowError.

    With Torricelli's outflow u(h) (:func:`torricelli_speed`) and continuity
    A dh/dt = −a u, the level falls as h(t) = (√h0 − c t)², c = a √(g/(2(1 − a²))),
    written as h0 ((T − t)/T)² with the drain time T = √h0/c (no c² = a² g/(2(1 − a²)),
    which underflows for a tiny hole: a = 1e-200 gave h(0) = 0); the empty tank stays empty
    (h = 0 for t ≥ T).  Times must be ≥ 0.

    Parameters
    ----------
    t : array_like, shape (...)
        Times since the hole was opened, s (≥ 0).
    h_0 : array_like, shape (...)
        Initial level above the hole, m (≥ 0).
    g : float
        Magnitude of gravity, m/s² (> 0).
    area_ratio : float
        a = (hole area)/(tank cross-section), in (0, 1).

    Returns
    -------
    h : ndarray, shape (...)
        Level at t, m, broadcast over t and h_0 (0 once the tank is empty).

    Raises
    ------
    OutOfDomainError
        If t < 0, h_0 < 0 or area_ratio lies outside (0, 1).
    NonPositiveParameterError
        If g is ≤ 0.
    ShapeError
        If g or area_ratio is not a scalar, an input is not real numeric, or the inputs do
        not broadcast.
    NonFiniteError
        If an input holds NaN or an infinity.
    ResultOverflowError
        If the result exceeds float64's range.

    Examples
    --------
    Half the level is lost after T (1 − 1/√2):

    >>> import numpy as np
    >>> T = drain_time(1.0, g=9.8, area_ratio=0.02)
    >>> round(float(tank_level(T * (1 - 1 / np.sqrt(2)), h_0=1.0, g=9.8, area_ratio=0.02)), 12)
    0.5
    """
    tt = as_float_array(t, "t")
    if np.any(tt < 0):
        raise OutOfDomainError(f"times must be ≥ 0 (t = 0 is the start); got {t!r}")
    T = drain_time(h_0, g=g, area_ratio=area_ratio)
    # (T − t)/T in [0, 1]: T = 0 only for h0 = 0, where the level stays 0
    left = np.maximum(T - tt, 0.0) / np.where(T > 0.0, T, 1.0)
    level: npt.NDArray[np.float64] = as_float_array(h_0, "h_0") * left * left
    return level


tank_level = finite_result(tank_level)
