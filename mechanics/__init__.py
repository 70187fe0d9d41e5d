"""bodycheck's numeric core: float64 numpy, vectorised over leading axes, no sympy.

Modules, one concept each:

- :mod:`mechanics.errors`: the specific ``ValueError`` subclasses raised on bad input.
- :mod:`mechanics.rotation`: rotation matrices, Euler angles, rotation vectors and
  quaternions (Essén ch. 2.2–2.4).
- :mod:`mechanics.kinematics`: angular velocity and the velocities of rigid-body
  points (Essén ch. 2.5–2.6).
- :mod:`mechanics.strategies` and :mod:`mechanics.testing`: public hypothesis
  strategies and assertions for anyone testing mechanics code (import them
  explicitly; they pull in hypothesis).
"""

__version__ = "0.1.0"
