"""Chapter 8 of the book: fluids."""
