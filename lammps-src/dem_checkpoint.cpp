// DEM-only runs that resume (see the header).
#include "dem_checkpoint.h"

#include "fix_powder_checkpoint.h"
#include "input_replay.h"
#include "lammps_coupling_host.h"

#include "comm.h"
#include "error.h"
#include "input.h"
#include "lammps.h"
#include "modify.h"
#include "update.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fstream>
#include <memory>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

using namespace LAMMPS_NS;

namespace meltdem {

namespace {

constexpr const char *kState = "state";
constexpr const char *kComplete = "complete";
constexpr const char *kFixId = "meltdem_checkpoint";

// where the input stood at a checkpoint: the run command in progress (0-based among the
// input's runs), its last step and its start/stop keywords, the simulated time
struct DemState {
  int run_index = -1;
  long long end = 0, start = 0, stop = 0;
  double time = 0;
  std::vector<long long> if_runs;  // the if commands (indices) that executed a run
  long long inside_if = -1;        // the if command whose run wrote the checkpoint
};

std::vector<long long> complete_steps(const std::string &dir)
{
  std::vector<long long> steps;
  if (DIR *d = opendir(dir.c_str())) {
    while (dirent *e = readdir(d)) {
      char *end = nullptr;
      const long long s = std::strtoll(e->d_name, &end, 10);
      struct stat st;
      if (end != e->d_name && *end == '\0' && ::stat((dir + "/" + e->d_name + "/" + kComplete).c_str(), &st) == 0)
        steps.push_back(s);
    }
    closedir(d);
  }
  std::sort(steps.begin(), steps.end());
  return steps;
}

void remove_folder(const std::string &path)
{
  if (DIR *d = opendir(path.c_str())) {
    while (dirent *e = readdir(d)) {
      const std::string n = e->d_name;
      if (n != "." && n != "..") std::remove((path + "/" + n).c_str());
    }
    closedir(d);
  }
  ::rmdir(path.c_str());
}

std::vector<std::string> plain_words(const std::string &text)
{
  std::istringstream is(text);
  std::vector<std::string> out;
  for (std::string x; is >> x;) out.push_back(x);
  return out;
}

class CheckpointedInput {
 public:
  CheckpointedInput(LAMMPS *lmp, std::string dir, long long every) : lmp_(lmp), dir_(std::move(dir)), every_(every) {}

  void execute(const std::vector<InputCommand> &commands, bool resume)
  {
    commands_ = &commands;
    expanded_.assign(commands.size(), std::string());
    DemState at;
    if (resume) at = start_resume(commands);
    int run_index = -1;
    for (std::size_t i = 0; i < commands.size(); ++i) {
      const InputCommand &c = commands[i];
      const bool run = c.name() == "run";
      if (run) ++run_index;
      if (resume && run_index < at.run_index) {
        // replayed as it was executed: its $(...) and ${...} as they were then, not now
        if (!run)
          for (const std::string &line : replay_->before_checkpoint(lmp_, c, expanded_[i])) lmp_->input->one(line);
        note(c);
        continue;
      }
      if (resume && run && run_index == at.run_index) {
        if (c.text.find('$') != std::string::npos) check_run_unchanged(c, at);  // (its variables known now)
        Update *u = lmp_->update;
        u->atime = at.time;
        u->atimestep = u->ntimestep;
        at_ = at;
        arm();
        // (also with no step left: its setup writes the checkpoint step's outputs again)
        if (u->ntimestep <= at.end) {
          char line[160];
          std::snprintf(line, sizeof line, "run %lld upto start %lld stop %lld", at.end, at.start, at.stop);
          lmp_->input->one(line);
        }
        continue;
      }
      if (run)
        run_command(run_index, c);
      else {
        expanded_[i] = substituted(lmp_, c.text);
        execute_command(i, c);
        note(c);
      }
    }
    if (lmp_->comm->me == 0 && replay_) {
      replay_->merge_outputs();
      replay_->remove_scratch();
    }
  }

 private:
  LAMMPS *lmp_;
  std::string dir_;
  long long every_;
  std::unique_ptr<InputReplay> replay_;
  DemState at_;  // the run in progress
  // the input's commands, and each executed one as LAMMPS executed it (variables
  // substituted; a checkpoint records them, empty for runs and commands not yet reached)
  const std::vector<InputCommand> *commands_ = nullptr;
  std::vector<std::string> expanded_;
  // the if commands that executed a run, and the one executing now (-1: none)
  std::vector<long long> if_runs_;
  long long inside_if_ = -1;
  // the output files of the dump and fix commands executed so far (named between runs:
  // the variables of later ones may not exist yet), and their sizes before the outputs of
  // the checkpoint step
  std::vector<std::string> outputs_;
  OutputSizes sizes_;

  void fail(const std::string &msg) { lmp_->error->all(FLERR, msg); }

  void note(const InputCommand &c)
  {
    if (c.name() != "dump" && c.name() != "fix") return;
    for (const std::string &f : output_files(lmp_, {c}))
      if (std::find(outputs_.begin(), outputs_.end(), f) == outputs_.end()) outputs_.push_back(f);
  }

  DemState start_resume(const std::vector<InputCommand> &commands)
  {
    for (const InputCommand &c : commands) {
      if (c.name() == "fix" && c.words.size() > 3 && c.words[3] == "pour")
        fail("Cannot resume " + c.where + ": fix " + c.words[1] +
             " pour keeps no restart state, so a resumed run would pour its particles again; use fix "
             "powder/insert (it resumes), or run the case again from the start");
    }
    const std::vector<long long> steps = complete_steps(dir_);
    if (steps.empty())
      fail("Cannot resume: no complete checkpoint in " + dir_ +
           " (<step>/complete; the run was stopped before its first checkpoint)");
    const std::string ck = dir_ + "/" + std::to_string(steps.back());
    DemState at;
    std::ifstream in(ck + "/" + kState);
    std::string key, value;
    int found = 0;
    while (in >> key >> value) {
      if (key == "run_index")
        at.run_index = std::atoi(value.c_str()), ++found;
      else if (key == "end")
        at.end = std::atoll(value.c_str()), ++found;
      else if (key == "start")
        at.start = std::atoll(value.c_str()), ++found;
      else if (key == "stop")
        at.stop = std::atoll(value.c_str()), ++found;
      else if (key == "time")
        at.time = std::strtod(value.c_str(), nullptr), ++found;
      else if (key == "every")
        every_ = std::atoll(value.c_str()), ++found;
      else if (key == "if_run")
        at.if_runs.push_back(std::atoll(value.c_str()));
      else if (key == "inside_if")
        at.inside_if = std::atoll(value.c_str());
    }
    if (found != 6) fail("Cannot resume: the checkpoint " + ck + "/" + kState + " is unreadable");
    check_no_if_run(commands, at);
    // before any output is cut back (one with variables: when they are known, at the run)
    int run_index = -1;
    for (const InputCommand &c : commands)
      if (c.name() == "run" && ++run_index == at.run_index && c.text.find('$') == std::string::npos)
        check_run_unchanged(c, at);
    expanded_ = read_executed_commands(ck + "/" + LammpsCouplingHost::kCommandsFile, commands);
    replay_ = std::make_unique<InputReplay>(ck + "/" + FixPowderCheckpoint::kRestartFile,
                                            read_output_sizes(ck + "/" + LammpsCouplingHost::kOutputsFile));
    if (lmp_->comm->me == 0) {
      try {
        replay_->rewind_outputs();
      } catch (const LammpsSetupError &e) {
        fail(e.what());
      }
      if (lmp_->logfile)
        fprintf(lmp_->logfile, "meltdem-lmp: resuming from the checkpoint %s (step %lld, run %d of the input)\n",
                ck.c_str(), steps.back(), at.run_index + 1);
    }
    MPI_Barrier(lmp_->world);
    return at;
  }

  // an if that executed a run (or minimize) before the checkpoint would run it again when
  // replayed, and a checkpoint written during such a run does not know where the input stood
  void check_no_if_run(const std::vector<InputCommand> &commands, const DemState &at)
  {
    auto stop = [&](long long i, const std::string &why) {
      const std::string where = i >= 0 && i < (long long)commands.size() ? commands[i].where : "an if command";
      fail("Cannot resume " + where + ": " + why +
           " (a checkpoint counts the input's own run commands); run the case again from the start, or write "
           "the input without a run inside if");
    };
    if (at.inside_if >= 0) stop(at.inside_if, "the checkpoint was written during the run its if executed");
    int run_index = -1;
    for (std::size_t i = 0; i < commands.size(); ++i) {
      if (commands[i].name() == "run" && ++run_index == at.run_index) break;
      if (std::find(at.if_runs.begin(), at.if_runs.end(), (long long)i) != at.if_runs.end())
        stop(i, "its if executed a run before the checkpoint, which the replay would run again");
    }
  }

  // a command of the input; for an if, whether it executed a run (a run or minimize sets the
  // first step of the run: set to -1 before, it tells)
  void execute_command(std::size_t i, const InputCommand &c)
  {
    if (c.name() != "if") {
      lmp_->input->one(c.text);
      return;
    }
    Update *u = lmp_->update;
    const bigint first = u->firststep;
    u->firststep = -1;
    inside_if_ = (long long)i;
    lmp_->input->one(c.text);
    inside_if_ = -1;
    if (u->firststep != -1)
      if_runs_.push_back((long long)i);
    else
      u->firststep = first;
  }

  // the run in progress at the checkpoint, as the input now writes it, must end where it did:
  // a resume continues that run (a changed length would be ignored without a word)
  void check_run_unchanged(const InputCommand &c, const DemState &at)
  {
    const std::vector<std::string> w = plain_words(substituted(lmp_, c.text));
    bool upto = false, start = false;
    for (std::size_t k = 2; k < w.size(); ++k) {
      if (w[k] == "upto") upto = true;
      if (w[k] == "start") start = true;
    }
    if (!upto && start) return;  // (its first step is not recorded: nothing to compare)
    const long long n = w.size() > 1 ? std::atoll(w[1].c_str()) : 0;
    const long long end = upto ? n : at.start + n;
    if (end != at.end)
      fail("Cannot resume " + c.where + ": '" + c.text + "' now ends at step " + std::to_string(end) +
           ", the run of the checkpoint at step " + std::to_string(at.end) +
           " (the input changed since). A resume continues the run as it was started: restore its step "
           "count, or add another run command after it to run longer");
  }

  // a run command of the input as written, with the checkpoint fix armed for it
  void run_command(int run_index, const InputCommand &c)
  {
    const std::vector<std::string> w = plain_words(substituted(lmp_, c.text));
    const long long now = lmp_->update->ntimestep;
    DemState at;
    at.run_index = run_index;
    bool upto = false, start = false, stop = false;
    for (std::size_t k = 2; k < w.size(); ++k) {
      if (w[k] == "upto")
        upto = true;
      else if (w[k] == "start" && k + 1 < w.size())
        start = true, at.start = std::atoll(w[++k].c_str());
      else if (w[k] == "stop" && k + 1 < w.size())
        stop = true, at.stop = std::atoll(w[++k].c_str());
      else if (w[k] == "every")
        fail("Cannot checkpoint " + c.where +
             ": a run ... every cannot be resumed in the middle; write the loop "
             "out, or run without -checkpoint");
    }
    const long long n = w.size() > 1 ? std::atoll(w[1].c_str()) : 0;
    at.end = upto ? n : now + n;
    if (!start) at.start = now;
    if (!stop) at.stop = at.end;
    at_ = at;
    arm();
    lmp_->input->one(c.text);
  }

  // the checkpoint fix, defined last (after the fixes whose files it records) for this run
  void arm()
  {
    if (lmp_->modify->find_fix(kFixId) >= 0) lmp_->input->one(std::string("unfix ") + kFixId);
    lmp_->input->one(std::string("fix ") + kFixId + " all powder/checkpoint " + std::to_string(every_) + " " + dir_);
    auto *fix = dynamic_cast<FixPowderCheckpoint *>(lmp_->modify->fix[lmp_->modify->find_fix(kFixId)]);
    fix->before_outputs = [this](bigint) { note_sizes(); };
    fix->written = [this](bigint step, const std::string &folder) { complete(step, folder); };
  }

  // rank 0, before the outputs of the checkpoint step: the redirected rows so far appended,
  // then each file's size (a run resumed here writes this step's outputs again)
  void note_sizes()
  {
    if (lmp_->comm->me != 0) return;
    try {
      if (replay_) replay_->merge_outputs();
    } catch (const LammpsSetupError &e) {
      lmp_->error->one(FLERR, e.what());
    }
    sizes_ = output_sizes(outputs_);
  }

  // after the restart file of a checkpoint: where the input stands, output sizes, 'complete'
  void complete(bigint step, const std::string &ck)
  {
    int ok = 1;
    std::string why;
    if (lmp_->comm->me == 0) {
      try {
        write_output_sizes(ck + "/" + LammpsCouplingHost::kOutputsFile, sizes_);
        write_executed_commands(ck + "/" + LammpsCouplingHost::kCommandsFile, *commands_, expanded_);
        const Update *u = lmp_->update;
        char t[64];
        std::snprintf(t, sizeof t, "%a", u->atime + double(u->ntimestep - u->atimestep) * u->dt);
        std::ofstream os(ck + "/" + kState, std::ios::trunc);
        os << "run_index " << at_.run_index << "\nend " << at_.end << "\nstart " << at_.start << "\nstop " << at_.stop
           << "\ntime " << t << "\nevery " << every_ << '\n';
        for (long long i : if_runs_) os << "if_run " << i << '\n';
        if (inside_if_ >= 0) os << "inside_if " << inside_if_ << '\n';
        os.close();
        if (!os) throw LammpsSetupError("cannot write " + ck + "/" + kState + ": " + std::strerror(errno));
        std::ofstream done(ck + "/" + kComplete, std::ios::trunc);
        done << step << '\n';
        done.close();
        if (!done) throw LammpsSetupError("cannot write " + ck + "/" + kComplete + ": " + std::strerror(errno));
        // the two latest complete checkpoints are kept
        const std::vector<long long> steps = complete_steps(dir_);
        for (std::size_t k = 0; k + 2 < steps.size(); ++k) remove_folder(dir_ + "/" + std::to_string(steps[k]));
      } catch (const LammpsSetupError &e) {
        ok = 0;
        why = e.what();
      }
    }
    MPI_Bcast(&ok, 1, MPI_INT, 0, lmp_->world);
    if (!ok)
      fail("Checkpoint at step " + std::to_string(step) + " failed (" + why +
           "); the disk holding it may be full. The last complete checkpoint is kept");
  }
};

}  // namespace

void run_with_checkpoints(LAMMPS *lmp, const std::string &input_file, const std::string &dir, long long every,
                          bool resume)
{
  if (every < 1) lmp->error->all(FLERR, "meltdem-lmp -checkpoint DIR N: N must be a positive number of steps");
  std::vector<InputCommand> commands;
  try {
    commands = read_input_commands(input_file);
  } catch (const LammpsSetupError &e) {
    lmp->error->all(FLERR, e.what());
  }
  CheckpointedInput(lmp, dir, every).execute(commands, resume);
}

}  // namespace meltdem
