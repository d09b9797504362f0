"""Element formulations: kinematics, energies, mass and forces of one element type each."""
