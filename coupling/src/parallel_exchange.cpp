#include "meltdem/coupling/parallel_exchange.h"

#include "meltdem/coupling/exact_sum.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace meltdem::coupling {

namespace {

// Gather `per` doubles per item from every rank, in rank order.
void allgather_doubles(const std::vector<double> &local, int per, MPI_Comm comm, std::vector<double> &all,
                       std::vector<int> &counts, std::vector<int> &displs)
{
  int size = 1;
  MPI_Comm_size(comm, &size);
  const int n = int(local.size()) / per;
  counts.assign(size, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  displs.assign(size, 0);
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  const int total = displs[size - 1] + counts[size - 1];
  std::vector<int> c(size), d(size);
  for (int r = 0; r < size; ++r) c[r] = counts[r] * per, d[r] = displs[r] * per;
  all.assign(std::size_t(total) * per, 0.0);
  MPI_Allgatherv(local.data(), n * per, MPI_DOUBLE, all.data(), c.data(), d.data(), MPI_DOUBLE, comm);
}

}  // namespace

ParallelExchange::ParallelExchange(const DistributionMesh &local_mesh, DistributionModel model, MPI_Comm comm) :
    mesh_(local_mesh), model_(model), comm_(comm)
{
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

void ParallelExchange::locate(const std::vector<ParticleShape> &local)
{
  std::vector<double> mine;
  mine.reserve(4 * local.size());
  for (const ParticleShape &p : local) {
    if (!(p.radius > 0.0) || !std::isfinite(p.radius) || !p.x.allFinite())
      throw std::invalid_argument("particle exchange: radius " + std::to_string(p.radius) +
                                  " or position not finite/positive");
    mine.insert(mine.end(), {p.x.x(), p.x.y(), p.x.z(), p.radius, double(p.id)});
  }
  std::vector<double> all;
  allgather_doubles(mine, 5, comm_, all, counts_, displs_);
  const std::size_t n = all.size() / 5;
  offset_ = std::size_t(displs_[rank_]);
  all_.resize(n);
  for (std::size_t g = 0; g < n; ++g)
    all_[g] = {Eigen::Vector3d(all[5 * g], all[5 * g + 1], all[5 * g + 2]), all[5 * g + 3],
               std::int64_t(all[5 * g + 4])};

  // the cell holding each centre: the lowest rank that finds it owns it
  std::vector<long> home(n, -1);
  std::vector<int> owner(n, INT_MAX);
  for (std::size_t g = 0; g < n; ++g) {
    home[g] = mesh_.find_cell(all_[g].x);
    if (home[g] >= 0) owner[g] = rank_;
  }
  if (n) MPI_Allreduce(MPI_IN_PLACE, owner.data(), int(n), MPI_INT, MPI_MIN, comm_);
  for (std::size_t g = 0; g < n; ++g)
    if (owner[g] != rank_) home[g] = -1;

  // the owner's home-cell box, for the neighbours model (others see +inf/-inf)
  std::vector<double> hbox;
  if (model_ == DistributionModel::Neighbours && n) {
    const double inf = std::numeric_limits<double>::infinity();
    hbox.assign(6 * n, 0.0);
    for (std::size_t g = 0; g < n; ++g) {
      Eigen::Vector3d lo(inf, inf, inf), hi(-inf, -inf, -inf);
      if (home[g] >= 0) mesh_.cell_bounds(home[g], lo, hi);
      for (int a = 0; a < 3; ++a) hbox[6 * g + a] = -lo[a], hbox[6 * g + 3 + a] = hi[a];
    }
    MPI_Allreduce(MPI_IN_PLACE, hbox.data(), int(6 * n), MPI_DOUBLE, MPI_MAX, comm_);
  }

  // raw weights over this rank's cells
  start_.assign(n + 1, 0);
  cells_.clear();
  weights_.clear();
  std::vector<CellWeight> raw;
  Eigen::Vector3d hlo = Eigen::Vector3d::Zero(), hhi = Eigen::Vector3d::Zero();
  for (std::size_t g = 0; g < n; ++g) {
    start_[g] = cells_.size();
    if (owner[g] == INT_MAX) continue;  // outside the mesh
    if (!hbox.empty()) {
      hlo = Eigen::Vector3d(-hbox[6 * g], -hbox[6 * g + 1], -hbox[6 * g + 2]);
      hhi = Eigen::Vector3d(hbox[6 * g + 3], hbox[6 * g + 4], hbox[6 * g + 5]);
    }
    raw.clear();
    append_raw_weights(mesh_, model_, all_[g].x, all_[g].radius, home[g], hlo, hhi, raw);
    for (const CellWeight &w : raw) cells_.push_back(w.cell), weights_.push_back(w.weight);
  }
  start_[n] = cells_.size();

  // global normalisation: compensated local sums, then summed over the ranks
  std::vector<double> sums(2 * n, 0.0);
  for (std::size_t g = 0; g < n; ++g) {
    ExactSum s;
    for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) s.add(weights_[k]);
    sums[g] = s.hi(), sums[n + g] = s.lo();
  }
  if (n) MPI_Allreduce(MPI_IN_PLACE, sums.data(), int(2 * n), MPI_DOUBLE, MPI_SUM, comm_);
  inside_.assign(n, 0);
  for (std::size_t g = 0; g < n; ++g) {
    const double total = sums[g] + sums[n + g];
    if (!(total > 0.0)) {
      for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) weights_[k] = 0.0;
      continue;
    }
    inside_[g] = 1;
    for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) weights_[k] /= total;
  }

  // each particle's share of its cells, by its conductance there: its weight in the cell times
  // its size (G ~ k Nu d), so a shrinking remnant keeps enough of a cell to melt away (every
  // rank holds every particle's weights over its own cells, so the per-cell sums are complete)
  share_.assign(cells_.size(), 0.0);
  const long ncells = cells_.empty() ? 0 : *std::max_element(cells_.begin(), cells_.end()) + 1;
  if (claimed_.size() < std::size_t(ncells)) claimed_.resize(std::size_t(ncells), 0.0);  // zero between calls
  for (std::size_t g = 0; g < n; ++g)
    for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) {
      share_[k] = weights_[k] * all_[g].radius;
      claimed_[std::size_t(cells_[k])] += share_[k];
    }
  for (std::size_t k = 0; k < cells_.size(); ++k)
    if (share_[k] > 0.0) share_[k] /= claimed_[std::size_t(cells_[k])];
  for (const long c : cells_) claimed_[std::size_t(c)] = 0.0;
}

void ParallelExchange::sample_global(const CellFluidFields &f, std::vector<SampledFluid> &out) const
{
  if (!f.T || !f.k || !f.rho || !f.mu || !f.cp || !f.U)
    throw std::invalid_argument("particle exchange: T, k, rho, mu, cp and U are required to sample the fluid");
  // sample_fluid's sums over this rank's cells, summed over the ranks, then finished
  const std::size_t n = all_.size();
  std::vector<double> partial(kSampleSums * n, 0.0);
  for (std::size_t g = 0; g < n; ++g)
    for (std::size_t k = start_[g]; k < start_[g + 1]; ++k)
      add_cell_to_sample(f, cells_[k], weights_[k], share_[k], &partial[kSampleSums * g]);
  if (n) MPI_Allreduce(MPI_IN_PLACE, partial.data(), int(kSampleSums * n), MPI_DOUBLE, MPI_SUM, comm_);
  out.assign(n, SampledFluid());
  for (std::size_t g = 0; g < n; ++g)
    if (inside_[g]) out[g] = finish_sample(&partial[kSampleSums * g]);
}

void ParallelExchange::sample(const CellFluidFields &f, std::vector<SampledFluid> &local_out) const
{
  std::vector<SampledFluid> all;
  sample_global(f, all);
  local_out.assign(all.begin() + std::ptrdiff_t(offset_), all.begin() + std::ptrdiff_t(offset_) + counts_[rank_]);
}

void ParallelExchange::deposit(const std::vector<Amounts> &local_amounts, std::vector<Amounts> &cell_amounts) const
{
  if (local_amounts.size() != std::size_t(counts_[rank_]))
    throw std::invalid_argument("particle exchange: deposit() needs one amount per located local particle");
  std::vector<double> mine;
  mine.reserve(kComponents * local_amounts.size());
  for (const Amounts &a : local_amounts) mine.insert(mine.end(), a.begin(), a.end());
  std::vector<double> all;
  std::vector<int> counts, displs;
  allgather_doubles(mine, kComponents, comm_, all, counts, displs);
  for (std::size_t g = 0; g < all_.size(); ++g) {
    if (!inside_[g]) continue;
    const double *a = &all[kComponents * g];
    for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) {
      Amounts &c = cell_amounts.at(std::size_t(cells_[k]));
      for (int q = 0; q < kComponents; ++q) c[q] += weights_[k] * a[q];
    }
  }
}

void ParallelExchange::weighted_mean(const double *cell_values, std::vector<double> &local_out) const
{
  const std::size_t n = all_.size();
  std::vector<double> sums(n, 0.0);
  for (std::size_t g = 0; g < n; ++g)
    for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) sums[g] += weights_[k] * cell_values[cells_[k]];
  if (n) MPI_Allreduce(MPI_IN_PLACE, sums.data(), int(n), MPI_DOUBLE, MPI_SUM, comm_);
  local_out.assign(sums.begin() + std::ptrdiff_t(offset_), sums.begin() + std::ptrdiff_t(offset_) + counts_[rank_]);
}

void ParallelExchange::deposit_taken(const std::vector<std::int64_t> &ids, const std::vector<double> &heat,
                                     const std::vector<Eigen::Vector3d> &impulse, const std::vector<double> &particle_T,
                                     const CellFluidFields &f, std::vector<Amounts> &cell_amounts) const
{
  const std::size_t nmine = ids.size();
  if (heat.size() != nmine || impulse.size() != nmine || particle_T.size() != nmine)
    throw std::invalid_argument(
        "particle exchange: deposit_taken() needs one heat, impulse and temperature per particle id");
  if (!f.rho || !f.cp || !f.T) throw std::invalid_argument("particle exchange: deposit_taken() needs T, rho and cp");
  // any rank may report any located particle (it may have moved to another DEM rank since
  // it was located): gather (id, heat, impulse, T) and find each located particle's entry
  constexpr int kIn = 6, kOut = 5;
  std::vector<double> mine;
  mine.reserve(kIn * nmine);
  for (std::size_t i = 0; i < nmine; ++i)
    mine.insert(mine.end(), {double(ids[i]), heat[i], impulse[i].x(), impulse[i].y(), impulse[i].z(), particle_T[i]});
  std::vector<double> gathered;
  std::vector<int> counts, displs;
  allgather_doubles(mine, kIn, comm_, gathered, counts, displs);
  const std::size_t n = all_.size(), ngathered = gathered.size() / kIn;
  std::vector<double> all(kOut * n, 0.0);
  // usually the reports come in the order the particles were located: look them up by id
  // only where they do not
  bool same_order = ngathered == n;
  for (std::size_t g = 0; g < n && same_order; ++g) same_order = std::int64_t(gathered[kIn * g]) == all_[g].id;
  if (same_order) {
    for (std::size_t g = 0; g < n; ++g)
      for (int q = 0; q < kOut; ++q) all[kOut * g + q] = gathered[kIn * g + 1 + q];
  } else {
    std::unordered_map<std::int64_t, std::size_t> entry;
    for (std::size_t k = 0; k < ngathered; ++k) entry[std::int64_t(gathered[kIn * k])] = k;
    for (std::size_t g = 0; g < n; ++g) {
      const auto it = entry.find(all_[g].id);
      if (it == entry.end()) continue;
      for (int q = 0; q < kOut; ++q) all[kOut * g + q] = gathered[kIn * it->second + 1 + q];
    }
  }
  // the heat a cell can give particle g before it reaches the particle's temperature: g's
  // share of the cell's capacity times the cell's temperature difference to the particle, in
  // the direction g took heat (the parcel g exchanged heat with is the sum of these shares)
  std::vector<double> available(cells_.size(), 0.0);
  if (f.volume)
    for (std::size_t g = 0; g < n; ++g)
      for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) {
        const long c = cells_[k];
        const double capacity = share_[k] * f.rho[c] * f.cp[c] * f.volume[c];
        const double *a = &all[kOut * g];
        const double dT = a[0] >= 0.0 ? f.T[c] - a[4] : a[4] - f.T[c];
        available[k] = capacity * std::max(dT, 0.0);
      }
  // per particle over every rank's cells: the parcel's capacity and mass, the available heat
  std::vector<double> sums(3 * n, 0.0);
  for (std::size_t g = 0; g < n; ++g)
    for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) {
      sums[3 * g] += parcel_capacity(f, k);
      sums[3 * g + 1] += parcel_mass(f, k);
      sums[3 * g + 2] += available[k];
    }
  if (n) MPI_Allreduce(MPI_IN_PLACE, sums.data(), int(3 * n), MPI_DOUBLE, MPI_SUM, comm_);
  for (std::size_t g = 0; g < n; ++g) {
    if (!inside_[g]) continue;
    const double *a = &all[kOut * g];
    const double capacity = sums[3 * g], mass = sums[3 * g + 1], room = sums[3 * g + 2];
    const double Q = std::abs(a[0]);
    for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) {
      const long c = cells_[k];
      const double by_capacity = capacity > 0.0 ? parcel_capacity(f, k) / capacity : weights_[k];
      // each cell by the heat it has above (below) the particle's temperature, so each moves
      // the same fraction of the way towards it and none passes it; the two-body exchange
      // never takes more (round-off aside: what is beyond all cells' room goes by capacity)
      const double given =
          Q <= room ? (room > 0.0 ? Q * available[k] / room : 0.0) : available[k] + (Q - room) * by_capacity;
      const double mass_share = mass > 0.0 ? parcel_mass(f, k) / mass : weights_[k];
      Amounts &cell = cell_amounts.at(std::size_t(c));
      cell[kEnthalpy] -= std::copysign(given, a[0]);
      for (int d = 0; d < 3; ++d) cell[kMomX + d] -= mass_share * a[1 + d];
    }
  }
}

double ParallelExchange::parcel_mass(const CellFluidFields &f, std::size_t k) const
{
  const long c = cells_[k];
  return f.volume ? share_[k] * f.rho[c] * f.volume[c] : weights_[k] * f.rho[c];
}

double ParallelExchange::parcel_capacity(const CellFluidFields &f, std::size_t k) const
{
  return parcel_mass(f, k) * f.cp[cells_[k]];
}

void ParallelExchange::local_weights(std::int64_t g, std::vector<CellWeight> &out) const
{
  out.clear();
  for (std::size_t k = start_[std::size_t(g)]; k < start_[std::size_t(g) + 1]; ++k)
    out.push_back({cells_[k], weights_[k]});
}

}  // namespace meltdem::coupling

namespace meltdem::coupling {

void ParallelExchange::nearest_solid(const double *solid_fraction, double reach, std::vector<SolidSurface> &out) const
{
  const std::size_t n = all_.size();
  std::vector<SolidSurface> local(n);
  struct DistRank {
    double d;
    int rank;
  };
  std::vector<DistRank> best(n, DistRank{std::numeric_limits<double>::infinity(), rank_});
  std::vector<long> cells;
  std::vector<Eigen::Vector3d> lo, hi;
  for (std::size_t g = 0; g < n; ++g) {
    cells.clear();
    mesh_.cells_in_sphere(all_[g].x, all_[g].radius + reach, cells);
    lo.clear();
    hi.clear();
    for (long c : cells) {
      if (!(solid_fraction[c] >= 0.5)) continue;
      Eigen::Vector3d l, h;
      mesh_.cell_bounds(c, l, h);
      lo.push_back(l);
      hi.push_back(h);
    }
    local[g] = nearest_solid_surface(all_[g].x, lo, hi);
    if (local[g].present) best[g].d = local[g].distance;
  }
  // the rank with the nearest surface provides it (lowest rank on ties)
  if (n) MPI_Allreduce(MPI_IN_PLACE, best.data(), int(n), MPI_DOUBLE_INT, MPI_MINLOC, comm_);
  constexpr int kPack = 8;  // present, distance, point, normal
  std::vector<double> pack(kPack * n, 0.0);
  for (std::size_t g = 0; g < n; ++g)
    if (local[g].present && best[g].rank == rank_) {
      double *q = &pack[kPack * g];
      q[0] = 1.0, q[1] = local[g].distance;
      for (int a = 0; a < 3; ++a) q[2 + a] = local[g].point[a], q[5 + a] = local[g].normal[a];
    }
  if (n) MPI_Allreduce(MPI_IN_PLACE, pack.data(), int(kPack * n), MPI_DOUBLE, MPI_SUM, comm_);
  out.assign(n, SolidSurface());
  for (std::size_t g = 0; g < n; ++g) {
    const double *q = &pack[kPack * g];
    if (q[0] == 0.0) continue;
    out[g].present = true;
    out[g].distance = q[1];
    out[g].point = Eigen::Vector3d(q[2], q[3], q[4]);
    out[g].normal = Eigen::Vector3d(q[5], q[6], q[7]);
  }
}

}  // namespace meltdem::coupling
