/* ----------------------------------------------------------------------
   MeltDEM: fix powder/dt -- DEM time step from the Hertz contact time.

   dt = t_c / S with t_c the shortest Hertz contact time (Codina2019 eq. 3.1-3.3) of the
   current particles: two equal spheres of the smallest radius and smallest density, the
   largest E* of the granular pair style, at the approach speed U = max(2 max|v|, vmin).
   That pair has the shortest contact of any pair or particle-wall contact, and
   2 max|v| bounds every relative speed, so dt never exceeds t_c/S of a real collision.
   The largest U is held for three contact times (a collision keeps its duration while the
   speeds drop during it, and a damped one lasts longer).
------------------------------------------------------------------------- */

#include "fix_powder_dt.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "integrate.h"
#include "math_const.h"
#include "modify.h"
#include "pair.h"
#include "pair_granular.h"
#include "update.h"
#include "lammps_api.h"
#if MELTDEM_LAMMPS_2025_API
#include "gran_sub_mod_normal.h"
#include "granular_model.h"
#endif

#include "meltdem/coupling/dem_step_control.h"
#include "meltdem/coupling/hertz_contact.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;
using MathConst::MY_PI;
namespace mc = meltdem::coupling;

namespace {
#if MELTDEM_LAMMPS_2025_API
// E and nu of type pair i j from its granular model (the normal sub-model's accessors); false
// when its normal model has no material (hooke, hertz)
bool pair_material(PairGranular *gran, int i, int j, double &E, double &nu)
{
  if (!gran->models_list || !gran->types_indices) return false;
  const Granular_NS::GranularModel *model = gran->models_list[gran->types_indices[i][j]];
  if (!model || !model->normal_model || !model->normal_model->get_material_properties()) return false;
  E = model->normal_model->get_emod();
  nu = model->normal_model->get_poiss();
  return true;
}
#else
// PairGranular keeps E, nu and the normal model private and offers no accessor. An
// explicit template instantiation may name private members (C++17 [temp.spec]/6); the
// member pointers obtained that way read them from any PairGranular (stock granular and
// its subclass granular/powder). The ABI guard of meltdem-lmp ensures that the headers
// match the library, so the layout is the one compiled here.
template <typename Tag, typename Tag::type M> struct Expose {
  friend typename Tag::type member(Tag) { return M; }
};
struct EmodTag {
  using type = double **PairGranular::*;
  friend type member(EmodTag);
};
struct PoissTag {
  using type = double **PairGranular::*;
  friend type member(PoissTag);
};
struct NormalTag {
  using type = int **PairGranular::*;
  friend type member(NormalTag);
};
template struct Expose<EmodTag, &PairGranular::Emod>;
template struct Expose<PoissTag, &PairGranular::poiss>;
template struct Expose<NormalTag, &PairGranular::normal_model>;

// PairGranular's enum of normal models (pair_granular.cpp); the ones with E and nu
constexpr int HERTZ_MATERIAL = 2, DMT = 3, JKR = 4;
bool has_material(int model)
{
  return model == HERTZ_MATERIAL || model == DMT || model == JKR;
}
// E and nu of type pair i j as pair_coeff set them; false when its normal model has none
bool pair_material(PairGranular *gran, int i, int j, double &E, double &nu)
{
  double **Es = gran->*member(EmodTag());
  double **nus = gran->*member(PoissTag());
  int **model = gran->*member(NormalTag());
  if (!Es || !nus || !model || !has_material(model[i][j])) return false;
  E = Es[i][j];
  nu = nus[i][j];
  return true;
}
#endif
constexpr double BIG = std::numeric_limits<double>::max();
}  // namespace

/* ---------------------------------------------------------------------- */

FixPowderDt::FixPowderDt(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), steps(0.0), dtmax(0.0), interval(0.0), vfloor(0.01), maxoverlap(0.3), estar(0.0), uhold(0.0),
    thold(0.0), respaflag(0)
{
  // time_depend: elapsed time is accumulated across dt changes
  time_depend = 1;
  vector_flag = 1;
  size_vector = 7;
  global_freq = 1;
  extvector = 0;
  nevery = 1;
  for (double &o : out) o = 0.0;

  int iarg = 3;
  bool have_steps = false;
  auto need = [&](const char *kw) {
    if (iarg + 2 > narg) error->all(FLERR, "Fix powder/dt keyword {} needs 1 value", kw);
  };
  while (iarg < narg) {
    if (strcmp(arg[iarg], "steps") == 0) {
      need("steps");
      steps = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (steps <= 0.0) error->all(FLERR, "Fix powder/dt steps must be > 0");
      have_steps = true;
    } else if (strcmp(arg[iarg], "every") == 0) {
      need("every");
      nevery = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (nevery <= 0) error->all(FLERR, "Fix powder/dt every must be > 0");
    } else if (strcmp(arg[iarg], "max") == 0) {
      need("max");
      dtmax = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (dtmax <= 0.0) error->all(FLERR, "Fix powder/dt max must be > 0");
    } else if (strcmp(arg[iarg], "interval") == 0) {
      need("interval");
      interval = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (interval <= 0.0) error->all(FLERR, "Fix powder/dt interval must be > 0");
    } else if (strcmp(arg[iarg], "max_overlap") == 0) {
      need("max_overlap");
      maxoverlap = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (maxoverlap <= 0.0) error->all(FLERR, "Fix powder/dt max_overlap must be > 0");
    } else if (strcmp(arg[iarg], "vmin") == 0) {
      need("vmin");
      vfloor = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (vfloor <= 0.0) error->all(FLERR, "Fix powder/dt vmin must be > 0");
    } else
      error->all(FLERR, "Fix powder/dt: unknown keyword {}", arg[iarg]);
    iarg += 2;
  }
  if (!have_steps) error->all(FLERR, "Fix powder/dt requires keyword steps");

  if (strcmp(update->unit_style, "si") != 0)
    error->all(FLERR, "Fix powder/dt requires units si (eq. 3.1 is evaluated in SI)");
  if (!atom->radius_flag || !atom->rmass_flag)
    error->all(FLERR, "Fix powder/dt requires atom_style sphere (per-atom radius and mass)");
}

/* ---------------------------------------------------------------------- */

int FixPowderDt::setmask()
{
  return END_OF_STEP;
}

/* ---------------------------------------------------------------------- */

void FixPowderDt::init()
{
  respaflag = utils::strmatch(update->integrate_style, "^respa") ? 1 : 0;
  // two fixes setting the time step would overwrite each other every step
  for (int i = 0; i < modify->nfix; i++) {
    Fix *f = modify->fix[i];
    if (f != this && (utils::strmatch(f->style, "^dt/reset") || strcmp(f->style, "powder/dt") == 0))
      error->all(FLERR, "Fix powder/dt {} and fix {} {} both set the time step: use one of them", id, f->id, f->style);
  }
  read_pair_modulus();
}

/* ----------------------------------------------------------------------
   E* of the pair style: the largest over all type pairs (the stiffest contact is the
   shortest). Explicitly set pairs use their own E, nu for both partners (as PairGranular
   does); unset mixed pairs mix the two types' E, nu by eq. 3.2.
------------------------------------------------------------------------- */

void FixPowderDt::read_pair_modulus()
{
  Pair *pair = force->pair;
  if (!pair || !force->pair_style ||
      (strcmp(force->pair_style, "granular") != 0 && strcmp(force->pair_style, "granular/powder") != 0))
    error->all(FLERR,
               "Fix powder/dt requires pair_style granular or granular/powder (with hertz/material), "
               "not {}",
               force->pair_style ? force->pair_style : "none");

  auto *gran = static_cast<PairGranular *>(pair);
  int **setflag = pair->setflag;
  const int ntypes = atom->ntypes;
  if (!setflag) error->all(FLERR, "Fix powder/dt: pair_style {} has no coefficients set", force->pair_style);

  estar = 0.0;
  // E and nu as the pair coefficients give them; out of range is the user's input to name
  auto modulus = [&](int a, int b, double E1, double nu1, double E2, double nu2) {
    try {
      return mc::effective_modulus(E1, nu1, E2, nu2);
    } catch (const std::invalid_argument &e) {
      error->all(FLERR, "Fix powder/dt: pair_coeff {} {} of pair_style {}: {} (E {} nu {})", a, b, force->pair_style,
                 e.what(), a == b ? E1 : E2, a == b ? nu1 : nu2);
    }
    return 0.0;
  };
  for (int i = 1; i <= ntypes; i++)
    for (int j = i; j <= ntypes; j++) {
      double Es = 0.0, E1, nu1, E2, nu2;
      bool material = false;
      if (setflag[i][j]) {
        material = pair_material(gran, i, j, E1, nu1);
        if (material) Es = modulus(i, j, E1, nu1, E1, nu1);
      } else if (setflag[i][i] && setflag[j][j]) {
        material = pair_material(gran, i, i, E1, nu1) && pair_material(gran, j, j, E2, nu2);
        if (material) Es = modulus(i, j, E1, nu1, E2, nu2);
      } else
        error->all(FLERR, "Fix powder/dt: pair coefficients for types {} {} are not set", i, j);
      // dmt and jkr: the Hertz contact time of their E and nu (adhesion ignored)
      if (!material)
        error->all(FLERR,
                   "Fix powder/dt needs Young's modulus: pair_style {} must use hertz/material, dmt or jkr "
                   "for types {} {}",
                   force->pair_style, i, j);
      estar = std::max(estar, Es);
    }
}

/* ---------------------------------------------------------------------- */

void FixPowderDt::setup(int /*vflag*/)
{
  // a new run may start from velocities set in between: forget the held speed
  uhold = 0.0;
  update_dt();
}

/* ---------------------------------------------------------------------- */

void FixPowderDt::end_of_step()
{
  update_dt();
}

/* ---------------------------------------------------------------------- */

void FixPowderDt::update_dt()
{
  double **v = atom->v;
  double *radius = atom->radius;
  double *rmass = atom->rmass;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;

  // local minima of radius and density, maxima of |v|^2 and density (negated to reduce
  // with MIN)
  double loc[4] = {BIG, BIG, 0.0, 0.0};
  for (int i = 0; i < nlocal; i++)
    if ((mask[i] & groupbit) && radius[i] > 0.0) {
      const double r = radius[i];
      const double rho = rmass[i] / (4.0 / 3.0 * MY_PI * r * r * r);
      loc[0] = std::min(loc[0], r);
      loc[1] = std::min(loc[1], rho);
      loc[2] = std::min(loc[2], -(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]));
      loc[3] = std::min(loc[3], -rho);
    }
  double all[4];
  MPI_Allreduce(loc, all, 4, MPI_DOUBLE, MPI_MIN, world);

  // no particle (yet): nothing to resolve, keep the current dt
  if (all[0] == BIG) {
    out[0] = update->dt;
    out[1] = out[2] = out[3] = out[4] = out[6] = 0.0;
    out[5] = estar;
    return;
  }

  const double rmin = all[0], rhomin = all[1], vmax = std::sqrt(-all[2]), rhomax = -all[3];

  // stiffness and speed must keep contacts small: a soft particle hit hard overlaps its
  // neighbour by a good part of its radius, and Hertz's law (and the time step) stop
  // meaning anything; stop and name the knobs instead of computing nonsense
  if (vmax > 0.0) {
    const double worst = mc::head_on_overlap_ratio(rhomax, estar, 2.0 * vmax);
    if (worst > maxoverlap)
      error->all(FLERR,
                 "Fix powder/dt: two particles meeting head-on at {:.4g} m/s would overlap {:.3g} "
                 "of their radius (E* = {:.4g} Pa, rho = {:.4g} kg/m^3), more than max_overlap {}: "
                 "raise Young's modulus in pair_coeff, lower the impact speed, or raise max_overlap",
                 2.0 * vmax, worst, estar, rhomax, maxoverlap);
  }
  // A collision that started at speed U lasts t_c(U) even though the speeds drop while
  // it lasts, up to 1.8 t_c damped (e = 0.05), and 2^0.2 longer against a wall: hold the
  // largest U for three contact times, so dt does not grow mid-contact.
  const double now = update->atime + (update->ntimestep - update->atimestep) * update->dt;
  const double Unow = mc::approach_speed_bound(vmax, vfloor);
  if (Unow >= uhold || now - thold > 3.0 * mc::shortest_contact_time(rmin, rhomin, estar, uhold)) {
    uhold = Unow;
    thold = now;
  }
  const double U = uhold;
  const double tc = mc::shortest_contact_time(rmin, rhomin, estar, U);
  double dt = mc::dem_timestep(tc, steps);
  if (dtmax > 0.0) dt = std::min(dt, dtmax);

  out[0] = dt;
  out[1] = tc;
  out[2] = interval > 0.0 ? (double)mc::dem_subcycles(interval, dt) : 0.0;
  out[3] = rmin;
  out[4] = U;
  out[5] = estar;
  out[6] = rhomin;

  apply_dt(ceiling > 0.0 ? std::min(dt, ceiling) : dt);
}

/* ---------------------------------------------------------------------- */

void FixPowderDt::set_step_ceiling(double dt_ceiling)
{
  ceiling = dt_ceiling;
  if (ceiling == 0.0 && out[0] > 0.0) apply_dt(out[0]);
}

/* ---------------------------------------------------------------------- */

void FixPowderDt::apply_dt(double dt)
{
  if (dt == update->dt) return;

  // as fix dt/reset: book the elapsed time, then tell every style that caches dt
  update->update_time();
  update->dt = dt;
  update->dt_default = 0;
  if (respaflag) update->integrate->reset_dt();
  if (force->pair) force->pair->reset_dt();
  for (int i = 0; i < modify->nfix; i++) modify->fix[i]->reset_dt();
}

/* ---------------------------------------------------------------------- */

double FixPowderDt::compute_vector(int n)
{
  return out[n];
}
