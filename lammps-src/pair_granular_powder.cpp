// pair granular with the exact e -> alpha map of meltdem::coupling (doc/pair_granular_powder.rst).
#include "pair_granular_powder.h"
#include "error.h"
#include "atom.h"
#include "force.h"
#include "update.h"
#include "modify.h"
#include "fix_powder_insert.h"
#include <mpi.h>
#include "meltdem/coupling/hertz_restitution.h"
#include <cstring>
#include <string>
#include <vector>
using namespace LAMMPS_NS;

// PairGranular keeps normal_coeffs private in this LAMMPS version; an explicit
// template instantiation may name private members (C++ [temp.explicit]), which lets
// the subclass set alpha without forking the stock style.
namespace {
template <typename Tag, typename Tag::type M> struct Rob {
  friend typename Tag::type get(Tag) { return M; }
};
struct NormalCoeffsTag {
  typedef double ***PairGranular::*type;
  friend type get(NormalCoeffsTag);
};
template struct Rob<NormalCoeffsTag, &PairGranular::normal_coeffs>;
}  // namespace

void PairGranularPowder::coeff(int narg, char **arg)
{
  // hertz/material E e nu ... damping tsuji|tsuji/alpha: find e and the damping form,
  // let the stock parser do the rest, then overwrite alpha with the exact value.
  int mode = 0;  // 0 none, 1 tsuji (exact e), 2 tsuji/alpha
  double value = 0.0;
  bool hertz = false;  // e depends on alpha alone only for a Hertz contact
  std::vector<std::string> copy(arg, arg + narg);
  for (int i = 2; i < narg; i++) {
    if ((copy[i] == "hertz/material" && i + 3 < narg) || (copy[i] == "hertz" && i + 2 < narg)) {
      value = utils::numeric(FLERR, arg[i + 2], false, lmp);
      hertz = true;
    }
    if ((copy[i] == "hertz/material" || copy[i] == "dmt" || copy[i] == "jkr") && i + 3 < narg) {
      // the material the contact law and fix powder/dt's contact time are computed from
      const double E = utils::numeric(FLERR, arg[i + 1], false, lmp);
      const double nu = utils::numeric(FLERR, arg[i + 3], false, lmp);
      if (!(E > 0.0)) error->all(FLERR, "Illegal pair_coeff command: {} Young's modulus E must be > 0", copy[i]);
      if (!(nu > -1.0 && nu <= 0.5))
        error->all(FLERR, "Illegal pair_coeff command: {} Poisson's ratio {} must lie in (-1,0.5]", copy[i], nu);
    }
    if (copy[i] == "hooke" || copy[i] == "dmt" || copy[i] == "jkr") hertz = false;
    if (copy[i] == "damping" && i + 1 < narg) {
      if (copy[i + 1] == "tsuji")
        mode = 1;
      else if (copy[i + 1] == "tsuji/alpha") {
        if (i + 2 >= narg) error->all(FLERR, "Illegal pair_coeff command: damping tsuji/alpha needs a value");
        mode = 2;
        value = utils::numeric(FLERR, arg[i + 2], false, lmp);
        if (value < 0.0) error->all(FLERR, "Illegal pair_coeff command: tsuji/alpha must be >= 0");
        copy[i + 1] = "tsuji";
        copy.erase(copy.begin() + i + 2);
      }
    }
  }
  if (mode == 1 && !hertz)
    error->all(FLERR, "Illegal pair_coeff command: damping tsuji needs normal model hertz/material or hertz "
                      "(use tsuji/alpha otherwise)");
  if (mode == 1 && (value <= 0.0 || value > 1.0))
    error->all(FLERR, "Illegal pair_coeff command: restitution e must lie in (0,1] for damping tsuji");
  // with tsuji/alpha the stock parser still needs a valid e in hertz/material: use 0.5
  std::vector<char *> argv;
  for (auto &s : copy) argv.push_back(const_cast<char *>(s.c_str()));
  PairGranular::coeff((int)argv.size(), argv.data());
  if (mode == 0) return;
  const double alpha = (mode == 1) ? meltdem::coupling::alpha_for_restitution(value) : value;
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  for (int i = ilo; i <= ihi; i++)
    for (int j = MAX(jlo, i); j <= jhi; j++)
      if (setflag[i][j]) {
        double ***nc = this->*get(NormalCoeffsTag());
        nc[i][j][1] = nc[j][i][1] = alpha;
      }
}

void PairGranularPowder::init_style()
{
  if (strcmp(update->unit_style, "si") != 0) error->all(FLERR, "Pair granular/powder requires units si");
  PairGranular::init_style();
  // the stock style sizes its cutoff from existing particles and fix pour/deposit only
  // (an empty box gives 0): count the particles fix powder/insert will insert as well
  for (int i = 0; i < modify->nfix; i++) {
    auto *ins = dynamic_cast<FixPowderInsert *>(modify->fix[i]);
    if (!ins) continue;
    double rnew = 0.5 * ins->max_new_diameter(), rall = 0.0;
    MPI_Allreduce(&rnew, &rall, 1, MPI_DOUBLE, MPI_MAX, world);
    const int t = ins->insert_type();
    maxrad_dynamic[t] = MAX(maxrad_dynamic[t], rall);
  }
}

double PairGranularPowder::init_one(int i, int j)
{
  // stock mixing of unset i != j pairs is wrong in this LAMMPS version: refuse
  if (setflag[i][j] == 0 && setflag[j][i] == 0)
    error->all(FLERR, "Pair granular/powder: pair_coeff {} {} not set (mixed pairs must be given explicitly)", i, j);
  return PairGranular::init_one(i, j);
}
