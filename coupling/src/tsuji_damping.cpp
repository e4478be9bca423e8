#include "meltdem/coupling/tsuji_damping.h"

#include <stdexcept>
#include <string>

namespace meltdem::coupling {

double tsuji_alpha(double e)
{
  if (!(e >= 0.0 && e <= 1.0))
    throw std::invalid_argument("restitution coefficient must lie in [0, 1], got " + std::to_string(e));
  // Horner form of the polynomial LAMMPS evaluates
  return 1.2728 + e * (-4.2783 + e * (11.087 + e * (-22.348 + e * (27.467 + e * (-18.022 + e * 4.8218)))));
}

double tsuji_restitution(double alpha)
{
  const double a_lo = tsuji_alpha(1.0), a_hi = tsuji_alpha(0.0);
  if (!(alpha >= a_lo && alpha <= a_hi))
    throw std::invalid_argument("Tsuji damping alpha must lie in [" + std::to_string(a_lo) + ", " +
                                std::to_string(a_hi) + "], got " + std::to_string(alpha));
  // alpha(e) is strictly decreasing: bisection is robust and exact enough
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (tsuji_alpha(mid) > alpha)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace meltdem::coupling
