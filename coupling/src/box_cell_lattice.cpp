#include "meltdem/coupling/box_cell_lattice.h"

#include <algorithm>

namespace meltdem::coupling {

bool BoxCellLattice::build(const std::vector<Eigen::Vector3d> &lo, const std::vector<Eigen::Vector3d> &hi,
                           double max_slots_per_cell)
{
  slots_.clear();
  const std::size_t ncells = lo.size();
  if (ncells == 0 || hi.size() != ncells) return false;
  // the planes are the cells' own coordinates: cells that share a face share them exactly
  for (int a = 0; a < 3; ++a) {
    std::vector<double> &p = planes_[a];
    p.clear();
    p.reserve(2 * ncells);
    for (std::size_t c = 0; c < ncells; ++c) p.push_back(lo[c][a]), p.push_back(hi[c][a]);
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    n_[a] = int(p.size()) - 1;
    if (n_[a] < 1) return false;
    per_length_[a] = n_[a] / (p.back() - p.front());
  }
  const double total = double(n_[0]) * n_[1] * n_[2];
  if (total > max_slots_per_cell * double(ncells)) return false;
  std::vector<long> slots(std::size_t(total), -1);
  spanning_ = false;
  for (std::size_t c = 0; c < ncells; ++c) {
    // the slots [first, end) the cell covers on each axis: one on a uniform or graded mesh,
    // several for a coarse cell beside refined ones
    int first[3], end[3];
    for (int a = 0; a < 3; ++a) {
      const std::vector<double> &p = planes_[a];
      first[a] = int(std::lower_bound(p.begin(), p.end(), lo[c][a]) - p.begin());
      end[a] = int(std::lower_bound(p.begin(), p.end(), hi[c][a]) - p.begin());
      if (end[a] <= first[a]) return false;  // an empty or inverted box
      spanning_ = spanning_ || end[a] - first[a] > 1;
    }
    for (int k = first[2]; k < end[2]; ++k)
      for (int j = first[1]; j < end[1]; ++j)
        for (int i = first[0]; i < end[0]; ++i) {
          long &s = slots[(std::size_t(k) * n_[1] + std::size_t(j)) * n_[0] + i];
          if (s >= 0) return false;  // two cells in one slot: boxes that overlap
          s = long(c);
        }
  }
  slots_.swap(slots);
  return true;
}

int BoxCellLattice::guess(int axis, double x) const
{
  const double g = (x - planes_[axis].front()) * per_length_[axis];
  return g > 0.0 ? int(std::min(g, double(n_[axis]))) : 0;  // (NaN to 0)
}

int BoxCellLattice::bound(int axis, double x, bool upper) const
{
  const std::vector<double> &q = planes_[axis];
  const int m = int(q.size());
  // the planes before the index: q <= x for upper_bound, q < x for lower_bound
  const auto before = [&](double plane) { return upper ? plane <= x : plane < x; };
  int i = guess(axis, x);
  for (int step = 0; step < 4; ++step) {
    if (i < m && before(q[std::size_t(i)]))
      ++i;
    else if (i > 0 && !before(q[std::size_t(i) - 1]))
      --i;
    else
      return i;
  }
  return int((upper ? std::upper_bound(q.begin(), q.end(), x) : std::lower_bound(q.begin(), q.end(), x)) - q.begin());
}

long BoxCellLattice::find_cell(const Eigen::Vector3d &p) const
{
  if (slots_.empty()) return -1;
  // per axis the one or two intervals whose closed range holds the coordinate (two on a plane)
  int first[3], last[3];
  for (int a = 0; a < 3; ++a) {
    const std::vector<double> &q = planes_[a];
    if (!(p[a] >= q.front() && p[a] <= q.back())) return -1;
    const int up = bound(a, p[a], true);  // q[up-1] <= p < q[up]
    last[a] = std::min(up - 1, n_[a] - 1);
    first[a] = q[std::size_t(up) - 1] == p[a] && up >= 2 ? up - 2 : last[a];
  }
  long best = -1;
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i) {
        const long c = slot(i, j, k);
        if (c >= 0 && (best < 0 || c < best)) best = c;
      }
  return best;
}

void BoxCellLattice::cells_in_box(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, std::vector<long> &cells) const
{
  int first[3], last[3];
  if (!slot_range(lo, hi, first, last)) return;
  const std::size_t start = cells.size();
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i) {
        const long c = slot(i, j, k);
        if (c >= 0) cells.push_back(c);
      }
  // (a blockMesh numbers its cells in this order already; a cell spanning several slots
  // came once per slot)
  if (!std::is_sorted(cells.begin() + std::ptrdiff_t(start), cells.end()))
    std::sort(cells.begin() + std::ptrdiff_t(start), cells.end());
  if (spanning_) cells.erase(std::unique(cells.begin() + std::ptrdiff_t(start), cells.end()), cells.end());
}

bool BoxCellLattice::slot_range(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, int first[3], int last[3]) const
{
  if (slots_.empty()) return false;
  for (int a = 0; a < 3; ++a) {
    const std::vector<double> &q = planes_[a];
    if (!(lo[a] <= q.back() && hi[a] >= q.front())) return false;
    // intervals [q[i], q[i+1]] with q[i+1] >= lo and q[i] <= hi
    first[a] = std::max(0, bound(a, lo[a], false) - 1);
    last[a] = std::min(n_[a] - 1, bound(a, hi[a], true) - 1);
    if (first[a] > last[a]) return false;
  }
  return true;
}

void BoxCellLattice::slots_in_sphere(const Eigen::Vector3d &c, double r, std::vector<long> &cells,
                                     std::vector<Eigen::Vector3d> &lo, std::vector<Eigen::Vector3d> &hi) const
{
  int first[3], last[3];
  if (!slot_range(c.array() - r, c.array() + r, first, last)) return;
  thread_local std::vector<double> out2[3];  // squared distance from the centre to each interval, per axis
  for (int a = 0; a < 3; ++a) {
    const std::vector<double> &q = planes_[a];
    out2[a].resize(std::size_t(last[a] - first[a] + 1));
    for (int i = first[a]; i <= last[a]; ++i) {
      const double d = std::max({q[std::size_t(i)] - c[a], c[a] - q[std::size_t(i) + 1], 0.0});
      out2[a][std::size_t(i - first[a])] = d * d;
    }
  }
  const double r2 = r * r;
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j) {
      const double dyz = out2[1][std::size_t(j - first[1])] + out2[2][std::size_t(k - first[2])];
      if (dyz >= r2) continue;
      for (int i = first[0]; i <= last[0]; ++i) {
        const long cell = slot(i, j, k);
        if (cell < 0 || dyz + out2[0][std::size_t(i - first[0])] >= r2) continue;
        cells.push_back(cell);
        lo.emplace_back(planes_[0][std::size_t(i)], planes_[1][std::size_t(j)], planes_[2][std::size_t(k)]);
        hi.emplace_back(planes_[0][std::size_t(i) + 1], planes_[1][std::size_t(j) + 1], planes_[2][std::size_t(k) + 1]);
      }
    }
}

}  // namespace meltdem::coupling
