// Tsuji's e -> alpha polynomial (as LAMMPS pair granular applies it) and its inverse.
#include "meltdem/coupling/tsuji_damping.h"
#include "validation_report.h"

#include <stdexcept>
#include <string>

using namespace meltdem::coupling;
using meltdem::testing::expect_absolute;
using meltdem::testing::expect_relative;

TEST(TsujiDamping, PolynomialValues)
{
  const double e[] = {0.3, 0.5, 0.7, 0.9};
  const double alpha[] = {0.5659483322000002, 0.3407406250000001, 0.178405108200001, 0.05289813379999764};
  for (int i = 0; i < 4; ++i)
    expect_relative("alpha(e=" + std::to_string(e[i]).substr(0, 3) + ")", tsuji_alpha(e[i]), alpha[i], 1e-12);
  expect_relative("alpha(0)", tsuji_alpha(0.0), 1.2728, 1e-15);
  expect_relative("alpha(1)", tsuji_alpha(1.0), 3.0e-4, 1e-9);
}

TEST(TsujiDamping, InverseRoundTrip)
{
  for (double e = 0.0; e <= 1.0; e += 0.05) EXPECT_NEAR(tsuji_restitution(tsuji_alpha(e)), e, 1e-12) << "e = " << e;
  expect_absolute("e(alpha(0.5))", tsuji_restitution(0.3407406250000001), 0.5, 1e-12);
}

TEST(TsujiDamping, RejectsOutOfRange)
{
  EXPECT_THROW(tsuji_alpha(1.2), std::invalid_argument);
  EXPECT_THROW(tsuji_alpha(-0.1), std::invalid_argument);
  EXPECT_THROW(tsuji_restitution(1.5), std::invalid_argument);
  EXPECT_THROW(tsuji_restitution(0.0), std::invalid_argument);
}
