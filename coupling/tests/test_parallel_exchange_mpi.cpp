// parallel_exchange.h over N ranks (mpirun -np 2 and -np 4): the mesh is cut into N slabs
// along x (np 2: at x node 6) and the particles are dealt round-robin, unlike the mesh:
// every cell's deposit and every particle's sampled field must equal the single-rank result
// on the whole mesh, what the particles took is reported by another rank than the one that
// located them, and each rank receives exactly the particles whose sphere reaches its
// cells (no rank sees them all). The nearest solid surface of each particle, at rest and
// moving (approached first, fresh or old), is the one found on one rank.
#include "mpi_gtest.h"
#include "meltdem/coupling/parallel_exchange.h"
#include "parallel_exchange_case.h"
#include "validation_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace meltdem::coupling;
using namespace meltdem::coupling::testing;

namespace {
const int &rank = meltdem::testing::mpi_rank, &size = meltdem::testing::mpi_size;
}

class ParallelExchangeMpi : public ::testing::TestWithParam<DistributionModel> {};

TEST_P(ParallelExchangeMpi, EqualsOneRank)
{
  ExchangeCase k;
  const int nx = int(k.x.size()) - 1, ny = int(k.y.size()) - 1, nz = int(k.z.size()) - 1;
  ASSERT_LE(size, nx) << "at most " << nx << " ranks";
  // slabs of x cells: np 2 cuts at node 6 (where the case puts straddling particles)
  const int i0 = rank * nx / size, i1 = (rank + 1) * nx / size;
  const CartesianGridMesh whole(k.x, k.y, k.z), mine = k.part(i0, i1);

  auto fields = [&](const CartesianGridMesh &m, std::vector<double> &T, std::vector<double> &one,
                    std::vector<double> &U) {
    for (long c = 0; c < m.n_cells(); ++c) {
      const Eigen::Vector3d x = m.cell_centre(c);
      T.push_back(ExchangeCase::field(x));
      one.push_back(1.0 + 1e3 * x.y());  // density varies: capacity weights differ from volume weights
      U.insert(U.end(), {x.x(), x.y(), x.z()});
    }
    // cell "volumes" vary too, so the heat goes by what each cell holds beyond the particle
    return CellFluidFields{T.data(), one.data(), one.data(), one.data(), one.data(),
                           U.data(), one.data(), nullptr,    one.data()};
  };

  // reference: everything on this rank alone
  std::vector<double> Ts, ones, Us;
  const CellFluidFields fs = fields(whole, Ts, ones, Us);
  ParallelExchange serial(whole, GetParam(), MPI_COMM_SELF);
  serial.locate(k.particles);
  std::vector<Amounts> cells_serial(std::size_t(whole.n_cells()), Amounts{});
  serial.deposit(k.amounts, cells_serial);
  std::vector<double> heat, particle_T;
  std::vector<Eigen::Vector3d> impulse;
  for (const Amounts &a : k.amounts)
    heat.push_back(a[kEnthalpy] * 0.3), impulse.push_back(Eigen::Vector3d(a[kMomY], a[kMomZ], a[kMomX]));
  // the field at the centre: some covered cells are above, some below the particle
  for (const auto &p : k.particles) particle_T.push_back(ExchangeCase::field(p.x));
  std::vector<std::int64_t> ids;
  for (const auto &p : k.particles) ids.push_back(p.id);
  serial.deposit_taken(ids, heat, impulse, particle_T, fs, cells_serial);
  std::vector<SampledFluid> sampled_serial;
  serial.sample(fs, sampled_serial);
  // solid metal in a pattern of cells, searched within 0.1 mm beyond each particle
  auto solid_of = [](const CartesianGridMesh &m) {
    std::vector<double> solid;
    for (long c = 0; c < m.n_cells(); ++c) {
      const Eigen::Vector3d x = m.cell_centre(c);
      solid.push_back(x.z() < 1.5e-4 || (x.x() > 4e-4 && x.x() < 6e-4 && x.y() > 5e-4) ? 1.0 : 0.0);
    }
    return solid;
  };
  const double reach = 1e-4;
  const std::vector<double> solid_serial = solid_of(whole);
  std::vector<SolidSurface> surfaces_serial;
  serial.nearest_solid(solid_serial.data(), reach, surfaces_serial);
  // again with velocities (moving particles are handed the nearest surface they approach) and
  // last interval's solid (part of it: fresh and old surfaces)
  auto velocity_of = [](const ParticleShape &p) {
    const double t = 0.7 * double(p.id);
    return Eigen::Vector3d(std::sin(t), std::cos(1.3 * t), -0.5 + std::sin(2.1 * t));
  };
  auto was_solid_of = [&](const CartesianGridMesh &m) {
    std::vector<double> was = solid_of(m);
    for (long c = 0; c < m.n_cells(); ++c)
      if (m.cell_centre(c).x() > 5e-4) was[std::size_t(c)] = 0.0;
    return was;
  };
  std::vector<Eigen::Vector3d> velocity_serial;
  for (const auto &p : k.particles) velocity_serial.push_back(velocity_of(p));
  const std::vector<double> was_serial = was_solid_of(whole);
  std::vector<SolidSurface> moving_serial;
  serial.nearest_solid(solid_serial.data(), reach, moving_serial, was_serial.data(), &velocity_serial);

  // parallel: round-robin particles, half the mesh each
  std::vector<ParticleShape> my_particles;
  std::vector<Amounts> my_amounts;
  std::vector<std::size_t> my_index;
  for (std::size_t i = 0; i < k.particles.size(); ++i)
    if (int(i % size) == rank)
      my_particles.push_back(k.particles[i]), my_amounts.push_back(k.amounts[i]), my_index.push_back(i);
  std::vector<double> Tp, onep, Up;
  const CellFluidFields fp = fields(mine, Tp, onep, Up);
  ParallelExchange parallel(mine, GetParam(), MPI_COMM_WORLD);
  parallel.locate(my_particles);
  ASSERT_EQ(parallel.global_particles(), std::int64_t(k.particles.size()));
  std::vector<Amounts> cells_parallel(std::size_t(mine.n_cells()), Amounts{});
  parallel.deposit(my_amounts, cells_parallel);
  // the records come from the other rank than the one that located them (particles move
  // between DEM ranks during the sub-cycles)
  std::vector<std::int64_t> other_ids;
  std::vector<int> other_located_by;
  std::vector<double> other_heat, other_T;
  std::vector<Eigen::Vector3d> other_impulse;
  for (std::size_t i = 0; i < k.particles.size(); ++i)
    if (int((i + 1) % size) == rank)  // the next rank reports what rank i % size located
      other_ids.push_back(k.particles[i].id), other_located_by.push_back(int(i % size)), other_heat.push_back(heat[i]),
          other_impulse.push_back(impulse[i]), other_T.push_back(particle_T[i]);
  parallel.deposit_taken(other_ids, other_located_by, other_heat, other_impulse, other_T, fp, cells_parallel);
  std::vector<SampledFluid> sampled_parallel;
  parallel.sample(fp, sampled_parallel);
  const std::vector<double> solid_parallel = solid_of(mine);
  std::vector<SolidSurface> surfaces_parallel;
  parallel.nearest_solid(solid_parallel.data(), reach, surfaces_parallel);
  std::vector<Eigen::Vector3d> velocity_parallel;
  for (const auto &p : my_particles) velocity_parallel.push_back(velocity_of(p));
  const std::vector<double> was_parallel = was_solid_of(mine);
  std::vector<SolidSurface> moving_parallel;
  parallel.nearest_solid(solid_parallel.data(), reach, moving_parallel, was_parallel.data(), &velocity_parallel);

  // the visitors: the particles whose sphere reaches this rank's slab, and no others
  std::size_t reaching = 0;
  Eigen::Vector3d lo, hi;
  mine.bounds(lo, hi);
  for (const auto &p : k.particles) reaching += (p.x.cwiseMax(lo).cwiseMin(hi) - p.x).norm() <= p.radius * (1 + 1e-12);
  EXPECT_EQ(parallel.visitor_count(), reaching);
  if (size > 1) EXPECT_LT(parallel.visitor_count(), k.particles.size());

  Amounts scale{};
  for (const Amounts &a : k.amounts)
    for (int q = 0; q < kComponents; ++q) scale[q] = std::max(scale[q], std::abs(a[q]));
  double worst_cell = 0.0, worst_sample = 0.0;
  for (int kk = 0; kk < nz; ++kk)
    for (int j = 0; j < ny; ++j)
      for (int i = i0; i < i1; ++i) {
        const Amounts &a = cells_parallel[std::size_t(mine.index(i - i0, j, kk))];
        const Amounts &b = cells_serial[std::size_t(whole.index(i, j, kk))];
        for (int q = 0; q < kComponents; ++q) worst_cell = std::max(worst_cell, std::abs(a[q] - b[q]) / scale[q]);
      }
  for (std::size_t l = 0; l < my_index.size(); ++l) {
    ASSERT_EQ(parallel.inside(l), serial.inside(my_index[l]));
    if (!parallel.inside(l)) continue;
    const auto &a = sampled_parallel[l], &b = sampled_serial[my_index[l]];
    worst_sample = std::max(
        {worst_sample, std::abs(a.fluid.T - b.fluid.T) / b.fluid.T, std::abs(a.fluid.U[0] - b.fluid.U[0]) / 1e-3});
  }
  int surfaces_found = 0;
  for (std::size_t l = 0; l < my_index.size(); ++l) {
    const SolidSurface &a = surfaces_parallel[l], &b = surfaces_serial[my_index[l]];
    ASSERT_EQ(a.present, b.present) << "particle " << my_index[l];
    if (!a.present) continue;
    ++surfaces_found;
    EXPECT_NEAR(a.distance, b.distance, 1e-15) << "particle " << my_index[l];
    EXPECT_LE((a.point - b.point).norm(), 1e-15) << "particle " << my_index[l];
  }
  MPI_Allreduce(MPI_IN_PLACE, &surfaces_found, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_GT(surfaces_found, 10);
  // moving particles: the same surface as on one rank, approached or not, fresh or old; and
  // the velocities change some choices (the test exercises the preference across ranks)
  int counts[4] = {0, 0, 0, 0};  // approached, fresh, old, another surface than at rest
  for (std::size_t l = 0; l < my_index.size(); ++l) {
    const SolidSurface &a = moving_parallel[l], &b = moving_serial[my_index[l]];
    ASSERT_EQ(a.present, b.present) << "moving particle " << my_index[l];
    if (!a.present) continue;
    EXPECT_NEAR(a.distance, b.distance, 1e-15) << "moving particle " << my_index[l];
    EXPECT_LE((a.point - b.point).norm(), 1e-15) << "moving particle " << my_index[l];
    EXPECT_LE((a.normal - b.normal).norm(), 1e-15) << "moving particle " << my_index[l];
    EXPECT_EQ(a.approached, b.approached) << "moving particle " << my_index[l];
    EXPECT_EQ(a.fresh, b.fresh) << "moving particle " << my_index[l];
    counts[0] += a.approached;
    counts[1] += a.fresh;
    counts[2] += !a.fresh;
    counts[3] += (a.point - surfaces_parallel[l].point).norm() > 0.0;
  }
  MPI_Allreduce(MPI_IN_PLACE, counts, 4, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_GT(counts[0], 0);
  EXPECT_GT(counts[1], 0);
  EXPECT_GT(counts[2], 0);
  EXPECT_GT(counts[3], 0);
  if (rank == 0)
    std::printf("moving particles: %d approach their surface, %d fresh, %d old, %d handed another than at rest\n",
                counts[0], counts[1], counts[2], counts[3]);
  double w[2] = {worst_cell, worst_sample};
  MPI_Allreduce(MPI_IN_PLACE, w, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  const std::string m = to_string(GetParam());
  if (rank == 0) {
    meltdem::testing::expect_absolute("parallel_exchange np" + std::to_string(size) + " " + m +
                                          ": cell deposit vs one rank (relative to the largest amount)",
                                      w[0], 0.0, 1e-12);
    meltdem::testing::expect_absolute("parallel_exchange np" + std::to_string(size) + " " + m +
                                          ": sampled fields vs one rank (relative)",
                                      w[1], 0.0, 1e-12);
  } else {
    EXPECT_LE(w[0], 1e-12);
    EXPECT_LE(w[1], 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, ParallelExchangeMpi,
                         ::testing::Values(DistributionModel::Centre, DistributionModel::Neighbours,
                                           DistributionModel::Overlap),
                         [](const auto &info) { return std::string(to_string(info.param)); });
