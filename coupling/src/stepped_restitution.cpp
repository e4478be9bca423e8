#include "meltdem/coupling/stepped_restitution.h"

#include "meltdem/coupling/hertz_restitution.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace meltdem::coupling {

namespace {

// 4/5 x^(5/4) for x > 0, else 0: the damping's integral per unit alpha sqrt(m* K)
double damping_integral(double x)
{
  return x > 0.0 ? 0.8 * x * std::sqrt(std::sqrt(x)) : 0.0;
}

constexpr int phases = 16;

}  // namespace

double contact_step(double dt, double impact_speed, double hertz_k, double meff)
{
  return contact_step(dt * std::pow(impact_speed, 0.2), hertz_k, meff);
}

double contact_step(double dt_speed_factor, double hertz_k, double meff)
{
  return dt_speed_factor * std::pow(hertz_k / meff, 0.4);
}

double stepped_damping_force(double alpha, double hertz_k, double meff, double delta, double delta_prev, double dt)
{
  return alpha * std::sqrt(meff * hertz_k) * (damping_integral(delta) - damping_integral(delta_prev)) / dt;
}

double stepped_damping_correction(double alpha, double alpha_stock, double hertz_k, double meff, double delta,
                                  double separation_rate, double dt)
{
  double fn = stepped_damping_force(alpha, hertz_k, meff, delta, delta + dt * separation_rate, dt);
  if (delta > 0.0) fn += alpha_stock * std::sqrt(meff * hertz_k * std::sqrt(delta)) * separation_rate;
  return fn;
}

double restitution_at_step(double alpha, double h, double phase)
{
  // the pair style's loop in dimensionless form (m* = K = v0 = 1): kick, drift, force, kick
  double x = -phase * h, v = 1.0, a = 0.0;
  bool touched = false;
  // an over-damped contact creeps back to x = 0 without separating: stop after 60 elastic
  // contact times (3.22 each) and return its remaining speed (e ~ 0)
  const long limit = 2 + (long)(200.0 / h);
  for (long n = 0; n < limit; ++n) {
    v += 0.5 * h * a;
    x += h * v;
    const double x_prev = x - h * v;
    a = (x > 0.0 ? -x * std::sqrt(x) : 0.0) - stepped_damping_force(alpha, 1.0, 1.0, x, x_prev, h);
    v += 0.5 * h * a;
    if (x > 0.0)
      touched = true;
    else if (touched && x_prev <= 0.0)
      return -v;  // no force acted this step: free flight
  }
  return -v;
}

double mean_restitution_at_step(double alpha, double h)
{
  double sum = 0.0;
  for (int k = 0; k < phases; ++k) sum += restitution_at_step(alpha, h, (k + 0.5) / phases);
  return sum / phases;
}

double alpha_for_restitution_at_step(double e, double h)
{
  if (!(e > 0.0 && e <= 1.0)) throw std::invalid_argument("alpha_for_restitution_at_step: e must lie in (0, 1]");
  if (!(h >= 0.0 && h <= max_contact_step))
    throw std::invalid_argument("alpha_for_restitution_at_step: h must lie in [0, max_contact_step]");
  if (h == 0.0) return alpha_for_restitution(e);
  // e(alpha) decreases with alpha; the stepped contact needs less alpha than the continuous
  double lo = 0.0, hi = 1.5 * alpha_for_restitution(e) + 0.1;
  const double e_lo = mean_restitution_at_step(lo, h);
  if (e >= e_lo) return 0.0;  // the elastic step already loses more than asked: no damping
  while (mean_restitution_at_step(hi, h) > e) {
    hi *= 1.5;
    if (hi > 10.0) throw std::invalid_argument("alpha_for_restitution_at_step: e too small for this step");
  }
  for (int it = 0; it < 60 && hi - lo > 1e-10 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mean_restitution_at_step(mid, h) > e)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

SteppedAlphaTable::SteppedAlphaTable(double e, double alpha_continuous) : e_(e)
{
  if (alpha_continuous >= 0.0) {
    alpha_[0] = alpha_continuous;
    known_[0] = true;
  }
}

double SteppedAlphaTable::node(int k) const
{
  if (!known_[k]) {
    try {
      alpha_[k] = alpha_for_restitution_at_step(e_, max_contact_step * k / (points - 1));
    } catch (const std::invalid_argument &) {
      alpha_[k] = node(k - 1);  // k > 0: h = 0 always has an alpha
    }
    known_[k] = true;
  }
  return alpha_[k];
}

double SteppedAlphaTable::alpha(double h) const
{
  const double s = std::clamp(h / max_contact_step, 0.0, 1.0) * (points - 1);
  const int k = std::min((int)s, points - 2);
  const double w = s - k;
  return (1.0 - w) * node(k) + w * node(k + 1);
}

}  // namespace meltdem::coupling
