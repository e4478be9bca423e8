#pragma once
// Shared by the gtest programs run under mpirun (mpi_gtest_main.cpp): MPI is initialised,
// rank 0 alone prints, the exit code is the worst over the ranks.
namespace meltdem::testing {
extern int mpi_rank, mpi_size;
}
