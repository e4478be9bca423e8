/* -*- c++ -*- ----------------------------------------------------------
   MeltDEM: fix powder/checkpoint -- a LAMMPS restart file every N steps during a run,
   into DIR/<step>/, for runs that resume (meltdem-lmp -checkpoint: dem_checkpoint.h).
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
  void end_of_step() override;

  // called on every rank after the restart file of a checkpoint is written: the caller
  // completes the checkpoint folder (where the input stands, output sizes, 'complete')
  std::function<void(bigint step, const std::string &folder)> written;

  static constexpr const char *kRestartFile = "lammps.restart";

 private:
  std::string dir;
};

}    // namespace LAMMPS_NS

#endif
#endif
