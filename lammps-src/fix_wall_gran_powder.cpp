/* ----------------------------------------------------------------------
   MeltDEM: fix wall/gran/powder (see fix_wall_gran_powder.h, doc/fix_wall_gran_powder.rst)
------------------------------------------------------------------------- */

#include "fix_wall_gran_powder.h"

#include "atom.h"
#include "error.h"
#include "fix_powder_dt.h"
#include "granular_exact_damping.h"
#if MELTDEM_LAMMPS_2025_API
#include "gran_sub_mod_normal.h"
#include "gran_sub_mod_tangential.h"
#include "granular_model.h"
#endif
#include "lammps.h"
#include "modify.h"
#include "update.h"

#include "meltdem/coupling/hertz_restitution.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {
enum { XPLANE = 0, YPLANE = 1, ZPLANE = 2, ZCYLINDER, REGION };  // fix_wall_gran.cpp's wall styles

bool is_wallstyle(const std::string &w)
{
  return w == "xplane" || w == "yplane" || w == "zplane" || w == "zcylinder" || w == "region";
}
}  // namespace

/* ---------------------------------------------------------------------- */

#if MELTDEM_LAMMPS_2025_API
void WallGranPowderCoeffs::apply_material(Granular_NS::GranularModel *model) const
{
  // the stock wall model takes 4/3 E/(2(1-nu^2)) of the particle alone: give it the E with
  // which its formula yields 4/3 E* of particle and wall (nu kept)
  if (material) {
    const double nu = model->normal_model->coeffs[2];
    model->normal_model->coeffs[0] = 0.75 * kn * 2.0 * (1.0 - nu * nu);
    model->normal_model->coeffs_to_local();
  }
  // a NULL Mindlin stiffness: 8 G* of particle and wall, as the pair style's 8 G*
  if (kt_from_material) {
    model->tangential_model->coeffs[0] = kt;
    model->tangential_model->coeffs_to_local();
  }
}

void WallGranPowderCoeffs::apply_damping(Granular_NS::GranularModel *model, LAMMPS *lmp) const
{
  if (damping != DAMP_STOCK) meltdem_granular::use_tsuji_alpha(model, lmp, alpha);
}

double WallGranPowderCoeffs::stiffness(const Granular_NS::GranularModel *model) const
{
  return material ? kn : model->normal_model->coeffs[0];
}
#else
void WallGranPowderCoeffs::apply_material(double *normal_coeffs, double *tangential_coeffs) const
{
  // stock wall/gran sets 4/3 E/(2(1-nu)) here: neither E* of particle and wall nor
  // the pair style's 4/3 E* (DESIGN.md pitfall 2)
  if (material) normal_coeffs[0] = kn;
  // stock sets E/4 (2-nu)(1+nu) for a NULL Mindlin stiffness; the pair style uses 8 G*
  if (kt_from_material) tangential_coeffs[0] = kt;
}

void WallGranPowderCoeffs::apply_damping(double *normal_coeffs) const
{
  // stock init() maps normal_coeffs[1] by Tsuji's polynomial again on every run:
  // overwrite it with the exact alpha after each init()
  if (damping != DAMP_STOCK) normal_coeffs[1] = alpha;
}
#endif

void WallGranPowderCoeffs::find_step_fix(LAMMPS *lmp)
{
  fix_dt = nullptr;
  for (int i = 0; i < lmp->modify->nfix; i++)
    if (auto *f = dynamic_cast<FixPowderDt *>(lmp->modify->fix[i])) fix_dt = f;
}

double WallGranPowderCoeffs::contact_speed() const
{
  if (fix_dt && fix_dt->approach_speed() > 0.0) return 0.5 * fix_dt->approach_speed();
  return impact_speed;
}

double WallGranPowderCoeffs::damping_correction(double kn_factor, double alpha_continuous, double delta,
                                                double separation_rate, double reff, double meff, double dt,
                                                double speed_factor) const
{
  if (damping != DAMP_TSUJI_EXACT || e <= 0.0) return 0.0;
  // apart now and a step ago: no contact this step, no correction (most grains near a wall)
  if (delta <= 0.0 && delta + dt * separation_rate <= 0.0) return 0.0;
  const double hertz_k = kn_factor * std::sqrt(reff);
  const double h = speed_factor > 0.0 ? contact_step(speed_factor, hertz_k, meff) : 0.0;
  return stepped.correction(h, alpha_continuous, hertz_k, meff, delta, separation_rate, dt);
}

/* ---------------------------------------------------------------------- */

WallGranPowderArgs::WallGranPowderArgs(LAMMPS *lmp, int narg, char **arg, bool region_wall)
{
  Error *error = lmp->error;
  const std::string style = narg > 2 ? arg[2] : "wall/gran/powder";
  if (narg < 5) error->all(FLERR, "Illegal fix {} command: too few arguments", style);
  if (strcmp(lmp->update->unit_style, "si") != 0)
    error->all(FLERR, "Fix {} requires units si (E is given in Pa)", style);
  if (strcmp(arg[3], "granular") != 0)
    error->all(FLERR, "Fix {} supports only the 'granular' interaction style, not '{}'", style, arg[3]);
  if (!meltdem::lammps_api::sphere_style(lmp->atom)) error->all(FLERR, "Fix {} requires atom style sphere", style);

  words.assign(arg, arg + narg);
  enum { NONE, HOOKE, HERTZ, MATERIAL } model = NONE;
  bool jkr = false;
  double E = 0.0, nu = 0.0, e = 0.0, Ew = 0.0, nuw = 0.0;
  bool wall_given = false, rigid = false, kt_null = false, found_wallstyle = false;
  auto need = [&](size_t i, size_t n, const char *what) {
    if (i + n >= words.size()) error->all(FLERR, "Illegal fix {} command: {} needs {} value(s)", style, what, n);
  };
  auto num = [&](size_t i) { return utils::numeric(FLERR, words[i].c_str(), false, lmp); };

  for (size_t i = 4; i < words.size(); i++) {
    const std::string w = words[i];
    if (is_wallstyle(w)) {
      found_wallstyle = true;
      if (w == "region" && !region_wall)
        error->all(FLERR, "Fix {}: region walls need fix wall/gran/region/powder", style);
      if (w != "region" && region_wall)
        error->all(FLERR, "Fix {}: the wall style must be 'region ID', not '{}'", style, w);
      if (w == "region") need(i, 1, "region");
      break;  // the stock parser checks the wall arguments and options
    }
    if (w == "hooke" || w == "hertz") {
      need(i, 2, w.c_str());
      model = (w == "hooke") ? HOOKE : HERTZ;
      e = num(i + 2);
      i += 2;
    } else if (w == "hertz/material" || w == "dmt" || w == "jkr") {
      const size_t n = (w == "hertz/material") ? 3 : 4;
      need(i, n, w.c_str());
      model = MATERIAL;
      jkr = w == "jkr";
      E = num(i + 1);
      e = num(i + 2);
      nu = num(i + 3);
      if (E <= 0.0) error->all(FLERR, "Illegal fix {} command: Young's modulus E must be > 0", style);
      if (nu <= -1.0 || nu > 0.5)
        error->all(FLERR, "Illegal fix {} command: Poisson's ratio must lie in (-1,0.5]", style);
      i += n;
    } else if (w == "damping") {
      need(i, 1, "damping");
      if (words[i + 1] == "tsuji") {
        coeffs.damping = WallGranPowderCoeffs::DAMP_TSUJI_EXACT;
      } else if (words[i + 1] == "tsuji/alpha") {
        need(i + 1, 1, "damping tsuji/alpha");
        coeffs.damping = WallGranPowderCoeffs::DAMP_TSUJI_ALPHA;
        coeffs.alpha = num(i + 2);
        if (coeffs.alpha < 0.0) error->all(FLERR, "Illegal fix {} command: tsuji/alpha must be >= 0", style);
        // the stock parser knows only 'tsuji'; alpha replaces its mapped value in init()
        words[i + 1] = "tsuji";
        words.erase(words.begin() + i + 2);
      }
      i += 1;
    } else if (w == "wall_material") {
      need(i, 1, "wall_material");
      if (words[i + 1] == "rigid") {
        rigid = true;
        words.erase(words.begin() + i, words.begin() + i + 2);
      } else {
        need(i, 2, "wall_material");
        Ew = num(i + 1);
        nuw = num(i + 2);
        if (Ew <= 0.0) error->all(FLERR, "Illegal fix {} command: wall_material E must be > 0", style);
        if (nuw <= -1.0 || nuw > 0.5)
          error->all(FLERR, "Illegal fix {} command: wall_material Poisson's ratio must lie in (-1,0.5]", style);
        words.erase(words.begin() + i, words.begin() + i + 3);
      }
      wall_given = true;
      i -= 1;  // the next word now sits at i
    } else if (w == "impact_speed") {
      need(i, 1, "impact_speed");
      coeffs.impact_speed = num(i + 1);
      if (!(coeffs.impact_speed > 0.0))
        error->all(FLERR, "Illegal fix {} command: impact_speed must be > 0 (m/s)", style);
      words.erase(words.begin() + i, words.begin() + i + 2);
      i -= 1;
    } else if (w == "tangential") {
      need(i, 1, "tangential");
      if (words[i + 1].compare(0, 7, "mindlin") == 0 && i + 2 < words.size() && words[i + 2] == "NULL") kt_null = true;
      i += 1;
    }
    // anything else is left to the stock parser
  }
  if (!found_wallstyle)
    error->all(FLERR, "Illegal fix {} command: missing wall style ({})", style,
               region_wall ? "region ID" : "xplane, yplane, zplane or zcylinder");

  if (coeffs.damping == WallGranPowderCoeffs::DAMP_TSUJI_EXACT) {
    // e depends on alpha alone for a Hertz contact (delta^3/2 spring, delta^1/4 damping); dmt and
    // jkr get the alpha of their non-cohesive limit
    if (model != MATERIAL && model != HERTZ)
      error->all(FLERR, "Fix {}: damping tsuji needs normal model hertz/material, hertz, dmt or jkr", style);
    if (e <= 0.0 || e > 1.0)
      error->all(FLERR, "Illegal fix {} command: restitution e must lie in (0,1] for damping tsuji", style);
    for (const auto &w : words)
      if (w == "limit_damping")
        error->all(FLERR,
                   "Fix {}: damping tsuji applies its damping over the whole step and cannot be combined "
                   "with limit_damping (use tsuji/alpha)",
                   style);
    coeffs.alpha = meltdem::coupling::alpha_for_restitution(e);
    if (!jkr) {
      coeffs.e = e;
      coeffs.stepped = meltdem::coupling::SteppedAlphaTable(e, coeffs.alpha);
    }
  }
  if (wall_given && model != MATERIAL)
    error->all(FLERR, "Fix {}: wall_material needs normal model hertz/material, dmt or jkr", style);
  if (kt_null && model != MATERIAL)
    error->all(FLERR, "Fix {}: a NULL Mindlin stiffness needs normal model hertz/material, dmt or jkr", style);

  if (model == MATERIAL) {
    // Hertz: 1/E* = (1-nu^2)/E + (1-nu_w^2)/E_w, 1/G* = 2(2-nu)(1+nu)/E + (wall); by
    // default the wall is the particle's material, 'rigid' drops its term
    if (!wall_given) Ew = E, nuw = nu;
    const double inv_E = (1.0 - nu * nu) / E + (rigid ? 0.0 : (1.0 - nuw * nuw) / Ew);
    const double inv_G = 2.0 * (2.0 - nu) * (1.0 + nu) / E + (rigid ? 0.0 : 2.0 * (2.0 - nuw) * (1.0 + nuw) / Ew);
    coeffs.material = true;
    coeffs.kn = 4.0 / 3.0 / inv_E;
    coeffs.kt_from_material = kt_null;
    coeffs.kt = 8.0 / inv_G;
  }

#if MELTDEM_LAMMPS_2025_API
  // the stock tsuji sub-model refuses dmt and jkr: the stock parser gets the velocity damping and
  // apply_damping puts Tsuji's with the alpha in its place (as pair_style granular/powder)
  bool cohesive = false;
  for (auto &w : words) cohesive = cohesive || w == "dmt" || w == "jkr";
  if (coeffs.damping != WallGranPowderCoeffs::DAMP_STOCK && cohesive)
    for (size_t i = 4; i + 1 < words.size(); i++)
      if (words[i] == "damping" && words[i + 1] == "tsuji") words[i + 1] = "velocity";
#endif
  for (auto &s : words) argv.push_back(const_cast<char *>(s.c_str()));
}

/* ---------------------------------------------------------------------- */

FixWallGranPowder::FixWallGranPowder(LAMMPS *lmp, WallGranPowderArgs &&a) :
    FixWallGran(lmp, a.narg(), a.arg()), coeffs(a.coeffs)
{
#if MELTDEM_LAMMPS_2025_API
  coeffs.apply_material(model);
  coeffs.apply_damping(model, lmp);
#else
  coeffs.apply_material(normal_coeffs, tangential_coeffs);
#endif
}

void FixWallGranPowder::init()
{
  FixWallGran::init();
#if !MELTDEM_LAMMPS_2025_API
  coeffs.apply_damping(normal_coeffs);
#endif
  coeffs.find_step_fix(lmp);
}

void FixWallGranPowder::post_force(int vflag)
{
  FixWallGran::post_force(vflag);
  if (coeffs.damping != WallGranPowderCoeffs::DAMP_TSUJI_EXACT || coeffs.e <= 0.0 || wallstyle == REGION) return;

  // the stock wall geometry (fix_wall_gran.cpp post_force) for the stepped damping
  double wlo = lo, whi = hi, vwall[3] = {0.0, 0.0, 0.0};
  if (wiggle) {
    const double arg = omega * (update->ntimestep - time_origin) * dt;
    if (wallstyle == axis) {
      wlo = lo + amplitude - amplitude * cos(arg);
      whi = hi + amplitude - amplitude * cos(arg);
    }
    vwall[axis] = amplitude * omega * sin(arg);
  } else if (wshear)
    vwall[axis] = vshear;

  double **x = atom->x, **v = atom->v, **f = atom->f;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *mask = atom->mask;
  const double speed = coeffs.contact_speed(), speed_factor = speed > 0.0 ? update->dt * pow(speed, 0.2) : 0.0;
#if MELTDEM_LAMMPS_2025_API
  const double kn = coeffs.stiffness(model), alpha_continuous = coeffs.alpha;
#else
  const double kn = normal_coeffs[0], alpha_continuous = normal_coeffs[1];
#endif
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double d[3] = {0.0, 0.0, 0.0}, vw[3] = {vwall[0], vwall[1], vwall[2]}, rwall = 0.0, r;
    if (wallstyle == XPLANE || wallstyle == YPLANE || wallstyle == ZPLANE) {
      const int k = wallstyle;  // XPLANE, YPLANE, ZPLANE are 0, 1, 2
      const double del1 = x[i][k] - wlo, del2 = whi - x[i][k];
      d[k] = del1 < del2 ? del1 : -del2;
      r = std::fabs(d[k]);  // (= sqrt(d[k]^2) exactly, without its latency)
    } else if (wallstyle == ZCYLINDER) {
      const double delxy = sqrt(x[i][0] * x[i][0] + x[i][1] * x[i][1]);
      const double delr = cylradius - delxy;
      if (delr > 2.0 * radius[i]) continue;  // far from the wall even one step ago
      d[0] = -delr / delxy * x[i][0];
      d[1] = -delr / delxy * x[i][1];
      rwall = (delxy < cylradius) ? -2 * cylradius : 2 * cylradius;
      if (wshear && axis != 2) {
        vw[0] += vshear * x[i][1] / delxy;
        vw[1] += -vshear * x[i][0] / delxy;
        vw[2] = 0.0;
      }
      r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } else
      continue;
    if (!(r > 0.0) || r > 2.0 * radius[i]) continue;
    const double n[3] = {d[0] / r, d[1] / r, d[2] / r};
    const double rate = (v[i][0] - vw[0]) * n[0] + (v[i][1] - vw[1]) * n[1] + (v[i][2] - vw[2]) * n[2];
    const double reff = rwall == 0.0 ? radius[i] : radius[i] * rwall / (radius[i] + rwall);
    double meff = rmass[i];
    if (fix_rigid && mass_rigid[i] > 0.0) meff = mass_rigid[i];
    const double fn =
        coeffs.damping_correction(kn, alpha_continuous, radius[i] - r, rate, reff, meff, update->dt, speed_factor);
    for (int k = 0; k < 3; k++) f[i][k] += n[k] * fn;
  }
}
