#pragma once
// Particle <-> cell exchange when the particles and the mesh are decomposed differently
// (LAMMPS's decomposition need not match the mesh's). Every rank holds some
// particles (its DEM sub-domain) and some cells (its mesh sub-domain). locate() gathers
// the particles' shapes on every rank; each rank computes the raw weights of every
// particle over ITS cells, and the weights are normalised with the global sum, so a
// particle spanning a processor boundary is split exactly as in a serial run:
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
// Serial runs use the same code, so np N equals np 1 to round-off.
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

class ParallelExchange {
 public:
  // local_mesh: this rank's cells (cell ids are local indices); comm: all ranks holding
  // particles or cells (a rank may hold none of either)
  ParallelExchange(const DistributionMesh &local_mesh, DistributionModel model, MPI_Comm comm);

  DistributionModel model() const { return model_; }

  // Collective. The particles this rank holds; their weights over every rank's cells
  // are computed and kept until the next locate(). Throws std::invalid_argument for a
  // radius <= 0 or a non-finite position (on the rank holding it).
  void locate(const std::vector<ParticleShape> &local_particles);

  std::int64_t global_particles() const { return std::int64_t(all_.size()); }
  // global index of this rank's first located particle (local i is global local_offset() + i)
  std::size_t local_offset() const { return offset_; }
  // whether local particle i lies in the mesh (its centre is in a cell; for overlap also
  // some of its volume); one outside exchanges nothing and is booked as outflow
  bool inside(std::size_t local_index) const { return inside_[offset_ + local_index] != 0; }

  // Collective. Fluid seen by each local particle (weighted cell means); entries of
  // particles outside the mesh are left default.
  void sample(const CellFluidFields &fields, std::vector<SampledFluid> &local_out) const;

  // Collective. The same for every particle of every rank, in global order (global_id(g)
  // names them): a particle that moves to another DEM rank during the interval still
  // finds its fluid there.
  void sample_global(const CellFluidFields &fields, std::vector<SampledFluid> &global_out) const;
  // Collective. For every particle of every rank, the nearest surface of the cells whose
  // solid_fraction (metal that is solid, per cell) is >= 1/2, searched within the
  // particle's radius + reach of its centre (solid_metal_contact.h).
  void nearest_solid(const double *solid_fraction, double reach, std::vector<SolidSurface> &global_out) const;

  std::int64_t global_id(std::int64_t g) const { return all_[std::size_t(g)].id; }
  // every rank's particles as last located, in global order
  const std::vector<ParticleShape> &global_shapes() const { return all_; }
  bool global_inside(std::int64_t g) const { return inside_[std::size_t(g)] != 0; }

  // Collective. Adds w_ic * amounts[i] of every particle i (all ranks) to cell c of this
  // rank: cell_amounts has one entry per local cell. Amounts of particles outside the
  // mesh are not deposited (the caller books them as outflow).
  void deposit(const std::vector<Amounts> &local_amounts, std::vector<Amounts> &cell_amounts) const;

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
  // are named by id (any rank may report any located particle: call it with the location
  // the fluid was sampled at, and the particles' records after they moved); located
  // particles no rank reports took nothing. Without cell volumes (fields.volume null) the
  // heat goes by the capacity weights alone.
  void deposit_taken(const std::vector<std::int64_t> &ids, const std::vector<double> &heat,
                     const std::vector<Eigen::Vector3d> &impulse, const std::vector<double> &particle_T,
                     const CellFluidFields &fields, std::vector<Amounts> &cell_amounts) const;

  // weights of global particle g over this rank's cells (for tests and diagnostics)
  void local_weights(std::int64_t g, std::vector<CellWeight> &out) const;

  // number of (particle, local cell) weights held: the memory/cost of the exchange
  std::size_t weight_count() const { return cells_.size(); }

 private:
  const DistributionMesh &mesh_;
  DistributionModel model_;
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  std::vector<ParticleShape> all_;  // every rank's particles, in rank order
  std::vector<int> counts_, displs_;
  std::size_t offset_ = 0;    // first global index of this rank's particles
  std::vector<char> inside_;  // per global particle
  // CSR of this rank's weights: particle g owns [start_[g], start_[g+1])
  std::vector<std::size_t> start_;
  std::vector<long> cells_;
  std::vector<double> weights_;
  std::vector<double> share_;    // per weight: the particle's share of the cell (its parcel)
  std::vector<double> claimed_;  // per cell: the sum of its particles' claims (locate's scratch)
  // weight k's cell's part of its particle's parcel: mass, heat capacity (per unit volume
  // and by the weights without cell volumes)
  double parcel_mass(const CellFluidFields &f, std::size_t k) const;
  double parcel_capacity(const CellFluidFields &f, std::size_t k) const;
};

}  // namespace meltdem::coupling
