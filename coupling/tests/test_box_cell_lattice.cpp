#include "meltdem/coupling/box_cell_lattice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>

using meltdem::coupling::BoxCellLattice;
using V = Eigen::Vector3d;

namespace {

// a graded nx x ny x nz lattice with shuffled cell labels and every `hole`-th slot left out
struct Boxes {
  std::vector<V> lo, hi;
  std::vector<double> planes[3];
};

Boxes graded_lattice(int nx, int ny, int nz, int hole, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.3, 1.7);
  Boxes b;
  const int n[3] = {nx, ny, nz};
  for (int a = 0; a < 3; ++a) {
    b.planes[a].push_back(-0.37 * a);
    for (int i = 0; i < n[a]; ++i) b.planes[a].push_back(b.planes[a].back() + 1e-5 * u(rng));
  }
  std::vector<std::array<int, 3>> slots;
  int count = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (hole == 0 || ++count % hole != 0) slots.push_back({i, j, k});
  std::shuffle(slots.begin(), slots.end(), rng);
  for (const auto &s : slots) {
    b.lo.emplace_back(b.planes[0][s[0]], b.planes[1][s[1]], b.planes[2][s[2]]);
    b.hi.emplace_back(b.planes[0][s[0] + 1], b.planes[1][s[1] + 1], b.planes[2][s[2] + 1]);
  }
  return b;
}

bool contains(const V &lo, const V &hi, const V &p)
{
  return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
}

bool overlaps(const V &lo, const V &hi, const V &slo, const V &shi)
{
  return (shi.array() >= lo.array()).all() && (slo.array() <= hi.array()).all();
}

// find_cell and cells_in_box against brute force at 4000 points over the lattice (a third of the
// coordinates exactly on a plane: faces, edges, corners, the ends) and boxes around them
void expect_brute_force(const BoxCellLattice &lattice, const Boxes &b, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, 100);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  for (int trial = 0; trial < 4000; ++trial) {
    V p;
    for (int a = 0; a < 3; ++a) {
      const auto &q = b.planes[a];
      p[a] = pick(rng) < 33 ? q[std::size_t(pick(rng)) % q.size()] : q.front() + u(rng) * (q.back() - q.front());
    }
    long expected = -1;
    for (std::size_t c = 0; c < b.lo.size(); ++c)
      if (contains(b.lo[c], b.hi[c], p) && expected < 0) expected = long(c);
    ASSERT_EQ(lattice.find_cell(p), expected) << "trial " << trial;

    const V r(2e-5 * (u(rng) + 0.1), 1e-5 * (u(rng) + 0.1), 3e-6 * (u(rng) + 0.1));
    const V slo = p - r, shi = p + r;
    std::vector<long> want, got = {-5};  // appends after what the list holds
    for (std::size_t c = 0; c < b.lo.size(); ++c)
      if (overlaps(b.lo[c], b.hi[c], slo, shi)) want.push_back(long(c));
    lattice.cells_in_box(slo, shi, got);
    want.insert(want.begin(), -5);
    ASSERT_EQ(got, want) << "trial " << trial;
  }
}

}  // namespace

TEST(BoxCellLattice, MatchesBruteForceOnGradedLatticeWithHoles)
{
  for (int hole : {0, 7}) {
    const Boxes b = graded_lattice(9, 6, 7, hole, 11u + unsigned(hole));
    BoxCellLattice lattice;
    ASSERT_TRUE(lattice.build(b.lo, b.hi));
    expect_brute_force(lattice, b, 5u);
  }
}

TEST(BoxCellLattice, RefusesWhatIsNoLattice)
{
  Boxes b = graded_lattice(4, 3, 2, 0, 3u);
  BoxCellLattice lattice;
  ASSERT_TRUE(lattice.build(b.lo, b.hi));
  // a box that overlaps another by half its width
  Boxes merged = b;
  const V half(0.5 * (b.hi[0][0] - b.lo[0][0]), 0, 0);
  merged.lo.push_back(b.lo[0] + half);
  merged.hi.push_back(b.hi[0] + half);
  EXPECT_FALSE(lattice.build(merged.lo, merged.hi));
  EXPECT_TRUE(lattice.empty());
  EXPECT_EQ(lattice.find_cell(b.lo[1]), -1);
  // two cells in one slot
  Boxes twice = b;
  twice.lo.push_back(b.lo[0]);
  twice.hi.push_back(b.hi[0]);
  EXPECT_FALSE(lattice.build(twice.lo, twice.hi));
  // too sparse: two cells at opposite corners of a 100^3 lattice
  std::vector<V> lo = {V(0, 0, 0), V(99, 99, 99)}, hi = {V(1, 1, 1), V(100, 100, 100)};
  EXPECT_FALSE(lattice.build(lo, hi));
  EXPECT_FALSE(lattice.build({}, {}));
}

TEST(BoxCellLattice, OutsideAndNonFinite)
{
  const Boxes b = graded_lattice(3, 3, 3, 0, 9u);
  BoxCellLattice lattice;
  ASSERT_TRUE(lattice.build(b.lo, b.hi));
  EXPECT_EQ(lattice.find_cell(V(1.0, 0.0, 0.0)), -1);
  EXPECT_EQ(lattice.find_cell(V(std::nan(""), 0.0, 0.0)), -1);
  std::vector<long> cells;
  lattice.cells_in_box(V(1.0, 1.0, 1.0), V(2.0, 2.0, 2.0), cells);
  EXPECT_TRUE(cells.empty());
  lattice.cells_in_box(V(-1, -1, -1), V(1, 1, 1), cells);
  EXPECT_EQ(cells.size(), 27u);
}

TEST(BoxCellLattice, MatchesBruteForceOnRefinedMesh)
{
  // a 4 x 3 x 3 graded block whose cells are split into 8 (hexRef8's midpoints) where a random
  // draw says so, one in five of those split again: cells of three sizes side by side, the
  // coarse ones spanning 2 or 4 slots per axis
  const Boxes base = graded_lattice(4, 3, 3, 0, 21u);
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> pick(0, 99);
  Boxes b;
  auto add = [&](const V &lo, const V &hi) {
    b.lo.push_back(lo), b.hi.push_back(hi);
    for (int a = 0; a < 3; ++a) b.planes[a].push_back(lo[a]), b.planes[a].push_back(hi[a]);
  };
  std::function<void(const V &, const V &, int)> split = [&](const V &lo, const V &hi, int level) {
    if (level == 2 || pick(rng) >= (level == 0 ? 50 : 20)) return add(lo, hi);
    const V mid = 0.5 * (lo + hi);
    for (int o = 0; o < 8; ++o) {
      V l, h;
      for (int a = 0; a < 3; ++a) {
        const bool up = (o >> a) & 1;
        l[a] = up ? mid[a] : lo[a], h[a] = up ? hi[a] : mid[a];
      }
      split(l, h, level + 1);
    }
  };
  for (std::size_t c = 0; c < base.lo.size(); ++c) split(base.lo[c], base.hi[c], 0);
  for (auto &p : b.planes) std::sort(p.begin(), p.end()), p.erase(std::unique(p.begin(), p.end()), p.end());
  BoxCellLattice lattice;
  ASSERT_TRUE(lattice.build(b.lo, b.hi, 64.0));
  expect_brute_force(lattice, b, 8u);
}
