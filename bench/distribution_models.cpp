// Error vs cost of the particle -> cell distribution models (centre, neighbours, overlap)
// at several cells per particle diameter. Driven by bench/distribution_models.py, which
// explains the error measures; this program prints one whitespace-separated row per
// (model, cells per diameter) under a header line ('#' lines are remarks).
//
//   bench_distribution_models [--positions 2000] [--cells-per-d 0.5,1,2,4,8] [--reps 7]
//                             [--time 0.1] [--seed 12345]
//
// Geometry: d = 1, uniform grid of spacing h = d / cells_per_d, large enough that the
// sphere never leaves it; the same random centres (fractions of one cell, fixed seed) are
// used at every resolution, so every offset of the sphere against the grid is sampled.
#include "meltdem/coupling/exact_sum.h"
#include "meltdem/coupling/particle_distribution.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using meltdem::coupling::CartesianGridMesh;
using meltdem::coupling::CellWeight;
using meltdem::coupling::DistributionModel;
using Eigen::Vector3d;

namespace {

[[noreturn]] void fail(const std::string &msg)
{
  std::fprintf(stderr, "bench_distribution_models: FATAL: %s\n", msg.c_str());
  std::fflush(stderr);
  std::abort();
}

struct Options {
  int positions = 2000;
  std::vector<double> cells_per_d = {0.5, 1.0, 2.0, 4.0, 8.0};
  int reps = 7;
  double time_per_rep = 0.1;  // seconds per timed repetition
  unsigned long seed = 12345;
};

Options parse(int argc, char **argv)
{
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) fail("option " + a + " needs a value");
    const std::string v = argv[++i];
    try {
      if (a == "--positions") o.positions = std::stoi(v);
      else if (a == "--reps") o.reps = std::stoi(v);
      else if (a == "--time") o.time_per_rep = std::stod(v);
      else if (a == "--seed") o.seed = std::stoul(v);
      else if (a == "--cells-per-d") {
        o.cells_per_d.clear();
        std::stringstream ss(v);
        std::string item;
        while (std::getline(ss, item, ',')) o.cells_per_d.push_back(std::stod(item));
      } else
        fail("unknown option " + a + " (valid: --positions --cells-per-d --reps --time --seed)");
    } catch (const std::logic_error &) {
      fail("bad value '" + v + "' for " + a);
    }
  }
  if (o.positions < 1 || o.reps < 1 || !(o.time_per_rep > 0.0) || o.cells_per_d.empty())
    fail("need --positions >= 1, --reps >= 1, --time > 0 and at least one cells per diameter");
  for (double c : o.cells_per_d)
    if (!(c > 0.0) || !std::isfinite(c)) fail("cells per diameter must be finite and > 0");
  return o;
}

// the weights must sum to 1 (compensated) and be finite and in (0, 1]: the bench relies on it
void check_weights(const std::vector<CellWeight> &w, long n_cells, const char *model, double cpd, double &worst)
{
  if (w.empty()) fail(std::string(model) + ": no weights for a particle inside the mesh");
  meltdem::coupling::ExactSum sum;
  for (const auto &cw : w) {
    if (!std::isfinite(cw.weight) || !(cw.weight > 0.0) || cw.weight > 1.0 + 1e-15 || cw.cell < 0 ||
        cw.cell >= n_cells)
      fail(std::string(model) + " at " + std::to_string(cpd) + " cells/d: weight " + std::to_string(cw.weight) +
           " for cell " + std::to_string(cw.cell));
    sum.add(cw.weight);
  }
  const double dev = std::abs(sum.value() - 1.0);
  worst = std::max(worst, dev);
  if (dev > 4e-16)
    fail(std::string(model) + " at " + std::to_string(cpd) + " cells/d: weights sum to 1 + " +
         std::to_string(sum.value() - 1.0));
}

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char **argv)
{
  const Options opt = parse(argc, argv);
  const double d = 1.0, r = 0.5 * d, vp = M_PI / 6.0 * d * d * d;
  const DistributionModel models[] = {DistributionModel::Centre, DistributionModel::Neighbours,
                                      DistributionModel::Overlap};

  std::mt19937_64 rng(opt.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vector3d> frac(opt.positions);
  for (auto &f : frac) f = Vector3d(unit(rng), unit(rng), unit(rng));

  std::printf("# d = %g, positions = %d (uniform in one cell, seed %lu), timing: median of %d repetitions of "
              ">= %g s\n",
              d, opt.positions, opt.seed, opt.reps, opt.time_per_rep);
  std::printf("model cells_per_d cells_per_particle l1_mean l1_max peak_mean peak_max exact_peak_mean "
              "exact_peak_max peak_bound centroid_mean centroid_max us_per_particle\n");

  double worst_sum = 0.0;
  long checked = 0;
  std::size_t sink = 0;  // keeps the timed calls observable
  for (double cpd : opt.cells_per_d) {
    const double h = d / cpd, vc = h * h * h;
    const int m = int(std::ceil(r / h)) + 1;  // cells on either side of the central cell [0, h)^3
    const int n = 2 * m + 1;
    const auto mesh = CartesianGridMesh::uniform(Vector3d::Constant(-m * h), Vector3d::Constant((m + 1) * h), n, n, n);
    const long nc = mesh.n_cells();
    std::vector<Vector3d> pos(frac.size());
    for (std::size_t p = 0; p < frac.size(); ++p) pos[p] = frac[p] * h;
    std::vector<Vector3d> centre(nc);
    for (long c = 0; c < nc; ++c) centre[c] = mesh.cell_centre(c);

    // exact overlap volumes per position, on the cells of the sphere's bounding box
    // (found from the grid indices, independent of the mesh's cells_in_sphere)
    std::vector<std::vector<std::pair<long, double>>> exact(pos.size());
    std::vector<double> exact_peak(pos.size());
    for (std::size_t p = 0; p < pos.size(); ++p) {
      int lo[3], hi[3];
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::max(0, int(std::floor((pos[p][a] - r) / h)) + m);
        hi[a] = std::min(n - 1, int(std::floor((pos[p][a] + r) / h)) + m);
      }
      meltdem::coupling::ExactSum total;
      double peak = 0.0;
      for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int i = lo[0]; i <= hi[0]; ++i) {
            const long c = mesh.index(i, j, k);
            Vector3d blo, bhi;
            mesh.cell_bounds(c, blo, bhi);
            const double v = meltdem::coupling::sphere_box_overlap(pos[p], r, blo, bhi);
            if (v > 0.0) exact[p].push_back({c, v});
            total.add(v);
            peak = std::max(peak, v / vc);
          }
      if (std::abs(total.value() / vp - 1.0) > 1e-10)
        fail("exact overlaps do not add up to the sphere volume at " + std::to_string(cpd) + " cells/d");
      exact_peak[p] = peak;
    }
    double exact_peak_mean = 0.0, exact_peak_max = 0.0;
    for (double e : exact_peak) {
      exact_peak_mean += e / pos.size();
      exact_peak_max = std::max(exact_peak_max, e);
    }

    std::vector<double> dep(nc, 0.0), ex(nc, 0.0);
    std::vector<CellWeight> w;
    for (auto model : models) {
      const char *name = meltdem::coupling::to_string(model);
      // error pass
      double l1_mean = 0.0, l1_max = 0.0, pk_mean = 0.0, pk_max = 0.0, cen_mean = 0.0, cen_max = 0.0, ncells = 0.0;
      for (std::size_t p = 0; p < pos.size(); ++p) {
        if (!meltdem::coupling::distribute_particle(mesh, model, pos[p], r, w))
          fail(std::string(name) + ": particle inside the mesh was not distributed");
        check_weights(w, nc, name, cpd, worst_sum);
        ++checked;
        ncells += double(w.size()) / pos.size();
        double peak = 0.0;
        Vector3d centroid = Vector3d::Zero();
        for (const auto &cw : w) {
          dep[cw.cell] += cw.weight * vp;  // deposited volume: fraction * V_cell
          peak = std::max(peak, cw.weight * vp / vc);
          centroid += cw.weight * centre[cw.cell];
        }
        for (const auto &e : exact[p]) ex[e.first] = e.second;
        double l1 = 0.0;
        for (const auto &cw : w) {
          l1 += std::abs(dep[cw.cell] - ex[cw.cell]);
          dep[cw.cell] = ex[cw.cell] = 0.0;  // counted once
        }
        for (const auto &e : exact[p]) {
          l1 += std::abs(dep[e.first] - ex[e.first]);  // exact cells that got nothing
          dep[e.first] = ex[e.first] = 0.0;
        }
        l1 /= vp;
        const double cen = (centroid - pos[p]).norm() / d;
        l1_mean += l1 / pos.size();
        l1_max = std::max(l1_max, l1);
        pk_mean += peak / pos.size();
        pk_max = std::max(pk_max, peak);
        cen_mean += cen / pos.size();
        cen_max = std::max(cen_max, cen);
      }

      // cost: calibrate on a few positions, then time repetitions of >= time_per_rep each
      const std::size_t probe = std::min<std::size_t>(pos.size(), 8);
      auto t0 = std::chrono::steady_clock::now();
      for (std::size_t p = 0; p < probe; ++p) {
        meltdem::coupling::distribute_particle(mesh, model, pos[p], r, w);
        sink += w.size();
      }
      const double t_probe =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / double(probe);
      const long count = std::max(16L, long(std::ceil(opt.time_per_rep / std::max(t_probe, 1e-9))));
      std::vector<double> per;
      for (int rep = 0; rep < opt.reps; ++rep) {
        t0 = std::chrono::steady_clock::now();
        for (long q = 0; q < count; ++q) {
          meltdem::coupling::distribute_particle(mesh, model, pos[std::size_t(q) % pos.size()], r, w);
          sink += w.size();
        }
        per.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() /
                      double(count));
      }

      std::printf("%s %g %.4g %.4g %.4g %.4g %.4g %.4g %.4g %.4g %.4g %.4g %.4g\n", name, cpd, ncells, l1_mean,
                  l1_max, pk_mean, pk_max, exact_peak_mean, exact_peak_max, std::min(1.0, vp / vc), cen_mean, cen_max,
                  median(per));
      std::fflush(stdout);
    }
  }
  std::printf("# weights sum to 1 checked on %ld distributions: largest |sum - 1| = %.3g (compensated sum)\n",
              checked, worst_sum);
  std::printf("# timed calls returned %zu weights in all\n", sink);
  return 0;
}
