/* ----------------------------------------------------------------------
   MeltDEM: fix wall/gran/region/powder (see fix_wall_gran_region_powder.h,
   doc/fix_wall_gran_powder.rst). Argument handling is fix wall/gran/powder's.
------------------------------------------------------------------------- */

#include "fix_wall_gran_region_powder.h"

#include "lammps_api.h"
#include "atom.h"
#include "domain.h"
#include "region.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

FixWallGranRegionPowder::FixWallGranRegionPowder(LAMMPS *lmp, WallGranPowderArgs &&a) :
    FixWallGranRegion(lmp, a.narg(), a.arg()), coeffs(a.coeffs)
{
#if MELTDEM_LAMMPS_2025_API
  coeffs.apply_material(model);
  coeffs.apply_damping(model, lmp);
#else
  coeffs.apply_material(normal_coeffs, tangential_coeffs);
#endif
}

void FixWallGranRegionPowder::init()
{
  FixWallGranRegion::init();
#if !MELTDEM_LAMMPS_2025_API
  coeffs.apply_damping(normal_coeffs);
#endif
  coeffs.find_step_fix(lmp);
}

void FixWallGranRegionPowder::post_force(int vflag)
{
  FixWallGranRegion::post_force(vflag);
  if (coeffs.damping != WallGranPowderCoeffs::DAMP_TSUJI_EXACT || coeffs.e <= 0.0) return;

  // the stock region contacts (fix_wall_gran_region.cpp post_force), searched one step's
  // travel further out so that a particle that has just left gets its last damping kick
  double **x = atom->x, **v = atom->v, **f = atom->f;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *mask = atom->mask;
  const double speed = coeffs.contact_speed(), step = update->dt;
  const double speed_factor = speed > 0.0 ? step * pow(speed, 0.2) : 0.0;
  Region *region = meltdem::lammps_api::region(domain, idregion);
  if (!region) return;  // the stock fix has already stopped on a missing region
  const int dynamic = region->dynamic_check();
#if MELTDEM_LAMMPS_2025_API
  const double kn = coeffs.stiffness(model), alpha_continuous = coeffs.alpha;
#else
  const double kn = normal_coeffs[0], alpha_continuous = normal_coeffs[1];
#endif
  double vwall[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (!region->match(x[i][0], x[i][1], x[i][2])) continue;
    const double vmag = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    const int nc = region->surface(x[i][0], x[i][1], x[i][2], radius[i] + step * vmag);
    for (int ic = 0; ic < nc; ic++) {
      const double r = region->contact[ic].r;
      if (!(r > 0.0)) continue;
      const double n[3] = {region->contact[ic].delx / r, region->contact[ic].dely / r, region->contact[ic].delz / r};
      if (dynamic) region->velocity_contact(vwall, x[i], ic);
      const double rate = (v[i][0] - vwall[0]) * n[0] + (v[i][1] - vwall[1]) * n[1] + (v[i][2] - vwall[2]) * n[2];
      const double rwall = region->contact[ic].radius;
      const double reff = rwall == 0.0 ? radius[i] : radius[i] * rwall / (radius[i] + rwall);
      double meff = rmass[i];
      if (fix_rigid && mass_rigid[i] > 0.0) meff = mass_rigid[i];
      const double fn =
          coeffs.damping_correction(kn, alpha_continuous, radius[i] - r, rate, reff, meff, step, speed_factor);
      for (int k = 0; k < 3; k++) f[i][k] += n[k] * fn;
    }
  }
}
