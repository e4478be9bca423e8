// Drag and buoyancy on one particle (Codina2019 eq. 2.14 with the fluid viscosity).
#include "meltdem/coupling/particle_forces.h"
#include "validation_report.h"

#include <cmath>

using namespace meltdem::coupling;
using meltdem::testing::expect_relative;

TEST(ParticleForces, StokesDragAndBuoyancy)
{
  FluidState f;
  f.rho = 1000.0, f.mu = 1e-3, f.U[0] = 0.0, f.U[1] = 0.0, f.U[2] = 1e-9;  // slip 1e-6 m/s
  const double v[3] = {0.0, 0.0, -1.0e-6 + 1e-9}, g[3] = {0.0, 0.0, -9.81}, d = 20e-6;
  for (auto model : {DragModel::Thesis, DragModel::SchillerNaumann}) {
    const auto F = drag_and_buoyancy(model, f, v, d, g);
    const double Re = f.rho * 1e-6 * d / f.mu;
    expect_relative("slip Re", F.Re, Re, 1e-13);
    // Re = 2e-5: Cd Re / 24 = 1 to 2e-4 (Codina2019) / 6e-5 (Schiller-Naumann)
    expect_relative("drag vs Stokes 3 pi mu d U", F.drag[2], 3.0 * M_PI * f.mu * d * 1e-6, 3e-4);
    expect_relative("drag = beta slip", F.drag[2], drag_beta(model, Re, f.mu, d) * 1e-6, 1e-13);
    expect_relative("buoyancy = rho_f V g (up)", F.buoyancy[2], f.rho * M_PI / 6.0 * d * d * d * 9.81, 1e-14);
    EXPECT_EQ(F.drag[0], 0.0);
    EXPECT_EQ(F.buoyancy[0], 0.0);
  }
}

TEST(ParticleForces, Thesis23SlipReynolds)
{
  // Codina2019 §2.3 particle injected at rest into the -2 m/s gas: Re = rho |U| d / mu
  FluidState f;
  f.rho = 1.6115, f.mu = 2.1e-5, f.U[1] = -2.0;
  const double v[3] = {0, 0, 0}, g[3] = {0, 0, 0};
  const auto F = drag_and_buoyancy(DragModel::Thesis, f, v, 600e-6, g);
  expect_relative("Re (thesis 2.3 slip)", F.Re, 92.08571428571429, 1e-13);
  expect_relative("drag = 3/4 m Cd Re mu / (rho_p d^2) U", F.drag[1],
                  0.75 * (M_PI / 6.0 * 8020.0 * 2.16e-10) * drag_coefficient_thesis(F.Re) * F.Re * f.mu /
                      (8020.0 * 3.6e-7) * -2.0,
                  1e-12);
}

// Two-body drag: explicit while a step stays short of the common velocity, at most the impulse
// that brings grain and parcel to it; the parcel never passes the grain that drives it.
TEST(ParticleForces, TwoBodyDragNeverOvershoots)
{
  const double beta = 1e-6, m = 1e-9, dt = 1e-4;  // beta dt / m = 0.1: explicit
  EXPECT_DOUBLE_EQ(two_body_drag_coefficient(beta, m, 0.0, dt), beta);
  EXPECT_DOUBLE_EQ(two_body_drag_coefficient(beta, m, 1e-6, dt), beta);
  // a light parcel (the Fuchs2022 gas in one 10 um cell beside a 20 um grain)
  const double M = 7.43e-15, mg = 3.1e-11, b = 1.4e-7, h = 6e-8;
  const double be = two_body_drag_coefficient(b, mg, M, h);
  const double mu = mg * M / (mg + M);
  meltdem::testing::expect_relative("two-body drag: coefficient for a light parcel = mu/dt", be, mu / h, 1e-14);
  // one step from grain 1 m/s, parcel at rest: both end at the common velocity, momentum kept
  double v = 1.0, U = 0.0;
  const double F = be * (U - v);
  v += F * h / mg;
  U -= F * h / M;
  meltdem::testing::expect_relative("two-body drag: grain and parcel at the common velocity", U, v, 1e-9);
  meltdem::testing::expect_relative("two-body drag: pair momentum", mg * v + M * U, mg * 1.0, 1e-14);
  EXPECT_LE(U, v * (1 + 1e-12));  // the parcel never passes the grain
  // explicit drag would have carried the pair past the common velocity (beta dt > mu)
  EXPECT_GT(b * h / mu, 1.1);
}
