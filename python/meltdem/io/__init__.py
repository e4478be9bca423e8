"""Readers of what MeltDEM and its runs write (OpenFOAM dictionaries and fields, LAMMPS
inputs and dumps, the ledger and balances) and the VTK writers of the post-processing."""
