"""Chapter 6 of the book: examples, impulse, problems, restitution."""
