"""The floating-point constants and error-free transformations, once (issue 35).

Every module of :mod:`mechanics` that needs float64's machine epsilon or an exact
sum or product of two floats takes it from here; the tests' tolerances, named multiples
of :data:`EPS`, take it from here too.

- :data:`EPS`: float64's machine epsilon, 2⁻⁵² (the gap from 1 to the next float).
- :func:`two_sum`: s + e = a + b exactly, s = fl(a + b) (Knuth's TwoSum; any order of
  magnitude, no branch: 6 operations, elementwise on arrays).
- :func:`fast_two_sum`: the same in 3 operations where |a| ≥ |b| or a = 0 (Dekker).
- :func:`split`: a = hi + lo exactly, hi with 26 significant bits (Veltkamp's
  splitting with :data:`SPLITTER` = 2²⁷ + 1; |a| < :data:`SPLIT_LIMIT` = 2⁹⁹⁶, else the
  product overflows).
- :func:`two_prod`: p + e = a b exactly, p = fl(a b) (Dekker's product from two splits;
  |a|, |b| < 2⁹⁹⁶ and no underflow of e, which the callers ensure by scaling).
- :func:`two_prod_or_zero` (arrays) and :func:`two_prod_or_zero_scalar` (floats): the same
  with e = 0 where a split overflows (|a| or |b| ≥ 2⁹⁹⁶), for callers that only refine a
  product that is already correctly rounded.
- Double-double helpers (a value is an unevaluated pair hi + lo, |lo| ≤ ulp(hi)/2, as a
  tuple): :func:`dd_add` (two pairs), :func:`dd_times` (float × pair), :func:`dd_mul`
  (pair × pair), :func:`dd_div` (float / pair), :func:`dd_add_float` (float + pair,
  rounded to float).  Operands scaled to magnitude ≤ 1 by the callers (Dekker's split).
- :func:`ulps`: |actual − exact| in units in the last place of float64 at the exact
  value, for tests and checks that measure a result against exact arithmetic.

Each is written operation for operation as the textbook forms (Ogita, Rump and Oishi,
"Accurate sum and dot product", SIAM J. Sci. Comput. 26, 2005, Algorithms 3.1–3.3), so
a caller's result is the same bit for bit as before these moved here.
"""

from __future__ import annotations

import math
from typing import Any, TypeAlias

import numpy as np
import numpy.typing as npt

__all__ = [
    "EPS",
    "SPLITTER",
    "SPLIT_LIMIT",
    "dd_add",
    "dd_add_float",
    "dd_div",
    "dd_mul",
    "dd_times",
    "fast_two_sum",
    "split",
    "two_prod",
    "two_prod_or_zero",
    "two_prod_or_zero_scalar",
    "two_sum",
    "ulps",
]

#: a float or an array of floats: every transformation here works elementwise on either
Floats: TypeAlias = float | npt.NDArray[np.float64]
#: a double-double (hi, lo)
Pair: TypeAlias = tuple[Floats, Floats]

#: float64's machine epsilon, 2⁻⁵²
EPS = float(np.finfo(np.float64).eps)
#: Veltkamp's splitter for float64: 2²⁷ + 1
SPLITTER = 2.0**27 + 1.0
#: the magnitude below which :func:`split` (a product with :data:`SPLITTER`) cannot
#: overflow: (2²⁷ + 1) 2⁹⁹⁶ < 2¹⁰²⁴; callers scale their operands below it
SPLIT_LIMIT = 2.0**996


def two_sum(a: Floats, b: Floats) -> Pair:
    """(s, e) with s = fl(a + b) and s + e = a + b exactly (Knuth)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def fast_two_sum(a: Floats, b: Floats) -> Pair:
    """(s, e) with s = fl(a + b) and s + e = a + b exactly, for |a| ≥ |b| or a = 0
    (Dekker)."""
    s = a + b
    return s, b - (s - a)


def split(a: Floats) -> Pair:
    """(hi, lo) with a = hi + lo exactly and hi of 26 significant bits (Veltkamp;
    |a| < 2⁹⁹⁶)."""
    c = SPLITTER * a
    hi = c - (c - a)
    return hi, a - hi


def two_prod(a: Floats, b: Floats) -> Pair:
    """(p, e) with p = fl(a b) and p + e = a b exactly (Dekker; |a|, |b| < 2⁹⁹⁶)."""
    p = a * b
    ah, al = split(a)
    bh, bl = split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


def two_prod_or_zero(a: Floats, b: Floats) -> Pair:
    """:func:`two_prod` elementwise with e = 0 where a split overflows (|a| or |b| ≥ 2⁹⁹⁶)."""
    with np.errstate(over="ignore", invalid="ignore"):
        p, e = two_prod(a, b)
    return p, np.where(np.isfinite(e), e, 0.0)


def two_prod_or_zero_scalar(a: float, b: float) -> tuple[float, float]:
    """:func:`two_prod_or_zero` of two Python floats (no array is built)."""
    p, e = two_prod(a, b)  # floats in, floats out (float() only narrows the type)
    return float(p), (float(e) if math.isfinite(e) else 0.0)


# ------------------------------------------------------------ double-double
# A value is an unevaluated sum hi + lo with |lo| <= ulp(hi)/2 (Dekker 1971, Knuth
# TAOCP 4.2.2).  The callers scale their operands to magnitude <= 1 by powers of two,
# so that Dekker's split cannot overflow.


def dd_add(ah: Floats, al: Floats, bh: Floats, bl: Floats) -> Pair:
    """(ah + al) + (bh + bl) as a double-double."""
    s, e = two_sum(ah, bh)
    e = e + (al + bl)
    return two_sum(s, e)


def dd_times(m: Floats, xh: Floats, xl: Floats) -> Pair:
    """m (xh + xl) as a double-double (m a float)."""
    p, e = two_prod(m, xh)
    return two_sum(p, e + m * xl)


def dd_mul(a: Pair, b: Pair) -> Pair:
    """a b of two double-doubles (pairs) as a double-double."""
    p, err = two_prod(a[0], b[0])
    err = err + (a[0] * b[1] + a[1] * b[0])
    return fast_two_sum(p, err)


def dd_div(a: Floats, b: Pair) -> Pair:
    """float a / double-double b, as a double-double."""
    q1 = a / b[0]
    p, pe = two_prod(q1, b[0])
    r = ((a - p) - pe) - q1 * b[1]
    return fast_two_sum(q1, r / b[0])


def dd_add_float(a: Floats, x: Pair) -> Floats:
    """float a + double-double x, rounded to float."""
    s, err = two_sum(a, x[0])
    return s + (err + x[1])


# ------------------------------------------------------------ measuring errors


def ulps(actual: float, exact: Any) -> float:
    """|actual − exact| in units in the last place of float64 at ``exact``.

    ``exact`` is an exact or high-precision number (:class:`fractions.Fraction`,
    ``mpmath.mpf``, a float) into whose type ``actual`` converts exactly; the unit is
    ``math.ulp(float(exact))`` (the smallest subnormal where ``exact`` is 0).

    >>> from fractions import Fraction
    >>> ulps(0.1, Fraction(1, 10))  # 0.1 is the float nearest 1/10: within half an ulp
    0.4
    >>> ulps(1.0 + EPS, Fraction(1))
    1.0
    """
    kind = type(exact)
    unit = kind(math.ulp(float(exact)))
    return float(abs(kind(float(actual)) - exact) / unit)
