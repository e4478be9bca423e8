// The Hertz-Tsuji contact as MeltDEM's styles step it (stepped damping, velocity-Verlet)
// and the alpha that returns a prescribed e at that step.
#include "meltdem/coupling/hertz_restitution.h"
#include "meltdem/coupling/stepped_restitution.h"
#include "validation_report.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

using namespace meltdem::coupling;
using meltdem::testing::expect_absolute;
using meltdem::testing::expect_relative;

namespace {
constexpr double contact_time = 3.2199;  // elastic Hertz contact in delta0/v0 (eq. 3.1's 2.87 (4/3)^0.4)
}

TEST(SteppedRestitution, ConvergesToTheContinuousContact)
{
  // fine steps: the stepped contact is the continuous one (first order in h)
  for (double alpha : {0.08, 0.48, 1.3}) {
    const double fine = restitution_at_step(alpha, contact_time / 4000, 0.3);
    expect_absolute("e(alpha=" + std::to_string(alpha) + ") at 4000 steps vs continuous", fine,
                    restitution_for_alpha(alpha), 5e-4);
  }
}

TEST(SteppedRestitution, AlphaAtStepReturnsE)
{
  for (double e : {0.1, 0.3, 0.5, 0.7, 0.95})
    for (double S : {5.0, 10.0, 20.0}) {
      const double h = contact_time / S;
      const double a = alpha_for_restitution_at_step(e, h);
      expect_absolute("phase-mean e at S=" + std::to_string(S) + " (prescribed " + std::to_string(e) + ")",
                      mean_restitution_at_step(a, h), e, 1e-8);
    }
  expect_absolute("alpha at h = 0 is the continuous alpha", alpha_for_restitution_at_step(0.3, 0.0),
                  alpha_for_restitution(0.3), 0.0);
}

TEST(SteppedRestitution, PhaseScatterIsSmall)
{
  // what the stepped damping buys: e hardly depends on where in a step a contact starts
  for (double e : {0.1, 0.3, 0.5, 0.7, 0.95})
    for (double S : {10.0, 20.0}) {
      const double h = contact_time / S, a = alpha_for_restitution_at_step(e, h);
      double worst = 0.0;
      for (int k = 0; k < 64; ++k)
        worst = std::max(worst, std::fabs(restitution_at_step(a, h, (k + 0.5) / 64) / e - 1));
      expect_absolute("worst phase |e/e0 - 1| at S=" + std::to_string(S) + " (e " + std::to_string(e) + ")", worst, 0.0,
                      0.005);
    }
}

TEST(SteppedRestitution, TableInterpolatesTheNodes)
{
  const SteppedAlphaTable table(0.3);
  // between nodes the interpolated alpha must still give e to a tenth of the 0.5 % budget
  for (double S : {4.0, 7.0, 13.0, 37.0}) {
    const double h = contact_time / S;
    expect_relative("phase-mean e with the table's alpha at S=" + std::to_string(S) + " (prescribed 0.3)",
                    mean_restitution_at_step(table.alpha(h), h), 0.3, 5e-4);
  }
  expect_absolute("table alpha at h = 0", table.alpha(0.0), alpha_for_restitution(0.3), 1e-12);
}

TEST(SteppedRestitution, DampingImpulsesCancelOverAContact)
{
  // the stepped damping force times dt telescopes: a contact's damping impulses sum to zero
  const double k = 3.0e6, m = 1.0e-10, dt = 1.0e-9;
  const double path[] = {-1e-9, 2e-8, 5e-8, 6e-8, 4e-8, 1e-8, -2e-8};
  double sum = 0.0, scale = 0.0;
  for (int n = 1; n < 7; ++n) {
    const double f = stepped_damping_force(0.5, k, m, path[n], path[n - 1], dt);
    sum += f * dt;
    scale = std::max(scale, std::fabs(f * dt));
  }
  expect_absolute("sum of damping impulses / largest impulse", sum / scale, 0.0, 1e-14);
  // and the correction removes the stock damping where the contact overlaps
  const double rate = -0.3, delta = 4e-8;
  const double stock = -0.7 * std::sqrt(m * k * std::sqrt(delta)) * rate;
  expect_relative("correction = stepped - stock", stepped_damping_correction(0.6, 0.7, k, m, delta, rate, dt),
                  stepped_damping_force(0.6, k, m, delta, delta + dt * rate, dt) - stock, 1e-14);
}

TEST(SteppedRestitution, ContactStepScaling)
{
  // h = dt v0^(1/5) (K/m*)^(2/5): the elastic contact time t_c = 3.22 delta0/v0 is S steps at h = 3.22/S
  const double E = 200e9, nu = 0.3, R = 15e-6, rho = 7800.0, v0 = 2.0;
  const double Es = E / (2.0 * (1.0 - nu * nu)), Rs = R / 2.0, m = 4.0 / 3.0 * M_PI * R * R * R * rho;
  const double K = 4.0 / 3.0 * Es * std::sqrt(Rs), ms = m / 2.0;
  const double tc = 2.87 * std::pow(ms * ms / (Rs * Es * Es * v0), 0.2);  // eq. 3.1
  expect_relative("h at dt = t_c/10", contact_step(tc / 10, v0, K, ms), contact_time / 10, 1e-4);
}

TEST(SteppedRestitution, RejectsBadInput)
{
  EXPECT_THROW(alpha_for_restitution_at_step(0.0, 0.3), std::invalid_argument);
  EXPECT_THROW(alpha_for_restitution_at_step(0.5, -0.1), std::invalid_argument);
  EXPECT_THROW(alpha_for_restitution_at_step(0.5, 2.0), std::invalid_argument);
}

TEST(SteppedRestitution, OnsetRatioRemovesThePhaseScatter)
{
  // with the table's onset ratio every phase returns e, at the coarsest steps users run and
  // between the table's nodes of h and phase
  for (double e : {0.1, 0.3, 0.5, 0.7, 0.95}) {
    const SteppedAlphaTable table(e);
    for (double S : {4.0, 5.0, 7.0, 10.0, 20.0, 60.0}) {
      const double h = contact_time / S, a = table.alpha(h);
      double worst = 0.0, worst_without = 0.0;
      for (int k = 0; k < 200; ++k) {
        const double phase = (k + 0.37) / 200;
        worst = std::max(worst, std::fabs(restitution_at_step(a, h, phase, table.onset_ratio(h, h, phase)) / e - 1));
        worst_without = std::max(worst_without, std::fabs(restitution_at_step(a, h, phase) / e - 1));
      }
      const std::string at = " at S=" + std::to_string(S) + " (e " + std::to_string(e) + ")";
      expect_absolute("worst phase |e/e0 - 1| with the onset ratio" + at, worst, 0.0, 0.001);
      if (S <= 5.0) EXPECT_GT(worst_without, 0.005) << "the scatter the ratio removes" << at;
    }
  }
}

TEST(SteppedRestitution, OnsetRatioHoldsAtOtherImpactSpeeds)
{
  // a contact slower or faster than the calibration speed runs at its own step with the
  // alpha of the calibration step; the onset ratio returns e at every phase
  for (double e : {0.1, 0.3, 0.5, 0.95}) {
    const SteppedAlphaTable table(e);
    for (double S : {5.0, 10.0, 20.0})
      for (double speed : {1e-6, 0.01, 0.1, 0.2, 0.5, 1.0, 1.5}) {
        const double h = contact_time / S, a = table.alpha(h);
        const double h_contact = h * std::pow(speed, 0.2);
        double worst = 0.0;
        for (int k = 0; k < 50; ++k) {
          const double phase = (k + 0.37) / 50;
          worst = std::max(
              worst,
              std::fabs(restitution_at_step(a, h_contact, phase, table.onset_ratio(h, h_contact, phase)) / e - 1));
        }
        expect_absolute("worst phase |e/e0 - 1| at " + std::to_string(speed) +
                            " of the calibration speed, S=" + std::to_string(S) + " (e " + std::to_string(e) + ")",
                        worst, 0.0, 0.001);
      }
  }
  // without a calibration speed (h = 0: the continuous alpha) no onset force
  EXPECT_EQ(SteppedAlphaTable(0.3).onset_ratio(0.0, 0.3, 0.5), 1.0);
}

TEST(SteppedRestitution, OnsetForceActsAtTheFirstOverlappingStepOnly)
{
  const double m = 2e-10, dt = 1e-9, rate = -2.0;
  // approach speed 2 scaled by 0.99: an impulse of m * 0.02 over the step
  expect_relative("onset impulse", stepped_onset_force(0.99, m, 0.5 * dt * 2.0, rate, dt) * dt, m * 0.02, 1e-12);
  EXPECT_EQ(stepped_onset_force(0.99, m, 3.0 * dt * 2.0, rate, dt), 0.0);  // overlapping a step ago too
  EXPECT_EQ(stepped_onset_force(0.99, m, -1e-12, rate, dt), 0.0);          // not yet touching
  expect_relative("phase of a contact starting three quarters into the step", onset_phase(0.25, -0.75), 0.75, 1e-15);
}
