#pragma once
// Hertzian contact duration and the DEM time step derived from it (Codina2019 eq. 3.1-3.4).

namespace meltdem::coupling {

// E* = ((1-nu1^2)/E1 + (1-nu2^2)/E2)^-1  (eq. 3.2)
double effective_modulus(double E1, double nu1, double E2, double nu2);

// Effective value of a pair quantity x*: (1/x1 + 1/x2)^-1 (eq. 3.2 for mass and radius)
double harmonic_pair(double x1, double x2);

// t_c = 2.87 (m*^2 / (R* E*^2 U_rel))^(1/5)  (eq. 3.1), SI units.
double hertz_contact_time(double m_eff, double R_eff, double E_eff, double U_rel);

// The shortest contact time of two equal spheres of radius R and density rho
// (eq. 3.1 with R1 = R2 = R, m = 4/3 pi R^3 rho): t = C R (rho / (E* sqrt(U)))^0.4
// with C = 2.87 (8 pi^2 / 9)^(1/5) = 4.4311. Codina2019 prints C = 5.429675 in eq. 3.3,
// which does not follow from eq. 3.1; we use eq. 3.1 itself.
double hertz_contact_time_equal_spheres(double R, double rho, double E_eff, double U_rel);

// DEM step = t_contact / collision_resolution_steps; number of DEM sub-cycles in one
// coupling step of length dt_step, rounded up (eq. 3.4).
double dem_timestep(double t_contact, double collision_resolution_steps);
long dem_subcycles(double dt_step, double dt_dem);

}  // namespace meltdem::coupling
