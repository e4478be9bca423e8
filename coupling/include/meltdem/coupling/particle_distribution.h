#pragma once
// Particle -> cell distribution of the extensive quantities a particle hands to the
// continuum (mass, enthalpy, momentum, absorbed heat). Codina2019 §3.2.3: depositing a whole
// grain into the one cell holding its centre spikes density/velocity/enthalpy there and
// collapses the fluid time step (Codina2019 fig. 3.7) once cells are as small as grains, so the
// share can be spread over several cells. Three models:
//   centre     : everything to the cell holding the particle centre;
//   neighbours : centre cell + occupied face neighbours (Codina2019 fig. 3.9), volume-weighted
//                as Codina2019 eq. 3.7  w_i = V_i / sum_j V_j;
//   overlap    : w_i = |sphere ∩ cell_i| / sum_j |sphere ∩ cell_j| (powder-bed regime,
//                cells 3-10x smaller than grains); the part outside the mesh is dropped
//                and the rest renormalised.
// Weights are normalised so that their (exact) sum is 1 to round-off: the caller's
// distributed quantity q * w_i sums back to q to round-off.
// `overlap` uses the closed-form sphere-box volume (sphere_box_overlap.h), each plane
// triple the cells share evaluated once per particle.
#include "meltdem/coupling/box_cell_lattice.h"
#include "meltdem/coupling/sphere_box_overlap.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace meltdem::coupling {

// The mesh as the distribution sees it; the OpenFOAM side implements it on a polyMesh
// (cell bounding boxes stand in for the cells in `overlap`, exact for hexahedral
// axis-aligned cells such as blockMesh / snappy background cells).
class DistributionMesh {
 public:
  virtual ~DistributionMesh() = default;
  // cell holding point p, -1 when p is outside the mesh
  virtual long find_cell(const Eigen::Vector3d &p) const = 0;
  virtual void cell_bounds(long cell, Eigen::Vector3d &lo, Eigen::Vector3d &hi) const = 0;
  virtual Eigen::Vector3d cell_centre(long cell) const = 0;
  virtual double cell_volume(long cell) const = 0;
  // every cell whose bounding box intersects the sphere (a superset is allowed)
  virtual void cells_in_sphere(const Eigen::Vector3d &c, double r, std::vector<long> &cells) const = 0;
  // the cells as a lattice of boxes (box_cell_lattice.h), where they are one: `overlap` then
  // takes the planes from it instead of the cells' boxes; nullptr otherwise
  virtual const BoxCellLattice *lattice() const { return nullptr; }
  // box holding every cell's bounding box; false when there are no cells
  virtual bool bounds(Eigen::Vector3d &lo, Eigen::Vector3d &hi) const = 0;
};

// Rectilinear (possibly non-uniform) Cartesian grid, cell id = i + nx (j + ny k).
class CartesianGridMesh : public DistributionMesh {
 public:
  // node coordinates per axis, strictly increasing, >= 2 each
  CartesianGridMesh(std::vector<double> x, std::vector<double> y, std::vector<double> z);
  // uniform grid of n[0] x n[1] x n[2] cells spanning [lo, hi]
  static CartesianGridMesh uniform(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, int nx, int ny, int nz);

  long find_cell(const Eigen::Vector3d &p) const override;
  void cell_bounds(long cell, Eigen::Vector3d &lo, Eigen::Vector3d &hi) const override;
  Eigen::Vector3d cell_centre(long cell) const override;
  double cell_volume(long cell) const override;
  void cells_in_sphere(const Eigen::Vector3d &c, double r, std::vector<long> &cells) const override;
  bool bounds(Eigen::Vector3d &lo, Eigen::Vector3d &hi) const override;
  const BoxCellLattice *lattice() const override { return &lattice_; }

  long n_cells() const { return long(n_[0]) * n_[1] * n_[2]; }
  long index(int i, int j, int k) const { return i + long(n_[0]) * (j + long(n_[1]) * k); }

 private:
  std::vector<double> nodes_[3];
  int n_[3];
  BoxCellLattice lattice_;  // the same cells, slot = cell id
  void ijk(long cell, int &i, int &j, int &k) const;
};

enum class DistributionModel { Centre, Neighbours, Overlap };

// "centre" | "neighbours" | "overlap"; anything else throws std::invalid_argument naming the valid ones
DistributionModel parse_distribution_model(const std::string &name);
const char *to_string(DistributionModel model);

struct CellWeight {
  long cell;
  double weight;
};

// Weights of the particle (centre c, radius r > 0) over the mesh cells, appended to a
// cleared `out`. Returns false (out empty) when the centre lies outside the mesh, or,
// for `overlap`, when nothing of the sphere lies inside it: the caller books outflow.
// Throws std::invalid_argument for r <= 0 or a non-finite centre/radius.
bool distribute_particle(const DistributionMesh &mesh, DistributionModel model, const Eigen::Vector3d &c, double r,
                         std::vector<CellWeight> &out);

// Raw (unnormalised) weights of the particle over the cells of `mesh`, appended to `out`:
// the one kernel behind distribute_particle() and ParallelExchange (a rank's cells).
// home: the cell of `mesh` holding the centre (-1 when it is on no cell of `mesh`);
// home_lo/home_hi: the bounding box of the cell holding the centre, wherever it lies
// (`neighbours` takes the cells whose boxes share a face with it and that the particle
// reaches, Codina2019 fig. 3.9: exact for axis-aligned hexahedra, also across a refinement
// level jump, where a smaller neighbour counts only if the sphere touches its box).
void append_raw_weights(const DistributionMesh &mesh, DistributionModel model, const Eigen::Vector3d &c, double r,
                        long home, const Eigen::Vector3d &home_lo, const Eigen::Vector3d &home_hi,
                        std::vector<CellWeight> &out);

// Does box [lo, hi] share a face with box [hlo, hhi] (a common plane, overlapping in the other
// two axes)? Then the axis, the plane and the side of [hlo, hhi] it lies on (+1 / -1).
bool boxes_share_face(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, const Eigen::Vector3d &hlo,
                      const Eigen::Vector3d &hhi, int &axis, double &plane, double &outward);

// Raw (unnormalised) overlap weights |sphere ∩ cell| of the cells of `mesh` the sphere
// touches, appended to `out` (the `overlap` model before normalisation).
void append_overlap_volumes(const DistributionMesh &mesh, const Eigen::Vector3d &c, double r,
                            std::vector<CellWeight> &out);

// Scale positive raw weights to sum 1: divide by their compensated sum, then put the
// residual 1 - sum(w) (compensated) onto the largest weight.
void normalise_weights(std::vector<CellWeight> &weights);

}  // namespace meltdem::coupling
