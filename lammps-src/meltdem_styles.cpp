#include "meltdem_styles.h"

#include "force.h"
#include "lammps.h"
#include "modify.h"

// The generated meltdem_style_*.h include every project style header. As in LAMMPS's
// modify.cpp: included plainly they declare the classes; included again with the
// *_CLASS macro set, each header's XStyle(name,Class) line expands to a table entry.
#include "meltdem_style_compute.h"
#include "meltdem_style_fix.h"
#include "meltdem_style_pair.h"

namespace meltdem {

namespace {
using namespace LAMMPS_NS;

template <typename T> Fix *fix_creator(LAMMPS *lmp, int narg, char **arg) { return new T(lmp, narg, arg); }
template <typename T> Compute *compute_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> Pair *pair_creator(LAMMPS *lmp) { return new T(lmp); }

template <typename Creator> struct Entry { const char *name; Creator creator; };

// a leading null entry keeps the arrays valid when a kind has no style yet
const Entry<Modify::FixCreator> fix_styles[] = {
    {nullptr, nullptr},
#define FIX_CLASS
#define FixStyle(key, Class) {#key, &fix_creator<Class>},
#include "meltdem_style_fix.h"
#undef FixStyle
#undef FIX_CLASS
};
const Entry<Modify::ComputeCreator> compute_styles[] = {
    {nullptr, nullptr},
#define COMPUTE_CLASS
#define ComputeStyle(key, Class) {#key, &compute_creator<Class>},
#include "meltdem_style_compute.h"
#undef ComputeStyle
#undef COMPUTE_CLASS
};
const Entry<Force::PairCreator> pair_styles[] = {
    {nullptr, nullptr},
#define PAIR_CLASS
#define PairStyle(key, Class) {#key, &pair_creator<Class>},
#include "meltdem_style_pair.h"
#undef PairStyle
#undef PAIR_CLASS
};

template <typename Map, typename Table> void add_all(Map &map, const Table &table)
{
  for (const auto &e : table)
    if (e.name) map[e.name] = e.creator;
}
template <typename Table> void list_all(std::vector<std::string> &out, const char *kind, const Table &table)
{
  for (const auto &e : table)
    if (e.name) out.push_back(std::string(kind) + " " + e.name);
}
}  // namespace

void register_lammps_styles(LAMMPS *lmp)
{
  add_all(*lmp->modify->fix_map, fix_styles);
  add_all(*lmp->modify->compute_map, compute_styles);
  add_all(*lmp->force->pair_map, pair_styles);
}

std::vector<std::string> registered_lammps_styles()
{
  std::vector<std::string> names;
  list_all(names, "fix", fix_styles);
  list_all(names, "compute", compute_styles);
  list_all(names, "pair", pair_styles);
  return names;
}

}  // namespace meltdem
