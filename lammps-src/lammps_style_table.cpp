#include "lammps_style_table.h"

// The generated meltdem_style_*.h include every project style header. As in LAMMPS's
// modify.cpp: included plainly they declare the classes; included again with the
// *_CLASS macro set, each header's XStyle(name,Class) line expands to a table entry, so
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

std::vector<LammpsStyleCreator> build_table()
{
  std::vector<LammpsStyleCreator> table;
#define FIX_CLASS
#define FixStyle(key, Class) table.push_back({"fix", #key, nullptr, &fix_creator<Class>, nullptr});
#include "meltdem_style_fix.h"
#undef FixStyle
#undef FIX_CLASS
#define COMPUTE_CLASS
#define ComputeStyle(key, Class) table.push_back({"compute", #key, nullptr, nullptr, &compute_creator<Class>});
#include "meltdem_style_compute.h"
#undef ComputeStyle
#undef COMPUTE_CLASS
#define PAIR_CLASS
#define PairStyle(key, Class) table.push_back({"pair", #key, &pair_creator<Class>, nullptr, nullptr});
#include "meltdem_style_pair.h"
#undef PairStyle
#undef PAIR_CLASS
  return table;
}
}  // namespace

const std::vector<LammpsStyleCreator> &lammps_style_creators()
{
  static const std::vector<LammpsStyleCreator> table = build_table();
  return table;
}

}  // namespace meltdem
