/* ----------------------------------------------------------------------
   MeltDEM: compute powder/overlap -- pop-corn measure (Codina2019 §3.2.1).

   Pop-corn is a contact resolved too late: the overlap grows far beyond what the impact
   speed allows and the Hertz force (eq. 3.5) throws the particles apart. This compute
   reports the largest overlap relative to the smaller radius over all particle pairs
   (occasional neighbor list) and flat granular walls, and counts the contacts above a
   threshold, so a run can check it instead of guessing from the velocities.
------------------------------------------------------------------------- */

#include "compute_powder_overlap.h"

#include "lammps_api.h"
#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "pair_granular.h"
#include "update.h"

#include "GRANULAR/fix_wall_gran.h"

#include "meltdem/coupling/dem_step_control.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
namespace mc = meltdem::coupling;

namespace {
// FixWallGran keeps its geometry protected and offers no accessor. An explicit template
// instantiation may name non-public members (C++17 [temp.spec]/6); the member pointers
// read them from any FixWallGran (stock wall/gran and its subclass wall/gran/powder).
template <typename Tag, typename Tag::type M> struct Expose {
  friend typename Tag::type member(Tag) { return M; }
};
struct WallStyleTag {
  using type = int FixWallGran::*;
  friend type member(WallStyleTag);
};
struct WiggleTag {
  using type = int FixWallGran::*;
  friend type member(WiggleTag);
};
struct LoTag {
  using type = double FixWallGran::*;
  friend type member(LoTag);
};
struct HiTag {
  using type = double FixWallGran::*;
  friend type member(HiTag);
};
template struct Expose<WallStyleTag, &FixWallGran::wallstyle>;
template struct Expose<WiggleTag, &FixWallGran::wiggle>;
template struct Expose<LoTag, &FixWallGran::lo>;
template struct Expose<HiTag, &FixWallGran::hi>;

// FixWallGran's wall styles 0..2 are the x, y, z planes (fix_wall_gran.cpp)
constexpr int ZPLANE = 2;
// FixWallGran marks an absent lo/hi plane with +-1e20
constexpr double NOWALL = 1.0e19;
}  // namespace

/* ---------------------------------------------------------------------- */

ComputePowderOverlap::ComputePowderOverlap(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), threshold(0.05), warnflag(1), nextwarn(0), warnevery(1000), nwarned(0), list(nullptr),
    planes(nullptr), nplanes(0)
{
  vector_flag = 1;
  size_vector = 4;
  extvector = 0;

  int iarg = 3;
  while (iarg < narg) {
    if (iarg + 2 > narg) error->all(FLERR, "Compute powder/overlap keyword {} needs 1 value", arg[iarg]);
    if (strcmp(arg[iarg], "threshold") == 0) {
      threshold = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (threshold <= 0.0) error->all(FLERR, "Compute powder/overlap threshold must be > 0");
    } else if (strcmp(arg[iarg], "warn") == 0) {
      if (strcmp(arg[iarg + 1], "no") == 0)
        warnflag = 0;
      else {
        warnflag = 1;
        warnevery = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
        if (warnevery <= 0) error->all(FLERR, "Compute powder/overlap warn must be no or a number of steps > 0");
      }
    } else
      error->all(FLERR, "Compute powder/overlap: unknown keyword {}", arg[iarg]);
    iarg += 2;
  }

  if (!atom->radius_flag) error->all(FLERR, "Compute powder/overlap requires atom_style sphere (per-atom radius)");
  vector = new double[size_vector];
  for (int i = 0; i < size_vector; i++) vector[i] = 0.0;
}

/* ---------------------------------------------------------------------- */

ComputePowderOverlap::~ComputePowderOverlap()
{
  delete[] vector;
  delete[] planes;
}

/* ---------------------------------------------------------------------- */

void ComputePowderOverlap::init()
{
  if (force->pair == nullptr) error->all(FLERR, "Compute powder/overlap requires a pair style be defined");

  // an occasional half list with the granular size cutoff, as compute contact/atom
  meltdem::lammps_api::request_occasional_size_list(neighbor, this, instance_me);

  find_walls();
}

/* ---------------------------------------------------------------------- */

void ComputePowderOverlap::init_list(int /*id*/, NeighList *ptr)
{
  list = ptr;
}

/* ----------------------------------------------------------------------
   flat granular walls (xplane/yplane/zplane of fix wall/gran, wall/gran/powder);
   cylinders, regions and wiggling walls are not measured
------------------------------------------------------------------------- */

void ComputePowderOverlap::find_walls()
{
  delete[] planes;
  planes = new Plane[2 * modify->nfix + 1];
  nplanes = 0;
  for (int k = 0; k < modify->nfix; k++) {
    Fix *f = modify->fix[k];
    if (strcmp(f->style, "wall/gran") != 0 && strcmp(f->style, "wall/gran/powder") != 0) continue;
    auto *w = static_cast<FixWallGran *>(f);
    const int style = w->*member(WallStyleTag());
    if (style > ZPLANE || w->*member(WiggleTag())) continue;
    planes[nplanes].axis = style;
    planes[nplanes].lo = w->*member(LoTag());
    planes[nplanes].hi = w->*member(HiTag());
    nplanes++;
  }
}

/* ---------------------------------------------------------------------- */

void ComputePowderOverlap::compute_vector()
{
  invoked_vector = update->ntimestep;
  neighbor->build_one(list);

  double **x = atom->x;
  double **v = atom->v;
  double *radius = atom->radius;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;

  // a pair with a ghost partner is listed on both of its owners when newton_pair is off
  const double ghostweight = force->newton_pair ? 1.0 : 0.5;
  double maxratio = 0.0, vmax2 = 0.0, nabove = 0.0, ncontact = 0.0;

  const int inum = list->inum;
  for (int ii = 0; ii < inum; ii++) {
    const int i = list->ilist[ii];
    if (!(mask[i] & groupbit)) continue;
    const int *jlist = list->firstneigh[i];
    const int jnum = list->numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!(mask[j] & groupbit)) continue;
      const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
      const double radsum = radius[i] + radius[j];
      const double rsq = dx * dx + dy * dy + dz * dz;
      if (rsq >= radsum * radsum) continue;
      const double ratio = mc::overlap_ratio(std::sqrt(rsq), radius[i], radius[j]);
      const double w = j < nlocal ? 1.0 : ghostweight;
      ncontact += w;
      if (ratio > threshold) nabove += w;
      maxratio = std::max(maxratio, ratio);
    }
  }

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    vmax2 = std::max(vmax2, v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    for (int p = 0; p < nplanes; p++) {
      const double c = x[i][planes[p].axis];
      for (const double wall : {planes[p].lo, planes[p].hi}) {
        if (std::fabs(wall) > NOWALL) continue;
        const double dist = std::fabs(c - wall);
        if (dist >= radius[i]) continue;
        const double ratio = mc::wall_overlap_ratio(dist, radius[i]);
        ncontact += 1.0;
        if (ratio > threshold) nabove += 1.0;
        maxratio = std::max(maxratio, ratio);
      }
    }
  }

  double loc[2] = {maxratio, vmax2}, all[2];
  MPI_Allreduce(loc, all, 2, MPI_DOUBLE, MPI_MAX, world);
  double locs[2] = {nabove, ncontact}, alls[2];
  MPI_Allreduce(locs, alls, 2, MPI_DOUBLE, MPI_SUM, world);

  vector[0] = all[0];
  vector[1] = std::round(alls[0]);
  vector[2] = std::sqrt(all[1]);
  vector[3] = std::round(alls[1]);

  if (warnflag && vector[1] > 0.0 && update->ntimestep >= nextwarn) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "Compute powder/overlap {}: pop-corn at step {}: {} contacts with "
                     "overlap/radius > {}, largest {:.4g} (reduce the time step, e.g. fix "
                     "powder/dt steps)",
                     id, update->ntimestep, (bigint)vector[1], threshold, vector[0]);
    nextwarn = update->ntimestep + warnevery;
    nwarned++;
  }
}
