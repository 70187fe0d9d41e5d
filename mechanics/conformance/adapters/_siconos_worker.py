"""The Siconos side of :class:`mechanics.conformance.adapters.siconos.SiconosAdapter`:
run by the interpreter that has Siconos (Debian's ``python3`` with ``python3-siconos``),
not by bodycheck's, so it imports nothing from bodycheck.

Reads one JSON request on stdin, writes one JSON answer on stdout:

- request: ``bodies`` (mass, inertia (J1, J2, J3), shape kind and dims or null,
  position, velocity (space), quaternion (w, x, y, z; active, body to space), omega
  (body components)), ``gravity``, ``ground`` (normal, height, restitution, friction) or null,
  ``pairs`` ([i, j, e] of two spheres), ``step``, ``counts`` (the number of steps to
  each sample), ``theta`` (Moreau–Jean's), ``tolerance`` (the friction solver's).
- answer: ``q`` (per sample, per body: x, y, z, w, qx, qy, qz) and ``twist`` (v in
  space, Ω in body components), or ``error`` (one line).

``--version`` prints Siconos's version and exits (the adapter's probe).

Contacts: one ``ContactR`` (a 3-D contact relation of Siconos's mechanics component)
per sphere and per box corner with the ground, and per sphere pair, with Newton's
impact law and Coulomb friction (``NewtonImpactFrictionNSL(e, 0, mu, 3)``: the ground's
mu, zero between spheres), solved by
``FrictionContact(3)`` at the tolerance asked (Siconos's default, 1e-4, leaves a spurious
spin of 7e-4 rad/s on a box landing flat).  A ``ContactR`` holds its points in the
bodies' frames; for a plane or a sphere the contact point moves over the surface, so
the points are set again from the state before every step (what Siconos's own
collision managers do).  Moreau–Jean time stepping (``MoreauJeanOSI(theta)``) with
fixed steps.
"""

import json
import math
import os
import sys

# run as a script, its directory leads sys.path, and bodycheck's adapter module
# siconos.py there would shadow the siconos package
_HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:] = [p for p in sys.path if os.path.abspath(p or os.curdir) != _HERE]


def _rotation(w, x, y, z):
    """The active rotation (body to space) of the unit quaternion (w, x, y, z)."""
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ]


def _apply(R, v):
    return [sum(R[i][k] * v[k] for k in range(3)) for i in range(3)]


def _apply_t(R, v):
    return [sum(R[k][i] * v[k] for k in range(3)) for i in range(3)]


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b, strict=True))


def _corners(dims):
    a, b, c = dims
    return [[i * a, j * b, k * c] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)]


def run(req):
    import numpy as np
    import siconos.kernel as sk
    from siconos.mechanics.collision import ContactR

    bodies = req["bodies"]
    T = req["step"] * max(req["counts"])
    nsds = sk.NonSmoothDynamicalSystem(0.0, max(T, req["step"]))
    ds = []
    for b in bodies:
        q = list(b["position"]) + list(b["quaternion"])
        twist = list(b["velocity"]) + list(b["omega"])
        d = sk.NewtonEulerDS(q, twist, b["mass"], np.diag(b["inertia"]))
        g = req["gravity"]
        if any(g):
            d.setFExtPtr(np.array([b["mass"] * x for x in g], dtype=float))
        nsds.insertDynamicalSystem(d)
        ds.append(d)

    contacts = []  # (relation, body i, body j or None, how to set its points)
    ground = req["ground"]
    if ground is not None:
        n = [float(x) for x in ground["normal"]]
        for i, b in enumerate(bodies):
            shape = b["shape"]
            if shape is None:
                continue
            # a sphere: its point nearest the plane (None: found each step)
            points = [None] if shape["kind"] == "sphere" else _corners(shape["dims"])
            for p in points:
                r = ContactR()
                law = sk.NewtonImpactFrictionNSL(
                    ground["restitution"], 0.0, ground.get("friction", 0.0), 3
                )
                nsds.link(sk.Interaction(law, r), ds[i])
                contacts.append((r, ("ground", i, p, shape["dims"][0])))
    for i, j, e in req["pairs"]:
        r = ContactR()
        law = sk.NewtonImpactFrictionNSL(e, 0.0, 0.0, 3)
        nsds.link(sk.Interaction(law, r), ds[i], ds[j])
        radii = (bodies[i]["shape"]["dims"][0], bodies[j]["shape"]["dims"][0])
        contacts.append((r, ("pair", i, j, *radii)))

    def place():
        """Set every contact's points from the present state."""
        for r, how in contacts:
            if how[0] == "ground":
                _, i, p, radius = how
                q = list(ds[i].q())
                R = _rotation(*q[3:7])
                if p is None:  # sphere: its point nearest the plane, in body axes
                    p = _apply_t(R, [-radius * x for x in n])
                P = [q[k] + _apply(R, p)[k] for k in range(3)]
                gap = _dot(P, n) - ground["height"]
                on_plane = [P[k] - gap * n[k] for k in range(3)]
                r.updateContactPoints(
                    sk.SiconosVector(p), sk.SiconosVector(on_plane), sk.SiconosVector(n)
                )
            else:
                _, i, j, ri, rj = how
                qi, qj = list(ds[i].q()), list(ds[j].q())
                d = [qi[k] - qj[k] for k in range(3)]
                length = math.sqrt(_dot(d, d))
                u = [x / length for x in d]  # from j's centre towards i's
                Ri, Rj = _rotation(*qi[3:7]), _rotation(*qj[3:7])
                pi = _apply_t(Ri, [-ri * x for x in u])
                pj = _apply_t(Rj, [rj * x for x in u])
                r.updateContactPoints(
                    sk.SiconosVector(pi), sk.SiconosVector(pj), sk.SiconosVector(_apply_t(Rj, u))
                )

    place()
    osi = sk.MoreauJeanOSI(req["theta"])
    td = sk.TimeDiscretisation(0.0, req["step"])
    solver = sk.FrictionContact(3)
    solver.numericsSolverOptions().dparam[0] = req["tolerance"]
    sim = sk.TimeStepping(nsds, td, osi, solver)

    def state():
        return [list(d.q()) for d in ds], [list(d.twist()) for d in ds]

    out_q, out_tw = [], []
    done = 0
    for c in req["counts"]:
        while done < c:
            place()
            sim.computeOneStep()
            sim.nextStep()
            done += 1
        q, tw = state()
        out_q.append(q)
        out_tw.append(tw)
    return {"q": out_q, "twist": out_tw}


def main():
    if sys.argv[1:] == ["--version"]:
        import siconos

        print(getattr(siconos, "version", "unknown"))
        return 0
    req = json.load(sys.stdin)
    # Siconos's C++ writes its warnings (a friction solve that did not converge) to
    # file descriptor 1: while it runs, that descriptor is stderr, and the answer goes
    # to the original stdout alone
    sys.stdout.flush()
    answer_fd = os.dup(1)
    os.dup2(2, 1)
    try:
        ans = run(req)
    except Exception as exc:  # one line back to the adapter, which raises it
        ans = {"error": f"{type(exc).__name__}: {exc}"}
    finally:
        sys.stdout.flush()
        os.dup2(answer_fd, 1)
        os.close(answer_fd)
    json.dump(ans, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
