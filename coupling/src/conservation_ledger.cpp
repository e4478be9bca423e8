#include "meltdem/coupling/conservation_ledger.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace meltdem::coupling {

namespace {

const char *const kCategoryNames[kCategories] = {"particles",        "continuum",      "pending", "exchange",
                                                 "boundary_in",      "boundary_out",   "lost",    "feed",
                                                 "continuum_source", "particle_source"};
const char *const kComponentNames[kComponents] = {"mass", "enthalpy", "mom_x", "mom_y", "mom_z"};

// exact sum of the stores (particles + continuum + pending) of one component
ExactSum stored_total(const ExactSum (&g)[kCategories][kComponents], int q)
{
  ExactSum t;
  for (int c : {kParticles, kContinuum, kPending}) {
    t.add(g[c][q].hi());
    t.add(g[c][q].lo());
  }
  return t;
}

void add_sum(ExactSum &to, const ExactSum &x, double sign)
{
  to.add(sign * x.hi());
  to.add(sign * x.lo());
}

// sources of the whole system over one step: in - out - lost + feed + all external sources
ExactSum system_sources(const ExactSum (&g)[kCategories][kComponents], int q)
{
  ExactSum s;
  add_sum(s, g[kBoundaryIn][q], 1.0);
  add_sum(s, g[kBoundaryOut][q], -1.0);
  add_sum(s, g[kLost][q], -1.0);
  add_sum(s, g[kFeed][q], 1.0);
  add_sum(s, g[kContinuumSource][q], 1.0);
  add_sum(s, g[kParticleSource][q], 1.0);
  return s;
}

// sources of the continuum (Codina2019: phase change + boundaries, plus external sources)
ExactSum continuum_sources(const ExactSum (&g)[kCategories][kComponents], int q)
{
  ExactSum s;
  add_sum(s, g[kExchange][q], 1.0);
  add_sum(s, g[kBoundaryIn][q], 1.0);
  add_sum(s, g[kBoundaryOut][q], -1.0);
  add_sum(s, g[kContinuumSource][q], 1.0);
  return s;
}

}  // namespace

const char *category_name(Category c)
{
  return kCategoryNames[c];
}
const char *component_name(Component c)
{
  return kComponentNames[c];
}

ConservationLedger::ConservationLedger(MPI_Comm comm) : comm_(comm)
{
  int init = 0;
  MPI_Initialized(&init);
  if (!init) throw std::logic_error("ConservationLedger: MPI is not initialised");
  MPI_Comm_rank(comm_, &rank_);
}

ConservationLedger::~ConservationLedger() = default;

void ConservationLedger::begin_step(double time, double dt)
{
  if (open_step_) throw std::logic_error("ConservationLedger: begin_step before end_step of the previous step");
  if (!std::isfinite(time) || !std::isfinite(dt) || dt < 0.0)
    throw std::invalid_argument("ConservationLedger: time and dt must be finite, dt >= 0");
  open_step_ = true;
  time_ = time;
  dt_ = dt;
  for (auto &row : local_)
    for (auto &e : row) e.set(0.0, 0.0);
  local_particles_ = local_lost_ = 0;
}

void ConservationLedger::book(Category c, const Amounts &a)
{
  if (!open_step_) throw std::logic_error("ConservationLedger: booking outside begin_step/end_step");
  if (c < 0 || c >= kCategories) throw std::invalid_argument("ConservationLedger: unknown category");
  for (int q = 0; q < kComponents; ++q) {
    if (!std::isfinite(a[q]))
      throw std::invalid_argument(std::string("ConservationLedger: non-finite ") + kComponentNames[q] + " booked in " +
                                  kCategoryNames[c]);
    local_[c][q].add(a[q]);
  }
}

void ConservationLedger::book(Category c, Component q, double value)
{
  Amounts a{};
  a[q] = value;
  book(c, a);
}

namespace {
// the particle's exchange, each term added on its own so no difference is rounded first
void book_exchange(ExactSum (&row)[kComponents], const ExchangeRecord &r)
{
  row[kMass].add(r.mass_out);
  row[kEnthalpy].add(r.enthalpy_out);
  row[kEnthalpy].add(-r.heat_absorbed);
  for (int d = 0; d < 3; ++d) {
    row[kMomX + d].add(r.momentum_out[d]);
    row[kMomX + d].add(-r.impulse_from_fluid[d]);
  }
}
}  // namespace

void ConservationLedger::book_particle(const ExchangeRecord &r)
{
  const Amounts stored = stored_in(r);
  book(kParticles, stored);  // checks the step is open and the values finite
  const Amounts ex = net_to_continuum(r);
  for (int q = 0; q < kComponents; ++q)
    if (!std::isfinite(ex[q]))
      throw std::invalid_argument("ConservationLedger: non-finite exchange of particle " + std::to_string(r.id));
  book_exchange(local_[kExchange], r);
  if (r.external_heat != 0.0) book(kParticleSource, kEnthalpy, r.external_heat);
  ++local_particles_;
}

void ConservationLedger::book_particles(const std::vector<ExchangeRecord> &records)
{
  for (const auto &r : records) book_particle(r);
}

void ConservationLedger::book_lost(const ExchangeRecord &r)
{
  book(kLost, stored_in(r));
  book_exchange(local_[kExchange], r);
  if (r.external_heat != 0.0) book(kParticleSource, kEnthalpy, r.external_heat);
  ++local_lost_;
}

const LedgerStep &ConservationLedger::end_step()
{
  if (!open_step_) throw std::logic_error("ConservationLedger: end_step without begin_step");
  open_step_ = false;

  // gather every rank's (hi, lo) pairs and the counts; sum in rank order -> same on all ranks
  constexpr int n_sums = kCategories * kComponents;
  constexpr int n_pack = 2 * n_sums + 2;
  std::vector<double> pack(n_pack);
  for (int c = 0; c < kCategories; ++c)
    for (int q = 0; q < kComponents; ++q) {
      pack[2 * (c * kComponents + q)] = local_[c][q].hi();
      pack[2 * (c * kComponents + q) + 1] = local_[c][q].lo();
    }
  pack[2 * n_sums] = static_cast<double>(local_particles_);
  pack[2 * n_sums + 1] = static_cast<double>(local_lost_);
  int nranks = 1;
  MPI_Comm_size(comm_, &nranks);
  std::vector<double> all(static_cast<std::size_t>(n_pack) * nranks);
  MPI_Allgather(pack.data(), n_pack, MPI_DOUBLE, all.data(), n_pack, MPI_DOUBLE, comm_);

  ExactSum g[kCategories][kComponents];
  LedgerStep s;
  for (int r = 0; r < nranks; ++r) {
    const double *p = all.data() + static_cast<std::size_t>(r) * n_pack;
    for (int i = 0; i < n_sums; ++i) {
      g[i / kComponents][i % kComponents].add(p[2 * i]);
      g[i / kComponents][i % kComponents].add(p[2 * i + 1]);
    }
    s.particles += static_cast<std::int64_t>(p[2 * n_sums]);
    s.lost_particles += static_cast<std::int64_t>(p[2 * n_sums + 1]);
  }

  s.step = history_.empty() ? 0 : history_.back().step + 1;
  s.time = time_;
  s.dt = dt_;
  s.has_previous = !history_.empty();
  for (int c = 0; c < kCategories; ++c)
    for (int q = 0; q < kComponents; ++q) s.booked[c][q] = g[c][q].value();

  // momentum is a vector: each component's error is measured against the largest
  // momentum magnitude seen, not against its own (possibly zero) component
  double momentum_magnitude = 0.0;
  for (int q = kMomX; q <= kMomZ; ++q) {
    const double v = stored_total(g, q).value();
    momentum_magnitude += v * v;
  }
  momentum_magnitude = std::sqrt(momentum_magnitude);
  for (int q = 0; q < kComponents; ++q) {
    const ExactSum total = stored_total(g, q);
    s.system_total[q] = total.value();
    auto_scale_[q] = std::max(auto_scale_[q], q >= kMomX ? momentum_magnitude : std::abs(s.system_total[q]));
    const double floor = scale_[q] > 0.0 ? scale_[q] : auto_scale_[q];
    const double den_sys = std::max(std::abs(s.system_total[q]), floor);
    const double den_con = std::max(std::abs(s.booked[kContinuum][q]), floor);
    const auto ratio = [](double num, double den) { return den > 0.0 ? num / den : (num == 0.0 ? 0.0 : HUGE_VAL); };

    if (s.has_previous) {
      // step: sources - (new - old), every term exact until the final rounding
      const ExactSum src_sys = system_sources(g, q), src_con = continuum_sources(g, q);
      ExactSum num_sys = src_sys, num_con = src_con;
      add_sum(num_sys, stored_total(prev_, q), 1.0);
      add_sum(num_sys, total, -1.0);
      add_sum(num_con, prev_[kContinuum][q], 1.0);
      add_sum(num_con, g[kContinuum][q], -1.0);
      s.system_error[q] = ratio(num_sys.value(), den_sys);
      s.continuum_error[q] = ratio(num_con.value(), den_con);

      add_sum(cum_system_sources_[q], src_sys, 1.0);
      add_sum(cum_continuum_sources_[q], src_con, 1.0);
      add_sum(cum_in_[q], g[kBoundaryIn][q], 1.0);
      add_sum(cum_out_[q], g[kBoundaryOut][q], 1.0);
      add_sum(cum_lost_[q], g[kLost][q], 1.0);

      ExactSum cum_sys = cum_system_sources_[q], cum_con = cum_continuum_sources_[q];
      add_sum(cum_sys, stored_total(first_, q), 1.0);
      add_sum(cum_sys, total, -1.0);
      add_sum(cum_con, first_[kContinuum][q], 1.0);
      add_sum(cum_con, g[kContinuum][q], -1.0);
      s.cumulative_system_error[q] = ratio(cum_sys.value(), den_sys);
      s.cumulative_continuum_error[q] = ratio(cum_con.value(), den_con);
    }
    s.cumulative_boundary_in[q] = cum_in_[q].value();
    s.cumulative_boundary_out[q] = cum_out_[q].value();
    s.cumulative_lost[q] = cum_lost_[q].value();
  }

  for (int c = 0; c < kCategories; ++c)
    for (int q = 0; q < kComponents; ++q) {
      prev_[c][q] = g[c][q];
      if (!s.has_previous) first_[c][q] = g[c][q];
    }
  history_.push_back(s);
  if (csv_ && rank_ == 0) *csv_ << csv_row(s) << std::flush;
  return history_.back();
}

void ConservationLedger::open_csv(const std::string &path)
{
  if (rank_ != 0) return;
  csv_ = std::make_unique<std::ofstream>(path, std::ios::trunc);
  if (!*csv_) throw std::runtime_error("ConservationLedger: cannot open " + path + " for writing");
  *csv_ << csv_header() << std::flush;
}

std::string ConservationLedger::csv_header()
{
  std::ostringstream o;
  o << "step,time,dt,particles,lost_particles";
  for (int q = 0; q < kComponents; ++q) {
    const std::string n = kComponentNames[q];
    for (int c = 0; c < kCategories; ++c) o << ',' << n << '_' << kCategoryNames[c];
    o << ',' << n << "_total," << n << "_continuum_error," << n << "_system_error," << n
      << "_cumulative_continuum_error," << n << "_cumulative_system_error," << n << "_cumulative_boundary_in," << n
      << "_cumulative_boundary_out," << n << "_cumulative_lost";
  }
  o << '\n';
  return o.str();
}

std::string ConservationLedger::csv_row(const LedgerStep &s)
{
  std::ostringstream o;
  o << std::setprecision(17) << s.step << ',' << s.time << ',' << s.dt << ',' << s.particles << ',' << s.lost_particles;
  for (int q = 0; q < kComponents; ++q) {
    for (int c = 0; c < kCategories; ++c) o << ',' << s.booked[c][q];
    o << ',' << s.system_total[q] << ',' << s.continuum_error[q] << ',' << s.system_error[q] << ','
      << s.cumulative_continuum_error[q] << ',' << s.cumulative_system_error[q] << ',' << s.cumulative_boundary_in[q]
      << ',' << s.cumulative_boundary_out[q] << ',' << s.cumulative_lost[q];
  }
  o << '\n';
  return o.str();
}

namespace {
Amounts worst(const std::vector<LedgerStep> &h, Amounts LedgerStep::*field)
{
  Amounts w{};
  for (const auto &s : h)
    if (s.has_previous)
      for (int q = 0; q < kComponents; ++q) w[q] = std::max(w[q], std::abs((s.*field)[q]));
  return w;
}
}  // namespace

Amounts ConservationLedger::worst_continuum_error() const
{
  Amounts w = worst(history_, &LedgerStep::continuum_error);
  for (int q = 0; q < kComponents; ++q) w[q] = std::max(w[q], loaded_worst_continuum_[q]);
  return w;
}
Amounts ConservationLedger::worst_system_error() const
{
  Amounts w = worst(history_, &LedgerStep::system_error);
  for (int q = 0; q < kComponents; ++q) w[q] = std::max(w[q], loaded_worst_system_[q]);
  return w;
}

}  // namespace meltdem::coupling
