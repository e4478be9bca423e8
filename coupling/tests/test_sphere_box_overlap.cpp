// Sphere-box overlap in closed form: against 30-digit references (sphere_box_reference.py),
// the adaptive quadrature, analytic caps, and the per-particle lattice of shared planes.
#include "meltdem/coupling/exact_sum.h"
#include "meltdem/coupling/particle_distribution.h"
#include "meltdem/coupling/sphere_box_overlap.h"
#include "validation_report.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace meltdem::coupling;
using Eigen::Vector3d;
using meltdem::testing::expect_absolute;
using meltdem::testing::expect_relative;

namespace {

struct ReferenceBox {
  Vector3d lo, hi;
  double volume;  // unit sphere at the origin, mpmath to 20 digits
};

// printed by coupling/tests/sphere_box_reference.py
const ReferenceBox kReference[] = {
    {{0.0, 0.0, 0.0}, {2.0, 2.0, 2.0}, 0.52359877559829887308},
    {{0.3, 0.5, 0.7}, {2.0, 2.0, 2.0}, 0.00072931826812383059522},
    {{-0.6106402478264825, -1.2509781158427484, -0.0074228645278879846},
     {1.140548785210349, -0.36073179451739534, 0.9949745747275258},
     0.4779311737087830854},
    {{-0.2, -0.3, -0.4}, {0.1, 0.25, 0.05}, 0.074250000000000006745},
    {{0.5, 0.5, 0.5}, {0.6, 0.6, 0.6}, 0.00094609563470697510814},
    {{0.57, 0.57, 0.57}, {0.9, 0.9, 0.9}, 1.7701827584928189598e-6},
    {{-1.0, -1.0, 0.999}, {1.0, 1.0, 1.0}, 3.1405454560386022185e-6},
    {{0.7, -0.1, -0.1}, {1.5, 0.1, 0.1}, 0.011866353827971023907},
    {{-0.9, 0.4, -0.3}, {-0.2, 0.9, 0.6}, 0.20801023173865321765},
    {{-0.05, -0.05, -0.05}, {0.05, 0.05, 0.05}, 0.0010000000000000001665},
    {{0.0, 0.0, -1.5}, {1.5, 1.5, 1e-06}, 0.52359956099646227026},
    {{-0.3, 0.2, 0.95}, {0.3, 0.3, 1.2}, 0.00046959682825260459444},
};

double sphere_volume(double r)
{
  return 4.0 / 3.0 * M_PI * r * r * r;
}

}  // namespace

TEST(SphereBoxOverlap, ThirtyDigitReferences)
{
  // the sphere moved and scaled: the error is round-off of r^3
  const double r = 3.7e-5;
  const Vector3d c(1.1e-4, -2.3e-4, 0.7e-4);
  double worst = 0.0, worst_unit = 0.0;
  for (const ReferenceBox &b : kReference) {
    worst_unit = std::max(worst_unit, std::abs(sphere_box_overlap(Vector3d::Zero(), 1.0, b.lo, b.hi) - b.volume));
    const double v = sphere_box_overlap(c, r, c + r * b.lo, c + r * b.hi);
    worst = std::max(worst, std::abs(v / (r * r * r) - b.volume));
  }
  expect_absolute("unit sphere, 12 boxes: max |closed form - mpmath|", worst_unit, 0.0, 2e-15);
  expect_absolute("r = 37 um off the origin, 12 boxes: max |closed form - mpmath| / r^3", worst, 0.0, 1e-14);
}

TEST(SphereBoxOverlap, AgreesWithQuadrature)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pos(-1.3, 1.3), len(0.001, 1.5);
  double worst = 0.0;
  for (int n = 0; n < 4000; ++n) {
    Vector3d lo(pos(rng), pos(rng), pos(rng));
    Vector3d hi = lo + Vector3d(len(rng), len(rng), len(rng));
    if (n % 4 == 1) hi.x() -= lo.x(), lo.x() = 0.0;  // a plane through the centre
    if (n % 4 == 2) lo.y() = 1.0 - 1e-9;             // a plane almost tangent
    const double a = sphere_box_overlap(Vector3d::Zero(), 1.0, lo, hi);
    const double b = sphere_box_overlap_quadrature(Vector3d::Zero(), 1.0, lo, hi);
    worst = std::max(worst, std::abs(a - b));
  }
  expect_absolute("4000 random boxes, unit sphere: max |closed form - quadrature|", worst, 0.0, 2e-12);
}

TEST(SphereBoxOverlap, CapsSlabsAndSymmetry)
{
  const double r = 1.0;
  for (double h : {1e-6, 0.01, 0.3, 1.0, 1.7, 2.0 - 1e-9}) {
    const double cap = M_PI * h * h * (3.0 * r - h) / 3.0;
    expect_absolute("cap of height " + std::to_string(h) + " / r^3",
                    sphere_box_overlap(Vector3d::Zero(), r, Vector3d(-2, -2, 1.0 - h), Vector3d(2, 2, 2)), cap, 2e-15);
  }
  // the eight octant boxes around a centre off every plane sum to the sphere
  const Vector3d c(0.1, -0.2, 0.3), big(5, 5, 5);
  ExactSum s;
  for (int o = 0; o < 8; ++o) {
    Vector3d lo, hi;
    for (int a = 0; a < 3; ++a) {
      const bool up = (o >> a) & 1;
      lo[a] = up ? 0.0 : -big[a];
      hi[a] = up ? big[a] : 0.0;
    }
    s.add(sphere_box_overlap(c, r, lo, hi));
  }
  expect_relative("8 orthants about a point inside vs sphere", s.value(), sphere_volume(r), 1e-15);
}

TEST(SphereBoxOverlap, SharedPlanesEqualSingleBoxes)
{
  // cells of 0.25 to 10 per diameter, uniform and stretched: the lattice gives each cell's
  // single-box value and the cells sum to the sphere (below 1 cell per diameter most spheres
  // are cut by at most one plane per axis: the octant path); a quarter of the centres lie
  // on a cell face, edge or corner
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  double worst_cell = 0.0, worst_sum = 0.0;
  for (double cells_per_d : {0.25, 0.5, 0.8, 1.0, 2.0, 3.0, 5.0, 10.0}) {
    const double h = 2.0 / cells_per_d;
    const int n = int(std::ceil(4.0 / h)) + 2;
    std::vector<double> x(n + 1), y(n + 1), z(n + 1);
    for (int i = 0; i <= n; ++i) {
      x[i] = -2.0 - h + i * h;
      y[i] = i ? y[i - 1] + h * (1.0 + 0.3 * (i % 2)) : -2.0 - h;  // uneven spacing
      z[i] = -2.0 - h + i * h;
    }
    CartesianGridMesh mesh(x, y, z);
    for (int p = 0; p < 40; ++p) {
      Vector3d c(u(rng) * h, u(rng) * h, u(rng) * h);
      if (p % 4 == 3) c.x() = x[std::size_t(n / 2)];
      if (p % 8 == 7) c.y() = y[std::size_t(n / 2)];
      std::vector<CellWeight> raw;
      append_overlap_volumes(mesh, c, 1.0, raw);
      ExactSum s;
      for (const CellWeight &w : raw) {
        Vector3d lo, hi;
        mesh.cell_bounds(w.cell, lo, hi);
        worst_cell = std::max(worst_cell, std::abs(w.weight - sphere_box_overlap(c, 1.0, lo, hi)));
        s.add(w.weight);
      }
      worst_sum = std::max(worst_sum, std::abs(s.value() / sphere_volume(1.0) - 1.0));
    }
  }
  expect_absolute("0.25-10 cells/d: max |lattice - single box| / r^3", worst_cell, 0.0, 1e-14);
  expect_absolute("0.25-10 cells/d: max |sum over cells / sphere - 1|", worst_sum, 0.0, 1e-14);
}
