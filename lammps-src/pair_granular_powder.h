#ifdef PAIR_CLASS
// clang-format off
// no trailing semicolon: meltdem_styles.cpp expands this inside an array initializer
PairStyle(granular/powder,PairGranularPowder)
// clang-format on
#else
#ifndef MELTDEM_PAIR_GRANULAR_POWDER_H
#define MELTDEM_PAIR_GRANULAR_POWDER_H
#include "pair_granular.h"

#include "meltdem/coupling/stepped_restitution.h"

#include <vector>

namespace LAMMPS_NS {
class PairGranularPowder : public PairGranular {
 public:
  PairGranularPowder(class LAMMPS *lmp) : PairGranular(lmp) {}
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;

 private:
  // 'damping tsuji' type pairs: the prescribed e (0: stock damping) and alpha(h) for it
  std::vector<double> exact_e;
  std::vector<double> tsuji_alpha;  // the alpha set per type pair (0: stock damping), the 2023+ API
  std::vector<double> hertz_kn;     // per type pair, read from its normal sub-model in init_one (2023+ API)
  std::vector<meltdem::coupling::SteppedAlphaTable> alpha_tables;
  bool any_stepped = false;             // some type pair has 'damping tsuji' with the stepped damping
  double impact_speed = 0.0;            // pair_style keyword impact_speed (m/s), 0: none
  class FixPowderDt *fix_dt = nullptr;  // the step's approach speed, when there is one

  int slot(int i, int j) const;  // index of type pair i j in exact_e and alpha_tables
  // e > 0: stepped damping for e; alpha_continuous: its continuous alpha when known (< 0: not)
  void set_exact(int i, int j, double e, double alpha_continuous);
  double current_impact_speed() const;
  void add_stepped_damping(int eflag, int vflag);
};
}  // namespace LAMMPS_NS
#endif
#endif
