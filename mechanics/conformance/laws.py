"""The laws a trajectory must keep, as one public check (issue 29, item 3): point it at
any engine's trajectory of a battery scenario, drawn or built in, and it names each law
that fails, with the book's equation.

- **Conservation**: every quantity the scenario's physics keeps
  (:func:`~.scenarios.invariant_names`: E, p, L about the point where it is conserved,
  L_z about a pivot's vertical, L₃, the horizontal or tangential momentum) drifts by no
  more than ``rtol`` of its scale, the scale taken from the exact motion.
- **Restitution**: a bouncing ball's successive apex heights fall by e² (the median
  over its rebounds; Newton's law (6.6): the rebound speed e v, the height e² h); a
  head-on impact's separation speed is e times the approach speed (6.6, 6.36–6.38).
- **Rotations**: every attitude is a rotation (R Rᵀ = I, det R = +1), by
  :func:`~.protocol.check_trajectory`, which raises rather than reports.

The conservation and rotation laws take the trajectory alone; restitution reads the
scenario's e.  No exact solution is needed for them (the scales excepted): they hold for
any scenario of a known kind.
"""

from __future__ import annotations

import numpy as np

from .protocol import Scenario, Trajectory, check_trajectory
from .scenarios import bounce_apexes, invariants, measure, reference

__all__ = ["LAW_EQUATIONS", "law_violations"]

#: the book's equation for each conserved quantity's law
LAW_EQUATIONS = {
    "E": "energy: no force does work (Chapter 3; the heavy top's 5.66)",
    "p": "the momentum principle with no external force (Chapter 1)",
    "L": "the angular momentum principle with no external moment (Chapter 1)",
    "L_z": "angular momentum about the pivot's vertical (5.55)",
    "L_3": "the spin's angular momentum L₃ = J₃ω₃ (5.53)",
    "p_horizontal": "horizontal momentum: gravity is vertical (Chapter 1)",
    "p_tangential": "tangential momentum: smooth impacts (6.6)",
}


def law_violations(s: Scenario, trajectory: Trajectory, *, rtol: float) -> list[str]:
    """One sentence per law the trajectory breaks by more than ``rtol``; empty when none.

    ``rtol`` is relative to the law's scale.  The trajectory is validated first
    (:func:`~.protocol.check_trajectory`: shapes, finite values, rotations).

    Parameters
    ----------
    s : Scenario
        A scenario of a known kind, built in or drawn.
    trajectory : Trajectory
        Any engine's trajectory of ``s``.
    rtol : float
        The tolerance, relative to each law's scale, finite, ≥ 0.

    Returns
    -------
    list of str
        One sentence per broken law, naming it and the book's equation
        (:data:`LAW_EQUATIONS`).

    Raises
    ------
    ValueError
        Where ``rtol`` is not a finite number ≥ 0.
    ConformanceError
        Where the trajectory breaks the protocol (:func:`~.protocol.check_trajectory`).
    UnknownScenarioError
        Where the scenario's kind is unknown.

    Examples
    --------
    The exact parabola keeps its laws; half its horizontal speed lost, it breaks two:

    >>> import dataclasses
    >>> from mechanics.conformance import get_scenario, reference
    >>> s = get_scenario("parabola")
    >>> tr = reference(s).trajectory
    >>> law_violations(s, tr, rtol=2**-40)
    []
    >>> v = tr.velocity.copy()
    >>> v[1:, :, 0] *= 0.5
    >>> slowed = dataclasses.replace(tr, velocity=v)
    >>> [law.split()[0] for law in law_violations(s, slowed, rtol=2**-10)]
    ['E', 'p_horizontal']
    """
    if not (isinstance(rtol, int | float) and np.isfinite(rtol) and rtol >= 0):
        raise ValueError(f"rtol must be a finite number >= 0; got {rtol!r}")
    tr = check_trajectory(s, trajectory)
    scales = {k: v[1] for k, v in invariants(s, reference(s).trajectory).items()}
    out = []
    for name, (q, _) in invariants(s, tr).items():
        q = np.asarray(q, dtype=float)
        drift = float(np.max(np.abs(q - q[0]))) / scales[name]
        if drift > rtol:
            law = LAW_EQUATIONS.get(name, name)
            out.append(
                f"{name} is not conserved: it drifts {drift:.3g} of its scale, more than "
                f"rtol {rtol:.3g} ({law})"
            )
    kind = s.extra.get("kind")
    if kind in ("bounce", "rest") and s.ground is not None:
        e = s.ground.restitution
        _, h = bounce_apexes(s, tr)
        h = h[h > 0]
        if h.size >= 2:  # the median over the rebounds: robust to one badly resolved
            e_m = float(np.median(np.sqrt(h[1:] / h[:-1])))
            if abs(e_m - e) > rtol * e:
                out.append(
                    f"the rebounds restitute e = {e_m:.3g} (the median of √(h_k+1/h_k) over "
                    f"{h.size - 1} rebound(s)), not the scenario's {e:.3g} (Newton's law of "
                    "restitution, 6.6)"
                )
    elif kind == "impact":
        e = s.pair_restitution[0][2]
        got = measure(s, tr)["restitution"]
        if isinstance(got, float) and abs(got - e) > rtol * max(e, rtol):
            out.append(
                f"the impact restitutes e = {got:.3g}, not the scenario's {e:.3g} (the "
                "separation speed is e times the approach speed, 6.6, 6.36-6.38)"
            )
    return out
