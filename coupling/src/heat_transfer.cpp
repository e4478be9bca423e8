#include "meltdem/coupling/heat_transfer.h"

#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

double ranz_marshall_nusselt(double Re, double Pr)
{
  if (!(Re >= 0.0) || !(Pr > 0.0)) throw std::invalid_argument("Ranz-Marshall needs Re >= 0, Pr > 0");
  return 2.0 + 0.6 * std::sqrt(Re) * std::cbrt(Pr);
}

double prandtl_number(double cp, double mu, double k)
{
  if (!(cp > 0.0) || !(mu > 0.0) || !(k > 0.0)) throw std::invalid_argument("Prandtl number needs cp, mu, k > 0");
  return cp * mu / k;
}

double heat_transfer_coefficient(double k_fluid, double Nu, double d)
{
  if (!(k_fluid >= 0.0) || !(d > 0.0)) throw std::invalid_argument("h needs k >= 0, d > 0");
  return k_fluid * Nu / d;
}

double convective_heat_rate(double h, double d, double T_fluid, double T_particle)
{
  return h * M_PI * d * d * (T_fluid - T_particle);
}

}  // namespace meltdem::coupling
