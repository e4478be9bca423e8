"""Analyses of runs and their references: bead and melt-pool profiles, powder beds, the Hertz
contact, the Rosenthal solution."""
