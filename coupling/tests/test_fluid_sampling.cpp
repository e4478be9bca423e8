// Continuum fields at a particle (fluid_sampling.h): weighted cell means.
#include "meltdem/coupling/fluid_sampling.h"
#include "validation_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace meltdem::coupling;

namespace {

// a 10 x 10 x 10 grid of 1 mm cells with fields linear in x, y, z
struct LinearFields {
  CartesianGridMesh mesh =
      CartesianGridMesh::uniform(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1e-2, 1e-2, 1e-2), 10, 10, 10);
  std::vector<double> T, k, rho, mu, cp, U, alpha, fl;
  CellFluidFields view;
  static double Tof(const Eigen::Vector3d &x) { return 1500.0 + 2e4 * x[0] - 1e4 * x[1] + 3e3 * x[2]; }
  LinearFields()
  {
    const long n = mesh.n_cells();
    for (long c = 0; c < n; ++c) {
      const Eigen::Vector3d x = mesh.cell_centre(c);
      T.push_back(Tof(x));
      k.push_back(0.03);
      rho.push_back(1.6);
      mu.push_back(4e-5);
      cp.push_back(520.0);
      U.insert(U.end(), {1.0, -2.0 + 100 * x[2], 0.5});
      alpha.push_back(x[1] < 5e-3 ? 1.0 : 0.0);
      fl.push_back(0.25);
    }
    view = CellFluidFields{T.data(), k.data(), rho.data(), mu.data(), cp.data(), U.data(), alpha.data(), fl.data()};
  }
};

}  // namespace

TEST(FluidSampling, UniformPropertiesAreReproducedByEveryModel)
{
  LinearFields f;
  const double radii[1] = {1.7e-3};
  for (auto model : {DistributionModel::Centre, DistributionModel::Neighbours, DistributionModel::Overlap}) {
    MeshFluidProvider provider(f.mesh, model, f.view, radii);
    const double x[3] = {4.3e-3, 6.1e-3, 2.2e-3};
    FluidState s;
    ASSERT_TRUE(provider.fluid_state(0, x, s));
    meltdem::testing::expect_relative(std::string("k seen, model ") + to_string(model), s.k, 0.03, 1e-14);
    meltdem::testing::expect_relative(std::string("cp seen, model ") + to_string(model), s.cp, 520.0, 1e-14);
    EXPECT_NEAR(s.rho, 1.6, 1.6e-14);
    EXPECT_NEAR(s.U[0], 1.0, 1e-14);
  }
}

TEST(FluidSampling, LinearFieldAtASymmetricParticleIsTheCentreValue)
{
  // a sphere centred on a cell centre covers cells symmetrically: the weighted mean of a
  // linear field is its value at the centre, for every model
  LinearFields f;
  const Eigen::Vector3d c = f.mesh.cell_centre(f.mesh.index(4, 5, 3));
  const double radii[1] = {2.2e-3};
  for (auto model : {DistributionModel::Centre, DistributionModel::Neighbours, DistributionModel::Overlap}) {
    MeshFluidProvider provider(f.mesh, model, f.view, radii);
    FluidState s;
    ASSERT_TRUE(provider.fluid_state(0, c.data(), s));
    meltdem::testing::expect_relative(std::string("T at a symmetric particle [K], model ") + to_string(model), s.T,
                                      LinearFields::Tof(c), 1e-12);
  }
}

TEST(FluidSampling, MetalFractionAndOutsideParticles)
{
  LinearFields f;
  std::vector<CellWeight> w;
  // a sphere centred on the metal/gas plane y = 5 mm sees half metal by overlap
  ASSERT_TRUE(distribute_particle(f.mesh, DistributionModel::Overlap, Eigen::Vector3d(5e-3, 5e-3, 5e-3), 1.5e-3, w));
  const SampledFluid s = sample_fluid(w, f.view);
  meltdem::testing::expect_relative("metal fraction seen by a particle on the interface (overlap)", s.alpha_metal, 0.5,
                                    1e-12);
  meltdem::testing::expect_relative("liquid fraction seen", s.liquid_fraction, 0.25, 1e-14);
  const double radii[1] = {1e-4};
  MeshFluidProvider provider(f.mesh, DistributionModel::Centre, f.view, radii);
  const double outside[3] = {-1e-3, 5e-3, 5e-3};
  FluidState q;
  EXPECT_FALSE(provider.fluid_state(0, outside, q));
  EXPECT_THROW(sample_fluid({}, f.view), std::invalid_argument);
}
