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
#include "meltdem/coupling/particle_melting.h"

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

  // What particle i (local index) handed over / absorbed during the last step; the
  // coupling distributes these to cells. Valid after end_of_step until the next step.
  struct StepExchange {
    double mass = 0.0;                     // molten mass [kg] (eq. 2.3)
    double enthalpy = 0.0;                 // enthalpy with it [J] (eq. 2.9)
    double momentum[3] = {0.0, 0.0, 0.0};  // momentum with it [kg m/s] (eq. 2.11)
    double heat = 0.0;                     // heat absorbed from the fluid [J] (eq. 2.13)
    double drag[3] = {0.0, 0.0, 0.0};      // drag force of this step [N] (eq. 2.14)
  };
  const StepExchange *step_exchange() const { return exchange; }

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
  // intervals
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
    NCOL
  };
  std::vector<meltdem::coupling::ExchangeRecord> finished;  // deleted this interval
  meltdem::coupling::ExchangeRecord record(int i) const;
  void records(std::vector<meltdem::coupling::ExchangeRecord> &out, bool with_finished) const;
  meltdem::coupling::MeltMaterial mat;
  meltdem::coupling::DragModel drag_model;
  double T0;
  int ambient_flag;
  std::unique_ptr<meltdem::coupling::UniformFluid> ambient;
  const meltdem::coupling::FluidStateProvider *provider;
  int in_setup;
  int solid_flag;  // solid_metal keyword: the continuum's solid metal is a wall
  double solid_estar, solid_alpha;

  // per-atom fluid held for the interval (hold_fluid): HELD_SET 1 when held, HELD_BY the rank
  // that located it, then the packed FluidState
  enum { HELD_SET, HELD_BY, HELD_STATE, NHELD = HELD_STATE + meltdem::coupling::kFluidStateDoubles };
  double **held;
  int held_flag;
  // the fluid particle i sees this step (held or from the provider); false: none
  bool fluid_at(int i, meltdem::coupling::FluidState &out) const;

  double **melt;           // per-atom state, columns above
  StepExchange *exchange;  // per-atom exchange of the last step
  int nmax_exchange;

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
