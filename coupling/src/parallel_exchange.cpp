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

constexpr int kTag = 7401;
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

// does the sphere (c, r) reach the box stored at b (lo x, y, z, hi x, y, z)?
bool sphere_reaches_box(const Eigen::Vector3d &c, double r, const double *b)
{
  if (!(b[0] <= b[3])) return false;  // a rank without cells
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double lo = b[a] - r, hi = b[3 + a] + r;
    if (c[a] < lo || c[a] > hi) return false;
    const double below = b[a] - c[a], above = c[a] - b[3 + a];
    const double out = std::max({below, above, 0.0});
    d2 += out * out;
  }
  return d2 <= r * r;
}

}  // namespace

ParallelExchange::ParallelExchange(const DistributionMesh &local_mesh, DistributionModel model, MPI_Comm comm) :
    mesh_(local_mesh), model_(model), comm_(comm)
{
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

void ParallelExchange::exchange_rows(const std::vector<std::size_t> &send_rows, const std::vector<double> &send,
                                     int per, const std::vector<std::size_t> &recv_rows, std::vector<double> &recv,
                                     bool copy_own) const
{
  std::vector<MPI_Request> requests;
  requests.reserve(2 * std::size_t(size_));
  for (int r = 0; r < size_; ++r) {
    const std::size_t n = recv_rows[r + 1] - recv_rows[r];
    if (!n || r == rank_) continue;
    requests.emplace_back();
    MPI_Irecv(recv.data() + recv_rows[r] * per, int(n * per), MPI_DOUBLE, r, kTag, comm_, &requests.back());
    traffic_.messages_received += 1;
    traffic_.bytes_received += std::int64_t(n * per * sizeof(double));
  }
  for (int r = 0; r < size_; ++r) {
    const std::size_t n = send_rows[r + 1] - send_rows[r];
    if (!n) continue;
    if (r == rank_) {
      if (copy_own)
        std::copy(send.begin() + std::ptrdiff_t(send_rows[r] * per),
                  send.begin() + std::ptrdiff_t(send_rows[r + 1] * per),
                  recv.begin() + std::ptrdiff_t(recv_rows[r] * per));
      continue;
    }
    requests.emplace_back();
    MPI_Isend(send.data() + send_rows[r] * per, int(n * per), MPI_DOUBLE, r, kTag, comm_, &requests.back());
    traffic_.messages_sent += 1;
    traffic_.bytes_sent += std::int64_t(n * per * sizeof(double));
  }
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

void ParallelExchange::route(const std::vector<ParticleShape> &local, double grow, Routing &routing,
                             std::vector<ParticleShape> &visitors) const
{
  const std::vector<double> &boxes = boxes_;
  // the ranks each particle reaches, in rank order (a box grown by a relative tolerance, so
  // that a sphere touching a processor boundary goes to both sides)
  std::vector<std::vector<std::size_t>> to(static_cast<std::size_t>(size_));
  for (std::size_t i = 0; i < local.size(); ++i) {
    const double reach = local[i].radius + grow;
    const double tol = 1e-12 * std::max(reach, local[i].x.cwiseAbs().maxCoeff());
    for (int r = 0; r < size_; ++r)
      if (sphere_reaches_box(local[i].x, reach + tol, &boxes[std::size_t(6 * r)])) to[r].push_back(i);
  }
  routing.send_from.assign(std::size_t(size_) + 1, 0);
  routing.send_index.clear();
  std::vector<int> send_counts(static_cast<std::size_t>(size_)), recv_counts(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r) {
    routing.send_index.insert(routing.send_index.end(), to[r].begin(), to[r].end());
    routing.send_from[r + 1] = routing.send_index.size();
    send_counts[r] = int(to[r].size());
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm_);
  routing.recv_from.assign(std::size_t(size_) + 1, 0);
  for (int r = 0; r < size_; ++r) routing.recv_from[r + 1] = routing.recv_from[r] + std::size_t(recv_counts[r]);

  constexpr int kShape = 5;
  std::vector<double> send(kShape * routing.send_index.size());
  for (std::size_t j = 0; j < routing.send_index.size(); ++j) {
    const ParticleShape &p = local[routing.send_index[j]];
    double *q = &send[kShape * j];
    q[0] = p.x.x(), q[1] = p.x.y(), q[2] = p.x.z(), q[3] = p.radius, q[4] = double(p.id);
  }
  std::vector<double> recv(kShape * routing.recv_from[size_]);
  exchange_rows(routing.send_from, send, kShape, routing.recv_from, recv, true);
  visitors.resize(routing.recv_from[size_]);
  for (std::size_t v = 0; v < visitors.size(); ++v) {
    const double *q = &recv[kShape * v];
    visitors[v] = {Eigen::Vector3d(q[0], q[1], q[2]), q[3], std::int64_t(q[4])};
  }
}

void ParallelExchange::forward(const Routing &routing, const std::vector<double> &per_local, int per,
                               std::vector<double> &per_visitor) const
{
  const std::size_t p = std::size_t(per);
  per_visitor.resize(p * routing.recv_from[size_]);
  // this rank's own particles straight to their visitor rows, the others' through messages
  const std::size_t self0 = routing.send_from[rank_], self1 = routing.send_from[rank_ + 1];
  for (std::size_t j = self0; j < self1; ++j)
    std::copy_n(&per_local[p * routing.send_index[j]], per, &per_visitor[p * (routing.recv_from[rank_] + j - self0)]);
  if (size_ == 1) return;
  std::vector<double> send(p * routing.send_index.size());
  for (std::size_t j = 0; j < routing.send_index.size(); ++j)
    if (j < self0 || j >= self1) std::copy_n(&per_local[p * routing.send_index[j]], per, &send[p * j]);
  exchange_rows(routing.send_from, send, per, routing.recv_from, per_visitor, false);
}

void ParallelExchange::backward(const Routing &routing, const std::vector<double> &per_visitor, int per,
                                std::vector<double> &per_sent) const
{
  per_sent.resize(std::size_t(per) * routing.send_index.size());
  exchange_rows(routing.recv_from, per_visitor, per, routing.send_from, per_sent, true);
}

void ParallelExchange::sum_backward(const Routing &routing, const std::vector<double> &per_visitor, int per,
                                    std::vector<double> &per_local) const
{
  const std::size_t p = std::size_t(per);
  std::vector<double> rows;
  if (size_ > 1) {
    rows.resize(p * routing.send_index.size());
    exchange_rows(routing.recv_from, per_visitor, per, routing.send_from, rows, false);
  }
  per_local.assign(p * local_.size(), 0.0);
  const std::size_t self0 = routing.send_from[rank_], self1 = routing.send_from[rank_ + 1];
  for (std::size_t j = 0; j < routing.send_index.size(); ++j) {  // rank order
    const double *q = j >= self0 && j < self1 ? &per_visitor[p * (routing.recv_from[rank_] + j - self0)] : &rows[p * j];
    double *o = &per_local[p * routing.send_index[j]];
    for (std::size_t c = 0; c < p; ++c) o[c] += q[c];
  }
}

void ParallelExchange::locate(const std::vector<ParticleShape> &local)
{
  for (const ParticleShape &p : local)
    if (!(p.radius > 0.0) || !std::isfinite(p.radius) || !p.x.allFinite())
      throw std::invalid_argument("particle exchange: radius " + std::to_string(p.radius) +
                                  " or position not finite/positive");
  local_ = local;
  std::int64_t n_local = std::int64_t(local_.size());
  MPI_Allreduce(&n_local, &global_count_, 1, MPI_INT64_T, MPI_SUM, comm_);
  // every rank's cell box (6 doubles per rank: the routing table, not the particles), as the
  // mesh is now (it may have changed since the last locate)
  double mine[6] = {1.0, 1.0, 1.0, -1.0, -1.0, -1.0};
  Eigen::Vector3d box_lo, box_hi;
  if (mesh_.bounds(box_lo, box_hi))
    for (int a = 0; a < 3; ++a) mine[a] = box_lo[a], mine[3 + a] = box_hi[a];
  boxes_.assign(std::size_t(6 * size_), 0.0);
  MPI_Allgather(mine, 6, MPI_DOUBLE, boxes_.data(), 6, MPI_DOUBLE, comm_);
  route(local_, 0.0, routing_, visitors_);
  const std::size_t nv = visitors_.size(), nl = local_.size();
  traffic_.located += std::int64_t(nl);
  traffic_.visitors += std::int64_t(nv);
  visitor_of_local_.assign(nl, kNone);
  for (std::size_t j = routing_.send_from[rank_]; j < routing_.send_from[rank_ + 1]; ++j)
    visitor_of_local_[routing_.send_index[j]] = routing_.recv_from[rank_] + (j - routing_.send_from[rank_]);

  // the cell holding each centre: the lowest rank that finds it owns it; for the neighbours
  // model the owner's home-cell box goes with it
  const bool with_box = model_ == DistributionModel::Neighbours;
  const int kFound = with_box ? 7 : 1;
  std::vector<long> home(nv, -1);
  std::vector<double> found(std::size_t(kFound) * nv, 0.0);
  for (std::size_t v = 0; v < nv; ++v) {
    home[v] = mesh_.find_cell(visitors_[v].x);
    if (home[v] < 0) continue;
    double *q = &found[std::size_t(kFound) * v];
    q[0] = 1.0;
    if (with_box) {
      Eigen::Vector3d lo, hi;
      mesh_.cell_bounds(home[v], lo, hi);
      for (int a = 0; a < 3; ++a) q[1 + a] = lo[a], q[4 + a] = hi[a];
    }
  }
  std::vector<double> rows;
  backward(routing_, found, kFound, rows);
  std::vector<double> owner(std::size_t(kFound) * nl, 0.0);
  for (std::size_t i = 0; i < nl; ++i) owner[std::size_t(kFound) * i] = -1.0;
  for (int r = 0; r < size_; ++r)
    for (std::size_t j = routing_.send_from[r]; j < routing_.send_from[r + 1]; ++j) {
      double *o = &owner[std::size_t(kFound) * routing_.send_index[j]];
      const double *q = &rows[std::size_t(kFound) * j];
      if (q[0] == 0.0 || o[0] >= 0.0) continue;
      o[0] = double(r);
      std::copy_n(q + 1, kFound - 1, o + 1);
    }
  std::vector<double> owner_of_visitor;
  forward(routing_, owner, kFound, owner_of_visitor);

  // raw weights over this rank's cells
  start_.assign(nv + 1, 0);
  cells_.clear();
  weights_.clear();
  std::vector<CellWeight> raw;
  Eigen::Vector3d hlo = Eigen::Vector3d::Zero(), hhi = Eigen::Vector3d::Zero();
  for (std::size_t v = 0; v < nv; ++v) {
    start_[v] = cells_.size();
    const double *o = &owner_of_visitor[std::size_t(kFound) * v];
    if (o[0] < 0.0) continue;  // outside the mesh
    if (with_box) hlo = Eigen::Vector3d(o[1], o[2], o[3]), hhi = Eigen::Vector3d(o[4], o[5], o[6]);
    raw.clear();
    append_raw_weights(mesh_, model_, visitors_[v].x, visitors_[v].radius, int(o[0]) == rank_ ? home[v] : -1, hlo, hhi,
                       raw);
    for (const CellWeight &w : raw) cells_.push_back(w.cell), weights_.push_back(w.weight);
  }
  start_[nv] = cells_.size();
  traffic_.weights += std::int64_t(cells_.size());

  // normalisation: compensated sums on each rank, summed over the ranks in rank order
  std::vector<double> sums(2 * nv, 0.0);
  for (std::size_t v = 0; v < nv; ++v) {
    ExactSum s;
    for (std::size_t k = start_[v]; k < start_[v + 1]; ++k) s.add(weights_[k]);
    sums[2 * v] = s.hi(), sums[2 * v + 1] = s.lo();
  }
  std::vector<double> local_sums;
  sum_backward(routing_, sums, 2, local_sums);
  std::vector<double> total(nl, 0.0);
  inside_.assign(nl, 0);
  for (std::size_t i = 0; i < nl; ++i) {
    total[i] = local_sums[2 * i] + local_sums[2 * i + 1];
    inside_[i] = total[i] > 0.0;
  }
  std::vector<double> total_of_visitor;
  forward(routing_, total, 1, total_of_visitor);
  for (std::size_t v = 0; v < nv; ++v) {
    const double t = total_of_visitor[v];
    for (std::size_t k = start_[v]; k < start_[v + 1]; ++k) weights_[k] = t > 0.0 ? weights_[k] / t : 0.0;
  }

  // each particle's share of its cells, by its conductance there: its weight in the cell times
  // its size (G ~ k Nu d), so a shrinking remnant keeps enough of a cell to melt away (every
  // particle with weights in this rank's cells is a visitor here, so the per-cell sums are complete)
  share_.assign(cells_.size(), 0.0);
  const long ncells = cells_.empty() ? 0 : *std::max_element(cells_.begin(), cells_.end()) + 1;
  if (claimed_.size() < std::size_t(ncells)) claimed_.resize(std::size_t(ncells), 0.0);  // zero between calls
  for (std::size_t v = 0; v < nv; ++v)
    for (std::size_t k = start_[v]; k < start_[v + 1]; ++k) {
      share_[k] = weights_[k] * visitors_[v].radius;
      claimed_[std::size_t(cells_[k])] += share_[k];
    }
  for (std::size_t k = 0; k < cells_.size(); ++k)
    if (share_[k] > 0.0) share_[k] /= claimed_[std::size_t(cells_[k])];
  for (const long c : cells_) claimed_[std::size_t(c)] = 0.0;
}

void ParallelExchange::sample(const CellFluidFields &f, std::vector<SampledFluid> &out) const
{
  if (!f.T || !f.k || !f.rho || !f.mu || !f.cp || !f.U)
    throw std::invalid_argument("particle exchange: T, k, rho, mu, cp and U are required to sample the fluid");
  // sample_fluid's sums over this rank's cells, summed over the ranks, then finished
  const std::size_t nv = visitors_.size();
  std::vector<double> partial(kSampleSums * nv, 0.0);
  for (std::size_t v = 0; v < nv; ++v)
    for (std::size_t k = start_[v]; k < start_[v + 1]; ++k)
      add_cell_to_sample(f, cells_[k], weights_[k], share_[k], &partial[kSampleSums * v]);
  std::vector<double> sums;
  sum_backward(routing_, partial, kSampleSums, sums);
  out.resize(local_.size());
  for (std::size_t i = 0; i < local_.size(); ++i)
    out[i] = inside_[i] ? finish_sample(&sums[kSampleSums * i]) : SampledFluid();
}

template <class CellRow>
void ParallelExchange::deposit_rows(const std::vector<double> &per_local, int per, CellRow cell_row) const
{
  std::vector<double> rows;
  forward(routing_, per_local, per, rows);
  for (std::size_t v = 0; v < visitors_.size(); ++v) {
    const double *a = &rows[std::size_t(per) * v];
    for (std::size_t k = start_[v]; k < start_[v + 1]; ++k) {
      double *c = cell_row(cells_[k]);
      for (int q = 0; q < per; ++q) c[q] += weights_[k] * a[q];
    }
  }
}

void ParallelExchange::deposit(const std::vector<Amounts> &local_amounts, std::vector<Amounts> &cell_amounts) const
{
  if (local_amounts.size() != local_.size())
    throw std::invalid_argument("particle exchange: deposit() needs one amount per located local particle");
  std::vector<double> mine(kComponents * local_.size(), 0.0);
  for (std::size_t i = 0; i < local_.size(); ++i)
    if (inside_[i]) std::copy(local_amounts[i].begin(), local_amounts[i].end(), &mine[kComponents * i]);
  deposit_rows(mine, kComponents, [&](long c) { return cell_amounts.at(std::size_t(c)).data(); });
}

void ParallelExchange::deposit(const std::vector<double> &local_values, std::vector<double> &cell_values) const
{
  if (local_values.size() != local_.size())
    throw std::invalid_argument("particle exchange: deposit() needs one value per located local particle");
  std::vector<double> mine(local_.size(), 0.0);
  for (std::size_t i = 0; i < local_.size(); ++i)
    if (inside_[i]) mine[i] = local_values[i];
  deposit_rows(mine, 1, [&](long c) { return &cell_values.at(std::size_t(c)); });
}

void ParallelExchange::weighted_mean(const double *cell_values, std::vector<double> &local_out) const
{
  std::vector<double> partial(visitors_.size(), 0.0);
  for (std::size_t v = 0; v < visitors_.size(); ++v)
    for (std::size_t k = start_[v]; k < start_[v + 1]; ++k) partial[v] += weights_[k] * cell_values[cells_[k]];
  sum_backward(routing_, partial, 1, local_out);
}

void ParallelExchange::deposit_taken(const std::vector<std::int64_t> &ids, const std::vector<double> &heat,
                                     const std::vector<Eigen::Vector3d> &impulse, const std::vector<double> &particle_T,
                                     const CellFluidFields &f, std::vector<Amounts> &cell_amounts) const
{
  deposit_taken(ids, std::vector<int>(ids.size(), rank_), heat, impulse, particle_T, f, cell_amounts);
}

void ParallelExchange::deposit_taken(const std::vector<std::int64_t> &ids, const std::vector<int> &located_by,
                                     const std::vector<double> &heat, const std::vector<Eigen::Vector3d> &impulse,
                                     const std::vector<double> &particle_T, const CellFluidFields &f,
                                     std::vector<Amounts> &cell_amounts) const
{
  const std::size_t nreports = ids.size();
  if (heat.size() != nreports || impulse.size() != nreports || particle_T.size() != nreports ||
      located_by.size() != nreports)
    throw std::invalid_argument(
        "particle exchange: deposit_taken() needs one locating rank, heat, impulse and temperature per particle id");
  if (!f.rho || !f.cp || !f.T) throw std::invalid_argument("particle exchange: deposit_taken() needs T, rho and cp");
  // each report goes to the rank that located the particle (it may have moved to another DEM
  // rank since): (id, heat, impulse, T) by point-to-point messages
  constexpr int kIn = 6, kOut = 5;
  std::vector<std::size_t> send_rows(std::size_t(size_) + 1, 0), order;
  for (std::size_t i = 0; i < nreports; ++i)
    if (located_by[i] >= 0 && located_by[i] < size_) ++send_rows[std::size_t(located_by[i]) + 1];
  for (int r = 0; r < size_; ++r) send_rows[r + 1] += send_rows[r];
  std::vector<double> send(kIn * send_rows[size_]);
  {
    std::vector<std::size_t> next(send_rows.begin(), send_rows.end() - 1);
    for (std::size_t i = 0; i < nreports; ++i) {
      if (located_by[i] < 0 || located_by[i] >= size_) continue;
      double *q = &send[kIn * next[std::size_t(located_by[i])]++];
      q[0] = double(ids[i]), q[1] = heat[i], q[2] = impulse[i].x(), q[3] = impulse[i].y(), q[4] = impulse[i].z();
      q[5] = particle_T[i];
    }
  }
  std::vector<int> send_counts(static_cast<std::size_t>(size_)), recv_counts(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r) send_counts[r] = int(send_rows[r + 1] - send_rows[r]);
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm_);
  std::vector<std::size_t> recv_rows(std::size_t(size_) + 1, 0);
  for (int r = 0; r < size_; ++r) recv_rows[r + 1] = recv_rows[r] + std::size_t(recv_counts[r]);
  std::vector<double> reports(kIn * recv_rows[size_]);
  exchange_rows(send_rows, send, kIn, recv_rows, reports, true);

  // the reports by located particle: usually in the order they were located, else by id
  const std::size_t nl = local_.size(), nr = recv_rows[size_];
  std::vector<double> mine(kOut * nl, 0.0);
  bool same_order = nr == nl;
  for (std::size_t i = 0; i < nl && same_order; ++i) same_order = std::int64_t(reports[kIn * i]) == local_[i].id;
  if (same_order) {
    for (std::size_t i = 0; i < nl; ++i) std::copy_n(&reports[kIn * i + 1], kOut, &mine[kOut * i]);
  } else {
    std::unordered_map<std::int64_t, std::size_t> entry;
    entry.reserve(nl);
    for (std::size_t i = 0; i < nl; ++i) entry[local_[i].id] = i;
    for (std::size_t k = 0; k < nr; ++k) {
      const auto it = entry.find(std::int64_t(reports[kIn * k]));
      if (it != entry.end()) std::copy_n(&reports[kIn * k + 1], kOut, &mine[kOut * it->second]);
    }
  }
  std::vector<double> all;
  forward(routing_, mine, kOut, all);

  // each weight's part of its particle's parcel (mass, heat capacity) and the heat its cell can
  // give the particle before it reaches the particle's temperature: the part's capacity times
  // the cell's temperature difference to the particle, in the direction the particle took heat
  const std::size_t nv = visitors_.size(), nw = cells_.size();
  std::vector<double> part_mass(nw), part_capacity(nw), available(nw, 0.0);
  for (std::size_t k = 0; k < nw; ++k) {
    part_mass[k] = parcel_mass(f, k);
    part_capacity[k] = part_mass[k] * f.cp[cells_[k]];
  }
  if (f.volume)
    for (std::size_t v = 0; v < nv; ++v) {
      const double *a = &all[kOut * v];
      for (std::size_t k = start_[v]; k < start_[v + 1]; ++k) {
        const double T = f.T[cells_[k]];
        const double dT = a[0] >= 0.0 ? T - a[4] : a[4] - T;
        available[k] = part_capacity[k] * std::max(dT, 0.0);
      }
    }
  // per particle over every rank's cells: the parcel's capacity and mass, the available heat
  std::vector<double> partial(3 * nv, 0.0);
  for (std::size_t v = 0; v < nv; ++v)
    for (std::size_t k = start_[v]; k < start_[v + 1]; ++k) {
      partial[3 * v] += part_capacity[k];
      partial[3 * v + 1] += part_mass[k];
      partial[3 * v + 2] += available[k];
    }
  std::vector<double> sums, sums_of_visitor;
  sum_backward(routing_, partial, 3, sums);
  forward(routing_, sums, 3, sums_of_visitor);
  for (std::size_t v = 0; v < nv; ++v) {
    const double *a = &all[kOut * v];
    const double capacity = sums_of_visitor[3 * v], mass = sums_of_visitor[3 * v + 1],
                 room = sums_of_visitor[3 * v + 2];
    const double Q = std::abs(a[0]);
    for (std::size_t k = start_[v]; k < start_[v + 1]; ++k) {
      const double by_capacity = capacity > 0.0 ? part_capacity[k] / capacity : weights_[k];
      // each cell by the heat it has above (below) the particle's temperature, so each moves
      // the same fraction of the way towards it and none passes it; the two-body exchange
      // never takes more (round-off aside: what is beyond all cells' room goes by capacity)
      const double given =
          Q <= room ? (room > 0.0 ? Q * available[k] / room : 0.0) : available[k] + (Q - room) * by_capacity;
      const double mass_share = mass > 0.0 ? part_mass[k] / mass : weights_[k];
      Amounts &cell = cell_amounts.at(std::size_t(cells_[k]));
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

void ParallelExchange::local_weights(std::size_t i, std::vector<CellWeight> &out) const
{
  out.clear();
  const std::size_t v = visitor_of_local_.at(i);
  if (v == kNone) return;
  for (std::size_t k = start_[v]; k < start_[v + 1]; ++k) out.push_back({cells_[k], weights_[k]});
}

void ParallelExchange::nearest_solid(const double *solid_fraction, double reach, std::vector<SolidSurface> &out,
                                     const double *was_solid_fraction,
                                     const std::vector<Eigen::Vector3d> *velocity) const
{
  // the spheres grown by the reach go to the ranks whose cells they reach, with their velocity
  Routing routing;
  std::vector<ParticleShape> visitors;
  route(local_, reach, routing, visitors);
  std::vector<double> v_visitor(3 * visitors.size(), 0.0);
  if (velocity) {
    std::vector<double> v_local(3 * local_.size());
    for (std::size_t i = 0; i < local_.size(); ++i)
      for (int a = 0; a < 3; ++a) v_local[3 * i + a] = velocity->at(i)[a];
    forward(routing, v_local, 3, v_visitor);
  }
  constexpr int kPack = 10;  // present, distance, point, normal, fresh, approached
  std::vector<double> found(kPack * visitors.size(), 0.0);
  std::vector<long> cells;
  std::vector<Eigen::Vector3d> lo, hi;
  std::vector<char> was_solid;
  for (std::size_t v = 0; v < visitors.size(); ++v) {
    cells.clear();
    mesh_.cells_in_sphere(visitors[v].x, visitors[v].radius + reach, cells);
    lo.clear();
    hi.clear();
    was_solid.clear();
    for (long c : cells) {
      if (!(solid_fraction[c] >= 0.5)) continue;
      Eigen::Vector3d l, h;
      mesh_.cell_bounds(c, l, h);
      lo.push_back(l);
      hi.push_back(h);
      if (was_solid_fraction) was_solid.push_back(was_solid_fraction[c] >= 0.5);
    }
    const Eigen::Vector3d vel(v_visitor[3 * v], v_visitor[3 * v + 1], v_visitor[3 * v + 2]);
    const SolidSurface s = nearest_solid_surface(visitors[v].x, lo, hi, was_solid, vel);
    if (!s.present) continue;
    double *q = &found[kPack * v];
    q[0] = 1.0, q[1] = s.distance;
    for (int a = 0; a < 3; ++a) q[2 + a] = s.point[a], q[5 + a] = s.normal[a];
    q[8] = s.fresh ? 1.0 : 0.0;
    q[9] = s.approached ? 1.0 : 0.0;
  }
  std::vector<double> rows;
  backward(routing, found, kPack, rows);
  // the rank with the nearest (approached) surface provides it (rows come in rank order:
  // lowest on ties)
  out.assign(local_.size(), SolidSurface());
  for (std::size_t j = 0; j < routing.send_index.size(); ++j) {
    const double *q = &rows[kPack * j];
    SolidSurface found_there;
    found_there.present = q[0] != 0.0;
    found_there.distance = q[1];
    found_there.point = Eigen::Vector3d(q[2], q[3], q[4]);
    found_there.normal = Eigen::Vector3d(q[5], q[6], q[7]);
    found_there.fresh = q[8] != 0.0;
    found_there.approached = q[9] != 0.0;
    SolidSurface &s = out[routing.send_index[j]];
    if (preferred_surface(found_there, s)) s = found_there;
  }
}

}  // namespace meltdem::coupling
