"""Chapter 7 of the book: examples, open_systems, problems."""
