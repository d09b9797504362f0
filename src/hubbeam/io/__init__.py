"""Input and output: scenario files, result datasets."""
