/* ----------------------------------------------------------------------
   MeltDEM: fix wall/gran/region/powder (see fix_wall_gran_region_powder.h,
   doc/fix_wall_gran_powder.rst). Argument handling is fix wall/gran/powder's.
------------------------------------------------------------------------- */

#include "fix_wall_gran_region_powder.h"

using namespace LAMMPS_NS;

FixWallGranRegionPowder::FixWallGranRegionPowder(LAMMPS *lmp, WallGranPowderArgs &&a) :
    FixWallGranRegion(lmp, a.narg(), a.arg()), coeffs(a.coeffs)
{
  coeffs.apply_material(normal_coeffs, tangential_coeffs);
}

void FixWallGranRegionPowder::init()
{
  FixWallGranRegion::init();
  coeffs.apply_damping(normal_coeffs);
}
