#include "meltdem_styles.h"

#include "lammps_style_table.h"

#include "force.h"
#include "lammps.h"
#include "modify.h"

#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>

using namespace LAMMPS_NS;

namespace meltdem {

namespace {
// set once the driver has checked the library's version: before that, the instance's
// layout may not be the one these styles were compiled for
bool registration_armed = false;
}  // namespace

void register_lammps_styles(LAMMPS *lmp)
{
  registration_armed = true;
  for (const auto &style : lammps_style_creators()) {
    const std::string kind = style.kind;
    if (kind == "fix")
      (*lmp->modify->fix_map)[style.name] = style.fix;
    else if (kind == "compute")
      (*lmp->modify->compute_map)[style.name] = style.compute;
    else if (kind == "pair")
      (*lmp->force->pair_map)[style.name] = style.pair;
  }
}

}  // namespace meltdem

// The input command "clear" destroys Modify and Force and builds fresh ones from the
// library's compiled-in style tables, which forgets the project styles. Input::clear()
// ends with LAMMPS::post_create(), called through the PLT, so this definition in the
// executable interposes the library's: it runs the original, then registers again.
void LAMMPS_NS::LAMMPS::post_create()
{
  using PostCreate = void (*)(LAMMPS *);
  static const auto original = reinterpret_cast<PostCreate>(dlsym(RTLD_NEXT, "_ZN9LAMMPS_NS6LAMMPS11post_createEv"));
  if (!original) {
    fprintf(stderr, "ERROR: meltdem: LAMMPS::post_create not found in liblammps\n");
    abort();
  }
  original(this);
  if (meltdem::registration_armed) meltdem::register_lammps_styles(this);
}
