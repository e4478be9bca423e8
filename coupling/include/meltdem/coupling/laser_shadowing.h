#pragma once
// Laser absorption by powder particles and the shadow they cast on the continuum:
// particles in the beam absorb their share, and what they intercept
// does not reach the melt pool below, so particles + continuum absorb eta P exactly.
//
// Beam: the continuum's profile (foam-src/meltdemModels/laserHeatSource, Fuchs2022 eq. 17),
// a collimated Gaussian of power P and 1/e^2 radius w,
//     I(rho) = 2P/(pi w^2) exp(-2 rho^2/w^2),   rho = distance from the axis,
// with the axis through `centre` along the unit `direction` (from the source into the
// domain). It has no focus or divergence and comes from infinitely far upstream: every
// particle is lit whatever its depth. Depth of a point x: (x - centre) . direction.
// A disk of radius R centred on the axis receives P (1 - exp(-2 R^2/w^2)).
// Cost: 12 bytes and one init per ray of the n^2 grid, plus one test per ray inside each
// particle's disk.
//
// Scheme (ray casting, exact balance by construction): the beam's cross-section (the plane
// normal to the axis through `centre`) is cut into a Cartesian grid of square cells of
// side h over the square |u|, |v| <= extent w (ShadowOptions: h = min(w/cells_per_radius,
// R_min/cells_per_particle_radius), n even, the grid symmetric about the axis; u, v from
// beam_plane_basis). Each cell is one ray
// along the axis through the cell centre, carrying the exact beam power over the cell
// (the profile is separable: P g_i g_j, g_i = (erf(sqrt2 u_{i+1}/w) - erf(sqrt2 u_i/w))/2).
// A ray is intercepted by the sphere it enters first (smallest entry depth d_k -
// sqrt(R_k^2 - rho^2), a z-buffer: exact for overlapping spheres too, no sorting). A
// particle's intercepted power is the sum of its rays; it absorbs eta times that (the
// rest, (1 - eta), is reflected and leaves the domain, as the continuum's (1 - eta)
// does: no multiple reflections). Rays no particle hits, and the beam tail outside the sampled square
// (P (1 - erf(sqrt2 extent)^2), 2e-15 P at extent 4), reach the continuum:
//     transmitted_power = P - intercepted_total,
//     sum(absorbed) + eta transmitted_power = eta P   (to round-off).
// Discretisation error (tests/test_laser_shadowing.cpp; values in doc/coupling_laser_shadowing.rst):
// a particle's share is its disk counted in whole rays, so the error depends on R/h, the
// rays across its radius, and falls as R/h grows (default R/h = 20).
// The balance is exact whatever the resolution: only the split between particles and
// continuum carries that error.
//
// The continuum (laserHeatSource) uses the result in two ways:
//   * it deposits eta * transmitted_power instead of eta P (normalisation target), and
//   * it multiplies its beam shape exp(-2 rho^2/w^2) <grad(alpha).e> at a cell by
//     transmitted_fraction(result, cell centre [, footprint]) (0 in the shadow of a
//     particle, 1 where the beam arrives), so the heat goes where the light arrives.
// Pass only particles the beam can reach as particles (in the gas): a particle captured
// by the melt is continuum and must not absorb twice.
#include <Eigen/Core>
#include <mpi.h>

#include <cstdint>
#include <vector>

namespace meltdem::coupling {

struct GaussianBeam {
  double power = 0.0;                                           // P [W] >= 0
  double absorptivity = 1.0;                                    // eta in [0, 1]
  double radius = 0.0;                                          // w, 1/e^2 radius [m] > 0
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();             // a point on the axis [m]
  Eigen::Vector3d direction = Eigen::Vector3d(0.0, 0.0, -1.0);  // source -> domain, non-zero
};

struct BeamParticle {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  // centre [m]
  double radius = 0.0;                          // [m] > 0
};

struct ShadowOptions {
  // ray spacing h = min(w / cells_per_radius, R_min / cells_per_particle_radius), R_min the
  // smallest particle in the sampled square: a particle's share is its disk counted in
  // whole cells, so its error depends on R/h (see above)
  double cells_per_radius = 50.0;           // rays per beam radius w (> 0)
  double cells_per_particle_radius = 20.0;  // rays per particle radius (>= 0, 0: off)
  double extent = 4.0;                      // half-width of the sampled square in beam radii (> 0)
  // at most max_cells rays: cells_per_radius beyond it throws; the particle criterion is
  // capped there (the grid then has max_cells rays, grid.h says which spacing was used)
  std::int64_t max_cells = 4'000'000;  // 12 bytes per ray
};

// The ray grid after casting: enough to answer "is this point lit?" and to list the rays
// that reach the continuum.
struct ShadowGrid {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();                       // unit
  Eigen::Vector3d u = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();  // plane basis
  double h = 0.0;                                                            // cell side [m]
  double half_width = 0;                                                     // extent w [m]
  int n = 0;                                                                 // cells per side
  std::vector<double> g;            // 1D cell fractions, ray (i, j) carries P g[i] g[j]
  std::vector<double> entry_depth;  // per ray (j n + i): first sphere entry, +inf if none
  std::vector<int> owner;           // per ray: index of the particle hit first, -1 if none
  // the smallest entry depth in each square block of kShadowBlock^2 rays (row-major, nb per
  // side; +inf where no ray is hit): a point above it is lit by every ray of the block
  int nb = 0;
  std::vector<double> block_entry_depth;
  // the largest entry depth in each block (+inf where a ray of the block is not hit): a point
  // at or below it is dark for every ray of the block
  std::vector<double> block_max_entry_depth;
  // the largest entry depth of the block's hit rays (-inf where none is hit): at or below it a
  // point is dark for exactly the block's hit rays, which hits_before counts along a row
  std::vector<double> block_max_hit_depth;
  // per row j, n + 1 entries: hits_before[j (n + 1) + i] = rays hit among (0..i-1, j)
  std::vector<std::uint16_t> hits_before;
};
inline constexpr int kShadowBlock = 16;  // rays per block side

struct ShadowResult {
  std::vector<double> absorbed;     // W per particle: eta * intercepted
  std::vector<double> intercepted;  // W per particle, before eta
  double intercepted_total = 0.0;   // W, sum(intercepted) (before eta)
  double transmitted_power = 0.0;   // W reaching the continuum: P - intercepted_total
  double sampled_power = 0.0;       // W carried by the rays (P minus the tail)
  double tail_power = 0.0;          // W outside the sampled square (goes to the continuum)
  double power = 0.0;               // P of the beam [W]
  double absorptivity = 0.0;        // eta of the beam
  // what the continuum absorbs, eta * transmitted_power; + sum(absorbed) = eta P
  double continuum_absorbed() const { return absorptivity * transmitted_power; }
  ShadowGrid grid;
};

// Orthonormal basis (u, v) of the plane normal to the unit `direction`, fixed so the grid
// is reproducible: u is the unit projection of e_x on the plane, or of e_z when
// |direction . e_x| > 0.9; v = direction x u. For (0,0,-1): u = e_x, v = -e_y.
void beam_plane_basis(const Eigen::Vector3d &direction, Eigen::Vector3d &u, Eigen::Vector3d &v);

// Irradiance [W/m^2] at distance rho from the axis (the continuum's profile)
double beam_irradiance(const GaussianBeam &beam, double rho);

// Power [W] of the beam through a disk of radius R normal to the axis, centred at distance
// s from it (exact: the Marcum-Q integral, by a fine Gauss-Legendre quadrature in rho;
// P (1 - exp(-2 R^2/w^2)) for s = 0). The reference for the tests.
double beam_power_in_disk(const GaussianBeam &beam, double R, double s = 0.0);

// Cast the beam through the particles. Throws std::invalid_argument (message naming the
// bad value) for P < 0, eta outside [0,1], w <= 0, a zero or non-finite direction or
// centre, a particle with radius <= 0 or a non-finite centre, or bad options.
ShadowResult shade_particles(const GaussianBeam &beam, const std::vector<BeamParticle> &particles,
                             const ShadowOptions &options = {});
// The same into result, whose storage is kept: a caller casting every step allocates the ray
// grid once
void shade_particles(const GaussianBeam &beam, const std::vector<BeamParticle> &particles, const ShadowOptions &options,
                     ShadowResult &result);

// The same over MPI (collective on comm; the beam and options must be the same on every
// rank): each rank passes its own particles; those whose disk reaches the sampled square
// are gathered onto every rank (in rank order) and cast there, so all ranks hold the same
// grid and totals. absorbed / intercepted are returned for the caller's particles (0 for
// those outside the square). Bad particle input on any rank throws on every rank.
ShadowResult shade_particles(MPI_Comm comm, const GaussianBeam &beam, const std::vector<BeamParticle> &local,
                             const ShadowOptions &options = {});
void shade_particles(MPI_Comm comm, const GaussianBeam &beam, const std::vector<BeamParticle> &local,
                     const ShadowOptions &options, ShadowResult &result);

// Geometric fraction of the beam arriving at `point` (0 or 1): the ray through the point's
// projection on the grid is lit at the point's depth if no particle intercepted it upstream
// (entry depth > depth of the point). Outside the sampled square: 1. With footprint > 0:
// the fraction of the rays whose centres lie within `footprint` of the point's projection
// that are lit at its depth (the continuum cell's size: a smooth shadow edge on a mesh
// coarser than the ray grid); the single ray when none lies that close.
double transmitted_fraction(const ShadowResult &result, const Eigen::Vector3d &point, double footprint = 0.0);

// One ray reaching the continuum: where it crosses the plane through the beam centre, and
// its power [W] (before eta).
struct TransmittedRay {
  Eigen::Vector3d x;
  double power;
};
// The rays no particle intercepted; their powers sum to transmitted_power - tail_power.
std::vector<TransmittedRay> transmitted_rays(const ShadowResult &result);

}  // namespace meltdem::coupling
