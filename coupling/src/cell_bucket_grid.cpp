#include "meltdem/coupling/cell_bucket_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

void CellBucketGrid::build(const std::vector<Eigen::Vector3d> &lo, const std::vector<Eigen::Vector3d> &hi,
                           const std::vector<Eigen::Vector3d> &face_centre,
                           const std::vector<Eigen::Vector3d> &face_area, const std::vector<long> &cell_offsets,
                           const std::vector<long> &cell_faces)
{
  const std::size_t ncells = lo.size();
  if (hi.size() != ncells || cell_offsets.size() != ncells + 1 || face_centre.size() != face_area.size())
    throw std::invalid_argument("CellBucketGrid: inconsistent cell and face lists");
  offsets_.clear();
  cells_.clear();
  lo_ = lo;
  hi_ = hi;
  cell_offsets_ = cell_offsets;
  cell_faces_ = cell_faces;
  if (ncells == 0) return;
  Eigen::Vector3d blo = lo[0], bhi = hi[0], sum = Eigen::Vector3d::Zero();
  for (std::size_t c = 0; c < ncells; ++c) {
    blo = blo.cwiseMin(lo[c]);
    bhi = bhi.cwiseMax(hi[c]);
    sum += hi[c] - lo[c];
  }
  // a rounding tolerance: 1e-9 of the mean cell size
  tol_ = 1e-9 * sum.sum() / (3.0 * double(ncells));
  planes_.resize(face_centre.size());
  for (std::size_t f = 0; f < face_centre.size(); ++f) {
    const double a = face_area[f].norm();
    if (!(a > 0.0)) throw std::invalid_argument("CellBucketGrid: a face with zero area");
    const Eigen::Vector3d n = face_area[f] / a;
    planes_[f] << n, n.dot(face_centre[f]);
  }
  // buckets of about the mean cell size on each axis (at most ~2 per cell in all)
  const Eigen::Vector3d extent = (bhi - blo).cwiseMax(Eigen::Vector3d::Constant(1e-300));
  const Eigen::Vector3d mean = sum / double(ncells);
  double scale = 1.0;
  for (int it = 0; it < 64; ++it) {
    double total = 1.0;
    for (int a = 0; a < 3; ++a) total *= std::max(1.0, std::floor(extent[a] / (scale * mean[a])));
    if (total <= 2.0 * double(ncells)) break;
    scale *= 1.25;
  }
  for (int a = 0; a < 3; ++a) {
    n_[a] = int(std::max(1.0, std::floor(extent[a] / (scale * std::max(mean[a], 1e-300)))));
    per_length_[a] = n_[a] / extent[a];
  }
  origin_ = blo;
  const std::size_t nb = std::size_t(n_[0]) * n_[1] * n_[2];
  std::vector<long> count(nb + 1, 0);
  int first[3], last[3];
  first_bucket_.resize(ncells);
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t c = 0; c < ncells; ++c) {
      bucket_range(lo[c], hi[c], first, last);
      if (pass == 0) first_bucket_[c] = {first[0], first[1], first[2]};
      for (int k = first[2]; k <= last[2]; ++k)
        for (int j = first[1]; j <= last[1]; ++j)
          for (int i = first[0]; i <= last[0]; ++i) {
            const std::size_t b = (std::size_t(k) * n_[1] + j) * n_[0] + i;
            if (pass == 0)
              ++count[b + 1];
            else
              cells_[std::size_t(count[b]++)] = long(c);
          }
    }
    if (pass == 0) {
      for (std::size_t b = 0; b < nb; ++b) count[b + 1] += count[b];
      offsets_ = count;
      cells_.resize(std::size_t(count[nb]));
    }
  }
  // (cells went in ascending order, so every bucket's list is ascending)
}

void CellBucketGrid::bucket_range(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, int first[3], int last[3]) const
{
  for (int a = 0; a < 3; ++a) {
    first[a] = std::clamp(int(std::floor((lo[a] - origin_[a]) * per_length_[a])), 0, n_[a] - 1);
    last[a] = std::clamp(int(std::floor((hi[a] - origin_[a]) * per_length_[a])), 0, n_[a] - 1);
  }
}

bool CellBucketGrid::inside(long c, const Eigen::Vector3d &p) const
{
  for (long k = cell_offsets_[std::size_t(c)]; k < cell_offsets_[std::size_t(c) + 1]; ++k) {
    const long f = cell_faces_[std::size_t(k)];
    const Eigen::Vector4d &q = planes_[std::size_t(f >= 0 ? f : -1 - f)];
    const double out = q[0] * p[0] + q[1] * p[1] + q[2] * p[2] - q[3];
    if ((f >= 0 ? out : -out) > tol_) return false;
  }
  return true;
}

long CellBucketGrid::find_cell(const Eigen::Vector3d &p) const
{
  if (offsets_.empty()) return -1;
  std::size_t b = 0;
  for (int a = 2; a >= 0; --a) {
    const double x = (p[a] - origin_[a]) * per_length_[a];
    if (!(x >= -1e-9 * n_[a]) || !(x <= n_[a] * (1.0 + 1e-9))) return -1;  // outside every cell box
    b = b * std::size_t(n_[a]) + std::size_t(std::clamp(int(x), 0, n_[a] - 1));
  }
  for (long k = offsets_[b]; k < offsets_[b + 1]; ++k) {
    const long c = cells_[std::size_t(k)];
    const std::size_t ci = std::size_t(c);
    if (p[0] < lo_[ci][0] - tol_ || p[0] > hi_[ci][0] + tol_ || p[1] < lo_[ci][1] - tol_ || p[1] > hi_[ci][1] + tol_ ||
        p[2] < lo_[ci][2] - tol_ || p[2] > hi_[ci][2] + tol_)
      continue;
    if (inside(c, p)) return c;
  }
  return -1;
}

void CellBucketGrid::cells_in_box(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, std::vector<long> &cells) const
{
  if (offsets_.empty()) return;
  const std::size_t start = cells.size();
  int first[3], last[3];
  for (int a = 0; a < 3; ++a)
    if (hi[a] < origin_[a] || lo[a] > origin_[a] + n_[a] / per_length_[a]) return;
  bucket_range(lo, hi, first, last);
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i) {
        const std::size_t b = (std::size_t(k) * n_[1] + j) * n_[0] + i;
        for (long m = offsets_[b]; m < offsets_[b + 1]; ++m) {
          const std::size_t c = std::size_t(cells_[std::size_t(m)]);
          // a cell binned in several buckets of the range is taken in the lowest of them only
          const std::array<int, 3> &f = first_bucket_[c];
          if (std::max(f[0], first[0]) != i || std::max(f[1], first[1]) != j || std::max(f[2], first[2]) != k) continue;
          if (lo_[c][0] <= hi[0] && hi_[c][0] >= lo[0] && lo_[c][1] <= hi[1] && hi_[c][1] >= lo[1] &&
              lo_[c][2] <= hi[2] && hi_[c][2] >= lo[2])
            cells.push_back(long(c));
        }
      }
  std::sort(cells.begin() + std::ptrdiff_t(start), cells.end());
}

double CellBucketGrid::convexity_defect(long c, const std::vector<Eigen::Vector3d> &points) const
{
  double worst = 0.0;
  for (long k = cell_offsets_[std::size_t(c)]; k < cell_offsets_[std::size_t(c) + 1]; ++k) {
    const long f = cell_faces_[std::size_t(k)];
    const Eigen::Vector4d &q = planes_[std::size_t(f >= 0 ? f : -1 - f)];
    for (const Eigen::Vector3d &p : points) {
      const double out = q[0] * p[0] + q[1] * p[1] + q[2] * p[2] - q[3];
      worst = std::max(worst, f >= 0 ? out : -out);
    }
  }
  return worst;
}

}  // namespace meltdem::coupling
