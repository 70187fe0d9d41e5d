"""The randomised invariants as catalogue checks of kind ``property``.

Each module states properties of one concept (impacts, rotations, inertia) as plain
functions that raise ``AssertionError`` when an invariant fails for the arguments they
are given, registers a catalogue check that runs each over a stated number of
hypothesis examples with the derivation's seed (:mod:`identities.verify.properties`),
with a deliberately wrong variant as its negative control, and is imported by the
theorem tests (``tests/theorems/``), which run the same functions under ``@given`` with
their pinned ``@example``s: one source for each invariant.
"""
