"""Post-processing of results (signals), independent of how they were computed."""
