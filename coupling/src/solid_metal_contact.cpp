#include "meltdem/coupling/solid_metal_contact.h"

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
          if (down < nearest) nearest = down, best.normal = -Eigen::Vector3d::Unit(a), best.point = c, best.point[a] = lo[i][a];
          if (up < nearest) nearest = up, best.normal = Eigen::Vector3d::Unit(a), best.point = c, best.point[a] = hi[i][a];
        }
        best.distance = -nearest;
      }
    }
  }
  return best;
}

Eigen::Vector3d solid_contact_force(const SolidSurface &s, const Eigen::Vector3d &x, double R, double m,
                                    const Eigen::Vector3d &v, double E_star, double alpha)
{
  if (!s.present) return Eigen::Vector3d::Zero();
  const double delta = R - (x - s.point).dot(s.normal);
  if (delta <= 0.0) return Eigen::Vector3d::Zero();
  const double knfac = 4.0 / 3.0 * E_star * std::sqrt(R * delta);
  const double Fn = knfac * delta - alpha * std::sqrt(m * knfac) * v.dot(s.normal);
  return Fn * s.normal;
}

}  // namespace meltdem::coupling
