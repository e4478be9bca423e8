// Particle size distributions for powder insertion (Codina2019 §3.2.2, ch. 5 "custom size
// distributions"): truncated number CDFs, inverse-CDF sampling, volume->number weighting,
// and a seeded random generator whose state can be saved in a restart file.
#pragma once

#include <array>
#include <cstdint>
#include <istream>
#include <string>
#include <utility>
#include <vector>

namespace meltdem::coupling {

// xoshiro256** seeded through splitmix64: the same 64-bit stream on every platform and
// every MPI rank, and a plain 4-word state to checkpoint.
class Rng64 {
 public:
  explicit Rng64(std::uint64_t seed = 1);
  std::uint64_t next();
  double uniform();  // in (0,1): never 0 or 1, so inverse CDFs stay finite
  std::array<std::uint64_t, 4> state() const { return s_; }
  void set_state(const std::array<std::uint64_t, 4> &s) { s_ = s; }

 private:
  std::array<std::uint64_t, 4> s_;
};

enum class SizeDistKind { One, Uniform, Normal, Lognormal, RosinRammler, Table };

// A diameter distribution on [dmin, dmax]. The parameters describe a number distribution,
// or with by_volume() a volume (= mass at one density) distribution, which is converted to
// number weights proportional to w(d)/d^3 so that the drawn particles carry the requested
// volume distribution. All constructors throw std::invalid_argument naming the problem.
class SizeDistribution {
 public:
  SizeDistribution() = default;  // a placeholder: kind One with diameter 0, assign before use
  static SizeDistribution one(double d);
  static SizeDistribution uniform(double dlo, double dhi);
  static SizeDistribution normal(double mean, double sd, double dlo, double dhi);
  static SizeDistribution lognormal(double median, double sigma_ln, double dlo, double dhi);
  static SizeDistribution rosin_rammler(double d63, double n, double dlo, double dhi);
  // discrete diameters with (not necessarily normalised) weights
  static SizeDistribution table(const std::vector<std::pair<double, double>> &rows);

  SizeDistribution by_volume() const;  // reinterpret the weights as volume weights

  SizeDistKind kind() const { return kind_; }
  bool is_by_volume() const { return byvolume_; }
  double dmin() const { return lo_; }
  double dmax() const { return hi_; }
  double cdf(double d) const;     // number CDF, 0 below dmin, 1 at and above dmax
  double sample(double u) const;  // inverse number CDF, u in (0,1)
  double draw(Rng64 &rng) const { return sample(rng.uniform()); }
  double mean_cube() const;  // E[d^3] of the number distribution (volume per particle * 6/pi)

 private:
  // a parametric distribution (two parameters) truncated to [dlo, dhi]
  static SizeDistribution truncated(SizeDistKind kind, double p1, double p2, double dlo, double dhi);
  double base_cdf(double d) const;  // untruncated CDF of the parameters (continuous kinds)
  double base_pdf(double d) const;
  void build_volume_table();

  SizeDistKind kind_ = SizeDistKind::One;
  bool byvolume_ = false;
  double p1_ = 0.0, p2_ = 0.0;  // kind parameters
  double lo_ = 0.0, hi_ = 0.0;
  double glo_ = 0.0, ghi_ = 1.0;   // base_cdf at lo/hi
  std::vector<double> td_, tcum_;  // table / tabulated number CDF (by volume) nodes
};

// Reads "diameter weight" lines ('#' comments and blank lines skipped); throws
// std::invalid_argument with the line number on malformed or non-positive entries.
std::vector<std::pair<double, double>> parse_size_table(std::istream &in);

}  // namespace meltdem::coupling
