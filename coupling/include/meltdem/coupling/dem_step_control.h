#pragma once
// Step control and pop-corn measure for DEM (Codina2019 eq. 3.1-3.4 and §3.2.1):
// the bounds fix powder/dt and compute powder/overlap evaluate.

namespace meltdem::coupling {

// Upper bound on the relative approach speed of any particle pair or particle-wall pair
// from the largest particle speed: |v_i - v_j| <= |v_i| + |v_j| <= 2 max|v|. A bed at rest
// has max|v| = 0, where eq. 3.1 diverges, so the bound never drops below floor (> 0).
double approach_speed_bound(double v_max, double floor);

// Lower bound of the Hertz contact time (eq. 3.1) over a population: two equal spheres of
// the smallest radius and the smallest density, with the largest E*, at approach speed U.
// t_c ~ rho^0.4 R (m*^2/R* with m ~ rho R^3), and a small sphere on a larger one or on a
// wall (R* -> R, m* -> m) lasts 2^0.2 times longer than two equal small spheres.
double shortest_contact_time(double R_min, double rho_min, double E_eff_max, double U);

// Largest overlap / radius of a head-on Hertz contact of two equal spheres (density rho)
// at approach speed U, undamped (the upper bound): delta_max = (15 m* U^2 / (16 E* sqrt(R*)))^0.4
// with m* = m/2, R* = R/2, i.e. delta_max / R = (10 pi sqrt(2)/16 rho U^2 / E*)^0.4,
// independent of R. Hertz's law assumes small overlaps: above ~0.1-0.3 R the contact is
// not a Hertz contact any more (and beyond 1 the spheres pass through each other).
double head_on_overlap_ratio(double rho, double E_eff, double U);

// Normal overlap of two spheres relative to the smaller radius, 0 when apart.
double overlap_ratio(double distance, double R1, double R2);

// Normal overlap of a sphere with a plane wall relative to its radius, 0 when apart.
double wall_overlap_ratio(double distance, double R);

}  // namespace meltdem::coupling
