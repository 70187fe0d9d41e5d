"""Chapter 2 of the book: examples, problems, rotations, velocity."""
