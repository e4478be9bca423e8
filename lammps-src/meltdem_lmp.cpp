// meltdem-lmp: Debian's LAMMPS library plus MeltDEM's styles. Same command line as lmp;
// without a project style in the input it behaves exactly as /usr/bin/lmp. Two flags of
// its own (dem_checkpoint.h), taken out before LAMMPS reads the rest:
//   -checkpoint DIR N   checkpoints every N steps into DIR/<step>/ (needs -in FILE)
//   -resume             continue from the latest complete checkpoint in DIR
#include "dem_checkpoint.h"
#include "lammps_version_guard.h"
#include "meltdem_styles.h"

#include "accelerator_kokkos.h"
#include "exceptions.h"
#include "input.h"
#include "lammps.h"
#include "lmppython.h"
#include "version.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>
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
  int me = 0;
  MPI_Comm_rank(lammps_comm, &me);

  // meltdem-lmp's own flags
  std::vector<char *> args;
  std::string checkpoint_dir, input_file;
  long long every = 0;
  bool resume = false;
  for (int i = 0; i < argc; i++) {
    const std::string a = argv[i];
    if (a == "-checkpoint") {
      char *end = nullptr;
      if (i + 2 < argc) every = std::strtoll(argv[i + 2], &end, 10);
      if (i + 2 >= argc || !end || *end != '\0' || every < 1) {
        if (me == 0)
          fprintf(stderr, "ERROR: meltdem-lmp -checkpoint DIR N: N, the steps between checkpoints, "
                          "must be a positive integer\n");
        MPI_Finalize();
        return 1;
      }
      checkpoint_dir = argv[i + 1];
      i += 2;
      continue;
    }
    if (a == "-resume") {
      resume = true;
      continue;
    }
    if ((a == "-in" || a == "-i") && i + 1 < argc) input_file = argv[i + 1];
    args.push_back(argv[i]);
  }
  if ((resume || !checkpoint_dir.empty()) && (checkpoint_dir.empty() || input_file.empty())) {
    if (me == 0) fprintf(stderr, "ERROR: meltdem-lmp: -resume needs -checkpoint DIR N, and both need -in FILE\n");
    MPI_Finalize();
    return 1;
  }
  args.push_back(nullptr);
  argc = int(args.size()) - 1;
  argv = args.data();

  try {
    auto *lammps = new LAMMPS(argc, argv, lammps_comm);
    const std::string mismatch = meltdem::lammps_version_mismatch(lammps, MELTDEM_HEADER_LAMMPS_VERSION);
    if (!mismatch.empty()) {
      if (me == 0) fprintf(stderr, "ERROR: %s\n", mismatch.c_str());
      // do not touch the instance further: its layout is not the one we were built for
      MPI_Barrier(lammps_comm);
      MPI_Finalize();
      return 2;
    }
    meltdem::register_lammps_styles(lammps);
    if (checkpoint_dir.empty())
      lammps->input->file();
    else
      meltdem::run_with_checkpoints(lammps, input_file, checkpoint_dir, every, resume);
    delete lammps;
  } catch (LAMMPSAbortException &ae) {
    // error->one (LAMMPS since 2023 throws; older builds abort inside LAMMPS): only this rank
    // knows; its message and what is buffered go out before the abort
    const std::string what = ae.what();
    fprintf(stderr, "%s%s", what.rfind("ERROR", 0) == 0 ? "" : "ERROR: ", what.c_str());
    if (what.empty() || what.back() != '\n') fprintf(stderr, "\n");
    fflush(stdout);
    fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  } catch (LAMMPSException &) {
    // error->all: every rank is here and rank 0 printed the message, so the job ends as stock
    // lmp's does (below), without an abort that could kill rank 0 before its output is forwarded
    status = 1;
  } catch (fmt::format_error &fe) {
    fprintf(stderr, "fmt::format_error: %s\n", fe.what());
    KokkosLMP::finalize();
    Python::finalize();
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  } catch (std::exception &e) {
    // what a style did not turn into a LAMMPS error: said as one, not as an abort
    fprintf(stderr, "ERROR: %s\n", e.what());
    fflush(stdout);
    fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }
  KokkosLMP::finalize();
  Python::finalize();
  MPI_Barrier(lammps_comm);
  MPI_Finalize();
  return status;
}
