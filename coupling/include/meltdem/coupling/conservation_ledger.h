#pragma once
// Conservation ledger of metal mass, enthalpy and momentum across the particle-continuum
// coupling (Codina2019 §2.3). Every step the solver books where each amount is:
//   stored    - in particles (from the exchange records), in the continuum (sum over cells),
//               pending insertion (powder scheduled but not yet inserted);
//   exchanged - handed from particles to the continuum (melt, minus heat and impulse taken);
//   crossing  - through continuum boundaries (in / out), fed into the pending store,
//               lost (particles leaving the mesh: booked as outflow, never dropped),
//               external sources (laser, gravity, walls) into the continuum or the particles.
// end_step() reduces the bookings over the communicator and evaluates the balances.
//
// Relative balance errors, Codina2019 eq. 2.20 (mass), 2.26 (energy), 2.36 (momentum):
//   relativeError = (X_sources - (X_new - X_old)) / X_new
// i.e. Codina2019 normalises by the NEW total of the continuum (the VOF domain) at the end of
// the step, signed, without absolute value; its sources are phase change + boundaries. We
// evaluate exactly that for the continuum ('continuum' errors, sources = exchange + in - out +
// continuum sources) and the same form for the whole system particles + continuum + pending
// ('system' errors, sources = in - out - lost + feed + all external sources), where the
// particle-to-continuum exchange cancels. Codina2019's X_new can be ~0 (momentum of a gas at
// rest), so the denominator is max(|X_new|, scale), scale = set_reference_scale() or, by
// default, the largest |system total| seen so far for that component, for momentum the largest
// momentum magnitude (an x-momentum error is measured against the momentum present, not
// divided by a zero x component).
// Cumulative errors: (sum of sources since the first step - (X_now - X_first)) / same denominator.
//
// MPI: every booking is kept as a compensated (double-double) sum; end_step gathers each
// rank's (hi, lo) pairs and sums them in rank order with the same compensated sum, so every
// rank gets the same totals and serial and parallel runs agree to ~1e-16 relative.

#include "meltdem/coupling/exact_sum.h"
#include "meltdem/coupling/exchange_record.h"

#include <mpi.h>

#include <cstdint>
#include <fstream>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace meltdem::coupling {

// Booking categories (one compensated sum per category and component).
enum Category : int {
  kParticles = 0,    // stored in particles at the end of the step
  kContinuum,        // stored in the continuum at the end of the step
  kPending,          // stored in particles pending insertion at the end of the step
  kExchange,         // particles -> continuum over the step (net)
  kBoundaryIn,       // into the continuum through its boundaries over the step
  kBoundaryOut,      // out of the continuum through its boundaries over the step (>= 0 for mass)
  kLost,             // carried out by particles leaving the mesh over the step (outflow)
  kFeed,             // new powder added to the pending store over the step
  kContinuumSource,  // external sources into the continuum (laser heat, gravity, ...)
  kParticleSource,   // external sources into the particles (gravity, walls, laser, ...)
  kCategories
};

const char *category_name(Category c);
const char *component_name(Component c);

struct LedgerStep {
  std::int64_t step = 0;
  double time = 0.0, dt = 0.0;
  std::int64_t particles = 0, lost_particles = 0;  // counts this step (global)
  Amounts booked[kCategories] = {};                // global totals of this step
  Amounts system_total = {};                       // particles + continuum + pending
  Amounts continuum_error = {};                    // Codina2019 eq. 2.20 / 2.26 / 2.36, continuum
  Amounts system_error = {};                       // same form, whole system
  Amounts cumulative_continuum_error = {};
  Amounts cumulative_system_error = {};
  Amounts cumulative_boundary_out = {}, cumulative_lost = {}, cumulative_boundary_in = {};
  bool has_previous = false;  // false for the first step: errors are 0 by definition
};

class ConservationLedger {
 public:
  // comm: the communicator the totals are reduced over (MPI must be initialised)
  explicit ConservationLedger(MPI_Comm comm = MPI_COMM_WORLD);
  ~ConservationLedger();
  ConservationLedger(const ConservationLedger &) = delete;
  ConservationLedger &operator=(const ConservationLedger &) = delete;

  // start a step: clears this rank's bookings; throws if the previous step was not ended
  void begin_step(double time, double dt);

  // a particle present at the end of the step: its inventory and its exchange with the continuum
  void book_particle(const ExchangeRecord &r);
  void book_particles(const std::vector<ExchangeRecord> &records);
  // a particle that left the mesh this step: its exchange up to leaving is booked, its
  // inventory goes to 'lost' (an outflow of the system); it must not also be booked above
  void book_lost(const ExchangeRecord &r);

  // add an amount to a category on this rank (the continuum sum over local cells, boundary
  // fluxes, pending store, feed, sources); each rank books only what it owns
  void book(Category c, const Amounts &a);
  void book(Category c, Component q, double value);

  // collective over the communicator: reduce, evaluate the balances, append the CSV row
  const LedgerStep &end_step();

  // denominator floor per component (see header comment); 0 = automatic
  void set_reference_scale(const Amounts &scale) { scale_ = scale; }

  // rank 0 writes one row per end_step() to path (header written once, file truncated)
  void open_csv(const std::string &path);
  // after load_state(): keep path's rows up to the loaded step, drop later ones (a run that
  // went on past its checkpoint before it stopped) and append from there
  void resume_csv(const std::string &path);

  // Checkpoint (conservation_ledger_checkpoint.cpp): everything the balances of later steps
  // depend on (previous and first totals, cumulative sources, scales, the last step and the
  // worst errors so far), as text with every double exact. save_state writes on rank 0 only
  // (os may be a dummy elsewhere); load_state is read by every rank from the same file, so
  // a resumed run continues the ledger as if it had not stopped. Throws std::runtime_error
  // for a malformed checkpoint.
  void save_state(std::ostream &os) const;
  void load_state(std::istream &is);
  static std::string csv_header();
  static std::string csv_row(const LedgerStep &s);

  const std::vector<LedgerStep> &history() const { return history_; }
  const LedgerStep &last() const { return history_.back(); }
  // the largest |error| so far over steps with a previous step (per component)
  Amounts worst_continuum_error() const;
  Amounts worst_system_error() const;

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  bool open_step_ = false;
  double time_ = 0.0, dt_ = 0.0;
  ExactSum local_[kCategories][kComponents];
  std::int64_t local_particles_ = 0, local_lost_ = 0;
  std::vector<LedgerStep> history_;
  Amounts scale_ = {};
  Amounts auto_scale_ = {};
  // previous and first global totals kept as compensated sums (hi, lo) for exact differences
  ExactSum prev_[kCategories][kComponents], first_[kCategories][kComponents];
  ExactSum cum_system_sources_[kComponents], cum_continuum_sources_[kComponents];
  ExactSum cum_out_[kComponents], cum_lost_[kComponents], cum_in_[kComponents];
  // the worst errors of the steps before a checkpoint this run resumed from
  Amounts loaded_worst_continuum_ = {}, loaded_worst_system_ = {};
  std::unique_ptr<std::ofstream> csv_;
};

}  // namespace meltdem::coupling
