"""Chapter 1 of the book: angular_momentum, examples, momentum, problems."""
