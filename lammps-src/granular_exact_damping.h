#ifndef MELTDEM_GRANULAR_EXACT_DAMPING_H
#define MELTDEM_GRANULAR_EXACT_DAMPING_H
// On LAMMPS's GRANULAR API of 2023 and later (GranularModel and its sub-models): 'damping tsuji'
// with a given alpha (Codina2019 eq. 3.5) instead of the stock polynomial in e, for
// pair_style granular/powder and the powder walls. Not used with the 29 Sep 2021 headers, where
// the styles set alpha in the stock coefficient arrays.
#include "lammps_api.h"

#if MELTDEM_LAMMPS_2025_API
namespace LAMMPS_NS {
class LAMMPS;
namespace Granular_NS {
class GranularModel;
}
namespace meltdem_granular {
// replace the model's damping sub-model by Tsuji's form with this alpha (initialised)
void use_tsuji_alpha(Granular_NS::GranularModel *model, LAMMPS *lmp, double alpha);
// the Hertz stiffness factor k of F = k sqrt(R delta) delta of the model's normal sub-model:
// 4/3 E/(2 (1 - nu^2)) for material models (pairs of one material), else its first coefficient
double hertz_stiffness(const Granular_NS::GranularModel *model);
}  // namespace meltdem_granular
}  // namespace LAMMPS_NS
#endif

#endif
