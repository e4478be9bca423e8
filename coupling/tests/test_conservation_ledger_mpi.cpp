// Conservation ledger over MPI: run with mpirun -np 2. Particles and cells of the
// synthetic melt are split round-robin over the ranks; every rank also runs the whole case
// alone on MPI_COMM_SELF. The reduced totals and errors must equal the serial ones to 1e-12.
#include "mpi_gtest.h"
#include "ledger_synthetic_melt.h"
#include "meltdem/coupling/conservation_ledger.h"
#include "validation_report.h"

#include <mpi.h>

using namespace meltdem::coupling;
using namespace meltdem::coupling::testing;

namespace {
const int &rank = meltdem::testing::mpi_rank, &size = meltdem::testing::mpi_size;

// relative difference, measured against the largest magnitude of the quantity in the run
void compare(const std::string &what, double worst, double tol)
{
  if (rank == 0) {
    meltdem::testing::expect_absolute(what, worst, 0.0, tol);
  } else {
    EXPECT_LE(worst, tol) << what;
  }
}
}  // namespace

TEST(ConservationLedgerMpi, TotalsEqualSerial)
{
  ASSERT_GE(size, 2) << "run with mpirun -np 2 (or more)";
  SyntheticOptions o;
  o.particles = 7;  // 4 on rank 0, 3 on rank 1; cells interleaved
  o.lose_particle_step = 120;
  ConservationLedger parallel(MPI_COMM_WORLD), serial(MPI_COMM_SELF);
  parallel.open_csv(::testing::TempDir() + "ledger_mpi_test.csv");
  o.rank = rank, o.size = size;
  run_synthetic_melt(parallel, o);
  o.rank = 0, o.size = 1;
  run_synthetic_melt(serial, o);

  const auto &hp = parallel.history(), &hs = serial.history();
  ASSERT_EQ(hp.size(), hs.size());
  Amounts scale{};
  for (const auto &s : hs)
    for (int q = 0; q < kComponents; ++q)
      for (int c = 0; c < kCategories; ++c) scale[q] = std::max(scale[q], std::abs(s.booked[c][q]));
  double worst_total = 0.0, worst_error = 0.0, worst_counts = 0.0;
  for (std::size_t k = 0; k < hs.size(); ++k) {
    for (int q = 0; q < kComponents; ++q) {
      if (scale[q] == 0.0) continue;
      for (int c = 0; c < kCategories; ++c)
        worst_total = std::max(worst_total, std::abs(hp[k].booked[c][q] - hs[k].booked[c][q]) / scale[q]);
      worst_error = std::max({worst_error, std::abs(hp[k].system_error[q] - hs[k].system_error[q]),
                              std::abs(hp[k].continuum_error[q] - hs[k].continuum_error[q]),
                              std::abs(hp[k].cumulative_system_error[q] - hs[k].cumulative_system_error[q])});
    }
    worst_counts = std::max(worst_counts, std::abs(double(hp[k].particles - hs[k].particles)) +
                                              std::abs(double(hp[k].lost_particles - hs[k].lost_particles)));
  }
  compare("np " + std::to_string(size) + " vs serial: worst |total difference| / largest |total|", worst_total, 1e-12);
  compare("np " + std::to_string(size) + " vs serial: worst |balance error difference|", worst_error, 1e-12);
  compare("np vs serial: particle and lost counts", worst_counts, 0.0);
  // every rank holds the same (reduced) totals
  double mine = hp.back().booked[kContinuum][kEnthalpy], root = mine;
  MPI_Bcast(&root, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  EXPECT_EQ(mine, root);
  // the balances themselves close in parallel too
  const Amounts ws = parallel.worst_system_error(), wc = parallel.worst_continuum_error();
  for (int q = 0; q < kComponents; ++q) {
    // enthalpy: ~0.3 J per particle moves through cells holding ~7e-3 J (see test_conservation_ledger.cpp)
    const double tol = q == kEnthalpy ? 1e-13 : 1e-14;
    compare(std::string("np: worst per-step system error, ") + component_name(Component(q)), ws[q], tol);
    compare(std::string("np: worst per-step continuum error, ") + component_name(Component(q)), wc[q], tol);
  }
  if (rank == 0)
    std::cout << "np " << size << ": " << hp.size() << " steps, worst total difference " << worst_total
              << ", worst error difference " << worst_error << std::endl;
}
