#include "meltdem/coupling/size_distribution.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace meltdem::coupling {

namespace {
std::uint64_t splitmix64(std::uint64_t &x)
{
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
inline std::uint64_t rotl(std::uint64_t x, int k)
{
  return (x << k) | (x >> (64 - k));
}

void require(bool ok, const std::string &what)
{
  if (!ok) throw std::invalid_argument(what);
}
void check_range(double dlo, double dhi)
{
  require(std::isfinite(dlo) && std::isfinite(dhi), "diameter bounds must be finite");
  require(dlo > 0.0, "dlo must be > 0");
  require(dhi > 0.0, "dhi must be > 0");
  require(dlo <= dhi, "dlo > dhi");
}

// by-volume tabulation: number pdf ~ base_pdf(d)/d^3, integrated on this many intervals
constexpr int NTAB = 4096;
}  // namespace

Rng64::Rng64(std::uint64_t seed)
{
  std::uint64_t x = seed;
  for (auto &w : s_) w = splitmix64(x);
}

std::uint64_t Rng64::next()
{
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Rng64::uniform()
{
  // 53 random bits, shifted by half an ulp: strictly inside (0,1)
  return ((next() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

SizeDistribution SizeDistribution::one(double d)
{
  require(std::isfinite(d) && d > 0.0, "diameter must be > 0");
  SizeDistribution s;
  s.kind_ = SizeDistKind::One;
  s.lo_ = s.hi_ = d;
  return s;
}

SizeDistribution SizeDistribution::uniform(double dlo, double dhi)
{
  check_range(dlo, dhi);
  SizeDistribution s;
  s.kind_ = SizeDistKind::Uniform;
  s.lo_ = dlo;
  s.hi_ = dhi;
  s.glo_ = s.base_cdf(dlo);
  s.ghi_ = s.base_cdf(dhi);
  return s;
}

SizeDistribution SizeDistribution::truncated(SizeDistKind kind, double p1, double p2, double dlo, double dhi)
{
  check_range(dlo, dhi);
  SizeDistribution s;
  s.kind_ = kind;
  s.p1_ = p1;
  s.p2_ = p2;
  s.lo_ = dlo;
  s.hi_ = dhi;
  s.glo_ = s.base_cdf(dlo);
  s.ghi_ = s.base_cdf(dhi);
  require(dlo == dhi || s.ghi_ - s.glo_ > 1e-12, "[dlo,dhi] holds no probability of the distribution");
  return s;
}

SizeDistribution SizeDistribution::normal(double mean, double sd, double dlo, double dhi)
{
  require(std::isfinite(mean) && mean > 0.0, "mean must be > 0");
  require(std::isfinite(sd) && sd > 0.0, "sd must be > 0");
  return truncated(SizeDistKind::Normal, mean, sd, dlo, dhi);
}

SizeDistribution SizeDistribution::lognormal(double median, double sigma_ln, double dlo, double dhi)
{
  require(std::isfinite(median) && median > 0.0, "median must be > 0");
  require(std::isfinite(sigma_ln) && sigma_ln > 0.0, "sigma_ln must be > 0");
  return truncated(SizeDistKind::Lognormal, median, sigma_ln, dlo, dhi);
}

SizeDistribution SizeDistribution::rosin_rammler(double d63, double n, double dlo, double dhi)
{
  require(std::isfinite(d63) && d63 > 0.0, "d63 must be > 0");
  require(std::isfinite(n) && n > 0.0, "n must be > 0");
  return truncated(SizeDistKind::RosinRammler, d63, n, dlo, dhi);
}

SizeDistribution SizeDistribution::table(const std::vector<std::pair<double, double>> &rows)
{
  require(!rows.empty(), "table has no entries");
  auto sorted = rows;
  std::sort(sorted.begin(), sorted.end());
  SizeDistribution s;
  s.kind_ = SizeDistKind::Table;
  double sum = 0.0;
  for (const auto &r : sorted) {
    require(std::isfinite(r.first) && r.first > 0.0, "table diameter must be > 0");
    require(std::isfinite(r.second) && r.second >= 0.0, "table weight must be >= 0");
    s.td_.push_back(r.first);
    sum += r.second;
    s.tcum_.push_back(sum);
  }
  require(sum > 0.0, "table weights sum to zero");
  for (auto &c : s.tcum_) c /= sum;
  s.tcum_.back() = 1.0;
  s.lo_ = s.td_.front();
  s.hi_ = s.td_.back();
  return s;
}

SizeDistribution SizeDistribution::by_volume() const
{
  SizeDistribution s = *this;
  if (byvolume_) return s;
  s.byvolume_ = true;
  if (kind_ == SizeDistKind::One) return s;
  if (kind_ == SizeDistKind::Table) {
    // number weight = volume weight / d^3
    double prev = 0.0, sum = 0.0;
    std::vector<double> w(td_.size());
    for (std::size_t i = 0; i < td_.size(); ++i) {
      w[i] = (tcum_[i] - prev) / (td_[i] * td_[i] * td_[i]);
      prev = tcum_[i];
      sum += w[i];
    }
    double c = 0.0;
    for (std::size_t i = 0; i < td_.size(); ++i) {
      c += w[i];
      s.tcum_[i] = c / sum;
    }
    s.tcum_.back() = 1.0;
    return s;
  }
  s.build_volume_table();
  return s;
}

double SizeDistribution::base_cdf(double d) const
{
  switch (kind_) {
    case SizeDistKind::Uniform:
      return d;
    case SizeDistKind::Normal:
      return 0.5 * std::erfc(-(d - p1_) / (p2_ * std::sqrt(2.0)));
    case SizeDistKind::Lognormal:
      return 0.5 * std::erfc(-(std::log(d) - std::log(p1_)) / (p2_ * std::sqrt(2.0)));
    case SizeDistKind::RosinRammler:
      return -std::expm1(-std::pow(d / p1_, p2_));
    default:
      return 0.0;
  }
}

double SizeDistribution::base_pdf(double d) const
{
  constexpr double inv_sqrt_2pi = 0.3989422804014327;
  switch (kind_) {
    case SizeDistKind::Uniform:
      return 1.0;
    case SizeDistKind::Normal: {
      const double z = (d - p1_) / p2_;
      return inv_sqrt_2pi / p2_ * std::exp(-0.5 * z * z);
    }
    case SizeDistKind::Lognormal: {
      const double z = (std::log(d) - std::log(p1_)) / p2_;
      return inv_sqrt_2pi / (p2_ * d) * std::exp(-0.5 * z * z);
    }
    case SizeDistKind::RosinRammler: {
      const double x = std::pow(d / p1_, p2_);
      return p2_ / d * x * std::exp(-x);
    }
    default:
      return 0.0;
  }
}

void SizeDistribution::build_volume_table()
{
  // cumulative integral of pdf(d)/d^3 with 3-point Gauss-Legendre per interval on a
  // geometric grid (the weight varies as d^-3, so equal ratios keep the error uniform)
  td_.resize(NTAB + 1);
  tcum_.resize(NTAB + 1);
  const double ratio = hi_ / lo_;
  for (int i = 0; i <= NTAB; ++i) td_[i] = lo_ * std::pow(ratio, double(i) / NTAB);
  td_[NTAB] = hi_;
  const double gx[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  tcum_[0] = 0.0;
  for (int i = 0; i < NTAB; ++i) {
    const double a = td_[i], b = td_[i + 1], h = 0.5 * (b - a), m = 0.5 * (a + b);
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = m + h * gx[k];
      sum += gw[k] * base_pdf(d) / (d * d * d);
    }
    tcum_[i + 1] = tcum_[i] + h * sum;
  }
  require(tcum_[NTAB] > 0.0, "[dlo,dhi] holds no probability of the distribution");
  const double total = tcum_[NTAB];
  for (auto &c : tcum_) c /= total;
  tcum_[NTAB] = 1.0;
}

double SizeDistribution::cdf(double d) const
{
  if (d < lo_) return 0.0;
  if (d >= hi_) return 1.0;
  if (kind_ == SizeDistKind::One) return 1.0;
  if (kind_ == SizeDistKind::Table) {
    // right-continuous step function
    auto it = std::upper_bound(td_.begin(), td_.end(), d);
    if (it == td_.begin()) return 0.0;
    return tcum_[(it - td_.begin()) - 1];
  }
  if (byvolume_) {
    auto it = std::upper_bound(td_.begin(), td_.end(), d);
    const std::size_t i = (it - td_.begin()) - 1;
    const double t = (d - td_[i]) / (td_[i + 1] - td_[i]);
    return tcum_[i] + t * (tcum_[i + 1] - tcum_[i]);
  }
  return (base_cdf(d) - glo_) / (ghi_ - glo_);
}

double SizeDistribution::sample(double u) const
{
  if (kind_ == SizeDistKind::One || lo_ == hi_) return lo_;
  if (kind_ == SizeDistKind::Table) {
    auto it = std::lower_bound(tcum_.begin(), tcum_.end(), u);
    if (it == tcum_.end()) --it;
    return td_[it - tcum_.begin()];
  }
  if (byvolume_) {
    auto it = std::upper_bound(tcum_.begin(), tcum_.end(), u);
    std::size_t i = (it - tcum_.begin());
    if (i == 0) i = 1;
    if (i > td_.size() - 1) i = td_.size() - 1;
    const double c0 = tcum_[i - 1], c1 = tcum_[i];
    const double t = c1 > c0 ? (u - c0) / (c1 - c0) : 0.0;
    return std::min(hi_, std::max(lo_, td_[i - 1] + t * (td_[i] - td_[i - 1])));
  }
  if (kind_ == SizeDistKind::Uniform) return lo_ + u * (hi_ - lo_);
  if (kind_ == SizeDistKind::RosinRammler) {
    // closed form: G^-1(g) = d63 (-ln(1-g))^(1/n)
    const double g = glo_ + u * (ghi_ - glo_);
    const double d = p1_ * std::pow(-std::log1p(-g), 1.0 / p2_);
    return std::min(hi_, std::max(lo_, d));
  }
  // normal/lognormal: bisection on the truncated CDF (monotone, to double precision)
  double a = lo_, b = hi_;
  for (int it = 0; it < 200 && b - a > 1e-15 * hi_; ++it) {
    const double m = 0.5 * (a + b);
    if (cdf(m) < u)
      a = m;
    else
      b = m;
  }
  return 0.5 * (a + b);
}

double SizeDistribution::mean_cube() const
{
  if (kind_ == SizeDistKind::One || lo_ == hi_) return lo_ * lo_ * lo_;
  if (kind_ == SizeDistKind::Table) {
    double prev = 0.0, s = 0.0;
    for (std::size_t i = 0; i < td_.size(); ++i) {
      s += (tcum_[i] - prev) * td_[i] * td_[i] * td_[i];
      prev = tcum_[i];
    }
    return s;
  }
  // midpoint quadrature of d^3 dF on a fine grid
  const int n = 4096;
  double s = 0.0, fprev = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double d1 = lo_ + (hi_ - lo_) * i / n, dm = lo_ + (hi_ - lo_) * (i - 0.5) / n;
    const double f = cdf(d1);
    s += (f - fprev) * dm * dm * dm;
    fprev = f;
  }
  return s;
}

std::vector<std::pair<double, double>> parse_size_table(std::istream &in)
{
  std::vector<std::pair<double, double>> rows;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream ls(line);
    double d, w;
    if (!(ls >> d)) {
      std::string rest;
      std::istringstream probe(line);
      if (probe >> rest) throw std::invalid_argument("table line " + std::to_string(lineno) + ": cannot read diameter");
      continue;  // blank
    }
    if (!(ls >> w)) throw std::invalid_argument("table line " + std::to_string(lineno) + ": missing weight");
    std::string extra;
    if (ls >> extra)
      throw std::invalid_argument("table line " + std::to_string(lineno) + ": extra text '" + extra + "'");
    if (!(d > 0.0)) throw std::invalid_argument("table line " + std::to_string(lineno) + ": diameter must be > 0");
    if (!(w >= 0.0)) throw std::invalid_argument("table line " + std::to_string(lineno) + ": weight must be >= 0");
    rows.emplace_back(d, w);
  }
  if (rows.empty()) throw std::invalid_argument("table has no entries");
  return rows;
}

}  // namespace meltdem::coupling
