#include "meltdem/coupling/laser_shadowing.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace meltdem::coupling {

namespace {

[[noreturn]] void bad(const std::string &what)
{
  throw std::invalid_argument("laser shadowing: " + what);
}

std::string str(double x)
{
  std::ostringstream os;
  os << x;
  return os.str();
}

std::string str(const Eigen::Vector3d &x)
{
  std::ostringstream os;
  os << "(" << x.x() << " " << x.y() << " " << x.z() << ")";
  return os.str();
}

void check_beam(const GaussianBeam &beam)
{
  if (!(beam.power >= 0.0) || !std::isfinite(beam.power))
    bad("beam power P = " + str(beam.power) + " W must be finite and >= 0");
  if (!(beam.absorptivity >= 0.0 && beam.absorptivity <= 1.0))
    bad("beam absorptivity eta = " + str(beam.absorptivity) + " must be in [0, 1]");
  if (!(beam.radius > 0.0) || !std::isfinite(beam.radius))
    bad("beam radius w = " + str(beam.radius) + " m (1/e^2 radius) must be finite and > 0");
  if (!beam.centre.allFinite()) bad("beam centre " + str(beam.centre) + " is not finite");
  if (!beam.direction.allFinite() || !(beam.direction.norm() > 0.0))
    bad("beam direction " + str(beam.direction) + " must be finite and non-zero");
}

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n)
void gauss_legendre(int n, std::vector<double> &x, std::vector<double> &wt)
{
  x.assign(n, 0.0);
  wt.assign(n, 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1.0;
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = -z;
    x[n - 1 - i] = z;
    wt[i] = wt[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

}  // namespace

void beam_plane_basis(const Eigen::Vector3d &direction, Eigen::Vector3d &u, Eigen::Vector3d &v)
{
  const Eigen::Vector3d d = direction.normalized();
  const Eigen::Vector3d e = std::abs(d.x()) > 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  u = (e - e.dot(d) * d).normalized();
  v = d.cross(u);
}

double beam_irradiance(const GaussianBeam &beam, double rho)
{
  check_beam(beam);
  const double w2 = beam.radius * beam.radius;
  return 2.0 * beam.power / (M_PI * w2) * std::exp(-2.0 * rho * rho / w2);
}

double beam_power_in_disk(const GaussianBeam &beam, double R, double s)
{
  check_beam(beam);
  if (!(R >= 0.0) || !(s >= 0.0)) bad("disk radius " + str(R) + " and offset " + str(s) + " must be >= 0");
  const double w = beam.radius;
  if (s == 0.0) return -beam.power * std::expm1(-2.0 * R * R / (w * w));
  // polar quadrature about the disk centre: composite Gauss-Legendre in rho (smooth
  // integrand), trapezoid in theta (periodic: spectrally accurate)
  std::vector<double> gx, gw;
  gauss_legendre(16, gx, gw);
  const int panels = 64, ntheta = 1024;
  const double dr = R / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    for (int k = 0; k < 16; ++k) {
      const double rho = dr * (p + 0.5 * (gx[k] + 1.0));
      double ring = 0.0;
      for (int t = 0; t < ntheta; ++t) {
        const double th = 2.0 * M_PI * t / ntheta;
        const double r2 = rho * rho + s * s + 2.0 * rho * s * std::cos(th);
        ring += std::exp(-2.0 * r2 / (w * w));
      }
      sum += 0.5 * dr * gw[k] * rho * ring * (2.0 * M_PI / ntheta);
    }
  }
  return 2.0 * beam.power / (M_PI * w * w) * sum;
}

ShadowResult shade_particles(const GaussianBeam &beam, const std::vector<BeamParticle> &particles,
                             const ShadowOptions &options)
{
  ShadowResult res;
  shade_particles(beam, particles, options, res);
  return res;
}

void shade_particles(const GaussianBeam &beam, const std::vector<BeamParticle> &particles, const ShadowOptions &options,
                     ShadowResult &res)
{
  check_beam(beam);
  if (!(options.cells_per_radius > 0.0) || !std::isfinite(options.cells_per_radius))
    bad("cells_per_radius = " + str(options.cells_per_radius) + " must be finite and > 0");
  if (!(options.extent > 0.0) || !std::isfinite(options.extent))
    bad("extent = " + str(options.extent) + " beam radii must be finite and > 0");
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const auto &p = particles[k];
    if (!(p.radius > 0.0) || !std::isfinite(p.radius))
      bad("particle " + std::to_string(k) + " radius = " + str(p.radius) + " m must be finite and > 0");
    if (!p.x.allFinite()) bad("particle " + std::to_string(k) + " centre " + str(p.x) + " is not finite");
  }

  if (!(options.cells_per_particle_radius >= 0.0) || !std::isfinite(options.cells_per_particle_radius))
    bad("cells_per_particle_radius = " + str(options.cells_per_particle_radius) + " must be finite and >= 0");
  if (!(options.max_cells >= 4)) bad("max_cells = " + std::to_string(options.max_cells) + " must be >= 4");

  ShadowGrid &g = res.grid;
  const double w = beam.radius, P = beam.power, eta = beam.absorptivity;
  g.centre = beam.centre;
  g.direction = beam.direction.normalized();
  beam_plane_basis(g.direction, g.u, g.v);
  // half the number of cells per side (even count: the grid is symmetric about the axis)
  const double max_half = std::floor(0.5 * std::sqrt(static_cast<double>(options.max_cells)));
  double half_cells = std::ceil(options.extent * options.cells_per_radius - 1e-9);
  if (!(half_cells <= max_half))
    bad("a ray grid of " + str(2 * half_cells) + "^2 cells (cells_per_radius " + str(options.cells_per_radius) +
        ", extent " + str(options.extent) + ") exceeds max_cells = " + std::to_string(options.max_cells));
  if (options.cells_per_particle_radius > 0.0) {
    // the smallest particle whose disk reaches into the sampled square
    const double half = options.extent * w;
    double rmin = std::numeric_limits<double>::infinity();
    for (const auto &p : particles) {
      const Eigen::Vector3d q = p.x - g.centre;
      if (std::abs(q.dot(g.u)) < half + p.radius && std::abs(q.dot(g.v)) < half + p.radius)
        rmin = std::min(rmin, p.radius);
    }
    if (std::isfinite(rmin))
      half_cells =
          std::max(half_cells, std::min(max_half, std::ceil(half * options.cells_per_particle_radius / rmin - 1e-9)));
  }
  g.n = 2 * static_cast<int>(half_cells);
  const int n = g.n, m = n / 2;
  g.h = options.extent * w / m;
  g.half_width = m * g.h;

  // exact 1D cell fractions of the separable profile, mirrored so the grid is symmetric;
  // erfc differences keep the tail cells' relative precision
  g.g.assign(n, 0.0);
  const double a = std::sqrt(2.0) * g.h / w;
  for (int i = 0; i < m; ++i) {
    const double gi = 0.5 * (std::erfc(a * i) - std::erfc(a * (i + 1)));
    g.g[m + i] = gi;
    g.g[m - 1 - i] = gi;
  }
  double sum_g = 0.0;
  for (int i = 0; i < m; ++i) sum_g += g.g[m + i];  // half, in one order
  sum_g *= 2.0;

  const std::size_t ncell = static_cast<std::size_t>(n) * n;
  g.entry_depth.assign(ncell, std::numeric_limits<double>::infinity());
  g.owner.assign(ncell, -1);
  g.nb = (n + kShadowBlock - 1) / kShadowBlock;
  g.block_entry_depth.assign(static_cast<std::size_t>(g.nb) * g.nb, std::numeric_limits<double>::infinity());

  // z-buffer: each ray keeps the sphere it enters first
  const double inv_h = 1.0 / g.h, inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const Eigen::Vector3d p = particles[k].x - g.centre;
    const double depth = p.dot(g.direction), pu = p.dot(g.u), pv = p.dot(g.v);
    const double R = particles[k].radius, R2 = R * R;
    // a disk outside the square has no rays (and far-away centres would overflow the indices)
    if (!(std::abs(pu) < g.half_width + R && std::abs(pv) < g.half_width + R)) continue;
    // cell centres u_i = (i + 0.5 - m) h
    const int j0 = std::max(0, static_cast<int>(std::ceil((pv - R) * inv_h + m - 0.5)));
    const int j1 = std::min(n - 1, static_cast<int>(std::floor((pv + R) * inv_h + m - 0.5)));
    for (int j = j0; j <= j1; ++j) {
      const double dv = (j + 0.5 - m) * g.h - pv;
      const double rem = R2 - dv * dv;
      if (rem <= 0.0) continue;
      const double chord = std::sqrt(rem);
      const int i0 = std::max(0, static_cast<int>(std::ceil((pu - chord) * inv_h + m - 0.5)));
      const int i1 = std::min(n - 1, static_cast<int>(std::floor((pu + chord) * inv_h + m - 0.5)));
      const std::size_t row = static_cast<std::size_t>(j) * n;
      // each block's smallest entry: the smallest value ever written to it (entries only fall)
      double *blocks = g.block_entry_depth.data() + static_cast<std::size_t>(j / kShadowBlock) * g.nb;
      int block = i0 / kShadowBlock;
      double block_min = inf;
      for (int i = i0; i <= i1; ++i) {
        if (i / kShadowBlock != block) {
          blocks[block] = std::min(blocks[block], block_min);
          block = i / kShadowBlock;
          block_min = inf;
        }
        // (the sphere enters no ray before depth - R: a ray hit there or above keeps its entry)
        if (!(g.entry_depth[row + i] > depth - R)) continue;
        const double du = (i + 0.5 - m) * g.h - pu;
        const double r2 = du * du + dv * dv;
        if (!(r2 < R2)) continue;
        const double entry = depth - std::sqrt(R2 - r2);
        if (entry < g.entry_depth[row + i]) {
          g.entry_depth[row + i] = entry;
          g.owner[row + i] = static_cast<int>(k);
          block_min = std::min(block_min, entry);
        }
      }
      if (i0 <= i1) blocks[block] = std::min(blocks[block], block_min);
    }
  }

  // each row's runs of rays with one owner are summed before they are booked: consecutive
  // rays mostly share their particle, and a sum into memory per ray waits on the last one
  // (the same pass takes each block's largest entry depth, of all rays and of the hit ones, and
  // counts each row's hit rays)
  res.intercepted.assign(particles.size(), 0.0);
  g.block_max_entry_depth.assign(static_cast<std::size_t>(g.nb) * g.nb, -inf);
  g.block_max_hit_depth.assign(static_cast<std::size_t>(g.nb) * g.nb, -inf);
  // (16-bit counts: rows of up to 65535 rays; wider grids read their rays)
  const bool count_hits = n <= std::numeric_limits<std::uint16_t>::max();
  g.hits_before.resize(count_hits ? static_cast<std::size_t>(n) * (n + 1) : 0);
  for (int j = 0; j < n; ++j) {
    const int *owner = g.owner.data() + static_cast<std::size_t>(j) * n;
    const double *entry = g.entry_depth.data() + static_cast<std::size_t>(j) * n;
    double *block_max = g.block_max_entry_depth.data() + static_cast<std::size_t>(j / kShadowBlock) * g.nb;
    double *block_hit = g.block_max_hit_depth.data() + static_cast<std::size_t>(j / kShadowBlock) * g.nb;
    std::uint16_t *before = count_hits ? g.hits_before.data() + static_cast<std::size_t>(j) * (n + 1) : nullptr;
    std::uint16_t hits = 0;
    for (int i0 = 0; i0 < n; i0 += kShadowBlock) {
      double largest = block_max[i0 / kShadowBlock], largest_hit = block_hit[i0 / kShadowBlock];
      for (int i = i0; i < std::min(n, i0 + kShadowBlock); ++i) {
        largest = std::max(largest, entry[i]);
        if (before) before[i] = hits;
        if (owner[i] >= 0) {
          largest_hit = std::max(largest_hit, entry[i]);
          ++hits;
        }
      }
      block_max[i0 / kShadowBlock] = largest;
      block_hit[i0 / kShadowBlock] = largest_hit;
    }
    if (before) before[n] = hits;
    for (int i = 0; i < n;) {
      const int o = owner[i];
      double run = 0.0;
      do {
        run += P * g.g[i] * g.g[j];
        ++i;
      } while (i < n && owner[i] == o);
      if (o >= 0) res.intercepted[o] += run;
    }
  }
  res.absorbed.resize(particles.size());
  double total = 0.0;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    total += res.intercepted[k];
    res.absorbed[k] = eta * res.intercepted[k];
  }
  res.intercepted_total = total;
  res.transmitted_power = P - total;
  res.sampled_power = P * sum_g * sum_g;
  res.tail_power = P - res.sampled_power;
  res.power = P;
  res.absorptivity = eta;
}

ShadowResult shade_particles(MPI_Comm comm, const GaussianBeam &beam, const std::vector<BeamParticle> &local,
                             const ShadowOptions &options)
{
  ShadowResult global;
  shade_particles(comm, beam, local, options, global);
  return global;
}

void shade_particles(MPI_Comm comm, const GaussianBeam &beam, const std::vector<BeamParticle> &local,
                     const ShadowOptions &options, ShadowResult &global)
{
  check_beam(beam);  // the same beam everywhere: every rank throws alike
  // check the local particles first, and agree on the outcome, so that no rank is left
  // waiting in the gather below
  std::string local_error;
  for (std::size_t k = 0; k < local.size() && local_error.empty(); ++k) {
    if (!(local[k].radius > 0.0) || !std::isfinite(local[k].radius))
      local_error =
          "local particle " + std::to_string(k) + " radius = " + str(local[k].radius) + " m must be finite and > 0";
    else if (!local[k].x.allFinite())
      local_error = "local particle " + std::to_string(k) + " centre " + str(local[k].x) + " is not finite";
  }
  int rank = 0, size = 1, mine = local_error.empty() ? 0 : 1, any = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
  if (any) bad(mine ? local_error + " (rank " + std::to_string(rank) + ")" : "bad particle input on another rank");

  // the particles whose disk reaches the sampled square
  Eigen::Vector3d u, v;
  const Eigen::Vector3d d = beam.direction.normalized();
  beam_plane_basis(d, u, v);
  const double half = options.extent * beam.radius;
  std::vector<int> selected;
  std::vector<double> packed;
  for (std::size_t k = 0; k < local.size(); ++k) {
    const Eigen::Vector3d q = local[k].x - beam.centre;
    if (std::abs(q.dot(u)) < half + local[k].radius && std::abs(q.dot(v)) < half + local[k].radius) {
      selected.push_back(static_cast<int>(k));
      packed.insert(packed.end(), {local[k].x.x(), local[k].x.y(), local[k].x.z(), local[k].radius});
    }
  }
  int count = static_cast<int>(packed.size());
  std::vector<int> counts(size), offsets(size, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < size; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<double> all(offsets[size - 1] + counts[size - 1]);
  MPI_Allgatherv(packed.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, comm);
  std::vector<BeamParticle> gathered(all.size() / 4);
  for (std::size_t k = 0; k < gathered.size(); ++k)
    gathered[k] = {Eigen::Vector3d(all[4 * k], all[4 * k + 1], all[4 * k + 2]), all[4 * k + 3]};

  shade_particles(beam, gathered, options, global);
  // back to the caller's particles
  std::vector<double> absorbed(local.size(), 0.0), intercepted(local.size(), 0.0);
  const std::size_t first = offsets[rank] / 4;
  for (std::size_t j = 0; j < selected.size(); ++j) {
    absorbed[selected[j]] = global.absorbed[first + j];
    intercepted[selected[j]] = global.intercepted[first + j];
  }
  global.absorbed = std::move(absorbed);
  global.intercepted = std::move(intercepted);
}

double transmitted_fraction(const ShadowResult &result, const Eigen::Vector3d &point, double footprint)
{
  const ShadowGrid &g = result.grid;
  if (g.n == 0) bad("transmitted_fraction needs the result of shade_particles");
  if (!point.allFinite()) bad("transmitted_fraction: point " + str(point) + " is not finite");
  if (!(footprint >= 0.0) || !std::isfinite(footprint))
    bad("transmitted_fraction: footprint " + str(footprint) + " m must be finite and >= 0");
  const Eigen::Vector3d p = point - g.centre;
  const double depth = p.dot(g.direction), pu = p.dot(g.u), pv = p.dot(g.v);
  const double m = g.n / 2, inv_h = 1.0 / g.h;
  const bool blocks = g.nb > 0 && g.block_entry_depth.size() == static_cast<std::size_t>(g.nb) * g.nb &&
                      g.block_max_entry_depth.size() == g.block_entry_depth.size();
  const bool hit_counts = blocks && g.block_max_hit_depth.size() == g.block_entry_depth.size() &&
                          g.hits_before.size() == static_cast<std::size_t>(g.n) * (g.n + 1);
  // lattice index of a ray; those outside the grid carry no particle: lit
  auto lit_at = [&](double fi, double fj) {
    if (fi < 0 || fj < 0 || fi >= g.n || fj >= g.n) return true;
    const std::size_t idx = static_cast<std::size_t>(fj) * g.n + static_cast<std::size_t>(fi);
    return depth < g.entry_depth[idx];
  };
  const bool single_lit = lit_at(std::floor(pu * inv_h) + m, std::floor(pv * inv_h) + m);
  if (footprint > 0.0) {
    // the rays of the (unbounded) lattice whose centres lie in the footprint disk
    const double j0 = std::ceil((pv - footprint) * inv_h + m - 0.5);
    const double j1 = std::floor((pv + footprint) * inv_h + m - 0.5);
    const double i0 = std::ceil((pu - footprint) * inv_h + m - 0.5);
    const double i1 = std::floor((pu + footprint) * inv_h + m - 0.5);
    if ((j1 - j0 + 1) * (i1 - i0 + 1) > 1e8)
      bad("transmitted_fraction: footprint " + str(footprint) + " m covers more than 1e8 rays");
    // every block under the disk's bounding square starts below the point: all its rays are lit
    // (then the answer is 1 whether or not a ray centre lies in the disk, if the nearest ray is lit)
    const double c0 = std::max(i0, 0.0), c1 = std::min(i1, g.n - 1.0);
    const double r0 = std::max(j0, 0.0), r1 = std::min(j1, g.n - 1.0);
    if (single_lit && blocks) {
      bool all_lit = true;
      if (r0 <= r1 && c0 <= c1) {
        const auto bj0 = static_cast<std::size_t>(r0) / kShadowBlock, bj1 = static_cast<std::size_t>(r1) / kShadowBlock;
        const auto bi0 = static_cast<std::size_t>(c0) / kShadowBlock, bi1 = static_cast<std::size_t>(c1) / kShadowBlock;
        for (std::size_t bj = bj0; all_lit && bj <= bj1; ++bj)
          for (std::size_t bi = bi0; all_lit && bi <= bi1; ++bi) all_lit = depth < g.block_entry_depth[bj * g.nb + bi];
      }
      if (all_lit) return 1.0;
    }
    const double f2 = footprint * footprint;
    auto inside = [&](double fi, double dv) {
      const double du = (fi + 0.5 - m) * g.h - pu;
      return !(du * du + dv * dv > f2);
    };
    long total = 0, dark = 0;
    for (double fj = j0; fj <= j1; ++fj) {
      const double dv = (fj + 0.5 - m) * g.h - pv;
      const double rem = f2 - dv * dv;
      if (rem < 0.0) continue;  // dv^2 > f^2: no ray of this row lies in the disk
      // the row's chord, its ends settled by the membership test itself
      const double chord = std::sqrt(rem);
      double a = std::max(i0, std::ceil((pu - chord) * inv_h + m - 0.5));
      double b = std::min(i1, std::floor((pu + chord) * inv_h + m - 0.5));
      while (a <= b && !inside(a, dv)) ++a;
      while (a > i0 && inside(a - 1, dv)) --a;
      while (b >= a && !inside(b, dv)) --b;
      while (b < i1 && inside(b + 1, dv)) ++b;
      if (b < a) continue;
      total += static_cast<long>(b - a + 1);
      if (fj < 0 || fj >= g.n) continue;  // off the grid: lit
      const std::size_t row = static_cast<std::size_t>(fj) * g.n;
      const std::size_t lo = static_cast<std::size_t>(std::max(a, 0.0));
      const double hi_d = std::min(b, g.n - 1.0);
      if (hi_d < static_cast<double>(lo)) continue;
      const std::size_t hi = static_cast<std::size_t>(hi_d);
      const std::size_t block_row = static_cast<std::size_t>(fj) / kShadowBlock * g.nb;
      const double *bmin = blocks ? g.block_entry_depth.data() + block_row : nullptr;
      const double *bmax = blocks ? g.block_max_entry_depth.data() + block_row : nullptr;
      const double *bhit = hit_counts ? g.block_max_hit_depth.data() + block_row : nullptr;
      const std::uint16_t *before =
          hit_counts ? g.hits_before.data() + static_cast<std::size_t>(fj) * (g.n + 1) : nullptr;
      for (std::size_t i = lo; i <= hi;) {
        const std::size_t end = std::min(hi, (i / kShadowBlock + 1) * kShadowBlock - 1);
        if (bmin && depth < bmin[i / kShadowBlock]) {
          // every ray of the block lit at this depth
        } else if (bmax && !(depth < bmax[i / kShadowBlock])) {
          dark += static_cast<long>(end - i + 1);  // every ray of the block dark
        } else if (bhit && !(depth < bhit[i / kShadowBlock])) {
          dark += before[end + 1] - before[i];  // below every hit ray of the block: its hit rays dark
        } else {
          for (std::size_t k = i; k <= end; ++k) dark += depth < g.entry_depth[row + k] ? 0 : 1;
        }
        i = end + 1;
      }
    }
    if (total > 0) return static_cast<double>(total - dark) / total;
  }
  return single_lit ? 1.0 : 0.0;
}

std::vector<TransmittedRay> transmitted_rays(const ShadowResult &result)
{
  const ShadowGrid &g = result.grid;
  std::vector<TransmittedRay> rays;
  const int m = g.n / 2;
  for (int j = 0; j < g.n; ++j) {
    for (int i = 0; i < g.n; ++i) {
      if (g.owner[static_cast<std::size_t>(j) * g.n + i] >= 0) continue;
      const double power = result.power * g.g[i] * g.g[j];
      if (power == 0.0) continue;
      rays.push_back({g.centre + (i + 0.5 - m) * g.h * g.u + (j + 0.5 - m) * g.h * g.v, power});
    }
  }
  return rays;
}

}  // namespace meltdem::coupling
