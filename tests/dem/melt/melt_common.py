"""Helpers of the fix powder/melt tests: run meltdem-lmp on an input text, read thermo."""
import os
import sys

sys.path.insert(0, os.path.join(os.environ["MELTDEM_SOURCE_DIR"], "tests", "support"))
from meltdem_report import check_absolute, check_at_most, check_relative, report  # noqa: E402,F401
from lammps_run import LMP, check_errors, printed_value as value, run, thermo_rows as thermo  # noqa: E402,F401


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
