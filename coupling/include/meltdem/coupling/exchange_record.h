#pragma once
// What one particle hands to (and takes from) the continuum in one coupling step. The DEM
// side fills one record per local particle; the distribution to cells and the conservation
// ledger read only these records, so neither needs LAMMPS.

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace meltdem::coupling {

// The conserved amounts the ledger books: metal mass [kg], enthalpy [J], momentum [kg m/s].
enum Component : int { kMass = 0, kEnthalpy = 1, kMomX = 2, kMomY = 3, kMomZ = 4 };
constexpr int kComponents = 5;
using Amounts = std::array<double, kComponents>;

inline Amounts make_amounts(double mass, double enthalpy, const Eigen::Vector3d &momentum)
{
  return {mass, enthalpy, momentum.x(), momentum.y(), momentum.z()};
}

struct ExchangeRecord {
  std::int64_t id = 0;                          // particle tag (global, stable)
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  // position at the end of the step [m]
  double radius = 0.0;                          // [m] (the last solid radius once fully molten)
  Eigen::Vector3d v = Eigen::Vector3d::Zero();  // velocity at the end of the step [m/s]
  double T = 0.0;                               // temperature [K]
  double h = 0.0;                               // specific enthalpy [J/kg] (same reference as the continuum)
  double mass = 0.0;                            // solid mass left at the end of the step [kg]

  // handed to the continuum over this step (melting, eq. 2.2, 2.9, 2.11)
  double mass_out = 0.0;                                   // [kg]
  double enthalpy_out = 0.0;                               // [J]
  Eigen::Vector3d momentum_out = Eigen::Vector3d::Zero();  // [kg m/s]

  // taken from the continuum over this step: the continuum loses both
  double heat_absorbed = 0.0;                                    // convective heat [J] (< 0 when cooling)
  Eigen::Vector3d impulse_from_fluid = Eigen::Vector3d::Zero();  // drag + buoyancy impulse [kg m/s]

  // from outside the system over this step (laser light on the particle) [J]
  double external_heat = 0.0;

  // implicit heat exchange: the particle's convective conductance k Nu pi d [W/K] and heat
  // capacity m cp [J/K] at the end of the step, and the heat [J] the continuum gave it in this
  // step's energy solve, which it takes at the start of the next interval (held until then)
  double conductance = 0.0;
  double heat_capacity = 0.0;
  double heat_owed = 0.0;

  // the rank (of the coupling's communicator) that located the particle at the start of the
  // interval and handed it its fluid (-1: it had none), and the light it absorbs [W] with
  // that fluid: the particle may have moved to another DEM rank since
  int located_by = -1;
  double light = 0.0;
};

// mass, enthalpy m h (and the heat owed to it) and momentum m v the particle carries at the
// end of the step
inline Amounts stored_in(const ExchangeRecord &r)
{
  return make_amounts(r.mass, r.mass * r.h + r.heat_owed, r.mass * r.v);
}

// the net gain of the continuum from this particle over the step: what melted, minus the heat
// and the momentum the particle took from the fluid
inline Amounts net_to_continuum(const ExchangeRecord &r)
{
  return make_amounts(r.mass_out, r.enthalpy_out - r.heat_absorbed, r.momentum_out - r.impulse_from_fluid);
}

}  // namespace meltdem::coupling
