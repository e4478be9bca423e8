#pragma once
// A particle's drag and heat-step coefficients held over the DEM sub-steps of a coupling
// interval, while the fluid it sees is frozen. Both depend on the step only through the slip
// speed s = |U_f - v| (and the particle's size and mass, and dt). They are evaluated once as
// straight lines in y = s^(1/2), in which the Nusselt number 2 + 0.6 Re^(1/2) Pr^(1/3) is exactly
// linear and the drag law Cd Re is smooth from rest, and the lines are used while s^2 stays in a
// window where both are within a relative tolerance of the exact laws. Per sub-step a particle
// then pays a window check, two square roots and a few multiply-adds instead of a drag law, a
// Nusselt correlation and an exponential.
#include "meltdem/coupling/drag.h"

#include <cmath>

namespace meltdem::coupling {

// v0 + slope (y - y0), y = s^(1/2)
struct HeldLine {
  double y0 = 0.0, v0 = 0.0, slope = 0.0;
  double operator()(double y) const { return v0 + slope * (y - y0); }
};

// y = s^(1/2) from the squared slip speed s2
inline double held_variable(double s2)
{
  return std::sqrt(std::sqrt(s2));
}

struct HeldExchangeInput {
  DragModel model = DragModel::Thesis;
  double rho = 0.0, mu = 0.0, k = 0.0, cp = 0.0;  // fluid; k = 0: no heat exchange
  double C_fluid = 0.0;                           // parcel heat capacity [J/K] (<= 0: unbounded)
  double d = 0.0, m = 0.0, cp_particle = 0.0;     // particle
  double dt = 0.0;
  double s2 = 0.0;   // squared slip speed now
  double tol = 0.0;  // relative tolerance of the held lines (0: the exact values at s2 only)
};

struct HeldExchange {
  double lo = 0.0, hi = 0.0;  // the window of s^2
  // drag coefficient beta [kg/s] of F = beta (U_f - v) (Cd Re / 24 * 3 pi mu d)
  HeldLine beta;
  // heat step: after dt the particle's temperature is T - share (T_f - T) expm1_rate, with
  // expm1_rate at y0 exactly heat_melt_step(_two_body)'s sensible-stage factor; share =
  // C_f / (C_p + C_f), 1 for an unbounded fluid, 0 without heat exchange
  HeldLine expm1_rate;
  double share = 0.0;
  bool contains(double s2) const { return s2 >= lo && s2 <= hi; }
};

// The coefficients at in.s2 and a window around it over which beta and expm1_rate as lines are
// within in.tol of the exact laws (relative to their values at in.s2), from bounds on the
// laws' second derivatives in y (at most y0 / 2 either side).
HeldExchange hold_exchange(const HeldExchangeInput &in);

}  // namespace meltdem::coupling
