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

/// A slab of mesh/tooth_slab held at its bore (its kSurfaceClamped faces), factorised once: under plane strain
/// (u_z = 0 at every node, so the 3-D TET10 model is exactly the 2-D plane-strain one), or free in z (a slab as deep
/// as the face: the solid tooth with its two free ends).
class ClampedSlab {
public:
  ClampedSlab(ToothSlab slab, const Material& m, bool plane_strain = true);
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

/// How a solid flexspline tooth shares a flank's load between the loaded contact's face sections
/// (contact/contact_body.hpp face_slice: n sections, each for its band of the face). The fast model's teeth are
/// plane-strain slabs, one spring per section side by side; a real tooth is one solid along the face and carries a
/// band's load into its neighbours (a cantilever plate). From two bore-clamped slabs as deep as the face, free in z
/// (mesh/tooth_slab, the same pair as flexspline_tooth_fem: the teeth, and the ring the 3-D model already holds):
/// band j loaded by 1 N along the flank's normal at mid-flank (the explicit slab: the elliptic strip over the band;
/// the ring slab: contact/'s flank pattern over the band), band i's deflection read as flexspline_tooth_fem reads it
/// (the explicit slab's centre line averaged over the band; the ring's fᵀu). C = explicit − ring (m/N, symmetrised).
/// The shape is C·b / c_3D with c_3D = b·wᵀCw (b the face width, w_j the bands' fractions of it): the coupled
/// sections under a uniform line load hold the energy the plane-strain tooth holds, so the tooth's level stays
/// flexspline_tooth_fem's (its radius dependence included) and only its spread along the face comes from here. For
/// springs side by side (C = diag(t/b_j)) the shape is diag(1/w_j): today's sections exactly.
struct FaceCoupling {
  /// n×n, symmetric, dimensionless, its diagonal positive. Not always positive definite: from some 8 sections on a
  /// load alternating band to band deflects the toothed slab less than the bare one (the tooth a deep rib along the
  /// face over a thin rim), so the explicit slab's coupling less the ring's has negative eigenvalues. Only its sum
  /// with the body's coefficients, which hold the bare rim's, has to be positive definite.
  Eigen::MatrixXd shape;
  double uniform_m2_per_N = 0;    ///< c_3D: the slabs' energy-mean deflection per line load under a uniform line load
  double interior_m2_per_N = 0;   ///< band n/2's deflection per line load under it (near plane strain on a long face)
  double radius_m = 0;            ///< the contact radius loaded (mid-flank)
  std::size_t nodes = 0;          ///< of both slabs
  double seconds = 0;
};

/// Throws InputError when the bore is not inside the root circle, n < 2, or a band holds no flank surface under the
/// strip.
FaceCoupling face_coupling(const GearParams& g, const Material& m, double bore_radius_m, double ring_outer_radius_m,
                           double face_width_m, int sections, int points_per_flank = 8);

}  // namespace sw
