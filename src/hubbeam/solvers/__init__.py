"""Solvers: static equilibrium, modal analysis (and, later, generalized-alpha)."""
