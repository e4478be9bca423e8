#pragma once
// LAMMPS inside another code's MPI job: meltdemFoam owns the time loop and
// drives a LAMMPS instance built from the case's input script through this class. The
// header has no LAMMPS headers, so OpenFOAM translation units can include it.
//
// Per coupling interval the host: sets the fluid each particle sees (by particle tag,
// fixed over the interval), advances LAMMPS by whole DEM steps (sub-cycles; fix
// powder/dt may resize them), and collects one exchange record per particle: what it
// handed over (melt: mass, enthalpy, momentum) and took (heat, drag impulse) over the
// interval. Particles the continuum reports outside its mesh are removed here and
// booked by the caller as outflow.
#include "meltdem/coupling/exchange_record.h"
#include "meltdem/coupling/fluid_state.h"
#include "meltdem/coupling/particle_melting.h"

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace meltdem {

// A setup problem the caller reports in its own style (FatalError for OpenFOAM).
struct LammpsSetupError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class LammpsCouplingHost {
 public:
  // Opens LAMMPS on comm (log to log_file, no screen output unless echo), checks the
  // library against the headers, registers MeltDEM's styles, runs input_file. The input
  // must use units si, define exactly one fix powder/melt, and not end inside a run.
  //
  // Resuming (restart_file not empty, kRestartFile of a checkpoint folder): the input is
  // replayed on the restart (input_replay.h): settings as written, so fixes with restart
  // state (powder/melt, powder/insert) continue, the state-making commands left out, the
  // output files continued from their size at the checkpoint. LAMMPS 29Sep2021 does not
  // store the simulated time in restarts: restart_time sets it. Inputs with jump, label,
  // next or clear cannot be replayed (LammpsSetupError).
  LammpsCouplingHost(MPI_Comm comm, const std::string &input_file, const std::string &log_file, bool echo,
                     const std::string &restart_file = "", double restart_time = 0.0);
  ~LammpsCouplingHost();
  LammpsCouplingHost(const LammpsCouplingHost &) = delete;
  LammpsCouplingHost &operator=(const LammpsCouplingHost &) = delete;

  // why a run of this input cannot be resumed ("" when it can): its input cannot be
  // replayed on a restart (jump, label, next, clear)
  const std::string &resume_limitation() const;

  double timestep() const;       // current DEM step [s]
  void set_timestep(double dt);  // as the input command timestep (LAMMPS books the time so far)
  double time() const;           // simulated time of LAMMPS [s]
  std::int64_t step() const;
  std::int64_t particles() const;  // global number of atoms
  void box(double lo[3], double hi[3], int periodic[3]) const;
  double gravity(double g[3]) const;  // sum of fix gravity vectors; returns |g|
  const coupling::MeltMaterial &material() const;
  std::string melt_fix_id() const;
  // whether fix powder/melt has the solid_metal keyword (the coupling then finds the
  // solid-metal surface near each particle)
  bool solid_metal_wall() const;

  // powder of every fix powder/insert (the same on every rank), each as mass [kg], enthalpy
  // [J] and momentum [kg m/s] in the state the particles are inserted with: drawn = all drawn
  // so far (inserted + pending), pending = drawn but not yet placed. The coupling's ledger
  // books the growth of drawn as feed and pending as the pending store.
  void insertion_store(coupling::Amounts &drawn, coupling::Amounts &pending) const;

  // the particles of the melt group on this rank now (state only; exchange fields zero
  // unless an interval is open)
  void local_particles(std::vector<coupling::ExchangeRecord> &out) const;

  // the fluid each of this rank's particles sees over the next advance() (ids: tags in
  // ascending order, states alike); particles without an entry see no fluid (they neither
  // heat nor feel drag). The state moves with a particle that changes rank, and its record
  // names located_by (the coupling's rank that located it) for what it took.
  void set_fluid(const std::vector<std::int64_t> &ids, const std::vector<coupling::FluidState> &states, int located_by);

  // the heat [J] the continuum's implicit energy solve gave each of this rank's listed
  // particles (tags from the records of the last advance()); they take it in the next one
  void set_heat_owed(const std::vector<std::int64_t> &tags, const std::vector<double> &heat);

  // run n DEM steps; records: this rank's particles with their interval exchange
  // (including particles that melted away during the interval). span > 0: the steps span
  // exactly span seconds: fix powder/dt may not lengthen the current step meanwhile, and
  // steps it shortened are made up by further steps, the last one cut. Returns the steps run.
  int advance(int n, std::vector<coupling::ExchangeRecord> &records, double span = 0.0);

  // remove particles (any rank may list any tag; collective); returns how many went
  std::int64_t remove(const std::vector<std::int64_t> &tags);

  // execute one LAMMPS command (e.g. write_restart) between intervals
  void command(const std::string &line);

  // between intervals: the checkpoint a resumed run starts from, in the folder dir
  // (collective): the LAMMPS restart kRestartFile, the sizes of the input's output files
  // kOutputsFile (throws LammpsSetupError when it cannot be written).
  static constexpr const char *kRestartFile = "lammps.restart";
  static constexpr const char *kOutputsFile = "lammps.outputs";
  static constexpr const char *kCommandsFile = "lammps.commands";  // the input's commands as executed
  void write_checkpoint(const std::string &dir);
  // between intervals: every particle as a LAMMPS custom dump (id type x y z vx vy vz radius
  // mass and fix powder/melt's temperature and melted fraction), the simulated time in it
  void write_particles(const std::string &file);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meltdem
