#include "meltdem/coupling/hertz_restitution.h"

#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

namespace {

struct State {
  double x, v;
};

State rhs(const State &s, double alpha)
{
  // overlap may dip marginally below 0 inside an RK stage: clamp for the powers
  const double xp = s.x > 0.0 ? s.x : 0.0;
  return {s.v, -xp * std::sqrt(xp) - alpha * std::sqrt(std::sqrt(xp)) * s.v};
}

}  // namespace

double restitution_for_alpha(double alpha)
{
  if (!(alpha >= 0.0) || !std::isfinite(alpha))
    throw std::invalid_argument("restitution_for_alpha: alpha must be finite and >= 0");
  const double h = 2.0e-4;  // undamped contact lasts ~3.2 in tau
  State s{0.0, 1.0};
  for (long n = 0; n < 10000000L; ++n) {
    const State k1 = rhs(s, alpha);
    const State k2 = rhs({s.x + 0.5 * h * k1.x, s.v + 0.5 * h * k1.v}, alpha);
    const State k3 = rhs({s.x + 0.5 * h * k2.x, s.v + 0.5 * h * k2.v}, alpha);
    const State k4 = rhs({s.x + h * k3.x, s.v + h * k3.v}, alpha);
    const State s1{s.x + h / 6.0 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x),
                   s.v + h / 6.0 * (k1.v + 2 * k2.v + 2 * k3.v + k4.v)};
    if (s1.x <= 0.0 && n > 0) {
      // end of contact inside [0, h]: cubic Hermite on x, then bisect for x = 0
      double lo = 0.0, hi = 1.0;
      auto xh = [&](double t) {
        const double t2 = t * t, t3 = t2 * t;
        return (2 * t3 - 3 * t2 + 1) * s.x + (t3 - 2 * t2 + t) * h * s.v + (-2 * t3 + 3 * t2) * s1.x +
               (t3 - t2) * h * s1.v;
      };
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (xh(mid) > 0.0)
          lo = mid;
        else
          hi = mid;
      }
      const double t = 0.5 * (lo + hi);
      // velocity by Hermite derivative
      const double t2 = t * t;
      const double v = ((6 * t2 - 6 * t) * s.x + (3 * t2 - 4 * t + 1) * h * s.v + (-6 * t2 + 6 * t) * s1.x +
                        (3 * t2 - 2 * t) * h * s1.v) /
                       h;
      return -v;
    }
    s = s1;
  }
  // never separated within tau = 2e3 (extremely over-damped): treat as sticking
  return 0.0;
}

double alpha_for_restitution(double e)
{
  if (!(e > 0.0 && e <= 1.0)) throw std::invalid_argument("alpha_for_restitution: e must lie in (0, 1]");
  if (e == 1.0) return 0.0;
  double lo = 0.0, hi = 1.0;
  while (restitution_for_alpha(hi) > e) {
    hi *= 2.0;
    if (hi > 1e3) throw std::invalid_argument("alpha_for_restitution: e too small");
  }
  // e(alpha) decreases monotonically
  for (int it = 0; it < 60 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (restitution_for_alpha(mid) > e)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace meltdem::coupling
