#include "meltdem/coupling/fluid_sampling.h"

#include <stdexcept>

namespace meltdem::coupling {

SampledFluid sample_fluid(const std::vector<CellWeight> &weights, const CellFluidFields &f)
{
  if (weights.empty()) throw std::invalid_argument("sample_fluid: no cell weights");
  if (!f.T || !f.k || !f.rho || !f.mu || !f.cp || !f.U)
    throw std::invalid_argument("sample_fluid: T, k, rho, mu, cp and U are required");
  SampledFluid s;
  FluidState &q = s.fluid;
  double capacity = 0.0, heat = 0.0, mass = 0.0, momentum[3] = {0.0, 0.0, 0.0};
  for (const CellWeight &cw : weights) {
    const long c = cw.cell;
    const double w = cw.weight;
    q.T += w * f.T[c];
    capacity += w * f.rho[c] * f.cp[c];
    heat += w * f.rho[c] * f.cp[c] * f.T[c];
    mass += w * f.rho[c];
    if (f.volume) q.mass += w * f.rho[c] * f.volume[c];
    for (int d = 0; d < 3; ++d) momentum[d] += w * f.rho[c] * f.U[3 * c + d];
    q.k += w * f.k[c];
    q.rho += w * f.rho[c];
    q.mu += w * f.mu[c];
    q.cp += w * f.cp[c];
    for (int d = 0; d < 3; ++d) q.U[d] += w * f.U[3 * c + d];
    if (f.alpha_metal) s.alpha_metal += w * f.alpha_metal[c];
    if (f.liquid_fraction) s.liquid_fraction += w * f.liquid_fraction[c];
  }
  if (capacity > 0.0) q.T = heat / capacity;
  if (mass > 0.0)
    for (int d = 0; d < 3; ++d) q.U[d] = momentum[d] / mass;
  return s;
}

bool MeshFluidProvider::fluid_state(int index, const double x[3], FluidState &out) const
{
  const Eigen::Vector3d c(x[0], x[1], x[2]);
  if (!distribute_particle(mesh_, model_, c, radii_[index], weights_)) return false;
  out = sample_fluid(weights_, fields_).fluid;
  return true;
}

}  // namespace meltdem::coupling
