/* -*- c++ -*- ----------------------------------------------------------
   MeltDEM: fix powder/melt -- heating, drag, buoyancy and melting of particles
   (Codina2019 eq. 2.3, 2.9, 2.11, 2.13, 2.14). The physics lives in coupling/.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
// no trailing semicolon: meltdem_styles.cpp expands this inside an array initializer
FixStyle(powder/melt,FixPowderMelt)
// clang-format on
#else

#ifndef MELTDEM_FIX_POWDER_MELT_H
#define MELTDEM_FIX_POWDER_MELT_H

#include "fix.h"

#include "meltdem/coupling/drag.h"
#include "meltdem/coupling/exchange_record.h"
#include "meltdem/coupling/exact_sum.h"
#include "meltdem/coupling/fluid_state.h"
#include "meltdem/coupling/held_exchange.h"
#include "meltdem/coupling/particle_melting.h"

#include <algorithm>
#include <functional>
#include <memory>
#include <vector>

namespace LAMMPS_NS {

class FixPowderMelt : public Fix {
 public:
  FixPowderMelt(class LAMMPS *, int, char **);
  ~FixPowderMelt() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void setup_pre_exchange() override;
  void pre_exchange() override;
  void post_force(int) override;
  void end_of_step() override;

  double compute_vector(int) override;
  double memory_usage() override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

  // called by fix powder/insert for its 'temp' keyword: 0 <= T <= Tmelt
  void set_particle_temperature(int i, double T);

  // The coupling's fluid for one interval: the local particles with these tags (ascending)
  // see these states until the next call, also after moving to another rank (the state
  // travels with the atom), and their records name located_by as the rank that gave it.
  // Particles not listed see no fluid. From the first call on the fix reads no provider.
  void hold_fluid(const std::vector<tagint> &tags, const std::vector<meltdem::coupling::FluidState> &states,
                  int located_by);

  // The coupling's view over a coupling interval of several steps (sub-cycles): what each
  // particle handed over and took from the fluid since the last reset_interval(), one
  // record per particle of the group now present on this rank plus one per particle
  // deleted as fully molten during the interval (mass 0). Records carry the particle's
  // state now (position, radius, velocity, T, h; mass 0 once fully molten).
  void interval_records(std::vector<meltdem::coupling::ExchangeRecord> &out) const;
  // the same for the particles present now only (without those deleted this interval): one
  // per tag (a tag LAMMPS gave again to a new particle is not also a deleted one's)
  void current_records(std::vector<meltdem::coupling::ExchangeRecord> &out) const;
  void reset_interval();
  // implicit heat exchange: the heat [J] the continuum's energy solve gave each listed local
  // particle (by tag), taken at the start of the next interval
  void set_heat_owed(const std::vector<tagint> &tags, const std::vector<double> &heat);
  // remove the local particles whose tag is in `tags` (sorted) now, between runs, e.g.
  // particles that left the continuum's mesh; collective; returns the global count
  bigint remove_particles(const std::vector<tagint> &tags);
  const meltdem::coupling::MeltMaterial &material() const { return mat; }
  bool solid_metal_wall() const { return solid_flag != 0; }
  // the temperature new particles start at (keyword temp) [K]
  double initial_temperature() const { return T0; }
  // the gravity the particles feel: the sum of the fix gravity vectors (as of the last init)
  const double *gravity(double *g) const;

 private:
  // per-atom columns; dumps see TEMP and FRAC. MOLTEN = 1: fully molten, booked, removed
  // at the next step's pre_exchange. I_* accumulate over the coupling interval: molten
  // mass, enthalpy and momentum handed over, heat absorbed, drag impulse, laser energy
  // P_*: the velocity and temperature of the fluid parcel the particle exchanges momentum
  // and heat with over the coupling interval (two bodies; P_SET 0: not yet taken from the
  // fluid this interval). Implicit heat exchange: OWED, the heat the energy solve gave it, not
  // yet taken; COND, its conductance k Nu pi d at its last step [W/K]. S_*: the
  // particle's memory of its solid-metal contact (mc::SolidContactMemory), kept across
  // intervals (S_HAS_MARK, S_M*: its centre at the first step of the last interval)
  enum {
    TEMP,
    FRAC,
    HSPEC,
    MASS0,
    MOLTEN,
    S_OFFSET,
    S_HAS,
    S_PX,
    S_PY,
    S_PZ,
    S_NX,
    S_NY,
    S_NZ,
    I_MASS,
    I_ENTH,
    I_PX,
    I_PY,
    I_PZ,
    I_HEAT,
    I_DX,
    I_DY,
    I_DZ,
    I_LASER,
    P_UX,
    P_UY,
    P_UZ,
    P_SET,
    P_T,
    OWED,
    COND,
    S_HAS_MARK,
    S_MX,
    S_MY,
    S_MZ,
    NCOL
  };
  // the columns before the solid-contact mark: restarts written before it hold these
  static constexpr int NCOL_BEFORE_MARK = S_HAS_MARK;
  meltdem::coupling::SolidContactMemory contact_memory(int i) const;
  void store_contact_memory(int i, const meltdem::coupling::SolidContactMemory &m);
  std::vector<meltdem::coupling::ExchangeRecord> finished;  // deleted this interval
  meltdem::coupling::ExchangeRecord record(int i) const;
  // the same written into r (every field: a reused record keeps nothing of its old value)
  void fill_record(int i, meltdem::coupling::ExchangeRecord &r) const;
  void records(std::vector<meltdem::coupling::ExchangeRecord> &out, bool with_finished) const;
  // the local slot of each tag, -1 where it is not a local atom of this rank
  std::vector<int> local_slots(const std::vector<tagint> &tags) const;
  // the local atoms of the group by ascending tag (kept while LAMMPS moves no atom)
  const std::vector<int> &local_order_by_tag() const;
  mutable std::vector<int> tag_order;
  mutable std::vector<tagint> order_tags;  // per local slot, its tag when tag_order was made (-1: not in the group)
  mutable std::vector<int> tag_rank;       // per local slot, its index in tag_order (-1: not in the group)
  meltdem::coupling::MeltMaterial mat;
  meltdem::coupling::DragModel drag_model;
  double T0;
  int ambient_flag;
  std::unique_ptr<meltdem::coupling::UniformFluid> ambient;
  const meltdem::coupling::FluidStateProvider *provider;
  int in_setup;
  int solid_flag;  // solid_metal keyword: the continuum's solid metal is a wall
  double solid_estar, solid_alpha;
  int interval_start;  // set by hold_fluid: the next steps' forces are the interval's first
  double handover_d;   // keyword handover: a grain melting below this diameter goes to the continuum whole

  // per-atom fluid held for the interval (hold_fluid): HELD_SET 1 when held, HELD_BY the rank
  // that located it, then the packed FluidState
  enum { HELD_SET, HELD_BY, HELD_STATE, NHELD = HELD_STATE + meltdem::coupling::kFluidStateDoubles };
  double **held;
  int held_flag;
  // the fluid particle i sees this step (held or from the provider); false: none
  bool fluid_at(int i, meltdem::coupling::FluidState &out) const;

  double **melt;  // per-atom state, columns above
  // the per-atom output (array_atom): TEMP and FRAC, a copy in an array of exactly its two
  // columns, as LAMMPS reads F_ID[I][J] with the stride size_peratom_cols
  enum { NOUT = 2 };
  double **output;
  inline void copy_output(int i)
  {
    output[i][0] = melt[i][TEMP];
    output[i][1] = melt[i][FRAC];
  }

  // per-atom exchange coefficients held over the sub-steps of an interval
  // (meltdem/coupling/held_exchange.h); they travel with the atom and are in restart files, so
  // a run does not depend on the rank count or on a restart. C_STATE 0: to evaluate, 1: held, 2: evaluated
  // every step (light, solid-metal contact, implicit heat). Then the drag coefficient and the
  // heat step's expm1 as lines in the root of the slip speed (C_Y0, value, slope), their
  // window of slip^2, the two-body cap of the drag coefficient, the buoyancy volume term
  // -rho pi d^3/6, dt over the parcel's mass, the parcel's heat capacity, the heat share (0: no
  // heat this interval, also where particle and parcel start equally warm), and the diameter
  // and step they hold for. While held, the
  // columns a held step changes live here (C_PUX.. = P_UX.., C_PT = P_T, C_IDX.. = I_DX..,
  // C_IHEAT = I_HEAT) and go back to melt when released (release()), so a held step reads and
  // writes three cache lines of this row and one of melt. C_HEATED 1: post_force took this
  // step's held heat step (written by every post_force of a run, read by end_of_step)
  enum {
    C_STATE,
    C_D,
    C_DT,
    C_SHARE,
    C_LO,
    C_HI,
    C_Y0,
    C_BETA0,
    C_BETA1,
    C_CAP,
    C_VB,
    C_DTMF,
    C_PUX,
    C_PUY,
    C_PUZ,
    C_IDX,
    C_IDY,
    C_IDZ,
    C_E10,
    C_E11,
    C_CF,
    C_PT,
    C_IHEAT,
    C_HEATED,
    NCOEF
  };
  double **coef;
  std::vector<double> step_heats;  // this step's held heat steps' heats, summed after the loop
  int heated_nlocal;               // nlocal where post_force took every particle's held step this step, else -1
  double coef_tol;                 // keyword coefficient_tolerance (0: every step; default 0.01)
  // evaluate particle i's coefficients for the fluid it sees (after parcel_state) and step dt;
  // returns its squared slip, or -1 where it is evaluated every step
  double hold_coefficients(int i, const meltdem::coupling::FluidState &fluid, double dt);
  // particle i's held coefficients are valid for this step: its size and dt unchanged (the
  // fix invalidates them when it melts mass away)
  // (inline: a style library is built with -fPIC, where out-of-line members are not inlined)
  inline bool holds(int i, const double *radius, double dt) const
  {
    const double *c = coef[i];
    return c[C_STATE] == 1.0 && c[C_D] == 2.0 * radius[i] && c[C_DT] == dt;
  }
  // give the held columns back to melt; the coefficients are evaluated again at the next use
  inline void release(int i)
  {
    double *c = coef[i];
    if (c[C_STATE] == 1.0) {
      for (int k = 0; k < 3; k++) {
        melt[i][P_UX + k] = c[C_PUX + k];
        melt[i][I_DX + k] = c[C_IDX + k];
      }
      melt[i][P_T] = c[C_PT];
      melt[i][I_HEAT] = c[C_IHEAT];
      melt[i][P_SET] = 1.0;  // the parcel was taken this interval
    }
    c[C_STATE] = 0.0;
  }
  void release_all()
  {
    for (int i = 0; i < atom_nlocal(); i++) release(i);
  }
  int atom_nlocal() const;
  // the held fluid states q and p give the same held coefficients: they differ at most in the
  // fluid's velocity and temperature, which only start the parcel
  static bool same_coefficients(const double *q, const double *p);
  // column col (P_* or I_*) of particle i, wherever it lives now
  double interval_value(int i, int col) const;
  // the held drag coefficient of particle i at squared slip s2 (inside its window): the line in
  // y = s^(1/2), at most the two-body cap
  inline double held_drag_coefficient(int i, double s2) const
  {
    const double *c = coef[i];
    const double y = c[C_BETA1] == 0.0 ? c[C_Y0] : meltdem::coupling::held_variable(s2);
    return held_drag_at(c, y);
  }
  // the same at y = s^(1/2) (any finite y where the slope is 0)
  static inline double held_drag_at(const double *c, double y)
  {
    return std::min(c[C_BETA0] + c[C_BETA1] * (y - c[C_Y0]), c[C_CAP]);
  }
  // particle i's (mass m) held heat step at y = s^(1/2) (the sensible heat step of
  // heat_melt_step(_two_body) while it stays below melting), its heat appended at *heats; false
  // where the step would reach melting (the full step takes it then)
  inline bool held_heat_step(int i, double m, double y, double *&heats)
  {
    double *c = coef[i];
    const double h = melt[i][HSPEC];
    const double T = melt[i][TEMP], D0 = c[C_PT] - T;
    if (D0 == 0.0) return true;
    const double T_new = T - c[C_SHARE] * D0 * (c[C_E10] + c[C_E11] * (y - c[C_Y0]));
    const double h_new = mat.cp * T_new;
    const double hm = mat.cp * mat.Tmelt;
    if (!(h < hm && h_new < hm)) return false;
    const double heat = m * (h_new - h);
    if (c[C_CF] > 0.0) c[C_PT] -= heat / c[C_CF];
    *heats++ = heat;
    melt[i][HSPEC] = h_new;
    c[C_IHEAT] += heat;
    melt[i][TEMP] = output[i][0] = T_new;  // below melting
    return true;
  }
  // the squared slip of particle i (velocity v) against its parcel; negative when outside the
  // held window
  inline double held_slip2(int i, const double *v) const
  {
    const double *p = &coef[i][C_PUX];
    const double s0 = p[0] - v[0], s1 = p[1] - v[1], s2 = p[2] - v[2];
    const double s = s0 * s0 + s1 * s1 + s2 * s2;
    return s >= coef[i][C_LO] && s <= coef[i][C_HI] ? s : -1.0;
  }

  // cumulative ledger (this rank): molten mass, enthalpy, momentum x/y/z, heat absorbed
  meltdem::coupling::ExactSum ledger[6];
  double vector_all[6];
  int vector_dirty;

  std::vector<int> gravity_fixes;

  void refresh_output(int i);
  // the fluid velocity the particle drags: its parcel's (taken from fluid at the first
  // use in a coupling interval) when the fluid has a parcel mass
  void parcel_state(int i, meltdem::coupling::FluidState &fluid);
  int delete_molten();
  bigint delete_local(const std::function<bool(int)> &doomed);
};

}  // namespace LAMMPS_NS

#endif
#endif
