/* -*- c++ -*- ----------------------------------------------------------
   MeltDEM: compute powder/overlap -- measures "pop-corn" (Codina2019 §3.2.1): the
   largest overlap/radius over all contacts and the contacts above a threshold.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
// no trailing semicolon: meltdem_styles.cpp expands this inside an array initializer
ComputeStyle(powder/overlap,ComputePowderOverlap);
// clang-format on
#else

#ifndef MELTDEM_COMPUTE_POWDER_OVERLAP_H
#define MELTDEM_COMPUTE_POWDER_OVERLAP_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputePowderOverlap : public Compute {
 public:
  ComputePowderOverlap(class LAMMPS *, int, char **);
  ~ComputePowderOverlap() override;
  void init() override;
  void init_list(int, class NeighList *) override;
  void compute_vector() override;

 private:
  double threshold;  // overlap/radius above which a contact counts as pop-corn
  int warnflag;      // 1: warn when the threshold is exceeded
  bigint nextwarn;   // earliest step of the next warning (rate limit)
  bigint warnevery;  // steps between two warnings
  int nwarned;       // warnings given so far
  class NeighList *list;

  struct Plane {
    int axis;
    double lo, hi;
  };
  Plane *planes;
  int nplanes;
  void find_walls();
};

}  // namespace LAMMPS_NS

#endif
#endif
