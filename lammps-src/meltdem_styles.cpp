#include "meltdem_styles.h"

#include "force.h"
#include "lammps.h"
#include "modify.h"

#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>

// The generated meltdem_style_*.h include every project style header. As in LAMMPS's
// modify.cpp: included plainly they declare the classes; included again with the
// *_CLASS macro set, each header's XStyle(name,Class) line expands to a statement, so
// both LAMMPS's "FixStyle(x,FixX);" and a line without the semicolon work.
#include "meltdem_style_compute.h"
#include "meltdem_style_fix.h"
#include "meltdem_style_pair.h"

using namespace LAMMPS_NS;

namespace meltdem {

namespace {
template <typename T> Fix *fix_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> Compute *compute_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> Pair *pair_creator(LAMMPS *lmp)
{
  return new T(lmp);
}

// set once the driver has checked the library's version: before that, the instance's
// layout may not be the one these styles were compiled for
bool registration_armed = false;

// calls visit(kind, name, creator-inserting lambda) for every project style
template <typename Visit> void for_each_style(Visit &&visit)
{
#define FIX_CLASS
#define FixStyle(key, Class) visit("fix", #key, [](LAMMPS *l) { (*l->modify->fix_map)[#key] = &fix_creator<Class>; });
#include "meltdem_style_fix.h"
#undef FixStyle
#undef FIX_CLASS
#define COMPUTE_CLASS
#define ComputeStyle(key, Class)                                                                                       \
  visit("compute", #key, [](LAMMPS *l) { (*l->modify->compute_map)[#key] = &compute_creator<Class>; });
#include "meltdem_style_compute.h"
#undef ComputeStyle
#undef COMPUTE_CLASS
#define PAIR_CLASS
#define PairStyle(key, Class)                                                                                          \
  visit("pair", #key, [](LAMMPS *l) { (*l->force->pair_map)[#key] = &pair_creator<Class>; });
#include "meltdem_style_pair.h"
#undef PairStyle
#undef PAIR_CLASS
}
}  // namespace

void register_lammps_styles(LAMMPS *lmp)
{
  registration_armed = true;
  for_each_style([lmp](const char *, const char *, void (*insert)(LAMMPS *)) { insert(lmp); });
}

std::vector<std::string> registered_lammps_styles()
{
  std::vector<std::string> names;
  for_each_style([&names](const char *kind, const char *name, void (*)(LAMMPS *)) {
    names.push_back(std::string(kind) + " " + name);
  });
  return names;
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
