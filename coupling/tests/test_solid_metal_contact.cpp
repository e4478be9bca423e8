// solid_metal_contact.h: the nearest solid surface from cell boxes, and a bounce off it
// with the Hertz/Tsuji force reproduces the restitution of that damping.
#include "meltdem/coupling/hertz_restitution.h"
#include "meltdem/coupling/solid_metal_contact.h"
#include "validation_report.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace meltdem::coupling;

TEST(SolidMetalContact, NearestSurfaceOfCellBoxes)
{
  // a floor of two cells [0,1]x[0,1]x[0,1] and [1,2]x[0,1]x[0,1]
  const std::vector<Eigen::Vector3d> lo{{0, 0, 0}, {1, 0, 0}}, hi{{1, 1, 1}, {2, 1, 1}};
  SolidSurface s = nearest_solid_surface(Eigen::Vector3d(1.2, 1.5, 0.5), lo, hi);
  ASSERT_TRUE(s.present);
  EXPECT_NEAR(s.distance, 0.5, 1e-15);
  EXPECT_NEAR(s.normal.y(), 1.0, 1e-15);
  EXPECT_NEAR(s.point.y(), 1.0, 1e-15);
  // inside the solid, nearer the top face than any other: pushed out through the top
  s = nearest_solid_surface(Eigen::Vector3d(0.5, 0.9, 0.5), lo, hi);
  EXPECT_NEAR(s.normal.y(), 1.0, 1e-15);
  EXPECT_NEAR(s.distance, -0.1, 1e-15);
  EXPECT_FALSE(nearest_solid_surface(Eigen::Vector3d(0, 0, 0), {}, {}).present);
}

TEST(SolidMetalContact, BounceRestitutionMatchesTsujiDamping)
{
  // 30 um steel grain at 2 m/s onto the plane y = 0, E* = 1.1e11 Pa
  const double R = 15e-6, m = 7800 * 4.0 / 3.0 * M_PI * R * R * R, E = 1.1e11;
  SolidSurface s;
  s.present = true;
  s.normal = Eigen::Vector3d::UnitY();
  for (double e : {0.3, 0.5, 0.9}) {
    const double alpha = alpha_for_restitution(e);
    Eigen::Vector3d x(0, R, 0), v(0, -2.0, 0);
    const double dt = 2e-11;
    Eigen::Vector3d f = solid_contact_force(s, x, R, m, v, E, alpha);
    for (int k = 0; k < 2000000 && !(x.y() > R && v.y() > 0); ++k) {  // velocity Verlet
      v += 0.5 * dt * f / m;
      x += dt * v;
      f = solid_contact_force(s, x, R, m, v, E, alpha);
      v += 0.5 * dt * f / m;
    }
    meltdem::testing::expect_relative("solid metal contact: rebound / impact speed, e = " + std::to_string(e),
                                      v.y() / 2.0, e, 0.01);
  }
  EXPECT_EQ(solid_contact_force(s, Eigen::Vector3d(0, 2 * R, 0), R, m, Eigen::Vector3d::Zero(), E, 0.5).norm(), 0.0);
}
