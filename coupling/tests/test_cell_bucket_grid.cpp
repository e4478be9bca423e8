// Cell search on general meshes (cell_bucket_grid.h): a sheared and graded lattice of
// hexahedra (the cells are parallelepipeds, none of them a box) with a known cell for every
// point: the search finds it, points outside find none, and boxes find every cell they touch.
#include "meltdem/coupling/cell_bucket_grid.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace meltdem::coupling;

namespace {
// a lattice of nx x ny x nz cells, graded in x, sheared: x' = x + 0.6 y, z' = z + 0.3 x
struct ShearedMesh {
  int nx = 6, ny = 5, nz = 4;
  std::vector<double> xs, ys, zs;
  ShearedMesh()
  {
    for (int i = 0; i <= nx; ++i) xs.push_back(std::pow(double(i) / nx, 1.3));
    for (int j = 0; j <= ny; ++j) ys.push_back(0.8 * j / ny);
    for (int k = 0; k <= nz; ++k) zs.push_back(0.5 * k / nz);
  }
  static Eigen::Vector3d map(const Eigen::Vector3d &u) { return {u[0] + 0.6 * u[1], u[1], u[2] + 0.3 * u[0]}; }
  static Eigen::Vector3d unmap(const Eigen::Vector3d &p)
  {
    const double x = p[0] - 0.6 * p[1];
    return {x, p[1], p[2] - 0.3 * x};
  }
  long cell(int i, int j, int k) const { return (long(k) * ny + j) * nx + i; }
  // the cell of point p in the unsheared lattice (-1 outside)
  long expected(const Eigen::Vector3d &p) const
  {
    const Eigen::Vector3d u = unmap(p);
    const auto find = [](const std::vector<double> &v, double x) {
      for (std::size_t a = 0; a + 1 < v.size(); ++a)
        if (x >= v[a] && x < v[a + 1]) return int(a);
      return -1;
    };
    const int i = find(xs, u[0]), j = find(ys, u[1]), k = find(zs, u[2]);
    return i < 0 || j < 0 || k < 0 ? -1 : cell(i, j, k);
  }
  // cell (i, j, k)'s bounding box
  void box(int i, int j, int k, Eigen::Vector3d &lo, Eigen::Vector3d &hi) const
  {
    const auto corner = [&](int a, int b, int c) { return map({xs[a], ys[b], zs[c]}); };
    lo = hi = corner(i, j, k);
    for (int d = 0; d < 8; ++d) {
      const Eigen::Vector3d q = corner(i + (d & 1), j + (d >> 1 & 1), k + (d >> 2 & 1));
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
  // every cell's box, its 6 faces (owner: the lower cell; boundary faces owned by their cell)
  void build(CellBucketGrid &g) const
  {
    const long n = long(nx) * ny * nz;
    std::vector<Eigen::Vector3d> lo(n), hi(n), fc, fa;
    std::vector<std::vector<long>> faces(n);
    const auto corner = [&](int i, int j, int k) { return map({xs[i], ys[j], zs[k]}); };
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const long c = cell(i, j, k);
          box(i, j, k, lo[c], hi[c]);
        }
    // faces normal to each lattice axis a at plane index m, between cells m-1 and m along a
    for (int a = 0; a < 3; ++a) {
      const int na[3] = {nx, ny, nz};
      const int b = (a + 1) % 3, e = (a + 2) % 3;
      for (int m = 0; m <= na[a]; ++m)
        for (int jb = 0; jb < na[b]; ++jb)
          for (int je = 0; je < na[e]; ++je) {
            int idx[3];
            idx[a] = m, idx[b] = jb, idx[e] = je;
            const auto c4 = [&](int db, int de) {
              int q[3] = {idx[0], idx[1], idx[2]};
              q[b] += db, q[e] += de;
              return corner(q[0], q[1], q[2]);
            };
            const Eigen::Vector3d p0 = c4(0, 0), p1 = c4(1, 0), p2 = c4(1, 1), p3 = c4(0, 1);
            const Eigen::Vector3d area = 0.5 * (p2 - p0).cross(p3 - p1);  // along +a
            const long f = long(fc.size());
            fc.push_back(0.25 * (p0 + p1 + p2 + p3));
            int lower[3] = {idx[0], idx[1], idx[2]};
            lower[a] -= 1;
            if (m > 0 && m < na[a]) {
              fa.push_back(area);  // owner: the lower cell
              faces[cell(lower[0], lower[1], lower[2])].push_back(f);
              faces[cell(idx[0], idx[1], idx[2])].push_back(-1 - f);
            } else if (m == 0) {
              fa.push_back(-area);  // out of the first cell
              faces[cell(idx[0], idx[1], idx[2])].push_back(f);
            } else {
              fa.push_back(area);
              faces[cell(lower[0], lower[1], lower[2])].push_back(f);
            }
          }
    }
    std::vector<long> offsets(1, 0), flat;
    for (const auto &fl : faces) {
      flat.insert(flat.end(), fl.begin(), fl.end());
      offsets.push_back(long(flat.size()));
    }
    g.build(lo, hi, fc, fa, offsets, flat);
  }
};
}  // namespace

TEST(CellBucketGrid, FindsTheCellOfEveryPointOnASkewedGradedMesh)
{
  ShearedMesh m;
  CellBucketGrid g;
  m.build(g);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  int inside = 0, wrong = 0;
  for (int n = 0; n < 20000; ++n) {
    const Eigen::Vector3d p = ShearedMesh::map({u(rng), 0.8 * u(rng), 0.5 * u(rng)});
    const long want = m.expected(p), got = g.find_cell(p);
    inside += want >= 0;
    wrong += got != want;
  }
  std::printf("%d of 20000 points inside, %d found in another cell\n", inside, wrong);
  EXPECT_GT(inside, 10000);
  EXPECT_EQ(wrong, 0);
}

TEST(CellBucketGrid, BoxQueryHoldsEveryCellTouched)
{
  ShearedMesh m;
  CellBucketGrid g;
  m.build(g);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n = 0; n < 200; ++n) {
    const Eigen::Vector3d c = ShearedMesh::map({u(rng), 0.8 * u(rng), 0.5 * u(rng)});
    const double r = 0.02 + 0.1 * u(rng);
    std::vector<long> cells;
    g.cells_in_box(c - Eigen::Vector3d::Constant(r), c + Eigen::Vector3d::Constant(r), cells);
    ASSERT_TRUE(std::is_sorted(cells.begin(), cells.end()));
    ASSERT_TRUE(std::adjacent_find(cells.begin(), cells.end()) == cells.end());
    // every point of the box inside the mesh lies in a listed cell
    for (int s = 0; s < 50; ++s) {
      const Eigen::Vector3d p = c + r * Eigen::Vector3d(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1);
      const long want = m.expected(p);
      if (want >= 0) EXPECT_TRUE(std::binary_search(cells.begin(), cells.end(), want));
    }
  }
}

// the sheared cells' boxes span several buckets each: every cell whose box overlaps the query
// box is listed exactly once, and no other
TEST(CellBucketGrid, BoxQueryListsEachOverlappingCellOnce)
{
  ShearedMesh m;
  CellBucketGrid g;
  m.build(g);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  int differ = 0;
  std::size_t listed = 0;
  for (int n = 0; n < 300; ++n) {
    const Eigen::Vector3d c = ShearedMesh::map({u(rng), 0.8 * u(rng), 0.5 * u(rng)});
    const Eigen::Vector3d r(0.3 * u(rng) + 0.03, 0.2 * u(rng) + 0.03, 0.1 * u(rng) + 0.03);
    std::vector<long> cells, want;
    g.cells_in_box(c - r, c + r, cells);
    for (int k = 0; k < m.nz; ++k)
      for (int j = 0; j < m.ny; ++j)
        for (int i = 0; i < m.nx; ++i) {
          Eigen::Vector3d lo, hi;
          m.box(i, j, k, lo, hi);
          if ((lo.array() <= (c + r).array()).all() && (hi.array() >= (c - r).array()).all())
            want.push_back(m.cell(i, j, k));
        }
    std::sort(want.begin(), want.end());
    differ += cells == want ? 0 : 1;
    listed += cells.size();
  }
  std::printf("300 box queries, %zu cells listed, %d differ from the brute-force list\n", listed, differ);
  EXPECT_EQ(differ, 0);
  EXPECT_GT(listed, 3000u);
}

TEST(CellBucketGrid, ConvexCellsHaveNoDefect)
{
  ShearedMesh m;
  CellBucketGrid g;
  m.build(g);
  // the corners of cell (2, 3, 1) lie on or behind its own planes
  std::vector<Eigen::Vector3d> corners;
  for (int d = 0; d < 8; ++d)
    corners.push_back(ShearedMesh::map({m.xs[2 + (d & 1)], m.ys[3 + (d >> 1 & 1)], m.zs[1 + (d >> 2 & 1)]}));
  EXPECT_LT(g.convexity_defect(m.cell(2, 3, 1), corners), 1e-12);
  // a point well outside one of its faces is a defect of that size
  corners.push_back(ShearedMesh::map({m.xs[2] - 0.05, m.ys[3], m.zs[1]}));
  EXPECT_GT(g.convexity_defect(m.cell(2, 3, 1), corners), 1e-3);
}
