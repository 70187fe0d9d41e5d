"""How the splitting's rounding grows with the number of steps, plain and compensated
(issue 15, part 3).

The free asymmetric top of the study (J = (1, 2, 3), ω0 = (0.4, 0.2, 1.0), in the
splitting's axis order (J_mid, J_max, J_min)) is run by the order-8 splitting at
:data:`STEPS_PER_ROTATION` steps per rotation, where its truncation error is far below
rounding ((h ω)^8 ≈ 2e-18 for the energy): what is left is rounding.  For each decade
n = 1e4, 1e5, 1e6 of steps it reports the RMS of |E/E0 − 1| and of ||L|/|L0| − 1| over
the steps n/3.2 … n (in eps), and the state's error at the last step against
:class:`mechanics.tops.FreeAsymmetricTop` (whose own error there is ~1e-12: 4 eps per
unit of elliptic phase).  ``plain`` is the default splitting (|L| and R Rᵀ projected
every :data:`mechanics.integrators.PROJECT_EVERY` steps), ``compensated`` the turns
added by Kahan summation (``compensated=True``).

Run ``python -m bench.roundoff [--out DIR]`` (about 20 s); it prints a markdown table
and writes ``roundoff.md`` into DIR if given.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

from mechanics.integrators import free_rigid_body_splitting, rigid_body_parts
from mechanics.rotation import EPS
from mechanics.tops import FreeAsymmetricTop

__all__ = ["DECADES", "STEPS_PER_ROTATION", "main", "measure"]

STEPS_PER_ROTATION = 1000
#: step counts at the end of each window n/3.2 … n
DECADES = (10**4, 10**5, 10**6)
ORDER = 8
_J = np.array([1.0, 2.0, 3.0])
_W0 = np.array([0.4, 0.2, 1.0])
_PERM = np.eye(3)[[1, 2, 0]]  # to the axis order (J_mid, J_max, J_min), det +1


def measure(decades=DECADES) -> dict:
    """``{"plain": rows, "compensated": rows}``, a row per decade: ``n``, ``energy_eps``,
    ``norm_eps`` (RMS over the window, in eps), ``state_error`` (at step n); and
    ``time_s`` of each run."""
    Jp = _J[[1, 2, 0]]
    L0 = _PERM @ (_J * _W0)
    E0 = 0.5 * float(np.sum(L0 * L0 / Jp))
    n0 = float(np.linalg.norm(L0))
    rot = 2 * math.pi / float(np.linalg.norm(_W0))
    h = rot / STEPS_PER_ROTATION
    k = np.unique(np.round(np.geomspace(decades[0] / 3.2, decades[-1], 400)).astype(int))
    k = np.unique(np.concatenate([k, decades]))
    t = np.concatenate([[0.0], k * h])
    top = FreeAsymmetricTop(_J, _W0)
    out: dict = {"order": ORDER, "steps_per_rotation": STEPS_PER_ROTATION}
    for name, comp in (("plain", False), ("compensated", True)):
        t0 = time.perf_counter()
        sol = free_rigid_body_splitting(Jp, L0, _PERM, t, h, order=ORDER, compensated=comp)
        out[f"{name}_time_s"] = time.perf_counter() - t0
        L = sol.y[1:, :3]
        dE = (0.5 * np.sum(L * L / Jp, axis=1) / E0 - 1) / EPS
        dn = (np.linalg.norm(L, axis=1) / n0 - 1) / EPS
        rows = []
        for n in decades:
            m = (k > n / 3.2) & (k <= n)
            i = int(np.searchsorted(k, n))
            Lf, Rf = rigid_body_parts(sol.y[i + 1])
            Lf, Rf = _PERM.T @ Lf, _PERM.T @ Rf
            w, Rx = top.state(float(t[i + 1]))
            err = max(
                float(np.abs(Lf / _J - w).max()) / float(np.linalg.norm(_W0)),
                float(np.abs(Rf - Rx).max()),
            )
            rows.append(
                {
                    "n": int(n),
                    "energy_eps": float(np.sqrt(np.mean(dE[m] ** 2))),
                    "norm_eps": float(np.sqrt(np.mean(dn[m] ** 2))),
                    "state_error": err,
                }
            )
        out[name] = rows
    return out


def to_markdown(res: dict) -> str:
    lines = [
        "# Rounding of the splitting: plain and compensated",
        "",
        f"`python -m bench.roundoff` — order {res['order']}, {res['steps_per_rotation']} "
        "steps per rotation of the free top J = (1, 2, 3), ω0 = (0.4, 0.2, 1.0) "
        "(truncation far below rounding). RMS over steps n/3.2 … n, in eps; the state's "
        "error at step n against the exact solution.",
        "",
        "| steps n | energy, plain | energy, compensated | abs L, plain | abs L, compensated "
        "| state error, plain | state error, compensated |",
        "|---|---|---|---|---|---|---|",
    ]
    for p, c in zip(res["plain"], res["compensated"], strict=True):
        lines.append(
            f"| {p['n']:.0e} | {p['energy_eps']:.3g} | {c['energy_eps']:.3g} | "
            f"{p['norm_eps']:.3g} | {c['norm_eps']:.3g} | {p['state_error']:.2e} | "
            f"{c['state_error']:.2e} |"
        )
    first, last = res["plain"][0], res["plain"][-1]
    cf, cl = res["compensated"][0], res["compensated"][-1]
    decades = math.log10(last["n"] / first["n"])
    lines += [
        "",
        "Growth exponent of the energy rounding (log-log slope over the decades; 0.5 is "
        f"√n, 1 is n): plain {math.log10(last['energy_eps'] / first['energy_eps']) / decades:.2f}, "
        f"compensated {math.log10(cl['energy_eps'] / cf['energy_eps']) / decades:.2f}. "
        f"Run time plain {res['plain_time_s']:.1f} s, compensated "
        f"{res['compensated_time_s']:.1f} s.",
        "",
    ]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        prog="python -m bench.roundoff", description=__doc__.split("\n")[0]
    )
    ap.add_argument("--out", default=None, help="write roundoff.md into this directory")
    args = ap.parse_args(argv)
    md = to_markdown(measure())
    print(md)
    if args.out:
        Path(args.out).mkdir(parents=True, exist_ok=True)
        (Path(args.out) / "roundoff.md").write_text(md, encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
