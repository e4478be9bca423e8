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

namespace {
SolidSurface plane(double height)
{
  SolidSurface s;
  s.present = true;
  s.point = Eigen::Vector3d(0, height, 0);
  s.normal = Eigen::Vector3d::UnitY();
  return s;
}
}  // namespace

TEST(SolidMetalContact, FreezingAroundAGrainGivesNoKick)
{
  // a 16 um steel grain at rest; the melt under it freezes and the solid surface appears
  // 0.8 R above its lowest point (and later jumps above its centre): no force, while plain
  // Hertz would push with ~0.1 N, 1e10 m/s^2
  const double R = 8e-6, m = 7430 * 4.0 / 3.0 * M_PI * R * R * R, E = 1.1e11, alpha = alpha_for_restitution(0.5);
  const Eigen::Vector3d x(0, R, 0), v = Eigen::Vector3d::Zero();
  SolidContactMemory memory;
  const SolidSurface s = plane(0.8 * R);
  const double offset = update_solid_contact(memory, s, x, R);
  const double plain = solid_contact_force(s, x, R, m, v, E, alpha).norm();
  EXPECT_GT(plain / m, 1e9);
  meltdem::testing::expect_absolute("solid metal contact: force on a grain the solid froze around [N]",
                                    solid_contact_force(s, x, R, m, v, E, alpha, offset).norm(), 0.0, 0.0);
  EXPECT_NEAR(offset, 0.8 * R, 1e-18);
  // the staircase switches to a face above the centre: still no force
  const SolidSurface higher = plane(1.5 * R);
  EXPECT_EQ(solid_contact_force(higher, x, R, m, v, E, alpha, update_solid_contact(memory, higher, x, R)).norm(), 0.0);
  // pressed 0.1 R further into the unchanged surface: the force of an overlap of 0.1 R
  const Eigen::Vector3d pressed(0, 0.9 * R, 0);
  const double off = update_solid_contact(memory, higher, pressed, R);
  meltdem::testing::expect_relative(
      "solid metal contact: force after pressing 0.1 R into a surface that froze around",
      solid_contact_force(higher, pressed, R, m, v, E, alpha, off).norm(),
      solid_contact_force(plane(0.1 * R), Eigen::Vector3d(0, R, 0), R, m, v, E, alpha).norm(), 1e-12);
  // moving out lowers the offset with the overlap; clear of the surface it is forgotten
  EXPECT_NEAR(update_solid_contact(memory, higher, Eigen::Vector3d(0, 2.0 * R, 0), R), 0.5 * R, 1e-18);
  EXPECT_EQ(update_solid_contact(memory, higher, Eigen::Vector3d(0, 3.0 * R, 0), R), 0.0);
  EXPECT_EQ(memory.offset, 0.0);
}

TEST(SolidMetalContact, ApproachingGrainBouncesAsWithoutMemory)
{
  // the surface is known before the grain reaches it (reach = travel + a cell): the memory
  // changes nothing, the bounce keeps the restitution of the damping
  const double R = 15e-6, m = 7800 * 4.0 / 3.0 * M_PI * R * R * R, E = 1.1e11, e = 0.5;
  const double alpha = alpha_for_restitution(e);
  const SolidSurface s = plane(0.0);
  SolidContactMemory memory;
  Eigen::Vector3d x(0, 1.2 * R, 0), v(0, -2.0, 0);
  const double dt = 2e-11;
  double worst_offset = 0.0;
  auto force = [&]() {
    const double off = update_solid_contact(memory, s, x, R);
    worst_offset = std::max(worst_offset, off);
    return solid_contact_force(s, x, R, m, v, E, alpha, off);
  };
  Eigen::Vector3d f = force();
  for (int k = 0; k < 4000000 && !(x.y() > R && v.y() > 0); ++k) {
    v += 0.5 * dt * f / m;
    x += dt * v;
    f = force();
    v += 0.5 * dt * f / m;
  }
  EXPECT_EQ(worst_offset, 0.0);
  meltdem::testing::expect_relative("solid metal contact with memory: rebound / impact speed, e = 0.5", v.y() / 2.0, e,
                                    0.01);
}

TEST(SolidMetalContact, GrainMovingIntoOldSolidWhileAnotherIsNearestIsPushed)
{
  // a falling grain beside a wall of solid metal (the nearest surface over one coupling
  // interval) moves 0.2 R into the floor, solid for as long: when the floor becomes the
  // nearest, that overlap is the grain's own and pushes as Hertz does. Had the floor frozen
  // in that interval (fresh), the overlap came with it (no push).
  const double R = 10e-6, m = 7800 * 4.0 / 3.0 * M_PI * R * R * R, E = 1.1e11, alpha = alpha_for_restitution(0.5);
  const Eigen::Vector3d v(0, -1.0, 0);
  SolidSurface wall;  // x = -1.05 R, facing +x
  wall.present = true, wall.normal = Eigen::Vector3d::UnitX(), wall.point = Eigen::Vector3d(-1.05 * R, 0, 0);
  wall.fresh = false;
  SolidSurface floor = plane(0.0);
  const Eigen::Vector3d above(0, 1.5 * R, 0), in(0, 0.8 * R, 0);
  for (const bool fresh : {false, true}) {
    SolidContactMemory memory;
    update_solid_contact(memory, wall, above, R, true);  // the interval's first step, the mark
    update_solid_contact(memory, wall, in, R);           // the interval's last step
    floor.fresh = fresh;
    const double off = update_solid_contact(memory, floor, in, R, true);
    const double F = solid_contact_force(floor, in, R, m, v, E, alpha, off).norm();
    if (fresh) {
      EXPECT_NEAR(off, 0.2 * R, 1e-18);
      EXPECT_EQ(F, 0.0);
    } else {
      meltdem::testing::expect_relative(
          "solid metal contact: force of 0.2 R made by moving into old solid while a wall was nearest", F,
          solid_contact_force(floor, in, R, m, v, E, alpha).norm(), 1e-12);
    }
  }
}

TEST(SolidMetalContact, EngulfedGrainMeetingOldSolidGivesNoKick)
{
  // a grain the melt froze around (offset 0.8 R) rests; at the next interval the staircase
  // switches to another face, solid since the freeze, that overlaps it as much as at the
  // mark: no force
  const double R = 8e-6, m = 7430 * 4.0 / 3.0 * M_PI * R * R * R, E = 1.1e11, alpha = alpha_for_restitution(0.5);
  const Eigen::Vector3d x(0, R, 0), v = Eigen::Vector3d::Zero();
  SolidContactMemory memory;
  update_solid_contact(memory, plane(0.8 * R), x, R, true);
  SolidSurface side;
  side.present = true, side.fresh = false;
  side.normal = Eigen::Vector3d::UnitX(), side.point = Eigen::Vector3d(0.7 * R, R, 0);
  const double off = update_solid_contact(memory, side, x, R, true);
  meltdem::testing::expect_absolute(
      "solid metal contact: force on an engulfed grain when the nearest face switches [N]",
      solid_contact_force(side, x, R, m, v, E, alpha, off).norm(), 0.0, 0.0);
}

TEST(SolidMetalContact, FallingGrainIsHandedTheFloorItApproaches)
{
  // a grain falls at 7 m/s and drifts 7 m/s in +x over a solid floor (z < 0), its centre on
  // the face of a cell beside it that froze (y > 0) and past a solid cell behind it (x < 0):
  // the surfaces it slides along or leaves are nearer, the floor is the one it approaches
  const std::vector<Eigen::Vector3d> lo{{-1, -1, -1}, {-1, 0, 0.2}, {-1, -1, 0}},
      hi{{1, 1, 0}, {1, 1, 1}, {-0.2, 1, 1}};
  const Eigen::Vector3d c(0, 0, 0.5), v(7, 0, -7);
  const SolidSurface at_rest = nearest_solid_surface(c, lo, hi);
  EXPECT_NEAR(at_rest.distance, 0.0, 1e-15);  // without a velocity: the face it is on
  const SolidSurface s = nearest_solid_surface(c, lo, hi, {}, v);
  ASSERT_TRUE(s.present);
  EXPECT_TRUE(s.approached);
  EXPECT_NEAR(s.normal.z(), 1.0, 1e-15);
  meltdem::testing::expect_absolute(
      "solid metal contact: distance to the floor a falling grain approaches (one cell 1)", s.distance, 0.5, 1e-15);
}
