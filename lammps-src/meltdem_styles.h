#pragma once
// Registration of MeltDEM's LAMMPS styles into a running LAMMPS instance.
// Debian's LAMMPS (bookworm and trixie) has no PLUGIN package, so meltdem-lmp and meltdemFoam
// insert the creators into the style maps of Modify / Force directly, before the input is
// read; a LAMMPS built with PLUGIN loads the same styles from meltdemplugin.so instead.

namespace LAMMPS_NS {
class LAMMPS;
}

namespace meltdem {

void register_lammps_styles(LAMMPS_NS::LAMMPS *lmp);

}  // namespace meltdem
