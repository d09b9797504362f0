"""3D Euler-Bernoulli ANCF beam element with torsion (paper Sec. 2)."""
