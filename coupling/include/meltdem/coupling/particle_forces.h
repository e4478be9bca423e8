#pragma once
// Fluid forces on one particle (Codina2019 eq. 2.14 with the fluid viscosity kept):
//   drag      F_d = beta (U_f - U_p), beta = 3 pi mu_f d (Cd Re / 24)  (drag.h)
//   buoyancy  F_b = -rho_f V_p g = -(rho_f / rho_p) m_p g  (gravity itself is fix gravity's)

#include "meltdem/coupling/drag.h"
#include "meltdem/coupling/fluid_state.h"

namespace meltdem::coupling {

struct ParticleForces {
  double drag[3] = {0.0, 0.0, 0.0};      // [N]
  double buoyancy[3] = {0.0, 0.0, 0.0};  // [N]
  double Re = 0.0;                       // slip Reynolds number
  double beta = 0.0;                     // drag coefficient [kg/s] of F_d = beta (U_f - U_p)
};

// slip Reynolds number rho_f |U_f - v| d / mu_f
double slip_reynolds(const FluidState &fluid, const double v[3], double d);

// v: particle velocity, d: diameter, g: gravitational acceleration vector (zero: none)
ParticleForces drag_and_buoyancy(DragModel model, const FluidState &fluid, const double v[3], double d,
                                 const double g[3]);

// Drag between a particle (mass m) and the fluid parcel it exchanges momentum with (mass M,
// FluidState::mass; M <= 0: unbounded) over a step dt, as two bodies: the coefficient to use
// in F = beta_eff (U - v), the parcel then changing by -F dt / M, is
//   beta_eff = min(beta, mu / dt),  mu = m M / (m + M),
// explicit drag while a step cannot carry the pair past their common velocity, and at most
// the impulse that brings both to it in one step (explicit drag overshoots once beta dt > mu:
// a grain whose response time is shorter than the step, or a light gas parcel pushed past the
// grain that drives it, which then grows without bound). The pair's momentum is conserved. (The
// exact slip decay as a constant force, (mu/dt)(1 - exp(-beta dt/mu)), would bias a forced steady
// state such as the terminal velocity by beta dt / 2 mu; explicit drag keeps it exact.)
double two_body_drag_coefficient(double beta, double m, double M, double dt);

}  // namespace meltdem::coupling
