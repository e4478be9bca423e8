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

constexpr int mean_phases = 16;

// where coordinate s (in node spacings, clamped to [0, nodes - 1]) lies on a grid of nodes: the
// lower node of its interval and its weight on the upper one
struct GridPosition {
  int node;
  double weight;
};

GridPosition grid_position(double s, int nodes)
{
  const int k = std::min((int)s, nodes - 2);
  return {k, s - k};
}

// the contact starts this step: it overlaps now and did not at the step's start
bool contact_starts(double delta, double delta_prev)
{
  return delta > 0.0 && delta_prev <= 0.0;
}

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

double onset_phase(double delta, double delta_prev)
{
  return -delta_prev / (delta - delta_prev);
}

double stepped_onset_force(double onset_ratio, double meff, double delta, double separation_rate, double dt)
{
  if (!contact_starts(delta, delta + dt * separation_rate)) return 0.0;
  // the force's impulse dt reaches the velocity in two half kicks, as every other force's
  return -meff * (1.0 - onset_ratio) * separation_rate / dt;
}

double restitution_at_step(double alpha, double h, double phase, double onset_ratio)
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
    a = (x > 0.0 ? -x * std::sqrt(x) : 0.0) - stepped_damping_force(alpha, 1.0, 1.0, x, x_prev, h) -
        stepped_onset_force(onset_ratio, 1.0, x, -v, h);
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
  for (int k = 0; k < mean_phases; ++k) sum += restitution_at_step(alpha, h, (k + 0.5) / mean_phases);
  return sum / mean_phases;
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

double onset_ratio_for_restitution(double e, double alpha, double h, double phase)
{
  // the rebound grows with the approach speed kept, nearly in proportion: secant steps from
  // r = 1 and e / e(1), bisection in [0.5, 1.5] if they leave it
  auto miss = [&](double r) { return restitution_at_step(alpha, h, phase, r) - e; };
  double r0 = 1.0, f0 = miss(r0);
  double r1 = e / (f0 + e), f1 = miss(r1);
  for (int it = 0; it < 30 && std::fabs(f1) > 1e-11 * e; ++it) {
    if (f1 == f0 || !(r1 > 0.5 && r1 < 1.5)) break;
    const double r2 = r1 - f1 * (r1 - r0) / (f1 - f0);
    r0 = r1;
    f0 = f1;
    r1 = r2;
    f1 = miss(r1);
  }
  if (r1 > 0.5 && r1 < 1.5 && std::fabs(f1) <= 1e-9 * e) return r1;
  double lo = 0.5, hi = 1.5;
  if (!(miss(lo) < 0.0)) return lo;
  if (!(miss(hi) > 0.0)) return hi;
  for (int it = 0; it < 60 && hi - lo > 1e-12; ++it) {
    const double mid = 0.5 * (lo + hi);
    (miss(mid) < 0.0 ? lo : hi) = mid;
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

const double *SteppedAlphaTable::ratios(int k, int j) const
{
  std::vector<double> &r = ratio_[k * ratio_nodes + j];
  if (r.empty()) {
    const double h_contact = 1.0 / (1.0 + ratio_spacing * j), a = ratio_node_alpha(k);
    r.resize(phases + 1);
    // (phase 1 is not phase 0: the onset force then acts a step earlier, at a vanishing overlap)
    for (int p = 0; p <= phases; ++p)
      r[p] = onset_ratio_for_restitution(e_, a, h_contact, p < phases ? double(p) / phases : 1.0 - 1e-9);
  }
  return r.data();
}

double SteppedAlphaTable::alpha(double h) const
{
  const GridPosition g = grid_position(std::clamp(h / max_contact_step, 0.0, 1.0) * (points - 1), points);
  return (1.0 - g.weight) * node(g.node) + g.weight * node(g.node + 1);
}

double SteppedAlphaTable::ratio_node_alpha(int k) const
{
  return alpha(max_contact_step * k / (ratio_points - 1));
}

double SteppedAlphaTable::node_ratio(int k, double h_contact, double phase) const
{
  const double s = (std::max(1.0, 1.0 / h_contact) - 1.0) / ratio_spacing;
  if (s >= ratio_nodes - 1) {
    // finer steps: a phase scatter below 0.05 %; e over the phase-mean e of the node's alpha
    const double h_fine = 1.0 / (1.0 + ratio_spacing * (ratio_nodes - 1));
    if (!fine_known_[k]) {
      const double a = ratio_node_alpha(k);
      for (int j = 0; j < fine_points; ++j)
        fine_mean_[k][j] =
            j == 0 ? restitution_for_alpha(a) : mean_restitution_at_step(a, h_fine * j / (fine_points - 1));
      fine_known_[k] = true;
    }
    // the ratio also scales the contact's step (h ~ v^(1/5)): three fixed-point passes
    double ratio = 1.0;
    for (int pass = 0; pass < 3; ++pass) {
      const GridPosition g =
          grid_position(std::min(h_contact * std::pow(ratio, 0.2) / h_fine, 1.0) * (fine_points - 1), fine_points);
      ratio = e_ / ((1.0 - g.weight) * fine_mean_[k][g.node] + g.weight * fine_mean_[k][g.node + 1]);
    }
    return ratio;
  }
  const GridPosition a = grid_position(s, ratio_nodes);                                    // of 1/h_a
  const GridPosition b = grid_position(std::clamp(phase, 0.0, 1.0) * phases, phases + 1);  // of the phase
  const double *lo = ratios(k, a.node), *hi = ratios(k, a.node + 1);
  const double u = b.weight;
  const int p = b.node;
  return (1.0 - a.weight) * ((1.0 - u) * lo[p] + u * lo[p + 1]) + a.weight * ((1.0 - u) * hi[p] + u * hi[p + 1]);
}

double SteppedAlphaTable::onset_ratio(double h, double h_contact, double phase) const
{
  if (e_ <= 0.0 || !(h > 0.0) || !(h_contact > 0.0)) return 1.0;
  const GridPosition g = grid_position(std::clamp(h / max_contact_step, 0.0, 1.0) * (ratio_points - 1), ratio_points);
  return (1.0 - g.weight) * node_ratio(g.node, h_contact, phase) +
         (g.weight > 0.0 ? g.weight * node_ratio(g.node + 1, h_contact, phase) : 0.0);
}

double SteppedAlphaTable::correction(double h, double alpha_stock, double hertz_k, double meff, double delta,
                                     double separation_rate, double dt) const
{
  double fn = stepped_damping_correction(alpha(h), alpha_stock, hertz_k, meff, delta, separation_rate, dt);
  const double delta_prev = delta + dt * separation_rate;
  if (contact_starts(delta, delta_prev)) {
    const double h_contact = contact_step(dt, -separation_rate, hertz_k, meff);
    fn += stepped_onset_force(onset_ratio(h, h_contact, onset_phase(delta, delta_prev)), meff, delta, separation_rate,
                              dt);
  }
  return fn;
}

}  // namespace meltdem::coupling
