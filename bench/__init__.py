"""What accuracy costs in time: the work-precision study behind ``bodycheck bench``
and ``docs/bench`` (:mod:`.workprecision`), measured against scipy in the same run.
Tooling, not a book check: it imports :mod:`mechanics` (and scipy), never
:mod:`identities`.  The pytest-benchmark benchmarks (``make bench``) live in
``tests/benchmarks/``.
"""
