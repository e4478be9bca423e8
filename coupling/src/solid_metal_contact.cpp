#include "meltdem/coupling/solid_metal_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meltdem::coupling {

SolidSurface nearest_solid_surface(const Eigen::Vector3d &c, const std::vector<Eigen::Vector3d> &lo,
                                   const std::vector<Eigen::Vector3d> &hi, const std::vector<char> &was_solid,
                                   const Eigen::Vector3d &v)
{
  SolidSurface best;
  const double speed = v.norm();
  for (std::size_t i = 0; i < lo.size(); ++i) {
    SolidSurface box;
    box.present = true;
    const Eigen::Vector3d p = c.cwiseMax(lo[i]).cwiseMin(hi[i]);
    box.distance = (c - p).norm();
    box.point = p;
    if (box.distance > 0.0) {
      box.normal = (c - p) / box.distance;
    } else {  // centre inside the solid: out through the nearest face
      double nearest = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a) {
        const double down = c[a] - lo[i][a], up = hi[i][a] - c[a];
        if (down < nearest)
          nearest = down, box.normal = -Eigen::Vector3d::Unit(a), box.point = c, box.point[a] = lo[i][a];
        if (up < nearest) nearest = up, box.normal = Eigen::Vector3d::Unit(a), box.point = c, box.point[a] = hi[i][a];
      }
      box.distance = -nearest;
    }
    box.fresh = was_solid.empty() || !was_solid[i];
    box.approached = speed > 0.0 && v.dot(box.normal) < -kApproachShare * speed;
    if (preferred_surface(box, best)) best = box;
  }
  return best;
}

bool preferred_surface(const SolidSurface &a, const SolidSurface &b)
{
  if (!a.present || !b.present) return a.present && !b.present;
  if (a.approached != b.approached) return a.approached;
  return a.distance < b.distance;
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

double update_solid_contact(SolidContactMemory &m, const SolidSurface &s, const Eigen::Vector3d &x, double R,
                            bool interval_start)
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
    double brought = std::max(0.0, delta - before);
    // old solid: at most the overlap the particle had with it at the mark
    if (!s.fresh && m.has_mark) brought = std::min(brought, std::max(0.0, R - (m.mark - s.point).dot(s.normal)));
    m.offset += brought;
    m.has_plane = true;
    m.point = s.point;
    m.normal = s.normal;
  }
  m.offset = std::clamp(m.offset, 0.0, std::max(delta, 0.0));
  if (interval_start) m.has_mark = true, m.mark = x;
  return m.offset;
}

}  // namespace meltdem::coupling
