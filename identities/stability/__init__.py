"""The library's hard cases against an mpmath oracle (catalogue checks of kind
``stability``): :mod:`.rotation`.  Imports :mod:`mechanics` and
:mod:`identities.verify`, never the command line.
"""
