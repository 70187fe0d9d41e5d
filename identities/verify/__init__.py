"""The verification machinery: the registry of checks and the book's inventory
(:mod:`.catalogue`), proof procedures with their negative controls (:mod:`.proof`),
sympy helpers (:mod:`.symbolic`) and the rendering of CHECKS.md (:mod:`.render`).
It imports no chapter, no command line and no matplotlib: the book's checks import it.
"""
