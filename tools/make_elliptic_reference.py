"""Write ``tests/data/elliptic_reference.json``: elliptic functions and free tops, exact.

Run from the repository root (about two minutes; mpmath's Taylor ODE solver
dominates)::

    python tools/make_elliptic_reference.py

Deterministic: every input is pinned here (the random times come from
``random.Random(SEED)``), float64 inputs are stored as ``repr`` strings (they
round-trip exactly) and taken by mpmath as exact binary numbers, and the
values are computed at ``DPS`` = 50 significant digits (more where m = 1 − m1
needs more digits to be represented: the working precision is raised so that
1 − m1 is exact).  Values are stored as decimal strings of ``DIGITS`` digits.

Contents
--------
- ``ellipj``: sn, cn, dn, am at m ∈ {−1e10, −10, −1, −1e-15, 0, 1e-300, 0.5,
  1 − 1e-6, 1 − 1e-12, 1 − 1e-15, 1 − 1e-100 and 1 − 1e-300 (through m1), 1,
  1 + 1e-15, 1.5, 10, 1e10} and u from 1e-10 to 1e4 (both signs).  am is
  atan2(sn, cn) continued by the multiple of 2π nearest to π u/(2K).
- ``ellipk`` / ``ellipe`` at m ≤ 1 including m1 = 1e-300 … 1e-6.
- ``ellipf`` / ``ellippi`` at amplitudes within and beyond π/2, n < 1.
- ``free_top``: ω(t) and the attitude ^A R^O(t) of free asymmetric tops near
  (and on) the separatrix, by mpmath's Taylor-series ODE solver ``odefun`` on
  Euler's equations (4.47) and dR/dt = −[ω]× R at 40 digits: an independent
  route (no elliptic function, no formula of ``mechanics.tops``).
"""

from __future__ import annotations

import json
import random
import sys
from pathlib import Path

import mpmath

SEED = 20261122
DPS = 50
DIGITS = 40
OUT = Path(__file__).resolve().parent.parent / "tests" / "data" / "elliptic_reference.json"

# (m, m1) as floats; m1 is None where 1 − m is computed from the float m exactly
PARAMS = [
    (-1e10, None),
    (-10.0, None),
    (-1.0, None),
    (-1e-15, None),
    (0.0, None),
    (1e-300, None),
    (0.5, None),
    (1 - 1e-6, None),
    (1 - 1e-12, None),
    (1 - 1e-15, None),
    (1.0, 1e-100),
    (1.0, 1e-300),
    (1.0, 0.0),
    (1 + 1e-15, None),
    (1.5, None),
    (10.0, None),
    (1e10, None),
]
ARGS = [1e-10, 0.3, -1.7, 5.0, 20.0, -37.25, 200.5, 1e4 + 0.125]

TOPS = [
    # (J, omega_0, t_max, with attitude): near the separatrix from both sides and on it
    ((1.0, 2.0, 3.0), (1.0, 0.001, 0.5773502691896257), 20.0, True),
    ((1.0, 2.0, 3.0), (1.0, 1e-6, 0.5773502691896258), 20.0, False),
    ((1.0, 2.0, 3.0), (0.001, 1.0, 0.001), 20.0, True),
    ((3.0, 4.0, 6.0), (2.0, 0.5, 1.0), 20.0, False),
    ((3.0, 4.0, 6.0), (2.0, 0.5, 1.0 + 2**-40), 20.0, False),
    ((1.0, 2.0, 3.0), (0.4, 1.0, 0.9), 20.0, True),
]
EULER0 = (0.3, 1.1, -0.7)  # initial attitude R3(φ) R1(θ) R3(ψ) with (ψ, θ, φ)


def _s(x) -> str:
    return mpmath.nstr(x, DIGITS, min_fixed=1, max_fixed=0)


def _prec_for(m1: float) -> int:
    if m1 == 0 or abs(m1) >= 1e-20:
        return DPS
    return DPS + int(-mpmath.log10(abs(m1))) + 10


def _ellipj_case(u: float, m: float, m1: float | None) -> dict:
    m1v = 1.0 - m if m1 is None else m1
    with mpmath.workdps(_prec_for(m1v)):
        M = 1 - mpmath.mpf(m1v) if m1 is not None else mpmath.mpf(m)
        U = mpmath.mpf(u)
        sn, cn, dn = (mpmath.re(mpmath.ellipfun(f, U, m=M)) for f in ("sn", "cn", "dn"))
        if M > 1:
            am = mpmath.asin(sn)
        elif M == 1:
            am = mpmath.atan(mpmath.sinh(U))
        else:
            K = mpmath.ellipk(M)
            a = mpmath.atan2(sn, cn)
            trend = mpmath.pi * U / (2 * K)
            am = a + 2 * mpmath.pi * mpmath.nint((trend - a) / (2 * mpmath.pi))
        return {
            "u": repr(u),
            "m": repr(m),
            "m1": None if m1 is None else repr(m1),
            "sn": _s(sn),
            "cn": _s(cn),
            "dn": _s(dn),
            "am": _s(am),
        }


def _complete_cases() -> list[dict]:
    out = []
    for m, m1 in [
        (-1e10, None),
        (-1.0, None),
        (0.0, None),
        (1e-300, None),
        (0.5, None),
        (1 - 1e-6, None),
        (1 - 1e-15, None),
        (1.0, 1e-15),
        (1.0, 1e-300),
    ]:
        m1v = 1.0 - m if m1 is None else m1
        with mpmath.workdps(_prec_for(m1v)):
            M = 1 - mpmath.mpf(m1v) if m1 is not None else mpmath.mpf(m)
            out.append(
                {
                    "m": repr(m),
                    "m1": None if m1 is None else repr(m1),
                    "K": _s(mpmath.ellipk(M)),
                    "E": _s(mpmath.ellipe(M)),
                }
            )
    return out


def _incomplete_cases() -> list[dict]:
    out = []
    phis = [0.3, 1.5, 1.5707963, -4.0, 7.0]
    for m, m1 in [(-10.0, None), (0.5, None), (1 - 1e-12, None), (1.0, 1e-300)]:
        for phi in phis:
            for n in (-3.0, 0.0, 0.5):
                m1v = 1.0 - m if m1 is None else m1
                with mpmath.workdps(_prec_for(m1v)):
                    M = 1 - mpmath.mpf(m1v) if m1 is not None else mpmath.mpf(m)
                    P = mpmath.mpf(phi)
                    out.append(
                        {
                            "phi": repr(phi),
                            "n": repr(n),
                            "m": repr(m),
                            "m1": None if m1 is None else repr(m1),
                            "F": _s(mpmath.ellipf(P, M)),
                            "Pi": _s(mpmath.ellippi(mpmath.mpf(n), P, M)),
                        }
                    )
    return out


def _R(psi, theta, phi):
    def r1(a):
        c, s = mpmath.cos(a), mpmath.sin(a)
        return mpmath.matrix([[1, 0, 0], [0, c, s], [0, -s, c]])

    def r3(a):
        c, s = mpmath.cos(a), mpmath.sin(a)
        return mpmath.matrix([[c, s, 0], [-s, c, 0], [0, 0, 1]])

    return r3(phi) * r1(theta) * r3(psi)


def _top_case(J, w0, t_max, with_R, rng) -> dict:
    with mpmath.workdps(40):
        Jm = [mpmath.mpf(x) for x in J]
        psi, theta, phi = (mpmath.mpf(x) for x in EULER0)
        R0 = _R(psi, theta, phi)

        def rhs(t, y):
            w = y[:3]
            dw = [
                (Jm[1] - Jm[2]) * w[1] * w[2] / Jm[0],
                (Jm[2] - Jm[0]) * w[2] * w[0] / Jm[1],
                (Jm[0] - Jm[1]) * w[0] * w[1] / Jm[2],
            ]
            if not with_R:
                return dw
            R = y[3:]
            S = [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]
            dR = [
                -sum(S[i][k] * R[3 * k + j] for k in range(3)) for i in range(3) for j in range(3)
            ]
            return dw + dR

        y0 = [mpmath.mpf(x) for x in w0]
        if with_R:
            y0 += [R0[i, j] for i in range(3) for j in range(3)]
        f = mpmath.odefun(rhs, 0, y0)
        times = sorted([rng.uniform(0, t_max) for _ in range(3)] + [t_max / 2, t_max])
        rows = []
        for t in times:
            y = f(mpmath.mpf(t))
            rows.append(
                {
                    "t": repr(t),
                    "omega": [_s(v) for v in y[:3]],
                    "R": [_s(v) for v in y[3:]] if with_R else None,
                }
            )
        return {
            "J": [repr(x) for x in J],
            "omega_0": [repr(x) for x in w0],
            "euler_0": [repr(x) for x in EULER0],
            "samples": rows,
        }


def build() -> dict:
    rng = random.Random(SEED)
    mpmath.mp.dps = DPS
    data = {
        "about": "mpmath reference values; see tools/make_elliptic_reference.py",
        "dps": DPS,
        "ellipj": [_ellipj_case(u, m, m1) for m, m1 in PARAMS for u in ARGS],
        "complete": _complete_cases(),
        "incomplete": _incomplete_cases(),
        "free_top": [_top_case(J, w, tm, wr, rng) for J, w, tm, wr in TOPS],
    }
    return data


def main() -> int:
    data = build()
    OUT.write_text(json.dumps(data, indent=1) + "\n")
    print(f"wrote {OUT} ({len(data['ellipj'])} ellipj cases, {len(data['free_top'])} tops)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
