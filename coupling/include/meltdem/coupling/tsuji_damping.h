#pragma once
// Tsuji's polynomial between the coefficient of restitution e and the damping
// coefficient alpha of the Hertz contact eta_N = alpha sqrt(m* k_N) delta^(1/4)
// (Codina2019 eq. 3.5; Tsuji1992). This is the map LAMMPS's
// pair_style granular applies for 'damping tsuji'.

namespace meltdem::coupling {

// alpha(e) = 1.2728 - 4.2783 e + 11.087 e^2 - 22.348 e^3 + 27.467 e^4 - 18.022 e^5 + 4.8218 e^6
// for e in [0, 1]; strictly decreasing from 1.2728 to 3e-4.
double tsuji_alpha(double e);

// Inverse of tsuji_alpha on [0, 1], to 1e-14 in e; alpha must lie in [tsuji_alpha(1), tsuji_alpha(0)].
double tsuji_restitution(double alpha);

}  // namespace meltdem::coupling
