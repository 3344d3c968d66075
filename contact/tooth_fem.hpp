#pragma once
// The flexspline tooth's own compliance from the explicit-tooth FEM of the case's tooth, with what the 3-D ring model
// already holds of its load taken off, so the rim is not counted twice (contact/README.md, "A").
//
// Two plane-strain slabs of the rim held at its bore (mesh/tooth_slab: 2K + 1 teeth, TET10 with u_z = 0):
//   explicit: the real teeth; a line load along the involute's normal at the contact radius, spread over a small
//     elliptic strip, read along the load at the tooth's centre line at the contact's height (Weber's convention: the
//     local flattening is the contact term of gear/tooth_stiffness.hpp);
//   ring: the body out to the 3-D model's rim (the ring of teeth = "ring"); loaded by contact/'s own flank pattern (the
//     contact force carried down a rigid tooth: force and foot moment as hats on the ring's surface, the resultant
//     exactly the contact force's) and read work-conjugately (fᵀu), as the influence coefficients read it.
// The tooth = explicit − ring, per unit line load (m²/N), sampled across the active flank and interpolated linearly.
// Each slab is meshed and factorised once; every radius is one more right-hand side.
//
// Why not the analytic tooth: on the seed's tooth (z = 190 on a 0.7 mm rim) Sainsot's foundation fit is extrapolated
// far outside its range, and bending + foundation come out 1.8–8.6× this FEM tooth (tests/gear).
#include <vector>

#include <Eigen/Core>

#include "common/material.hpp"
#include "fem/assembly.hpp"
#include "fem/cholmod_factor.hpp"
#include "gear/gear.hpp"
#include "mesh/tooth_slab.hpp"

namespace sw {

/// A slab of mesh/tooth_slab held at its bore (its kSurfaceClamped faces) under plane strain (u_z = 0 at every node,
/// so the 3-D TET10 model is exactly the 2-D plane-strain one), factorised once.
class PlaneStrainSlab {
public:
  PlaneStrainSlab(ToothSlab slab, const Material& m);
  const ToothSlab& slab() const { return slab_; }
  /// Displacement (3·n_nodes, m) under nodal loads f (N).
  Eigen::VectorXd solve(const Eigen::VectorXd& f) const;

private:
  ToothSlab slab_;
  DofMap dofs_;
  CholmodFactor factor_;
};

struct FlexsplineToothFem {
  std::vector<double> radius_m;              ///< contact radii on the flexspline's flank, form to tip, ascending
  std::vector<double> explicit_m2_per_N;     ///< the explicit slab's centre-line deflection per line load
  std::vector<double> ring_m2_per_N;         ///< the ring slab's pattern deflection per line load
  std::size_t nodes = 0;                     ///< of both slabs
  double seconds = 0;                        ///< wall time of meshing, factorising and solving
  /// The tooth's own compliance (explicit − ring, m²/N) at contact radius r (clamped to the sampled flank).
  double operator()(double contact_radius_m) const;
};

/// Samples `samples` radii evenly from the form to the tip radius (the tip itself is taken 0.5 % of the flank inside,
/// where the strip still lies on the flank). `ring_outer_radius_m` is the 3-D model's rim_outer_radius (the ring's,
/// or the bare rim's). `points_per_flank` sets the slabs' resolution (24: the tooth within 1 % of 48, tests/gear).
/// Throws InputError when the bore is not inside the root circle.
FlexsplineToothFem flexspline_tooth_fem(const GearParams& g, const Material& m, double bore_radius_m,
                                        double ring_outer_radius_m, int samples = 9, int points_per_flank = 24);

}  // namespace sw
