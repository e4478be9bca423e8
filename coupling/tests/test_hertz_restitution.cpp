// Exact restitution of Hertz + Tsuji delta^(1/4) damping (the force law of LAMMPS
// pair granular hertz/material ... damping tsuji) and its inverse.
#include "meltdem/coupling/hertz_restitution.h"
#include "meltdem/coupling/tsuji_damping.h"
#include "validation_report.h"

#include <cmath>
#include <stdexcept>
#include <string>

using namespace meltdem::coupling;
using meltdem::testing::expect_absolute;

namespace {
// Independent integration in dimensional form (steel, 30 um, 2 m/s) with a finer
// step and a linear end crossing: checks the scaling and the integrator together.
double dimensional_restitution(double alpha)
{
  const double E = 200e9, nu = 0.3, R = 15e-6, rho = 7800.0, v0 = 2.0;
  const double Es = E / (2.0 * (1.0 - nu * nu)), Rs = R / 2.0;
  const double m = 4.0 / 3.0 * M_PI * R * R * R * rho, ms = m / 2.0;
  const double K = 4.0 / 3.0 * Es * std::sqrt(Rs);
  const double d0 = std::pow(ms * v0 * v0 / K, 0.4), T = d0 / v0, h = 2.0e-5 * T;
  auto acc = [&](double d, double v) {
    const double dp = d > 0 ? d : 0.0;
    const double kn = K * std::sqrt(dp);
    return (-kn * dp - alpha * std::sqrt(ms * kn) * v) / ms;
  };
  double d = 0.0, v = v0;
  for (long n = 0; n < 100000000L; ++n) {
    const double k1x = v, k1v = acc(d, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(d + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(d + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(d + h * k3x, v + h * k3v);
    const double d1 = d + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double v1 = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (n > 0 && d1 <= 0.0) {
      const double f = d / (d - d1);
      return -(v + f * (v1 - v)) / v0;
    }
    d = d1;
    v = v1;
  }
  return 0.0;
}
}  // namespace

TEST(HertzRestitution, ElasticLimit)
{
  expect_absolute("e(alpha=0)", restitution_for_alpha(0.0), 1.0, 1e-8);
  expect_absolute("e(alpha=1e-6)", restitution_for_alpha(1e-6), 1.0, 1e-5);
  EXPECT_LT(restitution_for_alpha(1e-6), 1.0);
  expect_absolute("alpha(e=1)", alpha_for_restitution(1.0), 0.0, 0.0);
}

TEST(HertzRestitution, MatchesIndependentIntegration)
{
  for (double alpha : {0.01, 0.075, 0.25, 0.48, 0.8, 1.0, 1.5})
    expect_absolute("e(alpha=" + std::to_string(alpha) + ") vs dimensional RK4", restitution_for_alpha(alpha),
                    dimensional_restitution(alpha), 1e-6);
}

TEST(HertzRestitution, InverseRoundTrip)
{
  for (double e : {0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99})
    expect_absolute("e(alpha(e=" + std::to_string(e) + "))", restitution_for_alpha(alpha_for_restitution(e)), e, 1e-6);
}

TEST(HertzRestitution, ExplainsStockBias)
{
  // restitution of stock LAMMPS (Tsuji polynomial) from LAMMPS runs: the exact map explains the bias
  const double e[] = {0.3, 0.5, 0.7, 0.9}, measured[] = {0.439, 0.617, 0.782, 0.929};
  for (int i = 0; i < 4; ++i)
    expect_absolute("stock e for prescribed " + std::to_string(e[i]), restitution_for_alpha(tsuji_alpha(e[i])),
                    measured[i], 0.005);
}

TEST(HertzRestitution, RejectsBadInput)
{
  EXPECT_THROW(restitution_for_alpha(-0.1), std::invalid_argument);
  EXPECT_THROW(restitution_for_alpha(NAN), std::invalid_argument);
  EXPECT_THROW(alpha_for_restitution(0.0), std::invalid_argument);
  EXPECT_THROW(alpha_for_restitution(1.1), std::invalid_argument);
}
