"""Chapter 3 of the book: examples, kinetic_energy, power, problems, work."""
