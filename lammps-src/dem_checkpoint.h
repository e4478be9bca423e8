#pragma once
// DEM-only runs that resume: meltdem-lmp -in IN -checkpoint DIR N [-resume].
//
// The input is executed command by command (input_replay.h: include files read in place;
// jump, label, next and clear refused). During each run command, fix powder/checkpoint
// writes the checkpoint DIR/<step>/ at every N-th step without stopping the run (the run is
// the one it is without checkpoints): the LAMMPS restart, where the input stood (which run,
// its end, start and stop steps, the simulated time), the sizes of the output files and,
// last, 'complete'. The two latest complete checkpoints are kept. A resumed run starts with
// LAMMPS's setup (neighbour lists built anew), so it continues the run to round-off, not
// bit for bit.
//
// -resume: the latest complete checkpoint in DIR; the input is replayed on its restart up
// to the run that was in progress, which continues to its end, and then goes on as written.
// A run whose input has a fix without restart state that creates particles (fix pour) is
// refused: the resumed run would insert them again.
#include <string>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace meltdem {

// executes input_file on lmp as above; errors go through lmp->error (LAMMPS's ERROR lines)
void run_with_checkpoints(LAMMPS_NS::LAMMPS *lmp, const std::string &input_file, const std::string &dir,
                          long long every, bool resume);

}  // namespace meltdem
