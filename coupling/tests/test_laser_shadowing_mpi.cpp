// Laser shadowing over MPI (run with mpirun -np 2): particles split round-robin over the
// ranks must absorb what the serial cast gives them, and the balance must close globally.
#include "mpi_gtest.h"
#include "meltdem/coupling/laser_shadowing.h"
#include "validation_report.h"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

using namespace meltdem::coupling;

namespace {
const int &rank = meltdem::testing::mpi_rank, &size = meltdem::testing::mpi_size;

void check(const std::string &what, double measured, double reference, double tol)
{
  if (rank == 0) {
    meltdem::testing::expect_relative(what, measured, reference, tol);
  } else {
    EXPECT_LE(std::abs(measured - reference), tol * std::abs(reference)) << what;
  }
}

GaussianBeam beam()
{
  GaussianBeam b;
  b.power = 200.0;
  b.absorptivity = 0.4;
  b.radius = 50e-6;
  b.centre = Eigen::Vector3d(1e-4, -2e-4, 3e-4);
  b.direction = Eigen::Vector3d(0.2, 0.1, -1.0);
  return b;
}

std::vector<BeamParticle> bed(const GaussianBeam &b, int n)
{
  std::mt19937_64 rng(99);
  const double w = b.radius;
  // some outside the sampled square (|u| up to 6 w) so the selection is exercised
  std::uniform_real_distribution<double> pos(-6 * w, 6 * w), rad(0.1 * w, 0.5 * w), z(0, 4 * w);
  std::vector<BeamParticle> ps;
  for (int k = 0; k < n; ++k) ps.push_back({b.centre + Eigen::Vector3d(pos(rng), pos(rng), z(rng)), rad(rng)});
  return ps;
}
}  // namespace

TEST(LaserShadowingMpi, EqualsSerial)
{
  ASSERT_GE(size, 2) << "run with mpirun -np 2 (or more)";
  const GaussianBeam b = beam();
  const auto all = bed(b, 400);
  const ShadowResult serial = shade_particles(b, all);
  std::vector<BeamParticle> mine;
  std::vector<int> index;
  for (int k = rank; k < static_cast<int>(all.size()); k += size) {
    mine.push_back(all[k]);
    index.push_back(k);
  }
  const ShadowResult par = shade_particles(MPI_COMM_WORLD, b, mine);
  ASSERT_EQ(par.absorbed.size(), mine.size());
  double worst = 0.0, local_sum = 0.0;
  for (std::size_t j = 0; j < mine.size(); ++j) {
    worst = std::max(worst, std::abs(par.absorbed[j] - serial.absorbed[index[j]]));
    local_sum += par.absorbed[j];
  }
  double worst_all = 0.0, absorbed_sum = 0.0;
  MPI_Allreduce(&worst, &worst_all, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(&local_sum, &absorbed_sum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0)
    meltdem::testing::expect_absolute("max |absorbed np - serial| per particle [W]", worst_all, 0.0, 1e-15 * b.power);
  check("intercepted total np vs serial [W]", par.intercepted_total, serial.intercepted_total, 1e-13);
  check("sum over ranks of absorbed + continuum_absorbed() vs eta P [W]", absorbed_sum + par.continuum_absorbed(),
        b.absorptivity * b.power, 1e-12);
  EXPECT_EQ(par.grid.n, serial.grid.n);
}

TEST(LaserShadowingMpi, BadInputOnOneRankThrowsEverywhere)
{
  ASSERT_GE(size, 2);
  const GaussianBeam b = beam();
  std::vector<BeamParticle> mine = {{b.centre, 10e-6}};
  if (rank == 1) mine.push_back({b.centre, -1.0});
  try {
    shade_particles(MPI_COMM_WORLD, b, mine);
    ADD_FAILURE() << "rank " << rank << ": no exception";
  } catch (const std::invalid_argument &e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(rank == 1 ? "local particle 1 radius = -1" : "on another rank"), std::string::npos) << msg;
  }
}
