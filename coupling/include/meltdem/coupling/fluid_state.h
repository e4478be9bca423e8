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
