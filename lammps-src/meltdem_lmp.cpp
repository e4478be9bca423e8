// meltdem-lmp: Debian's LAMMPS library plus MeltDEM's styles. Same command line as lmp;
// without a project style in the input it behaves exactly as /usr/bin/lmp.
#include "lammps_version_guard.h"
#include "meltdem_styles.h"

#include "accelerator_kokkos.h"
#include "input.h"
#include "lammps.h"
#include "lmppython.h"
#include "version.h"

#include <cstdio>
#include <mpi.h>

#ifndef MELTDEM_HEADER_LAMMPS_VERSION
#define MELTDEM_HEADER_LAMMPS_VERSION LAMMPS_VERSION
#endif

using namespace LAMMPS_NS;

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  MPI_Comm lammps_comm = MPI_COMM_WORLD;
  int status = 0;

  try {
    auto *lammps = new LAMMPS(argc, argv, lammps_comm);
    const std::string mismatch = meltdem::lammps_version_mismatch(lammps, MELTDEM_HEADER_LAMMPS_VERSION);
    if (!mismatch.empty()) {
      int me = 0;
      MPI_Comm_rank(lammps_comm, &me);
      if (me == 0) fprintf(stderr, "ERROR: %s\n", mismatch.c_str());
      // do not touch the instance further: its layout is not the one we were built for
      MPI_Barrier(lammps_comm);
      MPI_Finalize();
      return 2;
    }
    meltdem::register_lammps_styles(lammps);
    lammps->input->file();
    delete lammps;
  } catch (fmt::format_error &fe) {
    fprintf(stderr, "fmt::format_error: %s\n", fe.what());
    KokkosLMP::finalize();
    Python::finalize();
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }
  KokkosLMP::finalize();
  Python::finalize();
  MPI_Barrier(lammps_comm);
  MPI_Finalize();
  return status;
}
