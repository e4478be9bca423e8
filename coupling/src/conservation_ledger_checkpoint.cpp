// ConservationLedger checkpoints: a coupled run that is stopped and resumed from its last
// write time books the steps after it exactly as an uninterrupted run would.
// Doubles go as hexadecimal floats, so nothing is rounded on the way.
#include "meltdem/coupling/conservation_ledger.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace meltdem::coupling {

namespace {

constexpr const char *kMagic = "meltdem-ledger-checkpoint";
constexpr int kVersion = 1;

void put(std::ostream &os, double x)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, " %a", x);
  os << buf;
}

void put(std::ostream &os, const Amounts &a)
{
  for (double x : a) put(os, x);
  os << '\n';
}

void put(std::ostream &os, const ExactSum &s)
{
  put(os, s.hi());
  put(os, s.lo());
}

class Reader {
 public:
  explicit Reader(std::istream &is) : is_(is) {}
  double number()
  {
    std::string t;
    if (!(is_ >> t)) throw std::runtime_error("ledger checkpoint: ends early");
    char *end = nullptr;
    const double x = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || *end) throw std::runtime_error("ledger checkpoint: '" + t + "' is not a number");
    return x;
  }
  void amounts(Amounts &a)
  {
    for (double &x : a) x = number();
  }
  void sum(ExactSum &s)
  {
    const double hi = number();
    s.set(hi, number());
  }

 private:
  std::istream &is_;
};

}  // namespace

void ConservationLedger::save_state(std::ostream &os) const
{
  if (rank_ != 0) return;
  if (history_.empty()) throw std::runtime_error("ledger checkpoint: no step booked yet");
  os << kMagic << ' ' << kVersion << '\n';
  put(os, scale_);
  put(os, auto_scale_);
  for (int c = 0; c < kCategories; ++c)
    for (int q = 0; q < kComponents; ++q) put(os, prev_[c][q]), put(os, first_[c][q]);
  os << '\n';
  for (int q = 0; q < kComponents; ++q)
    put(os, cum_system_sources_[q]), put(os, cum_continuum_sources_[q]), put(os, cum_out_[q]), put(os, cum_lost_[q]),
        put(os, cum_in_[q]);
  os << '\n';
  const LedgerStep &s = history_.back();
  os << s.step << ' ' << s.particles << ' ' << s.lost_particles;
  put(os, s.time);
  put(os, s.dt);
  os << '\n';
  for (const auto &b : s.booked) put(os, b);
  for (const Amounts *a :
       {&s.system_total, &s.continuum_error, &s.system_error, &s.cumulative_continuum_error, &s.cumulative_system_error,
        &s.cumulative_boundary_out, &s.cumulative_lost, &s.cumulative_boundary_in})
    put(os, *a);
  put(os, worst_continuum_error());
  put(os, worst_system_error());
  os << "end\n";
  if (!os) throw std::runtime_error("ledger checkpoint: write failed");
}

void ConservationLedger::load_state(std::istream &is)
{
  std::string magic;
  int version = 0;
  if (!(is >> magic >> version) || magic != kMagic)
    throw std::runtime_error("ledger checkpoint: not a MeltDEM ledger checkpoint");
  if (version != kVersion)
    throw std::runtime_error("ledger checkpoint: version " + std::to_string(version) + ", this build reads " +
                             std::to_string(kVersion));
  Reader r(is);
  r.amounts(scale_);
  r.amounts(auto_scale_);
  for (int c = 0; c < kCategories; ++c)
    for (int q = 0; q < kComponents; ++q) r.sum(prev_[c][q]), r.sum(first_[c][q]);
  for (int q = 0; q < kComponents; ++q)
    r.sum(cum_system_sources_[q]), r.sum(cum_continuum_sources_[q]), r.sum(cum_out_[q]), r.sum(cum_lost_[q]),
        r.sum(cum_in_[q]);
  LedgerStep s;
  if (!(is >> s.step >> s.particles >> s.lost_particles)) throw std::runtime_error("ledger checkpoint: bad step line");
  s.time = r.number();
  s.dt = r.number();
  for (auto &b : s.booked) r.amounts(b);
  for (Amounts *a :
       {&s.system_total, &s.continuum_error, &s.system_error, &s.cumulative_continuum_error, &s.cumulative_system_error,
        &s.cumulative_boundary_out, &s.cumulative_lost, &s.cumulative_boundary_in})
    r.amounts(*a);
  r.amounts(loaded_worst_continuum_);
  r.amounts(loaded_worst_system_);
  std::string end;
  if (!(is >> end) || end != "end") throw std::runtime_error("ledger checkpoint: truncated (no end mark)");
  s.has_previous = s.step > 0;
  history_.assign(1, s);
}

void ConservationLedger::resume_csv(const std::string &path)
{
  if (rank_ != 0) return;
  if (history_.empty()) throw std::runtime_error("ConservationLedger::resume_csv: load_state first");
  const std::int64_t last = history_.back().step;
  std::vector<std::string> kept;
  {
    std::ifstream in(path);
    std::string line;
    if (!std::getline(in, line) || line + '\n' != csv_header())
      throw std::runtime_error("ConservationLedger: " + path + " is missing or not a ledger CSV; cannot resume it");
    while (std::getline(in, line)) {
      const std::int64_t step = std::strtoll(line.c_str(), nullptr, 10);
      if (step > last) break;
      kept.push_back(line);
    }
  }
  csv_ = std::make_unique<std::ofstream>(path, std::ios::trunc);
  if (!*csv_) throw std::runtime_error("ConservationLedger: cannot open " + path + " for writing");
  *csv_ << csv_header();
  for (const auto &l : kept) *csv_ << l << '\n';
  csv_->flush();
}

}  // namespace meltdem::coupling
