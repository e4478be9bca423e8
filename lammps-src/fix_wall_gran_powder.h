/* -*- c++ -*- ----------------------------------------------------------
   MeltDEM: fix wall/gran/powder -- stock fix wall/gran (granular) with the
   particle-wall E* of Hertz theory and the exact Tsuji e -> alpha map
   (coupling/hertz_restitution.h), as pair_style granular/powder does for pairs.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
// no trailing semicolon: meltdem_styles.cpp expands this inside an array initializer
FixStyle(wall/gran/powder,FixWallGranPowder)
// clang-format on
#else

#ifndef MELTDEM_FIX_WALL_GRAN_POWDER_H
#define MELTDEM_FIX_WALL_GRAN_POWDER_H

#include "fix_wall_gran.h"
#include "lammps_api.h"

#include "meltdem/coupling/stepped_restitution.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

// What the powder wall fixes change in the stock coefficients (shared with
// fix wall/gran/region/powder).
struct WallGranPowderCoeffs {
  enum { DAMP_STOCK, DAMP_TSUJI_EXACT, DAMP_TSUJI_ALPHA };
  int damping = DAMP_STOCK;
  double alpha = 0.0;             // Tsuji alpha (Codina2019 eq. 3.5) for both tsuji forms
  bool material = false;          // normal model hertz/material, dmt or jkr: kn from E*
  double kn = 0.0;                // 4/3 E*, E* of particle and wall (the pair style's form)
  bool kt_from_material = false;  // mindlin tangential with kt NULL
  double kt = 0.0;                // 8 G*, G* of particle and wall

  double e = 0.0;  // prescribed e of 'damping tsuji' with stepped damping (0: none; jkr damps as the stock)
  meltdem::coupling::SteppedAlphaTable stepped;  // its alpha at each contact step
  double impact_speed = 0.0;                     // keyword impact_speed (m/s), 0: none

#if MELTDEM_LAMMPS_2025_API
  // set the coefficients on the stock fix's granular model (2023+ API)
  void apply_material(class Granular_NS::GranularModel *model) const;
  void apply_damping(class Granular_NS::GranularModel *model, class LAMMPS *lmp) const;
  // the Hertz stiffness factor and the continuous alpha the stepped damping corrects
  double stiffness(const class Granular_NS::GranularModel *model) const;
#else
  // copy the coefficients into a stock fix's protected arrays
  void apply_material(double *normal_coeffs, double *tangential_coeffs) const;
  void apply_damping(double *normal_coeffs) const;
#endif
  class FixPowderDt *fix_dt = nullptr;  // the step's approach speed, when there is one (set in init)
  // find fix powder/dt (at each init: fixes come and go between runs)
  void find_step_fix(class LAMMPS *lmp);
  // the speed a wall contact's step is calibrated at: the largest particle speed of fix
  // powder/dt (half its pair approach speed), else impact_speed; 0: none
  double contact_speed() const;
  // the force 'damping tsuji' adds along the wall normal to the stock contact (see
  // stepped_restitution.h); 0 for the other damping forms. speed_factor: dt speed^(1/5) of
  // the step (0: no calibration speed)
  // kn: the Hertz stiffness factor (F = kn sqrt(R delta) delta), alpha_continuous: the stock alpha
  double damping_correction(double kn, double alpha_continuous, double delta, double separation_rate, double reff,
                            double meff, double dt, double speed_factor) const;

 private:
  mutable meltdem::coupling::ContactStepMemo contact_step;  // (its pow kept between contacts)
};

// Reads the keywords the powder wall fixes add to 'fix wall/gran granular ...'
// (damping tsuji/alpha A, wall_material Ew nuw | rigid), checks the arguments the
// stock parser would read past the end of, and holds the argument list handed on to
// the stock constructor.
class WallGranPowderArgs {
 public:
  WallGranPowderArgs(class LAMMPS *lmp, int narg, char **arg, bool region_wall);
  int narg() { return (int)argv.size(); }
  char **arg() { return argv.data(); }
  WallGranPowderCoeffs coeffs;

 private:
  std::vector<std::string> words;
  std::vector<char *> argv;
};

class FixWallGranPowder : public FixWallGran {
 public:
  FixWallGranPowder(class LAMMPS *lmp, int narg, char **arg) :
      FixWallGranPowder(lmp, WallGranPowderArgs(lmp, narg, arg, false))
  {
  }
  void init() override;
  void post_force(int) override;

 private:
  // the temporary argument list lives until this constructor returns
  FixWallGranPowder(class LAMMPS *lmp, WallGranPowderArgs &&a);
  WallGranPowderCoeffs coeffs;
};

}  // namespace LAMMPS_NS

#endif
#endif
