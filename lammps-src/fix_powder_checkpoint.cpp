/* ----------------------------------------------------------------------
   MeltDEM: fix powder/checkpoint

   N > 0: at the end of every N-th step the restart file DIR/<step>/lammps.restart is
   written during the run, the way LAMMPS's own `restart` output does: the run is not
   stopped, and the neighbour lists are rebuilt on that step (atoms are then inside the
   box, as a restart file needs them); then the hook `written` completes the checkpoint.
   Both N > 0 and N = 0 call `before_outputs` in the checkpoint step after the forces,
   before any fix or dump writes that step's output.
------------------------------------------------------------------------- */

#include "fix_powder_checkpoint.h"

#include "lammps_api.h"
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
  every = utils::inumeric(FLERR, arg[3], false, lmp);
  if (every < 0) error->all(FLERR, "Illegal fix powder/checkpoint command: N must be >= 0");
  dir = arg[4];
  // N = 0 writes nothing itself: a folder given there would silently get no checkpoint
  if (every == 0 && dir != "NULL")
    error->all(FLERR,
               "Illegal fix powder/checkpoint command: with N = 0 the fix writes no checkpoint, so DIR "
               "must be NULL (not {})",
               dir);
  if (every > 0 && dir == "NULL")
    error->all(FLERR, "Illegal fix powder/checkpoint command: N = {} needs a folder DIR, not NULL", every);
  nevery = every > 0 ? every : 1;
  force_reneighbor = every > 0 ? 1 : 0;
  next_reneighbor = -1;
}

int FixPowderCheckpoint::setmask()
{
  return POST_FORCE | (every > 0 ? END_OF_STEP : 0);
}

void FixPowderCheckpoint::init()
{
  if (every > 0) next_reneighbor = (update->ntimestep / every + 1) * every;
}

bool FixPowderCheckpoint::due(bigint step) const
{
  return every > 0 ? step % every == 0 : step == checkpoint_step;
}

void FixPowderCheckpoint::post_force(int)
{
  if (before_outputs && due(update->ntimestep)) before_outputs(update->ntimestep);
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
  meltdem::lammps_api::single_file_restart(restart);
  restart.write(folder + "/" + kRestartFile);
  if (written) written(step, folder);
  next_reneighbor = step + every;
}
