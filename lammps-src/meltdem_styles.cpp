#include "meltdem_styles.h"

#include "force.h"
#include "modify.h"
#include "lammps.h"

namespace meltdem {

namespace {
using namespace LAMMPS_NS;

template <typename T> Fix *fix_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> Pair *pair_creator(LAMMPS *lmp) { return new T(lmp); }

struct FixEntry { const char *name; Modify::FixCreator creator; };
struct PairEntry { const char *name; Force::PairCreator creator; };

// The project's styles; each new style adds one line here.
const FixEntry fix_styles[] = {
    {nullptr, nullptr},
};
const PairEntry pair_styles[] = {
    {nullptr, nullptr},
};
}  // namespace

void register_lammps_styles(LAMMPS *lmp)
{
  for (const auto &f : fix_styles)
    if (f.name) (*lmp->modify->fix_map)[f.name] = f.creator;
  for (const auto &p : pair_styles)
    if (p.name) (*lmp->force->pair_map)[p.name] = p.creator;
}

std::vector<std::string> registered_lammps_styles()
{
  std::vector<std::string> names;
  for (const auto &f : fix_styles)
    if (f.name) names.push_back(std::string("fix ") + f.name);
  for (const auto &p : pair_styles)
    if (p.name) names.push_back(std::string("pair ") + p.name);
  return names;
}

}  // namespace meltdem
