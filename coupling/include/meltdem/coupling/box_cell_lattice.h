#pragma once
// Cell search on meshes whose cells are axis-aligned boxes on a tensor-product lattice (the
// blockMesh hexahedra of the scenes, graded or not, refined by hexRef8 or not, a rank's part of
// one): a point or a box is located in the three lists of coordinate planes instead of a tree
// walk, by the index a uniform spacing predicts and a few steps from it (binary search when
// the planes are far from uniform).
#include <Eigen/Core>

#include <vector>

namespace meltdem::coupling {

class BoxCellLattice {
 public:
  // Cells by their bounding boxes (lo, hi); the planes are all the cells' coordinates, and a
  // cell covers the slots between its own planes (one per axis on a uniform or graded mesh,
  // several for a coarse cell beside refined ones). True when no two cells share a slot and the
  // lattice has at most max_slots_per_cell slots per cell (the rest are holes: a rank's irregular
  // part of a mesh). False otherwise, and the lattice stays empty.
  bool build(const std::vector<Eigen::Vector3d> &lo, const std::vector<Eigen::Vector3d> &hi,
             double max_slots_per_cell = 8.0);

  bool empty() const { return slots_.empty(); }

  // the lowest cell whose closed box contains p; -1 when none does
  long find_cell(const Eigen::Vector3d &p) const;

  // every cell whose closed box overlaps the closed box [lo, hi], in ascending order
  void cells_in_box(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, std::vector<long> &cells) const;

  // the slot intervals [first[a], last[a]] per axis whose closed ranges meet the closed box
  // [lo, hi]; false when the box misses the lattice
  bool slot_range(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, int first[3], int last[3]) const;

  // every slot the sphere (c, r) reaches, appended in lattice order as its cell and the slot's
  // box from the planes (the cell's own box unless the cell spans several slots, which then
  // come once each)
  void slots_in_sphere(const Eigen::Vector3d &c, double r, std::vector<long> &cells, std::vector<Eigen::Vector3d> &lo,
                       std::vector<Eigen::Vector3d> &hi) const;

  // plane i along axis a (slot i spans planes i and i + 1)
  double plane(int axis, int i) const { return planes_[axis][std::size_t(i)]; }
  // the cell of slot (i, j, k), -1 for a hole
  long slot(int i, int j, int k) const { return slots_[(std::size_t(k) * n_[1] + std::size_t(j)) * n_[0] + i]; }

 private:
  // std::upper_bound (upper) or std::lower_bound of x in planes_[axis], as an index, found
  // from the index a uniform spacing predicts (guess)
  int bound(int axis, double x, bool upper) const;
  int guess(int axis, double x) const;

  std::vector<double> planes_[3];  // sorted coordinate planes per axis; n_[a] = intervals
  int n_[3] = {0, 0, 0};
  double per_length_[3] = {0.0, 0.0, 0.0};  // intervals per unit length (the mean spacing's inverse)
  std::vector<long> slots_;                 // cell of each lattice slot, -1 for a hole
  bool spanning_ = false;                   // some cell covers more than one slot
};

}  // namespace meltdem::coupling
