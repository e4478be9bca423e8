// 'damping tsuji' with a given alpha on the GranularModel API (granular_exact_damping.h).
#include "granular_exact_damping.h"

#if MELTDEM_LAMMPS_2025_API
#include "gran_sub_mod_damping.h"
#include "gran_sub_mod_normal.h"
#include "granular_model.h"

using namespace LAMMPS_NS;
using namespace Granular_NS;

namespace {
// the stock Tsuji sub-model (damp sqrt(m F_n / delta) v_n) with damp = alpha
class TsujiAlphaDamping : public GranSubModDampingTsuji {
 public:
  TsujiAlphaDamping(GranularModel *gm, LAMMPS *lmp, double alpha) : GranSubModDampingTsuji(gm, lmp), alpha(alpha)
  {
    allow_cohesion = 1;  // (pair_granular_powder.cpp: the 29 Sep 2021 release allowed it)
  }
  void init() override { damp = alpha; }

 private:
  const double alpha;
};
}  // namespace

void meltdem_granular::use_tsuji_alpha(GranularModel *model, LAMMPS *lmp, double alpha)
{
  auto *damping = new TsujiAlphaDamping(model, lmp, alpha);
  damping->name = "tsuji";
  damping->allocate_coeffs();
  delete model->sub_models[DAMPING];
  model->sub_models[DAMPING] = damping;
  model->damping_model = damping;
  damping->init();
}

double meltdem_granular::hertz_stiffness(const GranularModel *model)
{
  const GranSubModNormal *normal = model->normal_model;
  if (!normal->get_material_properties()) return normal->coeffs[0];
  const double E = normal->get_emod(), nu = normal->get_poiss();
  return 4.0 / 3.0 * E / (2.0 * (1.0 - nu * nu));
}
#endif
