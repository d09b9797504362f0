"""Studies beyond the paper: Campbell diagram, sweeps, FFR applicability, identification."""
