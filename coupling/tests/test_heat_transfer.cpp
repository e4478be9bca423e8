// Ranz-Marshall heat transfer (Codina2019 eq. 2.13) against values computed by hand.
#include "meltdem/coupling/heat_transfer.h"
#include "validation_report.h"

#include <cmath>
#include <stdexcept>

using namespace meltdem::coupling;
using meltdem::testing::expect_relative;

TEST(HeatTransfer, RanzMarshall)
{
  expect_relative("Nu(Re=0) (conduction limit)", ranz_marshall_nusselt(0.0, 0.7), 2.0, 1e-15);
  // 2 + 0.6 sqrt(50) 0.7^(1/3)
  expect_relative("Nu(Re=50, Pr=0.7)", ranz_marshall_nusselt(50.0, 0.7), 5.76705764404919, 1e-13);
}

TEST(HeatTransfer, CoefficientAndRate)
{
  // Codina2019 §2.3 gas: k = 100 W/m/K, d = 600 um, Nu = 2 -> h = 333333.3 W/m^2/K
  const double h = heat_transfer_coefficient(100.0, 2.0, 600e-6);
  expect_relative("h [W/m2K]", h, 333333.3333333333, 1e-13);
  // Q = h pi d^2 (1500 - 0) = 565.4867 W
  expect_relative("Q [W]", convective_heat_rate(h, 600e-6, 1500.0, 0.0), 565.4866776461628, 1e-12);
  expect_relative("Pr(argon)", prandtl_number(520.0, 2.2e-5, 0.016), 0.715, 1e-13);
  EXPECT_THROW(ranz_marshall_nusselt(-1.0, 0.7), std::invalid_argument);
  EXPECT_THROW(heat_transfer_coefficient(1.0, 2.0, 0.0), std::invalid_argument);
}
