// Particle -> cell distribution models (Codina2019 §3.2.3, eq. 3.7) and the sphere-box overlap.
#include "meltdem/coupling/particle_distribution.h"

#include "meltdem/coupling/box_cell_lattice.h"
#include "meltdem/coupling/exact_sum.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

namespace {

void check_particle(const Eigen::Vector3d &c, double r)
{
  if (!(r > 0.0) || !std::isfinite(r) || !c.allFinite())
    throw std::invalid_argument("particle distribution: radius must be finite and > 0 and the centre finite");
}

}  // namespace

// ---------------------------------------------------------------------------------------
void normalise_weights(std::vector<CellWeight> &weights)
{
  if (weights.empty()) return;
  ExactSum total;
  for (const auto &cw : weights) total.add(cw.weight);
  const double sum = total.value();
  if (!(sum > 0.0) || !std::isfinite(sum))
    throw std::logic_error("particle distribution: raw weights must be positive with a finite sum");
  std::size_t largest = 0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    weights[i].weight /= sum;
    if (weights[i].weight > weights[largest].weight) largest = i;
  }
  ExactSum residual;
  residual.add(1.0);
  for (const auto &cw : weights) residual.add(-cw.weight);
  weights[largest].weight += residual.value();
}

// ---------------------------------------------------------------------------------------
DistributionModel parse_distribution_model(const std::string &name)
{
  if (name == "centre") return DistributionModel::Centre;
  if (name == "neighbours") return DistributionModel::Neighbours;
  if (name == "overlap") return DistributionModel::Overlap;
  throw std::invalid_argument("unknown particle distribution model '" + name +
                              "' (valid: centre, neighbours, overlap)");
}

const char *to_string(DistributionModel model)
{
  switch (model) {
    case DistributionModel::Centre:
      return "centre";
    case DistributionModel::Neighbours:
      return "neighbours";
    case DistributionModel::Overlap:
      return "overlap";
  }
  return "?";
}

namespace {

// the overlap volumes in ascending cell order, a cell given as several boxes once with their sum
void merge_cells(std::vector<CellWeight> &out, std::size_t start)
{
  const auto first = out.begin() + std::ptrdiff_t(start);
  const auto not_ascending = [](const CellWeight &a, const CellWeight &b) { return a.cell >= b.cell; };
  if (std::adjacent_find(first, out.end(), not_ascending) == out.end()) return;
  std::sort(first, out.end(), [](const CellWeight &a, const CellWeight &b) { return a.cell < b.cell; });
  auto kept = first;
  for (auto it = first + 1; it != out.end(); ++it) {
    if (it->cell == kept->cell)
      kept->weight += it->weight;
    else
      *++kept = *it;
  }
  out.erase(kept + 1, out.end());
}

// |sphere ∩ box| for boxes the sphere reaches, appended with their cells
void append_box_overlaps(const Eigen::Vector3d &c, double r, const std::vector<long> &cells,
                         const std::vector<Eigen::Vector3d> &lo, const std::vector<Eigen::Vector3d> &hi,
                         std::vector<CellWeight> &out)
{
  thread_local SphereBoxOverlaps overlaps;
  overlaps.reset(c, r, lo, hi);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const double v = overlaps.volume(i);
    if (v > 0.0) out.push_back({cells[i], v});
  }
}

// On a lattice: where at most one plane cuts the sphere along each axis (a grain no larger than
// its cells, away from the lattice's edges), every slot it reaches holds whole pieces of the
// eight those planes make, read straight from the planes; otherwise the slots' boxes take the
// general path
void append_lattice_overlaps(const BoxCellLattice &lattice, const Eigen::Vector3d &c, double r,
                             std::vector<CellWeight> &out)
{
  int first[3], last[3];
  if (!lattice.slot_range(c.array() - r, c.array() + r, first, last)) return;
  bool octants = true;  // at most one plane inside the sphere's extent per axis, none of them the lattice's edge
  for (int a = 0; a < 3; ++a)
    octants = octants && last[a] - first[a] <= 1 && lattice.plane(a, first[a]) <= c[a] - r &&
              lattice.plane(a, last[a] + 1) >= c[a] + r;
  if (!octants) {
    thread_local std::vector<long> cells;
    thread_local std::vector<Eigen::Vector3d> lo, hi;
    cells.clear(), lo.clear(), hi.clear();
    lattice.slots_in_sphere(c, r, cells, lo, hi);
    append_box_overlaps(c, r, cells, lo, hi, out);
    return;
  }
  // per axis the side of the cut each slot lies on (1 for the whole axis), -1 for a slot the
  // sphere only touches
  double cut[3];
  int side[3][2];
  for (int a = 0; a < 3; ++a) {
    cut[a] = -r;
    side[a][0] = side[a][1] = 1;
    if (last[a] == first[a]) continue;
    const double d = lattice.plane(a, first[a] + 1) - c[a];
    if (d <= -r)
      side[a][0] = -1;
    else if (d >= r)
      side[a][1] = -1;
    else
      cut[a] = d, side[a][0] = 0;
  }
  double piece[8];
  sphere_octant_pieces(r, cut, piece);
  for (int k = first[2]; k <= last[2]; ++k) {
    const int sz = side[2][k - first[2]];
    if (sz < 0) continue;
    for (int j = first[1]; j <= last[1]; ++j) {
      const int sy = side[1][j - first[1]];
      if (sy < 0) continue;
      for (int i = first[0]; i <= last[0]; ++i) {
        const int sx = side[0][i - first[0]];
        const long cell = lattice.slot(i, j, k);
        if (sx < 0 || cell < 0) continue;
        const double v = piece[sx | sy << 1 | sz << 2];
        if (v > 0.0) out.push_back({cell, v});
      }
    }
  }
}

}  // namespace

void append_overlap_volumes(const DistributionMesh &mesh, const Eigen::Vector3d &c, double r,
                            std::vector<CellWeight> &out)
{
  const std::size_t start = out.size();
  if (const BoxCellLattice *lattice = mesh.lattice()) {
    append_lattice_overlaps(*lattice, c, r, out);
    merge_cells(out, start);
    return;
  }
  thread_local std::vector<long> cells;
  thread_local std::vector<Eigen::Vector3d> lo, hi;
  cells.clear();
  mesh.cells_in_sphere(c, r, cells);
  lo.resize(cells.size());
  hi.resize(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) mesh.cell_bounds(cells[i], lo[i], hi[i]);
  append_box_overlaps(c, r, cells, lo, hi, out);
}

bool boxes_share_face(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, const Eigen::Vector3d &hlo,
                      const Eigen::Vector3d &hhi, int &axis, double &plane, double &outward)
{
  const double tol = 1e-9 * (hhi - hlo).maxCoeff();
  int touching = -1, overlapping = 0;
  for (int a = 0; a < 3; ++a) {
    const double ov = std::min(hi[a], hhi[a]) - std::max(lo[a], hlo[a]);
    if (ov > tol) {
      ++overlapping;
    } else if (std::abs(ov) <= tol) {
      if (touching >= 0) return false;  // an edge or a corner, not a face
      touching = a;
    } else {
      return false;
    }
  }
  if (overlapping != 2 || touching < 0) return false;
  axis = touching;
  if (std::abs(lo[axis] - hhi[axis]) <= tol) {
    plane = hhi[axis];
    outward = 1.0;
  } else {
    plane = hlo[axis];
    outward = -1.0;
  }
  return true;
}

void append_raw_weights(const DistributionMesh &mesh, DistributionModel model, const Eigen::Vector3d &c, double r,
                        long home, const Eigen::Vector3d &home_lo, const Eigen::Vector3d &home_hi,
                        std::vector<CellWeight> &out)
{
  switch (model) {
    case DistributionModel::Centre:
      if (home >= 0) out.push_back({home, 1.0});
      return;

    case DistributionModel::Neighbours: {
      // eq. 3.7 volume weights over the centre cell and the face neighbours the particle's
      // farthest point along the face normal, c + r n, lies beyond
      if (home >= 0) out.push_back({home, mesh.cell_volume(home)});
      thread_local std::vector<long> candidates;
      candidates.clear();
      mesh.cells_in_sphere(c, r, candidates);
      Eigen::Vector3d lo, hi;
      for (long cell : candidates) {
        if (cell == home) continue;
        mesh.cell_bounds(cell, lo, hi);
        int axis;
        double plane, outward;
        if (boxes_share_face(lo, hi, home_lo, home_hi, axis, plane, outward) && (c[axis] - plane) * outward + r > 0.0)
          out.push_back({cell, mesh.cell_volume(cell)});
      }
      return;
    }

    case DistributionModel::Overlap:
      append_overlap_volumes(mesh, c, r, out);
      return;
  }
}

bool distribute_particle(const DistributionMesh &mesh, DistributionModel model, const Eigen::Vector3d &c, double r,
                         std::vector<CellWeight> &out)
{
  check_particle(c, r);
  out.clear();
  const long home = mesh.find_cell(c);
  if (home < 0) return false;
  Eigen::Vector3d home_lo, home_hi;
  mesh.cell_bounds(home, home_lo, home_hi);
  append_raw_weights(mesh, model, c, r, home, home_lo, home_hi, out);
  if (out.empty()) return false;
  normalise_weights(out);
  return true;
}

// ---------------------------------------------------------------------------------------
CartesianGridMesh::CartesianGridMesh(std::vector<double> x, std::vector<double> y, std::vector<double> z) :
    nodes_{std::move(x), std::move(y), std::move(z)}
{
  for (int d = 0; d < 3; ++d) {
    if (nodes_[d].size() < 2) throw std::invalid_argument("CartesianGridMesh: every axis needs >= 2 nodes");
    for (std::size_t i = 1; i < nodes_[d].size(); ++i)
      if (!(nodes_[d][i] > nodes_[d][i - 1]))
        throw std::invalid_argument("CartesianGridMesh: node coordinates must be strictly increasing");
    n_[d] = int(nodes_[d].size()) - 1;
  }
  const std::size_t count = std::size_t(n_cells());
  std::vector<Eigen::Vector3d> lo(count), hi(count);
  for (long cell = 0; cell < n_cells(); ++cell) cell_bounds(cell, lo[std::size_t(cell)], hi[std::size_t(cell)]);
  lattice_.build(lo, hi);
}

CartesianGridMesh CartesianGridMesh::uniform(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, int nx, int ny,
                                             int nz)
{
  const int n[3] = {nx, ny, nz};
  std::vector<double> v[3];
  for (int d = 0; d < 3; ++d) {
    if (n[d] < 1 || !(hi[d] > lo[d])) throw std::invalid_argument("CartesianGridMesh::uniform: need n >= 1, hi > lo");
    v[d].resize(n[d] + 1);
    for (int i = 0; i <= n[d]; ++i) v[d][i] = lo[d] + (hi[d] - lo[d]) * i / n[d];
    v[d][n[d]] = hi[d];
  }
  return CartesianGridMesh(std::move(v[0]), std::move(v[1]), std::move(v[2]));
}

void CartesianGridMesh::ijk(long cell, int &i, int &j, int &k) const
{
  i = int(cell % n_[0]);
  j = int((cell / n_[0]) % n_[1]);
  k = int(cell / (long(n_[0]) * n_[1]));
}

long CartesianGridMesh::find_cell(const Eigen::Vector3d &p) const
{
  int idx[3];
  for (int d = 0; d < 3; ++d) {
    const auto &v = nodes_[d];
    if (!(p[d] >= v.front()) || !(p[d] <= v.back())) return -1;
    // half-open cells [x_i, x_i+1); the upper domain face belongs to the last cell
    idx[d] = std::min(int(std::upper_bound(v.begin(), v.end(), p[d]) - v.begin()) - 1, n_[d] - 1);
  }
  return index(idx[0], idx[1], idx[2]);
}

void CartesianGridMesh::cell_bounds(long cell, Eigen::Vector3d &lo, Eigen::Vector3d &hi) const
{
  int i, j, k;
  ijk(cell, i, j, k);
  lo = {nodes_[0][i], nodes_[1][j], nodes_[2][k]};
  hi = {nodes_[0][i + 1], nodes_[1][j + 1], nodes_[2][k + 1]};
}

Eigen::Vector3d CartesianGridMesh::cell_centre(long cell) const
{
  Eigen::Vector3d lo, hi;
  cell_bounds(cell, lo, hi);
  return 0.5 * (lo + hi);
}

double CartesianGridMesh::cell_volume(long cell) const
{
  Eigen::Vector3d lo, hi;
  cell_bounds(cell, lo, hi);
  return (hi - lo).prod();
}

bool CartesianGridMesh::bounds(Eigen::Vector3d &lo, Eigen::Vector3d &hi) const
{
  for (int a = 0; a < 3; ++a) lo[a] = nodes_[a].front(), hi[a] = nodes_[a].back();
  return true;
}

void CartesianGridMesh::cells_in_sphere(const Eigen::Vector3d &c, double r, std::vector<long> &cells) const
{
  int lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    const auto &v = nodes_[d];
    lo[d] = std::max(0, int(std::upper_bound(v.begin(), v.end(), c[d] - r) - v.begin()) - 1);
    hi[d] = std::min(n_[d] - 1, int(std::lower_bound(v.begin(), v.end(), c[d] + r) - v.begin()) - 1);
    if (hi[d] < lo[d]) return;
  }
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const Eigen::Vector3d blo(nodes_[0][i], nodes_[1][j], nodes_[2][k]);
        const Eigen::Vector3d bhi(nodes_[0][i + 1], nodes_[1][j + 1], nodes_[2][k + 1]);
        if ((c.cwiseMax(blo).cwiseMin(bhi) - c).squaredNorm() < r * r) cells.push_back(index(i, j, k));
      }
}

}  // namespace meltdem::coupling
