#include "meltdem/coupling/fluid_sampling.h"

#include <stdexcept>

namespace meltdem::coupling {

void add_cell_to_sample(const CellFluidFields &f, long c, double w, double share, double *q)
{
  q[0] += w * f.T[c];
  q[1] += w * f.k[c];
  q[2] += w * f.rho[c];
  q[3] += w * f.mu[c];
  q[4] += w * f.cp[c];
  for (int d = 0; d < 3; ++d) q[5 + d] += w * f.U[3 * c + d];
  if (f.alpha_metal) q[8] += w * f.alpha_metal[c];
  if (f.liquid_fraction) q[9] += w * f.liquid_fraction[c];
  // the parcel: the particle's share of each cell's mass and heat capacity (the weights
  // themselves, per unit volume, without cell volumes)
  const double V = f.volume ? f.volume[c] : 1.0, s = f.volume ? share : w;
  const double mass = s * f.rho[c] * V, capacity = mass * f.cp[c];
  q[10] += capacity;
  q[11] += capacity * f.T[c];
  q[12] += mass;
  for (int d = 0; d < 3; ++d) q[13 + d] += mass * f.U[3 * c + d];
  if (f.volume) q[16] += mass, q[17] += capacity;
}

SampledFluid finish_sample(const double *q)
{
  SampledFluid s;
  s.fluid.T = q[0], s.fluid.k = q[1], s.fluid.rho = q[2], s.fluid.mu = q[3], s.fluid.cp = q[4];
  for (int d = 0; d < 3; ++d) s.fluid.U[d] = q[5 + d];
  s.alpha_metal = q[8], s.liquid_fraction = q[9];
  if (q[10] > 0.0) s.fluid.T = q[11] / q[10];  // the parcel's: heat-capacity weighted
  if (q[12] > 0.0)
    for (int d = 0; d < 3; ++d) s.fluid.U[d] = q[13 + d] / q[12];  // mass weighted
  s.fluid.mass = q[16];
  s.fluid.capacity = q[17];
  return s;
}

SampledFluid sample_fluid(const std::vector<CellWeight> &weights, const CellFluidFields &f)
{
  if (weights.empty()) throw std::invalid_argument("sample_fluid: no cell weights");
  if (!f.T || !f.k || !f.rho || !f.mu || !f.cp || !f.U)
    throw std::invalid_argument("sample_fluid: T, k, rho, mu, cp and U are required");
  double sums[kSampleSums] = {};
  // a particle alone: its parcel is the whole of every cell it touches
  for (const CellWeight &cw : weights) add_cell_to_sample(f, cw.cell, cw.weight, 1.0, sums);
  return finish_sample(sums);
}

bool MeshFluidProvider::fluid_state(int index, const double x[3], FluidState &out) const
{
  const Eigen::Vector3d c(x[0], x[1], x[2]);
  if (!distribute_particle(mesh_, model_, c, radii_[index], weights_)) return false;
  out = sample_fluid(weights_, fields_).fluid;
  return true;
}

}  // namespace meltdem::coupling
