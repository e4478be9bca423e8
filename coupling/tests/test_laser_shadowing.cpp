// Laser absorption by particles and their shadow (laser_shadowing.h): per-particle shares
// against the analytic power through a disk, shadowing, symmetry, and the balance
// sum(absorbed) + eta (power reaching the continuum) = eta P.
#include "meltdem/coupling/laser_shadowing.h"
#include "meltdem/coupling/exact_sum.h"
#include "validation_report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace meltdem::coupling;
using meltdem::testing::expect_absolute;
using meltdem::testing::expect_relative;

namespace {

// a 200 W beam of 1/e^2 radius 50 um, eta 0.4, pointing down through an off-origin point
GaussianBeam test_beam(const Eigen::Vector3d &dir = Eigen::Vector3d(0, 0, -1))
{
  GaussianBeam b;
  b.power = 200.0;
  b.absorptivity = 0.4;
  b.radius = 50e-6;
  b.centre = Eigen::Vector3d(1e-4, -2e-4, 3e-4);
  b.direction = dir;
  return b;
}

// a point at distance `s` off the axis along u, `up` upstream of the centre plane
Eigen::Vector3d beam_point(const GaussianBeam &b, double up, double s_u, double s_v = 0.0)
{
  Eigen::Vector3d u, v;
  beam_plane_basis(b.direction, u, v);
  return b.centre - up * b.direction.normalized() + s_u * u + s_v * v;
}

double sum(const std::vector<double> &x)
{
  double s = 0.0;
  for (double y : x) s += y;
  return s;
}

std::string fmt(double x)
{
  std::ostringstream os;
  os << x;
  return os.str();
}

}  // namespace

TEST(LaserShadowing, ProfileMatchesContinuum)
{
  // the continuum's eq. 17 profile: I0 = 2P/(pi w^2), I(w) = I0 e^-2
  const GaussianBeam b = test_beam();
  const double I0 = 2.0 * 200.0 / (M_PI * 50e-6 * 50e-6);
  expect_relative("I(0) [W/m2]", beam_irradiance(b, 0.0), I0, 1e-15);
  expect_relative("I(w)/I(0)", beam_irradiance(b, 50e-6) / I0, std::exp(-2.0), 1e-15);
  // the quadrature reference reproduces the closed form on the axis (s -> 0+)
  expect_relative("disk power, quadrature at s = 1e-12 w vs closed form", beam_power_in_disk(b, 30e-6, 50e-18),
                  beam_power_in_disk(b, 30e-6, 0.0), 1e-12);
  expect_relative("disk power R = w on axis", beam_power_in_disk(b, 50e-6), 200.0 * (1.0 - std::exp(-2.0)), 1e-15);
}

// (1) one particle on the axis: the share vs P (1 - exp(-2 R^2/w^2)), and its convergence
// with the number of rays across the particle's radius, R/h (the grid is centred on the
// axis, so a particle there is the symmetric worst case of the cell counting)
TEST(LaserShadowing, SingleParticleOnAxisConverges)
{
  const GaussianBeam b = test_beam();
  const double w = b.radius;
  const std::vector<double> ratios = {0.25, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  const std::vector<double> per_particle = {5, 10, 20, 40, 80};
  std::vector<double> mean_err, max_err;
  std::cout << "R/h   mean|rel err| over R/w = 0.25..1   max|rel err|\n";
  for (double N : per_particle) {
    double e_sum = 0.0, e_max = 0.0;
    for (double q : ratios) {
      ShadowOptions opt;
      opt.extent = 1.5;  // holds the disk; the rest is tail (to the continuum)
      opt.cells_per_radius = N / q;
      opt.cells_per_particle_radius = 0.0;
      const double R = q * w;
      const ShadowResult r = shade_particles(b, {{beam_point(b, 2 * R, 0.0), R}}, opt);
      const double ref = beam_power_in_disk(b, R);
      const double e = std::abs(r.intercepted[0] - ref) / ref;
      e_sum += e;
      e_max = std::max(e_max, e);
    }
    mean_err.push_back(e_sum / ratios.size());
    max_err.push_back(e_max);
    std::cout << std::setw(3) << N << "   " << std::setw(14) << mean_err.back() << "   " << e_max << "\n";
  }
  // the default options (R/h >= 20), particles of R = 0.3 w and R = w
  for (const double q : {0.3, 1.0}) {
    const double R = q * w;
    const ShadowResult r = shade_particles(b, {{beam_point(b, R, 0.0), R}});
    std::cout << "default options, R = " << q << " w: R/h = " << R / r.grid.h << ", " << r.grid.n << "^2 rays\n";
    expect_relative("intercepted, R = " + fmt(q) + " w, default options [W]", r.intercepted[0],
                    beam_power_in_disk(b, R), 1e-2);
    expect_relative("absorbed = eta * intercepted [W]", r.absorbed[0], 0.4 * r.intercepted[0], 1e-15);
  }
  expect_absolute("max |rel err| at R/h = 20 (the default)", max_err[2], 0.0, 1e-2);
  expect_absolute("max |rel err| at R/h = 80", max_err[4], 0.0, 1e-3);
  // convergence: the mean error falls by 8x or more per 8x rays across the radius
  expect_absolute("mean error ratio R/h 40 vs 5 (<= 1/8)", mean_err[3] / mean_err[0], 0.0, 1.0 / 8.0);
  expect_absolute("mean error ratio R/h 80 vs 10 (<= 1/8)", mean_err[4] / mean_err[1], 0.0, 1.0 / 8.0);
  std::cout << "observed order (R/h 5 -> 80): " << -std::log(mean_err[4] / mean_err[0]) / std::log(16.0) << "\n";
}

TEST(LaserShadowing, TiltedBeamAndOffAxisParticle)
{
  // the same particle on the axis of a tilted beam: same share as for a vertical beam
  // to the discretisation error (the grid turns with the beam)
  const GaussianBeam tilted = test_beam(Eigen::Vector3d(1.0, 0.5, -2.0));
  const double w = tilted.radius, R = 0.5 * w;
  ShadowOptions opt;
  opt.cells_per_particle_radius = 40;
  const ShadowResult r = shade_particles(tilted, {{beam_point(tilted, 3 * R, 0.0), R}}, opt);
  expect_relative("tilted beam, on-axis particle [W]", r.intercepted[0], beam_power_in_disk(tilted, R), 2e-3);
  // a particle straddling the beam edge: s = 1.5 w off the axis, R = 0.5 w
  const GaussianBeam b = test_beam();
  const ShadowResult o = shade_particles(b, {{beam_point(b, R, 1.5 * w, 0.0), R}}, opt);
  expect_relative("off-axis (s = 1.5 w) particle vs Marcum-Q quadrature [W]", o.intercepted[0],
                  beam_power_in_disk(b, R, 1.5 * w), 3e-3);
}

// (2) a particle right below another of the same size (or a smaller one in its shadow)
TEST(LaserShadowing, HiddenParticleAbsorbsNothing)
{
  const GaussianBeam b = test_beam();
  const double w = b.radius, R = 0.4 * w;
  const BeamParticle top{beam_point(b, 5 * R, 0.3 * w, -0.2 * w), R};
  const BeamParticle below{beam_point(b, 3 * R, 0.3 * w, -0.2 * w), R};               // touching, under it
  const BeamParticle small{beam_point(b, -R, 0.3 * w + 0.5 * R, -0.2 * w), 0.4 * R};  // in its shadow
  ShadowOptions opt;  // the same grid with and without the small particle
  opt.cells_per_particle_radius = 0.0;
  opt.cells_per_radius = 100.0;
  const ShadowResult alone = shade_particles(b, {top}, opt);
  const ShadowResult r = shade_particles(b, {below, top, small}, opt);
  expect_absolute("absorbed by the particle below [W]", r.absorbed[0], 0.0, 0.0);
  expect_absolute("absorbed by the small particle in the shadow [W]", r.absorbed[2], 0.0, 0.0);
  expect_relative("the top particle absorbs as if alone [W]", r.absorbed[1], alone.absorbed[0], 1e-15);
  // the continuum under the pair is dark, next to it lit
  expect_absolute("transmitted fraction under the pair", transmitted_fraction(r, beam_point(b, 0.0, 0.3 * w, -0.2 * w)),
                  0.0, 0.0);
  expect_absolute("transmitted fraction beside the pair", transmitted_fraction(r, beam_point(b, 0.0, -0.5 * w, 0.0)),
                  1.0, 0.0);
  // above the top particle the beam has not been intercepted yet
  expect_absolute("transmitted fraction above the top particle",
                  transmitted_fraction(r, beam_point(b, 8 * R, 0.3 * w, -0.2 * w)), 1.0, 0.0);
  // the beam reversed: the former bottom particle now hides the former top one
  GaussianBeam up = b;
  up.direction = -b.direction;
  const ShadowResult rev = shade_particles(up, {below, top}, opt);
  expect_absolute("reversed beam: absorbed by the (now hidden) top particle [W]", rev.absorbed[1], 0.0, 0.0);
  expect_relative("reversed beam: the bottom particle absorbs the top one's share [W]", rev.absorbed[0],
                  alone.absorbed[0], 1e-12);
}

// (3) two particles side by side, mirrored about the axis
TEST(LaserShadowing, SideBySideShareSymmetrically)
{
  const GaussianBeam b = test_beam();
  const double w = b.radius, R = 0.35 * w;
  for (const double gap : {0.0, 0.1 * w}) {
    const BeamParticle left{beam_point(b, R, -(R + 0.5 * gap), 0.0), R};
    const BeamParticle right{beam_point(b, R, R + 0.5 * gap, 0.0), R};
    const ShadowResult r = shade_particles(b, {left, right});
    const ShadowResult one = shade_particles(b, {left});
    expect_relative("left vs right share, gap " + fmt(gap / w) + " w [W]", r.absorbed[0], r.absorbed[1], 1e-12);
    expect_relative("a neighbour does not shade (disks disjoint), gap " + fmt(gap / w) + " w [W]", r.absorbed[0],
                    one.absorbed[0], 1e-15);
    expect_relative("left share vs quadrature, gap " + fmt(gap / w) + " w [W]", r.intercepted[0],
                    beam_power_in_disk(b, R, R + 0.5 * gap), 1e-2);
  }
  // the same pair along v (front/back): the grid is symmetric in both directions
  const BeamParticle front{beam_point(b, R, 0.0, -R), R};
  const BeamParticle back{beam_point(b, R, 0.0, R), R};
  const ShadowResult fb = shade_particles(b, {front, back});
  expect_relative("front vs back share [W]", fb.absorbed[0], fb.absorbed[1], 1e-12);
}

// (4) many random particles: every ray counted once, the balance closes to round-off
TEST(LaserShadowing, ManyParticlesBalanceCloses)
{
  const GaussianBeam b = test_beam(Eigen::Vector3d(0.3, -0.2, -1.0));
  const double w = b.radius, eta = b.absorptivity, P = b.power;
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> pos(-2.0 * w, 2.0 * w), rad(0.1 * w, 0.5 * w), up(0.0, 4.0 * w);
  std::vector<BeamParticle> ps;
  for (int k = 0; k < 300; ++k) ps.push_back({beam_point(b, up(rng), pos(rng), pos(rng)), rad(rng)});
  const ShadowResult r = shade_particles(b, ps);
  const auto rays = transmitted_rays(r);
  // (a million rays: summed compensated, so the sum's own round-off stays below the tolerance)
  ExactSum ray_sum;
  for (const auto &ray : rays) ray_sum.add(ray.power);
  const double ray_power = ray_sum.value();
  const double continuum = ray_power + r.tail_power;  // what reaches the continuum, ray by ray
  std::cout << "300 particles: intercepted " << r.intercepted_total << " W of " << P << " W, " << rays.size()
            << " transmitted rays, tail " << r.tail_power << " W\n";
  std::cout << std::setprecision(17) << "balance: (sum(absorbed) + eta (rays + tail)) / (eta P) - 1 = "
            << (sum(r.absorbed) + eta * continuum) / (eta * P) - 1.0
            << ", with continuum_absorbed(): " << (sum(r.absorbed) + r.continuum_absorbed()) / (eta * P) - 1.0
            << std::setprecision(6) << "\n";
  expect_relative("sum(absorbed) + eta (transmitted rays + tail) [W]", sum(r.absorbed) + eta * continuum, eta * P,
                  1e-12);
  expect_relative("sum(absorbed) + continuum_absorbed() [W]", sum(r.absorbed) + r.continuum_absorbed(), eta * P, 1e-12);
  expect_relative("transmitted rays + tail vs P - intercepted [W]", continuum, r.transmitted_power, 1e-12);
  EXPECT_GT(r.intercepted_total, 0.3 * P);  // the bed really shades
  EXPECT_LT(r.tail_power, 1e-14 * P);
  // transmitted_fraction agrees with the rays: summing the lit rays' powers (probed deep
  // below the bed) gives the transmitted power
  const ShadowGrid &g = r.grid;
  ExactSum lit;
  for (int j = 0; j < g.n; ++j)
    for (int i = 0; i < g.n; ++i) {
      const Eigen::Vector3d x =
          g.centre + 10 * w * g.direction + (i + 0.5 - g.n / 2) * g.h * g.u + (j + 0.5 - g.n / 2) * g.h * g.v;
      lit.add(transmitted_fraction(r, x) * P * g.g[i] * g.g[j]);
    }
  expect_relative("sum of lit ray powers via transmitted_fraction [W]", lit.value(), ray_power, 1e-12);
  // an independent estimate: Monte Carlo rays drawn from the Gaussian, each intercepted
  // by the sphere it enters first (brute force over all particles)
  std::normal_distribution<double> gauss(0.0, 0.5 * w);  // standard deviation w/2
  const int nmc = 200000;
  int hit = 0;
  Eigen::Vector3d u, v;
  beam_plane_basis(b.direction, u, v);
  const Eigen::Vector3d d = b.direction.normalized();
  for (int s = 0; s < nmc; ++s) {
    const Eigen::Vector3d o = b.centre + gauss(rng) * u + gauss(rng) * v;
    for (const auto &p : ps) {
      const Eigen::Vector3d q = p.x - o;
      if ((q - q.dot(d) * d).squaredNorm() < p.radius * p.radius) {
        ++hit;
        break;
      }
    }
  }
  const double f = static_cast<double>(hit) / nmc, sigma = std::sqrt(f * (1 - f) / nmc);
  expect_absolute("intercepted fraction, grid vs Monte Carlo (4 sigma + 2e-3)", r.intercepted_total / P, f,
                  4 * sigma + 2e-3);
}

// (5) a particle outside the beam
TEST(LaserShadowing, ParticleOutsideBeam)
{
  const GaussianBeam b = test_beam();
  const double w = b.radius, R = 0.5 * w;
  // 6 w off the axis (outside the sampled square of 4 w): nothing
  const ShadowResult far = shade_particles(b, {{beam_point(b, R, 6 * w, 0.0), R}});
  expect_absolute("absorbed at 6 w off the axis [W]", far.absorbed[0], 0.0, 0.0);
  expect_relative("all of P reaches the continuum [W]", far.transmitted_power, b.power, 1e-15);
  // 3 w off the axis (inside the square): the exact share is 6e-6 W
  const ShadowResult edge = shade_particles(b, {{beam_point(b, R, 3 * w, 0.0), R}});
  const double ref = beam_power_in_disk(b, R, 3 * w);
  std::cout << "particle at 3 w: intercepted " << edge.intercepted[0] << " W, exact " << ref << " W\n";
  expect_absolute("intercepted at 3 w off the axis [W] (vs exact, tol 2e-6 W)", edge.intercepted[0], ref, 2e-6);
  // bound: the power of the half plane beyond s - R, P erfc(sqrt2 (s - R)/w)/2
  expect_absolute("intercepted at 3 w <= half-plane bound [W]", edge.intercepted[0], 0.0,
                  0.5 * b.power * std::erfc(std::sqrt(2.0) * 2.5));
}

// particles at the square's edge, covering all of it, or very far away
TEST(LaserShadowing, EdgeAndHugeParticles)
{
  const GaussianBeam b = test_beam();
  const double w = b.radius;
  // a particle far away (1 km): no rays, no overflow
  const ShadowResult far = shade_particles(b, {{beam_point(b, 0.0, 1e3, -1e3), 10e-6}});
  expect_absolute("particle 1 km away [W]", far.absorbed[0], 0.0, 0.0);
  // a particle whose disk covers the whole sampled square: it intercepts every ray, the
  // continuum gets only the tail outside the square
  const ShadowResult huge = shade_particles(b, {{beam_point(b, 20 * w, 0.0), 10 * w}});
  expect_relative("huge particle intercepts the sampled power [W]", huge.intercepted[0], huge.sampled_power, 1e-13);
  expect_absolute("what reaches the continuum is the tail (round-off of 1.6e5 rays) [W]", huge.transmitted_power,
                  huge.tail_power, 1e-12 * b.power);
  EXPECT_TRUE(transmitted_rays(huge).empty());
  // a particle straddling the square's edge (centre at u = 4 w) gets only its rays inside
  // the square: its inner half, the brighter one (between half and all of its share)
  ShadowOptions opt;
  opt.extent = 1.0;  // a small square, so the straddling share is not negligible
  const double R = 0.25 * w;
  const ShadowResult edge = shade_particles(b, {{beam_point(b, R, 1.0 * w, 0.0), R}}, opt);
  const double full = beam_power_in_disk(b, R, 1.0 * w);
  std::cout << "particle straddling the square edge (extent 1): " << edge.intercepted[0] << " W of its " << full
            << " W, tail " << edge.tail_power << " W\n";
  EXPECT_GT(edge.intercepted[0], 0.5 * full);
  EXPECT_LT(edge.intercepted[0], full);
  expect_relative("balance with a straddling particle [W]", edge.absorbed[0] + edge.continuum_absorbed(),
                  b.absorptivity * b.power, 1e-15);
}

// (6) bad input
TEST(LaserShadowing, BadInputThrows)
{
  const GaussianBeam b = test_beam();
  const BeamParticle ok{beam_point(b, 0.0, 0.0), 10e-6};
  auto expect_message = [&](const GaussianBeam &beam, const std::vector<BeamParticle> &ps, const ShadowOptions &opt,
                            const std::string &needle) {
    try {
      shade_particles(beam, ps, opt);
      ADD_FAILURE() << "no exception, expected one mentioning '" << needle << "'";
    } catch (const std::invalid_argument &e) {
      std::cout << "bad input: " << e.what() << "\n";
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  GaussianBeam neg = b;
  neg.power = -1.0;
  expect_message(neg, {ok}, {}, "power P = -1");
  GaussianBeam zero_dir = b;
  zero_dir.direction = Eigen::Vector3d::Zero();
  expect_message(zero_dir, {ok}, {}, "direction (0 0 0)");
  GaussianBeam eta = b;
  eta.absorptivity = 1.5;
  expect_message(eta, {ok}, {}, "absorptivity");
  GaussianBeam w0 = b;
  w0.radius = 0.0;
  expect_message(w0, {ok}, {}, "radius w = 0");
  expect_message(b, {ok, {ok.x, -1e-6}}, {}, "particle 1 radius = -1e-06");
  expect_message(b, {{Eigen::Vector3d(NAN, 0, 0), 1e-6}}, {}, "particle 0 centre");
  ShadowOptions res;
  res.cells_per_radius = 0.0;
  expect_message(b, {ok}, res, "cells_per_radius");
  res.cells_per_radius = 1e5;
  expect_message(b, {ok}, res, "max_cells");
  res.cells_per_radius = 50;
  res.cells_per_particle_radius = -1;
  expect_message(b, {ok}, res, "cells_per_particle_radius");
  // a tiny particle refines the grid only up to max_cells (no throw)
  res.cells_per_particle_radius = 20;
  res.max_cells = 1'000'000;
  const ShadowResult capped = shade_particles(b, {{ok.x, 1e-9}}, res);
  EXPECT_EQ(capped.grid.n, 1000);
  EXPECT_THROW(transmitted_fraction(ShadowResult{}, Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(beam_power_in_disk(b, -1.0), std::invalid_argument);
}

// the continuum's cells coarser than the rays: the footprint average
TEST(LaserShadowing, FootprintFraction)
{
  const GaussianBeam b = test_beam();
  const double w = b.radius, R = 0.5 * w;
  const ShadowResult r = shade_particles(b, {{beam_point(b, R, 0.0), R}});
  // a footprint of 2R around the axis: the particle's disk covers a quarter of it
  expect_relative("lit fraction of a 2R footprint around a particle of radius R",
                  transmitted_fraction(r, beam_point(b, -1e-6, 0.0), 2 * R), 0.75, 5e-3);
  // a footprint half outside the grid is lit there
  expect_absolute("footprint straddling the grid edge", transmitted_fraction(r, beam_point(b, 0.0, 4 * w), 0.5 * w),
                  1.0, 0.0);
}

// the footprint fraction counted ray by ray over the whole lattice square around the point
// (no blocks, no chords): the definition transmitted_fraction must reproduce exactly
double footprint_fraction_by_rays(const ShadowResult &r, const Eigen::Vector3d &point, double footprint)
{
  const ShadowGrid &g = r.grid;
  const Eigen::Vector3d p = point - g.centre;
  const double depth = p.dot(g.direction), pu = p.dot(g.u), pv = p.dot(g.v);
  const double m = g.n / 2, inv_h = 1.0 / g.h;
  auto lit_at = [&](double fi, double fj) {
    if (fi < 0 || fj < 0 || fi >= g.n || fj >= g.n) return true;
    return depth < g.entry_depth[static_cast<std::size_t>(fj) * g.n + static_cast<std::size_t>(fi)];
  };
  long total = 0, lit = 0;
  for (double fj = std::ceil((pv - footprint) * inv_h + m - 0.5); fj <= std::floor((pv + footprint) * inv_h + m - 0.5);
       ++fj)
    for (double fi = std::ceil((pu - footprint) * inv_h + m - 0.5);
         fi <= std::floor((pu + footprint) * inv_h + m - 0.5); ++fi) {
      const double du = (fi + 0.5 - m) * g.h - pu, dv = (fj + 0.5 - m) * g.h - pv;
      if (du * du + dv * dv > footprint * footprint) continue;
      ++total;
      if (lit_at(fi, fj)) ++lit;
    }
  if (total > 0) return static_cast<double>(lit) / total;
  return lit_at(std::floor(pu * inv_h) + m, std::floor(pv * inv_h) + m) ? 1.0 : 0.0;
}

// a bed of overlapping particles over a surface: the footprint fraction at points above, in
// and below the bed, on and off the grid, with footprints from below a ray to many blocks,
// equals the ray-by-ray count exactly; each block's smallest entry depth is its rays' smallest
TEST(LaserShadowing, FootprintFractionEqualsRayCount)
{
  const GaussianBeam b = test_beam(Eigen::Vector3d(0.2, -0.1, -1.0));
  const double w = b.radius;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pos(-3.0 * w, 3.0 * w), rad(0.1 * w, 0.3 * w), up(0.0, 0.6 * w);
  std::vector<BeamParticle> ps;
  for (int k = 0; k < 300; ++k) ps.push_back({beam_point(b, up(rng), pos(rng), pos(rng)), rad(rng)});
  ShadowOptions opt;
  opt.cells_per_particle_radius = 10.0;
  const ShadowResult r = shade_particles(b, ps, opt);
  const ShadowGrid &g = r.grid;
  ASSERT_EQ(g.nb, (g.n + kShadowBlock - 1) / kShadowBlock);
  ASSERT_EQ(g.block_max_entry_depth.size(), g.block_entry_depth.size());
  ASSERT_EQ(g.block_max_hit_depth.size(), g.block_entry_depth.size());
  ASSERT_EQ(g.hits_before.size(), std::size_t(g.n) * (g.n + 1));
  int wrong_blocks = 0, wrong_max = 0, wrong_hit = 0, covered = 0, mixed = 0;
  for (int bj = 0; bj < g.nb; ++bj)
    for (int bi = 0; bi < g.nb; ++bi) {
      double lowest = std::numeric_limits<double>::infinity(), largest = -lowest, largest_hit = -lowest;
      for (int j = bj * kShadowBlock; j < std::min(g.n, (bj + 1) * kShadowBlock); ++j)
        for (int i = bi * kShadowBlock; i < std::min(g.n, (bi + 1) * kShadowBlock); ++i) {
          const double e = g.entry_depth[std::size_t(j) * g.n + i];
          lowest = std::min(lowest, e);
          largest = std::max(largest, e);
          if (std::isfinite(e)) largest_hit = std::max(largest_hit, e);
        }
      wrong_blocks += g.block_entry_depth[std::size_t(bj) * g.nb + bi] == lowest ? 0 : 1;
      wrong_max += g.block_max_entry_depth[std::size_t(bj) * g.nb + bi] == largest ? 0 : 1;
      wrong_hit += g.block_max_hit_depth[std::size_t(bj) * g.nb + bi] == largest_hit ? 0 : 1;
      covered += std::isfinite(largest) ? 1 : 0;
      mixed += std::isfinite(lowest) && !std::isfinite(largest) ? 1 : 0;
    }
  EXPECT_EQ(wrong_blocks, 0) << "blocks whose smallest entry depth is not their rays' smallest";
  EXPECT_EQ(wrong_max, 0) << "blocks whose largest entry depth is not their rays' largest";
  EXPECT_EQ(wrong_hit, 0) << "blocks whose largest hit entry depth is not their hit rays' largest";
  EXPECT_GT(covered, 0) << "no block wholly in shadow: the dark-block path is not exercised";
  EXPECT_GT(mixed, 0) << "no block partly hit: the hit-count path is not exercised";
  int wrong_counts = 0;
  for (int j = 0; j < g.n; ++j) {
    int hits = 0;
    for (int i = 0; i <= g.n; ++i) {
      wrong_counts += g.hits_before[std::size_t(j) * (g.n + 1) + i] == hits ? 0 : 1;
      if (i < g.n) hits += g.owner[std::size_t(j) * g.n + i] >= 0 ? 1 : 0;
    }
  }
  EXPECT_EQ(wrong_counts, 0) << "row hit counts that are not the rays' count";
  std::uniform_real_distribution<double> where(-5.0 * w, 5.0 * w), height(-0.8 * w, 1.0 * w);
  int checked = 0, differ = 0, partial = 0;
  double t_fast = 0.0, t_rays = 0.0;
  for (const double footprint : {0.0, 0.3 * g.h, 2.0 * g.h, 0.05 * w, 0.2 * w, 0.5 * w}) {
    for (int k = 0; k < 400; ++k) {
      const Eigen::Vector3d x = beam_point(b, height(rng), where(rng), where(rng));
      const auto t0 = std::chrono::steady_clock::now();
      const double fast = transmitted_fraction(r, x, footprint);
      const auto t1 = std::chrono::steady_clock::now();
      const double slow = footprint_fraction_by_rays(r, x, footprint);
      const auto t2 = std::chrono::steady_clock::now();
      t_fast += std::chrono::duration<double>(t1 - t0).count();
      t_rays += std::chrono::duration<double>(t2 - t1).count();
      ++checked;
      differ += fast == slow ? 0 : 1;
      partial += slow > 0.0 && slow < 1.0 ? 1 : 0;
    }
  }
  std::cout << "footprint fractions: " << checked << " points (" << partial << " partly shadowed), " << differ
            << " differ from the ray count; " << t_fast / checked * 1e6 << " us per query against "
            << t_rays / checked * 1e6 << " us ray by ray\n";
  EXPECT_EQ(differ, 0);
  EXPECT_GT(partial, 100);  // the comparison covers shadow edges, not only lit or dark points
}

// a result cast into again (other particles, another grid) equals a fresh cast, ray for ray
TEST(LaserShadowing, ReusedResultEqualsFresh)
{
  const GaussianBeam b = test_beam(Eigen::Vector3d(0.1, 0.0, -1.0));
  const double w = b.radius;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> pos(-2.0 * w, 2.0 * w), rad(0.1 * w, 0.3 * w), up(0.0, w);
  ShadowResult reused;
  for (const double cpr : {20.0, 8.0, 12.0}) {
    std::vector<BeamParticle> ps;
    for (int k = 0; k < 200; ++k) ps.push_back({beam_point(b, up(rng), pos(rng), pos(rng)), rad(rng)});
    ShadowOptions opt;
    opt.cells_per_particle_radius = cpr;
    shade_particles(b, ps, opt, reused);
    const ShadowResult fresh = shade_particles(b, ps, opt);
    ASSERT_EQ(reused.grid.n, fresh.grid.n);
    EXPECT_EQ(reused.grid.entry_depth, fresh.grid.entry_depth) << "cells_per_particle_radius " << cpr;
    EXPECT_EQ(reused.grid.owner, fresh.grid.owner);
    EXPECT_EQ(reused.grid.block_entry_depth, fresh.grid.block_entry_depth);
    EXPECT_EQ(reused.grid.block_max_entry_depth, fresh.grid.block_max_entry_depth);
    EXPECT_EQ(reused.grid.block_max_hit_depth, fresh.grid.block_max_hit_depth);
    EXPECT_EQ(reused.grid.hits_before, fresh.grid.hits_before);
    EXPECT_EQ(reused.intercepted, fresh.intercepted);
    EXPECT_EQ(reused.absorbed, fresh.absorbed);
    EXPECT_EQ(reused.transmitted_power, fresh.transmitted_power);
    EXPECT_EQ(reused.tail_power, fresh.tail_power);
  }
}

// cost per particle for 1000 particles (printed, not asserted)
TEST(LaserShadowing, CostPerParticle)
{
  const GaussianBeam b = test_beam();
  const double w = b.radius;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-2.5 * w, 2.5 * w), rad(0.15 * w, 0.4 * w), up(0.0, 3.0 * w);
  std::vector<BeamParticle> ps;
  for (int k = 0; k < 1000; ++k) ps.push_back({beam_point(b, up(rng), pos(rng), pos(rng)), rad(rng)});
  for (double cpr : {10.0, 20.0, 40.0}) {
    ShadowOptions opt;
    opt.cells_per_radius = 1.0;
    opt.cells_per_particle_radius = cpr;
    shade_particles(b, ps, opt);  // warm-up
    const int reps = 5;
    const auto t0 = std::chrono::steady_clock::now();
    double total = 0.0;
    for (int k = 0; k < reps; ++k) total += shade_particles(b, ps, opt).intercepted_total;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / reps;
    ShadowResult reused;
    const auto t1 = std::chrono::steady_clock::now();
    for (int k = 0; k < reps; ++k) shade_particles(b, ps, opt, reused);
    const double s_reused = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count() / reps;
    const ShadowGrid grid = shade_particles(b, ps, opt).grid;
    std::cout << "COST 1000 particles (R = 0.15..0.4 w), cells_per_particle_radius " << cpr
              << ": 0.15 w / h = " << 0.15 * w / grid.h << " (" << grid.n << "^2 rays): " << s * 1e3 << " ms per call, "
              << s / 1000 * 1e6 << " us per particle (intercepted " << total / reps << " W); " << s_reused * 1e3
              << " ms with the storage kept\n";
  }
}
