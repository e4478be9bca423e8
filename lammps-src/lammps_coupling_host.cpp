// LammpsCouplingHost: LAMMPS driven from meltdemFoam's time loop (see the header).
#include "lammps_coupling_host.h"

#include "fix_powder_insert.h"
#include "fix_powder_checkpoint.h"
#include "fix_powder_dt.h"
#include "input_replay.h"
#include "fix_powder_melt.h"
#include "lammps_version_guard.h"
#include "meltdem_styles.h"

#include "atom.h"
#include "domain.h"
#include "exceptions.h"
#include "fix.h"
#include "input.h"
#include "lammps.h"
#include "modify.h"
#include "update.h"
#include "version.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace mc = meltdem::coupling;
using namespace LAMMPS_NS;

namespace meltdem {

namespace {

// LAMMPS's screen once the input is read: the per-run output (setup, thermo) goes to the log
// only, but ERROR and WARNING lines (and the 'Last command' after an error) still reach stdout,
// on every rank: after a LAMMPS error inside the coupled run nothing else says why the job
// stopped. LAMMPS closes the stream itself (error exit or destructor).
ssize_t screen_write(void *cookie, const char *buf, size_t n)
{
  auto &line = *static_cast<std::string *>(cookie);
  for (size_t i = 0; i < n; ++i) {
    line += buf[i];
    if (buf[i] != '\n') continue;
    if (line.rfind("ERROR", 0) == 0 || line.rfind("WARNING", 0) == 0 || line.rfind("Last command", 0) == 0) {
      std::fputs(line.c_str(), stdout);
      std::fflush(stdout);
    }
    line.clear();
  }
  return ssize_t(n);
}

int screen_close(void *cookie)
{
  delete static_cast<std::string *>(cookie);
  return 0;
}

FILE *errors_only_screen()
{
  auto *line = new std::string;
  FILE *f = fopencookie(line, "w", cookie_io_functions_t{nullptr, screen_write, nullptr, screen_close});
  if (!f) {
    delete line;
    return nullptr;
  }
  std::setvbuf(f, nullptr, _IONBF, 0);
  return f;
}

// LAMMPS since 2023 stops on an input error by throwing (the 29 Sep 2021 build exits): either way
// the coupled run ends with LAMMPS's message (printed to screen and log by LAMMPS on rank 0), the
// command the coupling gave, and exit code 1, never an uncaught exception
template <typename Call> void lammps_call(MPI_Comm comm, int me, const std::string &command, Call &&call)
{
  try {
    call();
  } catch (const std::exception &e) {
    std::string what = e.what();
    const bool from_lammps = what.rfind("ERROR", 0) == 0;
    // error->one throws on its rank alone, which may abort before rank 0 has written: it names
    // the command itself, as LAMMPS's own error->one does
    const bool one_rank = dynamic_cast<const LAMMPSAbortException *>(&e) != nullptr;
    while (!what.empty() && what.back() == '\n') what.pop_back();
    if (!from_lammps || me != 0) std::fprintf(stderr, "%s%s\n", from_lammps ? "" : "ERROR: ", what.c_str());
    if (me == 0 || one_rank) std::fprintf(stderr, "Last command: %s\n", command.c_str());
    std::fflush(stdout);
    std::fflush(stderr);
    // error->all throws on every rank: all have written their lines before any rank aborts
    if (!one_rank && dynamic_cast<const LAMMPSException *>(&e)) MPI_Barrier(comm);
    MPI_Abort(comm, 1);
  }
}

}  // namespace

struct LammpsCouplingHost::Impl {
  LAMMPS *lmp = nullptr;
  MPI_Comm comm = MPI_COMM_NULL;
  FixPowderMelt *melt = nullptr;
  void one(const std::string &command)
  {
    lammps_call(comm, me, command, [&] { lmp->input->one(command.c_str()); });
  }
  bool needs_setup = true;
  int me = 0;
  // the input's commands (empty, with the reason, when it cannot be replayed), its output
  // files, and the replay of a resumed run
  std::vector<InputCommand> commands;
  std::vector<std::string> executed;  // each command as executed (write_executed_commands)
  std::string not_replayable;
  std::unique_ptr<InputReplay> replay;
  // the input's output files, and their sizes before the outputs of the last step of the
  // last interval (a checkpoint's step; a run resumed there writes its outputs again)
  FixPowderCheckpoint *outputs_fix = nullptr;
  std::vector<std::string> outputs;
  OutputSizes sizes;
};

LammpsCouplingHost::LammpsCouplingHost(MPI_Comm comm, const std::string &input_file, const std::string &log_file,
                                       bool echo, const std::string &restart_file, double restart_time) :
    impl_(std::make_unique<Impl>())
{
  MPI_Comm_rank(comm, &impl_->me);
  impl_->comm = comm;
  {
    // a directory opens as a stream but reads nothing, and an empty input would run as
    // units lj: both are reported as what they are
    std::ifstream probe(input_file);
    int ok = probe.good() && probe.peek() != std::ifstream::traits_type::eof() ? 1 : 0, all = 0;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm);
    if (!all)
      throw LammpsSetupError("cannot open the LAMMPS input file " + input_file + " (missing, empty or not a file)");
  }
  // a resumed run appends to the log of the run it continues
  std::vector<std::string> args = {"meltdemFoam-lammps", "-log", restart_file.empty() ? log_file : "none", "-nocite"};
  if (!echo) args.insert(args.end(), {"-echo", "none"});
  std::vector<char *> argv;
  for (auto &a : args) argv.push_back(a.data());
  impl_->lmp = new LAMMPS(int(argv.size()), argv.data(), comm);
  const std::string mismatch = lammps_version_mismatch(impl_->lmp, LAMMPS_VERSION);
  if (!mismatch.empty()) throw LammpsSetupError(mismatch);
  register_lammps_styles(impl_->lmp);

  // setup errors reach the terminal (LAMMPS prints them to screen and log, then stops);
  // once the input is read, per-run output goes to the log only
  LAMMPS *lmp = impl_->lmp;
  try {
    impl_->commands = read_input_commands(input_file);
  } catch (const LammpsSetupError &e) {
    if (!restart_file.empty()) throw;
    impl_->not_replayable = e.what();
  }
  if (restart_file.empty() && !impl_->not_replayable.empty())
    lammps_call(comm, impl_->me, "the LAMMPS input " + input_file, [&] { lmp->input->file(input_file.c_str()); });
  else if (restart_file.empty()) {
    // command by command, each recorded as executed (a checkpoint keeps them for the replay)
    impl_->executed.assign(impl_->commands.size(), std::string());
    for (std::size_t i = 0; i < impl_->commands.size(); ++i) {
      const InputCommand &c = impl_->commands[i];
      lammps_call(comm, impl_->me, c.text, [&] {
        if (c.name() != "run") impl_->executed[i] = substituted(lmp, c.text);
        lmp->input->one(c.text.c_str());
      });
    }
  } else {
    const std::string dir = restart_file.substr(0, restart_file.find_last_of('/') + 1);
    impl_->replay = std::make_unique<InputReplay>(restart_file, read_output_sizes(dir + kOutputsFile));
    impl_->executed = read_executed_commands(dir + kCommandsFile, impl_->commands);
    if (impl_->me == 0) impl_->replay->rewind_outputs();
    MPI_Barrier(comm);
    impl_->one("log " + log_file + " append");
    for (std::size_t i = 0; i < impl_->commands.size(); ++i) {
      const InputCommand &c = impl_->commands[i];
      if (c.name() == "run") continue;  // the coupling drives the run
      // replayed as it was executed: its $(...) and ${...} as they were then, not now
      std::vector<std::string> lines;
      lammps_call(comm, impl_->me, c.text,
                  [&] { lines = impl_->replay->before_checkpoint(lmp, c, impl_->executed[i]); });
      for (const std::string &line : lines) impl_->one(line);
    }
    lmp->update->atime = restart_time;
    lmp->update->atimestep = lmp->update->ntimestep;
  }

  if (std::strcmp(lmp->update->unit_style, "si") != 0)
    throw LammpsSetupError(std::string("the LAMMPS input ") + input_file + " uses units " + lmp->update->unit_style +
                           "; the coupling exchanges SI quantities: use units si");
  if (!lmp->domain->box_exist) throw LammpsSetupError("the LAMMPS input " + input_file + " defines no simulation box");
  int nmelt = 0;
  for (int i = 0; i < lmp->modify->nfix; i++)
    if (std::strcmp(lmp->modify->fix[i]->style, "powder/melt") == 0) {
      impl_->melt = dynamic_cast<FixPowderMelt *>(lmp->modify->fix[i]);
      ++nmelt;
    }
  if (nmelt != 1)
    throw LammpsSetupError("the LAMMPS input " + input_file + " defines " + std::to_string(nmelt) +
                           " fix powder/melt; the coupling needs exactly one (its cp, Tmelt and latent are "
                           "the particles' material)");
  impl_->melt->hold_fluid({}, {}, -1);  // the coupling hands each interval's fluid in
  if (impl_->not_replayable.empty()) {
    impl_->outputs = output_files(lmp, impl_->commands);
    impl_->one("fix meltdem_outputs all powder/checkpoint 0 NULL");
    impl_->outputs_fix =
        dynamic_cast<FixPowderCheckpoint *>(lmp->modify->fix[lmp->modify->find_fix("meltdem_outputs")]);
    Impl *impl = impl_.get();
    impl_->outputs_fix->before_outputs = [impl](bigint) {
      if (impl->me != 0) return;
      if (impl->replay) impl->replay->merge_outputs();
      impl->sizes = output_sizes(impl->outputs);
    };
  }
  // initialise every style once (fix gravity sets its vector only in init)
  if (impl_->me == 0 && lmp->screen) fflush(lmp->screen);
  lmp->screen = errors_only_screen();
  impl_->one("run 0 post no");
}

LammpsCouplingHost::~LammpsCouplingHost()
{
  delete impl_->lmp;
  if (impl_->replay && impl_->me == 0) {
    try {
      impl_->replay->merge_outputs();
      impl_->replay->remove_scratch();
    } catch (const LammpsSetupError &e) {
      std::fprintf(stderr, "WARNING: %s\n", e.what());
    }
  }
}

const std::string &LammpsCouplingHost::resume_limitation() const
{
  return impl_->not_replayable;
}

double LammpsCouplingHost::timestep() const
{
  return impl_->lmp->update->dt;
}

void LammpsCouplingHost::set_timestep(double dt)
{
  char line[64];
  std::snprintf(line, sizeof line, "timestep %.17g", dt);
  impl_->one(line);
}

double LammpsCouplingHost::time() const
{
  const Update *u = impl_->lmp->update;
  return u->atime + double(u->ntimestep - u->atimestep) * u->dt;
}

std::int64_t LammpsCouplingHost::step() const
{
  return std::int64_t(impl_->lmp->update->ntimestep);
}

std::int64_t LammpsCouplingHost::particles() const
{
  return std::int64_t(impl_->lmp->atom->natoms);
}

void LammpsCouplingHost::box(double lo[3], double hi[3], int periodic[3]) const
{
  const Domain *d = impl_->lmp->domain;
  for (int k = 0; k < 3; k++) lo[k] = d->boxlo[k], hi[k] = d->boxhi[k], periodic[k] = d->periodicity[k];
}

double LammpsCouplingHost::gravity(double g[3]) const
{
  impl_->melt->gravity(g);  // the fixes were initialised by the constructor's run 0
  return std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
}

const mc::MeltMaterial &LammpsCouplingHost::material() const
{
  return impl_->melt->material();
}

std::string LammpsCouplingHost::melt_fix_id() const
{
  return impl_->melt->id;
}

void LammpsCouplingHost::insertion_store(coupling::Amounts &drawn, coupling::Amounts &pending) const
{
  drawn = pending = coupling::Amounts{};
  const coupling::MeltMaterial &mat = material();
  for (int i = 0; i < impl_->lmp->modify->nfix; i++) {
    auto *ins = dynamic_cast<FixPowderInsert *>(impl_->lmp->modify->fix[i]);
    if (!ins) continue;
    // a new particle: fix powder/insert's temp if given, else fix powder/melt's initial one
    const double T = ins->sets_temperature() ? ins->new_temperature() : impl_->melt->initial_temperature();
    const double h = coupling::specific_enthalpy(mat, T);
    const Eigen::Vector3d v(ins->new_velocity()[0], ins->new_velocity()[1], ins->new_velocity()[2]);
    const double m_pending = ins->compute_vector(4), m_drawn = ins->compute_vector(3) + m_pending;
    const coupling::Amounts a = coupling::make_amounts(m_drawn, m_drawn * h, m_drawn * v);
    const coupling::Amounts b = coupling::make_amounts(m_pending, m_pending * h, m_pending * v);
    for (int q = 0; q < coupling::kComponents; q++) drawn[q] += a[q], pending[q] += b[q];
  }
}

bool LammpsCouplingHost::solid_metal_wall() const
{
  return impl_->melt->solid_metal_wall();
}

void LammpsCouplingHost::local_particles(std::vector<mc::ExchangeRecord> &out) const
{
  impl_->melt->current_records(out);
}

void LammpsCouplingHost::set_fluid(const std::vector<std::int64_t> &ids, const std::vector<mc::FluidState> &states,
                                   int located_by)
{
  impl_->melt->hold_fluid(std::vector<tagint>(ids.begin(), ids.end()), states, located_by);
}

void LammpsCouplingHost::set_heat_owed(const std::vector<std::int64_t> &tags, const std::vector<double> &heat)
{
  impl_->melt->set_heat_owed(std::vector<tagint>(tags.begin(), tags.end()), heat);
}

int LammpsCouplingHost::advance(int n, std::vector<mc::ExchangeRecord> &records, double span)
{
  if (n < 1) throw std::invalid_argument("LammpsCouplingHost::advance: n must be >= 1");
  std::vector<FixPowderDt *> dt_fixes;
  for (int i = 0; i < impl_->lmp->modify->nfix; i++)
    if (std::strcmp(impl_->lmp->modify->fix[i]->style, "powder/dt") == 0)
      dt_fixes.push_back(dynamic_cast<FixPowderDt *>(impl_->lmp->modify->fix[i]));
  const double t_end = time() + span;
  const double dt_cycle = timestep();
  if (span > 0.0)
    for (FixPowderDt *f : dt_fixes) f->set_step_ceiling(dt_cycle);
  impl_->melt->reset_interval();
  if (impl_->outputs_fix) impl_->outputs_fix->checkpoint_step = impl_->lmp->update->ntimestep + n;
  impl_->one("run " + std::to_string(n) + (impl_->needs_setup ? " post no" : " pre no post no"));
  impl_->needs_setup = false;
  int steps = n;
  // steps fix powder/dt shortened: made up to the span, the last one cut to end on it
  while (span > 0.0 && t_end - time() > 1e-9 * span) {
    const double left = t_end - time();
    if (left < timestep()) {
      for (FixPowderDt *f : dt_fixes) f->set_step_ceiling(left);
      set_timestep(left);
    }
    if (impl_->outputs_fix) impl_->outputs_fix->checkpoint_step = impl_->lmp->update->ntimestep + 1;
    impl_->one("run 1 pre no post no");
    ++steps;
  }
  if (steps > n && timestep() != dt_cycle) set_timestep(dt_cycle);
  for (FixPowderDt *f : dt_fixes) f->set_step_ceiling(0.0);
  impl_->melt->interval_records(records);
  return steps;
}

std::int64_t LammpsCouplingHost::remove(const std::vector<std::int64_t> &tags)
{
  std::vector<tagint> sorted(tags.begin(), tags.end());
  std::sort(sorted.begin(), sorted.end());
  const bigint n = impl_->melt->remove_particles(sorted);
  if (n) impl_->needs_setup = true;
  return std::int64_t(n);
}

void LammpsCouplingHost::command(const std::string &line)
{
  impl_->one(line);
  impl_->needs_setup = true;
}

// through command(): the next advance() runs a full setup, as a run resumed from this file
// does, so an uninterrupted run and a resumed one take the same steps after it. The output
// files' sizes go beside it: a resumed run cuts back what a killed one wrote past them.
void LammpsCouplingHost::write_checkpoint(const std::string &dir)
{
  command("write_restart " + dir + "/" + kRestartFile);
  if (impl_->me != 0 || !impl_->not_replayable.empty()) return;
  write_output_sizes(dir + "/" + kOutputsFile, impl_->sizes);
  write_executed_commands(dir + "/" + kCommandsFile, impl_->commands, impl_->executed);
}

void LammpsCouplingHost::write_particles(const std::string &file)
{
  const std::string melt = std::string("f_") + impl_->melt->id;
  command("write_dump all custom " + file + " id type x y z vx vy vz radius mass " + melt + "[1] " + melt +
          "[2] modify time yes sort id format float %.17g");
}

}  // namespace meltdem
