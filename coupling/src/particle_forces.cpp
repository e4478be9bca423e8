#include "meltdem/coupling/particle_forces.h"

#include <algorithm>
#include <cmath>

namespace meltdem::coupling {

double slip_reynolds(const FluidState &fluid, const double v[3], double d)
{
  const double s0 = fluid.U[0] - v[0], s1 = fluid.U[1] - v[1], s2 = fluid.U[2] - v[2];
  return particle_reynolds(fluid.rho, std::sqrt(s0 * s0 + s1 * s1 + s2 * s2), d, fluid.mu);
}

ParticleForces drag_and_buoyancy(DragModel model, const FluidState &fluid, const double v[3], double d,
                                 const double g[3])
{
  ParticleForces f;
  f.Re = slip_reynolds(fluid, v, d);
  f.beta = drag_beta(model, f.Re, fluid.mu, d);
  const double vb = -fluid.rho * M_PI / 6.0 * d * d * d;
  for (int k = 0; k < 3; ++k) {
    f.drag[k] = f.beta * (fluid.U[k] - v[k]);
    f.buoyancy[k] = vb * g[k];
  }
  return f;
}

double two_body_drag_coefficient(double beta, double m, double M, double dt)
{
  if (!(beta > 0.0) || !(dt > 0.0) || !(m > 0.0)) return beta;
  const double mu = M > 0.0 ? m * M / (m + M) : m;
  return std::min(beta, mu / dt);
}

}  // namespace meltdem::coupling
