// meltdem-plugin-loader: a stock LAMMPS driver (as LAMMPS's main.cpp) that does what
// "plugin load FILE" does in a LAMMPS built with the PLUGIN package (PLUGIN/plugin.cpp:
// plugin_load and plugin_register for pair, fix and compute styles) before reading the
// input. Debian's LAMMPS lacks PLUGIN, so this is how meltdemplugin.so is tested there.
//     meltdem-plugin-loader PLUGIN.so [lmp arguments...]
// It links LAMMPS only, never MeltDEM's styles: every project style comes from the plugin.
#include "comm.h"
#include "force.h"
#include "input.h"
#include "lammps.h"
#include "lammpsplugin.h"
#include "modify.h"

#include <cstdio>
#include <cstring>
#include <dlfcn.h>
#include <mpi.h>
#include <string>

using namespace LAMMPS_NS;

namespace {
int registered = 0;

void register_plugin(lammpsplugin_t *plugin, void *ptr)
{
  auto *lmp = static_cast<LAMMPS *>(ptr);
  const std::string style = plugin->style;
  if (style == "pair")
    (*lmp->force->pair_map)[plugin->name] = (Force::PairCreator)plugin->creator.v1;
  else if (style == "fix")
    (*lmp->modify->fix_map)[plugin->name] = (Modify::FixCreator)plugin->creator.v2;
  else if (style == "compute")
    (*lmp->modify->compute_map)[plugin->name] = (Modify::ComputeCreator)plugin->creator.v2;
  else {
    fprintf(stderr, "ERROR: plugin style kind %s not handled by the loader\n", plugin->style);
    return;
  }
  if (plugin->handle == nullptr || std::strcmp(plugin->version, lmp->version) != 0)
    fprintf(stderr, "ERROR: plugin %s %s: no handle or version %s differs from %s\n", plugin->style, plugin->name,
            plugin->version, lmp->version);
  else
    ++registered;
}
}  // namespace

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  if (argc < 2) {
    fprintf(stderr, "usage: meltdem-plugin-loader PLUGIN.so [lmp arguments...]\n");
    MPI_Finalize();
    return 1;
  }
  const char *file = argv[1];
  argv[1] = argv[0];
  int status = 0;
  try {
    auto *lammps = new LAMMPS(argc - 1, argv + 1, MPI_COMM_WORLD);
    void *dso = dlopen(file, RTLD_NOW | RTLD_GLOBAL);
    void *init = dso ? dlsym(dso, "lammpsplugin_init") : nullptr;
    if (!init) {
      fprintf(stderr, "ERROR: loading %s: %s\n", file, dlerror());
      status = 1;
    } else {
      reinterpret_cast<lammpsplugin_initfunc>(init)(lammps, dso, reinterpret_cast<void *>(&register_plugin));
      if (lammps->comm->me == 0) printf("PLUGIN_STYLES %d\n", registered);
      lammps->input->file();
    }
    delete lammps;
  } catch (std::exception &e) {
    fprintf(stderr, "ERROR: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return status;
}
