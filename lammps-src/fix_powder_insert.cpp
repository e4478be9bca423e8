/* ----------------------------------------------------------------------
   MeltDEM: fix powder/insert

   Overlap-free insertion: every candidate sphere is checked against all particles near
   the region (gathered from all ranks, periodic images included), against the particles
   placed in the same step, against granular walls and against the region surface.
   A particle that fails 'attempts' trial positions stays in a FIFO pending queue with its
   drawn diameter and is retried first on later steps (Codina2019 §3.2.2), so neither the size
   distribution is biased nor any particle lost. All ranks draw the same random numbers
   and take the same decisions; diameters come from their own stream, so a seed gives
   the same diameter sequence for any processor count.
------------------------------------------------------------------------- */

#include "fix_powder_insert.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_powder_melt.h"
#include "fix_wall_gran.h"
#include "lammps_api.h"
#include "force.h"
#include "math_const.h"
#include "modify.h"
#include "pair.h"
#include "region.h"
#include "update.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

using namespace LAMMPS_NS;
using namespace FixConst;
using meltdem::coupling::SizeDistribution;

namespace {
enum { ALL, RATE, MASSRATE };
constexpr int RESTART_VERSION = 2;  // 2: the last ID assigned
constexpr double CREDIT_EPS = 1.0e-9;
constexpr double UNBOUNDED = 1.0e19;  // a region's INF bound is +-1e20

// Read access to fix wall/gran's protected geometry. A pointer to a member named through
// a derived class is a pointer to the base member, usable on any FixWallGran object.
struct WallGranAccess : public FixWallGran {
  static int wallstyle_of(FixWallGran *f) { return f->*(&WallGranAccess::wallstyle); }
  static double lo_of(FixWallGran *f) { return f->*(&WallGranAccess::lo); }
  static double hi_of(FixWallGran *f) { return f->*(&WallGranAccess::hi); }
  static double cylradius_of(FixWallGran *f) { return f->*(&WallGranAccess::cylradius); }
  static const char *idregion_of(FixWallGran *f) { return f->*(&WallGranAccess::idregion); }
  static void wiggle_shift(FixWallGran *f, double t, double &shift)
  {
    shift = 0.0;
    if (f->*(&WallGranAccess::wiggle) && f->*(&WallGranAccess::wallstyle) == f->*(&WallGranAccess::axis)) {
      const double amp = f->*(&WallGranAccess::amplitude);
      shift = amp - amp * cos(f->*(&WallGranAccess::omega) * t);
    }
  }
  static bigint time_origin_of(FixWallGran *f) { return f->*(&WallGranAccess::time_origin); }
};
// fix wall/gran's wallstyle values (enum in fix_wall_gran.cpp)
enum { XPLANE = 0, YPLANE = 1, ZPLANE = 2, ZCYLINDER, REGION };

// serialise the restart state
struct Writer {
  std::string buf;
  template <typename T> void put(const T &v) { buf.append(reinterpret_cast<const char *>(&v), sizeof(T)); }
};
struct Reader {
  const char *p;
  template <typename T> T get()
  {
    T v;
    memcpy(&v, p, sizeof(T));
    p += sizeof(T);
    return v;
  }
};
}  // namespace

/* ---------------------------------------------------------------------- */

FixPowderInsert::FixPowderInsert(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), idregion(nullptr), rng_size(1), rng_pos(1), fixmelt(nullptr)
{
  if (narg < 5) error->all(FLERR, "Illegal fix powder/insert command: expected N seed region ID diam DIST dens RHO");
  if (strcmp(update->unit_style, "si") != 0)
    error->all(FLERR, "Fix powder/insert requires units si (densities, masses and temperatures are SI)");
  if (!meltdem::lammps_api::sphere_style(atom)) error->all(FLERR, "Fix powder/insert requires atom style sphere");
  if (domain->dimension != 3) error->all(FLERR, "Fix powder/insert requires a 3d simulation");
  if (atom->tag_enable == 0) error->all(FLERR, "Fix powder/insert requires atom IDs");

  ninsert = utils::bnumeric(FLERR, arg[3], false, lmp);
  if (ninsert <= 0) error->all(FLERR, "Illegal fix powder/insert command: N must be > 0");
  const bigint seed = utils::bnumeric(FLERR, arg[4], false, lmp);
  if (seed <= 0) error->all(FLERR, "Illegal fix powder/insert command: seed must be > 0");
  rng_size = meltdem::coupling::Rng64(static_cast<std::uint64_t>(seed));
  // an independent stream for positions: splitmix of a different word
  rng_pos = meltdem::coupling::Rng64(static_cast<std::uint64_t>(seed) ^ 0x5deece66dULL ^ (1ULL << 63));

  insert_region = nullptr;
  ntype = 1;
  density = -1.0;
  ratemode = ALL;
  rate = 0.0;
  vnew[0] = vnew[1] = vnew[2] = 0.0;
  tempflag = 0;
  temp = 0.0;
  maxattempt = 100;
  gap = 0.0;
  insert_every = 1;
  stall_limit = 1000;
  stall_error = 0;
  nstall = 0;
  int diamflag = 0, byvolume = 0;

  int iarg = 5;
  auto need = [&](int n, const char *kw) {
    if (iarg + n > narg - 1)
      error->all(FLERR, fmt::format("Illegal fix powder/insert command: missing value for {}", kw));
  };
  auto positive = [&](const char *s, const char *what) {
    const double v = utils::numeric(FLERR, s, false, lmp);
    if (!(v > 0.0)) error->all(FLERR, fmt::format("Illegal fix powder/insert command: {} must be > 0", what));
    return v;
  };
  while (iarg < narg) {
    const std::string kw = arg[iarg];
    if (kw == "region") {
      need(1, "region");
      insert_region = meltdem::lammps_api::region(domain, arg[iarg + 1]);
      if (!insert_region)
        error->all(FLERR, fmt::format("Fix powder/insert region ID {} does not exist", arg[iarg + 1]));
      idregion = utils::strdup(arg[iarg + 1]);
      iarg += 2;
    } else if (kw == "diam") {
      need(1, "diam");
      const std::string style = arg[iarg + 1];
      try {
        if (style == "one") {
          need(2, "diam one");
          dist = SizeDistribution::one(utils::numeric(FLERR, arg[iarg + 2], false, lmp));
          iarg += 3;
        } else if (style == "uniform") {
          need(3, "diam uniform");
          dist = SizeDistribution::uniform(utils::numeric(FLERR, arg[iarg + 2], false, lmp),
                                           utils::numeric(FLERR, arg[iarg + 3], false, lmp));
          iarg += 4;
        } else if (style == "normal" || style == "lognormal" || style == "rosin-rammler") {
          need(5, ("diam " + style).c_str());
          double p[4];
          for (int k = 0; k < 4; k++) p[k] = utils::numeric(FLERR, arg[iarg + 2 + k], false, lmp);
          if (style == "normal")
            dist = SizeDistribution::normal(p[0], p[1], p[2], p[3]);
          else if (style == "lognormal")
            dist = SizeDistribution::lognormal(p[0], p[1], p[2], p[3]);
          else
            dist = SizeDistribution::rosin_rammler(p[0], p[1], p[2], p[3]);
          iarg += 6;
        } else if (style == "table") {
          need(2, "diam table");
          // read on rank 0, parse everywhere: every rank then holds the same table
          std::string text;
          int len = 0, ok = 1;
          if (comm->me == 0) {
            FILE *fp = fopen(arg[iarg + 2], "r");
            if (!fp)
              ok = 0;
            else {
              char chunk[4096];
              size_t n;
              while ((n = fread(chunk, 1, sizeof(chunk), fp)) > 0) text.append(chunk, n);
              fclose(fp);
            }
            len = text.size();
          }
          MPI_Bcast(&ok, 1, MPI_INT, 0, world);
          if (!ok)
            error->all(FLERR, fmt::format("Fix powder/insert cannot open diameter table file {}", arg[iarg + 2]));
          MPI_Bcast(&len, 1, MPI_INT, 0, world);
          text.resize(len);
          if (len) MPI_Bcast(&text[0], len, MPI_CHAR, 0, world);
          std::istringstream in(text);
          dist = SizeDistribution::table(meltdem::coupling::parse_size_table(in));
          iarg += 3;
        } else {
          error->all(FLERR, fmt::format("Illegal fix powder/insert command: unknown diam style {}", style));
        }
      } catch (std::invalid_argument &e) {
        error->all(FLERR, fmt::format("Illegal fix powder/insert command: diam {}: {}", style, e.what()));
      }
      diamflag = 1;
    } else if (kw == "byvolume") {
      byvolume = 1;
      iarg += 1;
    } else if (kw == "dens") {
      need(1, "dens");
      density = positive(arg[iarg + 1], "dens");
      iarg += 2;
    } else if (kw == "rate") {
      need(1, "rate");
      if (ratemode == MASSRATE) error->all(FLERR, "Illegal fix powder/insert command: rate and massrate are exclusive");
      rate = positive(arg[iarg + 1], "rate");
      ratemode = RATE;
      iarg += 2;
    } else if (kw == "massrate") {
      need(1, "massrate");
      if (ratemode == RATE) error->all(FLERR, "Illegal fix powder/insert command: rate and massrate are exclusive");
      rate = positive(arg[iarg + 1], "massrate");
      ratemode = MASSRATE;
      iarg += 2;
    } else if (kw == "vel") {
      need(3, "vel");
      for (int k = 0; k < 3; k++) vnew[k] = utils::numeric(FLERR, arg[iarg + 1 + k], false, lmp);
      iarg += 4;
    } else if (kw == "temp") {
      need(1, "temp");
      temp = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (temp < 0.0) error->all(FLERR, "Illegal fix powder/insert command: temp must be >= 0");
      tempflag = 1;
      iarg += 2;
    } else if (kw == "attempts") {
      need(1, "attempts");
      maxattempt = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (maxattempt <= 0) error->all(FLERR, "Illegal fix powder/insert command: attempts must be > 0");
      iarg += 2;
    } else if (kw == "gap") {
      need(1, "gap");
      gap = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (gap < 0.0) error->all(FLERR, "Illegal fix powder/insert command: gap must be >= 0");
      iarg += 2;
    } else if (kw == "type") {
      need(1, "type");
      ntype = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (ntype <= 0 || ntype > atom->ntypes)
        error->all(FLERR, fmt::format("Illegal fix powder/insert command: type {} outside 1..{}", ntype, atom->ntypes));
      iarg += 2;
    } else if (kw == "every") {
      need(1, "every");
      insert_every = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (insert_every <= 0) error->all(FLERR, "Illegal fix powder/insert command: every must be > 0");
      iarg += 2;
    } else if (kw == "stall") {
      need(2, "stall");
      stall_limit = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      if (stall_limit <= 0) error->all(FLERR, "Illegal fix powder/insert command: stall tries must be > 0");
      const std::string act = arg[iarg + 2];
      if (act == "warn")
        stall_error = 0;
      else if (act == "error")
        stall_error = 1;
      else
        error->all(FLERR, fmt::format("Illegal fix powder/insert command: stall action {} (use warn or error)", act));
      iarg += 3;
    } else {
      error->all(FLERR, fmt::format("Illegal fix powder/insert command: unknown keyword {}", kw));
    }
  }

  if (!insert_region) error->all(FLERR, "Illegal fix powder/insert command: region keyword is required");
  if (!diamflag) error->all(FLERR, "Illegal fix powder/insert command: diam keyword is required");
  if (density <= 0.0) error->all(FLERR, "Illegal fix powder/insert command: dens keyword is required");
  if (byvolume) dist = dist.by_volume();

  // the region must hold the largest particle with its gap to the region surface
  Region *region = insert_region;
  if (!region->bboxflag)
    error->all(FLERR, fmt::format("Fix powder/insert region {} is unbounded (use side in)", idregion));
  const double need_len = dist.dmax() + 2.0 * gap;
  if (region->extent_xhi - region->extent_xlo < need_len || region->extent_yhi - region->extent_ylo < need_len ||
      region->extent_zhi - region->extent_zlo < need_len)
    error->all(FLERR, fmt::format("Fix powder/insert region {} cannot hold the particles: its bounding box is "
                                  "smaller than dmax + 2 gap = {}",
                                  idregion, need_len));

  ndrawn = ninserted = nfailed = 0;
  mass_inserted = 0.0;
  credit = 0.0;
  lookahead = 0.0;
  last_insert_step = -1;
  last_tag = 0;

  vector_flag = 1;
  size_vector = 7;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
  force_reneighbor = 1;
  next_reneighbor = update->ntimestep + 1;
}

/* ---------------------------------------------------------------------- */

FixPowderInsert::~FixPowderInsert()
{
  delete[] idregion;
}

int FixPowderInsert::setmask()
{
  return PRE_EXCHANGE | POST_INTEGRATE | END_OF_STEP;
}

/* ---------------------------------------------------------------------- */

// the step being taken, before a fix defined earlier (fix powder/dt) resets dt at its end
void FixPowderInsert::post_integrate()
{
  dt_step = update->dt;
}

/* ---------------------------------------------------------------------- */

void FixPowderInsert::init()
{
  insert_region = meltdem::lammps_api::region(domain, idregion);
  if (!insert_region) error->all(FLERR, fmt::format("Fix powder/insert region ID {} does not exist", idregion));
  Region *region = insert_region;
  // candidates are drawn in the region's extent at definition, which a moving region leaves (a
  // variable shape inside a fixed extent, as a ring following the nozzle inside a block, is fine)
  if (region->dynamic)
    error->all(FLERR,
               "Fix powder/insert region {} cannot be dynamic (move or rotate): candidates are drawn in "
               "its extent at definition",
               idregion);
  // atoms created outside a fixed non-periodic boundary would be lost
  const double lo[3] = {region->extent_xlo, region->extent_ylo, region->extent_zlo};
  const double hi[3] = {region->extent_xhi, region->extent_yhi, region->extent_zhi};
  // (INF bounds mean the box: the candidates are drawn inside it)
  for (int d = 0; d < 3; d++)
    if (domain->boundary[d][0] == 1 && lo[d] < domain->boxlo[d] && lo[d] > -UNBOUNDED)
      error->all(FLERR, fmt::format("Fix powder/insert region {} extends outside the simulation box", idregion));
  for (int d = 0; d < 3; d++)
    if (domain->boundary[d][1] == 1 && hi[d] > domain->boxhi[d] && hi[d] < UNBOUNDED)
      error->all(FLERR, fmt::format("Fix powder/insert region {} extends outside the simulation box", idregion));

  // granular pair styles size their cutoff from existing particles and from fix pour /
  // deposit only: with a smaller cutoff, contacts of the new particles would be missed
  if (force->pair && force->pair->cutforce < dist.dmax())
    error->all(FLERR, fmt::format("Fix powder/insert: pair cutoff {} is smaller than the largest inserted "
                                  "diameter {}; give the pair style a cutoff (e.g. pair_style granular {})",
                                  force->pair->cutforce, dist.dmax(), dist.dmax()));

  fixmelt = nullptr;
  if (tempflag) {
    for (int i = 0; i < modify->nfix; i++)
      if (strcmp(modify->fix[i]->style, "powder/melt") == 0) fixmelt = dynamic_cast<FixPowderMelt *>(modify->fix[i]);
    if (!fixmelt) error->all(FLERR, "Fix powder/insert temp requires fix powder/melt");
    if (temp > fixmelt->material().Tmelt)
      error->all(FLERR, "Fix powder/insert temp {} is above Tmelt {} of fix powder/melt {}: solid grains only", temp,
                 fixmelt->material().Tmelt, fixmelt->id);
  }
}

/* ---------------------------------------------------------------------- */

double FixPowderInsert::particle_mass(double d) const
{
  return density * MathConst::MY_PI / 6.0 * d * d * d;
}

// move diameters whose time has come from the random stream into the pending queue
void FixPowderInsert::draw_due()
{
  if (ratemode == ALL) {
    while (ndrawn < ninsert) {
      pending.push_back(dist.draw(rng_size));
      ndrawn++;
    }
  } else if (ratemode == RATE) {
    // the tolerance keeps sums like 10 x 0.1 from lagging a step behind by round-off
    while (ndrawn < ninsert && credit >= 1.0 - CREDIT_EPS) {
      pending.push_back(dist.draw(rng_size));
      ndrawn++;
      credit -= 1.0;
    }
  } else {
    while (ndrawn < ninsert) {
      if (lookahead == 0.0) lookahead = dist.draw(rng_size);
      const double m = particle_mass(lookahead);
      if (credit < m * (1.0 - CREDIT_EPS)) break;
      pending.push_back(lookahead);
      ndrawn++;
      credit -= m;
      lookahead = 0.0;
    }
  }
}

// force a reneighbor (and so pre_exchange) on the next insertion step when work is due
void FixPowderInsert::schedule()
{
  if (pending.empty()) {
    next_reneighbor = 0;
    return;
  }
  bigint next = update->ntimestep + 1;
  if (insert_every > 1 && next % insert_every) next += insert_every - next % insert_every;
  next_reneighbor = next;
}

void FixPowderInsert::setup_pre_exchange()
{
  draw_due();
  schedule();
}

void FixPowderInsert::end_of_step()
{
  // accumulate rate*dt with the timestep of the step just done: dt may change
  if (ratemode != ALL && ndrawn < ninsert) credit += rate * dt_step;
  draw_due();
  schedule();
}

/* ---------------------------------------------------------------------- */

// sphere (center x, radius r) lies inside the insertion region, gap from its surface
int FixPowderInsert::region_fits(double *x, double r)
{
  Region *region = insert_region;
  if (!region->match(x[0], x[1], x[2])) return 0;
  return region->surface(x[0], x[1], x[2], r + gap) == 0;
}

// sphere touches (closer than gap) a granular wall
int FixPowderInsert::wall_overlap(double *x, double r)
{
  const double reach = r + gap;
  for (int i = 0; i < modify->nfix; i++) {
    auto *w = dynamic_cast<FixWallGran *>(modify->fix[i]);
    if (!w) continue;
    const int style = WallGranAccess::wallstyle_of(w);
    if (style == REGION) {
      Region *wr = meltdem::lammps_api::region(domain, WallGranAccess::idregion_of(w));
      if (!wr) continue;
      // as fix wall/gran/region: the particle lives inside the wall region
      if (!wr->match(x[0], x[1], x[2])) return 1;
      if (wr->surface(x[0], x[1], x[2], reach) > 0) return 1;
    } else if (style == ZCYLINDER) {
      const double rxy = sqrt(x[0] * x[0] + x[1] * x[1]);
      // fix wall/gran pushes every particle outside the cylinder inwards: inside only
      if (WallGranAccess::cylradius_of(w) - rxy < reach) return 1;
    } else {
      double shift;
      WallGranAccess::wiggle_shift(w, (update->ntimestep - WallGranAccess::time_origin_of(w)) * update->dt, shift);
      const double lo = WallGranAccess::lo_of(w) + shift, hi = WallGranAccess::hi_of(w) + shift;
      // a plane wall holds particles between lo and hi (NULL: no wall there)
      if (x[style] - lo < reach || hi - x[style] < reach) return 1;
    }
  }
  return 0;
}

/* ---------------------------------------------------------------------- */

void FixPowderInsert::pre_exchange()
{
  if (next_reneighbor != update->ntimestep) return;
  if (pending.empty()) return;
  last_insert_step = update->ntimestep;

  // same as the start of Comm::exchange(): inserting overwrites ghost atoms
  if (atom->map_style != Atom::MAP_NONE) atom->map_clear();
  atom->nghost = 0;
  atom->avec->clear_bonus();

  Region *region = insert_region;
  region->prematch();
  for (int i = 0; i < modify->nfix; i++) {
    auto *w = dynamic_cast<FixWallGran *>(modify->fix[i]);
    if (w && WallGranAccess::wallstyle_of(w) == REGION) {
      if (Region *wr = meltdem::lammps_api::region(domain, WallGranAccess::idregion_of(w))) wr->prematch();
    }
  }

  // candidates are drawn in the region's bounding box within the simulation box: a region
  // given as INF or wider than a periodic box is cut to the box (its periodic images are
  // checked below)
  double blo[3] = {region->extent_xlo, region->extent_ylo, region->extent_zlo};
  double bhi[3] = {region->extent_xhi, region->extent_yhi, region->extent_zhi};
  for (int d = 0; d < 3; d++) {
    blo[d] = MAX(blo[d], domain->boxlo[d]);
    bhi[d] = MIN(bhi[d], domain->boxhi[d]);
  }
  // largest new radius: pending diameters from a restart may exceed a changed distribution
  double dnew = dist.dmax();
  for (double d : pending) dnew = MAX(dnew, d);
  const double rnew = 0.5 * dnew;

  // gather every particle (all ranks, periodic images) that can touch a new one
  double **x = atom->x;
  double *radius = atom->radius;
  const int nlocal = atom->nlocal;
  std::vector<double> mine;
  double rmax_local = 0.0;
  const int *periodic = domain->periodicity;
  const double *prd = domain->prd;
  for (int i = 0; i < nlocal; i++) {
    for (int ix = -periodic[0]; ix <= periodic[0]; ix++)
      for (int iy = -periodic[1]; iy <= periodic[1]; iy++)
        for (int iz = -periodic[2]; iz <= periodic[2]; iz++) {
          const double p[3] = {x[i][0] + ix * prd[0], x[i][1] + iy * prd[1], x[i][2] + iz * prd[2]};
          double dsq = 0.0;
          for (int d = 0; d < 3; d++) {
            const double out = p[d] < blo[d] ? blo[d] - p[d] : (p[d] > bhi[d] ? p[d] - bhi[d] : 0.0);
            dsq += out * out;
          }
          const double reach = radius[i] + rnew + gap;
          if (dsq < reach * reach) {
            mine.insert(mine.end(), {p[0], p[1], p[2], radius[i]});
            if (radius[i] > rmax_local) rmax_local = radius[i];
          }
        }
  }
  const int nprocs = comm->nprocs;
  int nmine = mine.size();
  std::vector<int> counts(nprocs), displs(nprocs, 0);
  MPI_Allgather(&nmine, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  for (int p = 1; p < nprocs; p++) displs[p] = displs[p - 1] + counts[p - 1];
  std::vector<double> near(displs[nprocs - 1] + counts[nprocs - 1]);
  MPI_Allgatherv(mine.data(), nmine, MPI_DOUBLE, near.data(), counts.data(), displs.data(), MPI_DOUBLE, world);
  double rmax_near = 0.0;
  MPI_Allreduce(&rmax_local, &rmax_near, 1, MPI_DOUBLE, MPI_MAX, world);
  if (rmax_near < rnew) rmax_near = rnew;

  // hash grid: a candidate can only touch particles in its own and the 26 next cells
  const double cell = rnew + rmax_near + gap;
  auto key_of = [&](const double *p, int dx, int dy, int dz) {
    const int64_t i = (int64_t)floor((p[0] - blo[0]) / cell) + 2 + dx;
    const int64_t j = (int64_t)floor((p[1] - blo[1]) / cell) + 2 + dy;
    const int64_t k = (int64_t)floor((p[2] - blo[2]) / cell) + 2 + dz;
    return (i << 42) ^ (j << 21) ^ k;
  };
  std::unordered_map<int64_t, std::vector<int>> grid;
  int nnear = near.size() / 4;
  for (int n = 0; n < nnear; n++) grid[key_of(&near[4 * n], 0, 0, 0)].push_back(n);

  auto overlaps = [&](const double *c, double r) {
    for (int dx = -1; dx <= 1; dx++)
      for (int dy = -1; dy <= 1; dy++)
        for (int dz = -1; dz <= 1; dz++) {
          auto it = grid.find(key_of(c, dx, dy, dz));
          if (it == grid.end()) continue;
          for (int n : it->second) {
            const double *q = &near[4 * n];
            const double ddx = c[0] - q[0], ddy = c[1] - q[1], ddz = c[2] - q[2];
            const double reach = r + q[3] + gap;
            if (ddx * ddx + ddy * ddy + ddz * ddz < reach * reach) return true;
          }
        }
    return false;
  };

  // place the queue in order; stop at the first particle that finds no room this step,
  // so particles are inserted in the order they were drawn
  std::vector<double> placed;  // x y z d of the particles placed now
  while (!pending.empty()) {
    const double d = pending.front(), r = 0.5 * d;
    double c[3];
    int ok = 0;
    for (int a = 0; a < maxattempt; a++) {
      for (int k = 0; k < 3; k++) c[k] = blo[k] + rng_pos.uniform() * (bhi[k] - blo[k]);
      if (region_fits(c, r) && !wall_overlap(c, r) && !overlaps(c, r)) {
        ok = 1;
        break;
      }
      nfailed++;
    }
    if (!ok) break;
    pending.pop_front();
    placed.insert(placed.end(), {c[0], c[1], c[2], d});
    // the new particle and its periodic images, for the particles placed after it
    for (int ix = -periodic[0]; ix <= periodic[0]; ix++)
      for (int iy = -periodic[1]; iy <= periodic[1]; iy++)
        for (int iz = -periodic[2]; iz <= periodic[2]; iz++) {
          const double p[3] = {c[0] + ix * prd[0], c[1] + iy * prd[1], c[2] + iz * prd[2]};
          near.insert(near.end(), {p[0], p[1], p[2], r});
          grid[key_of(p, 0, 0, 0)].push_back(nnear++);
        }
  }
  const int nnew = placed.size() / 4;

  // above the current max atom ID, as fix pour, and above every ID this fix ever gave:
  // when the particle with the largest ID is deleted (melted away, left the mesh) its ID
  // must not come back, since the coupling keys each particle's fluid by its ID
  tagint maxtag = 0;
  for (int i = 0; i < nlocal; i++) maxtag = MAX(maxtag, atom->tag[i]);
  tagint maxtag_all;
  MPI_Allreduce(&maxtag, &maxtag_all, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  maxtag_all = MAX(maxtag_all, last_tag);

  // each rank creates the particles whose centre lies in its subdomain; beyond a
  // non-periodic box face (shrink-wrapped box) the edge rank takes them
  const double *sublo = domain->sublo, *subhi = domain->subhi;
  const double BIG = 1.0e300;
  double olo[3], ohi[3];
  for (int d = 0; d < 3; d++) {
    olo[d] = sublo[d];
    ohi[d] = subhi[d];
    if (periodic[d]) continue;
    if (comm->layout != Comm::LAYOUT_TILED) {
      if (comm->myloc[d] == 0) olo[d] = -BIG;
      if (comm->myloc[d] == comm->procgrid[d] - 1) ohi[d] = BIG;
    } else {
      if (comm->mysplit[d][0] == 0.0) olo[d] = -BIG;
      if (comm->mysplit[d][1] == 1.0) ohi[d] = BIG;
    }
  }
  for (int k = 0; k < nnew; k++) {
    double c[3] = {placed[4 * k], placed[4 * k + 1], placed[4 * k + 2]};
    const double d = placed[4 * k + 3];
    imageint image = ((imageint)IMGMAX << IMG2BITS) | ((imageint)IMGMAX << IMGBITS) | IMGMAX;
    domain->remap(c, image);
    mass_inserted += particle_mass(d);
    if (c[0] < olo[0] || c[0] >= ohi[0] || c[1] < olo[1] || c[1] >= ohi[1] || c[2] < olo[2] || c[2] >= ohi[2]) continue;
    atom->avec->create_atom(ntype, c);
    const int n = atom->nlocal - 1;
    atom->tag[n] = maxtag_all + k + 1;
    atom->mask[n] = 1 | groupbit;
    atom->image[n] = image;
    atom->v[n][0] = vnew[0];
    atom->v[n][1] = vnew[1];
    atom->v[n][2] = vnew[2];
    atom->radius[n] = 0.5 * d;
    atom->rmass[n] = particle_mass(d);
    modify->create_attribute(n);
    if (fixmelt) fixmelt->set_particle_temperature(n, temp);
  }
  ninserted += nnew;

  // a full region: the queue waits (no overlap is ever forced), but say so once per stall,
  // naming the knobs; every rank took the same decisions, so every rank gets here
  nstall = nnew ? 0 : nstall + 1;
  if (nstall == stall_limit) {
    const std::string msg = fmt::format(
        "Fix powder/insert {}: no particle placed in {} insertion tries in a row ({} trial positions each), "
        "{} particles pending (next d = {:.4g}): region {} has no room. The particles wait; to make progress "
        "enlarge region {} or empty it faster, raise attempts, lower gap, or lower rate/massrate "
        "(stall {} {})",
        id, nstall, maxattempt, pending.size(), pending.front(), idregion, idregion, stall_limit,
        stall_error ? "error" : "warn");
    if (stall_error) error->all(FLERR, msg);
    if (comm->me == 0) error->warning(FLERR, msg);
  }

  if (nnew) {
    last_tag = maxtag_all + nnew;
    atom->natoms += nnew;
    if (atom->natoms < 0) error->all(FLERR, "Too many total atoms");
    if (maxtag_all + nnew >= MAXTAGINT) error->all(FLERR, "New atom IDs exceed maximum allowed ID");
  }
  if (atom->map_style != Atom::MAP_NONE) {
    if (nnew) atom->map_init();
    atom->map_set();
  }
  // the next insertion is scheduled by end_of_step
}

/* ---------------------------------------------------------------------- */

double FixPowderInsert::compute_vector(int n)
{
  switch (n) {
    case 0:
      return ninserted;
    case 1:
      return pending.size();
    case 2:
      return nfailed;
    case 3:
      return mass_inserted;
    case 4: {
      double m = 0.0;
      for (double d : pending) m += particle_mass(d);
      return m;
    }
    case 5:
      return ndrawn;
    case 6:
      return nstall;
    default:
      return 0.0;
  }
}

/* ----------------------------------------------------------------------
   pending queue, counters and both random streams go into the restart file
------------------------------------------------------------------------- */

void FixPowderInsert::write_restart(FILE *fp)
{
  Writer w;
  w.put<int>(RESTART_VERSION);
  w.put<bigint>(ndrawn);
  w.put<bigint>(ninserted);
  w.put<bigint>(nfailed);
  w.put<double>(mass_inserted);
  w.put<double>(credit);
  w.put<double>(lookahead);
  for (auto s : rng_size.state()) w.put<std::uint64_t>(s);
  for (auto s : rng_pos.state()) w.put<std::uint64_t>(s);
  w.put<bigint>(pending.size());
  for (double d : pending) w.put<double>(d);
  w.put<tagint>(last_tag);
  if (comm->me == 0) {
    int size = w.buf.size();
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(w.buf.data(), 1, size, fp);
  }
}

void FixPowderInsert::restart(char *buf)
{
  Reader r{buf};
  if (r.get<int>() != RESTART_VERSION) error->all(FLERR, "Fix powder/insert restart data has an unknown version");
  ndrawn = r.get<bigint>();
  ninserted = r.get<bigint>();
  nfailed = r.get<bigint>();
  mass_inserted = r.get<double>();
  credit = r.get<double>();
  lookahead = r.get<double>();
  std::array<std::uint64_t, 4> s;
  for (auto &v : s) v = r.get<std::uint64_t>();
  rng_size.set_state(s);
  for (auto &v : s) v = r.get<std::uint64_t>();
  rng_pos.set_state(s);
  const bigint np = r.get<bigint>();
  pending.clear();
  for (bigint i = 0; i < np; i++) pending.push_back(r.get<double>());
  last_tag = r.get<tagint>();
  if (ndrawn > ninsert)
    error->all(FLERR, "Fix powder/insert restart holds more drawn particles than the new N requests");
}
