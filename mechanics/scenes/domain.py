"""The domain of a scene file's numbers: the magnitudes at which the engine's float64
arithmetic stays finite and within its stated eps.

Conventions
-----------
- **Magnitudes.**  Every number of a scene (a length, a mass, a speed, a time, a
  stiffness, ...) has magnitude at most 2⁸⁰ ≈ 1.2e24 in SI units.  Derivation: the
  quantities a run reports are products of at most six of the scene's numbers (the
  angular momentum about a point, r × m v, with r ~ g t² and v ~ g t, is of degree 6 in
  g, t and m), and the engine forms their squares (norms, energies of momenta):
  products of at most 12.  With every factor at most 2⁸⁰, such a product is at most
  2⁹⁶⁰, below float64's largest 2¹⁰²⁴ with 2⁶⁴ to spare for the numeric constants, so no
  intermediate overflows.  Small magnitudes, subnormals included, are accepted: they
  cannot overflow, and a quantity made of them alone that underflows below 2⁻¹⁰²² loses
  only digits below the self-checks' absolute floor of 1e-300.
- **Angles** (radians) have |θ| ≤ 2¹⁰: an angle carries the rounding eps·|θ| as an
  absolute error, which stays within the conserved quantities' 2¹⁰ eps
  (:data:`mechanics.scenes.result.CONSERVED_RTOL`).
- **Tolerances.** ``rtol`` lies in [100 eps, 1e-3] (DOP853 cannot hold a tighter relative
  tolerance: scipy's floor); ``atol`` in (0, 1e-3].
- A value outside its domain is refused with the field, the value and the domain.
"""

from __future__ import annotations

import math
from typing import Any

from .errors import SceneError
from .trajectory import EPS

__all__ = [
    "ANGLE_MAX",
    "MAGNITUDE_MAX",
    "RTOL_MIN",
    "check_angle",
    "check_magnitude",
    "domain_of",
]

#: the largest magnitude of a scene's number (see the Conventions)
MAGNITUDE_MAX = 2.0**80
#: the largest |angle| in radians
ANGLE_MAX = 2.0**10
#: the smallest rtol: DOP853's floor (scipy's ``100 * EPS``)
RTOL_MIN = 100 * EPS


def domain_of(unit: str, kind: str = "number") -> str:
    """The domain of a number with this SI unit and field kind, in words.

    For the reference of the scene format; ``abs(x)``, not bars, so that it sits in a
    Markdown table.  An angle (unit ``"rad"``) has abs(x) ≤ 2¹⁰ whatever its kind; any
    other number has magnitude at most 2⁸⁰ (see the Conventions).

    Parameters
    ----------
    unit : str
        The field's SI unit (``"m"``, ``"kg"``, ``"rad"``, ...; ``""`` for a pure number).
    kind : str, optional
        The field's kind in the schema: ``"positive"``, ``"nonnegative"`` or any other
        (default ``"number"``: a signed number).

    Returns
    -------
    str
        The domain in words, e.g. ``"0 < x ≤ 2⁸⁰"``.

    Examples
    --------
    The words match the bounds the checks apply:

    >>> domain_of("kg", "positive"), MAGNITUDE_MAX == 2.0**80
    ('0 < x ≤ 2⁸⁰', True)
    >>> domain_of("rad", "positive"), ANGLE_MAX == 2.0**10
    ('abs(x) ≤ 2¹⁰', True)
    """
    if unit == "rad":
        return "abs(x) ≤ 2¹⁰"
    if kind == "positive":
        return "0 < x ≤ 2⁸⁰"
    if kind == "nonnegative":
        return "0 ≤ x ≤ 2⁸⁰"
    return "abs(x) ≤ 2⁸⁰"


def check_magnitude(src: str, where: str, x: float) -> float:
    """``x`` if its magnitude is at most 2⁸⁰; else a SceneError.

    Domain: abs(x) ≤ 2⁸⁰ (:data:`MAGNITUDE_MAX`; else SceneError): the bound under which the
    engine's float64 arithmetic stays finite (see the Conventions).

    Parameters
    ----------
    src : str
        The scene's source (its file name), named by the error.
    where : str
        The field, e.g. ``"bodies[0].mass"``, named by the error.
    x : float
        The number, in SI units (a finite float: the parser has checked it).

    Returns
    -------
    float
        ``x`` itself.

    Raises
    ------
    SceneError
        If abs(x) > 2⁸⁰, or ``x`` is NaN (naming ``src``, ``where`` and the value).

    Examples
    --------
    The largest magnitude passes, the next float above it does not:

    >>> check_magnitude("s.toml", "bodies[0].mass", -MAGNITUDE_MAX) == -(2.0**80)
    True
    >>> check_magnitude("s.toml", "bodies[0].mass", math.nextafter(MAGNITUDE_MAX, math.inf))
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: s.toml: bodies[0].mass: 1.2089258196146294e+24 is too ...
    """
    if not abs(x) <= MAGNITUDE_MAX:
        raise SceneError(
            src,
            where,
            f"{x!r} is too large: a scene's numbers have magnitude at most 2⁸⁰ ≈ "
            f"{MAGNITUDE_MAX:.2g} (SI), where the engine's float64 arithmetic stays finite; "
            "choose units that bring it into range",
        )
    return x


def check_angle(src: str, where: str, x: float) -> float:
    """``x`` if |x| ≤ 2¹⁰ rad; else a SceneError.

    Domain: |x| ≤ 2¹⁰ rad (:data:`ANGLE_MAX`; else SceneError): an angle's rounding
    eps·|x| stays within the conserved quantities' 2¹⁰ eps (see the Conventions).

    Parameters
    ----------
    src : str
        The scene's source (its file name), named by the error.
    where : str
        The field, e.g. ``"bodies[0].initial.theta"``, named by the error.
    x : float
        The angle, rad (a finite float: the parser has checked it).

    Returns
    -------
    float
        ``x`` itself.

    Raises
    ------
    SceneError
        If |x| > 2¹⁰ rad, or ``x`` is NaN (naming ``src``, ``where`` and the value).

    Examples
    --------
    >>> check_angle("s.toml", "theta", -1024.0) == -ANGLE_MAX
    True
    >>> check_angle("s.toml", "theta", 1025.0)
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: s.toml: theta: 1025.0 rad is beyond the angles' domain ...
    """
    if not abs(x) <= ANGLE_MAX:
        raise SceneError(
            src,
            where,
            f"{x!r} rad is beyond the angles' domain |θ| ≤ 2¹⁰ = {ANGLE_MAX:g} rad (an "
            "angle's rounding eps·|θ| must stay within the conserved quantities' 2¹⁰ eps); "
            "reduce it modulo 2π",
        )
    return x


def check_number(src: str, where: str, x: float, unit: str) -> float:
    """A scene's number against the domain of its unit."""
    if unit == "rad":
        return check_angle(src, where, x)
    return check_magnitude(src, where, x)


def check_value(src: str, where: str, v: Any, unit: str) -> Any:
    """A number or a vector of numbers (already parsed as finite floats) in its domain."""
    if isinstance(v, list):
        return [check_value(src, f"{where}[{i}]", x, unit) for i, x in enumerate(v)]
    if isinstance(v, float) and math.isfinite(v):
        return check_number(src, where, v, unit)
    return v
