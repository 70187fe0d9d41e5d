"""The built-in scenes against the book: :mod:`.compare` (the comparisons with the
book's numbers, which :mod:`mechanics` does not know) and :mod:`.checks` (the scenes as
catalogue checks).  Never imports the command line or matplotlib.
"""
