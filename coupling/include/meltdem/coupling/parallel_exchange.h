#pragma once
// Particle <-> cell exchange when the particles and the mesh are decomposed differently
// (LAMMPS's decomposition need not match the mesh's). Every rank holds some particles (its
// DEM sub-domain) and some cells (its mesh sub-domain). locate() sends each particle to the
// ranks whose cells its sphere can reach (their bounding boxes; point-to-point messages, no
// collective that grows with the particle count): there it is a visitor, and that rank
// computes its raw weights over ITS cells. The partial sums come back to the rank that
// located the particle and are summed in rank order, so a particle spanning a processor
// boundary is split exactly as in a serial run:
//   centre     : the cell holding the centre (the lowest rank that finds it owns it);
//   neighbours : that cell plus the cells across its faces the particle reaches
//                (Codina2019 fig. 3.9 / eq. 3.7, volume-weighted). Faces are recognised from
//                cell bounding boxes (a cell whose box shares a face with the centre
//                cell's box), so a neighbour on another rank needs no face addressing:
//                exact for axis-aligned hexahedral meshes (blockMesh, snappy background),
//                the meshes these scenes use;
//   overlap    : sphere-cell overlap volumes (cell bounding boxes), part outside the
//                mesh dropped, the rest renormalised.
// sample() averages the continuum's cell fields with these weights (what the particle
// sees; its temperature weighted by heat capacity and its velocity by mass too); deposit()
// spreads the melt the particles hand over onto the cells with the same weights, and
// deposit_taken() takes the heat and impulse they took from the cells (heat by what each
// cell holds beyond the particle's temperature, impulse by the parcel's mass shares), so the
// exchange is symmetric and sums to what was handed over to round-off.
// Serial runs use the same code, so np N equals np 1 to round-off. traffic() counts what a
// rank located, weighed and sent (the scaling study's counters).
#include "meltdem/coupling/exchange_record.h"
#include "meltdem/coupling/fluid_sampling.h"
#include "meltdem/coupling/particle_distribution.h"
#include "meltdem/coupling/solid_metal_contact.h"

#include <mpi.h>

#include <cstdint>
#include <vector>

namespace meltdem::coupling {

struct ParticleShape {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  double radius = 0.0;
  std::int64_t id = 0;  // particle tag (carried along for global lookups; < 2^53)
};

// What one rank's exchange did since the counters were last reset: the scaling study's
// per-rank work and traffic (messages and bytes of the point-to-point rounds; the
// collectives of fixed size, a count per rank, are not counted).
struct ExchangeTraffic {
  std::int64_t located = 0;   // particles this rank located (its LAMMPS particles), summed over locate()
  std::int64_t visitors = 0;  // particles whose weights this rank computed (summed over locate())
  std::int64_t weights = 0;   // (particle, cell) weights computed
  std::int64_t messages_sent = 0, messages_received = 0;
  std::int64_t bytes_sent = 0, bytes_received = 0;
};

class ParallelExchange {
 public:
  // local_mesh: this rank's cells (cell ids are local indices); comm: all ranks holding
  // particles or cells (a rank may hold none of either)
  ParallelExchange(const DistributionMesh &local_mesh, DistributionModel model, MPI_Comm comm);

  DistributionModel model() const { return model_; }

  // Collective over comm (a count per rank, then point-to-point messages to the ranks each
  // particle reaches). The particles this rank holds; their weights over every rank's cells
  // are computed and kept until the next locate(). Throws std::invalid_argument for a
  // radius <= 0 or a non-finite position (on the rank holding it).
  void locate(const std::vector<ParticleShape> &local_particles);

  // particles located on all ranks together
  std::int64_t global_particles() const { return global_count_; }
  // this rank's located particles, in the order given to locate()
  std::size_t local_particles() const { return local_.size(); }
  // whether local particle i lies in the mesh (its centre is in a cell; for overlap also
  // some of its volume); one outside exchanges nothing and is booked as outflow
  bool inside(std::size_t local_index) const { return inside_[local_index] != 0; }
  // this rank in comm (what a particle's record names as the rank that located it)
  int rank() const { return rank_; }

  // Collective. Fluid seen by each local particle (weighted cell means); entries of
  // particles outside the mesh are left default.
  void sample(const CellFluidFields &fields, std::vector<SampledFluid> &local_out) const;

  // Collective. For each local particle, the nearest surface of the cells whose
  // solid_fraction (metal that is solid, per cell) is >= 1/2, searched within the
  // particle's radius + reach of its centre (solid_metal_contact.h); the rank with the
  // nearest surface provides it, the lowest on ties.
  // was_solid_fraction: the same one coupling interval ago, on the same cells (nullptr:
  // unknown, every surface is fresh); velocity: of each local particle (nullptr: at rest),
  // so that it is handed the nearest surface it approaches (nearest_solid_surface)
  void nearest_solid(const double *solid_fraction, double reach, std::vector<SolidSurface> &local_out,
                     const double *was_solid_fraction = nullptr,
                     const std::vector<Eigen::Vector3d> *velocity = nullptr) const;

  // Collective. Adds w_ic * amounts[i] of every particle i (all ranks) to cell c of this
  // rank: cell_amounts has one entry per local cell. Amounts of particles outside the
  // mesh are not deposited (the caller books them as outflow).
  void deposit(const std::vector<Amounts> &local_amounts, std::vector<Amounts> &cell_amounts) const;
  // the same for one value per particle (cell_values: one per local cell)
  void deposit(const std::vector<double> &local_values, std::vector<double> &cell_values) const;

  // Collective. Sum over each of this rank's located particles of w_i values[c_i] over its
  // cells on every rank (values per local cell), in local order: the mean of a cell field the
  // particle sees, by the weights deposit() spreads with (0 outside the mesh).
  void weighted_mean(const double *cell_values, std::vector<double> &local_out) const;
  // Collective. Takes what each particle took from the fluid out of the cells: its
  // heat (J; negative: gave) from the enthalpy, each cell c in proportion to the heat it
  // holds beyond the particle's temperature T_p (end of step) on the side the heat flowed,
  // A_c = s_ic rho_c cp_c V_c max(T_c - T_p, 0) for heat taken (T_p - T_c for heat given),
  // s_ic = w_ic d_i / sum_j w_jc d_j the particle's share of cell c by conductance (1 for a
  // particle alone in the cell), so every cell moves the same fraction of the way towards T_p and
  // none passes it: a gas cell colder than a grain that takes heat from the melt beside it
  // gives nothing, and the melt gives it all. The particle's parcel (sample()) is the sum of
  // its shares s_ic, and a two-body exchange with it (heat_melt_step_two_body) never takes
  // more than sum_c A_c; heat beyond it (round-off, or an explicit caller) is taken by the
  // parcel's capacities s_ic rho_c cp_c V_c / sum. The drag and buoyancy impulse (kg m/s)
  // comes from the momentum with the parcel's mass shares s_ic rho_c V_c / sum, so each
  // cell's velocity moves by s_ic times the parcel's and a light gas cell beside melt gives
  // little.
  // Sums to what was taken exactly; particles outside the mesh give nothing. The particles
  // are named by id and by the rank that located them (located_by[i]; a particle may have
  // moved to another DEM rank since: its report goes back to that rank by a point-to-point
  // message; a negative rank: not located, ignored); located particles no rank reports took
  // nothing. Without cell volumes (fields.volume null) the heat goes by the capacity weights
  // alone. The overload without located_by reports particles this rank located.
  void deposit_taken(const std::vector<std::int64_t> &ids, const std::vector<int> &located_by,
                     const std::vector<double> &heat, const std::vector<Eigen::Vector3d> &impulse,
                     const std::vector<double> &particle_T, const CellFluidFields &fields,
                     std::vector<Amounts> &cell_amounts) const;
  void deposit_taken(const std::vector<std::int64_t> &ids, const std::vector<double> &heat,
                     const std::vector<Eigen::Vector3d> &impulse, const std::vector<double> &particle_T,
                     const CellFluidFields &fields, std::vector<Amounts> &cell_amounts) const;

  // weights of local particle i over this rank's cells (for tests and diagnostics; empty
  // where its sphere does not reach this rank's cells)
  void local_weights(std::size_t local_index, std::vector<CellWeight> &out) const;

  // number of (particle, local cell) weights held: the memory/cost of the exchange
  std::size_t weight_count() const { return cells_.size(); }
  // particles (any rank's) whose weights this rank holds
  std::size_t visitor_count() const { return visitors_.size(); }

  const ExchangeTraffic &traffic() const { return traffic_; }
  void reset_traffic() const { traffic_ = ExchangeTraffic(); }

 private:
  // Which of this rank's particles go to which rank, and which visitors came from which:
  // send_index[send_from[r] .. send_from[r+1]) are the local indices sent to rank r (in local
  // order), and the visitors from rank r are [recv_from[r], recv_from[r+1]) (in r's order).
  struct Routing {
    std::vector<std::size_t> send_index, send_from, recv_from;
  };
  // the routing of spheres (centre, radius + grow) to the ranks whose cell box they reach,
  // and the shapes that came (the visitors, by rank of origin)
  void route(const std::vector<ParticleShape> &local, double grow, Routing &routing,
             std::vector<ParticleShape> &visitors) const;
  // `per` doubles per local particle to each rank it visits: out holds `per` per visitor
  void forward(const Routing &routing, const std::vector<double> &per_local, int per,
               std::vector<double> &per_visitor) const;
  // `per` doubles per visitor back to the rank that located it: out holds `per` per entry of
  // send_index (rank r's contribution to local particle send_index[j] at row j)
  void backward(const Routing &routing, const std::vector<double> &per_visitor, int per,
                std::vector<double> &per_sent) const;
  // adds w_vc * rows of `per` doubles per local particle to cell c's row (cell_row(c))
  template <class CellRow> void deposit_rows(const std::vector<double> &per_local, int per, CellRow cell_row) const;
  // the sum over the ranks (in rank order) of backward()'s rows for each local particle
  void sum_backward(const Routing &routing, const std::vector<double> &per_visitor, int per,
                    std::vector<double> &per_local) const;
  // rows of `per` doubles between this rank and the others: rows [send_rows[r], send_rows[r+1])
  // of send go to rank r, what comes from r goes to rows from recv_rows[r] of recv (this
  // rank's own rows are copied only with copy_own)
  void exchange_rows(const std::vector<std::size_t> &send_rows, const std::vector<double> &send, int per,
                     const std::vector<std::size_t> &recv_rows, std::vector<double> &recv, bool copy_own) const;

  const DistributionMesh &mesh_;
  DistributionModel model_;
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  std::vector<ParticleShape> local_;  // this rank's particles, as located
  std::vector<char> inside_;          // per local particle
  std::int64_t global_count_ = 0;
  std::vector<double> boxes_;  // every rank's cell bounding box (6 per rank; empty: lo > hi)
  Routing routing_;
  std::vector<ParticleShape> visitors_;        // the particles whose weights this rank holds
  std::vector<std::size_t> visitor_of_local_;  // this rank's own particles: their visitor index (or npos)
  // CSR of this rank's weights: visitor v owns [start_[v], start_[v+1])
  std::vector<std::size_t> start_;
  std::vector<long> cells_;
  std::vector<double> weights_;
  std::vector<double> share_;    // per weight: the particle's share of the cell (its parcel)
  std::vector<double> claimed_;  // per cell: the sum of its particles' claims (locate's scratch)
  mutable ExchangeTraffic traffic_;
  // weight k's cell's part of its particle's parcel: mass, heat capacity (per unit volume
  // and by the weights without cell volumes)
  double parcel_mass(const CellFluidFields &f, std::size_t k) const;
  double parcel_capacity(const CellFluidFields &f, std::size_t k) const;
};

}  // namespace meltdem::coupling
