#pragma once
// Particles meeting solid metal of the continuum (substrate, solidified track): the solid
// repels them as a granular wall. The coupling finds, once per coupling
// interval, the surface of the solid metal nearest to each particle from the cells that
// are solid (metal fraction x (1 - liquid fraction) >= 1/2) and hands it to the particle
// as a plane (point, outward normal). The DEM side then applies, every sub-step, the same
// Hertz contact with Tsuji delta^(1/4) damping as pair granular/powder and
// wall/gran/powder (Codina2019 eq. 3.5):
//   F = (4/3 E* sqrt(R delta) delta - alpha sqrt(m 4/3 E* sqrt(R delta)) v.n) n,
// delta = R - (x - p).n; no friction (the surface is a cell-face staircase, not a wall
// with a tangential reference).
#include <Eigen/Core>

#include <vector>

namespace meltdem::coupling {

struct SolidSurface {
  bool present = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // on the surface
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, out of the solid
  double distance = 0.0;                             // from the particle centre
  bool fresh = true;        // its cell was not solid one coupling interval ago (or that is unknown)
  bool approached = false;  // the particle moves towards it (v.n < -kApproachShare |v|)
};

// The share of its speed a particle must move with against a surface's normal to approach it.
constexpr double kApproachShare = 0.01;

// The surface nearest to centre c among the solid boxes [lo_i, hi_i]: the closest point of
// each box; the normal points from it to c (for c inside a box: out of its nearest face).
// was_solid[i] != 0: box i was solid one coupling interval ago (empty: none known to be).
// A particle moving with velocity v is handed the nearest surface it approaches, if any:
// only one surface acts over an interval, and one it slides along or moves away from (a
// wall beside a falling grain, a face of metal that froze around half of it) would hide
// the floor it falls onto.
SolidSurface nearest_solid_surface(const Eigen::Vector3d &c, const std::vector<Eigen::Vector3d> &lo,
                                   const std::vector<Eigen::Vector3d> &hi, const std::vector<char> &was_solid = {},
                                   const Eigen::Vector3d &v = Eigen::Vector3d::Zero());

// Whether surface a is handed over rather than b: any before none, approached before not,
// then the nearer (b on ties).
bool preferred_surface(const SolidSurface &a, const SolidSurface &b);

// Hertz/Tsuji normal force on a sphere (radius R, mass m, velocity v, centre x) from the
// plane; zero without overlap. E_star = effective modulus, alpha = Tsuji damping. offset:
// overlap the surface brought onto the particle (SolidContactMemory), not counted.
Eigen::Vector3d solid_contact_force(const SolidSurface &s, const Eigen::Vector3d &x, double R, double m,
                                    const Eigen::Vector3d &v, double E_star, double alpha, double offset = 0.0);

// What a particle remembers of its contact with the solid metal. A surface that appears
// on a particle or moves onto it (melt freezing around a grain, a cell turning solid, the
// cell-face staircase switching to another face) overlaps it without the particle having
// moved; Hertz would turn that overlap into a kick of 1e2..1e4 m/s within a microsecond
// (the ded-stream switch-off: a grain engulfed by freezing melt left at 622 m/s). Only
// the overlap the particle gains by its own motion against an unchanged surface counts:
// the rest is the offset. It shrinks as the particle moves out and is gone once the
// particle is clear, so a grain caught by freezing melt stays where it was caught.
// A surface of metal that was already solid one interval ago brought no more overlap than
// the particle had with it then (at the mark, its centre at the interval's first step):
// what it gained since by moving counts, even if another surface was the nearest meanwhile.
struct SolidContactMemory {
  double offset = 0.0;
  bool has_plane = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  bool has_mark = false;
  Eigen::Vector3d mark = Eigen::Vector3d::Zero();
};

// Update the memory for the surface s seen now by the sphere (centre x, radius R);
// interval_start: this is the first step of a coupling interval (the mark moves to x after
// the update). Returns the offset to pass to solid_contact_force.
double update_solid_contact(SolidContactMemory &m, const SolidSurface &s, const Eigen::Vector3d &x, double R,
                            bool interval_start = false);

}  // namespace meltdem::coupling
