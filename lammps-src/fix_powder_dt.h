/* -*- c++ -*- ----------------------------------------------------------
   MeltDEM: fix powder/dt -- DEM time step from the Hertz contact time
   (Codina2019 eq. 3.1-3.4). The physics lives in coupling/dem_step_control.h.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
// no trailing semicolon: meltdem_styles.cpp expands this inside an array initializer
FixStyle(powder/dt,FixPowderDt)
// clang-format on
#else

#ifndef MELTDEM_FIX_POWDER_DT_H
#define MELTDEM_FIX_POWDER_DT_H

#include "fix.h"

namespace LAMMPS_NS {

class FixPowderDt : public Fix {
 public:
  FixPowderDt(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  double compute_vector(int) override;
  // approach speed U of the current step (m/s; 0 before the first particle)
  double approach_speed() const { return out[4]; }
  // a coupling sub-cycle's step: the step set is at most this (0: none; clearing it sets the
  // step this fix computed)
  void set_step_ceiling(double dt_ceiling);

 private:
  double steps;          // collisionResolutionSteps S
  double dtmax;          // cap on dt (0: none)
  double interval;       // coupling interval for the sub-cycle count (0: none)
  double vfloor;         // floor of the approach speed [m/s]
  double maxoverlap;     // largest head-on overlap / radius allowed (Hertz validity)
  double estar;          // largest E* of the pair style's type pairs [Pa]
  double uhold, thold;   // held approach speed and the time it was recorded
  double ceiling = 0.0;  // the coupling sub-cycle's step while it runs (0: none)
  int respaflag;
  // output: dt, t_contact, sub-cycles, R_min, U used, E*, rho used
  double out[7] = {};

  void read_pair_modulus();
  void update_dt();
  void apply_dt(double dt);
};

}  // namespace LAMMPS_NS

#endif
#endif
