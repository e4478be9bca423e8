// Particle -> cell distribution models (Codina2019 §3.2.3, eq. 3.7) and the sphere-box overlap.
#include "meltdem/coupling/particle_distribution.h"

#include "meltdem/coupling/exact_sum.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

namespace {

constexpr int kGaussPoints = 16;

// Gauss-Legendre nodes/weights on [0, 1] (Newton on P_n, computed once)
struct GaussLegendre {
  std::array<double, kGaussPoints> x, w;
  GaussLegendre()
  {
    const int n = kGaussPoints;
    for (int i = 0; i < n; ++i) {
      double t = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = t;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (t * p1 - p0) / (t * t - 1.0);
        const double dt = p1 / dp;
        t -= dt;
        if (std::abs(dt) < 1e-16) break;
      }
      x[i] = 0.5 * (1.0 - t);
      w[i] = 1.0 / ((1.0 - t * t) * dp * dp);  // = 2/((1-t^2) P'^2) scaled by 1/2 for [0,1]
    }
  }
};

const GaussLegendre &gauss()
{
  static const GaussLegendre g;
  return g;
}

template <class F> double gauss_rule(const F &f, double u0, double u1)
{
  const auto &g = gauss();
  double sum = 0.0;
  for (int q = 0; q < kGaussPoints; ++q) sum += g.w[q] * f(u0 + (u1 - u0) * g.x[q]);
  return sum * (u1 - u0);
}

template <class F> double adaptive_gauss(const F &f, double u0, double u1, double whole, double tol, int depth)
{
  const double um = 0.5 * (u0 + u1);
  const double left = gauss_rule(f, u0, um), right = gauss_rule(f, um, u1);
  // tol is not halved per level: it sits near round-off of the whole, and a halved one
  // would chase the rounding noise down to the depth limit
  if (std::abs(left + right - whole) <= tol || depth >= 12) return left + right;
  return adaptive_gauss(f, u0, um, left, tol, depth + 1) + adaptive_gauss(f, um, u1, right, tol, depth + 1);
}

// ∫_0^y sqrt(R^2 - t^2) dt for |y| <= R
double circle_primitive(double R, double y)
{
  // (R - y)(R + y) and atan2 instead of R^2 - y^2 and asin(y/R): both lose half the digits near |y| = R
  const double yy = std::clamp(y, -R, R);
  const double s = std::sqrt((R - yy) * (R + yy));
  return 0.5 * (yy * s + R * R * std::atan2(yy, s));
}

// area of disk(0, R) ∩ rectangle [y0, y1] x [z0, z1]
double disk_rectangle_area(double R, double y0, double y1, double z0, double z1)
{
  if (!(R > 0.0) || y0 >= R || z0 >= R || y1 <= -R || z1 <= -R) return 0.0;
  const double a = disk_quadrant_area(R, y1, z1) - disk_quadrant_area(R, y0, z1) - disk_quadrant_area(R, y1, z0) +
                   disk_quadrant_area(R, y0, z0);
  return std::max(0.0, a);
}

void check_particle(const Eigen::Vector3d &c, double r)
{
  if (!(r > 0.0) || !std::isfinite(r) || !c.allFinite())
    throw std::invalid_argument("particle distribution: radius must be finite and > 0 and the centre finite");
}

}  // namespace

// ---------------------------------------------------------------------------------------
double disk_quadrant_area(double R, double b, double c)
{
  if (!(R > 0.0) || b <= -R || c <= -R) return 0.0;
  b = std::min(b, R);
  c = std::min(c, R);
  const double yc = std::sqrt(std::max(0.0, (R - c) * (R + c)));  // where the chord z = c meets the circle
  if (c >= 0.0) {
    // z-extent at y: 2 s(y) for |y| >= yc, c + s(y) inside
    double area = 2.0 * (circle_primitive(R, std::min(b, -yc)) - circle_primitive(R, -R));
    if (b > -yc) {
      const double yb = std::min(b, yc);
      area += c * (yb + yc) + circle_primitive(R, yb) - circle_primitive(R, -yc);
    }
    if (b > yc) area += 2.0 * (circle_primitive(R, b) - circle_primitive(R, yc));
    return area;
  }
  // c < 0: only |y| < yc has z-extent c + s(y) > 0
  if (b <= -yc) return 0.0;
  const double yb = std::min(b, yc);
  return std::max(0.0, c * (yb + yc) + circle_primitive(R, yb) - circle_primitive(R, -yc));
}

double sphere_box_overlap(const Eigen::Vector3d &c, double r, const Eigen::Vector3d &lo, const Eigen::Vector3d &hi)
{
  if (!(r > 0.0)) return 0.0;
  // disjoint: closest point of the box at distance >= r
  const Eigen::Vector3d closest = c.cwiseMax(lo).cwiseMin(hi);
  if ((closest - c).squaredNorm() >= r * r) return 0.0;
  // box inside the sphere: farthest corner within r
  const Eigen::Vector3d far = (c - lo).cwiseAbs().cwiseMax((hi - c).cwiseAbs());
  if (far.squaredNorm() <= r * r) return (hi - lo).prod();
  // sphere inside the box
  if ((c - lo).minCoeff() >= r && (hi - c).minCoeff() >= r) return 4.0 / 3.0 * M_PI * r * r * r;

  const double xa = std::max(lo.x(), c.x() - r), xb = std::min(hi.x(), c.x() + r);
  if (!(xb > xa)) return 0.0;
  const double y0 = lo.y() - c.y(), y1 = hi.y() - c.y(), z0 = lo.z() - c.z(), z1 = hi.z() - c.z();

  // kinks of A(x): slice radius rho(x) equal to an edge distance or a corner distance
  double cuts[2 + 2 * 8];
  int nc = 0;
  cuts[nc++] = xa;
  cuts[nc++] = xb;
  const double d2[8] = {y0 * y0,           y1 * y1,           z0 * z0,           z1 * z1,
                        y0 * y0 + z0 * z0, y0 * y0 + z1 * z1, y1 * y1 + z0 * z0, y1 * y1 + z1 * z1};
  for (double d : d2) {
    if (d >= r * r) continue;
    const double h = std::sqrt(r * r - d);  // kink position: rho(x) = sqrt(d)
    for (double x : {c.x() - h, c.x() + h})
      if (x > xa && x < xb) cuts[nc++] = x;
  }
  std::sort(cuts, cuts + nc);

  // A(u) is analytic in u between kinks, but for a slice circle that just clears an edge
  // (small edge distance) its complex singularities sit close to the real axis near the
  // ends: bisect adaptively until two halves agree with the whole to 1e-14 r^3
  double volume = 0.0;
  const double tol = 1e-14 * r * r * r;
  for (int s = 0; s + 1 < nc; ++s) {
    const double a = cuts[s], b = cuts[s + 1];
    if (!(b > a)) continue;
    auto slice = [&](double u) {
      const double x = a + (b - a) * 0.5 * (1.0 - std::cos(M_PI * u));
      const double jac = (b - a) * 0.5 * M_PI * std::sin(M_PI * u);
      const double dx = x - c.x();
      const double rho = std::sqrt(std::max(0.0, (r - dx) * (r + dx)));
      return jac * disk_rectangle_area(rho, y0, y1, z0, z1);
    };
    volume += adaptive_gauss(slice, 0.0, 1.0, gauss_rule(slice, 0.0, 1.0), tol, 0);
  }
  return volume;
}

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

void append_overlap_volumes(const DistributionMesh &mesh, const Eigen::Vector3d &c, double r,
                            std::vector<CellWeight> &out)
{
  thread_local std::vector<long> cells;
  cells.clear();
  mesh.cells_in_sphere(c, r, cells);
  Eigen::Vector3d lo, hi;
  for (long cell : cells) {
    mesh.cell_bounds(cell, lo, hi);
    const double v = sphere_box_overlap(c, r, lo, hi);
    if (v > 0.0) out.push_back({cell, v});
  }
}

bool distribute_particle(const DistributionMesh &mesh, DistributionModel model, const Eigen::Vector3d &c, double r,
                         std::vector<CellWeight> &out)
{
  check_particle(c, r);
  out.clear();
  const long home = mesh.find_cell(c);
  if (home < 0) return false;

  switch (model) {
    case DistributionModel::Centre:
      out.push_back({home, 1.0});
      return true;

    case DistributionModel::Neighbours: {
      // Codina2019 fig. 3.9: the neighbour across face f is occupied when the particle's
      // farthest point along the outward normal n, c + r n, lies beyond the face:
      // (c + r n - x_f) . n > 0. Only direct neighbours of the centre cell (no recursion).
      thread_local std::vector<DistributionMesh::Face> faces;
      faces.clear();
      mesh.face_neighbours(home, faces);
      out.push_back({home, mesh.cell_volume(home)});
      for (const auto &f : faces)
        if ((c - f.centre).dot(f.normal) + r > 0.0) out.push_back({f.neighbour, mesh.cell_volume(f.neighbour)});
      normalise_weights(out);  // eq. 3.7
      return true;
    }

    case DistributionModel::Overlap: {
      append_overlap_volumes(mesh, c, r, out);
      if (out.empty()) return false;
      normalise_weights(out);
      return true;
    }
  }
  return false;
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

void CartesianGridMesh::face_neighbours(long cell, std::vector<Face> &faces) const
{
  int ii[3];
  ijk(cell, ii[0], ii[1], ii[2]);
  Eigen::Vector3d lo, hi;
  cell_bounds(cell, lo, hi);
  const Eigen::Vector3d mid = 0.5 * (lo + hi);
  for (int d = 0; d < 3; ++d)
    for (int side : {-1, 1}) {
      int nb[3] = {ii[0], ii[1], ii[2]};
      nb[d] += side;
      if (nb[d] < 0 || nb[d] >= n_[d]) continue;  // boundary face
      Face f;
      f.neighbour = index(nb[0], nb[1], nb[2]);
      f.centre = mid;
      f.centre[d] = side < 0 ? lo[d] : hi[d];
      f.normal = Eigen::Vector3d::Zero();
      f.normal[d] = side;
      faces.push_back(f);
    }
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
