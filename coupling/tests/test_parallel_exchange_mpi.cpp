// parallel_exchange.h over 2 ranks (mpirun -np 2): the mesh is cut at x node 6 (rank 0
// holds cells i < 6, rank 1 the rest) and the particles are dealt round-robin, unlike
// the mesh: every cell's deposit and every particle's sampled field must equal the
// single-rank result on the whole mesh.
#include "mpi_gtest.h"
#include "meltdem/coupling/parallel_exchange.h"
#include "parallel_exchange_case.h"
#include "validation_report.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace meltdem::coupling;
using namespace meltdem::coupling::testing;

namespace {
const int &rank = meltdem::testing::mpi_rank, &size = meltdem::testing::mpi_size;
}

class ParallelExchangeMpi : public ::testing::TestWithParam<DistributionModel> {};

TEST_P(ParallelExchangeMpi, EqualsOneRank)
{
  ASSERT_EQ(size, 2) << "run with mpirun -np 2";
  ExchangeCase k;
  const int nx = int(k.x.size()) - 1, ny = int(k.y.size()) - 1, nz = int(k.z.size()) - 1, cut = 6;
  const int i0 = rank == 0 ? 0 : cut, i1 = rank == 0 ? cut : nx;
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

  // parallel: round-robin particles, half the mesh each
  std::vector<ParticleShape> my_particles;
  std::vector<Amounts> my_amounts;
  std::vector<std::size_t> my_index;
  for (std::size_t i = 0; i < k.particles.size(); ++i)
    if (int(i % 2) == rank)
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
  std::vector<double> other_heat, other_T;
  std::vector<Eigen::Vector3d> other_impulse;
  for (std::size_t i = 0; i < k.particles.size(); ++i)
    if (int(i % 2) != rank)
      other_ids.push_back(k.particles[i].id), other_heat.push_back(heat[i]), other_impulse.push_back(impulse[i]),
          other_T.push_back(particle_T[i]);
  parallel.deposit_taken(other_ids, other_heat, other_impulse, other_T, fp, cells_parallel);
  std::vector<SampledFluid> sampled_parallel;
  parallel.sample(fp, sampled_parallel);

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
  double w[2] = {worst_cell, worst_sample};
  MPI_Allreduce(MPI_IN_PLACE, w, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  const std::string m = to_string(GetParam());
  if (rank == 0) {
    meltdem::testing::expect_absolute(
        "parallel_exchange np2 " + m + ": cell deposit vs one rank (relative to the largest amount)", w[0], 0.0, 1e-12);
    meltdem::testing::expect_absolute("parallel_exchange np2 " + m + ": sampled fields vs one rank (relative)", w[1],
                                      0.0, 1e-12);
  } else {
    EXPECT_LE(w[0], 1e-12);
    EXPECT_LE(w[1], 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, ParallelExchangeMpi,
                         ::testing::Values(DistributionModel::Centre, DistributionModel::Neighbours,
                                           DistributionModel::Overlap),
                         [](const auto &info) { return std::string(to_string(info.param)); });
