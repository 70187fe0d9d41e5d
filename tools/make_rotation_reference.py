"""Write ``tests/data/rotation_hard_cases.json``: hard rotation inputs and their exact matrices.

Run from the repository root::

    python tools/make_rotation_reference.py

Deterministic: the general axes come from ``random.Random(SEED)``, everything
else is pinned, and the exact matrices are computed by mpmath at 50 digits, so
re-running the script gives the same file byte for byte
(``tests/stability/test_rotation_stability.py`` checks that it does).

Each case holds float64 inputs as ``repr`` strings (they round-trip exactly)
and the exact passive matrix ^A R^O of those inputs, taken as exact binary
numbers, as decimal strings of 48 significant digits.  The route here is
deliberately not the one of the test oracle in :mod:`identities.stability.rotation`
(Rodrigues and a product of basic matrices): rotation vectors and quaternions
go through the unit quaternion's quadratic form, Euler angles through the
written-out matrix (2.36), so that two independent computations must agree.

Cases: rotation angles 1e-300 … 1e-6 and within 1e-8 of π and exactly π about
general axes; half turns about coordinate axes; quaternions with w = 0 and
w = ±1e-17 and a vector part of 1e-300; Euler angles with θ at 0 and π and
within 1e-12 … 1e-6 of them, with non-zero outer angles.
"""

from __future__ import annotations

import json
import math
import random
import sys
from pathlib import Path

import mpmath

SEED = 20261122
DPS = 50
DIGITS = 48
OUT = Path(__file__).resolve().parent.parent / "tests" / "data" / "rotation_hard_cases.json"


def _axes(rng: random.Random, n: int) -> list[tuple[float, float, float]]:
    """n general unit axes: uniform on the sphere, all components away from 0."""
    out = []
    while len(out) < n:
        z = rng.uniform(-0.9, 0.9)
        az = rng.uniform(-math.pi, math.pi)
        rho = math.sqrt(1 - z * z)
        a = (rho * math.cos(az), rho * math.sin(az), z)
        if min(abs(c) for c in a) > 0.1:
            out.append(a)
    return out


def _quat_matrix(w, x, y, z) -> mpmath.matrix:
    """Exact ^A R^O of the quaternion (w, x, y, z), normalised exactly."""
    n2 = w * w + x * x + y * y + z * z
    w, x, y, z = (c / mpmath.sqrt(n2) for c in (w, x, y, z))
    # The passive matrix is the transpose of the active q-rotation matrix.
    return mpmath.matrix(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)],
            [2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)],
            [2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def exact_rotvec(v) -> mpmath.matrix:
    v = [mpmath.mpf(c) for c in v]
    phi = mpmath.sqrt(sum(c * c for c in v))
    if phi == 0:
        return mpmath.eye(3)
    s = mpmath.sin(phi / 2) / phi
    return _quat_matrix(mpmath.cos(phi / 2), *(c * s for c in v))


def exact_quat(q) -> mpmath.matrix:
    return _quat_matrix(*(mpmath.mpf(c) for c in q))


def exact_euler(psi, theta, phi) -> mpmath.matrix:
    """(2.36) written out: R3(φ) R1(θ) R3(ψ)."""
    cps, sps = mpmath.cos(psi), mpmath.sin(psi)
    cth, sth = mpmath.cos(theta), mpmath.sin(theta)
    cph, sph = mpmath.cos(phi), mpmath.sin(phi)
    return mpmath.matrix(
        [
            [cph * cps - sph * cth * sps, cph * sps + sph * cth * cps, sph * sth],
            [-sph * cps - cph * cth * sps, -sph * sps + cph * cth * cps, cph * sth],
            [sth * sps, -sth * cps, cth],
        ]
    )


def _strings(M: mpmath.matrix) -> list[list[str]]:
    return [
        [mpmath.nstr(M[i, j], DIGITS, min_fixed=1, max_fixed=0) for j in range(3)] for i in range(3)
    ]


def _floats(xs) -> list[str]:
    return [repr(float(x)) for x in xs]


def build() -> dict:
    """The reference data as a JSON-ready dict."""
    rng = random.Random(SEED)
    axes = _axes(rng, 4)
    with mpmath.workdps(DPS):
        rotvecs = []
        angles = [("tiny", t) for t in (1e-300, 3.7e-250, 1e-200, 1e-100, 1e-20, 1e-12, 1e-8, 1e-6)]
        angles += [("generic", t) for t in (0.5, 2.0)]
        angles += [("near-pi", math.pi - d) for d in (1e-8, 1e-10, 1e-12, 1e-14, math.ulp(math.pi))]
        angles += [("pi", math.pi)]
        for k, a in enumerate(axes):
            for regime, t in angles:
                v = [c * t for c in a]
                rotvecs.append({"id": f"{regime}-{t!r}-axis{k}", "rotvec": _floats(v)})
        for i in range(3):
            v = [0.0, 0.0, 0.0]
            v[i] = math.pi
            rotvecs.append({"id": f"pi-about-e{i + 1}", "rotvec": _floats(v)})
        for case in rotvecs:
            case["matrix"] = _strings(exact_rotvec([float(c) for c in case["rotvec"]]))

        quats = []
        for k, a in enumerate(axes[:2]):
            quats.append({"id": f"half-turn-axis{k}", "quat": _floats([0.0, *a])})
            quats.append(
                {"id": f"half-turn-negated-axis{k}", "quat": _floats([-0.0, *(-c for c in a)])}
            )
            for w in (1e-17, -1e-17):
                s = math.sqrt(1 - w * w)
                quats.append({"id": f"w={w!r}-axis{k}", "quat": _floats([w, *(s * c for c in a)])})
            quats.append(
                {"id": f"tiny-vector-axis{k}", "quat": _floats([1.0, *(1e-300 * c for c in a)])}
            )
        for case in quats:
            case["matrix"] = _strings(exact_quat([float(c) for c in case["quat"]]))

        eulers = []
        thetas = [0.0, 1e-12, 1e-9, 1e-6, math.pi, math.pi - 1e-12, math.pi - 1e-9, math.pi - 1e-6]
        outers = [(0.3, -1.2), (2.5, 2.9), (-3.0, 0.7), (1e-3, -2.2)]
        for th in thetas:
            for psi, phi in outers:
                eulers.append(
                    {
                        "id": f"theta={th!r},psi={psi!r},phi={phi!r}",
                        "euler": _floats([psi, th, phi]),
                    }
                )
        for case in eulers:
            case["matrix"] = _strings(exact_euler(*(mpmath.mpf(float(c)) for c in case["euler"])))
    return {
        "about": (
            "Exact passive matrices ^A R^O of float64 inputs (taken as exact binary "
            "numbers), mpmath at 50 digits; written by tools/make_rotation_reference.py"
        ),
        "seed": SEED,
        "dps": DPS,
        "rotvec": rotvecs,
        "quat": quats,
        "euler": eulers,
    }


def render(data: dict) -> str:
    return json.dumps(data, indent=1) + "\n"


def main(argv: list[str]) -> int:
    out = Path(argv[1]) if len(argv) > 1 else OUT
    out.write_text(render(build()), encoding="utf-8")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
