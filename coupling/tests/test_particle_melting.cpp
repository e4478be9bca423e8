// Heating and melting of one particle (Codina2019 eq. 2.3, 2.9, 2.13): exact integration over a
// step, exact bookkeeping, the Codina2019 §2.3 particle.
#include "meltdem/coupling/exact_sum.h"
#include "meltdem/coupling/particle_melting.h"
#include "validation_report.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

using namespace meltdem::coupling;
using meltdem::testing::expect_absolute;
using meltdem::testing::expect_relative;

namespace {
// Codina2019 table 2.3 particle, table 2.2 gas (Nu = 2: particle at rest in the gas)
const MeltMaterial steel{48.35, 1000.0, 0.248611 / 9.069e-7};
const double d0 = 600e-6, rho = 8020.0, m0 = M_PI / 6.0 * rho * d0 * d0 * d0;
const double k_gas = 100.0, T_gas = 1500.0, k_nu = 2.0 * k_gas;
const double tau = rho * steel.cp * d0 * d0 / (6.0 * 2.0 * k_gas);  // m cp / (h A)
}  // namespace

TEST(ParticleMelting, HeatingAtRestIsExactForAnyStep)
{
  // below melting (Tm huge): T(t) = Tf + (T0 - Tf) exp(-t/tau), one step or a thousand
  const MeltMaterial hot{48.35, 1e9, 2.7e5};
  const double t_end = 1.5 * tau, T0 = 300.0;
  for (int nsteps : {1, 7, 1000}) {
    double h = hot.cp * T0, heat = 0.0;
    for (int s = 0; s < nsteps; ++s) {
      const auto r = heat_melt_step(hot, h, m0, d0, k_nu, T_gas, t_end / nsteps);
      heat += r.heat;
      h = r.h;
      EXPECT_EQ(r.m, m0);
    }
    const double T_ref = T_gas + (T0 - T_gas) * std::exp(-t_end / tau);
    expect_relative("T(1.5 tau), " + std::to_string(nsteps) + " steps", particle_temperature(hot, h), T_ref, 1e-12);
    expect_relative("heat absorbed = m cp dT, " + std::to_string(nsteps) + " steps", heat, m0 * hot.cp * (T_ref - T0),
                    1e-11);
  }
}

TEST(ParticleMelting, CoolingRelaxesTowardsFluid)
{
  const double T0 = 900.0, Tf = 400.0, dt = 0.3 * tau;
  const auto r = heat_melt_step(steel, steel.cp * T0, m0, d0, k_nu, Tf, dt);
  expect_relative("cooling T(0.3 tau)", particle_temperature(steel, r.h), Tf + (T0 - Tf) * std::exp(-0.3), 1e-13);
  EXPECT_LT(r.heat, 0.0);
  EXPECT_EQ(r.mass_melted, 0.0);
  EXPECT_EQ(r.m, m0);
}

TEST(ParticleMelting, Thesis23ParticleBooksEverything)
{
  // the Codina2019 §2.3 particle heats from 0 K and melts completely; every step conserves
  // m h + handed-over enthalpy, and the totals match m cp Tm + m L
  const double dt = 1e-6;
  double h = 0.0, m = m0, d = d0;
  ExactSum heat, mass, enthalpy;
  double worst_step = 0.0;
  int steps = 0;
  bool molten = false;
  while (!molten && steps < 100000) {
    const auto r = heat_melt_step(steel, h, m, d, k_nu, T_gas, dt);
    const double before = m * h + r.heat, after = r.m * r.h + r.enthalpy_out;
    worst_step = std::max(worst_step, std::abs(after - before) / (m0 * (steel.cp * steel.Tmelt + steel.latent)));
    heat.add(r.heat);
    mass.add_difference(m, r.m);
    enthalpy.add(r.enthalpy_out);
    h = r.h;
    m = r.m;
    d = r.d;
    molten = r.fully_molten;
    ++steps;
  }
  ASSERT_TRUE(molten);
  EXPECT_EQ(m, 0.0);
  expect_absolute("worst per-step energy balance / (m (cp Tm + L))", worst_step, 0.0, 1e-15);
  expect_relative("heat absorbed vs m cp Tm + m L", heat.value(), m0 * (steel.cp * steel.Tmelt + steel.latent), 1e-12);
  expect_relative("mass handed over vs m0", mass.value(), m0, 1e-16);
  expect_relative("enthalpy handed over vs m (cp Tm + L)", enthalpy.value(),
                  m0 * (steel.cp * steel.Tmelt + steel.latent), 1e-13);
  expect_relative("latent heat = E_latent / m (thesis 0.248611 J / 9.069e-7 kg)", m0 * steel.latent,
                  0.248611 * m0 / 9.069e-7, 1e-15);
  // time to melt: t* = tau ln((Tf - T0)/(Tf - Tm)), then the d^2 law d0^2 rho L / (4 k Nu (Tf - Tm))
  const double t_melt = tau * std::log(T_gas / (T_gas - steel.Tmelt)) +
                        d0 * d0 * rho * steel.latent / (4.0 * k_nu * (T_gas - steel.Tmelt));
  expect_absolute("melt time [s] (resolved to dt)", steps * dt, t_melt, dt);
}

TEST(ParticleMelting, MeltingFollowsD2LawForAnyStep)
{
  const double t_star = tau * std::log(T_gas / (T_gas - steel.Tmelt));
  const double t1 = t_star + 1e-3;
  const double d_ref = std::sqrt(d0 * d0 - 4.0 * k_nu * (T_gas - steel.Tmelt) * 1e-3 / (rho * steel.latent));
  for (int nsteps : {1, 3, 1000}) {
    double h = 0.0, m = m0, d = d0;
    for (int s = 0; s < nsteps; ++s) {
      const auto r = heat_melt_step(steel, h, m, d, k_nu, T_gas, t1 / nsteps);
      h = r.h, m = r.m, d = r.d;
    }
    expect_relative("d(t* + 1 ms), " + std::to_string(nsteps) + " steps", d, d_ref, 1e-12);
    expect_relative("density kept, " + std::to_string(nsteps) + " steps", m / (M_PI / 6.0 * d * d * d), rho, 1e-12);
  }
}

TEST(ParticleMelting, ExactSumTelescopes)
{
  ExactSum s, naive_check;
  double m = 1.0, naive = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double m_new = m * (1.0 - 1.0 / 3.0e4);
    s.add_difference(m, m_new);
    naive += m - m_new;
    m = m_new;
  }
  expect_relative("exact sum of differences = 1 - m_final", s.value(), 1.0 - m, 1e-16);
  EXPECT_NE(naive, 1.0 - m);  // the plain sum drifts: why the ledger uses ExactSum
}

TEST(ParticleMelting, BadInput)
{
  EXPECT_THROW(check_material({0.0, 1000.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(check_material({1.0, -1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(check_material({1.0, 1000.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(specific_enthalpy(steel, 1001.0), std::invalid_argument);
  EXPECT_THROW(specific_enthalpy(steel, -1.0), std::invalid_argument);
  EXPECT_THROW(heat_melt_step(steel, 0.0, 0.0, d0, k_nu, T_gas, 1e-6), std::invalid_argument);
  EXPECT_THROW(heat_melt_step(steel, 0.0, m0, d0, k_nu, T_gas, -1e-6), std::invalid_argument);
  FluidState f;
  f.k = 100.0, f.cp = 5210.928, f.mu = 2.1e-5, f.rho = 1.6115;
  expect_relative("k Nu at Re = 0 (Nu = 2)", ranz_marshall_k_nu(f, 0.0), 200.0, 1e-15);
}

TEST(ParticleMelting, AbsorbHeatKeepsTheBalanceAndMeltsTheExcess)
{
  const MeltMaterial mat{500.0, 1700.0, 2.7e5};
  const double d = 1e-4, m = 7800 * M_PI / 6 * d * d * d, h = 500.0 * 300.0;
  const double half = m * 500 * 1400 + 0.5 * m * 2.7e5;      // to Tm, then half the latent heat
  for (double E : {0.0, 1e-4, m * 500 * 1400, half, 1.0}) {  // nothing, sensible, to Tm, partly, all molten
    const MeltStepResult r = absorb_heat(mat, h, m, d, E);
    EXPECT_NEAR(m * h + E, r.m * r.h + r.enthalpy_out, 1e-15 * (m * h + E)) << "E = " << E;
    EXPECT_EQ(r.heat, E);
    EXPECT_NEAR(r.mass_melted, m - r.m, 1e-25);
    if (E == 1.0) EXPECT_TRUE(r.fully_molten);
    if (E == half) {
      EXPECT_NEAR(r.mass_melted, 0.5 * m, 1e-15 * m);
      EXPECT_NEAR(r.d, d * std::cbrt(r.m / m), 1e-18);
    }
  }
  EXPECT_THROW(absorb_heat(mat, h, m, d, -1.0), std::invalid_argument);
}

TEST(ParticleMelting, ExchangeHeatOfEitherSignKeepsTheBalance)
{
  const MeltMaterial mat{500.0, 1700.0, 2.7e5};
  const double d = 1e-4, m = 7800 * M_PI / 6 * d * d * d, h = 500.0 * 300.0;
  for (double E : {-1e-5, -m * h / 2, 0.0, 1e-4, 1.0}) {
    const MeltStepResult r = exchange_heat(mat, h, m, d, E);
    EXPECT_NEAR(m * h + r.heat, r.m * r.h + r.enthalpy_out, 1e-15 * (m * h + std::abs(E))) << "E = " << E;
    EXPECT_EQ(r.heat, E);
  }
  expect_relative("cooling by half the enthalpy: T",
                  particle_temperature(mat, exchange_heat(mat, h, m, d, -m * h / 2).h), 150.0, 1e-14);
  // never below 0 K: what would take it there is refused (and shows as heat < energy)
  const MeltStepResult cold = exchange_heat(mat, h, m, d, -2 * m * h);
  expect_absolute("cooling past 0 K: h", cold.h, 0.0, 1e-9);
  expect_relative("cooling past 0 K: heat taken = m h", cold.heat, -m * h, 1e-15);
  EXPECT_THROW(exchange_heat(mat, h, m, d, std::nan("")), std::invalid_argument);
}

TEST(ParticleMelting, RelaxationFactorEndsWhereTheRelaxationEnds)
{
  // a particle at T0 against a bath at Tf over a step dt, taking dt G phi(x) (Tf - T0) at
  // once, ends at the exact relaxation Tf + (T0 - Tf) exp(-x), x = dt G / C, for any step
  const double C = 2.0, G = 3.0, T0 = 300.0, Tf = 900.0;
  double worst = 0.0, past = 0.0;
  for (double x : {0.0, 1e-12, 1e-9, 1e-8, 1e-6, 1e-3, 0.1, 1.0, 10.0, 1e3, 1e6}) {
    const double dt = x * C / G;
    const double end = T0 + dt * G * relaxation_factor(x) * (Tf - T0) / C;
    worst = std::max(worst, std::abs(end - (Tf + (T0 - Tf) * std::exp(-x))) / (Tf - T0));
    past = std::max(past, end - Tf);
  }
  expect_absolute("x = 0..1e6: max |T_end - exact relaxation| / (Tf - T0)", worst, 0.0, 1e-15);
  expect_absolute("x = 0..1e6: largest step past the bath [K]", std::max(past, 0.0), 0.0, 0.0);
  EXPECT_THROW(relaxation_factor(-1.0), std::invalid_argument);
}

TEST(ParticleMelting, ConductanceIsKNuPiD)
{
  // at rest Nu = 2 (Codina2019 gas, 600 um: 0.377 W/K); with slip Ranz-Marshall
  FluidState gas;
  gas.k = k_gas;
  gas.rho = 1.6115;
  gas.mu = 2.1e-5;
  gas.cp = 5210.928;
  const double rest[3] = {0.0, 0.0, 0.0};
  expect_relative("G at rest = 2 k pi d [W/K]", particle_conductance(gas, d0, rest), 2.0 * k_gas * M_PI * d0, 1e-14);
  const double v[3] = {0.0, 2.0, 0.0};
  const double Re = gas.rho * 2.0 * d0 / gas.mu;
  const double Pr = gas.cp * gas.mu / gas.k;
  expect_relative("G at 2 m/s slip [W/K]", particle_conductance(gas, d0, v),
                  gas.k * (2.0 + 0.6 * std::sqrt(Re) * std::cbrt(Pr)) * M_PI * d0, 1e-14);
  FluidState none;
  EXPECT_EQ(particle_conductance(none, d0, v), 0.0);
  EXPECT_THROW(particle_conductance(gas, 0.0, v), std::invalid_argument);
}

TEST(ParticleMelting, HeatExchangeTimeIsTheWorstCell)
{
  const double C[4] = {1.0, 2.0, 3.0, 1e-9};
  const double G[4] = {0.5, 4.0, 0.0, -1.0};
  EXPECT_EQ(heat_exchange_time(C, G, 4), 0.5);  // min(1/0.5, 2/4); G <= 0 skipped
  EXPECT_TRUE(std::isinf(heat_exchange_time(C, G + 2, 2)));
}

TEST(ParticleMelting, FrozenFluidStepOverdrawsASmallCell)
{
  // The Codina2019 particle (m cp = 4.4e-5 J/K) in one 0.7 mm gas cell (C = 2.9e-6 J/K, 15x less),
  // no melting (Tm huge), the cell's temperature frozen over each step and updated after it
  // (the explicit coupling). The cell passes below the particle's starting temperature once
  // (1 - exp(-dt/tau_p)) r > 1, r = m cp / C, i.e. dt > tau_p ln(r / (r - 1)) ~ C / G.
  const MeltMaterial hot{48.35, 1e9, 2.7e5};
  const double C = 1.6115 * 5210.928 * std::pow(0.7e-3, 3), mcp = m0 * hot.cp, G = k_nu * M_PI * d0;
  const double r = mcp / C, tau_p = mcp / G, t_cross = tau_p * std::log(r / (r - 1.0));
  const double T_c0 = 1500.0, T_p0 = 300.0, T_eq = (C * T_c0 + mcp * T_p0) / (C + mcp);
  expect_relative("crossing step vs C / G (C << m cp)", t_cross, C / G, 0.05);
  for (double f : {0.5, 0.9, 1.1, 3.0}) {
    double Tc = T_c0, h = hot.cp * T_p0, worst = 0.0;
    for (int s = 0; s < 40; ++s) {
      const double lo = std::min(Tc, h / hot.cp), hi = std::max(Tc, h / hot.cp);
      const auto res = heat_melt_step(hot, h, m0, d0, k_nu, Tc, f * t_cross);
      h = res.h;
      Tc -= res.heat / C;
      worst = std::max(worst, temperature_overshoot(lo, hi, Tc, Tc, 1e-2, true) / (hi - lo + 1e-300));
    }
    const std::string tag = "dt = " + std::to_string(f) + " x crossing step";
    if (f < 1.0) {
      expect_absolute(tag + ": overshoot / range over 40 steps", worst, 0.0, 0.0);
      expect_relative(tag + ": cell relaxes to the equilibrium T [K]", Tc, T_eq, 1e-6);
    } else {
      EXPECT_GT(worst, 0.0) << tag << ": the cell must pass the particle's starting temperature";
    }
  }
}

TEST(ParticleMelting, TwoBodyStepNeverOvershootsForAnyStep)
{
  // the cell of the frozen-fluid test as the parcel of a two-body step: at 0.5 to 1e4 times the
  // crossing step, 40 steps, the cell never leaves [particle, cell] and the pair's energy closes
  const MeltMaterial hot{48.35, 1e9, 2.7e5};
  const double C = 1.6115 * 5210.928 * std::pow(0.7e-3, 3), mcp = m0 * hot.cp, G = k_nu * M_PI * d0;
  const double r = mcp / C, t_cross = mcp / G * std::log(r / (r - 1.0));
  const double T_c0 = 1500.0, T_p0 = 300.0, T_eq = (C * T_c0 + mcp * T_p0) / (C + mcp);
  for (double f : {0.5, 1.1, 3.0, 1e4}) {
    double Tc = T_c0, h = hot.cp * T_p0, worst = 0.0, energy_error = 0.0;
    for (int s = 0; s < 40; ++s) {
      const double lo = std::min(Tc, h / hot.cp), hi = std::max(Tc, h / hot.cp);
      const auto res = heat_melt_step_two_body(hot, h, m0, d0, k_nu, Tc, C, f * t_cross);
      energy_error = std::max(energy_error, std::abs(C * (Tc - res.T_fluid) - res.heat) / (mcp * (T_c0 - T_p0)));
      h = res.h;
      Tc = res.T_fluid;
      worst =
          std::max(worst, temperature_overshoot(lo, hi, std::min(Tc, h / hot.cp), std::max(Tc, h / hot.cp), 0.0, true));
    }
    const std::string tag = "two-body, dt = " + std::to_string(f) + " x crossing step";
    expect_absolute(tag + ": overshoot [K] over 40 steps", worst, 0.0, 0.0);
    expect_absolute(tag + ": |C dT_cell - heat| / (m cp dT0)", energy_error, 0.0, 1e-13);
    expect_relative(tag + ": cell at the equilibrium T [K]", Tc, T_eq, 1e-6);
  }
  // the sensible stage is exact: one step equals a thousand
  double h1 = hot.cp * T_p0, Tc1 = T_c0;
  const auto one = heat_melt_step_two_body(hot, h1, m0, d0, k_nu, Tc1, C, 3.0 * t_cross);
  for (int s = 0; s < 1000; ++s) {
    const auto st = heat_melt_step_two_body(hot, h1, m0, d0, k_nu, Tc1, C, 3.0 * t_cross / 1000);
    h1 = st.h, Tc1 = st.T_fluid;
  }
  expect_relative("two-body: particle T after 3 crossing steps, 1 step vs 1000", one.h / hot.cp, h1 / hot.cp, 1e-12);
}

TEST(ParticleMelting, TwoBodyMeltingIsBoundedByTheParcel)
{
  // the Codina2019 particle in a parcel of 3 x its heat capacity at 2500 K: with an
  // unbounded step it melts exactly what the parcel holds above Tm beyond heating it
  const double mcp = m0 * steel.cp, C = 3.0 * mcp, Tf = 2500.0, T0 = 300.0;
  const auto r = heat_melt_step_two_body(steel, steel.cp * T0, m0, d0, k_nu, Tf, C, 1e3);
  const double sensible = mcp * (steel.Tmelt - T0);
  const double melted_ref = std::min(m0, (C * (Tf - steel.Tmelt) - sensible) / steel.latent);
  expect_relative("two-body, long step: mass melted vs (C (Tf - Tm) - m cp (Tm - T0)) / L", r.mass_melted, melted_ref,
                  1e-9);
  expect_relative("two-body, long step: parcel ends at Tm [K]", r.T_fluid, steel.Tmelt, 1e-9);
  expect_relative("two-body, long step: m h + heat = m' h' + out", m0 * steel.cp * T0 + r.heat,
                  r.m * r.h + r.enthalpy_out, 1e-14);
  // a parcel a million times the particle behaves as the unbounded fluid: the d^2 law
  const double t_star = tau * std::log(T_gas / (T_gas - steel.Tmelt));
  for (int nsteps : {1, 10}) {
    double h = 0.0, m = m0, d = d0;
    for (int s = 0; s < nsteps; ++s) {
      const auto st = heat_melt_step_two_body(steel, h, m, d, k_nu, T_gas, 1e6 * mcp, (t_star + 1e-3) / nsteps);
      h = st.h, m = st.m, d = st.d;
    }
    const double d_ref = std::sqrt(d0 * d0 - 4.0 * k_nu * (T_gas - steel.Tmelt) * 1e-3 / (rho * steel.latent));
    expect_relative("two-body, parcel 1e6 m cp: d(t* + 1 ms) vs d^2 law, " + std::to_string(nsteps) + " steps", d,
                    d_ref, 1e-4);
  }
}

TEST(ParticleMelting, TemperatureOvershoot)
{
  expect_absolute("inside", temperature_overshoot(300, 1500, 300, 1500, 0.0, true), 0.0, 0.0);
  expect_absolute("below by 12 K, 1 % allowance", temperature_overshoot(300, 1500, 276, 1500, 0.01, true),
                  12.0 - 1.5e-6, 1e-12);
  expect_absolute("above by 5 K", temperature_overshoot(300, 1500, 300, 1505, 0.0, true), 5.0 - 1.5e-6, 1e-12);
  expect_absolute("isothermal, round-off", temperature_overshoot(300, 300, 300 - 1e-10, 300 + 1e-10, 0.01, true), 0.0,
                  0.0);
  expect_absolute("above, upper bound off", temperature_overshoot(300, 1500, 300, 1505, 0.0, false), 0.0, 0.0);
  EXPECT_TRUE(std::isinf(temperature_overshoot(300, 1500, NAN, 1500, 0.0, true)));
  EXPECT_THROW(temperature_overshoot(1500, 300, 300, 1500, 0.0, true), std::invalid_argument);
}
