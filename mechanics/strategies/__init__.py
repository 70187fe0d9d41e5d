"""Public hypothesis strategies, valid by construction, with the hard regimes reachable.

One submodule per concept of :mod:`mechanics`, all re-exported here, so that
``from mechanics import strategies as ms`` gives every strategy:

- :mod:`mechanics.strategies.rotation`: unit vectors, angles, rotation vectors,
  Euler angles, quaternions, rotation matrices.
- :mod:`mechanics.strategies.particles`: masses and particle systems.
- :mod:`mechanics.strategies.inertia`: inertia tensors and rigid bodies.
- :mod:`mechanics.strategies.impact`: contacts and restitution.
- :mod:`mechanics.strategies.batching`: stacks of independent draws, for the
  promise that every function broadcasts over leading axes.
- :mod:`mechanics.strategies.conformance`: rigid-body states an engine can step and
  random variants of the conformance battery's scenarios, with their exact references.

Each submodule states its regimes (``*_REGIMES``); importing this package imports
hypothesis, ``import mechanics`` does not.
"""

from __future__ import annotations

from . import batching, conformance, impact, inertia, particles, rotation
from .batching import *  # noqa: F403
from .conformance import *  # noqa: F403
from .impact import *  # noqa: F403
from .inertia import *  # noqa: F403
from .particles import *  # noqa: F403
from .rotation import *  # noqa: F403

__all__ = [
    *rotation.__all__,
    *particles.__all__,
    *inertia.__all__,
    *impact.__all__,
    *batching.__all__,
    *conformance.__all__,
]
