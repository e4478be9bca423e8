#include "meltdem/coupling/dem_step_control.h"

#include "meltdem/coupling/hertz_contact.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

double approach_speed_bound(double v_max, double floor)
{
  if (!(v_max >= 0.0)) throw std::invalid_argument("largest particle speed must be >= 0");
  if (!(floor > 0.0)) throw std::invalid_argument("speed floor must be > 0");
  return std::max(2.0 * v_max, floor);
}

double shortest_contact_time(double R_min, double rho_min, double E_eff_max, double U)
{
  if (!(R_min > 0.0) || !(rho_min > 0.0) || !(E_eff_max > 0.0) || !(U > 0.0))
    throw std::invalid_argument("shortest contact time needs R, rho, E*, U > 0");
  return hertz_contact_time_equal_spheres(R_min, rho_min, E_eff_max, U);
}

double head_on_overlap_ratio(double rho, double E_eff, double U)
{
  if (!(rho > 0.0) || !(E_eff > 0.0) || !(U >= 0.0))
    throw std::invalid_argument("head-on overlap needs rho, E* > 0 and U >= 0");
  return std::pow(10.0 * M_PI * std::sqrt(2.0) / 16.0 * rho * U * U / E_eff, 0.4);
}

double overlap_ratio(double distance, double R1, double R2)
{
  if (!(R1 > 0.0) || !(R2 > 0.0)) throw std::invalid_argument("radii must be > 0");
  const double delta = R1 + R2 - distance;
  return delta > 0.0 ? delta / std::min(R1, R2) : 0.0;
}

double wall_overlap_ratio(double distance, double R)
{
  if (!(R > 0.0)) throw std::invalid_argument("radius must be > 0");
  const double delta = R - distance;
  return delta > 0.0 ? delta / R : 0.0;
}

}  // namespace meltdem::coupling
