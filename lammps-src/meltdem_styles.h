#pragma once
// Registration of MeltDEM's LAMMPS styles into a running LAMMPS instance.
// Debian's LAMMPS has no PLUGIN package, so the creators are inserted into the style maps
// of Modify / Force directly; this must happen before the input script is read.
#include <string>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace meltdem {

void register_lammps_styles(LAMMPS_NS::LAMMPS *lmp);

// "fix powder/insert", "pair granular/powder", ...: what register_lammps_styles adds
std::vector<std::string> registered_lammps_styles();

}  // namespace meltdem
