// Hertz contact time (Codina2019 eq. 3.1-3.4) against values computed by hand.
#include "meltdem/coupling/hertz_contact.h"
#include "validation_report.h"

#include <cmath>
#include <stdexcept>

using namespace meltdem::coupling;
using meltdem::testing::expect_relative;

TEST(HertzContact, EffectiveModulusSameMaterial)
{
  // E* = E / (2 (1 - nu^2)) for two equal steel spheres
  expect_relative("E* steel/steel [Pa]", effective_modulus(200e9, 0.3, 200e9, 0.3), 109890109890.1099, 1e-14);
}

TEST(HertzContact, EqualSteelSpheres)
{
  // d = 30 um, rho = 8000, E = 200 GPa, nu = 0.3, U = 1 m/s
  const double R = 15e-6, rho = 8000.0, m = 4.0 / 3.0 * M_PI * R * R * R * rho;
  const double Es = effective_modulus(200e9, 0.3, 200e9, 0.3);
  expect_relative("t_c eq. 3.1 [s]", hertz_contact_time(harmonic_pair(m, m), harmonic_pair(R, R), Es, 1.0),
                  9.278016747206419e-08, 1e-12);
  expect_relative("t_c equal spheres [s]", hertz_contact_time_equal_spheres(R, rho, Es, 1.0), 9.278016747206419e-08,
                  1e-12);
}

TEST(HertzContact, UnequalPair)
{
  // m 1e-9 / 3e-9 kg, R 20 / 40 um, steel (200 GPa, 0.3) on aluminium (70 GPa, 0.33), U = 2.5 m/s
  const double Es = effective_modulus(200e9, 0.3, 70e9, 0.33);
  expect_relative("E* steel/Al [Pa]", Es, 57870370370.37038, 1e-14);
  expect_relative("t_c unequal [s]",
                  hertz_contact_time(harmonic_pair(1e-9, 3e-9), harmonic_pair(20e-6, 40e-6), Es, 2.5),
                  2.5023505448306024e-07, 1e-12);
}

TEST(HertzContact, ScalingWithSpeed)
{
  // t_c ~ U^(-1/5): 32x faster -> half the contact time
  const double t1 = hertz_contact_time(1e-10, 1e-5, 1e11, 1.0);
  const double t32 = hertz_contact_time(1e-10, 1e-5, 1e11, 32.0);
  expect_relative("t_c(1)/t_c(32)", t1 / t32, 2.0, 1e-13);
}

TEST(HertzContact, SubCycles)
{
  EXPECT_DOUBLE_EQ(dem_timestep(1e-7, 10.0), 1e-8);
  EXPECT_EQ(dem_subcycles(1e-6, 1e-8), 100);  // exact ratio: no extra cycle from round-off
  EXPECT_EQ(dem_subcycles(1e-6, 3e-8), 34);   // 33.3 -> 34
  EXPECT_EQ(dem_subcycles(1e-9, 1e-8), 1);
  EXPECT_THROW(dem_timestep(1e-7, 0.0), std::invalid_argument);
  EXPECT_THROW(hertz_contact_time(1e-10, 1e-5, 1e11, 0.0), std::invalid_argument);
  EXPECT_THROW(effective_modulus(200e9, 0.51, 200e9, 0.3), std::invalid_argument);
  EXPECT_NO_THROW(effective_modulus(200e9, 0.5, 200e9, 0.3));  // the incompressible limit
}
