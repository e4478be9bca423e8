/* -*- c++ -*- ----------------------------------------------------------
   MeltDEM: fix wall/gran/region/powder -- stock fix wall/gran/region with the
   coefficient handling of fix wall/gran/powder (particle-wall E*, exact Tsuji map).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
// no trailing semicolon: meltdem_styles.cpp expands this inside an array initializer
FixStyle(wall/gran/region/powder,FixWallGranRegionPowder)
// clang-format on
#else

#ifndef MELTDEM_FIX_WALL_GRAN_REGION_POWDER_H
#define MELTDEM_FIX_WALL_GRAN_REGION_POWDER_H

#include "fix_wall_gran_powder.h"
#include "fix_wall_gran_region.h"

namespace LAMMPS_NS {

class FixWallGranRegionPowder : public FixWallGranRegion {
 public:
  FixWallGranRegionPowder(class LAMMPS *lmp, int narg, char **arg) :
      FixWallGranRegionPowder(lmp, WallGranPowderArgs(lmp, narg, arg, true))
  {
  }
  void init() override;
  void post_force(int) override;

 private:
  // the temporary argument list lives until this constructor returns
  FixWallGranRegionPowder(class LAMMPS *lmp, WallGranPowderArgs &&a);
  WallGranPowderCoeffs coeffs;
};

}  // namespace LAMMPS_NS

#endif
#endif
