// Conservation ledger: Codina2019 §2.3 balance errors (eq. 2.20, 2.26, 2.36) on a
// synthetic melt of the Codina2019 particle, detection of a missing booking, lost particles
// booked as outflow, the CSV a user plots.
#include "ledger_synthetic_melt.h"
#include "meltdem/coupling/conservation_ledger.h"
#include "validation_report.h"

#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace meltdem::coupling;
using namespace meltdem::coupling::testing;
using meltdem::testing::expect_absolute;
using meltdem::testing::expect_relative;

namespace {

// gtest_main does not start MPI; the ledger reduces over MPI_COMM_SELF here
class MpiEnvironment : public ::testing::Environment {
 public:
  void SetUp() override
  {
    int init = 0;
    MPI_Initialized(&init);
    if (!init) MPI_Init(nullptr, nullptr);
  }
  void TearDown() override
  {
    int fin = 0;
    MPI_Finalized(&fin);
    if (!fin) MPI_Finalize();
  }
};
[[maybe_unused]] auto *const mpi_env = ::testing::AddGlobalTestEnvironment(new MpiEnvironment);

const char *const names[kComponents] = {"mass", "enthalpy", "momentum x", "momentum y", "momentum z"};

// Per-step tolerance: a few roundings of the amounts moved, over the Codina2019 denominator (the
// new total). The synthetic gas holds ~1.5e-3 J while ~0.3 J pass through the cells (heat
// taken, melt enthalpy returned), so one rounding of the moved enthalpy is ~200 eps of the
// total: 1e-13 for enthalpy, 1e-14 for mass and momentum (moved amounts ~ the totals).
double step_tol(int q)
{
  return q == kEnthalpy ? 1e-13 : 1e-14;
}

// the step of the largest |error| of one component
double worst_at(const ConservationLedger &l, Amounts LedgerStep::*field, int q, std::int64_t *at = nullptr)
{
  double w = 0.0;
  for (const auto &s : l.history())
    if (std::abs((s.*field)[q]) >= w) {
      w = std::abs((s.*field)[q]);
      if (at) *at = s.step;
    }
  return w;
}

}  // namespace

TEST(ConservationLedger, ThesisParticleMeltBalancesClose)
{
  ConservationLedger ledger(MPI_COMM_SELF);
  // the CSV for plotting (coupling/tests/ledger_csv_check.py, scripts/plot_ledger.py)
  if (const char *csv = std::getenv("MELTDEM_LEDGER_CSV")) ledger.open_csv(csv);
  SyntheticOptions o;
  run_synthetic_melt(ledger, o);
  const auto &h = ledger.history();
  ASSERT_EQ(static_cast<int>(h.size()), o.melt_steps + o.outflow_steps + 1);

  // per-step Codina2019 errors (continuum) and whole-system errors; Codina2019 reached 2e-13 (mass),
  // 1.5e-5 (energy), 1.5e-6 (momentum)
  const Amounts wc = ledger.worst_continuum_error(), ws = ledger.worst_system_error();
  for (int q : {kMass, kEnthalpy, kMomY}) {
    expect_absolute(std::string("worst per-step continuum error, ") + names[q] + " (eq. 2.20/2.26/2.36)", wc[q], 0.0,
                    step_tol(q));
    expect_absolute(std::string("worst per-step system error, ") + names[q], ws[q], 0.0, step_tol(q));
    expect_absolute(std::string("final cumulative system error, ") + names[q],
                    std::abs(h.back().cumulative_system_error[q]), 0.0, 1e-13);
    expect_absolute(std::string("final cumulative continuum error, ") + names[q],
                    std::abs(h.back().cumulative_continuum_error[q]), 0.0, 1e-13);
  }
  // x/z momentum: exactly zero here (particle 0 moves along y), so the errors are exactly 0
  EXPECT_EQ(wc[kMomX], 0.0);
  EXPECT_EQ(ws[kMomZ], 0.0);

  // the particle melted completely, its whole mass crossed into the continuum and then left
  const MeltMaterial mat = thesis_steel();
  ExactSum mass_in, enthalpy_exchanged;
  for (const auto &s : h) mass_in.add(s.booked[kExchange][kMass]);
  EXPECT_EQ(h.back().particles, 0);
  EXPECT_EQ(h.back().booked[kParticles][kMass], 0.0);
  expect_relative("mass handed to the continuum vs thesis particle mass", mass_in.value(), kThesisMass, 1e-15);
  // the metal left through the outlet: 1 - 0.9^outflow_steps of it; the gas in = out
  const double gas_out = h.back().cumulative_boundary_out[kMass] - h.back().cumulative_boundary_in[kMass];
  expect_relative("metal through the outlet", gas_out, kThesisMass * (1.0 - std::pow(0.9, o.outflow_steps)), 1e-12);
  // particle's heat: m (cp Tm + L) absorbed (from 0 K) = enthalpy handed over
  double absorbed = 0.0;
  for (const auto &s : h) absorbed += s.booked[kExchange][kEnthalpy];
  expect_absolute("net enthalpy to the continuum (handed - absorbed) / m (cp Tm + L)",
                  absorbed / (kThesisMass * (mat.cp * mat.Tmelt + mat.latent)), 0.0, 1e-13);
}

TEST(ConservationLedger, MissingBookingIsDetected)
{
  const double tol = 1e-12;
  {
    // the melt of step 40 never reaches the cells: continuum and system balances both break there
    ConservationLedger ledger(MPI_COMM_SELF);
    SyntheticOptions o;
    o.skip_cell_update_step = 40;
    run_synthetic_melt(ledger, o);
    std::int64_t at = -1;
    const double e = worst_at(ledger, &LedgerStep::continuum_error, kMass, &at);
    expect_absolute("step of the missing melt booking", static_cast<double>(at), 40.0, 0.0);
    EXPECT_GT(e, tol) << "missing melt not detected in the continuum mass balance";
    // the Codina2019 form exactly: (sources - (new - old)) / new = the melt that never arrived / new
    const LedgerStep &s40 = ledger.history()[40];
    double den = std::abs(s40.booked[kContinuum][kMass]);
    for (int k = 0; k <= 40; ++k) den = std::max(den, std::abs(ledger.history()[k].system_total[kMass]));
    expect_relative("eq. 2.20 at the missing booking = melt of the step / max(|mass_new|, largest total)",
                    s40.continuum_error[kMass], s40.booked[kExchange][kMass] / den, 1e-10);
    EXPECT_GT(worst_at(ledger, &LedgerStep::system_error, kEnthalpy), tol);
    EXPECT_GT(worst_at(ledger, &LedgerStep::system_error, kMomY), tol);
    std::cout << "missing melt booking: continuum mass error " << e << " at step " << at << "\n";
    // the cumulative error keeps the defect
    EXPECT_GT(std::abs(ledger.last().cumulative_system_error[kMass]), tol);
  }
  {
    // metal leaves the cells at step 220 but the outflow is not booked
    ConservationLedger ledger(MPI_COMM_SELF);
    SyntheticOptions o;
    o.skip_outflow_booking_step = 220;
    run_synthetic_melt(ledger, o);
    std::int64_t at = -1;
    const double e = worst_at(ledger, &LedgerStep::system_error, kMass, &at);
    EXPECT_EQ(at, 220);
    EXPECT_GT(e, tol);
    EXPECT_GT(worst_at(ledger, &LedgerStep::continuum_error, kMomY), tol);
    std::cout << "missing outflow booking: system mass error " << e << " at step " << at << "\n";
  }
}

TEST(ConservationLedger, LostParticleIsBookedAsOutflow)
{
  // particle 0 leaves the mesh half molten at step 100; particle 1 melts completely
  ConservationLedger ledger(MPI_COMM_SELF);
  SyntheticOptions o;
  o.particles = 2;
  o.lose_particle_step = 100;
  double lost_mass = -1.0;
  o.on_step = [&](const LedgerStep &s) {
    if (s.step == 100) {
      EXPECT_EQ(s.lost_particles, 1);
      lost_mass = s.booked[kLost][kMass];
    }
  };
  run_synthetic_melt(ledger, o);
  const Amounts ws = ledger.worst_system_error();
  for (int q : {kMass, kEnthalpy, kMomX, kMomY, kMomZ})
    expect_absolute(std::string("worst per-step system error with a lost particle, ") + names[q], ws[q], 0.0,
                    step_tol(q));
  EXPECT_GT(lost_mass, 0.1 * kThesisMass);
  EXPECT_LT(lost_mass, kThesisMass);
  expect_relative("cumulative lost mass = mass at leaving", ledger.last().cumulative_lost[kMass], lost_mass, 0.0);
  // the metal of the lost particle never reached the continuum; the rest did
  ExactSum exchanged;
  for (const auto &s : ledger.history()) exchanged.add(s.booked[kExchange][kMass]);
  expect_relative("exchanged + lost = initial particle mass", exchanged.value() + lost_mass, kThesisMass * (1.0 + 1.37),
                  1e-15);

  // the same particle vanishing without booking: the system balance catches it at that step
  ConservationLedger silent(MPI_COMM_SELF);
  o.drop_lost_silently = true;
  o.on_step = nullptr;
  run_synthetic_melt(silent, o);
  std::int64_t at = -1;
  const double e = worst_at(silent, &LedgerStep::system_error, kMass, &at);
  EXPECT_EQ(at, 100);
  double den = 0.0;  // the default denominator floor: the largest |system total| so far
  for (int k = 0; k <= 100; ++k) den = std::max(den, std::abs(silent.history()[k].system_total[kMass]));
  expect_relative("silently dropped particle: system mass error = its mass / largest total", e, lost_mass / den, 1e-10);
}

TEST(ConservationLedger, CsvHeaderAndRows)
{
  const std::string path = ::testing::TempDir() + "ledger_test.csv";
  ConservationLedger ledger(MPI_COMM_SELF);
  ledger.open_csv(path);
  SyntheticOptions o;
  o.melt_steps = 4;
  o.outflow_steps = 2;
  run_synthetic_melt(ledger, o);
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 1u + 7u);  // header once, one row per step
  EXPECT_EQ(lines[0] + "\n", ConservationLedger::csv_header());
  const auto split = [](const std::string &l) {
    std::vector<std::string> f;
    std::stringstream ss(l);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    return f;
  };
  const auto head = split(lines[0]);
  ASSERT_EQ(head.size(), 5u + kComponents * (kCategories + 8u));
  EXPECT_EQ(head[0], "step");
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = split(lines[i]);
    ASSERT_EQ(f.size(), head.size()) << "row " << i;
    EXPECT_EQ(std::stoll(f[0]), static_cast<long long>(i - 1));
    // full precision: the row reads back to the booked doubles
    for (std::size_t k = 0; k < head.size(); ++k)
      if (head[k] == "mass_continuum")
        EXPECT_EQ(std::stod(f[k]), ledger.history()[i - 1].booked[kContinuum][kMass]);
      else if (head[k] == "enthalpy_system_error")
        EXPECT_EQ(std::stod(f[k]), ledger.history()[i - 1].system_error[kEnthalpy]);
  }
  std::remove(path.c_str());
}

TEST(ConservationLedger, BadUse)
{
  ConservationLedger ledger(MPI_COMM_SELF);
  EXPECT_THROW(ledger.book(kContinuum, kMass, 1.0), std::logic_error);
  EXPECT_THROW(ledger.end_step(), std::logic_error);
  ledger.begin_step(0.0, 1e-6);
  EXPECT_THROW(ledger.begin_step(0.0, 1e-6), std::logic_error);
  EXPECT_THROW(ledger.book(kContinuum, kEnthalpy, std::nan("")), std::invalid_argument);
  ExchangeRecord r;
  r.heat_absorbed = HUGE_VAL;
  EXPECT_THROW(ledger.book_particle(r), std::invalid_argument);
  ledger.end_step();
  EXPECT_THROW(ledger.begin_step(1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(ledger.open_csv("/nonexistent-dir/x.csv"), std::runtime_error);
}

TEST(ConservationLedger, PendingFeedAndReferenceScale)
{
  // powder fed into the pending store, then inserted as a particle at rest in a gas at rest:
  // the system balance needs the feed booked; the momentum totals are exactly 0, so the
  // relative momentum error uses the reference scale instead of dividing by zero
  const double m = kThesisMass, h = 48.35 * 300.0;
  const auto run = [&](bool book_feed, const Amounts &scale) {
    ConservationLedger l(MPI_COMM_SELF);
    l.set_reference_scale(scale);
    const Amounts gas{1e-6, 1e-6 * 3e5, 0.0, 0.0, 0.0};
    const Amounts powder{m, m * h, 0.0, 0.0, 0.0};
    // step 0: nothing pending; step 1: fed to pending; step 2: inserted; step 3: a stray impulse
    for (int step = 0; step < 4; ++step) {
      l.begin_step(step * 1e-5, 1e-5);
      l.book(kContinuum, gas);
      if (step == 1) {
        l.book(kPending, powder);
        if (book_feed) l.book(kFeed, powder);
      }
      if (step >= 2) {
        ExchangeRecord r;
        r.mass = m, r.h = h;
        if (step == 3) r.v = Eigen::Vector3d(0.0, 1e-3, 0.0);  // momentum from nowhere
        l.book_particle(r);
      }
      l.end_step();
    }
    return l.history();
  };
  const Amounts scale{0.0, 0.0, 1e-6, 1e-6, 1e-6};
  const auto ok = run(true, scale);
  for (const auto &s : ok)
    for (int q : {kMass, kEnthalpy}) EXPECT_LE(std::abs(s.system_error[q]), 1e-15) << s.step << " " << names[q];
  expect_absolute("inserted pending powder: system mass error", std::abs(ok[2].system_error[kMass]), 0.0, 1e-15);
  // the stray momentum m * 1e-3 shows against the scale 1e-6, not as inf or NaN
  expect_relative("momentum from nowhere / reference scale", std::abs(ok[3].system_error[kMomY]), m * 1e-3 / 1e-6,
                  1e-12);
  const auto missing = run(false, scale);
  EXPECT_GT(std::abs(missing[1].system_error[kMass]), 1e-3) << "unbooked feed not detected";
  // no scale given: the automatic floor is the largest |total| seen, i.e. the stray momentum
  // itself: the Codina2019 form gives (0 - (M_new - 0)) / |M_new| = -1, never inf or NaN
  const auto no_scale = run(true, Amounts{});
  EXPECT_EQ(no_scale[3].system_error[kMomY], -1.0);
  EXPECT_EQ(no_scale[2].system_error[kMomY], 0.0);
}

namespace {
// step i of an arbitrary but fixed booking sequence: every category and component moves, the
// continuum and particles change by what was exchanged, some metal leaves
void book_arbitrary_step(ConservationLedger &l, int i)
{
  l.begin_step(1e-3 * i, 1e-3);
  for (int c = 0; c < kCategories; ++c)
    for (int q = 0; q < kComponents; ++q)
      l.book(Category(c), Component(q), std::sin(1.0 + 0.37 * i + 1.3 * c + 0.71 * q) * std::pow(10.0, -(q % 3)));
  l.end_step();
}

std::vector<std::string> read_lines(const std::string &path)
{
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string s; std::getline(in, s);) lines.push_back(s);
  return lines;
}
}  // namespace

// A run stopped after its checkpoint and resumed from it: a fresh ledger that loads
// the state saved after step k and books steps k+1.. ends with every total, error and
// cumulative of the uninterrupted ledger, bit for bit, and its CSV (the stopped run wrote 3
// rows past the checkpoint) equals the uninterrupted CSV line for line.
TEST(ConservationLedger, CheckpointResumesExactly)
{
  constexpr int n = 20, k = 9;
  const std::string whole_csv = ::testing::TempDir() + "ledger_whole.csv",
                    resumed_csv = ::testing::TempDir() + "ledger_resumed.csv";
  ConservationLedger whole(MPI_COMM_SELF);
  whole.open_csv(whole_csv);
  for (int i = 0; i < n; ++i) book_arbitrary_step(whole, i);

  std::string state;
  {
    ConservationLedger stopped(MPI_COMM_SELF);
    stopped.open_csv(resumed_csv);
    for (int i = 0; i <= k; ++i) book_arbitrary_step(stopped, i);
    std::ostringstream os;
    stopped.save_state(os);
    state = os.str();
    for (int i = k + 1; i <= k + 3; ++i) book_arbitrary_step(stopped, i);  // then killed
  }
  ConservationLedger resumed(MPI_COMM_SELF);
  std::istringstream is(state);
  resumed.load_state(is);
  resumed.resume_csv(resumed_csv);
  EXPECT_EQ(resumed.last().step, k);
  for (int i = k + 1; i < n; ++i) book_arbitrary_step(resumed, i);

  const LedgerStep &a = whole.last(), &b = resumed.last();
  EXPECT_EQ(a.step, b.step);
  int differing = 0;
  const auto same = [&](const Amounts &x, const Amounts &y) {
    for (int q = 0; q < kComponents; ++q) differing += x[q] != y[q];
  };
  same(a.system_total, b.system_total);
  same(a.system_error, b.system_error);
  same(a.continuum_error, b.continuum_error);
  same(a.cumulative_system_error, b.cumulative_system_error);
  same(a.cumulative_continuum_error, b.cumulative_continuum_error);
  same(a.cumulative_boundary_in, b.cumulative_boundary_in);
  same(a.cumulative_boundary_out, b.cumulative_boundary_out);
  same(a.cumulative_lost, b.cumulative_lost);
  same(whole.worst_system_error(), resumed.worst_system_error());
  same(whole.worst_continuum_error(), resumed.worst_continuum_error());
  expect_absolute("ledger resumed from a checkpoint: final totals, errors and cumulatives differing from the "
                  "uninterrupted run (of 50)",
                  differing, 0.0, 0.0);
  const auto lw = read_lines(whole_csv), lr = read_lines(resumed_csv);
  EXPECT_EQ(lw.size(), std::size_t(n + 1));
  EXPECT_EQ(lw, lr) << "the resumed CSV differs from the uninterrupted one";

  std::istringstream bad("meltdem-ledger-checkpoint 1\n0x1p+0 0x1p+0");
  ConservationLedger broken(MPI_COMM_SELF);
  EXPECT_THROW(broken.load_state(bad), std::runtime_error);
  std::istringstream foreign("something else");
  EXPECT_THROW(broken.load_state(foreign), std::runtime_error);
  std::remove(whole_csv.c_str());
  std::remove(resumed_csv.c_str());
}
