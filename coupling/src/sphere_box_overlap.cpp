// Sphere-box overlap volume: closed form, the quadrature it is tested against, and the
// per-particle lattice of shared planes.
#include "meltdem/coupling/sphere_box_overlap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace meltdem::coupling {

namespace {

constexpr double kFree = -1.0;  // folded offset of an axis without a constraint

// atan(t) for 0 <= t <= 1 (Cephes atan: range reduction at tan(pi/8) and a 4/5 rational
// approximation, peak relative error 1.8e-16): several times faster than glibc's
// correctly rounded atan2, which dominated the overlap's cost
double atan_unit(double t)
{
  static constexpr double P[] = {-8.750608600031904122785e-1, -1.615753718733365076637e1, -7.500855792314704667340e1,
                                 -1.228866684490136173410e2, -6.485021904942025371773e1};
  static constexpr double Q[] = {2.485846490142306297962e1, 1.650270098316988542046e2, 4.328810604912902668951e2,
                                 4.853903996359136964868e2, 1.945506571482613964425e2};
  static constexpr double kMoreBits = 6.123233995736765886130e-17;  // pi/4 - its double
  double y = 0.0, corr = 0.0;
  if (t > 0.66) {
    y = M_PI / 4.0;
    corr = 0.5 * kMoreBits;
    t = (t - 1.0) / (t + 1.0);
  }
  const double z = t * t;
  const double p = (((P[0] * z + P[1]) * z + P[2]) * z + P[3]) * z + P[4];
  const double q = ((((z + Q[0]) * z + Q[1]) * z + Q[2]) * z + Q[3]) * z + Q[4];
  return y + (t * z * p / q + t + corr);
}

// atan2(y, x) for y, x >= 0 (every angle of the closed form lies in the first quadrant)
double atan2_first_quadrant(double y, double x)
{
  if (!(y >= 0.0 && x >= 0.0) || !std::isfinite(y) || !std::isfinite(x)) return std::atan2(y, x);
  if (y == 0.0) return 0.0;
  if (y <= x) return atan_unit(y / x);
  return M_PI / 2.0 + (6.123233995736765886130e-17 - atan_unit(x / y));  // the bits pi/2 lacks
}

// U(a, b, c) for 0 <= a, b, c with a^2 + b^2 + c^2 < R^2, by the divergence theorem:
// R^3/3 times the solid angle of the spherical triangle (Gauss-Bonnet: pi/2 less each face's
// arc angle phi_i times t_i / R and each edge's turn atan(t_j t_k / (R m_jk))), less
// t_i/3 times each flat face's area (a disk quadrant, angle phi_i);
// m_jk = sqrt(R^2 - t_j^2 - t_k^2) is where the edge of planes j and k meets the sphere
double octant_corner(double R, double a, double b, double c)
{
  const double R2 = R * R;
  const double mab = std::sqrt(std::max(0.0, (R - a) * (R + a) - b * b));
  const double mac = std::sqrt(std::max(0.0, (R - a) * (R + a) - c * c));
  const double mbc = std::sqrt(std::max(0.0, (R - b) * (R + b) - c * c));
  double v = M_PI / 6.0 * R2 * R + (a * b * mab + a * c * mac + b * c * mbc) / 3.0 - a * b * c;
  // a face at offset 0 and an edge with an offset 0 contribute nothing
  if (a > 0.0) v -= a * (3.0 * R2 - a * a) / 6.0 * atan2_first_quadrant(mac * mab - b * c, b * mac + c * mab);
  if (b > 0.0) v -= b * (3.0 * R2 - b * b) / 6.0 * atan2_first_quadrant(mbc * mab - a * c, a * mbc + c * mab);
  if (c > 0.0) v -= c * (3.0 * R2 - c * c) / 6.0 * atan2_first_quadrant(mbc * mac - a * b, a * mbc + b * mac);
  const double edge = R2 * R / 3.0;
  if (a > 0.0 && b > 0.0) v -= edge * atan2_first_quadrant(a * b, R * mab);
  if (a > 0.0 && c > 0.0) v -= edge * atan2_first_quadrant(a * c, R * mac);
  if (b > 0.0 && c > 0.0) v -= edge * atan2_first_quadrant(b * c, R * mbc);
  return v;
}

// U(a, b, c) for folded offsets in [0, R] or kFree (no constraint along that axis: twice the
// half at offset 0, the sphere being symmetric)
double upper_corner(double R, double a, double b, double c)
{
  double factor = 1.0;
  if (a == kFree) a = 0.0, factor *= 2.0;
  if (b == kFree) b = 0.0, factor *= 2.0;
  if (c == kFree) c = 0.0, factor *= 2.0;
  if (a * a + b * b + c * c >= R * R) return 0.0;
  // one offset alone is a quarter cap
  if (int(a == 0.0) + int(b == 0.0) + int(c == 0.0) >= 2) {
    const double t = a + b + c;
    return factor * M_PI * (R - t) * (R - t) * (2.0 * R + t) / 12.0;
  }
  return factor * octant_corner(R, a, b, c);
}

// One axis of a box [lo, hi] (offsets from the centre, clamped to [-R, R]) as signed
// half-space terms over folded offsets: the sphere is symmetric, so {x <= -t} counts as {x >= t}.
struct AxisTerms {
  int n = 0;
  double t[3];
  double sign[3];
  void add(double offset, double s, double R)
  {
    if (offset >= R) return;  // a half-space beyond the sphere holds none of it
    t[n] = offset;
    sign[n++] = s;
  }
};

AxisTerms axis_terms(double lo, double hi, double R)
{
  AxisTerms a;
  if (lo >= 0.0) {
    a.add(lo, 1.0, R);
    a.add(hi, -1.0, R);
  } else if (hi <= 0.0) {
    a.add(-hi, 1.0, R);
    a.add(-lo, -1.0, R);
  } else {
    a.add(kFree, 1.0, R);
    a.add(-lo, -1.0, R);
    a.add(hi, -1.0, R);
  }
  return a;
}

// |sphere ∩ box| as the signed sum of corner volumes over the three axes' terms, clipped at 0
// (round-off); corner(i, j, k) gives U at term i of x, j of y, k of z
template <class Corner> double alternating_sum(const AxisTerms ax[3], const Corner &corner)
{
  double v = 0.0;
  for (int i = 0; i < ax[0].n; ++i)
    for (int j = 0; j < ax[1].n; ++j)
      for (int k = 0; k < ax[2].n; ++k) v += ax[0].sign[i] * ax[1].sign[j] * ax[2].sign[k] * corner(i, j, k);
  return std::max(0.0, v);
}

// the shortcuts shared by both paths; returns false when the box needs the full evaluation
bool trivial_overlap(const Eigen::Vector3d &c, double r, const Eigen::Vector3d &lo, const Eigen::Vector3d &hi,
                     double &volume)
{
  const Eigen::Vector3d closest = c.cwiseMax(lo).cwiseMin(hi);
  if (!(r > 0.0) || !(hi.array() > lo.array()).all() || (closest - c).squaredNorm() >= r * r) {
    volume = 0.0;  // disjoint, or an empty box
    return true;
  }
  const Eigen::Vector3d far = (c - lo).cwiseAbs().cwiseMax((hi - c).cwiseAbs());
  if (far.squaredNorm() <= r * r) {
    volume = (hi - lo).prod();  // box inside the sphere
    return true;
  }
  if ((c - lo).minCoeff() >= r && (hi - c).minCoeff() >= r) {
    volume = 4.0 / 3.0 * M_PI * r * r * r;  // sphere inside the box
    return true;
  }
  return false;
}

double clamp_offset(double d, double r)
{
  return std::clamp(d, -r, r);
}

// ---- quadrature (reference) ----------------------------------------------------------
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

}  // namespace

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
  double volume;
  if (trivial_overlap(c, r, lo, hi, volume)) return volume;
  AxisTerms ax[3];
  for (int d = 0; d < 3; ++d) ax[d] = axis_terms(clamp_offset(lo[d] - c[d], r), clamp_offset(hi[d] - c[d], r), r);
  return alternating_sum(ax, [&](int i, int j, int k) { return upper_corner(r, ax[0].t[i], ax[1].t[j], ax[2].t[k]); });
}

double sphere_box_overlap_quadrature(const Eigen::Vector3d &c, double r, const Eigen::Vector3d &lo,
                                     const Eigen::Vector3d &hi)
{
  double trivial;
  if (trivial_overlap(c, r, lo, hi, trivial)) return trivial;

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

  // between kinks A is analytic in u under x = a + (b-a)(1 - cos(pi u))/2, but a slice circle
  // that just clears an edge puts its singularities near the real axis: bisect adaptively
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

// ---- lattice of shared planes --------------------------------------------------------
void SphereBoxOverlaps::reset(const Eigen::Vector3d &c, double r, const std::vector<Eigen::Vector3d> &lo,
                              const std::vector<Eigen::Vector3d> &hi)
{
  c_ = c;
  r_ = r;
  lo_ = &lo;
  hi_ = &hi;
  // the planes strictly inside the sphere's extent: at most one per axis takes the octant path
  octants_ = true;
  for (int a = 0; a < 3 && octants_; ++a) {
    bool found = false;
    cut_[a] = -r;
    for (std::size_t i = 0; i < lo.size() && octants_; ++i)
      for (const double d : {lo[i][a] - c[a], hi[i][a] - c[a]}) {
        if (!(d > -r && d < r)) continue;
        if (found && d != cut_[a]) octants_ = false;
        found = true;
        cut_[a] = d;
      }
  }
  if (octants_) {
    sphere_octant_pieces(r_, cut_, piece_);
    return;
  }
  for (int a = 0; a < 3; ++a) {
    // the boxes of a lattice repeat their coordinates: drop a value equal to one of the last
    // two kept before sorting, then fold
    auto &p = planes_[a];
    p.clear();
    for (std::size_t i = 0; i < lo.size(); ++i)
      for (const double v : {lo[i][a], hi[i][a]}) {
        const std::size_t m = p.size();
        if ((m > 0 && p[m - 1] == v) || (m > 1 && p[m - 2] == v)) continue;
        p.push_back(v);
      }
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    for (double &v : p) v = std::abs(clamp_offset(v - c[a], r));
    p.push_back(kFree);
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
  }
  corner_.assign(planes_[0].size() * planes_[1].size() * planes_[2].size(), std::numeric_limits<double>::quiet_NaN());
}

int SphereBoxOverlaps::index(int axis, double offset) const
{
  const auto &p = planes_[axis];
  return int(std::lower_bound(p.begin(), p.end(), offset) - p.begin());
}

double SphereBoxOverlaps::corner(int i, int j, int k)
{
  double &u = corner_[(std::size_t(k) * planes_[1].size() + j) * planes_[0].size() + i];
  if (std::isnan(u)) u = upper_corner(r_, planes_[0][i], planes_[1][j], planes_[2][k]);
  return u;
}

void sphere_octant_pieces(double r, const double cut[3], double piece[8])
{
  // U at the folded offsets {free, |cut|} of the three axes, each evaluated once
  double U[2][2][2] = {};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        const bool inside = (!i || cut[0] > -r) && (!j || cut[1] > -r) && (!k || cut[2] > -r);
        if (inside)
          U[i][j][k] =
              upper_corner(r, i ? std::abs(cut[0]) : kFree, j ? std::abs(cut[1]) : kFree, k ? std::abs(cut[2]) : kFree);
      }
  // each side of a cut as coefficients of the free and the folded term (the sphere is
  // symmetric): above a >= 0 is {x >= a}, (0, 1); below it, everything minus that, (1, -1);
  // mirrored for a < 0. Without a cut the whole axis counts as the side above, (1, 0)
  double coef[3][2][2];
  for (int a = 0; a < 3; ++a) {
    if (!(cut[a] > -r)) {
      coef[a][0][0] = coef[a][0][1] = 0.0;
      coef[a][1][0] = 1.0, coef[a][1][1] = 0.0;
      continue;
    }
    const int near = cut[a] >= 0.0 ? 1 : 0;
    coef[a][near][0] = 0.0, coef[a][near][1] = 1.0;
    coef[a][1 - near][0] = 1.0, coef[a][1 - near][1] = -1.0;
  }
  // contracted one axis at a time
  double Vx[2][2][2], Vxy[2][2][2];
  for (int s = 0; s < 2; ++s)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) Vx[s][j][k] = coef[0][s][0] * U[0][j][k] + coef[0][s][1] * U[1][j][k];
  for (int sx = 0; sx < 2; ++sx)
    for (int sy = 0; sy < 2; ++sy)
      for (int k = 0; k < 2; ++k) Vxy[sx][sy][k] = coef[1][sy][0] * Vx[sx][0][k] + coef[1][sy][1] * Vx[sx][1][k];
  for (int p = 0; p < 8; ++p) {
    const int sx = p & 1, sy = (p >> 1) & 1, sz = (p >> 2) & 1;
    piece[p] = std::max(0.0, coef[2][sz][0] * Vxy[sx][sy][0] + coef[2][sz][1] * Vxy[sx][sy][1]);
  }
}

double SphereBoxOverlaps::octant_volume(std::size_t b) const
{
  const Eigen::Vector3d &lo = (*lo_)[b], &hi = (*hi_)[b];
  // the sides of each cut the box spans (both when it spans the cut, the upper when none cuts)
  int sides[3][2], count[3];
  for (int a = 0; a < 3; ++a) {
    const double l = lo[a] - c_[a], h = hi[a] - c_[a];
    count[a] = 0;
    if (h <= -r_ || l >= r_) return 0.0;
    if (cut_[a] <= -r_) {
      sides[a][count[a]++] = 1;
      continue;
    }
    if (l < cut_[a]) sides[a][count[a]++] = 0;
    if (h > cut_[a]) sides[a][count[a]++] = 1;
    if (count[a] == 0) return 0.0;
  }
  double v = 0.0;
  for (int i = 0; i < count[0]; ++i)
    for (int j = 0; j < count[1]; ++j)
      for (int k = 0; k < count[2]; ++k) v += piece_[sides[0][i] | sides[1][j] << 1 | sides[2][k] << 2];
  return v;
}

double SphereBoxOverlaps::volume(std::size_t b)
{
  if (octants_) return octant_volume(b);
  const Eigen::Vector3d &lo = (*lo_)[b], &hi = (*hi_)[b];
  double v;
  if (trivial_overlap(c_, r_, lo, hi, v)) return v;
  AxisTerms ax[3];
  int idx[3][3];
  for (int d = 0; d < 3; ++d) {
    ax[d] = axis_terms(clamp_offset(lo[d] - c_[d], r_), clamp_offset(hi[d] - c_[d], r_), r_);
    for (int t = 0; t < ax[d].n; ++t) idx[d][t] = index(d, ax[d].t[t]);
  }
  return alternating_sum(ax, [&](int i, int j, int k) { return corner(idx[0][i], idx[1][j], idx[2][k]); });
}

}  // namespace meltdem::coupling
