"""Test helpers: the validation report every test writes into (report), running meltdem-lmp
(lammps_run), the meltdem command (cli), DEM references (dem)."""
