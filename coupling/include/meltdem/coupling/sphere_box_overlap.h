#pragma once
// Volume of a sphere inside an axis-aligned box, in closed form, and the same for the many
// boxes (cells) around one sphere at the cost of the planes they share.
//
// With the sphere at the origin, U(a, b, c) = |ball(R) ∩ {x >= a, y >= b, z >= c}| for
// a, b, c >= 0 is R^3/3 times the solid angle of its spherical triangle less a/3, b/3, c/3
// times its three flat faces' areas (divergence theorem; the angle by Gauss-Bonnet), six
// atans and three square roots; a negative offset is reflected: U(-a, b, c) = 2 U(0, b, c) -
// U(a, b, c). A box is the alternating sum of U over its eight corners
// (doc/foam_particle_coupling.rst, "Distribution models").
#include <Eigen/Core>

#include <vector>

namespace meltdem::coupling {

// |sphere(c, r) ∩ box [lo, hi]| in closed form (round-off of r^3 absolute).
double sphere_box_overlap(const Eigen::Vector3d &c, double r, const Eigen::Vector3d &lo, const Eigen::Vector3d &hi);

// The same by adaptive Gauss-Legendre over x of the exact slice area (the reference the
// closed form is tested against; about 1e-12 r^3 absolute, some ten times slower).
double sphere_box_overlap_quadrature(const Eigen::Vector3d &c, double r, const Eigen::Vector3d &lo,
                                     const Eigen::Vector3d &hi);

// Area of the disk y^2 + z^2 <= R^2 (centred at 0) with y <= b, z <= c (closed form).
double disk_quadrant_area(double R, double b, double c);

// The eight pieces of the ball of radius r (centred at 0) that one plane per axis cuts it
// into: cut[a] is the plane's offset along axis a, <= -r where none cuts (the whole axis then
// counts as the side above); the piece with bit a of its index set lies above cut[a].
void sphere_octant_pieces(double r, const double cut[3], double piece[8]);

// Overlaps of one sphere with many boxes whose faces lie on shared planes (the cells around
// a particle): the corner volume U is evaluated once per distinct triple of planes, so a
// particle over n x n x n cells costs (n + 1)^3 corner terms, not 8 n^3.
class SphereBoxOverlaps {
 public:
  // the sphere, and every box that will be asked for (their bounds fix the planes)
  void reset(const Eigen::Vector3d &c, double r, const std::vector<Eigen::Vector3d> &lo,
             const std::vector<Eigen::Vector3d> &hi);
  // |sphere ∩ box[i]|, i indexing the boxes given to reset()
  double volume(std::size_t i);

 private:
  Eigen::Vector3d c_ = Eigen::Vector3d::Zero();
  double r_ = 0.0;
  const std::vector<Eigen::Vector3d> *lo_ = nullptr, *hi_ = nullptr;
  std::vector<double> planes_[3];  // distinct plane offsets from the centre, clamped to [-r, r]
  std::vector<double> corner_;     // U at plane triples, NaN until evaluated
  int index(int axis, double offset) const;
  double corner(int i, int j, int k);

  // At most one plane cuts the sphere along each axis (a sphere smaller than its cells): each
  // box holds whole pieces of the eight the planes make, evaluated once in reset()
  bool octants_ = false;
  double cut_[3] = {0.0, 0.0, 0.0};  // the cutting plane's offset, or -r_ where none cuts
  double piece_[8] = {};             // piece with bit a set: the side above cut_[a]
  double octant_volume(std::size_t i) const;
};

}  // namespace meltdem::coupling
