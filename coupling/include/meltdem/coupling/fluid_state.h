#pragma once
// The fluid a particle sees: what fix powder/melt needs from the continuum (or from a
// uniform 'ambient'). The physics asks a provider once per particle and step, so the
// coupling can hand in interpolated local fields without touching the physics.

#include "meltdem/coupling/solid_metal_contact.h"

namespace meltdem::coupling {

struct FluidState {
  double T = 0.0;                 // temperature [K]
  double k = 0.0;                 // thermal conductivity [W/(m K)]
  double rho = 0.0;               // density [kg/m^3]
  double mu = 0.0;                // dynamic viscosity [Pa s]
  double cp = 0.0;                // specific heat capacity [J/(kg K)]
  double U[3] = {0.0, 0.0, 0.0};  // velocity [m/s]
  SolidSurface solid;             // nearest solid metal of the continuum (if any)
  double heat_source = 0.0;       // power from outside the fluid (laser) absorbed [W]
  bool thermal = true;            // false: the continuum solves no energy equation, so the
                                  // particle is isothermal (drag only: no heat, no melting)
  double mass = 0.0;              // fluid mass the particle exchanges momentum with [kg]:
                                  // its share of its cells' mass (0: unbounded, 'ambient')
  double capacity = 0.0;          // heat capacity [J/K] of the fluid it exchanges heat with:
                                  // its share of its cells' rho cp V (0: unbounded, 'ambient')
  bool implicit_heat = false;     // true: the continuum's energy solve exchanges the heat
                                  // (implicit in the cells' T); the particle takes what it owes
};

// A FluidState as doubles (LAMMPS per-atom arrays carry it when a particle changes rank).
constexpr int kFluidStateDoubles = 22;
constexpr int kFluidStateHeatSource = 16;  // where heat_source is
inline void pack_fluid_state(const FluidState &s, double *q)
{
  q[0] = s.T, q[1] = s.k, q[2] = s.rho, q[3] = s.mu, q[4] = s.cp;
  for (int a = 0; a < 3; ++a) q[5 + a] = s.U[a];
  q[8] = s.solid.present ? 1.0 : 0.0, q[9] = s.solid.distance;
  for (int a = 0; a < 3; ++a) q[10 + a] = s.solid.point[a], q[13 + a] = s.solid.normal[a];
  q[kFluidStateHeatSource] = s.heat_source, q[17] = s.thermal ? 1.0 : 0.0, q[18] = s.mass, q[19] = s.capacity;
  q[20] = s.implicit_heat ? 1.0 : 0.0;
  q[21] = s.solid.fresh ? 1.0 : 0.0;
}
inline void unpack_fluid_state(const double *q, FluidState &s)
{
  s.T = q[0], s.k = q[1], s.rho = q[2], s.mu = q[3], s.cp = q[4];
  for (int a = 0; a < 3; ++a) s.U[a] = q[5 + a];
  s.solid.present = q[8] != 0.0, s.solid.distance = q[9];
  for (int a = 0; a < 3; ++a) s.solid.point[a] = q[10 + a], s.solid.normal[a] = q[13 + a];
  s.heat_source = q[kFluidStateHeatSource], s.thermal = q[17] != 0.0, s.mass = q[18], s.capacity = q[19];
  s.implicit_heat = q[20] != 0.0;
  s.solid.fresh = q[21] != 0.0;
}

class FluidStateProvider {
 public:
  virtual ~FluidStateProvider() = default;
  // Fluid at particle 'index' (the caller's local index) located at x. Returns false where
  // the particle sees no fluid (then it exchanges nothing this step).
  virtual bool fluid_state(int index, const double x[3], FluidState &out) const = 0;
};

// The same fluid everywhere (fix powder/melt 'ambient').
class UniformFluid : public FluidStateProvider {
 public:
  explicit UniformFluid(const FluidState &s) : state_(s) {}
  bool fluid_state(int, const double *, FluidState &out) const override
  {
    out = state_;
    return true;
  }
  const FluidState &state() const { return state_; }

 private:
  FluidState state_;
};

}  // namespace meltdem::coupling
