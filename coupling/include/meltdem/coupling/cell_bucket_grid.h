#pragma once
// Cell search on general meshes (skewed, graded, polyhedral; the cells need not be boxes on a
// lattice): the cells' bounding boxes are binned into a uniform grid of buckets, about one cell
// per bucket, and a point is tested only against the cells of its bucket, each by its face
// planes (OpenFOAM's face-planes point-in-cell test, exact for convex cells with planar faces).
// A point costs a bucket index and a few dot products instead of an octree walk and a
// tetrahedral decomposition.
#include <Eigen/Core>

#include <array>
#include <vector>

namespace meltdem::coupling {

class CellBucketGrid {
 public:
  // Cells by their bounding boxes (lo, hi) and faces: face f is the plane through
  // face_centre[f] with area vector face_area[f] (pointing out of its owner cell); cell c's
  // faces are cell_faces[cell_offsets[c] .. cell_offsets[c + 1]), each as f for its owner and
  // -1 - f for its neighbour (the face seen from the other side).
  void build(const std::vector<Eigen::Vector3d> &lo, const std::vector<Eigen::Vector3d> &hi,
             const std::vector<Eigen::Vector3d> &face_centre, const std::vector<Eigen::Vector3d> &face_area,
             const std::vector<long> &cell_offsets, const std::vector<long> &cell_faces);

  bool empty() const { return offsets_.empty(); }

  // the lowest cell whose face planes hold p (on or behind every face, within a rounding
  // tolerance); -1 when none does
  long find_cell(const Eigen::Vector3d &p) const;

  // every cell whose bounding box overlaps the closed box [lo, hi], in ascending order
  void cells_in_box(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, std::vector<long> &cells) const;

  // whether p is on or behind every face plane of cell c (within the tolerance)
  bool inside(long c, const Eigen::Vector3d &p) const;

  // the largest distance of a point outside a plane of its own cell, over the given cell
  // points (the caller's mesh points of each cell): 0 for convex cells with planar faces
  double convexity_defect(long c, const std::vector<Eigen::Vector3d> &points) const;

 private:
  void bucket_range(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, int first[3], int last[3]) const;

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero(), per_length_ = Eigen::Vector3d::Zero();
  int n_[3] = {0, 0, 0};
  std::vector<long> offsets_, cells_;  // bucket b's cells: cells_[offsets_[b] .. offsets_[b + 1]), ascending
  std::vector<Eigen::Vector3d> lo_, hi_;
  std::vector<std::array<int, 3>> first_bucket_;  // per cell: the lowest bucket it is binned in
  std::vector<Eigen::Vector4d> planes_;           // unit outward normal and offset n.x = d, per face
  std::vector<long> cell_offsets_, cell_faces_;
  double tol_ = 0.0;  // how far outside a plane still counts as on it [m]
};

}  // namespace meltdem::coupling
