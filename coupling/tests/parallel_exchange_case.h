#pragma once
// Shared by the serial and the np 2 tests of parallel_exchange.h: a non-uniform grid,
// random particles from 0.3 to 4 cells across (some straddling the x = split plane,
// some partly or wholly outside), a per-cell field to sample and amounts to deposit.
#include "meltdem/coupling/parallel_exchange.h"

#include <random>
#include <vector>

namespace meltdem::coupling::testing {

inline std::vector<double> grid_nodes(double lo, double hi, int n, double stretch)
{
  std::vector<double> x;
  for (int i = 0; i <= n; ++i) {
    const double s = double(i) / n;
    x.push_back(lo + (hi - lo) * (s + stretch * s * (1 - s)));
  }
  return x;
}

struct ExchangeCase {
  std::vector<double> x = grid_nodes(0, 1e-3, 12, 0.3), y = grid_nodes(0, 8e-4, 8, 0.0),
                      z = grid_nodes(0, 6e-4, 6, -0.2);
  std::vector<ParticleShape> particles;
  std::vector<Amounts> amounts;
  explicit ExchangeCase(int n = 60)
  {
    std::mt19937_64 rng(20261125);
    std::uniform_real_distribution<double> ux(-5e-5, 1.05e-3), uy(0, 8e-4), uz(0, 6e-4), ur(2.5e-5, 2.2e-4);
    for (int i = 0; i < n; ++i) {
      ParticleShape p;
      p.x = Eigen::Vector3d(ux(rng), uy(rng), uz(rng));
      if (i % 7 == 0) p.x.x() = x[6] + (i % 2 ? 1 : -1) * 2e-5;  // straddles the split plane
      p.radius = ur(rng);
      p.id = i + 1;
      particles.push_back(p);
      amounts.push_back(
          make_amounts(1e-9 * (i + 1), 3e-4 * (i + 2), Eigen::Vector3d(1e-9 * i, -2e-9, 5e-10 * (i % 3))));
    }
  }
  // the cells with i in [i0, i1) as a mesh of their own (one rank's part)
  CartesianGridMesh part(int i0, int i1) const
  {
    return CartesianGridMesh(std::vector<double>(x.begin() + i0, x.begin() + i1 + 1), y, z);
  }
  static double field(const Eigen::Vector3d &c) { return 1000 + 3e5 * c.x() - 2e5 * c.y() + 7e4 * c.z(); }
};

}  // namespace meltdem::coupling::testing
