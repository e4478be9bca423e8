// meltdemplugin.so: MeltDEM's LAMMPS styles for a LAMMPS built with the PLUGIN package,
// loaded by "plugin load meltdemplugin.so" or from a directory in LAMMPS_PLUGIN_PATH.
// The styles need the LAMMPS version they were compiled against; a plugin loaded into
// another version says so and registers nothing (its classes would not fit the library).
#include "lammps_style_table.h"
#include "lammps_version_guard.h"

#include "lammps.h"
#include "lammpsplugin.h"
#include "version.h"

#include <cstdio>
#include <mpi.h>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto *lammps = static_cast<LAMMPS *>(lmp);
  const std::string mismatch = meltdem::lammps_version_mismatch(lammps, LAMMPS_VERSION);
  if (!mismatch.empty()) {
    int me = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &me);
    if (me == 0) fprintf(stderr, "ERROR: meltdemplugin.so: %s\n", mismatch.c_str());
    return;
  }
  auto register_style = reinterpret_cast<lammpsplugin_regfunc>(regfunc);
  // LAMMPS keeps the info pointers for "plugin list": they live as long as the plugin
  static std::vector<std::string> infos;
  const auto &styles = meltdem::lammps_style_creators();
  if (infos.empty())
    for (const auto &style : styles) infos.push_back(std::string("MeltDEM ") + style.kind + " " + style.name);
  for (std::size_t k = 0; k < styles.size(); ++k) {
    const auto &style = styles[k];
    lammpsplugin_t plugin{};
    plugin.version = LAMMPS_VERSION;
    plugin.style = style.kind;
    plugin.name = style.name;
    plugin.info = infos[k].c_str();
    plugin.author = "MeltDEM developers";
    if (style.pair)
      plugin.creator.v1 = reinterpret_cast<lammpsplugin_factory1 *>(style.pair);
    else if (style.fix)
      plugin.creator.v2 = reinterpret_cast<lammpsplugin_factory2 *>(style.fix);
    else
      plugin.creator.v2 = reinterpret_cast<lammpsplugin_factory2 *>(style.compute);
    plugin.handle = handle;
    register_style(&plugin, lmp);
  }
}
