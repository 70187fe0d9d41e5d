"""Chapter 4 of the book: dynamics, examples, inertia, problems."""
