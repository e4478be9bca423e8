/* ----------------------------------------------------------------------
   MeltDEM: fix powder/checkpoint

   At the end of every N-th step the restart file DIR/<step>/lammps.restart is written
   during the run, the way LAMMPS's own `restart` output does (the run is not stopped, so
   the run is the same with or without checkpoints), then the hook `written` completes the
   checkpoint. Defined last (after the fixes whose output files it records), it sees the
   rows they wrote at that step.
------------------------------------------------------------------------- */

#include "fix_powder_checkpoint.h"

#include "comm.h"
#include "error.h"
#include "update.h"
#include "write_restart.h"

#include <cerrno>
#include <cstring>
#include <sys/stat.h>

using namespace LAMMPS_NS;
using namespace FixConst;

FixPowderCheckpoint::FixPowderCheckpoint(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  if (narg != 5) error->all(FLERR, "Illegal fix powder/checkpoint command: expected N DIR");
  nevery = utils::inumeric(FLERR, arg[3], false, lmp);
  if (nevery <= 0) error->all(FLERR, "Illegal fix powder/checkpoint command: N must be > 0");
  dir = arg[4];
}

int FixPowderCheckpoint::setmask()
{
  return END_OF_STEP;
}

void FixPowderCheckpoint::end_of_step()
{
  const bigint step = update->ntimestep;
  const std::string folder = dir + "/" + std::to_string(step);
  int ok = 1;
  if (comm->me == 0) {
    ::mkdir(dir.c_str(), 0755);
    if (::mkdir(folder.c_str(), 0755) != 0 && errno != EEXIST) ok = 0;
    std::remove((folder + "/complete").c_str());
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, world);
  if (!ok) error->all(FLERR, "Fix powder/checkpoint cannot create {}: {}", folder, utils::getsyserror());
  WriteRestart restart(lmp);
  restart.multiproc_options(0, 0, 0, nullptr);
  restart.write(folder + "/" + kRestartFile);
  if (written) written(step, folder);
}
