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
  const double *volume = nullptr;  // cell volumes: give FluidState::mass, capacity (null: 0)
};

struct SampledFluid {
  FluidState fluid;
  double alpha_metal = 0.0;      // metal volume fraction around the particle
  double liquid_fraction = 0.0;  // of that metal
};

// What a particle sees of the continuum. Properties (k, rho, mu, cp, alpha, liquid fraction)
// are the means over its distribution weights w (which sum to 1). Temperature and velocity
// are those of its parcel, the fluid it exchanges heat and momentum with as a second body:
// its share s of each cell it touches (by conductance: w d over the sum of w d of the
// particles in the cell; all of a cell it is alone in), T = sum s rho cp V T / sum s rho cp V (a particle half in melt,
// half in gas sees the melt's temperature, not the middle), U = sum s rho V U / sum s rho V,
// with FluidState::capacity and ::mass the parcel's sums. As the shares of a cell sum to 1 over
// the particles in it, the parcels never hold more than the cells, and the exchange can be
// integrated as two bodies for any step (ParallelExchange::deposit_taken takes each parcel's
// loss from its cells). Without cell volumes the parcel uses w per unit volume and its mass
// and capacity are 0 (unbounded). sample_fluid() is a particle alone (s = 1).
// Throws std::invalid_argument for empty weights or a missing required field.
SampledFluid sample_fluid(const std::vector<CellWeight> &weights, const CellFluidFields &fields);

// The weighted sums sample_fluid() forms, kept apart so that they can be summed over ranks
// before they are finished (ParallelExchange::sample): add each cell, then finish.
constexpr int kSampleSums = 18;
void add_cell_to_sample(const CellFluidFields &fields, long cell, double weight, double share, double *sums);
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
