#include "meltdem/coupling/particle_melting.h"

#include "meltdem/coupling/heat_transfer.h"
#include "meltdem/coupling/particle_forces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace meltdem::coupling {

void check_material(const MeltMaterial &mat)
{
  if (!(mat.cp > 0.0)) throw std::invalid_argument("melting needs cp > 0");
  if (!(mat.Tmelt > 0.0)) throw std::invalid_argument("melting needs Tmelt > 0");
  if (!(mat.latent > 0.0)) throw std::invalid_argument("melting needs latent heat > 0");
}

double particle_temperature(const MeltMaterial &mat, double h)
{
  return std::min(h, mat.cp * mat.Tmelt) / mat.cp;
}

double specific_enthalpy(const MeltMaterial &mat, double T)
{
  if (!(T >= 0.0) || !(T <= mat.Tmelt)) throw std::invalid_argument("particle temperature must lie in [0, Tmelt]");
  return mat.cp * T;
}

double ranz_marshall_k_nu(const FluidState &fluid, double Re)
{
  return fluid.k * ranz_marshall_nusselt(Re, prandtl_number(fluid.cp, fluid.mu, fluid.k));
}

namespace {

// a step that changes nothing yet: the particle as it is, its enthalpy capped at melting
MeltStepResult unchanged(double h, double m, double d, double hm)
{
  MeltStepResult r;
  r.h = std::min(h, hm);
  r.m = m;
  r.d = d;
  return r;
}

}  // namespace

MeltStepResult heat_melt_step(const MeltMaterial &mat, double h, double m, double d, double k_nu, double T_fluid,
                              double dt)
{
  check_material(mat);
  if (!(m > 0.0) || !(d > 0.0)) throw std::invalid_argument("heat_melt_step needs m > 0, d > 0");
  if (!(k_nu >= 0.0) || !(dt >= 0.0)) throw std::invalid_argument("heat_melt_step needs k Nu >= 0, dt >= 0");

  const double hm = mat.cp * mat.Tmelt;
  MeltStepResult r = unchanged(h, m, d, hm);
  if (k_nu == 0.0 || dt == 0.0) return r;

  const double G = k_nu * M_PI * d;  // h_conv A [W/K]
  const bool melts = T_fluid > mat.Tmelt;
  double t_left = dt;

  if (!(r.h >= hm && melts)) {
    // sensible stage: T(t) = Tf + (T - Tf) exp(-t/tau), until T reaches Tm (if Tf > Tm)
    const double T = r.h / mat.cp;
    const double tau = m * mat.cp / G;
    double h_new;
    if (melts && tau * std::log((T_fluid - T) / (T_fluid - mat.Tmelt)) < dt) {
      t_left = dt - tau * std::log((T_fluid - T) / (T_fluid - mat.Tmelt));
      h_new = hm;
    } else {
      t_left = 0.0;
      // expm1 keeps the tiny increments of small dt / tau accurate
      h_new = std::min(mat.cp * (T - (T_fluid - T) * std::expm1(-dt / tau)), hm);
    }
    r.heat = m * (h_new - r.h);  // exactly the enthalpy change
    r.h = h_new;
  }

  if (t_left > 0.0 && r.h >= hm && melts) {
    // melting stage at T = Tm: d(d^2)/dt = -4 k Nu (Tf - Tm) / (rho L)
    const double rho = m / (M_PI / 6.0 * d * d * d);
    const double d2 = d * d - 4.0 * k_nu * (T_fluid - mat.Tmelt) * t_left / (rho * mat.latent);
    double m_new = 0.0;
    if (d2 > 0.0) {
      r.d = std::sqrt(d2);
      const double ratio = r.d / d;
      m_new = m * ratio * ratio * ratio;  // constant density
    }
    if (!(m_new > 0.0)) {
      m_new = 0.0;
      r.d = 0.0;
      r.fully_molten = true;
    }
    r.mass_melted = m - m_new;
    r.m = m_new;
    r.heat += r.mass_melted * mat.latent;
    r.enthalpy_out = r.mass_melted * (hm + mat.latent);
  }
  return r;
}

MeltStepResult heat_melt_step_two_body(const MeltMaterial &mat, double h, double m, double d, double k_nu,
                                       double T_fluid, double C_fluid, double dt)
{
  if (!(C_fluid > 0.0)) {
    MeltStepResult r = heat_melt_step(mat, h, m, d, k_nu, T_fluid, dt);
    r.T_fluid = T_fluid;
    return r;
  }
  check_material(mat);
  if (!(m > 0.0) || !(d > 0.0)) throw std::invalid_argument("heat_melt_step needs m > 0, d > 0");
  if (!(k_nu >= 0.0) || !(dt >= 0.0)) throw std::invalid_argument("heat_melt_step needs k Nu >= 0, dt >= 0");
  if (!std::isfinite(C_fluid)) throw std::invalid_argument("heat_melt_step needs a finite fluid heat capacity");

  const double hm = mat.cp * mat.Tmelt;
  MeltStepResult r = unchanged(h, m, d, hm);
  r.T_fluid = T_fluid;
  if (k_nu == 0.0 || dt == 0.0) return r;

  double t_left = dt;
  const double T = r.h / mat.cp;
  if (!(r.h >= hm && T_fluid > mat.Tmelt)) {
    // sensible stage: the particle gains the share C_f / (C_p + C_f) of the difference at equilibrium
    const double Cp = m * mat.cp, G = k_nu * M_PI * d;
    const double rate = G * (1.0 / Cp + 1.0 / C_fluid);
    const double D0 = T_fluid - T, gain = C_fluid / (Cp + C_fluid) * D0;
    double h_new;
    const double f = gain > 0.0 ? (mat.Tmelt - T) / gain : 2.0;  // fraction of the way that reaches Tm
    if (f < 1.0 && -std::log1p(-f) / rate < dt) {
      t_left = dt + std::log1p(-f) / rate;
      h_new = hm;
    } else {
      t_left = 0.0;
      h_new = std::min(mat.cp * (T - gain * std::expm1(-rate * dt)), hm);
    }
    r.heat = m * (h_new - r.h);  // exactly the enthalpy change
    r.h = h_new;
  }

  // melting stage: the particle at Tm, every joule it takes melts mass
  if (t_left > 0.0 && r.h >= hm && T_fluid - r.heat / C_fluid > mat.Tmelt) {
    const double rho = m / (M_PI / 6.0 * d * d * d);
    double theta = T_fluid - r.heat / C_fluid - mat.Tmelt, m_now = m, d_now = d;
    for (int piece = 0; t_left > 0.0 && theta > 0.0; ++piece) {
      const double cap = 0.03 * m_now * mat.latent;  // at most 3 % of the mass per piece
      double tau = t_left;
      auto heat_in = [&](double G, double t) { return -C_fluid * theta * std::expm1(-G * t / C_fluid); };
      if (C_fluid * theta > cap && piece < 1000) {
        const double G0 = k_nu * M_PI * d_now;
        tau = std::min(t_left, -C_fluid / G0 * std::log1p(-cap / (C_fluid * theta)));
      }
      // G at the mid diameter of the piece (predicted with the start diameter)
      const double m_pred = std::max(0.0, m_now - heat_in(k_nu * M_PI * d_now, tau) / mat.latent);
      const double d_mid = 0.5 * (d_now + d_now * std::cbrt(m_pred / m_now));
      double Q = heat_in(k_nu * M_PI * d_mid, tau);
      if (Q >= m_now * mat.latent) {
        m_now = 0.0;
        break;
      }
      theta -= Q / C_fluid;
      m_now -= Q / mat.latent;
      d_now = std::cbrt(m_now / (rho * M_PI / 6.0));
      t_left -= tau;
    }
    double m_new = m_now;
    if (!(m_new > 0.0)) {
      m_new = 0.0;
      r.d = 0.0;
      r.fully_molten = true;
    } else {
      r.d = d_now;
    }
    r.mass_melted = m - m_new;
    r.m = m_new;
    r.heat += r.mass_melted * mat.latent;
    r.enthalpy_out = r.mass_melted * (hm + mat.latent);
  }
  // the parcel lost what the particle took
  r.T_fluid = T_fluid - r.heat / C_fluid;
  return r;
}

MeltStepResult absorb_heat(const MeltMaterial &mat, double h, double m, double d, double energy)
{
  check_material(mat);
  if (!(m > 0.0) || !(d > 0.0)) throw std::invalid_argument("absorb_heat needs m > 0, d > 0");
  if (!(energy >= 0.0)) throw std::invalid_argument("absorb_heat needs energy >= 0");
  const double hm = mat.cp * mat.Tmelt;
  MeltStepResult r = unchanged(h, m, d, hm);
  r.heat = energy;
  const double sensible = std::min(energy, m * (hm - r.h));
  r.h += sensible / m;
  const double left = energy - sensible;
  if (left <= 0.0) return r;
  const double melted = std::min(m, left / mat.latent);
  r.mass_melted = melted;
  r.m = m - melted;
  if (melted >= m || !(r.m > 0.0)) {
    r.m = 0.0;
    r.d = 0.0;
    r.fully_molten = true;
    r.mass_melted = m;
    // everything the particle held plus the energy goes with the melt
    r.enthalpy_out = m * h + energy;
    r.h = hm;
    return r;
  }
  r.d = d * std::cbrt(r.m / m);
  r.enthalpy_out = melted * (hm + mat.latent);
  // the identity m h + energy = m' h' + out, exactly up to rounding
  return r;
}

MeltStepResult exchange_heat(const MeltMaterial &mat, double h, double m, double d, double energy)
{
  if (!std::isfinite(energy)) throw std::invalid_argument("exchange_heat needs a finite energy");
  if (energy >= 0.0) return absorb_heat(mat, h, m, d, energy);
  check_material(mat);
  if (!(m > 0.0) || !(d > 0.0)) throw std::invalid_argument("exchange_heat needs m > 0, d > 0");
  const double hm = mat.cp * mat.Tmelt;
  MeltStepResult r = unchanged(h, m, d, hm);
  r.heat = std::max(energy, -m * r.h);
  r.h += r.heat / m;
  return r;
}

double relaxation_factor(double x)
{
  if (!(x >= 0.0)) throw std::invalid_argument("relaxation_factor needs x >= 0");
  return x < 1e-8 ? 1.0 - 0.5 * x : -std::expm1(-x) / x;
}

double particle_conductance(const FluidState &fluid, double d, const double v[3])
{
  if (!(d > 0.0)) throw std::invalid_argument("particle_conductance needs d > 0");
  if (!(fluid.k > 0.0)) return 0.0;  // no fluid, no exchange
  // without viscosity or heat capacity there is no Prandtl number: conduction only (Nu = 2)
  if (!(fluid.mu > 0.0) || !(fluid.cp > 0.0)) return 2.0 * fluid.k * M_PI * d;
  return ranz_marshall_k_nu(fluid, slip_reynolds(fluid, v, d)) * M_PI * d;
}

double heat_exchange_time(const double *C, const double *G, std::size_t n)
{
  double t = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i)
    if (G[i] > 0.0) t = std::min(t, C[i] / G[i]);
  return t;
}

double temperature_overshoot(double lo, double hi, double Tmin, double Tmax, double tol, bool upper)
{
  if (!(hi >= lo) || !(tol >= 0.0)) throw std::invalid_argument("temperature_overshoot needs lo <= hi, tol >= 0");
  // NaN is out of any range
  if (std::isnan(Tmin) || std::isnan(Tmax)) return std::numeric_limits<double>::infinity();
  // plus 1e-9 of the level: round-off and solver tolerance where the range is empty (isothermal)
  const double allow = tol * (hi - lo) + 1e-9 * std::max(std::fabs(lo), std::fabs(hi));
  double out = std::max(0.0, lo - allow - Tmin);
  if (upper) out = std::max(out, Tmax - hi - allow);
  return out;
}

}  // namespace meltdem::coupling
