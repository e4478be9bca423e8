// Step-control bounds of fix powder/dt and the overlap measure of compute powder/overlap.
#include "meltdem/coupling/dem_step_control.h"
#include "meltdem/coupling/hertz_contact.h"
#include "validation_report.h"

#include <cmath>
#include <stdexcept>

using namespace meltdem::coupling;
using meltdem::testing::expect_relative;

TEST(DemStepControl, SpeedBound)
{
  expect_relative("2 max|v| [m/s]", approach_speed_bound(1.5, 1e-3), 3.0, 1e-15);
  expect_relative("floor at rest [m/s]", approach_speed_bound(0.0, 1e-3), 1e-3, 1e-15);
  EXPECT_THROW(approach_speed_bound(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(approach_speed_bound(-1.0, 1e-3), std::invalid_argument);
}

TEST(DemStepControl, ShortestContactTimeIsEqualSmallSpheres)
{
  // 15 um radius steel, E* = 200 GPa / (2 (1 - 0.09)), U = 1 m/s: eq. 3.1 by hand
  const double Es = effective_modulus(200e9, 0.3, 200e9, 0.3);
  expect_relative("t_c shortest [s]", shortest_contact_time(15e-6, 8000.0, Es, 1.0), 9.278016747206419e-08, 1e-12);
  // it is a lower bound: small on large sphere, sphere on wall (R* = R, m* = m), denser pair
  const double R = 15e-6, m = 4.0 / 3.0 * M_PI * R * R * R * 8000.0;
  const double tmin = shortest_contact_time(R, 8000.0, Es, 1.0);
  const double M = 4.0 / 3.0 * M_PI * 8 * R * R * R * 8000.0;
  EXPECT_LT(tmin, hertz_contact_time(harmonic_pair(m, M), harmonic_pair(R, 2 * R), Es, 1.0));
  EXPECT_LT(tmin, hertz_contact_time(m, R, Es, 1.0));
  EXPECT_LT(tmin, shortest_contact_time(R, 9000.0, Es, 1.0));
  expect_relative("wall / equal pair contact time", hertz_contact_time(m, R, Es, 1.0) / tmin, std::pow(2.0, 0.2),
                  1e-12);
}

TEST(DemStepControl, Overlap)
{
  expect_relative("overlap/R_small", overlap_ratio(30e-6, 10e-6, 25e-6), 0.5, 1e-12);
  EXPECT_EQ(overlap_ratio(40e-6, 10e-6, 25e-6), 0.0);
  expect_relative("wall overlap/R", wall_overlap_ratio(9e-6, 10e-6), 0.1, 1e-12);
  EXPECT_EQ(wall_overlap_ratio(11e-6, 10e-6), 0.0);
  EXPECT_THROW(overlap_ratio(1.0, 0.0, 1.0), std::invalid_argument);
}
