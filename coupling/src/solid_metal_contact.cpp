#include "meltdem/coupling/solid_metal_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meltdem::coupling {

SolidSurface nearest_solid_surface(const Eigen::Vector3d &c, const std::vector<Eigen::Vector3d> &lo,
                                   const std::vector<Eigen::Vector3d> &hi)
{
  SolidSurface best;
  best.distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < lo.size(); ++i) {
    const Eigen::Vector3d p = c.cwiseMax(lo[i]).cwiseMin(hi[i]);
    const double d = (c - p).norm();
    if (d < best.distance) {
      best.present = true;
      best.distance = d;
      best.point = p;
      if (d > 0.0) {
        best.normal = (c - p) / d;
      } else {  // centre inside the solid: out through the nearest face
        double nearest = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
          const double down = c[a] - lo[i][a], up = hi[i][a] - c[a];
          if (down < nearest)
            nearest = down, best.normal = -Eigen::Vector3d::Unit(a), best.point = c, best.point[a] = lo[i][a];
          if (up < nearest)
            nearest = up, best.normal = Eigen::Vector3d::Unit(a), best.point = c, best.point[a] = hi[i][a];
        }
        best.distance = -nearest;
      }
    }
  }
  return best;
}

Eigen::Vector3d solid_contact_force(const SolidSurface &s, const Eigen::Vector3d &x, double R, double m,
                                    const Eigen::Vector3d &v, double E_star, double alpha, double offset)
{
  if (!s.present) return Eigen::Vector3d::Zero();
  const double delta = R - (x - s.point).dot(s.normal) - offset;
  if (delta <= 0.0) return Eigen::Vector3d::Zero();
  const double knfac = 4.0 / 3.0 * E_star * std::sqrt(R * delta);
  const double Fn = knfac * delta - alpha * std::sqrt(m * knfac) * v.dot(s.normal);
  return Fn * s.normal;
}

double update_solid_contact(SolidContactMemory &m, const SolidSurface &s, const Eigen::Vector3d &x, double R)
{
  if (!s.present) {
    m = SolidContactMemory();
    return 0.0;
  }
  const double delta = R - (x - s.point).dot(s.normal);
  if (!(m.has_plane && m.point == s.point && m.normal == s.normal)) {
    // the surface changed: what it overlaps now beyond what the old one overlapped at the
    // same position came with the surface, not with the particle's motion
    const double before = m.has_plane ? std::max(0.0, R - (x - m.point).dot(m.normal)) : 0.0;
    m.offset += std::max(0.0, delta - before);
    m.has_plane = true;
    m.point = s.point;
    m.normal = s.normal;
  }
  m.offset = std::clamp(m.offset, 0.0, std::max(delta, 0.0));
  return m.offset;
}

}  // namespace meltdem::coupling
