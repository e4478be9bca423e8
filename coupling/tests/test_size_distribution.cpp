// Size distributions for fix powder/insert: truncated CDFs, inverse sampling, by-volume
// weighting, table parsing and the checkpointable generator.
#include "meltdem/coupling/size_distribution.h"
#include "validation_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

using namespace meltdem::coupling;
using meltdem::testing::expect_absolute;
using meltdem::testing::expect_relative;

namespace {
// Kolmogorov-Smirnov statistic of n draws against the distribution's own CDF
double ks_statistic(const SizeDistribution &dist, std::uint64_t seed, int n)
{
  Rng64 rng(seed);
  std::vector<double> d(n);
  for (auto &x : d) x = dist.draw(rng);
  std::sort(d.begin(), d.end());
  double D = 0.0;
  for (int i = 0; i < n; ++i) {
    const double F = dist.cdf(d[i]);
    D = std::max({D, std::abs(F - double(i + 1) / n), std::abs(F - double(i) / n)});
  }
  return D;
}
}  // namespace

TEST(SizeDistribution, Rng64IsReproducibleAndRestartable)
{
  Rng64 a(42), b(42);
  for (int i = 0; i < 100; ++i) a.next();
  const auto st = a.state();
  const double x = a.uniform();
  Rng64 c(7);
  c.set_state(st);
  expect_absolute("uniform after state restore - continued stream", c.uniform() - x, 0.0, 0.0);
  for (int i = 0; i < 100; ++i) b.next();
  expect_absolute("same seed, same stream", b.uniform() - x, 0.0, 0.0);
  double mean = 0.0;
  Rng64 r(3);
  for (int i = 0; i < 100000; ++i) mean += r.uniform();
  expect_absolute("mean of 1e5 uniforms", mean / 100000, 0.5, 5.0 * std::sqrt(1.0 / 12 / 100000));
}

TEST(SizeDistribution, TruncatedCdfsAnalytic)
{
  // hand-computed: uniform 10..30 at 15 -> 0.25
  expect_absolute("uniform cdf(15)", SizeDistribution::uniform(10, 30).cdf(15), 0.25, 1e-15);
  // normal 30,5 truncated at 20..40 (+-2 sd): cdf(30) = 0.5 by symmetry
  expect_absolute("normal cdf(mean)", SizeDistribution::normal(30, 5, 20, 40).cdf(30), 0.5, 1e-14);
  // lognormal median 30: cdf(30) of 30/2..30*2 (symmetric in ln d) = 0.5
  expect_absolute("lognormal cdf(median)", SizeDistribution::lognormal(30, 0.3, 15, 60).cdf(30), 0.5, 1e-14);
  // Rosin-Rammler untruncated-ish: 1 - exp(-1) at d63
  expect_absolute("rosin-rammler cdf(d63)", SizeDistribution::rosin_rammler(30, 3, 1e-9, 1e9).cdf(30),
                  1.0 - std::exp(-1.0), 1e-12);
  // by volume, uniform 10..30: number pdf ~ d^-3 -> F = (10^-2 - d^-2)/(10^-2 - 30^-2)
  const double ref = (1e-2 - 1.0 / 400) / (1e-2 - 1.0 / 900);
  expect_relative("uniform byvolume cdf(20)", SizeDistribution::uniform(10, 30).by_volume().cdf(20), ref, 1e-6);
  // table by volume: diameters 1 and 2 with equal volume -> number weights 1 and 1/8
  auto t = SizeDistribution::table({{1.0, 1.0}, {2.0, 1.0}}).by_volume();
  expect_absolute("table byvolume P(d=1)", t.cdf(1.0), 8.0 / 9.0, 1e-15);
}

TEST(SizeDistribution, InverseSamplingRoundTrip)
{
  const std::vector<SizeDistribution> dists = {
      SizeDistribution::uniform(15, 45), SizeDistribution::normal(30, 6, 15, 45),
      SizeDistribution::lognormal(28, 0.35, 15, 45), SizeDistribution::rosin_rammler(32, 4, 15, 45),
      SizeDistribution::lognormal(28, 0.35, 15, 45).by_volume()};
  double worst = 0.0;
  for (const auto &d : dists)
    for (double u = 0.01; u < 1.0; u += 0.01) worst = std::max(worst, std::abs(d.cdf(d.sample(u)) - u));
  expect_absolute("max |F(F^-1(u)) - u| over 5 distributions", worst, 0.0, 1e-9);
}

TEST(SizeDistribution, KolmogorovSmirnov)
{
  const int n = 20000;
  const double crit = 1.63 / std::sqrt(double(n));  // alpha = 0.01
  expect_absolute("KS normal", ks_statistic(SizeDistribution::normal(30, 6, 15, 45), 11, n), 0.0, crit);
  expect_absolute("KS lognormal byvolume",
                  ks_statistic(SizeDistribution::lognormal(28, 0.35, 15, 45).by_volume(), 12, n), 0.0, crit);
  expect_absolute("KS rosin-rammler", ks_statistic(SizeDistribution::rosin_rammler(32, 4, 15, 45), 13, n), 0.0, crit);
}

TEST(SizeDistribution, BadInputThrows)
{
  EXPECT_THROW(SizeDistribution::uniform(30, 10), std::invalid_argument);
  EXPECT_THROW(SizeDistribution::one(-1), std::invalid_argument);
  EXPECT_THROW(SizeDistribution::normal(30, 0, 10, 40), std::invalid_argument);
  EXPECT_THROW(SizeDistribution::lognormal(30, 0.3, 0, 40), std::invalid_argument);
  std::istringstream bad("# d w\n1.0 2.0\n3.0\n");
  EXPECT_THROW(parse_size_table(bad), std::invalid_argument);
  std::istringstream good("# d w\n1.0 2.0\n\n3.0 1 # comment\n");
  const auto rows = parse_size_table(good);
  expect_absolute("parsed table rows", rows.size(), 2, 0);
}
