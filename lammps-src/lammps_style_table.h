#pragma once
// The table of MeltDEM's LAMMPS styles: kind, name and creator of each, as LAMMPS's own
// style maps hold them. register_lammps_styles (meltdem-lmp, meltdemFoam) and the plugin
// (meltdemplugin.so, for a LAMMPS built with PLUGIN) both add the styles from it.
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
class Pair;
class Fix;
class Compute;
}  // namespace LAMMPS_NS

namespace meltdem {

struct LammpsStyleCreator {
  const char *kind;                                                   // "fix", "compute" or "pair"
  const char *name;                                                   // the style's name in an input script
  LAMMPS_NS::Pair *(*pair)(LAMMPS_NS::LAMMPS *);                      // set for kind "pair"
  LAMMPS_NS::Fix *(*fix)(LAMMPS_NS::LAMMPS *, int, char **);          // set for kind "fix"
  LAMMPS_NS::Compute *(*compute)(LAMMPS_NS::LAMMPS *, int, char **);  // set for kind "compute"
};

const std::vector<LammpsStyleCreator> &lammps_style_creators();

}  // namespace meltdem
