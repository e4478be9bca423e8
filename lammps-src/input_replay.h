#pragma once
// A LAMMPS input as a list of commands, and that input replayed on top of a restart file:
// what a resumed run executes (meltdemFoam's particles: lammps_coupling_host.h; DEM-only
// runs: meltdem-lmp -resume, dem_checkpoint.h). The restart file holds the state (atoms,
// groups, fix restart data, the time step); the replay applies the settings as written
// (pair, fixes with their IDs, computes, regions, variables, dumps) and leaves out what
// made or changed the state before the checkpoint. Output files continue where they stood
// at the checkpoint: what a killed run wrote past it is cut off (or removed, if it did not
// exist then), dumps and fix print append, and fix ave/* (which cannot append) write to
// <file>.resumed, whose rows are appended to <file> at every checkpoint and at the end.
#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace meltdem {

struct InputCommand {
  std::string text;                // as written, continuation lines joined, comment removed
  std::vector<std::string> words;  // split at white space, quoted words kept whole (quotes kept)
  std::string where;               // "file:line" for messages
  const std::string &name() const { return words.front(); }
};

// The commands of a LAMMPS input file, `include` files read in place. Throws
// LammpsSetupError naming file and line for what cannot be replayed command by command:
// jump, label, next, clear, an include whose file name has variables.
std::vector<InputCommand> read_input_commands(const std::string &file);

// the command's text with the instance's variables substituted
std::string substituted(LAMMPS_NS::LAMMPS *lmp, const std::string &text);

// The commands as they were executed, variables substituted (executed[i] for commands[i]; empty:
// not executed, or a run): a checkpoint records them, so that a resume replays what ran, with
// its $(...) and ${...} as they were then, not as they evaluate on the restart. Reading gives
// empty strings where there is no record or the input no longer holds the command as written.
// (write: throws LammpsSetupError on a failed write)
void write_executed_commands(const std::string &file, const std::vector<InputCommand> &commands,
                             const std::vector<std::string> &executed);
std::vector<std::string> read_executed_commands(const std::string &file, const std::vector<InputCommand> &commands);

// Files the commands write to, which a resume must continue: dump to one file, fix ave/*
// file, fix print file/append. Names with the instance's current variables substituted.
std::vector<std::string> output_files(LAMMPS_NS::LAMMPS *lmp, const std::vector<InputCommand> &commands);

// each file's size now, -1 when it does not exist (a checkpoint records them)
using OutputSizes = std::vector<std::pair<std::string, long long>>;
OutputSizes output_sizes(const std::vector<std::string> &files);
void write_output_sizes(const std::string &file, const OutputSizes &sizes);  // throws on a failed write
OutputSizes read_output_sizes(const std::string &file);                      // empty when missing

class InputReplay {
 public:
  // outputs: the output files at the checkpoint (read_output_sizes)
  InputReplay(std::string restart_file, OutputSizes outputs);
  InputReplay(const InputReplay &) = delete;
  InputReplay &operator=(const InputReplay &) = delete;

  // cut the output files back to the checkpoint: larger ones truncated, ones that did not
  // exist then removed (call on one rank, before replaying)
  void rewind_outputs() const;

  // What a command before the checkpoint becomes in the resumed run (none: left out): the
  // first box command -> read_restart, state-making commands and runs left out, dumps and
  // fix print appending, fix ave/* redirected. Call with the instance that executes the
  // commands, in order (the variables of file names are substituted with it).
  std::vector<std::string> before_checkpoint(LAMMPS_NS::LAMMPS *lmp, const InputCommand &command);

  // before_checkpoint of the command as it was executed (executed: its record from
  // read_executed_commands; without one, the command as written now, recorded into it)
  std::vector<std::string> before_checkpoint(LAMMPS_NS::LAMMPS *lmp, const InputCommand &command,
                                             std::string &executed);

  // append what the redirected fix ave/* files wrote since the last call to their files
  // (call on one rank at each checkpoint and at the end)
  void merge_outputs();

  // remove the redirected files' scratch copies (the rank that merged, after its last merge:
  // another rank removing them could race that merge)
  void remove_scratch() const;

 private:
  struct Redirect {
    std::string target, scratch;
    long long merged = 0;  // bytes of scratch already appended
    bool header_done = false;
  };
  std::string restart_file_;
  OutputSizes outputs_;
  bool box_done_ = false;
  std::vector<Redirect> redirects_;
};

}  // namespace meltdem
