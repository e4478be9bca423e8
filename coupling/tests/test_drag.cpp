// Drag laws: Codina2019 eq. 2.14 (exponent corrected to -1/3) and Schiller-Naumann.
#include "meltdem/coupling/drag.h"
#include "validation_report.h"

#include <cmath>
#include <stdexcept>
#include <string>

using namespace meltdem::coupling;
using meltdem::testing::expect_relative;

TEST(Drag, ThesisLaw)
{
  const double Re[] = {0.1, 10.0, 500.0, 2000.0};
  const double Cd[] = {248.61773876012754, 4.256635533445111, 0.5519684199579493, 0.424};
  for (int i = 0; i < 4; ++i)
    expect_relative("Cd_thesis(Re=" + std::to_string(Re[i]) + ")", drag_coefficient_thesis(Re[i]), Cd[i], 1e-13);
  // continuity at the switch Re = 1000 (holds only with the -1/3 exponent)
  expect_relative("Cd_thesis(1000-) vs 0.424", drag_coefficient_thesis(1000.0), 0.424, 1e-12);
}

TEST(Drag, SchillerNaumann)
{
  const double Re[] = {0.1, 10.0, 500.0, 2000.0};
  const double Cd[] = {247.4012061455429, 4.151065940489262, 0.5626653016291134, 0.44};
  for (int i = 0; i < 4; ++i)
    expect_relative("Cd_SN(Re=" + std::to_string(Re[i]) + ")", drag_coefficient_schiller_naumann(Re[i]), Cd[i], 1e-13);
}

TEST(Drag, StokesLimitOfBeta)
{
  // Re -> 0: F = 3 pi mu d (U_f - U_p) for both laws
  const double mu = 1.8e-5, d = 30e-6, stokes = 3.0 * M_PI * mu * d;
  expect_relative("beta_thesis(Re=0)/3pi mu d", drag_beta(DragModel::Thesis, 0.0, mu, d), stokes, 1e-15);
  expect_relative("beta_SN(Re=0)/3pi mu d", drag_beta(DragModel::SchillerNaumann, 0.0, mu, d), stokes, 1e-15);
  // beta = 3/4 m Cd Re mu / (rho_p d^2) at Re = 10
  const double rho_p = 8000.0, m = M_PI / 6.0 * rho_p * d * d * d;
  expect_relative("beta eq. 2.14 form (Re=10)", drag_beta(DragModel::Thesis, 10.0, mu, d),
                  0.75 * m * 4.256635533445111 * 10.0 * mu / (rho_p * d * d), 1e-13);
  expect_relative("Re_p", particle_reynolds(1.6115, 2.0, 600e-6, 2.1e-5), 92.08571428571429, 1e-13);
  EXPECT_THROW(drag_coefficient_thesis(0.0), std::invalid_argument);
}
