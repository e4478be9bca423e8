#include "meltdem/coupling/held_exchange.h"

#include "meltdem/coupling/heat_transfer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

namespace {
constexpr double kBranchRe = 1000.0;  // both drag laws switch to a constant Cd above it

// the laws as functions of y = s^(1/2): Re = a y^2, Nu = 2 + b sqrt(Re)
struct Laws {
  const HeldExchangeInput &in;
  double a, b;
  bool heat;

  double re(double y) const { return a * y * y; }
  double beta(double y) const { return drag_beta(in.model, re(y), in.mu, in.d); }
  // the heat step's factor: the expressions of heat_melt_step(_two_body)
  double expm1_rate(double y) const
  {
    if (!heat) return 0.0;
    const double G = in.k * (2.0 + b * std::sqrt(re(y))) * M_PI * in.d;
    if (in.C_fluid > 0.0) {
      const double Cp = in.m * in.cp_particle;
      return std::expm1(-(G * (1.0 / Cp + 1.0 / in.C_fluid)) * in.dt);
    }
    return std::expm1(-in.dt / (in.m * in.cp_particle / G));
  }
  // the heat step's exponent per unit Nusselt number
  double per_nu() const
  {
    const double Cp = in.m * in.cp_particle;
    return in.k * M_PI * in.d * (in.C_fluid > 0.0 ? 1.0 / Cp + 1.0 / in.C_fluid : 1.0 / Cp) * in.dt;
  }
};
}  // namespace

HeldExchange hold_exchange(const HeldExchangeInput &in)
{
  if (!(in.rho >= 0.0) || !(in.mu > 0.0) || !(in.d > 0.0) || !(in.m > 0.0) || !(in.dt >= 0.0) || !(in.s2 >= 0.0) ||
      !(in.tol >= 0.0) || !(in.k >= 0.0))
    throw std::invalid_argument("hold_exchange needs rho, k, dt, slip^2, tol >= 0 and mu, d, m > 0");
  const bool heat = in.k > 0.0;
  if (heat && (!(in.cp > 0.0) || !(in.cp_particle > 0.0)))
    throw std::invalid_argument("hold_exchange with heat needs fluid and particle cp > 0");
  const Laws laws{in, in.rho * in.d / in.mu, heat ? 0.6 * std::cbrt(prandtl_number(in.cp, in.mu, in.k)) : 0.0, heat};

  HeldExchange h;
  h.share = !heat ? 0.0 : in.C_fluid > 0.0 ? in.C_fluid / (in.m * in.cp_particle + in.C_fluid) : 1.0;
  const double y0 = held_variable(in.s2);
  h.beta.y0 = h.expm1_rate.y0 = y0;
  h.beta.v0 = laws.beta(y0);
  h.expm1_rate.v0 = laws.expm1_rate(y0);
  h.lo = h.hi = in.s2;
  if (in.tol == 0.0) return h;
  if (laws.a == 0.0) {
    // no fluid density: neither law depends on the slip
    h.lo = 0.0;
    h.hi = HUGE_VAL;
    return h;
  }
  // Cd Re = A + B y^p (Re is a y^2: p = 4/3 thesis, 2 x 0.687 Schiller-Naumann, 2 above the
  // branch where A = 0): its slope p B y^(p-1). Over a half width w = r y0 with r <= 1/2 the
  // tangent's error is at most max |f''| w^2 / 2 with f'' = p (p - 1) B y^(p-2), largest at
  // y0 - w for p < 2: (1 - r)^(p-2) <= 2^(2-p) < 2, so it is below p (p - 1) B y0^p r^2. From
  // rest the constant's error is B w^p. Both held within tol Cd Re.
  const double Re = laws.re(y0);
  const bool high = Re > kBranchRe;
  const bool thesis = in.model == DragModel::Thesis;
  const double p = high ? 2.0 : thesis ? 4.0 / 3.0 : 2.0 * 0.687;
  const double per_cd = 3.0 * M_PI * in.mu * in.d / 24.0;  // beta / (Cd Re)
  const double cd = h.beta.v0 / per_cd, rising = high ? cd : cd - 24.0;
  double w;
  if (y0 > 0.0 && rising > 0.0) {
    h.beta.slope = per_cd * p * rising / y0;
    w = y0 * std::min(0.5, std::sqrt(in.tol * cd / (p * (p - 1.0) * rising)));
  } else {
    // from rest: B w^p <= tol A with B = 4 a^(2/3) (thesis) or 3.6 a^0.687 (Schiller-Naumann)
    w = 0.999 * std::sqrt((thesis ? std::pow(6.0 * in.tol, 1.5) : std::pow(in.tol / 0.15, 1.0 / 0.687)) / laws.a);
  }
  if (heat) {
    // expm1(-c N), N = 2 + b sqrt(a) y: slope -(1 + e1) c b sqrt(a); |second derivative| <=
    // (c b sqrt(a))^2, so the line's error over w is at most (c b sqrt(a) w)^2 / 2
    const double e1 = h.expm1_rate.v0, cb = laws.per_nu() * laws.b * std::sqrt(laws.a);
    h.expm1_rate.slope = -(1.0 + e1) * cb;
    if (cb > 0.0) w = std::min(w, std::sqrt(2.0 * in.tol * std::abs(e1)) / cb);
  }
  double lo = std::max(0.0, y0 - w), hi = y0 + w;
  const double branch = std::sqrt(kBranchRe / laws.a);  // y at the branch
  if (!high)
    hi = std::min(hi, branch);
  else
    lo = std::max(lo, branch * (1.0 + 1e-12));
  // the window of s^2 (holding s2 itself whatever the rounding)
  h.lo = std::min(in.s2, lo * lo * (lo * lo));
  h.hi = std::max(in.s2, hi * hi * (hi * hi));
  return h;
}

}  // namespace meltdem::coupling
