#pragma once
// Continuum fields at a particle: the cell values averaged with the particle's
// distribution weights (particle_distribution.h). Using the same kernel for what the
// particle sees and for what it hands back keeps the exchange symmetric: a particle
// spanning many cells feels their mean, not the one cell holding its centre.
#include "meltdem/coupling/fluid_state.h"
#include "meltdem/coupling/particle_distribution.h"

#include <vector>

namespace meltdem::coupling {

// Views of the continuum's per-cell fields (the caller owns the arrays; U holds 3
// values per cell). A null alpha_metal / liquid_fraction reads as 0.
struct CellFluidFields {
  const double *T = nullptr;
  const double *k = nullptr;
  const double *rho = nullptr;
  const double *mu = nullptr;
  const double *cp = nullptr;
  const double *U = nullptr;
  const double *alpha_metal = nullptr;
  const double *liquid_fraction = nullptr;
  const double *volume = nullptr;  // cell volumes: gives FluidState::mass (null: mass 0)
};

struct SampledFluid {
  FluidState fluid;
  double alpha_metal = 0.0;      // metal volume fraction around the particle
  double liquid_fraction = 0.0;  // of that metal
};

// Weighted mean of the cell fields over `weights` (which sum to 1). The temperature is
// the heat-capacity-weighted mean sum w rho cp T / sum w rho cp (the temperature the
// covered cells would reach if mixed; the plain mean where all capacities are zero): a
// particle half in melt, half in gas sees the melt's temperature, not the middle, and
// the heat it takes is drawn from the cells by what each holds beyond the particle's
// temperature (ParallelExchange::deposit_taken), so gas colder than the particle gives none
// of it. The
// velocity likewise is the mass-weighted mean sum w rho U / sum w rho (the mixture's
// momentum over its mass), and the drag reaction is split by w rho.
// Throws std::invalid_argument for empty weights or a missing required field.
SampledFluid sample_fluid(const std::vector<CellWeight> &weights, const CellFluidFields &fields);

// The weighted sums sample_fluid() forms, kept apart so that they can be summed over ranks
// before they are finished (ParallelExchange::sample_global): add each cell, then finish.
constexpr int kSampleSums = 17;
void add_cell_to_sample(const CellFluidFields &fields, long cell, double weight, double *sums);
SampledFluid finish_sample(const double *sums);

// FluidStateProvider over a mesh: particle i (radius radii[i]) sees the fields averaged
// with the weights of the chosen distribution model. Returns false for a particle whose
// centre is outside the mesh (it exchanges nothing; the caller books it as outflow).
class MeshFluidProvider : public FluidStateProvider {
 public:
  MeshFluidProvider(const DistributionMesh &mesh, DistributionModel model, const CellFluidFields &fields,
                    const double *radii) :
      mesh_(mesh),
      model_(model), fields_(fields), radii_(radii)
  {
  }
  bool fluid_state(int index, const double x[3], FluidState &out) const override;

 private:
  const DistributionMesh &mesh_;
  DistributionModel model_;
  CellFluidFields fields_;
  const double *radii_;
  mutable std::vector<CellWeight> weights_;
};

}  // namespace meltdem::coupling
