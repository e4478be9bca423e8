#ifdef PAIR_CLASS
// clang-format off
// no trailing semicolon: meltdem_styles.cpp expands this inside an array initializer
PairStyle(granular/powder,PairGranularPowder)
// clang-format on
#else
#ifndef MELTDEM_PAIR_GRANULAR_POWDER_H
#define MELTDEM_PAIR_GRANULAR_POWDER_H
#include "pair_granular.h"
namespace LAMMPS_NS {
class PairGranularPowder : public PairGranular {
 public:
  PairGranularPowder(class LAMMPS *lmp) : PairGranular(lmp) {}
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
};
}  // namespace LAMMPS_NS
#endif
#endif
