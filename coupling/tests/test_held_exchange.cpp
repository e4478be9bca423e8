// Drag and heat-step coefficients held over DEM sub-steps (held_exchange.h): at the slip they
// were evaluated for they are the exact laws; anywhere in their window the held lines stay
// within the tolerance of the exact drag law and heat step, across slips from rest to above
// the drag law's branch, both drag laws, a bounded parcel and an unbounded fluid.
#include "meltdem/coupling/held_exchange.h"
#include "meltdem/coupling/particle_forces.h"
#include "meltdem/coupling/particle_melting.h"
#include "validation_report.h"

#include <cmath>

using namespace meltdem::coupling;
using meltdem::testing::expect_relative;

namespace {
// the argon-like gas and steel grain of the scenes; d 30 um or 6 mm (the hopper's grains)
HeldExchangeInput input(DragModel model, double d, double s2, double tol, double C_fluid)
{
  HeldExchangeInput in;
  in.model = model;
  in.rho = 1.6, in.mu = 2.2e-5, in.k = 0.018, in.cp = 520.0;
  in.C_fluid = C_fluid;
  in.d = d, in.m = 7800.0 * M_PI / 6.0 * d * d * d, in.cp_particle = 500.0;
  in.dt = 1e-7;
  in.s2 = s2, in.tol = tol;
  return in;
}

// the exact heat step's factor at slip^2 s2, from heat_melt_step(_two_body): a particle 1 K
// below the fluid gains share * (-expm1_rate) K
double exact_expm1_rate(const HeldExchangeInput &in, double s2, double share)
{
  FluidState f;
  f.rho = in.rho, f.mu = in.mu, f.k = in.k, f.cp = in.cp;
  const double v[3] = {std::sqrt(s2), 0.0, 0.0};
  const double knu = ranz_marshall_k_nu(f, slip_reynolds(f, v, in.d));
  MeltMaterial mat;
  mat.cp = in.cp_particle, mat.Tmelt = 5000.0, mat.latent = 2.7e5;
  const double T = 300.0, Tf = 301.0;
  const MeltStepResult r = heat_melt_step_two_body(mat, mat.cp * T, in.m, in.d, knu, Tf, in.C_fluid, in.dt);
  return -(r.h / mat.cp - T) / share / (Tf - T);
}
}  // namespace

TEST(HeldExchange, ExactAtTheSlipItHoldsFor)
{
  for (double C_fluid : {0.0, 1e-9}) {
    const auto in = input(DragModel::Thesis, 30e-6, 0.04, 1e-2, C_fluid);
    const HeldExchange h = hold_exchange(in);
    const double y = held_variable(in.s2);
    const double Re = in.rho * std::sqrt(in.s2) * in.d / in.mu;
    expect_relative("held drag coefficient at s2 vs drag_beta", h.beta(y), drag_beta(in.model, Re, in.mu, in.d), 1e-14);
    expect_relative("held heat factor at s2 vs heat_melt_step", h.expm1_rate(y), exact_expm1_rate(in, in.s2, h.share),
                    1e-6);
    EXPECT_TRUE(h.contains(in.s2));
  }
}

TEST(HeldExchange, LinesWithinToleranceOverTheirWindow)
{
  // slips from rest to Re ~ 2e4 (6 mm) and both sides of the branch at Re = 1000
  for (DragModel model : {DragModel::Thesis, DragModel::SchillerNaumann})
    for (double d : {30e-6, 6e-3})
      for (double C_fluid : {0.0, 1e-9, 1e-3})
        for (double tol : {1e-3, 1e-2})
          for (double s : {0.0, 1e-6, 1e-3, 0.05, 0.5, 1.2, 1.5, 3.0, 30.0}) {
            const auto in = input(model, d, s * s, tol, C_fluid);
            const HeldExchange h = hold_exchange(in);
            ASSERT_TRUE(h.contains(in.s2));
            ASSERT_GE(h.hi, h.lo);
            double worst_beta = 0.0, worst_heat = 0.0;
            for (int k = 0; k <= 64; ++k) {
              const double s2 = h.lo + (std::min(h.hi, 1e6) - h.lo) * k / 64.0;
              const double y = held_variable(s2), Re = in.rho * std::sqrt(s2) * in.d / in.mu;
              worst_beta = std::max(worst_beta, std::abs(h.beta(y) - drag_beta(model, Re, in.mu, in.d)) / h.beta.v0);
              const double e = h.share > 0.0 ? exact_expm1_rate(in, s2, h.share) : 0.0;
              worst_heat = std::max(worst_heat, std::abs(h.expm1_rate(y) - e) / std::abs(h.expm1_rate.v0));
            }
            EXPECT_LE(worst_beta, tol) << "drag, d " << d << " slip " << s << " Cf " << C_fluid;
            // the heat factor's reference goes through heat_melt_step's rounding (1e-6 of it)
            EXPECT_LE(worst_heat, tol + 1e-6) << "heat, d " << d << " slip " << s << " Cf " << C_fluid;
          }
}

TEST(HeldExchange, WindowsAreWideEnoughToHold)
{
  // a 30 um grain falling at 1 m/s through still argon and one jittering at 1 mm/s in a bed:
  // the windows span several per cent of the slip (each re-evaluation costs a drag law, a
  // Nusselt number and an exponential)
  for (double s : {1.0, 1e-3}) {
    const auto in = input(DragModel::Thesis, 30e-6, s * s, 1e-2, 1e-9);
    const HeldExchange h = hold_exchange(in);
    const double width = (std::sqrt(h.hi) - std::sqrt(h.lo)) / s;
    std::printf("slip %g m/s: window %.4g .. %.4g m/s (%.3g of the slip)\n", s, std::sqrt(h.lo), std::sqrt(h.hi),
                width);
    EXPECT_GT(width, 0.05);
  }
}

TEST(HeldExchange, ZeroToleranceIsTheSlipAlone)
{
  const auto in = input(DragModel::Thesis, 30e-6, 0.25, 0.0, 1e-9);
  const HeldExchange h = hold_exchange(in);
  EXPECT_EQ(h.lo, in.s2);
  EXPECT_EQ(h.hi, in.s2);
}

TEST(HeldExchange, BadInputThrows)
{
  auto in = input(DragModel::Thesis, 30e-6, 0.25, 1e-2, 0.0);
  in.mu = 0.0;
  EXPECT_THROW(hold_exchange(in), std::invalid_argument);
  in = input(DragModel::Thesis, 30e-6, -1.0, 1e-2, 0.0);
  EXPECT_THROW(hold_exchange(in), std::invalid_argument);
  in = input(DragModel::Thesis, 30e-6, 0.25, -1e-3, 0.0);
  EXPECT_THROW(hold_exchange(in), std::invalid_argument);
}
