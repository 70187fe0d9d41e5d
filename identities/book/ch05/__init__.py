"""Chapter 5 of the book: asymmetric_top, examples, problems, spherical_top, symmetric_top."""
