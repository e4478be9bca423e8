#include "meltdem/coupling/hertz_contact.h"

#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

double effective_modulus(double E1, double nu1, double E2, double nu2)
{
  if (!(E1 > 0.0) || !(E2 > 0.0)) throw std::invalid_argument("Young's modulus must be > 0");
  // (-1, 0.5]: 0.5 is the incompressible limit, a valid Hertz contact
  if (!(nu1 > -1.0 && nu1 <= 0.5) || !(nu2 > -1.0 && nu2 <= 0.5))
    throw std::invalid_argument("Poisson ratio must lie in (-1, 0.5]");
  return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
}

double harmonic_pair(double x1, double x2)
{
  if (!(x1 > 0.0) || !(x2 > 0.0)) throw std::invalid_argument("pair quantity must be > 0");
  return 1.0 / (1.0 / x1 + 1.0 / x2);
}

double hertz_contact_time(double m_eff, double R_eff, double E_eff, double U_rel)
{
  if (!(m_eff > 0.0) || !(R_eff > 0.0) || !(E_eff > 0.0) || !(U_rel > 0.0))
    throw std::invalid_argument("Hertz contact time needs m*, R*, E*, U_rel > 0");
  return 2.87 * std::pow(m_eff * m_eff / (R_eff * E_eff * E_eff * U_rel), 0.2);
}

double hertz_contact_time_equal_spheres(double R, double rho, double E_eff, double U_rel)
{
  const double m = 4.0 / 3.0 * M_PI * R * R * R * rho;
  return hertz_contact_time(0.5 * m, 0.5 * R, E_eff, U_rel);
}

double dem_timestep(double t_contact, double collision_resolution_steps)
{
  if (!(collision_resolution_steps > 0.0)) throw std::invalid_argument("collision resolution steps must be > 0");
  return t_contact / collision_resolution_steps;
}

long dem_subcycles(double dt_step, double dt_dem)
{
  if (!(dt_step > 0.0) || !(dt_dem > 0.0)) throw std::invalid_argument("time steps must be > 0");
  // a ratio within round-off of an integer must not add a cycle
  const double n = dt_step / dt_dem;
  const double nr = std::round(n);
  if (std::abs(n - nr) <= 1e-9 * n) return nr < 1.0 ? 1 : static_cast<long>(nr);
  return static_cast<long>(std::ceil(n));
}

}  // namespace meltdem::coupling
