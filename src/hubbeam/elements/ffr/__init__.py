"""The floating frame of reference (FFR) beam of the paper's Sec. 3."""
