"""bodycheck's numeric core: float64 numpy, vectorised over leading axes, no sympy.

Modules, one concept each (Essén 1996, chapter in brackets):

- :mod:`mechanics.errors`: the specific ``ValueError`` subclasses raised on bad input.
- :mod:`mechanics.particles`: particle systems: mass, centre of mass, momentum,
  angular momentum about a required base point, their decompositions [1].
- :mod:`mechanics.rotation`: rotation matrices, Euler angles, rotation vectors and
  quaternions [2.2–2.4].
- :mod:`mechanics.kinematics`: angular velocity and the velocities of rigid-body
  points [2.5–2.6].
- :mod:`mechanics.energy`: kinetic energy, power and work, potential energies [3].
- :mod:`mechanics.inertia`: inertia tensors, homogeneous bodies, the parallel-axis
  theorem, principal axes, ``check_inertia`` [4.1–4.2].
- :mod:`mechanics.dynamics`: Euler's equations, fixed-axis rotation, the physical
  pendulum (exact period and motion), bearing reactions [4.3].
- :mod:`mechanics.elliptic`: Jacobi elliptic functions and elliptic integrals for
  every parameter m, with the complementary parameter near m = 1 [5].
- :mod:`mechanics.tops`: the spherical, free symmetric, heavy symmetric and free
  asymmetric tops in closed form; stability about the principal axes [5].
- :mod:`mechanics.impact`: direct and rigid-body impact with restitution [6].
- :mod:`mechanics.open_systems`: open systems, the rocket, mass-flow forces [7].
- :mod:`mechanics.fluids`: velocity fields, divergence, curl, material derivative,
  Euler's equation, Bernoulli, Torricelli [8].
- :mod:`mechanics.integrators`: time steppers with one interface, which report their
  work.
- :mod:`mechanics.scenes`: scenes that simulate only the effects they list.
- :mod:`mechanics.strategies` and :mod:`mechanics.testing`: public hypothesis
  strategies and assertions for anyone testing mechanics code (import them
  explicitly; they pull in hypothesis).
- :mod:`mechanics.pytest_plugin`: the pytest plugin (entry point ``bodycheck``): the
  ``bodycheck-*`` hypothesis profiles, the ``bodycheck_rng`` and ``eps_close`` fixtures.
"""

__version__ = "0.1.0"
