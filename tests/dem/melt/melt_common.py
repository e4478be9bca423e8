"""Helpers of the fix powder/melt tests: run meltdem-lmp on an input text, read thermo."""


# a single particle in a large periodic box, SI units, radius changes allowed
HEADER = """units si
atom_style sphere 1
atom_modify map array
boundary p p p
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
create_box 1 box
comm_modify vel yes
neighbor 1e-4 bin
"""
