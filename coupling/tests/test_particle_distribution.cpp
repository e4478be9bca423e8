// Particle -> cell distribution (Codina2019 §3.2.3, eq. 3.7): weights sum to 1, conservation,
// sphere-box overlap against analytic sphere / cap / octant volumes, domain clipping.
#include "meltdem/coupling/particle_distribution.h"
#include "meltdem/coupling/box_cell_lattice.h"
#include "meltdem/coupling/exact_sum.h"
#include "validation_report.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace meltdem::coupling;
using Eigen::Vector3d;
using meltdem::testing::expect_absolute;
using meltdem::testing::expect_relative;

namespace {

const double kEps = std::numeric_limits<double>::epsilon();

double sphere_volume(double r)
{
  return 4.0 / 3.0 * M_PI * r * r * r;
}
// volume of the cap of height h cut from a sphere of radius r
double cap_volume(double r, double h)
{
  return M_PI * h * h * (3.0 * r - h) / 3.0;
}

// sum of the raw sphere-cell overlaps over the mesh (what `overlap` normalises by)
double overlap_in_mesh(const DistributionMesh &mesh, const Vector3d &c, double r)
{
  std::vector<long> cells;
  mesh.cells_in_sphere(c, r, cells);
  ExactSum s;
  Vector3d lo, hi;
  for (long cell : cells) {
    mesh.cell_bounds(cell, lo, hi);
    s.add(sphere_box_overlap(c, r, lo, hi));
  }
  return s.value();
}

double exact_weight_sum(const std::vector<CellWeight> &w)
{
  ExactSum s;
  for (const auto &cw : w) s.add(cw.weight);
  return s.value();
}

// Hexahedral cells of different sizes side by side (a refinement level jump with hanging
// faces): a list of boxes searched by brute force
class BoxListMesh : public DistributionMesh {
 public:
  std::vector<Vector3d> lo, hi;
  void add(const Vector3d &l, const Vector3d &h) { lo.push_back(l), hi.push_back(h); }
  long find_cell(const Vector3d &p) const override
  {
    for (std::size_t i = 0; i < lo.size(); ++i)
      if ((p.array() >= lo[i].array()).all() && (p.array() < hi[i].array()).all()) return long(i);
    return -1;
  }
  void cell_bounds(long cell, Vector3d &l, Vector3d &h) const override { l = lo[cell], h = hi[cell]; }
  Vector3d cell_centre(long cell) const override { return 0.5 * (lo[cell] + hi[cell]); }
  double cell_volume(long cell) const override { return (hi[cell] - lo[cell]).prod(); }
  void cells_in_sphere(const Vector3d &c, double r, std::vector<long> &cells) const override
  {
    for (std::size_t i = 0; i < lo.size(); ++i)
      if ((c.cwiseMax(lo[i]).cwiseMin(hi[i]) - c).squaredNorm() < r * r) cells.push_back(long(i));
  }
  bool bounds(Vector3d &l, Vector3d &h) const override
  {
    if (lo.empty()) return false;
    l = lo[0], h = hi[0];
    for (std::size_t i = 1; i < lo.size(); ++i) l = l.cwiseMin(lo[i]), h = h.cwiseMax(hi[i]);
    return true;
  }
};

// [0,1]^3 coarse beside [1,2]x[0,1]^2 split into 8 cells of 0.5
BoxListMesh level_jump_mesh()
{
  BoxListMesh m;
  m.add(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const Vector3d l(1.0 + 0.5 * i, 0.5 * j, 0.5 * k);
        m.add(l, l + Vector3d(0.5, 0.5, 0.5));
      }
  return m;
}

}  // namespace

TEST(ParticleDistribution, DiskQuadrantArea)
{
  const double R = 1.3;
  expect_relative("disk ∩ {y<=0,z<=0} vs pi R^2/4", disk_quadrant_area(R, 0.0, 0.0), M_PI * R * R / 4.0, 1e-15);
  expect_relative("disk ∩ {y<=R,z<=R} vs pi R^2", disk_quadrant_area(R, 2.0, 5.0), M_PI * R * R, 1e-15);
  // circular segment beyond y = b: R^2 acos(b/R) - b sqrt(R^2 - b^2)
  const double b = 0.4, seg = R * R * std::acos(b / R) - b * std::sqrt(R * R - b * b);
  expect_relative("disk ∩ {y<=b} vs pi R^2 - segment", disk_quadrant_area(R, b, 10.0), M_PI * R * R - seg, 1e-14);
  expect_relative("disk ∩ {z<=-b} vs segment", disk_quadrant_area(R, 10.0, -b), seg, 1e-14);
  // quadrant with a corner inside: symmetric in (b, c)
  expect_relative("G(b,c) = G(c,b)", disk_quadrant_area(R, 0.3, -0.7), disk_quadrant_area(R, -0.7, 0.3), 1e-14);
}

TEST(ParticleDistribution, OverlapSingleBoxAnalytic)
{
  const double r = 1.0;
  const Vector3d c(0.1, -0.2, 0.3);
  const Vector3d big(5, 5, 5);
  expect_relative("sphere inside box", sphere_box_overlap(c, r, c - big, c + big), sphere_volume(r), 1e-15);
  // octant / quadrant / half through the centre: exact fractions by symmetry
  expect_relative("octant (x,y,z >= c)", sphere_box_overlap(c, r, c, c + big), sphere_volume(r) / 8.0, 1e-13);
  expect_relative("quadrant (x,y >= c)", sphere_box_overlap(c, r, c - Vector3d(0, 0, 5), c + big),
                  sphere_volume(r) / 4.0, 1e-13);
  expect_relative("half (z >= c)", sphere_box_overlap(c, r, c - Vector3d(5, 5, 0), c + big), sphere_volume(r) / 2.0,
                  1e-13);
  // sphere-halfspace caps, cut by one face of a large box
  for (double h : {0.05, 0.3, 0.77, 1.0, 1.4, 1.95}) {
    const Vector3d lo = c + Vector3d(-5, -5, r - h);
    expect_relative("cap h/r=" + std::to_string(h), sphere_box_overlap(c, r, lo, c + big), cap_volume(r, h), 1e-12);
  }
  // slab between two planes = difference of two caps
  {
    const double h1 = 0.4, h2 = 1.7;
    const Vector3d lo = c + Vector3d(-5, -5, r - h2), hi = c + Vector3d(5, 5, r - h1);
    expect_relative("slab (cap 1.7 - cap 0.4)", sphere_box_overlap(c, r, lo, hi), cap_volume(r, h2) - cap_volume(r, h1),
                    1e-12);
  }
  expect_absolute("disjoint box", sphere_box_overlap(c, r, c + Vector3d(1.01, -5, -5), c + big), 0.0, 0.0);
  const Vector3d small(0.2, 0.2, 0.2);
  expect_relative("box inside sphere", sphere_box_overlap(c, r, c - small, c + small), 0.064, 1e-15);
}

TEST(ParticleDistribution, OverlapSumsToSphereVolume)
{
  // powder-bed regime: 3, 6.5 and 10 cells per diameter, sphere well inside the mesh
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (double cells_per_d : {3.0, 6.5, 10.0}) {
    const double r = 1.0, h = 2.0 * r / cells_per_d;
    const int n = int(std::ceil(6.0 * r / h));
    const auto mesh =
        CartesianGridMesh::uniform(Vector3d(-3, -3, -3), Vector3d(-3, -3, -3) + Vector3d::Constant(n * h), n, n, n);
    double worst = 0.0;
    for (int t = 0; t < 20; ++t) {
      const Vector3d c(u(rng), u(rng), u(rng));
      worst = std::max(worst, std::abs(overlap_in_mesh(mesh, c, r) / sphere_volume(r) - 1.0));
    }
    expect_absolute("max |sum overlap / (4/3 pi r^3) - 1|, " + std::to_string(cells_per_d) + " cells/d (20 spheres)",
                    worst, 0.0, 1e-12);
  }
}

TEST(ParticleDistribution, OverlapClippedAtDomainBoundary)
{
  // domain floor at z = 0, sphere centred at height d < r: the mesh holds 4/3 pi r^3 - cap(r - d)
  const double r = 1.0;
  const auto mesh = CartesianGridMesh::uniform(Vector3d(-2, -2, 0), Vector3d(2, 2, 3), 16, 16, 12);
  for (double d : {0.1, 0.5, 0.9}) {
    const Vector3d c(0.13, -0.07, d);
    const double inside = sphere_volume(r) - cap_volume(r, r - d);
    const double raw = overlap_in_mesh(mesh, c, r);
    expect_relative("overlap in mesh, centre " + std::to_string(d) + " r above the floor", raw, inside, 1e-12);
    std::vector<CellWeight> w;
    ASSERT_TRUE(distribute_particle(mesh, DistributionModel::Overlap, c, r, w));
    expect_absolute("weights sum (clipped, renormalised)", exact_weight_sum(w), 1.0, 1e-15);
    // each weight is the cell's overlap over the clipped volume
    double worst = 0.0;
    Vector3d lo, hi;
    for (const auto &cw : w) {
      mesh.cell_bounds(cw.cell, lo, hi);
      worst = std::max(worst, std::abs(cw.weight - sphere_box_overlap(c, r, lo, hi) / inside));
    }
    expect_absolute("max |w_i - V_i/V_inside|", worst, 0.0, 1e-13);
  }
  // centred on a domain corner: 1/8 of the sphere is inside
  const Vector3d corner(-2, -2, 0);
  expect_relative("sphere on a domain corner: overlap in mesh vs V/8", overlap_in_mesh(mesh, corner, r),
                  sphere_volume(r) / 8.0, 1e-13);
}

TEST(ParticleDistribution, NeighboursEq37ByHand)
{
  // non-uniform grid so eq. 3.7 differs from the 1/n rule (eq. 3.6)
  const CartesianGridMesh mesh({0, 1, 3, 4}, {0, 2, 3, 5}, {0, 1, 2, 4});
  std::vector<CellWeight> w;
  // centre cell (1,1,1): [1,3]x[2,3]x[1,2], V = 2; the particle pokes through x = 3 and y = 3:
  // (2,1,1) V = 1 and (1,2,1) V = 4 -> weights 2/7, 1/7, 4/7
  ASSERT_TRUE(distribute_particle(mesh, DistributionModel::Neighbours, Vector3d(2.8, 2.9, 1.5), 0.3, w));
  ASSERT_EQ(w.size(), 3u);
  auto weight_of = [&](long cell) {
    for (const auto &cw : w)
      if (cw.cell == cell) return cw.weight;
    return -1.0;
  };
  expect_relative("w centre (1,1,1) = 2/7", weight_of(mesh.index(1, 1, 1)), 2.0 / 7.0, 1e-15);
  expect_relative("w x+ (2,1,1) = 1/7", weight_of(mesh.index(2, 1, 1)), 1.0 / 7.0, 1e-15);
  expect_relative("w y+ (1,2,1) = 4/7", weight_of(mesh.index(1, 2, 1)), 4.0 / 7.0, 1e-15);
  // through z = 2 only: (1,1,2) V = 4 -> 2/6, 4/6
  ASSERT_TRUE(distribute_particle(mesh, DistributionModel::Neighbours, Vector3d(2.0, 2.5, 1.9), 0.15, w));
  ASSERT_EQ(w.size(), 2u);
  expect_relative("w centre = 1/3", weight_of(mesh.index(1, 1, 1)), 1.0 / 3.0, 1e-15);
  expect_relative("w z+ (1,1,2) = 2/3", weight_of(mesh.index(1, 1, 2)), 2.0 / 3.0, 1e-15);
  // inside its cell: centre only
  ASSERT_TRUE(distribute_particle(mesh, DistributionModel::Neighbours, Vector3d(2.0, 2.5, 1.5), 0.2, w));
  expect_absolute("particle inside its cell: number of cells", double(w.size()), 1.0, 0.0);
  // Codina2019 fig. 3.10: particle larger than a uniform cell -> 7 cells of 1/7 = 0.1429
  const auto uni = CartesianGridMesh::uniform(Vector3d(0, 0, 0), Vector3d(5, 5, 5), 5, 5, 5);
  ASSERT_TRUE(distribute_particle(uni, DistributionModel::Neighbours, Vector3d(2.5, 2.5, 2.5), 0.8, w));
  expect_absolute("fig. 3.10: number of occupied cells", double(w.size()), 7.0, 0.0);
  for (const auto &cw : w) expect_relative("fig. 3.10: w = 1/7", cw.weight, 1.0 / 7.0, 1e-15);
  // at the domain floor the boundary face has no neighbour: 6 cells of 1/6
  ASSERT_TRUE(distribute_particle(uni, DistributionModel::Neighbours, Vector3d(2.5, 2.5, 0.5), 0.8, w));
  expect_absolute("at the floor: number of occupied cells", double(w.size()), 6.0, 0.0);
  expect_absolute("at the floor: weights sum", exact_weight_sum(w), 1.0, 1e-15);
}

TEST(ParticleDistribution, AcrossARefinementLevelJump)
{
  const BoxListMesh mesh = level_jump_mesh();
  std::vector<CellWeight> w;
  // in the coarse cell, through x = 1 into one of the four small cells behind that face
  // (the sphere misses the other three): volume weights 1 and 1/8
  ASSERT_TRUE(distribute_particle(mesh, DistributionModel::Neighbours, Vector3d(0.9, 0.3, 0.3), 0.2, w));
  expect_absolute("coarse -> fine: occupied cells", double(w.size()), 2.0, 0.0);
  for (const auto &cw : w)
    expect_relative("coarse -> fine: w of cell " + std::to_string(cw.cell), cw.weight,
                    cw.cell == 0 ? 1.0 / 1.125 : 0.125 / 1.125, 1e-15);
  // in a small cell, through x = 1 into the coarse cell (a face that is part of its face)
  ASSERT_TRUE(distribute_particle(mesh, DistributionModel::Neighbours, Vector3d(1.1, 0.25, 0.25), 0.15, w));
  expect_absolute("fine -> coarse: occupied cells", double(w.size()), 2.0, 0.0);
  for (const auto &cw : w)
    expect_relative("fine -> coarse: w of cell " + std::to_string(cw.cell), cw.weight,
                    cw.cell == 0 ? 1.0 / 1.125 : 0.125 / 1.125, 1e-15);
  // overlap over the jump: each weight is its cell's sphere-box volume over the sphere
  const Vector3d c(0.95, 0.45, 0.55);
  const double r = 0.3;
  ASSERT_TRUE(distribute_particle(mesh, DistributionModel::Overlap, c, r, w));
  double worst = 0.0;
  for (const auto &cw : w) {
    Vector3d lo, hi;
    mesh.cell_bounds(cw.cell, lo, hi);
    worst = std::max(worst, std::abs(cw.weight - sphere_box_overlap(c, r, lo, hi) / sphere_volume(r)));
  }
  expect_absolute("overlap across the jump: cells", double(w.size()), 5.0, 0.0);
  expect_absolute("overlap across the jump: max |w - V_cell / V_sphere|", worst, 0.0, 1e-15);
  expect_absolute("overlap across the jump: weights sum", exact_weight_sum(w), 1.0, 1e-15);
}

namespace {

// the same boxes with their lattice (the path a blockMesh, hexRef8-refined or not, takes)
class LatticeBoxListMesh : public BoxListMesh {
 public:
  BoxCellLattice grid;
  const BoxCellLattice *lattice() const override { return &grid; }
};

// a 5 x 4 x 4 graded block of cells of about h, shuffled labels, a hole every 9th slot; cells
// split into 8 where `refine` draws so (one level, or two for one in five of those): coarse
// cells span 2 or 4 slots per axis beside finer ones
LatticeBoxListMesh lattice_mesh(bool refine, double h, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.6, 1.4);
  std::uniform_int_distribution<int> pick(0, 99);
  std::vector<double> planes[3];
  const int n[3] = {5, 4, 4};
  for (int a = 0; a < 3; ++a) {
    planes[a].push_back(0.3 * a * h);
    for (int i = 0; i < n[a]; ++i) planes[a].push_back(planes[a].back() + h * u(rng));
  }
  std::vector<std::pair<Vector3d, Vector3d>> boxes;
  std::function<void(const Vector3d &, const Vector3d &, int)> split = [&](const Vector3d &lo, const Vector3d &hi,
                                                                           int level) {
    if (!refine || level == 2 || pick(rng) >= (level == 0 ? 50 : 20)) return boxes.emplace_back(lo, hi), void();
    const Vector3d mid = 0.5 * (lo + hi);
    for (int o = 0; o < 8; ++o) {
      Vector3d l, m;
      for (int a = 0; a < 3; ++a) l[a] = (o >> a) & 1 ? mid[a] : lo[a], m[a] = (o >> a) & 1 ? hi[a] : mid[a];
      split(l, m, level + 1);
    }
  };
  int count = 0;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        if (++count % 9 != 0)
          split(Vector3d(planes[0][i], planes[1][j], planes[2][k]),
                Vector3d(planes[0][i + 1], planes[1][j + 1], planes[2][k + 1]), 0);
  std::shuffle(boxes.begin(), boxes.end(), rng);
  LatticeBoxListMesh m;
  for (const auto &b : boxes) m.add(b.first, b.second);
  if (!m.grid.build(m.lo, m.hi, 64.0)) throw std::logic_error("lattice_mesh: no lattice");
  return m;
}

}  // namespace

// `overlap` read from the lattice's planes (pieces of the sphere where at most one plane cuts
// each axis, the slots' boxes elsewhere) against the cells' own boxes, cell by cell, on graded
// lattices with holes and on refined ones whose coarse cells span several slots; spheres from a
// fifth of a cell to three cells across, inside, on planes and over the edges of the mesh
TEST(ParticleDistribution, OverlapOnLatticeMatchesCellBoxes)
{
  const double h = 1e-5;
  for (const bool refine : {false, true}) {
    const LatticeBoxListMesh mesh = lattice_mesh(refine, h, refine ? 5u : 3u);
    BoxListMesh plain;  // the same cells without the lattice
    plain.lo = mesh.lo, plain.hi = mesh.hi;
    Vector3d mlo, mhi;
    ASSERT_TRUE(mesh.bounds(mlo, mhi));
    std::mt19937 rng(17u);
    std::uniform_real_distribution<double> u(-0.1, 1.1), size(0.1, 1.5);
    std::uniform_int_distribution<int> pick(0, 9);
    double worst = 0.0;
    int shared = 0, mismatched = 0, unordered = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      Vector3d c = mlo + (mhi - mlo).cwiseProduct(Vector3d(u(rng), u(rng), u(rng)));
      if (pick(rng) < 3) c[pick(rng) % 3] = mesh.lo[std::size_t(trial) % mesh.lo.size()][pick(rng) % 3];
      const double r = h * (pick(rng) < 8 ? 0.5 * size(rng) : 1.5 * size(rng));
      std::vector<CellWeight> got, want;
      append_overlap_volumes(mesh, c, r, got);
      append_overlap_volumes(plain, c, r, want);
      if (got.size() != want.size()) {
        ++mismatched;
        continue;
      }
      for (std::size_t i = 0; i < got.size(); ++i) {
        mismatched += got[i].cell != want[i].cell;
        unordered += i > 0 && got[i].cell <= got[i - 1].cell;
        worst = std::max(worst, std::abs(got[i].weight - want[i].weight) / (r * r * r));
      }
      shared += got.size() > 1;
    }
    const std::string mesh_name = refine ? "refined lattice" : "graded lattice with holes";
    expect_absolute(mesh_name + ": spheres whose cells differ from the boxes' path", double(mismatched), 0.0, 0.0);
    expect_absolute(mesh_name + ": max |V_lattice - V_boxes| / r^3", worst, 0.0, 1e-13);
    expect_absolute(mesh_name + ": cells out of ascending order", double(unordered), 0.0, 0.0);
    EXPECT_GT(shared, 1000) << "too few spheres over several cells to test anything";
  }
}

TEST(ParticleDistribution, WeightsSumToOneAndMassConserved)
{
  // random particles over a non-uniform grid, many near or across the domain boundary
  std::vector<double> x{0.0}, y{0.0}, z{0.0};
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> dh(0.5, 1.5);
  for (int i = 0; i < 20; ++i) x.push_back(x.back() + dh(rng));
  for (int i = 0; i < 15; ++i) y.push_back(y.back() + dh(rng));
  for (int i = 0; i < 12; ++i) z.push_back(z.back() + dh(rng));
  const CartesianGridMesh mesh(x, y, z);
  std::uniform_real_distribution<double> ux(-0.5, x.back() + 0.5), uy(-0.5, y.back() + 0.5), uz(-0.5, z.back() + 0.5);
  std::uniform_real_distribution<double> ur(0.1, 4.0), um(1e-9, 3e-9);

  for (auto model : {DistributionModel::Centre, DistributionModel::Neighbours, DistributionModel::Overlap}) {
    std::vector<double> cell_mass(mesh.n_cells(), 0.0);
    ExactSum handed;
    double worst_exact = 0.0, worst_naive = 0.0;
    std::size_t max_cells = 0;
    int outside = 0;
    std::vector<CellWeight> w;
    for (int p = 0; p < 3000; ++p) {
      const Vector3d c(ux(rng), uy(rng), uz(rng));
      const double r = ur(rng), m = um(rng);
      if (!distribute_particle(mesh, model, c, r, w)) {
        ++outside;
        EXPECT_TRUE(w.empty());
        continue;
      }
      double naive = 0.0;
      for (const auto &cw : w) {
        naive += cw.weight;
        EXPECT_GT(cw.weight, 0.0);
        cell_mass[cw.cell] += m * cw.weight;
      }
      worst_exact = std::max(worst_exact, std::abs(exact_weight_sum(w) - 1.0));
      worst_naive = std::max(worst_naive, std::abs(naive - 1.0) / (kEps * w.size()));
      max_cells = std::max(max_cells, w.size());
      handed.add(m);
    }
    const std::string name = to_string(model);
    expect_absolute(name + ": max |sum w - 1| (compensated sum), 3000 particles", worst_exact, 0.0, 1e-15);
    expect_absolute(name + ": max |naive sum w - 1| / (n_cells eps)", worst_naive, 0.0, 1.0);
    ExactSum deposited;
    for (double mc : cell_mass) deposited.add(mc);
    expect_relative(name + ": mass in cells vs mass handed over", deposited.value(), handed.value(), 1e-14);
    std::cout << "NOTE " << name << ": " << outside << " of 3000 centres outside the mesh (booked as outflow), "
              << "up to " << max_cells << " cells per particle" << std::endl;
    EXPECT_GT(outside, 0);
  }
}

TEST(ParticleDistribution, BadInput)
{
  const auto mesh = CartesianGridMesh::uniform(Vector3d(0, 0, 0), Vector3d(1, 1, 1), 4, 4, 4);
  std::vector<CellWeight> w{{3, 0.5}};
  EXPECT_THROW(distribute_particle(mesh, DistributionModel::Overlap, Vector3d(0.5, 0.5, 0.5), 0.0, w),
               std::invalid_argument);
  EXPECT_THROW(distribute_particle(mesh, DistributionModel::Centre, Vector3d(0.5, NAN, 0.5), 0.1, w),
               std::invalid_argument);
  EXPECT_FALSE(distribute_particle(mesh, DistributionModel::Overlap, Vector3d(1.5, 0.5, 0.5), 0.1, w));
  EXPECT_TRUE(w.empty());
  EXPECT_THROW(parse_distribution_model("multicell"), std::invalid_argument);
  EXPECT_EQ(parse_distribution_model("neighbours"), DistributionModel::Neighbours);
  EXPECT_THROW(CartesianGridMesh({0, 1, 1}, {0, 1}, {0, 1}), std::invalid_argument);
}

TEST(ParticleDistribution, CostPerParticleNote)
{
  // not a benchmark: a note of the order of magnitude (no assertion on time)
  for (double cells_per_d : {0.5, 1.0, 2.0, 4.0, 8.0}) {
    const double r = 1.0, h = 2.0 * r / cells_per_d;
    const int n = std::max(4, int(std::ceil(8.0 * r / h)));
    const auto mesh = CartesianGridMesh::uniform(Vector3d::Zero(), Vector3d::Constant(n * h), n, n, n);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.4 * n * h, 0.6 * n * h);
    std::vector<CellWeight> w;
    for (auto model : {DistributionModel::Centre, DistributionModel::Neighbours, DistributionModel::Overlap}) {
      const int np = model == DistributionModel::Overlap ? 40 : 20000;
      std::size_t cells = 0;
      const auto t0 = std::chrono::steady_clock::now();
      for (int p = 0; p < np; ++p) {
        distribute_particle(mesh, model, Vector3d(u(rng), u(rng), u(rng)), r, w);
        cells += w.size();
      }
      const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / np;
      std::cout << "NOTE cost " << to_string(model) << " @ " << cells_per_d << " cells/d: " << us << " us/particle, "
                << double(cells) / np << " cells/particle" << std::endl;
    }
  }
}
