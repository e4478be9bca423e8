/* -*- c++ -*- ----------------------------------------------------------
   MeltDEM: fix powder/checkpoint -- what a run that resumes needs from inside the run:
   a LAMMPS restart file every N steps into DIR/<step>/ (meltdem-lmp -checkpoint,
   dem_checkpoint.h), and the moment to note the output files' sizes before the outputs
   of a checkpoint step (also for meltdemFoam's particles, N = 0: lammps_coupling_host.h).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
// no trailing semicolon: meltdem_styles.cpp expands this inside an array initializer
FixStyle(powder/checkpoint,FixPowderCheckpoint)
// clang-format on
#else

#ifndef MELTDEM_FIX_POWDER_CHECKPOINT_H
#define MELTDEM_FIX_POWDER_CHECKPOINT_H

#include "fix.h"

#include <functional>
#include <string>

namespace LAMMPS_NS {

class FixPowderCheckpoint : public Fix {
 public:
  FixPowderCheckpoint(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void post_force(int) override;
  void end_of_step() override;

  // on every rank, in the checkpoint step after its forces and before any output of that
  // step (fixes write theirs at end_of_step, dumps after it): a run resumed from this step
  // writes that step's outputs again, so the files are continued from here
  std::function<void(bigint step)> before_outputs;
  // on every rank after the restart file of a checkpoint is written (N > 0): the caller
  // completes the checkpoint folder (where the input stands, output sizes, 'complete')
  std::function<void(bigint step, const std::string &folder)> written;
  // N = 0: the step (set by the caller) at which before_outputs is called
  bigint checkpoint_step = -1;

  static constexpr const char *kRestartFile = "lammps.restart";

 private:
  int every;  // N
  std::string dir;
  bool due(bigint step) const;
};

}  // namespace LAMMPS_NS

#endif
#endif
