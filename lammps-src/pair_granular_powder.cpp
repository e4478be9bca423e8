// pair granular with the exact e -> alpha map of meltdem::coupling (doc/pair_granular_powder.rst).
#include "pair_granular_powder.h"
#include "error.h"
#include "atom.h"
#include "comm.h"
#include "force.h"
#include "update.h"
#include "modify.h"
#include "neigh_list.h"
#include "fix_powder_dt.h"
#include "fix_powder_insert.h"
#include "granular_exact_damping.h"
#include "lammps_api.h"
#if MELTDEM_LAMMPS_2025_API
#include "granular_model.h"
#endif
#include <mpi.h>
#include "meltdem/coupling/hertz_restitution.h"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>
using namespace LAMMPS_NS;
namespace mc = meltdem::coupling;

namespace {
// PairGranular keeps its coefficient arrays and settings private; an explicit template
// instantiation may name private members (C++ [temp.explicit]), which lets the subclass read
// and set them without forking the stock style.
template <typename Tag, typename Tag::type M> struct Rob {
  friend typename Tag::type get(Tag) { return M; }
};
// the tag of a private member of type T (K tells members of one type apart); each tag's get is
// the plain function Rob defines, which is what the warning is about
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-template-friend"
template <typename T, int K> struct Member {
  typedef T PairGranular::*type;
  friend type get(Member);
};
#pragma GCC diagnostic pop
using CutoffGlobalTag = Member<double, 0>;
template struct Rob<CutoffGlobalTag, &PairGranular::cutoff_global>;
#if !MELTDEM_LAMMPS_2025_API
using NormalCoeffsTag = Member<double ***, 0>;
template struct Rob<NormalCoeffsTag, &PairGranular::normal_coeffs>;
using LimitDampingTag = Member<int **, 0>;
template struct Rob<LimitDampingTag, &PairGranular::limit_damping>;
using EmodTag = Member<double **, 0>;
template struct Rob<EmodTag, &PairGranular::Emod>;
using PoissTag = Member<double **, 1>;
template struct Rob<PoissTag, &PairGranular::poiss>;
template <int K> using HistoryFlagTag = Member<int, K>;
template struct Rob<HistoryFlagTag<0>, &PairGranular::normal_history>;
template struct Rob<HistoryFlagTag<1>, &PairGranular::tangential_history>;
template struct Rob<HistoryFlagTag<2>, &PairGranular::roll_history>;
template struct Rob<HistoryFlagTag<3>, &PairGranular::twist_history>;
template <int K> using ModelTag = Member<int **, K>;  // 1 tangential, 2 roll, 3 twist
template struct Rob<ModelTag<1>, &PairGranular::tangential_model>;
template struct Rob<ModelTag<2>, &PairGranular::roll_model>;
template struct Rob<ModelTag<3>, &PairGranular::twist_model>;
#endif

// marks the restitution block this style appends to the stock pair section of a restart (on the
// 2023+ API the block also holds each type pair's alpha: the stock restart rebuilds the damping)
constexpr double RESTART_MAGIC = MELTDEM_LAMMPS_2025_API ? 20250.5 : 20201.5;
// the same block followed by what the stock restart leaves unset: the global cutoff and (before
// the 2023 API) each type pair's E and nu, which the mixing of unset pairs and fix powder/dt read
constexpr double RESTART_MAGIC_SETTINGS = MELTDEM_LAMMPS_2025_API ? 20250.75 : 20201.75;
}  // namespace

void PairGranularPowder::settings(int narg, char **arg)
{
  // [cutoff] [impact_speed V]: the keyword is ours, the cutoff goes to the stock style
  std::vector<char *> rest;
  impact_speed = 0.0;
  for (int i = 0; i < narg; i++) {
    if (strcmp(arg[i], "impact_speed") == 0) {
      if (i + 1 >= narg) error->all(FLERR, "Illegal pair_style granular/powder command: impact_speed needs a value");
      impact_speed = utils::numeric(FLERR, arg[i + 1], false, lmp);
      if (!(impact_speed > 0.0))
        error->all(FLERR, "Illegal pair_style granular/powder command: impact_speed must be > 0 (m/s)");
      i++;
    } else
      rest.push_back(arg[i]);
  }
  if (rest.size() > 1)
    error->all(FLERR, "Illegal pair_style granular/powder command: expected [cutoff] [impact_speed V]");
  PairGranular::settings((int)rest.size(), rest.data());
}

int PairGranularPowder::slot(int i, int j) const
{
  return i * (atom->ntypes + 1) + j;
}

void PairGranularPowder::set_exact(int i, int j, double e, double alpha_continuous)
{
  const int n = (atom->ntypes + 1) * (atom->ntypes + 1);
  if ((int)exact_e.size() != n) {
    exact_e.assign(n, 0.0);
    tsuji_alpha.assign(n, 0.0);
    alpha_tables.assign(n, mc::SteppedAlphaTable());
  }
  exact_e[slot(i, j)] = exact_e[slot(j, i)] = e;
  any_stepped = false;
  for (double each : exact_e) any_stepped = any_stepped || each > 0.0;
  if (e > 0.0) alpha_tables[slot(i, j)] = alpha_tables[slot(j, i)] = mc::SteppedAlphaTable(e, alpha_continuous);
}

void PairGranularPowder::coeff(int narg, char **arg)
{
  // hertz/material E e nu ... damping tsuji|tsuji/alpha: find e and the damping form,
  // let the stock parser do the rest, then overwrite alpha with the exact value.
  int mode = 0;  // 0 none, 1 tsuji (exact e), 2 tsuji/alpha
  double e_value = 0.0, alpha_value = 0.0;
  // e depends on alpha alone for a Hertz contact; DMT adds a constant pull and damps as Hertz
  // (stepped damping too), JKR damps with its own contact radius (the continuous alpha only)
  enum { OTHER, HERTZ_LIKE, JKR_MODEL } model = OTHER;
  bool limited = false;
  // the words are read at their places in arg, in any order; the stock parser gets a copy
  // with tsuji/alpha's value taken out
  std::vector<std::string> copy(arg, arg + narg);
  int alpha_at = -1;
  for (int i = 2; i < narg; i++) {
    const std::string word = arg[i];
    if (((word == "hertz/material" || word == "dmt" || word == "jkr") && i + 3 < narg) ||
        (word == "hertz" && i + 2 < narg)) {
      e_value = utils::numeric(FLERR, arg[i + 2], false, lmp);
      model = word == "jkr" ? JKR_MODEL : HERTZ_LIKE;
    }
    if ((word == "hertz/material" || word == "dmt" || word == "jkr") && i + 3 < narg) {
      // the material the contact law and fix powder/dt's contact time are computed from
      const double E = utils::numeric(FLERR, arg[i + 1], false, lmp);
      const double nu = utils::numeric(FLERR, arg[i + 3], false, lmp);
      if (!(E > 0.0)) error->all(FLERR, "Illegal pair_coeff command: {} Young's modulus E must be > 0", word);
      if (!(nu > -1.0 && nu <= 0.5))
        error->all(FLERR, "Illegal pair_coeff command: {} Poisson's ratio {} must lie in (-1,0.5]", word, nu);
    }
    if (word == "hooke") model = OTHER;
    if (word == "limit_damping") limited = true;
    if (word == "damping" && i + 1 < narg) {
      if (strcmp(arg[i + 1], "tsuji") == 0)
        mode = 1;
      else if (strcmp(arg[i + 1], "tsuji/alpha") == 0) {
        if (i + 2 >= narg) error->all(FLERR, "Illegal pair_coeff command: damping tsuji/alpha needs a value");
        if (alpha_at >= 0) error->all(FLERR, "Illegal pair_coeff command: damping given twice");
        mode = 2;
        alpha_value = utils::numeric(FLERR, arg[i + 2], false, lmp);
        if (alpha_value < 0.0) error->all(FLERR, "Illegal pair_coeff command: tsuji/alpha must be >= 0");
        copy[i + 1] = "tsuji";
        alpha_at = i + 2;
      }
    }
  }
  if (alpha_at >= 0) copy.erase(copy.begin() + alpha_at);
  const double value = mode == 2 ? alpha_value : e_value;
  if (mode == 1 && model == OTHER)
    error->all(FLERR, "Illegal pair_coeff command: damping tsuji needs normal model hertz/material, hertz, dmt "
                      "or jkr (use tsuji/alpha otherwise)");
  if (mode == 1 && (value <= 0.0 || value > 1.0))
    error->all(FLERR, "Illegal pair_coeff command: restitution e must lie in (0,1] for damping tsuji");
  // LAMMPS keeps JKR's touch flag in the contact history, but sizes the history from the
  // tangential, rolling and twisting models only: with none of them it stops with a bogus
  // "Neighbor history overflow"
  bool history = false;
  for (std::size_t i = 2; i + 1 < copy.size(); i++) {
    const std::string &next = copy[i + 1];
    if (copy[i] == "tangential") history = history || next != "linear_nohistory";
    if (copy[i] == "rolling" || copy[i] == "twisting") history = history || next != "none";
  }
  if (model == JKR_MODEL && !history && !MELTDEM_LAMMPS_2025_API)
    error->all(FLERR, "Illegal pair_coeff command: jkr needs a tangential, rolling or twisting model with history "
                      "in this LAMMPS version (e.g. tangential mindlin NULL 1.0 0.5; linear_nohistory leaves no "
                      "slot for its contact flag)");
  if (mode == 1 && limited)
    error->all(FLERR, "Illegal pair_coeff command: damping tsuji applies its damping over the whole step and "
                      "cannot be combined with limit_damping (use tsuji/alpha)");
#if MELTDEM_LAMMPS_2025_API
  // the stock tsuji sub-model refuses a cohesive normal model (dmt, jkr) although its damping is
  // well defined with them (the 29 Sep 2021 release allowed it): the stock parser gets the
  // velocity damping, which it accepts, and use_tsuji_alpha below puts Tsuji's in its place
  bool cohesive = false;
  for (auto &w : copy) cohesive = cohesive || w == "dmt" || w == "jkr";
  if (mode != 0 && cohesive)
    for (size_t i = 2; i + 1 < copy.size(); i++)
      if (copy[i] == "damping" && copy[i + 1] == "tsuji") copy[i + 1] = "velocity";
#endif
  std::vector<char *> argv;
  for (auto &s : copy) argv.push_back(const_cast<char *>(s.c_str()));
  PairGranular::coeff((int)argv.size(), argv.data());
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  // the stock alpha stays the continuous one: the tangential damping scales with it
  const double alpha = (mode == 1) ? mc::alpha_for_restitution(value) : value;
  for (int i = ilo; i <= ihi; i++)
    for (int j = MAX(jlo, i); j <= jhi; j++)
      if (setflag[i][j]) {
        set_exact(i, j, (mode == 1 && model == HERTZ_LIKE) ? value : 0.0, alpha);
        if (mode == 0) continue;
#if MELTDEM_LAMMPS_2025_API
        tsuji_alpha[slot(i, j)] = tsuji_alpha[slot(j, i)] = alpha;
#else
        double ***nc = this->*get(NormalCoeffsTag());
        nc[i][j][1] = nc[j][i][1] = alpha;
#endif
      }
#if MELTDEM_LAMMPS_2025_API
  // one model holds this command's type pairs: its damping gets the alpha
  if (mode != 0) meltdem_granular::use_tsuji_alpha(models_list[types_indices[ilo][MAX(jlo, ilo)]], lmp, alpha);
#endif
}

void PairGranularPowder::init_style()
{
  if (strcmp(update->unit_style, "si") != 0) error->all(FLERR, "Pair granular/powder requires units si");
  // stock mixing of unset i != j pairs is wrong in the 29 Sep 2021 release: refuse. Only
  // setflag[i][j] with i <= j is set and cleared by LAMMPS; the lower triangle is not initialised
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i + 1; j <= atom->ntypes; j++)
      if (setflag[i][j] == 0)
        error->all(FLERR, "Pair granular/powder: pair_coeff {} {} not set (mixed pairs must be given explicitly)", i,
                   j);
  PairGranular::init_style();
  // the stock style sizes its cutoff from existing particles and fix pour/deposit only
  // (an empty box gives 0): count the particles fix powder/insert will insert as well
  fix_dt = nullptr;
  for (int i = 0; i < modify->nfix; i++) {
    if (auto *dt_fix = dynamic_cast<FixPowderDt *>(modify->fix[i])) fix_dt = dt_fix;
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
  if (setflag[MIN(i, j)][MAX(i, j)] == 0)
    error->all(FLERR, "Pair granular/powder: pair_coeff {} {} not set (mixed pairs must be given explicitly)", i, j);
  const double cut = PairGranular::init_one(i, j);
#if MELTDEM_LAMMPS_2025_API
  const int n = (atom->ntypes + 1) * (atom->ntypes + 1);
  if ((int)hertz_kn.size() != n) hertz_kn.assign(n, 0.0);
  hertz_kn[slot(i, j)] = hertz_kn[slot(j, i)] = meltdem_granular::hertz_stiffness(models_list[types_indices[i][j]]);
#endif
  return cut;
}

double PairGranularPowder::current_impact_speed() const
{
  // the speed the step is sized for (fix powder/dt), else the pair_style keyword; 0: none
  if (fix_dt && fix_dt->approach_speed() > 0.0) return fix_dt->approach_speed();
  return impact_speed;
}

void PairGranularPowder::compute(int eflag, int vflag)
{
  PairGranular::compute(eflag, vflag);
  if (any_stepped) add_stepped_damping(eflag, vflag);
}

void PairGranularPowder::add_stepped_damping(int /*eflag*/, int /*vflag*/)
{
  // Replace the stock normal damping of 'damping tsuji' pairs by the stepped form of
  // meltdem/coupling/stepped_restitution.h, with alpha for this contact's step and its onset ratio.
  double **x = atom->x, **v = atom->v, **f = atom->f;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *type = atom->type, *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
#if !MELTDEM_LAMMPS_2025_API
  double ***nc = this->*get(NormalCoeffsTag());
#endif
  const double step = update->dt;
  const double speed = current_impact_speed();
  const double speed_factor = speed > 0.0 ? step * std::pow(speed, 0.2) : 0.0;

  mc::ContactStepMemo contact_step;  // (its pow kept between contacts)
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int itype = type[i];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const int jtype = type[j];
      const double e = exact_e[slot(itype, jtype)];
      if (e <= 0.0) continue;
      const double delx = x[i][0] - x[j][0], dely = x[i][1] - x[j][1], delz = x[i][2] - x[j][2];
      const double rsq = delx * delx + dely * dely + delz * delz;
      const double radsum = radius[i] + radius[j];
      const double vr[3] = {v[i][0] - v[j][0], v[i][1] - v[j][1], v[i][2] - v[j][2]};
      if (rsq >= radsum * radsum) {
        // apart now: only a pair that overlapped one step ago gets its last kick
        const double reach = radsum + step * std::sqrt(vr[0] * vr[0] + vr[1] * vr[1] + vr[2] * vr[2]);
        if (rsq >= reach * reach) continue;
      }
      const double r = std::sqrt(rsq), rinv = 1.0 / r;
      const double nx = delx * rinv, ny = dely * rinv, nz = delz * rinv;
      const double vnnr = vr[0] * nx + vr[1] * ny + vr[2] * nz;
      const double delta = radsum - r, delta_prev = delta + step * vnnr;
      if (delta <= 0.0 && delta_prev <= 0.0) continue;

      double mi = rmass[i], mj = rmass[j];
      if (fix_rigid) {
        if (mass_rigid[i] > 0.0) mi = mass_rigid[i];
        if (mass_rigid[j] > 0.0) mj = mass_rigid[j];
      }
      double meff = mi * mj / (mi + mj);
      if (mask[i] & freeze_group_bit) meff = mj;
      if (mask[j] & freeze_group_bit) meff = mi;
      const double reff = radius[i] * radius[j] / radsum;
#if MELTDEM_LAMMPS_2025_API
      const double kn = hertz_kn[slot(itype, jtype)];
      const double alpha_continuous = tsuji_alpha[slot(itype, jtype)];
#else
      const double kn = nc[itype][jtype][0], alpha_continuous = nc[itype][jtype][1];
#endif
      const double hertz_k = kn * std::sqrt(reff);

      const double h = speed > 0.0 ? contact_step(speed_factor, hertz_k, meff) : 0.0;
      const double fn =
          alpha_tables[slot(itype, jtype)].correction(h, alpha_continuous, hertz_k, meff, delta, vnnr, step);

      const double fx = nx * fn, fy = ny * fn, fz = nz * fn;
      f[i][0] += fx;
      f[i][1] += fy;
      f[i][2] += fz;
      if (newton_pair || j < nlocal) {
        f[j][0] -= fx;
        f[j][1] -= fy;
        f[j][2] -= fz;
      }
      if (evflag) ev_tally_xyz(i, j, nlocal, newton_pair, 0.0, 0.0, fx, fy, fz, delx, dely, delz);
    }
  }
}

void PairGranularPowder::write_restart(FILE *fp)
{
  PairGranular::write_restart(fp);
  // the prescribed e per type pair, behind a marker (older restarts have none)
  if (comm->me != 0) return;
  const int n = (atom->ntypes + 1) * (atom->ntypes + 1);
  std::vector<double> block(n, 0.0);
  if ((int)exact_e.size() == n) block = exact_e;
  fwrite(&RESTART_MAGIC_SETTINGS, sizeof(double), 1, fp);
  fwrite(&impact_speed, sizeof(double), 1, fp);
  fwrite(block.data(), sizeof(double), n, fp);
#if MELTDEM_LAMMPS_2025_API
  std::vector<double> alphas(n, 0.0);
  if ((int)tsuji_alpha.size() == n) alphas = tsuji_alpha;
  fwrite(alphas.data(), sizeof(double), n, fp);
#endif
  fwrite(&(this->*get(CutoffGlobalTag())), sizeof(double), 1, fp);
#if !MELTDEM_LAMMPS_2025_API
  for (double **a : {this->*get(EmodTag()), this->*get(PoissTag())})
    for (int i = 1; i <= atom->ntypes; i++) fwrite(&a[i][1], sizeof(double), atom->ntypes, fp);
#endif
}

void PairGranularPowder::read_restart(FILE *fp)
{
  PairGranular::read_restart(fp);
#if !MELTDEM_LAMMPS_2025_API
  // the stock restart leaves the history flags pair_coeff sets unset (init_style sizes the
  // contact history from them): set them as pair_coeff does, from the restored models
  this->*get(HistoryFlagTag<0>()) = 0;
  this->*get(HistoryFlagTag<1>()) = 0;
  this->*get(HistoryFlagTag<2>()) = 0;
  this->*get(HistoryFlagTag<3>()) = 0;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (!setflag[i][j]) continue;
      if ((this->*get(ModelTag<1>()))[i][j] != 0) this->*get(HistoryFlagTag<1>()) = 1;  // not linear_nohistory
      if ((this->*get(ModelTag<2>()))[i][j] != 0) this->*get(HistoryFlagTag<2>()) = 1;  // rolling sds
      if ((this->*get(ModelTag<3>()))[i][j] != 0) this->*get(HistoryFlagTag<3>()) = 1;  // twisting sds, marshall
    }
#endif
  const int n = (atom->ntypes + 1) * (atom->ntypes + 1);
  std::vector<double> block(n, 0.0), alphas(n, 0.0);
  const int nt = atom->ntypes;
  std::vector<double> moduli(2 * nt * nt, 0.0);
  int found = 0, settings = 0;
  double speed = 0.0, cutoff = 0.0;
  if (comm->me == 0) {
    const long at = ftell(fp);
    double magic = 0.0;
    if (fread(&magic, sizeof(double), 1, fp) == 1 && (magic == RESTART_MAGIC || magic == RESTART_MAGIC_SETTINGS) &&
        fread(&speed, sizeof(double), 1, fp) == 1 && fread(block.data(), sizeof(double), n, fp) == (size_t)n &&
        (!MELTDEM_LAMMPS_2025_API || fread(alphas.data(), sizeof(double), n, fp) == (size_t)n))
      found = 1;
    if (found && magic == RESTART_MAGIC_SETTINGS) {
      settings = fread(&cutoff, sizeof(double), 1, fp) == 1 &&
                 (MELTDEM_LAMMPS_2025_API || fread(moduli.data(), sizeof(double), moduli.size(), fp) == moduli.size());
      if (!settings) found = 0;
    }
    if (!found) fseek(fp, at, SEEK_SET);
  }
  MPI_Bcast(&found, 1, MPI_INT, 0, world);
  if (!found) return;
  MPI_Bcast(&settings, 1, MPI_INT, 0, world);
  if (settings) {
    MPI_Bcast(&cutoff, 1, MPI_DOUBLE, 0, world);
    this->*get(CutoffGlobalTag()) = cutoff;
#if !MELTDEM_LAMMPS_2025_API
    MPI_Bcast(moduli.data(), (int)moduli.size(), MPI_DOUBLE, 0, world);
    double **emod = this->*get(EmodTag()), **poiss = this->*get(PoissTag());
    for (int i = 1; i <= nt; i++)
      for (int j = 1; j <= nt; j++) {
        emod[i][j] = moduli[(i - 1) * nt + j - 1];
        poiss[i][j] = moduli[nt * nt + (i - 1) * nt + j - 1];
      }
#endif
  }
  MPI_Bcast(&speed, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(block.data(), n, MPI_DOUBLE, 0, world);
  impact_speed = speed;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) set_exact(i, j, block[slot(i, j)], -1.0);
#if MELTDEM_LAMMPS_2025_API
  MPI_Bcast(alphas.data(), n, MPI_DOUBLE, 0, world);
  tsuji_alpha = alphas;
  std::vector<Granular_NS::GranularModel *> done;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (!setflag[i][j] || tsuji_alpha[slot(i, j)] <= 0.0) continue;
      Granular_NS::GranularModel *model = models_list[types_indices[i][j]];
      if (std::find(done.begin(), done.end(), model) != done.end()) continue;
      meltdem_granular::use_tsuji_alpha(model, lmp, tsuji_alpha[slot(i, j)]);
      done.push_back(model);
    }
#endif
}
