"""bodycheck's verification layer (sympy): the catalogue, proofs and derivations.

Imports point down: ``identities`` uses :mod:`mechanics`, never the reverse.
"""
