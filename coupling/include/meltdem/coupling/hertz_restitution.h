#pragma once
// Exact coefficient of restitution of the Hertz contact with Tsuji's delta^(1/4)
// damping, as LAMMPS's pair_style granular implements 'hertz/material ... damping tsuji':
//   m* delta'' = -K delta^(3/2) - alpha sqrt(m* K) delta^(1/4) delta',  K = 4/3 E* sqrt(R*)
// (pair_granular.cpp compute(): Fne = knfac delta with knfac = 4/3 E* sqrt(R* delta),
// Fdamp = -alpha sqrt(m* knfac) vn; no clamping of tensile force by default).
// With delta = delta0 x, t = (delta0/v0) tau, delta0 = (m* v0^2 / K)^(2/5) it becomes
//   x'' = -x^(3/2) - alpha x^(1/4) x',  x(0) = 0, x'(0) = 1,
// so e = -x'(tau_end) depends on alpha alone (not on E, R, m or v0).

namespace meltdem::coupling {

// e(alpha) by integrating the dimensionless contact ODE (RK4, fine step, Hermite end
// crossing); accurate to ~1e-8. alpha >= 0 (throws std::invalid_argument otherwise).
double restitution_for_alpha(double alpha);

// Inverse: alpha such that restitution_for_alpha(alpha) = e, for e in (0, 1]
// (e = 1 gives 0); bracketed bisection to 1e-10 in e. Throws std::invalid_argument
// outside (0, 1]. Small e needs large alpha (e = 0.3 -> alpha ~ 0.9).
double alpha_for_restitution(double e);

}  // namespace meltdem::coupling
