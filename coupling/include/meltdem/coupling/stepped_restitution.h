#pragma once
// The Hertz contact with Tsuji damping as a time-stepped run integrates it, and the
// damping coefficient alpha that returns a prescribed restitution at that step.
//
// LAMMPS's velocity-Verlet evaluates the force at x(n) with the half-step velocity
// v(n-1/2), so the stock damping alpha sqrt(m* K) delta^(1/4) v acts half a step late
// and its impulse depends on where in a step the contact starts (e = 0.3 at 20 steps per
// contact: 0.287 to 0.300). MeltDEM's styles apply the damping as the change over the
// step just taken of its potential-like integral
//   D(delta) = alpha sqrt(m* K) 4/5 delta^(5/4),   F_damp(n) = (D(delta_n) - D(delta_n-1)) / dt,
// (delta_n-1 = delta_n - dt delta', known from v(n-1/2)); the damping impulses of a
// contact then sum exactly to D(end) - D(start) = 0 as in the continuous contact, and
// e no longer depends on the phase to within 0.25 % at 10 steps per contact. What remains
// is a smooth bias in the dimensionless step h = dt v0^(1/5) (K/m*)^(2/5), removed by
// choosing alpha for that h (alpha_for_restitution_at_step), a scatter with the phase where
// in a step the contact starts (+-1.7 % at 5 steps per contact) and a bias for contacts
// slower than the h is calibrated at, both removed by scaling the approach speed at the
// step the contact starts by a ratio for its phase and its own step
// (onset_ratio_for_restitution): the start is seen in that step alone, so no contact
// history is kept and a restart or a change of rank cannot lose it.

#include <cmath>
#include <unordered_map>
#include <vector>

namespace meltdem::coupling {

// Dimensionless step of a contact: dt in units of delta0/v0, delta0 = (m* v0^2/K)^(2/5),
// K = 4/3 E* sqrt(R*) (the Hertz force K delta^(3/2)), m* the effective mass, v0 the
// impact speed.
double contact_step(double dt, double impact_speed, double hertz_k, double meff);
// The same as dt v0^(1/5) (the part common to a step's contacts) times (K/m*)^(2/5).
double contact_step(double dt_speed_factor, double hertz_k, double meff);

// contact_step(dt_speed_factor, K, m*) with the pow of the last K/m* kept: the contacts of
// grains of one size in a row pay one multiplication each instead of a pow
class ContactStepMemo {
 public:
  double operator()(double dt_speed_factor, double hertz_k, double meff)
  {
    const double k_over_m = hertz_k / meff;
    if (k_over_m != k_over_m_) {
      k_over_m_ = k_over_m;
      power_ = std::pow(k_over_m, 0.4);
    }
    return dt_speed_factor * power_;
  }

 private:
  double k_over_m_ = -1.0, power_ = 0.0;
};

// Normal damping force of the stepped contact (repulsive > 0): (D(delta) - D(delta_prev))/dt
// with D = alpha sqrt(meff K) 4/5 max(delta,0)^(5/4). delta_prev is the overlap one step
// earlier; a pair that has just separated (delta <= 0 < delta_prev) gets its last kick.
double stepped_damping_force(double alpha, double hertz_k, double meff, double delta, double delta_prev, double dt);

// What a style adds to the stock force of LAMMPS's granular contact to turn its damping
// -alpha_stock sqrt(meff K) delta^(1/4) separation_rate (present only while delta > 0)
// into the stepped damping with alpha; separation_rate = relative normal velocity at
// v(n-1/2), > 0 apart, so the overlap one step earlier is delta + dt separation_rate.
// Returns the normal force on the particle (repulsive > 0).
double stepped_damping_correction(double alpha, double alpha_stock, double hertz_k, double meff, double delta,
                                  double separation_rate, double dt);

// Where in the step just taken a contact started: the fraction of the step before the
// overlap began, -delta_prev / (delta - delta_prev), for delta > 0 >= delta_prev.
double onset_phase(double delta, double delta_prev);

// The force (repulsive > 0) that at the step a contact starts (delta > 0 >= delta + dt
// separation_rate) scales its approach speed by onset_ratio over the step's two half kicks;
// 0 at every other step.
double stepped_onset_force(double onset_ratio, double meff, double delta, double separation_rate, double dt);

// Restitution of a head-on contact integrated by velocity-Verlet with the stepped damping
// in dimensionless form (x'' = -x^(3/2) - damping, x'(0-) = 1) at step h; the contact starts
// a fraction 'phase' in [0, 1) of a step before the first step that overlaps, and its first
// overlapping step scales the approach speed by onset_ratio (stepped_onset_force).
double restitution_at_step(double alpha, double h, double phase, double onset_ratio = 1.0);

// Its mean over the phase (16 equally spaced phases).
double mean_restitution_at_step(double alpha, double h);

// alpha whose phase-mean restitution at step h is e (e in (0, 1], h in [0, max_contact_step]);
// h = 0 gives alpha_for_restitution(e). Throws std::invalid_argument outside.
double alpha_for_restitution_at_step(double e, double h);

// The onset ratio with which the contact at step h, damped with alpha and starting at
// 'phase', returns e (the nearer end where no ratio in [0.5, 1.5] does).
double onset_ratio_for_restitution(double e, double alpha, double h, double phase);

// Largest h calibrated: 1.0 is 3.2 steps per contact (the elastic contact lasts
// 3.22 delta0/v0); below about 3 steps e(alpha) stops decreasing with alpha.
constexpr double max_contact_step = 1.0;

// alpha(h) for one e on a uniform grid of h in [0, max_contact_step] (alpha is nearly
// linear in h: 17 nodes interpolate it to ~1e-5), each node computed when first needed; h
// beyond the grid, or where no alpha reaches e (tiny e at the largest h), takes the alpha of
// the last node that does.
// The onset ratio of a contact that runs at its own step h_a (from its approach speed) with
// the alpha of the calibration step h (> 0; without a calibration speed, h = 0, none): for
// 65 nodes of h in [0, max_contact_step] and their alpha(h), on a grid of 64 phases times a
// grid of 1/h_a fine enough to follow the phase of the contact's end (which moves by a whole
// step as the contact lasts one step longer: 1/h_a from 1 to 6.2 by 0.01, i.e. up to 20
// steps per contact; beyond, the ratio of e over the phase-mean e of alpha(h) at h_a, 17
// nodes of h_a, where the phase scatter is below 0.05 %), each column computed when first
// needed.
class SteppedAlphaTable {
 public:
  SteppedAlphaTable() = default;
  // alpha_continuous: alpha_for_restitution(e), when the caller has it (it is the node h = 0)
  explicit SteppedAlphaTable(double e, double alpha_continuous = -1.0);
  double alpha(double h) const;
  double onset_ratio(double h, double h_contact, double phase) const;

  // What a style adds to the stock force of a contact at calibration step h: the stepped
  // damping correction with alpha(h), and at the step the contact starts the onset force
  // with the ratio for the contact's own step and phase.
  double correction(double h, double alpha_stock, double hertz_k, double meff, double delta, double separation_rate,
                    double dt) const;

 private:
  static constexpr int points = 17, ratio_points = 65, phases = 64, ratio_nodes = 521;
  static constexpr double ratio_spacing = 0.01;  // of 1/h_a, from 1
  double e_ = 0.0;
  mutable double alpha_[points] = {};
  mutable bool known_[points] = {};
  // [node of h (of ratio_points) * ratio_nodes + node of 1/h_a] -> ratios at phases 0 ... phases
  mutable std::unordered_map<int, std::vector<double>> ratio_;
  // [node of h][node of h_a in [0, 1/6.2]]: the phase-mean e of alpha(h) at the finer steps
  static constexpr int fine_points = 17;
  mutable double fine_mean_[ratio_points][fine_points] = {};
  mutable bool fine_known_[ratio_points] = {};
  double node(int k) const;
  // alpha at node k of the ratio table's grid of h
  double ratio_node_alpha(int k) const;
  const double *ratios(int k, int j) const;
  double node_ratio(int k, double h_contact, double phase) const;
};

}  // namespace meltdem::coupling
