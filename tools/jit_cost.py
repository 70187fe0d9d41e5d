"""The cost of the compiled steppers' first call in a process (issue 15).

Usage::

    .venv/bin/python tools/jit_cost.py          # warm: numba's on-disk cache present
    .venv/bin/python tools/jit_cost.py --cold   # delete the cache first, then measure

Prints the import time of :mod:`mechanics.integrators` (numba is not imported by it),
then for each kernel (DOP853, RK4, the splitting; then DOP853 on a numba-compiled
right-hand side, issue 30, whose module compiles or loads its kernels all at once) the
first call (numba's import and the cache load or the compilation) and the second call.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def main() -> None:
    if "--cold" in sys.argv[1:]:
        for f in (ROOT / "mechanics").rglob("__pycache__/*.nb[ic]"):
            f.unlink()
    t0 = time.perf_counter()
    import numpy as np

    from mechanics.integrators import (
        free_rigid_body_rhs,
        free_rigid_body_splitting,
        integrate,
        rigid_body_state,
    )

    t1 = time.perf_counter()
    J = np.array([1.0, 2.0, 3.0])
    L0 = J * np.array([0.4, 0.2, 1.0])
    y0 = rigid_body_state(L0, np.eye(3))
    rhs = free_rigid_body_rhs(J)
    calls = {
        "dop853": lambda: integrate(rhs, y0, (0.0, 1.0), method="dop853", rtol=1e-10),
        "rk4": lambda: integrate(rhs, y0, (0.0, 1.0), method="rk4", h=0.1),
        "splitting": lambda: free_rigid_body_splitting(J, L0, np.eye(3), (0.0, 1.0), 0.1),
        "dop853, a compiled rhs": lambda: integrate(
            _decay(), np.ones(3), (0.0, 1.0), method="dop853", rtol=1e-10
        ),
    }
    print(f"import mechanics.integrators: {t1 - t0:.3f} s")
    for name, call in calls.items():
        a = time.perf_counter()
        call()
        b = time.perf_counter()
        call()
        c = time.perf_counter()
        print(f"{name}: first call {b - a:.3f} s, second {1e3 * (c - b):.3f} ms")


_DECAY = None


def _decay():
    """y' = −y compiled by numba (made on first use, so that numba's import is timed there)."""
    global _DECAY
    if _DECAY is None:
        from numba import njit

        _DECAY = njit(lambda t, y: -y)
    return _DECAY


if __name__ == "__main__":
    main()
