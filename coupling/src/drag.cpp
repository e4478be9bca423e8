#include "meltdem/coupling/drag.h"

#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

namespace {
// Cd * Re, finite at Re = 0 (both laws tend to 24)
double cd_re(DragModel model, double Re)
{
  if (!(Re >= 0.0)) throw std::invalid_argument("Reynolds number must be >= 0");
  switch (model) {
    case DragModel::Thesis:
      return Re > 1000.0 ? 0.424 * Re : 24.0 + 4.0 * std::pow(Re, 2.0 / 3.0);
    case DragModel::SchillerNaumann:
      return Re > 1000.0 ? 0.44 * Re : 24.0 * (1.0 + 0.15 * std::pow(Re, 0.687));
  }
  throw std::invalid_argument("unknown drag model");
}
}  // namespace

double particle_reynolds(double rho_f, double slip_speed, double d, double mu_f)
{
  if (!(rho_f >= 0.0) || !(d > 0.0) || !(mu_f > 0.0)) throw std::invalid_argument("Re needs rho >= 0, d > 0, mu > 0");
  return rho_f * std::abs(slip_speed) * d / mu_f;
}

double drag_coefficient(DragModel model, double Re)
{
  if (!(Re > 0.0)) throw std::invalid_argument("drag coefficient needs Re > 0");
  return cd_re(model, Re) / Re;
}

double drag_coefficient_thesis(double Re)
{
  return drag_coefficient(DragModel::Thesis, Re);
}

double drag_coefficient_schiller_naumann(double Re)
{
  return drag_coefficient(DragModel::SchillerNaumann, Re);
}

double drag_beta(DragModel model, double Re, double mu_f, double d)
{
  if (!(mu_f >= 0.0) || !(d > 0.0)) throw std::invalid_argument("drag needs mu >= 0, d > 0");
  return 3.0 * M_PI * mu_f * d * cd_re(model, Re) / 24.0;
}

}  // namespace meltdem::coupling
