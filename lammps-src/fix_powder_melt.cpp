/* ----------------------------------------------------------------------
   MeltDEM: fix powder/melt -- heating, drag, buoyancy and melting of particles.
   The per-particle physics (one heat/melt step, drag and buoyancy) is in
   coupling/ (particle_melting.h, particle_forces.h); this fix owns the per-atom
   state, the ledger of what is handed to the continuum and the deletion of molten
   particles.
------------------------------------------------------------------------- */

#include "fix_powder_melt.h"

#include "lammps_api.h"
#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "memory.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include "meltdem/coupling/hertz_restitution.h"
#include "meltdem/coupling/held_exchange.h"
#include "meltdem/coupling/particle_forces.h"
#include "meltdem/coupling/solid_metal_contact.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <unordered_map>

using namespace LAMMPS_NS;
using namespace FixConst;
namespace mc = meltdem::coupling;

/* ---------------------------------------------------------------------- */

FixPowderMelt::FixPowderMelt(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), drag_model(mc::DragModel::Thesis), T0(0.0), ambient_flag(0), provider(nullptr), in_setup(0),
    solid_flag(0), solid_estar(0.0), solid_alpha(0.0), interval_start(0), handover_d(0.0), melt(nullptr),
    output(nullptr), coef(nullptr), coef_tol(0.01), vector_dirty(1)
{
  if (strcmp(update->unit_style, "si") != 0)
    error->all(FLERR, "Fix powder/melt requires units si (its heat and drag laws use SI values)");
  if (domain->dimension != 3) error->all(FLERR, "Fix powder/melt requires a 3d simulation");

  // radius and mass change as particles melt: ghosts must receive them every step,
  // which atom_style sphere does only with its dynamic-radius flag (atom_style sphere 1)
  bool radvary = false;
  if (meltdem::lammps_api::sphere_style(atom)) {
    const auto words = meltdem::lammps_api::comm_fields(atom->avec);
    bool r = false, m = false;
    for (auto &w : words) {
      if (w == "radius") r = true;
      if (w == "rmass") m = true;
    }
    radvary = r && m;
  }
  if (!radvary)
    error->all(FLERR,
               "Fix powder/melt requires atom_style sphere 1 (particle radius and mass "
               "change as they melt; atom_style {} does not communicate them)",
               atom->atom_style);

  int have_cp = 0, have_tm = 0, have_l = 0, have_t0 = 0;
  mc::FluidState amb;
  int iarg = 3;
  auto value = [&](const char *kw, int n) {
    if (iarg + n >= narg) error->all(FLERR, "Illegal fix powder/melt command: keyword {} needs {} value(s)", kw, n);
  };
  while (iarg < narg) {
    if (strcmp(arg[iarg], "cp") == 0) {
      value("cp", 1);
      mat.cp = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      have_cp = 1;
      iarg += 2;
    } else if (strcmp(arg[iarg], "Tmelt") == 0) {
      value("Tmelt", 1);
      mat.Tmelt = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      have_tm = 1;
      iarg += 2;
    } else if (strcmp(arg[iarg], "latent") == 0) {
      value("latent", 1);
      mat.latent = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      have_l = 1;
      iarg += 2;
    } else if (strcmp(arg[iarg], "temp") == 0) {
      value("temp", 1);
      T0 = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      have_t0 = 1;
      iarg += 2;
    } else if (strcmp(arg[iarg], "ambient") == 0) {
      for (int k = 1; k <= 8; k++)
        if (iarg + k >= narg || !utils::is_double(arg[iarg + k]))
          error->all(FLERR,
                     "Illegal fix powder/melt command: ambient needs 8 values "
                     "(TF KF RHOF MUF CPF UX UY UZ), value {} is {}",
                     k, iarg + k >= narg ? "missing" : arg[iarg + k]);
      amb.T = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      amb.k = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      amb.rho = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
      amb.mu = utils::numeric(FLERR, arg[iarg + 4], false, lmp);
      amb.cp = utils::numeric(FLERR, arg[iarg + 5], false, lmp);
      for (int k = 0; k < 3; k++) amb.U[k] = utils::numeric(FLERR, arg[iarg + 6 + k], false, lmp);
      if (!(amb.T >= 0.0)) error->all(FLERR, "Fix powder/melt ambient temperature must be >= 0 K");
      if (!(amb.k > 0.0)) error->all(FLERR, "Fix powder/melt ambient conductivity KF must be > 0");
      if (!(amb.rho >= 0.0)) error->all(FLERR, "Fix powder/melt ambient density RHOF must be >= 0");
      if (!(amb.mu > 0.0)) error->all(FLERR, "Fix powder/melt ambient viscosity MUF must be > 0");
      if (!(amb.cp > 0.0)) error->all(FLERR, "Fix powder/melt ambient heat capacity CPF must be > 0");
      ambient_flag = 1;
      iarg += 9;
    } else if (strcmp(arg[iarg], "solid_metal") == 0) {
      value("solid_metal", 2);
      solid_estar = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      const double e = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      if (!(solid_estar > 0.0)) error->all(FLERR, "Fix powder/melt solid_metal: effective modulus E* must be > 0 Pa");
      if (!(e > 0.0) || e > 1.0)
        error->all(FLERR, "Fix powder/melt solid_metal: restitution must be in (0, 1], not {}", e);
      solid_alpha = mc::alpha_for_restitution(e);
      solid_flag = 1;
      iarg += 3;
    } else if (strcmp(arg[iarg], "drag") == 0) {
      value("drag", 1);
      if (strcmp(arg[iarg + 1], "thesis") == 0)
        drag_model = mc::DragModel::Thesis;
      else if (strcmp(arg[iarg + 1], "schiller-naumann") == 0)
        drag_model = mc::DragModel::SchillerNaumann;
      else
        error->all(FLERR, "Fix powder/melt drag model {} unknown (use thesis or schiller-naumann)", arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "handover") == 0) {
      value("handover", 1);
      handover_d = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(handover_d >= 0.0))
        error->all(FLERR, "Fix powder/melt handover diameter must be >= 0 m, not {}", handover_d);
      iarg += 2;
    } else if (strcmp(arg[iarg], "coefficient_tolerance") == 0) {
      value("coefficient_tolerance", 1);
      coef_tol = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(coef_tol >= 0.0) || !(coef_tol < 1.0))
        error->all(FLERR, "Fix powder/melt coefficient_tolerance must be in [0, 1), not {}", coef_tol);
      iarg += 2;
    } else
      error->all(FLERR, "Illegal fix powder/melt command: unknown keyword {}", arg[iarg]);
  }

  if (!have_cp) error->all(FLERR, "Fix powder/melt requires keyword cp");
  if (!have_tm) error->all(FLERR, "Fix powder/melt requires keyword Tmelt");
  if (!have_l) error->all(FLERR, "Fix powder/melt requires keyword latent");
  if (!(mat.cp > 0.0)) error->all(FLERR, "Fix powder/melt cp must be > 0");
  if (!(mat.Tmelt > 0.0)) error->all(FLERR, "Fix powder/melt Tmelt must be > 0");
  if (!(mat.latent > 0.0)) error->all(FLERR, "Fix powder/melt latent must be > 0");
  if (have_t0 && (!(T0 >= 0.0) || !(T0 <= mat.Tmelt)))
    error->all(FLERR, "Fix powder/melt temp {} outside [0, Tmelt = {}] (particles are solid)", T0, mat.Tmelt);

  if (ambient_flag) {
    ambient = std::make_unique<mc::UniformFluid>(amb);
    provider = ambient.get();
  }

  vector_flag = 1;
  size_vector = 6;
  global_freq = 1;
  extvector = 1;
  peratom_flag = 1;
  size_peratom_cols = NOUT;
  peratom_freq = 1;
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  force_reneighbor = 1;
  next_reneighbor = -1;
  for (double &v : vector_all) v = 0.0;

  held = nullptr;
  held_flag = 0;
  heated_nlocal = -1;
  maxexchange = NCOL + NHELD + NCOEF;  // per atom in Comm::exchange()
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

/* ---------------------------------------------------------------------- */

FixPowderMelt::~FixPowderMelt()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(melt);
  memory->destroy(output);
  memory->destroy(held);
  memory->destroy(coef);
}

/* ---------------------------------------------------------------------- */

int FixPowderMelt::setmask()
{
  int mask = 0;
  mask |= PRE_EXCHANGE;
  mask |= POST_FORCE;
  mask |= END_OF_STEP;
  return mask;
}

/* ---------------------------------------------------------------------- */

void FixPowderMelt::init()
{
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix powder/melt does not support run_style respa");
  // a second one would heat, drag and melt the same particles again
  for (int i = 0; i < modify->nfix; i++)
    if (modify->fix[i] != this && strcmp(modify->fix[i]->style, "powder/melt") == 0)
      error->all(FLERR, "Fix powder/melt {} and fix powder/melt {} both act on the particles: use one of them", id,
                 modify->fix[i]->id);

  // buoyancy needs gravity; the values are read each step (fix gravity may vary them)
  gravity_fixes.clear();
  for (int i = 0; i < modify->nfix; i++)
    if (utils::strmatch(modify->fix[i]->style, "^gravity")) gravity_fixes.push_back(i);

  // particles that left the group since the last run are no longer held
  for (int i = 0; i < atom->nlocal; i++)
    if (!(atom->mask[i] & groupbit)) release(i);

  if (!provider && !held_flag && comm->me == 0)
    error->warning(FLERR, "Fix powder/melt has no fluid (no ambient keyword, no coupling): "
                          "particles are neither heated nor dragged");
}

/* ---------------------------------------------------------------------- */

const double *FixPowderMelt::gravity(double *g) const
{
  g[0] = g[1] = g[2] = 0.0;
  for (int ifix : gravity_fixes) {
    int dim;
    auto *gvec = (double *)modify->fix[ifix]->extract("gvec", dim);
    if (gvec)
      for (int k = 0; k < 3; k++) g[k] += gvec[k];
  }
  return g;
}

/* ---------------------------------------------------------------------- */

void FixPowderMelt::hold_fluid(const std::vector<tagint> &tags, const std::vector<mc::FluidState> &states,
                               int located_by)
{
  if (tags.size() != states.size()) error->one(FLERR, "Fix powder/melt: hold_fluid needs one state per tag");
  held_flag = 1;
  interval_start = 1;
  std::vector<int> state_of(std::size_t(atom->nlocal), -1);
  const std::vector<int> slot = local_slots(tags);
  for (std::size_t k = 0; k < tags.size(); ++k)
    if (slot[k] >= 0) state_of[std::size_t(slot[k])] = int(k);
  for (int i = 0; i < atom->nlocal; i++) {
    const int k = state_of[std::size_t(i)];
    const bool found = k >= 0;
    double q[mc::kFluidStateDoubles];
    if (found) mc::pack_fluid_state(states[std::size_t(k)], q);
    // a particle keeps its held coefficients while the fluid's properties it sees stay the same
    if (!(found && held[i][HELD_SET] != 0.0 && coef[i][C_STATE] == 1.0)) {
      release(i);
    } else {
      const mc::FluidState &now = states[std::size_t(k)];
      // (held without heat because particle and fluid were equally warm: still so?)
      const double h = melt[i][HSPEC];
      const bool level = h < mat.cp * mat.Tmelt && h / mat.cp == now.T;
      if (!same_coefficients(&held[i][HELD_STATE], q) ||
          (coef[i][C_SHARE] == 0.0 && now.thermal && now.k > 0.0 && !level))
        release(i);
    }
    held[i][HELD_SET] = found ? 1.0 : 0.0;
    held[i][HELD_BY] = found ? double(located_by) : -1.0;
    if (found) std::copy(q, q + mc::kFluidStateDoubles, &held[i][HELD_STATE]);
  }
}

bool FixPowderMelt::fluid_at(int i, mc::FluidState &out) const
{
  if (held_flag) {
    if (held[i][HELD_SET] == 0.0) return false;
    mc::unpack_fluid_state(&held[i][HELD_STATE], out);
    return true;
  }
  return provider && provider->fluid_state(i, atom->x[i], out);
}

/* ----------------------------------------------------------------------
   particles that exist before the first run (or were created and resized by
   'set' since): their initial mass is the mass they have now
------------------------------------------------------------------------- */

void FixPowderMelt::setup(int vflag)
{
  for (int i = 0; i < atom->nlocal; i++) {
    if (melt[i][MASS0] <= 0.0) melt[i][MASS0] = atom->rmass[i];
    refresh_output(i);
  }
  // the forces at the start of a run: not an impulse of the interval yet (the steps'
  // own post_force books each step's drag impulse once)
  heated_nlocal = -1;
  in_setup = 1;
  post_force(vflag);
  in_setup = 0;
}

/* ---------------------------------------------------------------------- */

void FixPowderMelt::setup_pre_exchange()
{
  delete_molten();
}

/* ---------------------------------------------------------------------- */

void FixPowderMelt::pre_exchange()
{
  if (next_reneighbor != update->ntimestep) return;
  delete_molten();
}

/* ----------------------------------------------------------------------
   remove fully molten particles (already booked in end_of_step) as fix evaporate
   does; collective
------------------------------------------------------------------------- */

int FixPowderMelt::delete_molten()
{
  return (int)delete_local([this](int i) {
    if (melt[i][MOLTEN] == 0.0) return false;
    finished.push_back(record(i));  // the coupling still has to hand its last melt over
    return true;
  });
}

/* ----------------------------------------------------------------------
   delete the local atoms for which doomed(i) holds; collective
------------------------------------------------------------------------- */

bigint FixPowderMelt::delete_local(const std::function<bool(int)> &doomed)
{
  AtomVec *avec = atom->avec;
  bigint ndel = 0;
  for (int i = atom->nlocal - 1; i >= 0; i--)
    if (doomed(i)) {
      avec->copy(atom->nlocal - 1, i, 1);
      atom->nlocal--;
      ndel++;
    }
  bigint ndel_all = 0;
  MPI_Allreduce(&ndel, &ndel_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (ndel_all) {
    atom->natoms -= ndel_all;
    if (atom->map_style != Atom::MAP_NONE) {
      atom->nghost = 0;
      atom->map_init();
      atom->map_set();
    }
  }
  return ndel_all;
}

/* ----------------------------------------------------------------------
   the fluid parcel a particle exchanges momentum and heat with over a coupling interval
   starts at the sampled velocity and temperature, then moves with the drag reaction and
   the heat the particle takes (two bodies)
------------------------------------------------------------------------- */

void FixPowderMelt::parcel_state(int i, mc::FluidState &fluid)
{
  if (melt[i][P_SET] == 0.0) {
    for (int k = 0; k < 3; k++) melt[i][P_UX + k] = fluid.U[k];
    melt[i][P_T] = fluid.T;
    melt[i][P_SET] = 1.0;
  }
  if (fluid.mass > 0.0)
    for (int k = 0; k < 3; k++) fluid.U[k] = melt[i][P_UX + k];
  if (fluid.capacity > 0.0) fluid.T = melt[i][P_T];
}

/* ----------------------------------------------------------------------
   the coefficients held over the interval's sub-steps: the fluid is frozen, so drag and
   heat depend on the step only through the slip, the particle's size and mass and dt
------------------------------------------------------------------------- */

bool FixPowderMelt::same_coefficients(const double *q, const double *p)
{
  mc::FluidState a, b;
  mc::unpack_fluid_state(q, a);
  mc::unpack_fluid_state(p, b);
  return a.k == b.k && a.rho == b.rho && a.mu == b.mu && a.cp == b.cp && a.thermal == b.thermal && a.mass == b.mass &&
         a.capacity == b.capacity && a.heat_source == b.heat_source && a.implicit_heat == b.implicit_heat &&
         a.solid.present == b.solid.present;
}

int FixPowderMelt::atom_nlocal() const
{
  return atom->nlocal;
}

double FixPowderMelt::interval_value(int i, int col) const
{
  const double *c = coef[i];
  if (c[C_STATE] != 1.0) return melt[i][col];
  if (col >= P_UX && col <= P_UZ) return c[C_PUX + col - P_UX];
  if (col >= I_DX && col <= I_DZ) return c[C_IDX + col - I_DX];
  if (col == P_T) return c[C_PT];
  if (col == I_HEAT) return c[C_IHEAT];
  return melt[i][col];
}

double FixPowderMelt::hold_coefficients(int i, const mc::FluidState &fluid, double dt)
{
  double *c = coef[i];
  if (melt[i][MASS0] <= 0.0) melt[i][MASS0] = atom->rmass[i];  // inserted during the run
  const bool every_step = fluid.heat_source > 0.0 || (solid_flag && fluid.solid.present) || fluid.implicit_heat;
  c[C_STATE] = every_step ? 2.0 : 1.0;
  if (every_step) return -1.0;
  if (solid_flag) {
    // no solid metal this interval: the contact memory is forgotten, as a step of the full path
    // does (mc::update_solid_contact)
    store_contact_memory(i, mc::SolidContactMemory());
  }
  mc::HeldExchangeInput in;
  in.model = drag_model;
  in.rho = fluid.rho, in.mu = fluid.mu, in.cp = fluid.cp;
  // equal temperatures stay equal: only this exchange would change either over the interval
  const double h_now = melt[i][HSPEC];
  const bool level = h_now < mat.cp * mat.Tmelt && h_now / mat.cp == melt[i][P_T];
  in.k = fluid.thermal && !level ? fluid.k : 0.0;
  in.C_fluid = fluid.capacity;
  in.d = 2.0 * atom->radius[i], in.m = atom->rmass[i], in.cp_particle = mat.cp;
  in.dt = dt;
  const double *v = atom->v[i];
  for (int k = 0; k < 3; k++) in.s2 += (melt[i][P_UX + k] - v[k]) * (melt[i][P_UX + k] - v[k]);
  in.tol = coef_tol;
  mc::HeldExchange h;
  try {
    h = mc::hold_exchange(in);
  } catch (std::invalid_argument &e) {
    error->one(FLERR, "Fix powder/melt: atom {}: {}", atom->tag[i], e.what());
  }
  c[C_Y0] = h.beta.y0;
  c[C_BETA0] = h.beta.v0, c[C_BETA1] = h.beta.slope;
  c[C_E10] = h.expm1_rate.v0, c[C_E11] = h.expm1_rate.slope;
  c[C_SHARE] = h.share;
  c[C_LO] = h.lo, c[C_HI] = h.hi;
  // the two-body cap of the drag coefficient (particle_forces.h)
  c[C_CAP] = mc::two_body_drag_coefficient(HUGE_VAL, in.m, fluid.mass, dt);
  c[C_VB] = -fluid.rho * M_PI / 6.0 * in.d * in.d * in.d;
  c[C_DTMF] = fluid.mass > 0.0 ? dt / fluid.mass : 0.0;
  c[C_CF] = fluid.capacity;
  c[C_D] = in.d;
  c[C_DT] = dt;
  // the held columns
  for (int k = 0; k < 3; k++) {
    c[C_PUX + k] = melt[i][P_UX + k];
    c[C_IDX + k] = melt[i][I_DX + k];
  }
  c[C_PT] = melt[i][P_T];
  c[C_IHEAT] = melt[i][I_HEAT];
  return in.s2;
}

/* ----------------------------------------------------------------------
   the particle's memory of its solid-metal contact, in the S_* columns
------------------------------------------------------------------------- */

mc::SolidContactMemory FixPowderMelt::contact_memory(int i) const
{
  mc::SolidContactMemory m;
  m.offset = melt[i][S_OFFSET];
  m.has_plane = melt[i][S_HAS] != 0.0;
  m.point = Eigen::Vector3d(melt[i][S_PX], melt[i][S_PY], melt[i][S_PZ]);
  m.normal = Eigen::Vector3d(melt[i][S_NX], melt[i][S_NY], melt[i][S_NZ]);
  m.has_mark = melt[i][S_HAS_MARK] != 0.0;
  m.mark = Eigen::Vector3d(melt[i][S_MX], melt[i][S_MY], melt[i][S_MZ]);
  return m;
}

void FixPowderMelt::store_contact_memory(int i, const mc::SolidContactMemory &m)
{
  melt[i][S_OFFSET] = m.offset;
  melt[i][S_HAS] = m.has_plane ? 1.0 : 0.0;
  melt[i][S_HAS_MARK] = m.has_mark ? 1.0 : 0.0;
  for (int k = 0; k < 3; k++) {
    melt[i][S_PX + k] = m.point[k];
    melt[i][S_NX + k] = m.normal[k];
    melt[i][S_MX + k] = m.mark[k];
  }
}

/* ----------------------------------------------------------------------
   drag and buoyancy (eq. 2.14); gravity itself is fix gravity's
------------------------------------------------------------------------- */

void FixPowderMelt::post_force(int /*vflag*/)
{
  const int nlocal = atom->nlocal;
  if (!provider && !held_flag) return;

  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double *radius = atom->radius;
  double *rmass = atom->rmass;
  int *mask = atom->mask;
  double g[3];
  gravity(g);
  const double dt = update->dt;

  mc::FluidState fluid;
  // the held heat steps' heats, booked after the loop (the exact sum's dependency chain kept
  // out of the per-particle work)
  if (step_heats.size() < std::size_t(nlocal)) step_heats.resize(std::size_t(nlocal));
  double *heats = step_heats.data();
  int nheated = 0;
  for (int i = 0; i < nlocal; i++) {
    // (held coefficients belong to a solid particle of the group: tested first)
    double s2 = -1.0;
    if (in_setup) {
      // the run's first forces: held particles with their lines, nothing booked
      if (holds(i, radius, dt) && (s2 = held_slip2(i, v[i])) >= 0.0) {
        const double *c = coef[i];
        const double beta = held_drag_coefficient(i, s2);
        for (int k = 0; k < 3; k++) f[i][k] += beta * (c[C_PUX + k] - v[i][k]) + c[C_VB] * g[k];
        continue;
      }
      s2 = -1.0;
    } else if (!(holds(i, radius, dt) && (s2 = held_slip2(i, v[i])) >= 0.0)) {
      // (re)evaluate: a new interval, a new size, or the slip left the window
      release(i);
      coef[i][C_HEATED] = 0.0;
      if (!(mask[i] & groupbit) || melt[i][MOLTEN] != 0.0 || !fluid_at(i, fluid)) continue;
      parcel_state(i, fluid);
      s2 = hold_coefficients(i, fluid, dt);
    }
    if (s2 >= 0.0) {
      // held coefficients: drag against the parcel's velocity now, buoyancy with g now, and the
      // heat step with the same slip (the step's mid-point velocity, as the drag)
      double *c = coef[i];
      const bool heats_now = c[C_SHARE] != 0.0;
      const double y = c[C_BETA1] != 0.0 || heats_now ? mc::held_variable(s2) : c[C_Y0];
      const double beta = held_drag_at(c, y);
      const bool parcel_moves = c[C_DTMF] != 0.0;  // (an unbounded ambient parcel does not)
      for (int k = 0; k < 3; k++) {
        const double drag = beta * (c[C_PUX + k] - v[i][k]);
        if (parcel_moves) c[C_PUX + k] -= drag * c[C_DTMF];
        f[i][k] += drag + c[C_VB] * g[k];
        c[C_IDX + k] += drag * dt;
      }
      const bool heated = !heats_now || held_heat_step(i, rmass[i], y, heats);
      c[C_HEATED] = heated ? 1.0 : 0.0;
      nheated += heated;
      continue;
    }
    // every step: light, solid-metal contact, implicit heat, and the setup's forces
    release(i);
    if (!in_setup) coef[i][C_HEATED] = 0.0;
    if (!(mask[i] & groupbit) || melt[i][MOLTEN] != 0.0) continue;
    if (!fluid_at(i, fluid)) continue;
    parcel_state(i, fluid);
    mc::ParticleForces F;
    try {
      F = mc::drag_and_buoyancy(drag_model, fluid, v[i], 2.0 * radius[i], g);
    } catch (std::invalid_argument &e) {
      error->one(FLERR, "Fix powder/melt: atom {}: {}", atom->tag[i], e.what());
    }
    // two-body drag with the fluid parcel (never past the common velocity; the parcel moves too)
    const double beta = mc::two_body_drag_coefficient(F.beta, rmass[i], fluid.mass, in_setup ? 0.0 : dt);
    for (int k = 0; k < 3; k++) F.drag[k] = beta * (fluid.U[k] - v[i][k]);
    if (fluid.mass > 0.0 && !in_setup)
      for (int k = 0; k < 3; k++) melt[i][P_UX + k] -= F.drag[k] * dt / fluid.mass;
    if (solid_flag) {
      // the continuum's solid metal repels the particle as a granular wall, counting only
      // the overlap the particle made by moving (not what freezing melt put around it)
      const Eigen::Vector3d xi(x[i][0], x[i][1], x[i][2]);
      mc::SolidContactMemory memory = contact_memory(i);
      const double offset = mc::update_solid_contact(memory, fluid.solid, xi, radius[i], interval_start != 0);
      store_contact_memory(i, memory);
      const Eigen::Vector3d Fs =
          mc::solid_contact_force(fluid.solid, xi, radius[i], rmass[i], Eigen::Vector3d(v[i][0], v[i][1], v[i][2]),
                                  solid_estar, solid_alpha, offset);
      for (int k = 0; k < 3; k++) f[i][k] += Fs[k];
    }
    for (int k = 0; k < 3; k++) {
      f[i][k] += F.drag[k] + F.buoyancy[k];
      if (!in_setup) melt[i][I_DX + k] += F.drag[k] * dt;
    }
  }
  if (!in_setup) {
    interval_start = 0;
    mc::ExactSum held_heat;
    for (const double *q = step_heats.data(); q != heats; ++q) held_heat.add(*q);
    ledger[5].add(held_heat.hi());
    ledger[5].add(held_heat.lo());
    heated_nlocal = nheated == nlocal ? nlocal : -1;
  }
}

/* ----------------------------------------------------------------------
   heating and melting (eq. 2.3, 2.9, 2.13) with the full-step velocity of the particles
   post_force did not heat; book what is handed over (eq. 2.3, 2.9, 2.11) and schedule the
   deletion of molten particles
------------------------------------------------------------------------- */

void FixPowderMelt::end_of_step()
{
  const int nlocal = atom->nlocal;
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  double *radius = atom->radius;
  double *rmass = atom->rmass;
  int *mask = atom->mask;
  const double dt = update->dt;

  int nmolten = 0;
  mc::FluidState fluid;
  // (every particle took its held step in post_force: nothing to do)
  const bool any = (provider || held_flag) && heated_nlocal != nlocal;
  for (int i = 0; i < nlocal && any; i++) {
    if (coef[i][C_HEATED] != 0.0) continue;  // post_force took its held heat step
    release(i);
    if (!(mask[i] & groupbit) || melt[i][MOLTEN] != 0.0) continue;
    if (melt[i][MASS0] <= 0.0) melt[i][MASS0] = rmass[i];  // inserted during the run
    if (!fluid_at(i, fluid)) continue;
    parcel_state(i, fluid);

    const double d = 2.0 * radius[i], m = rmass[i];
    mc::MeltStepResult r;
    try {
      // light absorbed this step first (operator split), then the fluid's heat
      mc::MeltStepResult lit;
      lit.h = melt[i][HSPEC], lit.m = m, lit.d = d;
      if (fluid.heat_source > 0.0) lit = mc::absorb_heat(mat, melt[i][HSPEC], m, d, fluid.heat_source * dt);
      if (!fluid.thermal) {
        // the continuum has no energy equation: an isothermal particle (drag only)
        r = lit;
        r.heat = 0.0;
      } else if (fluid.implicit_heat) {
        // the continuum's energy solve exchanged the heat: take what it gave at once (a particle
        // the light melted away hands it on with its melt). Heat that would cool it below 0 K
        // waits (it goes on with its melt)
        const double take = lit.fully_molten ? 0.0 : std::max(melt[i][OWED], -lit.m * lit.h);
        if (lit.fully_molten) {
          r = lit;
        } else {
          r = mc::exchange_heat(mat, lit.h, lit.m, lit.d, take);
          r.mass_melted += lit.mass_melted;
          r.enthalpy_out += lit.enthalpy_out;
        }
        melt[i][OWED] -= take;
        if (r.fully_molten) {
          r.heat += melt[i][OWED];
          r.enthalpy_out += melt[i][OWED];
          melt[i][OWED] = 0.0;
        }
        melt[i][COND] =
            r.fully_molten ? 0.0 : mc::ranz_marshall_k_nu(fluid, mc::slip_reynolds(fluid, v[i], r.d)) * M_PI * r.d;
      } else if (lit.fully_molten) {
        r = lit;
        r.heat = 0.0;
      } else {
        const double Re = mc::slip_reynolds(fluid, v[i], lit.d);
        r = mc::heat_melt_step_two_body(mat, lit.h, lit.m, lit.d, mc::ranz_marshall_k_nu(fluid, Re), fluid.T,
                                        fluid.capacity, dt);
        if (fluid.capacity > 0.0) melt[i][P_T] = r.T_fluid;
        r.mass_melted += lit.mass_melted;
        r.enthalpy_out += lit.enthalpy_out;
      }
      melt[i][I_LASER] += lit.heat;
    } catch (std::invalid_argument &e) {
      error->one(FLERR, "Fix powder/melt: atom {}: {}", atom->tag[i], e.what());
    }

    if (!r.fully_molten && r.mass_melted > 0.0 && r.d < handover_d && d >= handover_d) {
      // melted below the handover diameter in this step (a grain created smaller stays): the
      // rest goes to the continuum as it is (mass, enthalpy m h, momentum), as the melt of a
      // grain that melted away
      r.mass_melted += r.m;
      r.enthalpy_out += r.m * r.h;
      r.m = r.d = 0.0;
      r.fully_molten = true;
    }
    ledger[0].add_difference(m, r.m);  // exact: the totals telescope to the initial mass
    ledger[1].add(r.enthalpy_out);
    double momentum[3];
    for (int k = 0; k < 3; k++) {
      momentum[k] = r.mass_melted * v[i][k];
      ledger[2 + k].add(momentum[k]);
    }
    ledger[5].add(r.heat);
    melt[i][HSPEC] = r.h;
    melt[i][I_MASS] += r.mass_melted;
    melt[i][I_ENTH] += r.enthalpy_out;
    for (int k = 0; k < 3; k++) melt[i][I_PX + k] += momentum[k];
    melt[i][I_HEAT] += r.heat;

    if (r.fully_molten) {
      // keep mass and radius until the atom is deleted at the next pre_exchange (the
      // integrator divides by them); it rests there, no force acts on it before
      melt[i][MOLTEN] = 1.0;
      coef[i][C_STATE] = 0.0;
      for (int k = 0; k < 3; k++) v[i][k] = f[i][k] = omega[i][k] = torque[i][k] = 0.0;
      nmolten++;
    } else if (r.mass_melted > 0.0) {
      rmass[i] = r.m;
      radius[i] = 0.5 * r.d;
      coef[i][C_STATE] = 0.0;
    }
    refresh_output(i);
  }

  int nmolten_all = 0;
  MPI_Allreduce(&nmolten, &nmolten_all, 1, MPI_INT, MPI_SUM, world);
  if (nmolten_all) next_reneighbor = update->ntimestep + 1;
  vector_dirty = 1;
}

/* ---------------------------------------------------------------------- */

void FixPowderMelt::refresh_output(int i)
{
  melt[i][TEMP] = mc::particle_temperature(mat, melt[i][HSPEC]);
  if (melt[i][MOLTEN] != 0.0)
    melt[i][FRAC] = 1.0;
  else
    melt[i][FRAC] = melt[i][MASS0] > 0.0 ? 1.0 - atom->rmass[i] / melt[i][MASS0] : 0.0;
  copy_output(i);
}

/* ---------------------------------------------------------------------- */

void FixPowderMelt::set_particle_temperature(int i, double T)
{
  if (i < 0 || i >= atom->nmax)
    error->one(FLERR, "Fix powder/melt: set_particle_temperature for invalid local index {}", i);
  if (!(T >= 0.0) || !(T <= mat.Tmelt))
    error->one(FLERR, "Fix powder/melt: particle temperature {} outside [0, Tmelt = {}]", T, mat.Tmelt);
  melt[i][HSPEC] = mc::specific_enthalpy(mat, T);
  melt[i][TEMP] = T;
  copy_output(i);
}

/* ----------------------------------------------------------------------
   [1] molten mass, [2] enthalpy, [3..5] momentum handed over, [6] heat absorbed
------------------------------------------------------------------------- */

double FixPowderMelt::compute_vector(int n)
{
  if (vector_dirty) {
    double local[12], all[12];
    for (int k = 0; k < 6; k++) {
      local[k] = ledger[k].hi();
      local[6 + k] = ledger[k].lo();
    }
    MPI_Allreduce(local, all, 12, MPI_DOUBLE, MPI_SUM, world);
    for (int k = 0; k < 6; k++) vector_all[k] = all[k] + all[6 + k];
    vector_dirty = 0;
  }
  return vector_all[n];
}

/* ----------------------------------------------------------------------
   the ledger survives restarts: totals over ranks go to rank 0 on reading
------------------------------------------------------------------------- */

void FixPowderMelt::write_restart(FILE *fp)
{
  double local[12], all[12];
  for (int k = 0; k < 6; k++) {
    local[k] = ledger[k].hi();
    local[6 + k] = ledger[k].lo();
  }
  MPI_Allreduce(local, all, 12, MPI_DOUBLE, MPI_SUM, world);
  if (comm->me == 0) {
    int size = 12 * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(all, sizeof(double), 12, fp);
  }
}

void FixPowderMelt::restart(char *buf)
{
  auto *list = (double *)buf;
  for (int k = 0; k < 6; k++) {
    if (comm->me == 0)
      ledger[k].set(list[k], list[6 + k]);
    else
      ledger[k].set(0.0, 0.0);
  }
  vector_dirty = 1;
}

/* ---------------------------------------------------------------------- */

void FixPowderMelt::grow_arrays(int nmax)
{
  memory->grow(melt, nmax, NCOL, "powder/melt:melt");
  memory->grow(output, nmax, NOUT, "powder/melt:output");
  memory->grow(held, nmax, NHELD, "powder/melt:held");
  memory->grow(coef, nmax, NCOEF, "powder/melt:coef");
  array_atom = output;
}

void FixPowderMelt::copy_arrays(int i, int j, int /*delflag*/)
{
  for (int k = 0; k < NCOL; k++) melt[j][k] = melt[i][k];
  for (int k = 0; k < NHELD; k++) held[j][k] = held[i][k];
  for (int k = 0; k < NCOEF; k++) coef[j][k] = coef[i][k];
  copy_output(j);
}

// new atoms start at temp T0; the initial mass is taken at the first step, after the
// creating command has set their size
void FixPowderMelt::set_arrays(int i)
{
  melt[i][TEMP] = T0;
  melt[i][FRAC] = 0.0;
  copy_output(i);
  melt[i][HSPEC] = mat.cp * T0;
  melt[i][MASS0] = 0.0;
  melt[i][MOLTEN] = 0.0;
  for (int k = S_OFFSET; k < NCOL; k++) melt[i][k] = 0.0;
  held[i][HELD_SET] = 0.0;
  held[i][HELD_BY] = -1.0;
  coef[i][C_STATE] = 0.0;
  coef[i][C_HEATED] = 0.0;
}

int FixPowderMelt::pack_exchange(int i, double *buf)
{
  for (int k = 0; k < NCOL; k++) buf[k] = melt[i][k];
  for (int k = 0; k < NHELD; k++) buf[NCOL + k] = held[i][k];
  for (int k = 0; k < NCOEF; k++) buf[NCOL + NHELD + k] = coef[i][k];
  return NCOL + NHELD + NCOEF;
}

int FixPowderMelt::unpack_exchange(int nlocal, double *buf)
{
  for (int k = 0; k < NCOL; k++) melt[nlocal][k] = buf[k];
  for (int k = 0; k < NHELD; k++) held[nlocal][k] = buf[NCOL + k];
  for (int k = 0; k < NCOEF; k++) coef[nlocal][k] = buf[NCOL + NHELD + k];
  copy_output(nlocal);
  return NCOL + NHELD + NCOEF;
}

int FixPowderMelt::pack_restart(int i, double *buf)
{
  // buf[0] = count, as other fixes read it to skip this fix's values; the held coefficients and
  // the fluid they were held for, so that a resumed run holds them as the uninterrupted one
  buf[0] = NCOL + NCOEF + NHELD + 1;
  for (int k = 0; k < NCOL; k++) buf[k + 1] = melt[i][k];
  for (int k = 0; k < NCOEF; k++) buf[NCOL + k + 1] = coef[i][k];
  for (int k = 0; k < NHELD; k++) buf[NCOL + NCOEF + k + 1] = held[i][k];
  return NCOL + NCOEF + NHELD + 1;
}

void FixPowderMelt::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  // restarts of earlier versions hold fewer (interval scratch) columns, which start at 0, and
  // no held coefficients, which are then evaluated again; those written before the
  // solid-contact mark hold the columns before it, then coefficients that are not read
  const int stored = static_cast<int>(extra[nlocal][m]) - 1;
  m++;
  const bool current = stored == NCOL + NCOEF + NHELD;
  const int columns = current ? NCOL : std::min(stored, static_cast<int>(NCOL_BEFORE_MARK));
  for (int k = 0; k < NCOL; k++) melt[nlocal][k] = k < columns ? extra[nlocal][m++] : 0.0;
  copy_output(nlocal);
  coef[nlocal][C_STATE] = 0.0;
  if (current) {
    for (int k = 0; k < NCOEF; k++) coef[nlocal][k] = extra[nlocal][m++];
    for (int k = 0; k < NHELD; k++) held[nlocal][k] = extra[nlocal][m++];
  }
}

int FixPowderMelt::size_restart(int /*nlocal*/)
{
  return NCOL + NCOEF + NHELD + 1;
}

int FixPowderMelt::maxsize_restart()
{
  return NCOL + NCOEF + NHELD + 1;
}

double FixPowderMelt::memory_usage()
{
  return (double)atom->nmax * (NCOL + NOUT + NHELD + NCOEF) * sizeof(double) +
         (double)tag_order.capacity() * sizeof(int) + (double)tag_rank.capacity() * sizeof(int) +
         (double)order_tags.capacity() * sizeof(tagint) + (double)step_heats.capacity() * sizeof(double);
}

/* ----------------------------------------------------------------------
   coupling interface: the interval's exchange per particle
------------------------------------------------------------------------- */

mc::ExchangeRecord FixPowderMelt::record(int i) const
{
  mc::ExchangeRecord r;
  fill_record(i, r);
  return r;
}

void FixPowderMelt::fill_record(int i, mc::ExchangeRecord &r) const
{
  const bool molten = melt[i][MOLTEN] != 0.0;
  r.id = atom->tag[i];
  r.x = Eigen::Vector3d(atom->x[i][0], atom->x[i][1], atom->x[i][2]);
  r.radius = atom->radius[i];  // the last solid radius, also once fully molten
  r.v = Eigen::Vector3d(atom->v[i][0], atom->v[i][1], atom->v[i][2]);
  r.h = melt[i][HSPEC];
  r.T = mc::particle_temperature(mat, r.h);
  r.mass = molten ? 0.0 : atom->rmass[i];
  r.mass_out = melt[i][I_MASS];
  r.enthalpy_out = melt[i][I_ENTH];
  r.momentum_out = Eigen::Vector3d(melt[i][I_PX], melt[i][I_PY], melt[i][I_PZ]);
  r.heat_absorbed = interval_value(i, I_HEAT);
  r.impulse_from_fluid = Eigen::Vector3d(interval_value(i, I_DX), interval_value(i, I_DY), interval_value(i, I_DZ));
  r.external_heat = melt[i][I_LASER];
  r.conductance = molten ? 0.0 : melt[i][COND];
  r.heat_capacity = r.mass * mat.cp;
  r.heat_owed = melt[i][OWED];
  if (held_flag && held[i][HELD_SET] != 0.0) {
    r.located_by = int(held[i][HELD_BY]);
    r.light = held[i][HELD_STATE + mc::kFluidStateHeatSource];
  } else {
    r.located_by = -1;
    r.light = 0.0;
  }
}

void FixPowderMelt::interval_records(std::vector<mc::ExchangeRecord> &out) const
{
  records(out, true);
}

void FixPowderMelt::current_records(std::vector<mc::ExchangeRecord> &out) const
{
  records(out, false);
}

void FixPowderMelt::records(std::vector<mc::ExchangeRecord> &out, bool with_finished) const
{
  // by ID: the coupling's sums then do not depend on LAMMPS's atom order, which a sort or
  // a restart changes (a resumed run equals the uninterrupted one bit for bit)
  const std::vector<int> &order = local_order_by_tag();
  if (!with_finished || finished.empty()) {
    // the atoms read in slot order, each record written to its place by tag (every place
    // once: the records already there are overwritten, not made afresh)
    out.resize(order.size());
    for (int i = 0; i < atom->nlocal; i++)
      if (tag_rank[std::size_t(i)] >= 0) fill_record(i, out[std::size_t(tag_rank[std::size_t(i)])]);
    return;
  }
  out.clear();
  std::vector<std::pair<tagint, int>> gone;  // -1 - k: finished record k, by tag
  for (std::size_t k = 0; k < finished.size(); ++k) gone.emplace_back(tagint(finished[k].id), -1 - int(k));
  std::sort(gone.begin(), gone.end());
  out.reserve(order.size() + gone.size());
  auto g = gone.cbegin();
  for (const int i : order) {
    for (; g != gone.cend() && g->first < atom->tag[i]; ++g) out.push_back(finished[std::size_t(-1 - g->second)]);
    out.push_back(record(i));
  }
  for (; g != gone.cend(); ++g) out.push_back(finished[std::size_t(-1 - g->second)]);
}

const std::vector<int> &FixPowderMelt::local_order_by_tag() const
{
  // the last order still holds while every local slot holds the atom it held then (the
  // same tag, in or out of the group): one pass in slot order
  const tagint *tag = atom->tag;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  bool valid = order_tags.size() == std::size_t(nlocal);
  for (int i = 0; valid && i < nlocal; i++) valid = order_tags[std::size_t(i)] == ((mask[i] & groupbit) ? tag[i] : -1);
  if (valid) return tag_order;
  std::vector<std::pair<tagint, int>> by_tag;
  order_tags.assign(std::size_t(nlocal), -1);
  tag_rank.assign(std::size_t(nlocal), -1);
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) by_tag.emplace_back(tag[i], i), order_tags[std::size_t(i)] = tag[i];
  std::sort(by_tag.begin(), by_tag.end());
  tag_order.clear();
  for (const auto &t : by_tag) {
    tag_rank[std::size_t(t.second)] = int(tag_order.size());
    tag_order.push_back(t.second);
  }
  return tag_order;
}

void FixPowderMelt::reset_interval()
{
  finished.clear();
  for (int i = 0; i < atom->nlocal; i++) {
    for (int k = I_MASS; k <= P_T; k++) melt[i][k] = 0.0;
    double *c = coef[i];
    if (c[C_STATE] != 1.0) continue;
    // held: the parcel starts at the fluid's velocity and temperature, the interval's sums at 0
    // (parcel_state at the first step, as for a particle not held)
    const double *q = &held[i][HELD_STATE];
    mc::FluidState fluid;
    mc::unpack_fluid_state(q, fluid);
    for (int k = 0; k < 3; k++) c[C_PUX + k] = fluid.U[k], c[C_IDX + k] = 0.0;
    c[C_PT] = fluid.T;
    c[C_IHEAT] = 0.0;
    melt[i][P_SET] = 1.0;
  }
}

void FixPowderMelt::set_heat_owed(const std::vector<tagint> &tags, const std::vector<double> &heat)
{
  if (tags.size() != heat.size()) error->one(FLERR, "Fix powder/melt: set_heat_owed needs one heat per tag");
  const std::vector<int> slot = local_slots(tags);
  std::size_t missing = 0;
  for (std::size_t k = 0; k < tags.size(); ++k) {
    if (slot[k] < 0) {
      ++missing;
      continue;
    }
    melt[slot[k]][OWED] += heat[k];
  }
  if (missing)
    error->one(FLERR, "Fix powder/melt: {} of {} particles given heat are not on this rank", missing, tags.size());
}

std::vector<int> FixPowderMelt::local_slots(const std::vector<tagint> &tags) const
{
  // through the atom map where there is one and it is current, else through a map of the tags
  std::vector<int> slot(tags.size(), -1);
  bool mapped = atom->map_style != Atom::MAP_NONE;
  for (std::size_t k = 0; mapped && k < tags.size(); ++k) {
    const int i = atom->map(tags[k]);
    if (i < 0 || i >= atom->nlocal) continue;
    mapped = atom->tag[i] == tags[k];
    slot[k] = i;
  }
  if (mapped) return slot;
  std::fill(slot.begin(), slot.end(), -1);
  std::unordered_map<tagint, int> at;
  at.reserve(std::size_t(atom->nlocal));
  for (int i = 0; i < atom->nlocal; i++) at[atom->tag[i]] = i;
  for (std::size_t k = 0; k < tags.size(); ++k) {
    const auto it = at.find(tags[k]);
    if (it != at.end()) slot[k] = it->second;
  }
  return slot;
}

bigint FixPowderMelt::remove_particles(const std::vector<tagint> &tags)
{
  return delete_local([&](int i) { return std::binary_search(tags.begin(), tags.end(), atom->tag[i]); });
}
