"""The floating-point constants and error-free transformations, once (issue 35).

Every module of :mod:`mechanics` that needs float64's machine epsilon or an exact
sum or product of two floats takes it from here; the tests' tolerances, named multiples
of :data:`EPS`, take it from here too.

- :data:`EPS`: float64's machine epsilon, 2⁻⁵² (the gap from 1 to the next float).
- :func:`two_sum`: s + e = a + b exactly, s = fl(a + b) (Knuth's TwoSum; any order of
  magnitude, no branch: 6 operations, elementwise on arrays).
- :func:`fast_two_sum`: the same in 3 operations where |a| ≥ |b| or a = 0 (Dekker).
- :func:`split`: a = hi + lo exactly, hi with 26 significant bits (Veltkamp's
  splitting with :data:`SPLITTER` = 2²⁷ + 1; |a| < 2⁹⁹⁶, else the product overflows).
- :func:`two_prod`: p + e = a b exactly, p = fl(a b) (Dekker's product from two splits;
  |a|, |b| < 2⁹⁹⁶ and no underflow of e, which the callers ensure by scaling).

Each is written operation for operation as the textbook forms (Ogita, Rump and Oishi,
"Accurate sum and dot product", SIAM J. Sci. Comput. 26, 2005, Algorithms 3.1–3.3), so
a caller's result is the same bit for bit as before these moved here.
"""

from __future__ import annotations

import numpy as np

__all__ = ["EPS", "SPLITTER", "fast_two_sum", "split", "two_prod", "two_sum"]

#: float64's machine epsilon, 2⁻⁵²
EPS = float(np.finfo(np.float64).eps)
#: Veltkamp's splitter for float64: 2²⁷ + 1
SPLITTER = 2.0**27 + 1.0


def two_sum(a, b):
    """(s, e) with s = fl(a + b) and s + e = a + b exactly (Knuth)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def fast_two_sum(a, b):
    """(s, e) with s = fl(a + b) and s + e = a + b exactly, for |a| ≥ |b| or a = 0
    (Dekker)."""
    s = a + b
    return s, b - (s - a)


def split(a):
    """(hi, lo) with a = hi + lo exactly and hi of 26 significant bits (Veltkamp;
    |a| < 2⁹⁹⁶)."""
    c = SPLITTER * a
    hi = c - (c - a)
    return hi, a - hi


def two_prod(a, b):
    """(p, e) with p = fl(a b) and p + e = a b exactly (Dekker; |a|, |b| < 2⁹⁹⁶)."""
    p = a * b
    ah, al = split(a)
    bh, bl = split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl
