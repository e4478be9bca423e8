// main() of the gtest programs run under mpirun (see mpi_gtest.h).
#include "mpi_gtest.h"

#include <gtest/gtest.h>
#include <mpi.h>

namespace meltdem::testing {
int mpi_rank = 0, mpi_size = 1;
}

int main(int argc, char **argv)
{
  using namespace meltdem::testing;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &mpi_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &mpi_size);
  ::testing::InitGoogleTest(&argc, argv);
  if (mpi_rank != 0) {  // one rank prints
    auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int rc = RUN_ALL_TESTS();
  int worst = rc;
  MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return worst;
}
